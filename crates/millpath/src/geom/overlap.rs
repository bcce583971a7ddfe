//! Closed outlines of a drawing that touch, cross or repeat each other, resolved the way the
//! CAD program drew them, before they are nested ([`super::nesting`]).
//!
//! Real drawings hold outlines that are not apart or nested: a HATCH whose boundary paths
//! share an edge, a part sketched from overlapping rectangles, a notch drawn as a rectangle
//! over a panel's edge, the same outline twice. Each touching pair (an intersection, an
//! overlapping stretch, or a vertex of one within [`TOUCH_EPS`] of the other) is resolved by
//! what it means on the drawing, with a note:
//!
//! * **repeat**: every vertex of each within [`DUPLICATE_EPS`] of the other and the areas
//!   within `DUPLICATE_EPS` × the perimeter: the later one is dropped;
//! * **inside, touching the wall**: one outline's region holds the other's (their union is
//!   the larger one, to 1e-6 of its area): the pair becomes the larger less the smaller —
//!   the notch or slot an island drawn against a wall cuts into it (what even-odd nesting
//!   gives: the smaller outline is one level deeper);
//! * **overlapping or side by side**: neither holds the other: the pair becomes their
//!   union, the region either one draws (a HATCH's external paths, a shape built from
//!   overlapping pieces); holes of the union become islands.
//!
//! ```text
//!   ┌─────┬──┐            ┌────────┐          ┌──┐  ┌──┐
//!   │  ┌──┼──┼─┐   ──▶    │        └─┐        │  └──┘  │   a notch: ┌─┐ over the top edge
//!   │  │  │  │ │          │          │        │        │
//!   └──┼──┘  │ │          └─┐        │        └────────┘
//!      └─────┴─┘            └────────┘
//! ```
//!
//! **Single-point contacts.** Where the union or difference touches itself at a point (two
//! pockets drawn corner to corner: a figure 8; an island touching its pocket's wall at one
//! point; two HATCH paths whose union leaves an unfilled strip touching the outline at a
//! corner, `ez_clockwise_arcs_hatch.dxf`), no outline can be a simple loop. Such a point is
//! one where the two outlines meet and two stretches of the result's boundary pass (a vertex
//! of its non-sliver loops within [`TOUCH_EPS`], counted twice). Each is opened by a disc of
//! material of radius [`POINT_CONTACT_RADIUS`] (0.01 mm) taken from both outlines before the
//! boolean is taken again: `(A − D) ∪ (B − D) = (A ∪ B) − D`, `(A − D) − (B − D) = A − B − D`.
//! The figure 8 becomes two pockets 0.02 mm apart, the touching island a notch in the
//! wall; what is lost is a disc no tool reaches (the point lies in a corner of every piece,
//! where a tool of radius `r` leaves a cusp far larger than 0.01 mm), and the pocket is
//! verified against the opened outline, the more conservative one (its walls are the drawn
//! walls plus the disc).
//!
//! ```text
//!   ┌────┐                 ┌────┐
//!   │ A  │                 │ A  ╲          a point contact, opened by a 0.01 mm disc
//!   └────●────┐    ──▶     └─────╮ ╭────┐
//!        │ B  │                   ╲│ B  │
//!        └────┘                    └────┘
//! ```
//!
//! Booleans are cavalier_contours' (arcs stay exact) with positions equal within
//! [`TOUCH_EPS`]; pieces of the result with less than [`COLLAPSED_AREA`], or thinner than
//! [`TOUCH_EPS`] on average, are slivers of rounding and dropped, and vertices closer than
//! [`REDUNDANT_EPS`] merged. A pair the booleans still cannot separate (outlines that come
//! within [`TOUCH_EPS`] without meeting, a contact the disc does not open) is refused with
//! an input error naming both outlines (their index in the order read and a vertex of each),
//! where they meet, and what to do: draw them apart or read one layer (`--layer`).
//!
//! **Cost.** One intersection test per pair with overlapping bounds (as nesting's), and one
//! boolean per touching pair; a drawing with nothing touching pays only the test.

use super::region::TOUCH_EPS;
use super::{Aabb, Outline, Point};
use crate::error::InputError;
use cavalier_contours::polyline::{BooleanOp, PlineBooleanOptions, PlineSource, Polyline};

/// Largest distance between two outlines' vertices for them to be the same outline drawn
/// twice, mm (the join tolerance's default: coordinates rounded by an exporter).
pub const DUPLICATE_EPS: f64 = 0.01;

/// Smallest area of a piece a boolean leaves, mm²; less is a sliver of rounding.
pub const COLLAPSED_AREA: f64 = 1e-6;

/// Radius of the disc of material a single-point contact is opened by, mm: far below any
/// tool's radius (no tool reaches a point where two walls meet), far above [`TOUCH_EPS`]
/// (the opened outlines are apart to the touch test), and the default join tolerance.
pub const POINT_CONTACT_RADIUS: f64 = 0.01;

/// Vertices of a boolean's result closer than this are one, mm (cavalier_contours' default
/// position epsilon): two drawn edges 3 µm apart leave a jog that short, which the outline's
/// self-intersection test (at the same epsilon) would take for a crossing.
pub const REDUNDANT_EPS: f64 = 1e-5;

/// The outlines after resolving every touching pair, and what was done, one note a pair.
#[derive(Debug, Clone, Default)]
pub struct Resolved {
    /// Outlines that neither touch nor cross.
    pub outlines: Vec<Outline>,
    /// What was merged, cut or dropped, in words.
    pub notes: Vec<String>,
}

/// One outline and the names of the drawn outlines it came from (1-based, order read).
struct Tracked {
    outline: Outline,
    /// The drawn outlines it came from, indices in the order read.
    members: Vec<usize>,
    name: String,
    bounds: Aabb,
}

impl Tracked {
    fn new(outline: Outline, members: Vec<usize>) -> Self {
        let bounds = outline.bounds();
        let name = members
            .iter()
            .map(|m| (m + 1).to_string())
            .collect::<Vec<_>>()
            .join("+");
        Tracked {
            outline,
            members,
            name,
            bounds,
        }
    }
}

fn bounds_overlap(a: Aabb, b: Aabb) -> bool {
    let a = a.inflate(TOUCH_EPS);
    a.min.x <= b.max.x && b.min.x <= a.max.x && a.min.y <= b.max.y && b.min.y <= a.max.y
}

fn first_vertex(o: &Outline) -> Point {
    // `+ 0.0` writes −0 as 0.
    o.vertices()
        .next()
        .map_or(Point::ORIGIN, |v| Point::new(v.0.x + 0.0, v.0.y + 0.0))
}

fn same_outline(a: &Outline, b: &Outline) -> bool {
    let (aa, ab) = (a.signed_area().abs(), b.signed_area().abs());
    (aa - ab).abs() <= DUPLICATE_EPS * a.length().max(b.length())
        && a.vertices().all(|v| b.distance_to(v.0) <= DUPLICATE_EPS)
        && b.vertices().all(|v| a.distance_to(v.0) <= DUPLICATE_EPS)
}

/// A piece of a boolean's result that is rounding: less than [`COLLAPSED_AREA`], or thinner
/// than [`TOUCH_EPS`] on average (twice the area over the perimeter; an arc traced out and
/// back at 1e5 mm has 4e-6 mm²).
fn sliver(p: &Polyline<f64>) -> bool {
    let a = p.area().abs();
    a < COLLAPSED_AREA || 2.0 * a < TOUCH_EPS * p.path_length()
}

/// The pieces of a boolean result as outlines (holes included), slivers dropped; `None` when
/// one is not a simple outline (two outlines touching at a corner unite into a figure 8).
fn pieces(
    result: cavalier_contours::polyline::BooleanResult<Polyline<f64>>,
    origin: &str,
) -> Option<Vec<Outline>> {
    result
        .pos_plines
        .into_iter()
        .chain(result.neg_plines)
        .map(|p| {
            let p = p.pline;
            p.remove_redundant(REDUNDANT_EPS).unwrap_or(p)
        })
        .filter(|p| !sliver(p))
        .map(|p| Outline::from_polyline(p, origin).ok())
        .collect()
}

/// Resolves touching, crossing and repeated outlines (see the module docs); `origin` names
/// the drawing.
pub fn resolve(loops: Vec<Outline>, origin: &str) -> Result<Resolved, InputError> {
    let mut items: Vec<Tracked> = loops
        .into_iter()
        .enumerate()
        .map(|(k, o)| Tracked::new(o, vec![k]))
        .collect();
    // The drawn pairs that touch; nothing more to do when there are none.
    let touching: Vec<(usize, usize)> = (0..items.len())
        .flat_map(|i| ((i + 1)..items.len()).map(move |j| (i, j)))
        .filter(|&(i, j)| {
            bounds_overlap(items[i].bounds, items[j].bounds)
                && touch_point(&items[i].outline, &items[j].outline).is_some()
        })
        .collect();
    let mut notes = Vec::new();
    if touching.is_empty() {
        return Ok(Resolved {
            outlines: items.into_iter().map(|t| t.outline).collect(),
            notes,
        });
    }
    let opts = PlineBooleanOptions {
        pos_equal_eps: TOUCH_EPS,
        collapsed_area_eps: Some(COLLAPSED_AREA),
        ..PlineBooleanOptions::default()
    };
    // Every resolution removes at least one outline; bounded anyway.
    let budget = 4 * items.len() + 16;
    let mut start = 0;
    for _ in 0..budget {
        let Some((i, j, at)) = first_touch(&items, start) else {
            absorb(&mut items, &touching, &mut notes);
            return Ok(Resolved {
                outlines: items.into_iter().map(|t| t.outline).collect(),
                notes,
            });
        };
        start = i;
        let (a, b) = (&items[i], &items[j]);
        let refuse = |why: &str| ambiguous(a, b, at, origin, why);
        if same_outline(&a.outline, &b.outline) {
            notes.push(format!(
                "outline {} repeats outline {} (every vertex within {DUPLICATE_EPS} mm): \
                 dropped",
                b.name, a.name
            ));
            items.remove(j);
            continue;
        }
        let (aa, ab) = (a.outline.signed_area().abs(), b.outline.signed_area().abs());
        let (big, small) = if aa >= ab { (i, j) } else { (j, i) };
        let (pa, pb) = (a.outline.polyline(), b.outline.polyline());
        let holds = holds_other(pa, pb, aa.max(ab), &opts, origin);
        let (pg, ps) = if big == i { (pa, pb) } else { (pb, pa) };
        let (result, opened) = match combine(pg, ps, holds, &opts, origin) {
            Ok(r) => (r, Vec::new()),
            Err(why) => {
                // Touching at single points: opened there by a small disc, then again.
                let at_points = pinch_points(pg, ps, holds, at, &opts);
                let opened = open_at(pg, &at_points, &opts)
                    .zip(open_at(ps, &at_points, &opts))
                    .filter(|_| !at_points.is_empty());
                let Some((g, s)) = opened else {
                    return Err(refuse(why));
                };
                match combine(&g, &s, holds, &opts, origin) {
                    Ok(r) => (r, at_points),
                    Err(why) => return Err(refuse(why)),
                }
            }
        };
        let (nb, ns) = (&items[big].name, &items[small].name);
        let mut note = if holds {
            format!(
                "outline {ns} lies inside outline {nb} against its edge near ({:.3}, {:.3}): \
                 cut as {nb} less {ns} (a notch in its wall)",
                at.x, at.y
            )
        } else if opened.is_empty() {
            format!(
                "outlines {} and {} overlap or share an edge near ({:.3}, {:.3}): cut as their \
                 union",
                a.name, b.name, at.x, at.y
            )
        } else {
            format!(
                "outlines {} and {} meet near ({:.3}, {:.3}): cut as their union",
                a.name, b.name, at.x, at.y
            )
        };
        if !opened.is_empty() {
            let list: Vec<String> = opened
                .iter()
                .map(|p| format!("({:.3}, {:.3})", p.x + 0.0, p.y + 0.0))
                .collect();
            note.push_str(&format!(
                ", which touches itself at a single point ({}): opened there by a \
                 {POINT_CONTACT_RADIUS} mm disc of material (a point no tool reaches)",
                list.join(", ")
            ));
        }
        let mut members = items[i].members.clone();
        members.extend(&items[j].members);
        members.sort_unstable();
        notes.push(note);
        items.remove(j);
        items.remove(i);
        for o in result.into_iter().rev() {
            items.insert(i, Tracked::new(o, members.clone()));
        }
    }
    Err(InputError::new("closed outlines", "touching pairs")
        .at(origin)
        .expected(format!(
            "outlines whose overlaps resolve within {budget} unions and differences"
        )))
}

/// True when one of the pair's regions holds the other: their union is one outline of the
/// larger's area (to 1e-6 of it).
fn holds_other(
    pa: &Polyline<f64>,
    pb: &Polyline<f64>,
    area_big: f64,
    opts: &PlineBooleanOptions<'_, f64>,
    origin: &str,
) -> bool {
    pieces(pa.boolean_opt(pb, BooleanOp::Or, opts), origin).is_some_and(|u| {
        u.len() == 1 && (u[0].signed_area().abs() - area_big).abs() <= 1e-6 * area_big
    })
}

/// The pair resolved: `big` less `small` when `holds`, else their union; the reason it
/// cannot be when a piece touches itself or another piece.
fn combine(
    big: &Polyline<f64>,
    small: &Polyline<f64>,
    holds: bool,
    opts: &PlineBooleanOptions<'_, f64>,
    origin: &str,
) -> Result<Vec<Outline>, &'static str> {
    const PINCHED: &str = "their union or difference touches itself at a point";
    let op = if holds { BooleanOp::Not } else { BooleanOp::Or };
    let result = pieces(big.boolean_opt(small, op, opts), origin).ok_or(PINCHED)?;
    if result.is_empty() {
        return Err("nothing is left of the pair");
    }
    // The pieces of one boolean must be apart, else the pair is not resolved.
    for (x, p) in result.iter().enumerate() {
        for q in &result[x + 1..] {
            if bounds_overlap(p.bounds(), q.bounds()) && touch_point(p, q).is_some() {
                return Err(
                    "resolving them leaves pieces that touch at a point or come within 1 µm",
                );
            }
        }
    }
    Ok(result)
}

/// Where the pair's union (or difference, when `holds`) touches itself: the points where
/// the two outlines meet (and `at`) that two stretches of the result's boundary pass through
/// (a vertex of the result within [`TOUCH_EPS`], counted over all its loops).
fn pinch_points(
    big: &Polyline<f64>,
    small: &Polyline<f64>,
    holds: bool,
    at: Point,
    opts: &PlineBooleanOptions<'_, f64>,
) -> Vec<Point> {
    let hits = big.find_intersects(small);
    let mut candidates: Vec<Point> = vec![at];
    candidates.extend(
        hits.basic_intersects
            .iter()
            .map(|h| Point::new(h.point.x, h.point.y)),
    );
    for h in &hits.overlapping_intersects {
        candidates.push(Point::new(h.point1.x, h.point1.y));
        candidates.push(Point::new(h.point2.x, h.point2.y));
    }
    let op = if holds { BooleanOp::Not } else { BooleanOp::Or };
    let r = big.boolean_opt(small, op, opts);
    let loops: Vec<Polyline<f64>> = r
        .pos_plines
        .into_iter()
        .chain(r.neg_plines)
        .map(|p| p.pline.remove_redundant(REDUNDANT_EPS).unwrap_or(p.pline))
        .filter(|p| !sliver(p))
        .collect();
    let mut out: Vec<Point> = Vec::new();
    for c in candidates {
        let passes: usize = loops
            .iter()
            .map(|l| {
                l.iter_vertexes()
                    .filter(|v| Point::new(v.x, v.y).distance(c) <= TOUCH_EPS)
                    .count()
            })
            .sum();
        if passes >= 2 && out.iter().all(|q| q.distance(c) > POINT_CONTACT_RADIUS) {
            out.push(c);
        }
    }
    out
}

/// `pl` less a disc of radius [`POINT_CONTACT_RADIUS`] about each point; `None` when that
/// is not one outline.
fn open_at(
    pl: &Polyline<f64>,
    at: &[Point],
    opts: &PlineBooleanOptions<'_, f64>,
) -> Option<Polyline<f64>> {
    use cavalier_contours::polyline::PlineSourceMut;
    let mut out = pl.clone();
    for p in at {
        let w = POINT_CONTACT_RADIUS;
        let mut disc = Polyline::new_closed();
        disc.add(p.x - w, p.y, 1.0);
        disc.add(p.x + w, p.y, 1.0);
        let mut r = out.boolean_opt(&disc, BooleanOp::Not, opts);
        if r.pos_plines.len() != 1 || !r.neg_plines.is_empty() {
            return None;
        }
        out = r.pos_plines.pop()?.pline;
    }
    Some(out)
}

/// A union can swallow the crossings of a third outline with one of its members (outline 6
/// crossed 4, and lies inside 4 ∪ 5): an outline left nested without touching in one whose
/// members it touched as drawn is part of that union, and is dropped. A hole of a union (two
/// C shapes closing a ring) has the union's own members and stays: an island.
fn absorb(items: &mut Vec<Tracked>, touching: &[(usize, usize)], notes: &mut Vec<String>) {
    // Pieces of one boolean share their members (a union's hole is no absorbed outline).
    let touched = |a: &Tracked, b: &Tracked| {
        a.members.iter().all(|m| !b.members.contains(m))
            && touching.iter().any(|&(x, y)| {
                (a.members.contains(&x) && b.members.contains(&y))
                    || (a.members.contains(&y) && b.members.contains(&x))
            })
    };
    while let Some((outer, inner)) = (0..items.len())
        .flat_map(|i| (0..items.len()).map(move |j| (i, j)))
        .find(|&(i, j)| {
            i != j
                && items[i].bounds.contains(items[j].bounds.min)
                && items[i].bounds.contains(items[j].bounds.max)
                && items[i].outline.contains(first_vertex(&items[j].outline))
                && touched(&items[i], &items[j])
        })
    {
        notes.push(format!(
            "outline {} crosses outline {} as drawn and lies inside their union: absorbed",
            items[inner].name, items[outer].name
        ));
        let gone = items.remove(inner);
        let k = if inner < outer { outer - 1 } else { outer };
        items[k].members.extend(gone.members);
    }
}

/// The first touching pair at or after outline `start` (in the current order): indices and
/// where they meet.
fn first_touch(items: &[Tracked], start: usize) -> Option<(usize, usize, Point)> {
    let n = items.len();
    (start..n).chain(0..start).find_map(|i| {
        ((i + 1)..n).find_map(|j| {
            if !bounds_overlap(items[i].bounds, items[j].bounds) {
                return None;
            }
            touch_point(&items[i].outline, &items[j].outline).map(|p| (i, j, p))
        })
    })
}

fn ambiguous(a: &Tracked, b: &Tracked, at: Point, origin: &str, why: &str) -> InputError {
    let (va, vb) = (first_vertex(&a.outline), first_vertex(&b.outline));
    InputError::new(
        "closed outlines",
        format!(
            "{} (from ({:.3}, {:.3})) and {} (from ({:.3}, {:.3}))",
            a.name, va.x, va.y, b.name, vb.x, vb.y
        ),
    )
    .at(format!(
        "{origin}, where they meet near ({:.3}, {:.3}); {why}",
        at.x + 0.0,
        at.y + 0.0
    ))
    .expected(
        "closed outlines that are apart, nested, overlapping or repeated (a wall of zero \
         thickness at one point cannot be machined): draw them apart, or read one layer \
         with --layer",
    )
}

/// Where two closed loops meet: an intersection point, or a vertex of one within
/// [`TOUCH_EPS`] of the other; `None` when they are apart.
pub fn touch_point(a: &Outline, b: &Outline) -> Option<Point> {
    let (pa, pb) = (a.polyline(), b.polyline());
    let hits = pa.find_intersects(pb);
    if let Some(h) = hits.basic_intersects.first() {
        return Some(Point::new(h.point.x, h.point.y));
    }
    if let Some(h) = hits.overlapping_intersects.first() {
        return Some(Point::new(h.point1.x, h.point1.y));
    }
    let near = |p: &Outline, q: &Outline| {
        p.vertices()
            .map(|v| v.0)
            .find(|&v| q.distance_to(v) <= TOUCH_EPS)
    };
    near(a, b).or_else(|| near(b, a))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Outline {
        let p = Point::new;
        Outline::from_points(&[p(x0, y0), p(x1, y0), p(x1, y1), p(x0, y1)], "t").expect("rect")
    }

    fn areas(r: &Resolved) -> Vec<f64> {
        let mut a: Vec<f64> = r.outlines.iter().map(|o| o.signed_area().abs()).collect();
        a.sort_by(f64::total_cmp);
        a
    }

    #[test]
    fn overlapping_outlines_become_their_union() {
        // Two 40 × 40 squares overlapping by 10 × 20, and one apart.
        let r = resolve(
            vec![
                rect(0.0, 0.0, 40.0, 40.0),
                rect(30.0, 10.0, 60.0, 30.0),
                rect(100.0, 0.0, 110.0, 10.0),
            ],
            "d",
        )
        .expect("resolves");
        assert_eq!(areas(&r), vec![100.0, 1600.0 + 600.0 - 200.0]);
        assert_eq!(r.notes.len(), 1);
        assert!(
            r.notes[0].contains("outlines 1 and 2 overlap"),
            "{}",
            r.notes[0]
        );
    }

    #[test]
    fn a_ring_of_overlapping_outlines_keeps_its_hole() {
        // Four 10-wide bars around a 20 × 20 hole, each overlapping the next at a corner.
        let r = resolve(
            vec![
                rect(0.0, 0.0, 40.0, 10.0),
                rect(30.0, 0.0, 40.0, 40.0),
                rect(0.0, 30.0, 40.0, 40.0),
                rect(0.0, 0.0, 10.0, 40.0),
            ],
            "d",
        )
        .expect("resolves");
        assert_eq!(areas(&r), vec![400.0, 1600.0]);
        let p = crate::geom::nesting::nest(r.outlines, "d").expect("nests");
        assert_eq!(p.len(), 1);
        assert_eq!(p[0].islands.len(), 1);
        assert!((p[0].area() - 1200.0).abs() < 1e-9);
    }

    #[test]
    fn an_outline_against_its_parents_wall_is_a_notch() {
        // A 10 × 20 rectangle inside a 60 × 90 panel, its top on the panel's top edge.
        let r = resolve(
            vec![rect(0.0, 0.0, 60.0, 90.0), rect(10.0, 70.0, 20.0, 90.0)],
            "d",
        )
        .expect("resolves");
        assert_eq!(areas(&r), vec![5400.0 - 200.0]);
        assert!(!r.outlines[0].contains(Point::new(15.0, 80.0)));
        assert!(r.outlines[0].contains(Point::new(30.0, 80.0)));
        assert!(
            r.notes[0].contains("outline 2 lies inside outline 1"),
            "{}",
            r.notes[0]
        );
    }

    /// Independent of the booleans: the area of `o` sampled on a grid over `[x0, x1] ×
    /// [y0, y1]` at `h`, by `Outline::contains`.
    fn grid_area(o: &[Outline], x0: f64, y0: f64, x1: f64, y1: f64, h: f64) -> f64 {
        let (nx, ny) = (((x1 - x0) / h) as usize, ((y1 - y0) / h) as usize);
        let mut n = 0usize;
        for i in 0..nx {
            for j in 0..ny {
                let p = Point::new(x0 + (i as f64 + 0.5) * h, y0 + (j as f64 + 0.5) * h);
                if o.iter().filter(|l| l.contains(p)).count() % 2 == 1 {
                    n += 1;
                }
            }
        }
        n as f64 * h * h
    }

    #[test]
    fn corner_to_corner_outlines_become_two_pockets_apart() {
        let r = resolve(
            vec![rect(0.0, 0.0, 10.0, 10.0), rect(10.0, 10.0, 20.0, 20.0)],
            "c.svg",
        )
        .expect("a point contact is opened");
        assert_eq!(r.outlines.len(), 2, "{:?}", r.notes);
        assert!(
            r.notes[0].contains("opened there by a 0.01 mm disc")
                && r.notes[0].contains("(10.000, 10.000)"),
            "{}",
            r.notes[0]
        );
        // Apart: no touch, and nesting makes them two pockets with no island.
        assert!(touch_point(&r.outlines[0], &r.outlines[1]).is_none());
        let p = crate::geom::nesting::nest(r.outlines.clone(), "c.svg").expect("nests");
        assert_eq!(p.len(), 2);
        assert!(p.iter().all(|q| q.islands.is_empty()));
        // What was lost: two quarter discs of radius 0.01 mm.
        let lost = 200.0 - areas(&r).iter().sum::<f64>();
        let quarter = std::f64::consts::PI * 1e-4 / 4.0;
        assert!((lost - 2.0 * quarter).abs() < 1e-9, "{lost}");
        // The drawn squares, sampled on a grid, are the result everywhere off the disc.
        let g = grid_area(&r.outlines, 0.0, 0.0, 20.0, 20.0, 0.1);
        assert!((g - 200.0).abs() < 1e-9, "{g}");
    }

    #[test]
    fn an_island_touching_its_wall_at_a_point_is_a_notch() {
        // A diamond inside a 40 × 40 square, its bottom corner on the bottom edge.
        let p = Point::new;
        let diamond = Outline::from_points(
            &[p(20.0, 0.0), p(25.0, 5.0), p(20.0, 10.0), p(15.0, 5.0)],
            "t",
        )
        .expect("diamond");
        let r = resolve(vec![rect(0.0, 0.0, 40.0, 40.0), diamond], "d").expect("opened");
        assert_eq!(r.outlines.len(), 1, "{:?}", r.notes);
        assert!(
            r.notes[0].contains("lies inside outline 1"),
            "{}",
            r.notes[0]
        );
        assert!(r.notes[0].contains("(20.000, 0.000)"), "{}", r.notes[0]);
        let o = &r.outlines[0];
        assert!(!o.contains(p(20.0, 5.0)) && o.contains(p(5.0, 5.0)));
        // 1600 less the diamond (50) less a half disc of 0.01 mm (the diamond's corner
        // already holds a quarter of it).
        let a = o.signed_area().abs();
        let half = std::f64::consts::PI * 1e-4 / 2.0;
        assert!(
            (a - (1550.0 - half + std::f64::consts::PI * 1e-4 / 4.0)).abs() < 1e-6,
            "{a}"
        );
        let g = grid_area(&r.outlines, 0.0, 0.0, 40.0, 40.0, 0.1);
        assert!((g - 1550.0).abs() < 0.2, "{g}");
    }

    #[test]
    fn repeats_are_dropped() {
        let r = resolve(
            vec![rect(0.0, 0.0, 10.0, 10.0), rect(0.0, 0.0, 10.0, 10.004)],
            "d",
        )
        .expect("resolves");
        assert_eq!(r.outlines.len(), 1);
        assert!(
            r.notes[0].contains("outline 2 repeats outline 1"),
            "{}",
            r.notes[0]
        );
    }
}
