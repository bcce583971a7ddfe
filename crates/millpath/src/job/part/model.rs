//! What a drawing shows as a part: the outermost outlines are parts (cut out of the stock),
//! the outlines just inside a part are its pockets or, when they are circles, its holes, and
//! the outlines inside a pocket are its islands (bosses left standing), inside which the
//! pattern repeats.
//!
//! ```text
//!  ┌──────────────── part (depth 0) ──────────────────┐
//!  │   ┌──── pocket (depth 1) ───┐    ○ hole (a circle at depth 1)
//!  │   │  ┌ island (depth 2) ┐   │                    │
//!  │   │  └──────────────────┘   │                    │
//!  │   └─────────────────────────┘                    │
//!  └──────────────────────────────────────────────────┘
//! ```
//!
//! The nesting is the drawing reader's ([`crate::geom::nest`]: even depths are its pocket
//! boundaries, odd depths their islands); here an even-depth boundary other than an
//! outermost one becomes an island of the odd-depth outline around it.

use crate::geom::{Aabb, Outline, Pocket, Point, Winding};

/// A hole: a circle just inside a part.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ModelHole {
    /// Centre, mm.
    pub center: Point,
    /// Diameter, mm.
    pub diameter: f64,
    /// The part it is in (index into [`PartModel::parts`]).
    pub part: usize,
}

/// A pocket of a part: its boundary (counter-clockwise) and its islands (clockwise).
#[derive(Debug, Clone)]
pub struct ModelPocket {
    /// The boundary.
    pub outer: Outline,
    /// Islands standing in it.
    pub islands: Vec<Outline>,
    /// The part it is in.
    pub part: usize,
}

/// A drawing read as parts, pockets and holes.
#[derive(Debug, Clone)]
pub struct PartModel {
    /// The parts' outlines, counter-clockwise, largest first.
    pub parts: Vec<Outline>,
    /// Pockets, in the drawing's pocket order.
    pub pockets: Vec<ModelPocket>,
    /// Holes.
    pub holes: Vec<ModelHole>,
}

impl PartModel {
    /// The model of a drawing's nested outlines (`pockets` as [`crate::geom::nest`] gives
    /// them); `circle` tells whether an outline is a circle (its centre and diameter).
    pub fn new(pockets: &[Pocket], circle: &dyn Fn(&Outline) -> Option<(Point, f64)>) -> Self {
        // Each odd-depth outline (an island of a reader's pocket) and the reader's pocket it
        // belongs to.
        let islands: Vec<(usize, &Outline)> = pockets
            .iter()
            .enumerate()
            .flat_map(|(k, p)| p.islands.iter().map(move |i| (k, i)))
            .collect();
        // The smallest odd-depth outline around each reader's pocket, if any.
        let around: Vec<Option<usize>> = pockets
            .iter()
            .map(|p| {
                let at = first_vertex(&p.outer);
                islands
                    .iter()
                    .enumerate()
                    .filter(|(_, (_, i))| i.contains(at))
                    .min_by(|a, b| area(a.1.1).total_cmp(&area(b.1.1)))
                    .map(|(j, _)| j)
            })
            .collect();
        // Parts: the reader's pockets with nothing around them.
        let mut part_of = vec![usize::MAX; pockets.len()];
        let mut parts = Vec::new();
        for (k, p) in pockets.iter().enumerate() {
            if around[k].is_none() {
                part_of[k] = parts.len();
                parts.push(p.outer.clone().with_winding(Winding::CounterClockwise));
            }
        }
        // The part of every reader's pocket: follow the outlines around it outwards.
        for k in 0..pockets.len() {
            let mut at = k;
            let mut steps = 0;
            while let Some(j) = around[at]
                && steps <= pockets.len()
            {
                at = islands[j].0;
                steps += 1;
            }
            part_of[k] = part_of[at];
        }
        let mut model = PartModel {
            parts,
            pockets: Vec::new(),
            holes: Vec::new(),
        };
        for (j, (k, outline)) in islands.iter().enumerate() {
            let part = part_of[*k];
            let inside: Vec<Outline> = pockets
                .iter()
                .zip(&around)
                .filter(|(_, a)| **a == Some(j))
                .map(|(p, _)| p.outer.clone().with_winding(Winding::Clockwise))
                .collect();
            match circle(outline) {
                Some((center, diameter)) if inside.is_empty() => model.holes.push(ModelHole {
                    center,
                    diameter,
                    part,
                }),
                _ => model.pockets.push(ModelPocket {
                    outer: (*outline).clone().with_winding(Winding::CounterClockwise),
                    islands: inside,
                    part,
                }),
            }
        }
        model
    }

    /// The extents of every part.
    pub fn bounds(&self) -> Option<Aabb> {
        self.parts.iter().map(Outline::bounds).reduce(Aabb::union)
    }
}

fn first_vertex(o: &Outline) -> Point {
    o.vertices().next().map_or(Point::ORIGIN, |v| v.0)
}

fn area(o: &Outline) -> f64 {
    o.signed_area().abs()
}
