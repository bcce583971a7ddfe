//! The pockets of a whole drawing: closed outlines nested by containment.
//!
//! A drawing holds closed outlines in any order and winding. [`nest`] sorts them by area
//! (largest first) and gives each its **parent**, the smallest outline that contains it;
//! its **depth** is the number of outlines around it. Even depth is a pocket boundary, odd
//! depth an island of its parent's pocket, and an outline inside an island (depth 2) is a
//! pocket again:
//!
//! ```text
//!  ┌──────────────── depth 0: pocket 1 ───────────────┐   ┌─ depth 0: pocket 2 ─┐
//!  │   ┌──── depth 1: island ────┐                    │   │                     │
//!  │   │  ┌ depth 2: pocket 3 ┐  │                    │   └─────────────────────┘
//!  │   │  └───────────────────┘  │                    │
//!  │   └─────────────────────────┘                    │
//!  └──────────────────────────────────────────────────┘
//! ```
//!
//! Windings are normalised (pocket boundaries counter-clockwise, islands clockwise).
//!
//! **Containment.** Outlines that touch, cross, overlap or repeat are first resolved as the
//! drawing means them ([`super::overlap`]: a union, a notch, a repeat dropped; a point contact
//! opened by a 0.01 mm disc of material). Outlines that neither touch nor cross
//! are either nested or apart, so one point of an outline decides whether another contains
//! it (its first vertex, by winding number).
//!
//! **Order.** Pockets are listed by decreasing area (a tie by the lower-left corner of their
//! bounds), which does not depend on the order the CAD program wrote the entities in, nor on
//! the drawing's scale or position; the pocket command's `--select` uses this order (1-based).
//!
//! **Cost.** Pairs are tested only when their bounds overlap: `O(n²)` bound tests, and one
//! intersection test per overlapping pair (`O(m log m)` in their vertex counts).

use super::{Outline, Point, Winding};
use crate::error::InputError;

/// One pocket of a drawing: its boundary and its islands.
#[derive(Debug, Clone)]
pub struct Pocket {
    /// The boundary, counter-clockwise.
    pub outer: Outline,
    /// Islands, clockwise.
    pub islands: Vec<Outline>,
}

impl Pocket {
    /// Area of material to remove: the boundary's area less the islands', mm².
    pub fn area(&self) -> f64 {
        super::outline::area_less_islands(&self.outer, &self.islands)
    }

    /// True when `p` lies inside the boundary and outside every island.
    pub fn contains(&self, p: Point) -> bool {
        self.outer.contains(p) && !self.islands.iter().any(|i| i.contains(p))
    }
}

fn first_vertex(o: &Outline) -> Point {
    o.vertices().next().map_or(Point::ORIGIN, |v| v.0)
}

/// Nests closed outlines by containment into pockets (see the module docs); `origin` names
/// the drawing. At least one outline is needed.
pub fn nest(loops: Vec<Outline>, origin: &str) -> Result<Vec<Pocket>, InputError> {
    nest_noted(loops, origin).map(|(p, _)| p)
}

/// [`nest`], with the notes of what [`super::overlap::resolve`] merged, cut or dropped.
pub fn nest_noted(
    loops: Vec<Outline>,
    origin: &str,
) -> Result<(Vec<Pocket>, Vec<String>), InputError> {
    if loops.is_empty() {
        return Err(InputError::new("closed outlines", 0)
            .at(origin)
            .expected("at least one closed outline"));
    }
    let resolved = super::overlap::resolve(loops, origin)?;
    let loops = resolved.outlines;
    let bounds: Vec<_> = loops.iter().map(|o| o.bounds()).collect();
    let mut order: Vec<usize> = (0..loops.len()).collect();
    let area = |i: usize| loops[i].signed_area().abs();
    order.sort_by(|&a, &b| {
        area(b)
            .total_cmp(&area(a))
            .then(bounds[a].min.x.total_cmp(&bounds[b].min.x))
            .then(bounds[a].min.y.total_cmp(&bounds[b].min.y))
    });
    // Parent: the smallest earlier (larger) outline containing the first vertex.
    let mut depth = vec![0usize; loops.len()];
    let mut parent: Vec<Option<usize>> = vec![None; loops.len()];
    for (x, &j) in order.iter().enumerate() {
        let p = first_vertex(&loops[j]);
        if let Some(&i) = order[..x]
            .iter()
            .rev()
            .find(|&&i| bounds[i].contains(p) && loops[i].contains(p))
        {
            parent[j] = Some(i);
            depth[j] = depth[i] + 1;
        }
    }
    let mut slots: Vec<Option<Outline>> = loops.into_iter().map(Some).collect();
    let mut pocket_of = vec![usize::MAX; slots.len()];
    let mut pockets: Vec<Pocket> = Vec::new();
    for &j in &order {
        let Some(o) = slots[j].take() else { continue };
        if depth[j] % 2 == 0 {
            pocket_of[j] = pockets.len();
            pockets.push(Pocket {
                outer: o.with_winding(Winding::CounterClockwise),
                islands: Vec::new(),
            });
        } else if let Some(k) = parent[j].map(|i| pocket_of[i]) {
            if let Some(pk) = pockets.get_mut(k) {
                pk.islands.push(o.with_winding(Winding::Clockwise));
            }
        }
    }
    // Pockets by decreasing area of material (islands taken off).
    pockets.sort_by(|a, b| {
        b.area()
            .total_cmp(&a.area())
            .then(a.outer.bounds().min.x.total_cmp(&b.outer.bounds().min.x))
            .then(a.outer.bounds().min.y.total_cmp(&b.outer.bounds().min.y))
    });
    Ok((pockets, resolved.notes))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(x: f64, y: f64, s: f64, ccw: bool) -> Outline {
        let mut p = vec![
            Point::new(x, y),
            Point::new(x + s, y),
            Point::new(x + s, y + s),
            Point::new(x, y + s),
        ];
        if !ccw {
            p.reverse();
        }
        Outline::from_points(&p, "test").expect("square")
    }

    #[test]
    fn nests_pockets_islands_and_pockets_in_islands() {
        // Two parts side by side; the first has an island with a pocket inside it.
        let loops = vec![
            square(20.0, 20.0, 10.0, true), // pocket inside the island
            square(0.0, 0.0, 100.0, false), // part 1 (given clockwise)
            square(150.0, 0.0, 40.0, true), // part 2
            square(10.0, 10.0, 30.0, true), // island of part 1 (given counter-clockwise)
        ];
        let p = nest(loops, "t").expect("nests");
        assert_eq!(p.len(), 3);
        assert!((p[0].area() - (10_000.0 - 900.0)).abs() < 1e-9);
        assert_eq!(p[0].islands.len(), 1);
        assert_eq!(p[0].outer.winding(), Winding::CounterClockwise);
        assert_eq!(p[0].islands[0].winding(), Winding::Clockwise);
        assert!((p[1].area() - 1600.0).abs() < 1e-9);
        assert!((p[2].area() - 100.0).abs() < 1e-9);
        assert!(p[2].contains(Point::new(25.0, 25.0)));
        assert!(!p[0].contains(Point::new(25.0, 25.0)));
    }

    #[test]
    fn overlapping_outlines_nest_as_their_union_and_point_contacts_are_opened() {
        // Side by side, sharing part of an edge: one pocket, their union.
        let loops = vec![square(0.0, 0.0, 10.0, true), square(10.0, 2.0, 5.0, true)];
        let (p, notes) = nest_noted(loops, "d.dxf").expect("resolves");
        assert_eq!(p.len(), 1);
        assert!((p[0].area() - 125.0).abs() < 1e-9);
        assert!(notes[0].contains("outlines 1 and 2 overlap"), "{notes:?}");
        // Corner to corner: two pockets, opened at the corner by a 0.01 mm disc.
        let corner = vec![square(0.0, 0.0, 10.0, true), square(10.0, 10.0, 5.0, true)];
        let (p, notes) = nest_noted(corner, "d.dxf").expect("opened");
        assert_eq!(p.len(), 2);
        let quarter = std::f64::consts::PI * 1e-4 / 4.0;
        assert!((p[0].area() - (100.0 - quarter)).abs() < 1e-9);
        assert!((p[1].area() - (25.0 - quarter)).abs() < 1e-9);
        assert!(notes[0].contains("(10.000, 10.000)"), "{notes:?}");
        assert!(nest(Vec::new(), "e").is_err());
    }
}
