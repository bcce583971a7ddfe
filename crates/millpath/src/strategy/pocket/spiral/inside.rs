//! The spiral's sampled laps as moves, kept inside the last loop `B_ε` ([`super::last_loop`]).
//!
//! A lap blends the previous loop into the next one point by point; where the next one is
//! `B` (or near it) and `B` has a concave arc (round a corner of the wall pointing into the
//! pocket), the blend of two points on either side of the dent cuts across it: the tool
//! centre inside the wall's clearance, a gouge. The pocket fuzzer found such laps 0.2 mm deep
//! on a 4.7 mm tool (fuzz/README.md, session 6). [`keep_inside`] moves such samples onto
//! `B_ε`; [`lap_path`] then writes the samples as moves.

use super::{ARC_TOLERANCE, LAST_LOOP_MARGIN};
use crate::geom::Point;
use crate::strategy::pocket::chain::{Seg, fit_arcs, segs_from_points};
use crate::strategy::pocket::shape::v2;
use cavalier_contours::polyline::{PlineSource, Polyline};

/// The samples `pts` as moves, kept inside `b_eps` ([`keep_inside`], resampling at
/// `max_chord / 2` beside a moved sample): G1 chords, or with `arcs` tangent-continuous
/// biarcs within [`ARC_TOLERANCE`]. A moved stretch has a kink where it meets `B_ε`, and
/// biarcs fitted through it overshoot by more than their tolerance (18 µm found by the
/// fuzzer): a path with moved samples is written as chords.
pub(super) fn lap_path(
    pts: &[Point],
    b_eps: &Polyline<f64>,
    max_chord: f64,
    arcs: bool,
) -> Vec<Seg> {
    let (pts, moved) = keep_inside(pts, b_eps, max_chord);
    if arcs && !moved {
        fit_arcs(&pts, ARC_TOLERANCE)
    } else {
        segs_from_points(&pts)
    }
}

/// `pts` with every sample more than half [`LAST_LOOP_MARGIN`] outside `b_eps` moved onto its
/// nearest point, and the stretches next to a moved sample resampled at `max_chord / 2` (each
/// new sample moved in the same way), so that a chord between two moved samples stays within
/// the arc-fit margin of `b_eps`. A path whose samples never leave `B_ε` is returned
/// unchanged, with `false` (`true`: some moved).
fn keep_inside(pts: &[Point], b_eps: &Polyline<f64>, max_chord: f64) -> (Vec<Point>, bool) {
    let project = |p: Point| -> (Point, bool) {
        if b_eps.winding_number(v2(p)) != 0 {
            return (p, false);
        }
        // Samples on `B_ε` (the last lap ends on it) or less than half the margin outside it
        // are still well inside `B`: left alone, so that a lap merely touching `B_ε` keeps its
        // arcs.
        match b_eps.closest_point(v2(p), 1e-12) {
            Some(c) if c.distance > 0.5 * LAST_LOOP_MARGIN => {
                (Point::new(c.seg_point.x, c.seg_point.y), true)
            }
            _ => (p, false),
        }
    };
    let step = 0.5 * max_chord.max(1e-3);
    let mut out = Vec::with_capacity(pts.len());
    let mut prev: Option<(Point, bool)> = None;
    let mut any = false;
    for &p in pts {
        let (q, moved) = project(p);
        any |= moved;
        if let Some((a, a_moved)) = prev
            && (moved || a_moved)
        {
            let n = ((a.distance(p) / step).ceil() as usize).clamp(1, 10_000);
            for k in 1..n {
                out.push(project(a + (p - a) * (k as f64 / n as f64)).0);
            }
        }
        out.push(q);
        prev = Some((p, moved));
    }
    (out, any)
}
