//! Finding a drawing's holes among its closed outlines, and choosing some by diameter.
//!
//! Every outline that is a circle within the tolerance ([`Hole::from_outline`]) is a hole,
//! unless another outline of the drawing lies inside it: a circle round other outlines is a
//! round part or a pocket with islands, not a hole. The same circle drawn twice (centres
//! within the tolerance, diameters within twice it) is one hole. Holes are listed in the
//! drawing's order (the first drawn of each), numbered from 1 in reports.

use crate::error::InputError;
use crate::geom::{Hole, Outline};

/// The holes among `outlines` (module docs), with the tolerance of [`Hole::from_outline`].
pub fn find_holes(outlines: &[Outline], tolerance: f64) -> Vec<Hole> {
    let mut out: Vec<Hole> = Vec::new();
    let firsts: Vec<Option<crate::geom::Point>> = outlines
        .iter()
        .map(|o| o.vertices().next().map(|(p, _)| p))
        .collect();
    for (i, o) in outlines.iter().enumerate() {
        let Some(h) = Hole::from_outline(o, tolerance) else {
            continue;
        };
        let bounds = o.bounds();
        let holds_another = outlines
            .iter()
            .zip(&firsts)
            .enumerate()
            .any(|(j, (other, p))| {
                j != i
                    && p.is_some_and(|p| bounds.contains(p) && o.contains(p))
                    && other.signed_area().abs() < o.signed_area().abs()
                    && !same_circle(o, other, tolerance)
            });
        if holds_another {
            continue;
        }
        let seen = out.iter().any(|k| {
            k.center.distance(h.center) <= tolerance
                && (k.diameter - h.diameter).abs() <= 2.0 * tolerance
        });
        if !seen {
            out.push(h);
        }
    }
    out
}

/// Whether two outlines are the same circle drawn twice.
fn same_circle(a: &Outline, b: &Outline, tolerance: f64) -> bool {
    match (
        Hole::from_outline(a, tolerance),
        Hole::from_outline(b, tolerance),
    ) {
        (Some(x), Some(y)) => {
            x.center.distance(y.center) <= tolerance
                && (x.diameter - y.diameter).abs() <= 2.0 * tolerance
        }
        _ => false,
    }
}

/// The holes whose diameter is within `[min, max]` mm (either bound may be absent), with
/// their 1-based index in `holes`. A bound that is not a length ≥ 0, or a minimum above the
/// maximum, is refused naming `--min-diameter` / `--max-diameter`.
pub fn select_holes(
    holes: &[Hole],
    min: Option<f64>,
    max: Option<f64>,
) -> Result<Vec<(usize, Hole)>, InputError> {
    for (flag, v) in [("--min-diameter", min), ("--max-diameter", max)] {
        if let Some(v) = v
            && !(v.is_finite() && v >= 0.0)
        {
            return Err(InputError::new("hole diameter bound", v)
                .at(flag)
                .expected("a diameter >= 0 mm"));
        }
    }
    if let (Some(a), Some(b)) = (min, max)
        && a > b
    {
        return Err(
            InputError::new("hole diameter range", format!("{a} to {b} mm"))
                .at("--min-diameter / --max-diameter")
                .expected("a minimum at most the maximum"),
        );
    }
    Ok(holes
        .iter()
        .enumerate()
        .filter(|(_, h)| min.is_none_or(|m| h.diameter >= m) && max.is_none_or(|m| h.diameter <= m))
        .map(|(i, h)| (i + 1, *h))
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::{Point, Vec2};
    use std::f64::consts::PI;

    fn circle(c: Point, r: f64) -> Outline {
        Outline::new(
            &[(c + Vec2::new(r, 0.0), 1.0), (c - Vec2::new(r, 0.0), 1.0)],
            "circle",
        )
        .unwrap()
    }

    #[test]
    fn circles_are_holes_unless_they_hold_other_outlines() {
        let plate = Outline::from_points(
            &[
                Point::new(0.0, 0.0),
                Point::new(100.0, 0.0),
                Point::new(100.0, 50.0),
                Point::new(0.0, 50.0),
            ],
            "plate",
        )
        .unwrap();
        let round_part = circle(Point::new(200.0, 0.0), 40.0);
        let in_part = circle(Point::new(200.0, 0.0), 3.0);
        let outlines = vec![
            plate,
            circle(Point::new(10.0, 10.0), 2.5),
            circle(Point::new(10.0, 10.0), 2.5),
            round_part,
            in_part,
            circle(Point::new(50.0, 25.0), 8.0),
        ];
        let holes = find_holes(&outlines, 0.01);
        let d: Vec<f64> = holes.iter().map(|h| h.diameter).collect();
        assert_eq!(d.len(), 3, "{holes:?}");
        assert!((d[0] - 5.0).abs() < 1e-9 && (d[1] - 6.0).abs() < 1e-9);
        assert!((d[2] - 16.0).abs() < 1e-9);
        let sel = select_holes(&holes, Some(5.5), Some(20.0)).unwrap();
        assert_eq!(sel.iter().map(|(i, _)| *i).collect::<Vec<_>>(), [2, 3]);
        assert!(select_holes(&holes, Some(6.0), Some(5.0)).is_err());
        assert!(select_holes(&holes, Some(-1.0), None).is_err());
        assert!((holes[0].radius() * 2.0 * PI - 5.0 * PI).abs() < 1e-9);
    }
}
