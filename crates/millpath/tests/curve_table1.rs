//! The paper's Table 1: the blended segment 2 between segments 1 and 3, and invariance of
//! the four-point outline under reversed input and a rotated start group.

use millpath::curve::{self, CurveKind, blend, four_point, verify};
use millpath::geom::{Point, Vec2};

#[test]
fn table_1_blend_inner_points() {
    let g = curve::paper_groups();
    let pts = |k: usize| -> [Point; 4] { [g[k][0].p, g[k][1].p, g[k][2].p, g[k][3].p] };
    let (s1, s3) = (pts(0), pts(1));
    assert!((four_point::end_derivative(&s1) - Vec2::new(6.0, -9.5)).length() < 1e-12);
    assert!((four_point::start_derivative(&s3) - Vec2::new(-5.0, 49.75)).length() < 1e-12);
    let (p2, p3) = blend::inner_points(
        s1[3],
        four_point::end_derivative(&s1),
        s3[0],
        four_point::start_derivative(&s3),
    );
    for (got, want) in [(p2, (10.33, 4.38)), (p3, (14.11, 0.44))] {
        assert!(
            (got.x - want.0).abs() < 0.01 && (got.y - want.1).abs() < 0.01,
            "{got:?} vs {want:?}"
        );
    }
    // The built outline holds exactly this blend as its second piece (before scaling).
    let c = curve::build(&g, CurveKind::FourPoint, "paper").unwrap();
    let b = c.pieces()[1];
    assert!(
        b.p0.distance(Point::new(7.0, 10.0)) < 1e-12
            && b.p3.distance(Point::new(15.0, 8.0)) < 1e-12
    );
    assert!(b.eval(1.0 / 3.0).distance(p2) < 1e-9 && b.eval(2.0 / 3.0).distance(p3) < 1e-9);
}

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
        let f = curve::flatten::flatten(&c, 1e-3).unwrap();
        let dense = verify::chordal_deviation(&c, &f.params, &f.points, 1000);
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
