//! Unit tests of the limit verifier.

use super::*;

/// Where the root-free test says the blend checks pass, they pass computed with their
/// trigonometry: a grid of 35,280 cases (corners of 1e-9 to 1.2 rad, blend radii, limits
/// within 1e-8 of the computed values and far from them); at least 3,000 pass the test.
#[test]
fn blend_surely_fits_only_where_the_checks_pass() {
    let mut passed = 0;
    for ia in 0..60 {
        let angle = 10f64.powf(-9.0 + 9.08 * f64::from(ia) / 59.0);
        let dot = angle.cos();
        let half = 0.5 * dot.clamp(-1.0, 1.0).acos();
        for ir in 0..12 {
            let r = 10f64.powf(-4.0 + 8.0 * f64::from(ir) / 11.0);
            let deviation = r * (1.0 / half.cos() - 1.0);
            let reach = r * half.tan();
            for f in [1e-8, 1e-13, 0.0, -1e-13, -1e-8, 0.5, 2.0] {
                for g in [1e-8, 0.0, -1e-8, 1.0, 10.0, 1e-14, -1e-14] {
                    let (tolerance, room) = (deviation * (1.0 + f), reach * (1.0 + g));
                    if blend_surely_fits(dot, r, tolerance, room, 0.0) {
                        passed += 1;
                        assert!(
                            deviation <= tolerance && reach <= room,
                            "{angle} {r}: {deviation} vs {tolerance}, {reach} vs {room}"
                        );
                    }
                }
            }
        }
    }
    assert!(passed >= 3_000, "{passed}");
}

/// The verifier's own spiral derivatives (radial terms included; it differentiated
/// spiral arcs as circles before, like the planner) against central differences of its
/// own positions.
#[test]
fn verifier_differentiates_spirals_exactly() {
    let c = Point3::new(0.0, 0.0, 0.0);
    for (r1, dz, ccw) in [(3.0, 0.0, true), (0.4, 1.5, false), (1.0, -2.0, true)] {
        let from = Point3::new(1.0, 0.0, 0.0);
        let to = Point3::new(0.0, r1, dz);
        let m = Move::arc_xy(to, c, ccw, 10.0);
        let sh = Shape {
            from,
            m,
            len: m.length_from(from),
        };
        let h = 1e-5 * sh.len;
        for k in 1..10 {
            let s = sh.len * f64::from(k) / 10.0;
            let d = sh.eval(s);
            for (i, di) in d.iter().enumerate().skip(1) {
                let fd = (sh.eval(s + h)[i - 1] - sh.eval(s - h)[i - 1]) / (2.0 * h);
                assert!(
                    (*di - fd).length() <= 1e-5 * (1.0 + di.length()),
                    "r1 {r1} s {s} derivative {i}: {di:?} vs {fd:?}"
                );
            }
        }
        let end = sh.eval(sh.len)[0];
        assert!((end - (to - Point3::ORIGIN)).length() < 1e-12);
    }
}
