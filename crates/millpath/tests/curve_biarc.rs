//! Biarcs: the paper's outline (and its offsets) within the tolerance, verified with 1000
//! samples per arc, with far fewer blocks than lines.

use millpath::curve;
use millpath::geom::Point;
use millpath::strategy::contour::{ContourOptions, Side, offset_pass};

#[test]
fn biarcs_on_the_outline_are_within_tolerance_and_fewer_than_lines() {
    let c = curve::paper_outline().unwrap();
    let corner = c.corners()[0] as f64;
    for tol in [1e-1, 1e-2, 1e-3] {
        let arcs = curve::fit_biarcs(&c, corner, corner + c.len() as f64, tol);
        // Dense: 1000 curve samples per arc against the arcs near it (curve → arcs), and
        // 1000 samples on each arc against the curve (arcs → curve, kurbo nearest).
        let mut s0 = corner;
        let mut worst = 0.0_f64;
        for (k, a) in arcs.iter().enumerate() {
            for j in 0..=1000 {
                let s = s0 + (a.s_end - s0) * f64::from(j) / 1000.0;
                let p = c.eval(s.min(corner + c.len() as f64 - 1e-12));
                let near = [k.saturating_sub(1), k, (k + 1).min(arcs.len() - 1)];
                let d = near
                    .iter()
                    .map(|&i| arcs[i].distance(p))
                    .fold(f64::INFINITY, f64::min);
                worst = worst.max(d);
            }
            s0 = a.s_end;
        }
        for a in &arcs {
            for j in (0..=1000).step_by(50) {
                let q: Point = a.at(f64::from(j) / 1000.0);
                worst = worst.max(curve::distance_to_curve(&c, q));
            }
        }
        let lines = curve::flatten(&c, tol).unwrap().segments();
        assert!(worst <= tol * 1.0001, "T={tol}: {worst}");
        // Arc counts grow like T^(-1/3) against T^(-1/2) for lines: the gap widens as T shrinks.
        let factor = if tol >= 0.1 { 1 } else { 2 };
        assert!(
            arcs.len() * factor < lines,
            "T={tol}: {} arcs vs {lines} lines",
            arcs.len()
        );
    }
}

#[test]
fn arc_passes_keep_the_offset_distance() {
    let c = curve::paper_outline().unwrap();
    for side in [Side::Inside, Side::Outside] {
        let o = ContourOptions::default()
            .with_tolerance(1e-3)
            .with_side(side)
            .with_arcs(true);
        let d = 5.2;
        let pass = offset_pass(&c, if side == Side::Inside { d } else { -d }, &o).unwrap();
        let lines = o.clone().with_arcs(false);
        let line_pass = offset_pass(&c, if side == Side::Inside { d } else { -d }, &lines).unwrap();
        assert!(pass.segments() * 2 < line_pass.segments(), "{side:?}");
        let mut min = f64::INFINITY;
        for a in pass.arcs.iter().flatten() {
            for j in 0..=40 {
                min = min.min(curve::distance_to_curve(&c, a.at(f64::from(j) / 40.0)));
            }
        }
        assert!(min >= d - 1e-6, "{side:?}: {min}");
        assert!(
            pass.max_deviation <= 1e-3,
            "{side:?}: {}",
            pass.max_deviation
        );
    }
}
