//! Self-intersections of closed polylines (sweep over x-sorted segments), and the removal of
//! the tiny inverted "fish-tail" lobes that interpolating cubics can leave at a sharp corner.
//!
//! # Fish-tails
//! Where two pieces meet at a nearly reversing corner, the interpolating cubics may overshoot
//! and cross each other just before the corner, leaving a tiny lobe of the opposite
//! orientation. The paper's own Table 1 outline does this at (1, 15): segment 3 arrives with
//! tangent (−5, 2.5) and segment 1 leaves with (6, −2.75); near x = 1.03 the two cross, and
//! the lobe beyond is about 0.03 × 0.0002 units. The region the outline bounds is the one
//! without the lobe, so [`remove_fishtails`] cuts both pieces at the crossing (de Casteljau
//! subdivision keeps them cubic) and the crossing becomes a corner. Any other
//! self-intersection is the user's to fix and is reported as an input error.

use super::{CompositeCurve, Cubic, PieceKind};
use crate::error::InputError;
use crate::geom::Point;

/// Segment–segment intersection parameters `(ta, tb)` in `[0, 1)` (proper or touching).
fn seg_intersect(a0: Point, a1: Point, b0: Point, b1: Point) -> Option<(f64, f64)> {
    let (r, s) = (a1 - a0, b1 - b0);
    let den = r.cross(s);
    if den.abs() <= 1e-300 {
        return None;
    }
    let w = b0 - a0;
    let ta = w.cross(s) / den;
    let tb = w.cross(r) / den;
    ((0.0..1.0).contains(&ta) && (0.0..1.0).contains(&tb)).then_some((ta, tb))
}

/// All self-intersections of the closed polyline `v` as `(i, ta, j, tb)` with `i < j`,
/// segments not adjacent.
pub fn self_intersections(v: &[Point]) -> Vec<(usize, f64, usize, f64)> {
    let m = v.len();
    let mut segs: Vec<(f64, f64, usize)> = (0..m)
        .map(|i| {
            let (a, b) = (v[i], v[(i + 1) % m]);
            (a.x.min(b.x), a.x.max(b.x), i)
        })
        .collect();
    segs.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut out = Vec::new();
    for k in 0..segs.len() {
        let (_, xmax, i) = segs[k];
        for &(xmin2, _, j) in &segs[k + 1..] {
            if xmin2 > xmax {
                break;
            }
            let (i, j) = if i < j { (i, j) } else { (j, i) };
            if j == i + 1 || (i == 0 && j == m - 1) {
                continue;
            }
            let (a0, a1, b0, b1) = (v[i], v[(i + 1) % m], v[j], v[(j + 1) % m]);
            let (ylo, yhi) = (a0.y.min(a1.y), a0.y.max(a1.y));
            if b0.y.max(b1.y) < ylo || b0.y.min(b1.y) > yhi {
                continue;
            }
            if let Some((ta, tb)) = seg_intersect(a0, a1, b0, b1) {
                out.push((i, ta, j, tb));
            }
        }
    }
    out
}

fn sub(c: &Cubic, t0: f64, t1: f64) -> Cubic {
    use kurbo::ParamCurve;
    let k = c.to_kurbo().subsegment(t0..t1);
    Cubic::new(k.p0.into(), k.p1.into(), k.p2.into(), k.p3.into())
}

/// Cuts the fish-tail lobes at corners (module docs), then rejects any remaining
/// self-intersection of the curve. `origin` names the input for errors.
pub fn remove_fishtails(c: CompositeCurve, origin: &str) -> Result<CompositeCurve, InputError> {
    let n = c.len();
    let mut pieces = c.pieces().to_vec();
    let kinds: Vec<PieceKind> = c.piece_kinds().to_vec();
    let mut cut = false;
    let mut lobes = Vec::new();
    if n > 1 {
        for &k in c.corners() {
            let prev = (k + n - 1) % n;
            let (pa, pb) = (pieces[prev], pieces[k]);
            let m = 200;
            let span = 0.25;
            let ua_of = |j: usize| 1.0 - span + span * j as f64 / m as f64;
            let ub_of = |j: usize| span * j as f64 / m as f64;
            let ta: Vec<Point> = (0..m).map(|j| pa.eval(ua_of(j))).collect();
            let tb: Vec<Point> = (1..=m).map(|j| pb.eval(ub_of(j))).collect();
            // The crossing nearest the corner: largest ua.
            let mut found = None;
            'outer: for ia in (0..m - 1).rev() {
                for ib in 0..m - 1 {
                    if let Some((s, t)) = seg_intersect(ta[ia], ta[ia + 1], tb[ib], tb[ib + 1]) {
                        let ua = ua_of(ia) + s * span / m as f64;
                        let ub = ub_of(ib + 1) + t * span / m as f64;
                        found = Some((ua, ub));
                        break 'outer;
                    }
                }
            }
            let Some((mut ua, mut ub)) = found else {
                continue;
            };
            for _ in 0..30 {
                let r = pa.eval(ua) - pb.eval(ub);
                let (da, db) = (pa.d1(ua), -pb.d1(ub));
                let det = da.cross(db);
                if det.abs() < 1e-300 {
                    break;
                }
                let x = (-r).cross(db) / det;
                let y = da.cross(-r) / det;
                ua = (ua + x).clamp(0.0, 1.0);
                ub = (ub + y).clamp(0.0, 1.0);
            }
            let x: Point = pa.eval(ua).midpoint(pb.eval(ub));
            let mut a = sub(&pa, 0.0, ua);
            let mut b = sub(&pb, ub, 1.0);
            a.p3 = x;
            b.p0 = x;
            let mut to_tip = sub(&pa, ua, 1.0);
            let mut from_tip = sub(&pb, 0.0, ub);
            to_tip.p0 = x;
            from_tip.p3 = x;
            lobes.push(super::Lobe {
                corner: k,
                to_tip,
                from_tip,
            });
            pieces[prev] = a;
            pieces[k] = b;
            cut = true;
        }
    }
    let c = if cut {
        CompositeCurve::new(pieces, kinds, origin)?.with_lobes(lobes)
    } else {
        c
    };
    let b = c.bounds();
    let tol = 1e-4 * b.width().hypot(b.height()).max(1e-9);
    let Ok(f) = super::flatten::flatten(&c, tol) else {
        return Ok(c);
    };
    let pts = &f.points[..f.points.len() - 1];
    if let Some(&(i, ta, _, _)) = self_intersections(pts).first() {
        let at = pts[i].lerp(pts[(i + 1) % pts.len()], ta);
        return Err(InputError::new(
            "outline",
            format!("self-intersecting near ({:.4}, {:.4})", at.x, at.y),
        )
        .at(origin)
        .expected("a closed curve that does not cross itself (check the point order)"));
    }
    Ok(c)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_paper_outline_fishtail_is_cut_at_the_crossing() {
        let c = super::super::paper_outline().unwrap();
        // The corner moved from (1, 15)·20 + (40, 45) = (60, 345) to the crossing near
        // x = 1.03 units (about 0.6 mm to the right), and nothing crosses any more.
        let x = c.pieces()[0].p0;
        assert!(
            x.x > 60.1 && x.x < 61.5 && (x.y - 345.0).abs() < 1.0,
            "{x:?}"
        );
        assert!(c.pieces()[2].p3.distance(x) < 1e-12);
        let f = super::super::flatten::flatten(&c, 1e-4).unwrap();
        assert!(self_intersections(&f.points[..f.points.len() - 1]).is_empty());
    }
}
