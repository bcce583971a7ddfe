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
//! Booleans are cavalier_contours' (arcs stay exact) with positions equal within
//! [`TOUCH_EPS`]; pieces of the result with less than [`COLLAPSED_AREA`], or thinner than
//! [`TOUCH_EPS`] on average, are slivers of rounding and dropped, and vertices closer than
//! [`REDUNDANT_EPS`] merged. A pair the booleans cannot separate (outlines that touch at a
//! single point, or come within [`TOUCH_EPS`] without crossing) is refused with an input
//! error naming both outlines (their index in the order read and a vertex of each), where
//! they meet, and what to do: draw them apart or read one layer (`--layer`).
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
        // A sliver: less than COLLAPSED_AREA, or thinner than TOUCH_EPS on average (twice
        // the area over the perimeter; an arc traced out and back at 1e5 mm has 4e-6 mm²).
        .filter(|p| {
            let a = p.area().abs();
            a >= COLLAPSED_AREA && 2.0 * a >= TOUCH_EPS * p.path_length()
        })
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
        let (pa, pb) = (a.outline.polyline(), b.outline.polyline());
        const PINCHED: &str = "their union or difference touches itself at a point";
        let Some(union) = pieces(pa.boolean_opt(pb, BooleanOp::Or, &opts), origin) else {
            return Err(refuse(PINCHED));
        };
        let (aa, ab) = (a.outline.signed_area().abs(), b.outline.signed_area().abs());
        let (big, small) = if aa >= ab { (i, j) } else { (j, i) };
        let area_big = aa.max(ab);
        let holds =
            union.len() == 1 && (union[0].signed_area().abs() - area_big).abs() <= 1e-6 * area_big;
        let (result, note) = if holds {
            let (pg, ps) = (
                items[big].outline.polyline(),
                items[small].outline.polyline(),
            );
            let Some(less) = pieces(pg.boolean_opt(ps, BooleanOp::Not, &opts), origin) else {
                return Err(refuse(PINCHED));
            };
            let note = format!(
                "outline {} lies inside outline {} against its edge near ({:.3}, {:.3}): cut \
                 as {} less {} (a notch in its wall)",
                items[small].name, items[big].name, at.x, at.y, items[big].name, items[small].name
            );
            (less, note)
        } else {
            let note = format!(
                "outlines {} and {} overlap or share an edge near ({:.3}, {:.3}): cut as their \
                 union",
                a.name, b.name, at.x, at.y
            );
            (union, note)
        };
        if result.is_empty() {
            return Err(refuse("nothing is left of the pair"));
        }
        // The pieces of one boolean must be apart, else the pair is not resolved.
        for (x, p) in result.iter().enumerate() {
            for q in &result[x + 1..] {
                if bounds_overlap(p.bounds(), q.bounds()) && touch_point(p, q).is_some() {
                    return Err(refuse(
                        "resolving them leaves pieces that touch at a point or come within 1 µm",
                    ));
                }
            }
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

    #[test]
    fn repeats_are_dropped_and_point_contacts_refused() {
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
        let e = resolve(
            vec![rect(0.0, 0.0, 10.0, 10.0), rect(10.0, 10.0, 20.0, 20.0)],
            "c.svg",
        )
        .expect_err("a point contact is ambiguous")
        .to_string();
        assert!(
            e.contains("1 (from (0.000, 0.000)) and 2 (from (10.000, 10.000))"),
            "{e}"
        );
        assert!(
            e.contains("c.svg, where they meet near (10.000, 10.000)"),
            "{e}"
        );
        assert!(e.contains("--layer"), "{e}");
    }
}
