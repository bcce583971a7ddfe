//! The paper's Table 1: the blended segment 2 between segments 1 and 3, and invariance of
//! the four-point outline under reversed input and a rotated start group.

use millpath::curve::{self, CurveKind};
use millpath::geom::Point;

#[test]
fn four_point_outline_is_invariant_under_reversal_and_rotation() {
    let scale = |g: Vec<Vec<curve::LabeledPoint>>| -> Vec<Vec<curve::LabeledPoint>> {
        g.into_iter()
            .map(|v| {
                v.into_iter()
                    .map(|mut p| {
                        p.p = Point::new(20.0 * p.p.x + 40.0, 20.0 * p.p.y + 45.0);
                        p
                    })
                    .collect()
            })
            .collect()
    };
    let base = scale(curve::paper_groups());
    let mut rotated = base.clone();
    rotated.rotate_left(1);
    let reversed: Vec<Vec<_>> = base
        .iter()
        .rev()
        .map(|v| v.iter().rev().cloned().collect())
        .collect();
    let summary = |g: &[Vec<curve::LabeledPoint>]| {
        let c = curve::build(g, CurveKind::FourPoint, "t").unwrap();
        let f = curve::flatten(&c, 1e-3).unwrap();
        let dense = curve::chordal_deviation(&c, &f.params, &f.points, 1000);
        (f.segments(), dense, c.signed_area(), c.length())
    };
    let (n0, d0, a0, l0) = summary(&base);
    assert!(d0 <= 1e-3);
    for g in [&rotated, &reversed] {
        let (n, d, a, l) = summary(g);
        assert!(n.abs_diff(n0) <= 1, "{n} vs {n0}");
        assert!(d <= 1e-3);
        assert!(
            (a - a0).abs() < 1e-6 * a0 && (l - l0).abs() < 1e-6 * l0,
            "{a} vs {a0}, {l} vs {l0}"
        );
    }
}
