//! What an importer read from a drawing: its closed outlines in mm, the units it read them
//! in, and everything it did not use, counted by kind with the reason.
//!
//! A DXF or SVG reader fills a [`Drawing`]; [`Drawing::into_loops`] hands the outlines to
//! [`classify`] (outer outline and islands). A drawing with no closed outline is refused with
//! a message that says what the file holds and what was skipped, e.g.
//!
//! ```text
//! invalid closed outlines = 0 in lc_screw.dxf (read 23 LINE, 4 ARC; open chain of 27
//! pieces, 61.2 mm long, open at (…) and (…): gap 8.0000 mm) …
//! ```

use super::join::OpenChain;
use super::outline_json::{Loops, classify};
use crate::error::InputError;
use crate::geom::{Aabb, Outline};
use std::collections::{BTreeMap, BTreeSet};
use std::fmt::Write as _;

/// How an importer reads a drawing. Built from [`Default`] with the `with_*` methods (the struct is
/// `#[non_exhaustive]`: new settings do not break callers).
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct ReadOptions {
    /// Largest distance between a curve (spline, ellipse, Bézier, an arc under a non-uniform
    /// scale) and its flattening, mm. Circular arcs stay exact.
    pub tolerance: f64,
    /// Largest gap between two piece ends that are joined, mm (see `super::join`).
    pub join_tolerance: f64,
    /// Only the outlines on this layer (DXF layer name; SVG `<g>` whose `inkscape:label` or
    /// `id` is this name, with everything inside it).
    pub layer: Option<String>,
    /// Millimetres per drawing unit, overriding what the file says (DXF `$INSUNITS` /
    /// `$MEASUREMENT`; SVG user units from `width`/`height`/`viewBox`).
    pub mm_per_unit: Option<f64>,
}

/// The default flattening tolerance, mm.
pub const DEFAULT_TOLERANCE_MM: f64 = 0.001;
/// The default join tolerance, mm: below any machining tolerance, above the rounding of
/// coordinates written with 4–6 decimals by CAD exporters.
pub const DEFAULT_JOIN_TOLERANCE_MM: f64 = 0.01;

impl Default for ReadOptions {
    fn default() -> Self {
        ReadOptions {
            tolerance: DEFAULT_TOLERANCE_MM,
            join_tolerance: DEFAULT_JOIN_TOLERANCE_MM,
            layer: None,
            mm_per_unit: None,
        }
    }
}

option_builders! {
    ReadOptions;
    /// Sets [`ReadOptions::tolerance`], mm.
    with_tolerance => tolerance: f64;
    /// Sets [`ReadOptions::join_tolerance`], mm.
    with_join_tolerance => join_tolerance: f64;
    /// Sets [`ReadOptions::layer`].
    with_layer => layer: Option<String>;
    /// Sets [`ReadOptions::mm_per_unit`], mm per drawing unit.
    with_mm_per_unit => mm_per_unit: Option<f64>;
}

impl ReadOptions {
    /// Checks the tolerances and the unit override; `origin` names the file.
    pub fn validate(&self, origin: &str) -> Result<(), InputError> {
        let ok = |v: f64| v.is_finite() && v > 0.0;
        if !(ok(self.tolerance) && self.tolerance >= 1e-6) {
            return Err(InputError::new("flattening tolerance", self.tolerance)
                .at(origin)
                .expected("a finite number ≥ 1e-6 mm"));
        }
        if !(ok(self.join_tolerance) || self.join_tolerance == 0.0) || self.join_tolerance > 10.0 {
            return Err(InputError::new("join tolerance", self.join_tolerance)
                .at(origin)
                .expected("a number from 0 to 10 mm"));
        }
        if let Some(s) = self.mm_per_unit
            && !ok(s)
        {
            return Err(InputError::new("drawing unit", s)
                .at(origin)
                .expected("a positive number of mm per drawing unit"));
        }
        Ok(())
    }
}

/// The closed outlines of a drawing and an account of the rest.
#[derive(Debug, Clone, Default)]
pub struct Drawing {
    /// Closed outlines, mm, as the file draws them (windings not normalised).
    pub outlines: Vec<Outline>,
    /// The units read: e.g. `"in ($MEASUREMENT = 0)"`.
    pub units: String,
    /// Millimetres per drawing unit applied.
    pub mm_per_unit: f64,
    /// Entities (DXF) or elements (SVG) read, by kind.
    pub counts: BTreeMap<String, usize>,
    /// Entities or elements not used, by kind and reason: how many.
    pub skipped: BTreeMap<(String, String), usize>,
    /// Pieces that joined into no closed outline.
    pub open: Vec<OpenChain>,
    /// Pieces of zero length dropped.
    pub degenerate: usize,
    /// The layers the file has (DXF layers; SVG groups with a label or id).
    pub layers: BTreeSet<String>,
    /// The layer read, when only one was.
    pub layer: Option<String>,
}

impl Drawing {
    /// Counts one entity or element of `kind` read.
    pub fn count(&mut self, kind: &str) {
        *self.counts.entry(kind.to_owned()).or_default() += 1;
    }

    /// Counts one entity or element of `kind` skipped, and why.
    pub fn skip(&mut self, kind: &str, why: &str) {
        *self
            .skipped
            .entry((kind.to_owned(), why.to_owned()))
            .or_default() += 1;
    }

    /// Adds the closed loops `loops` as outlines, runs of lines on one circle within
    /// `tolerance` mm read back as arcs (`super::arcs`); one that is not a valid outline
    /// (self-intersecting, zero area, out of range) is skipped and the reason kept.
    pub fn add_closed(&mut self, loops: &[super::affine::Piece], origin: &str, tolerance: f64) {
        for (k, lp) in loops.iter().enumerate() {
            match Outline::new(lp, &format!("{origin}, closed outline {k}")) {
                Ok(o) => self.outlines.push(super::arcs::with_arcs(o, tolerance)),
                Err(e) => self.skip("closed outline", &e.to_string()),
            }
        }
    }

    /// The extents of the closed outlines, mm.
    pub fn extents(&self) -> Aabb {
        self.outlines
            .iter()
            .fold(Aabb::EMPTY, |a, o| a.union(o.bounds()))
    }

    /// One paragraph: what was read, in which units, the extents, what was skipped.
    pub fn summary(&self) -> String {
        let mut s = String::new();
        let read: Vec<String> = self
            .counts
            .iter()
            .map(|(k, n)| format!("{n} {k}"))
            .collect();
        let _ = write!(
            s,
            "read {} in {}",
            if read.is_empty() {
                "nothing".to_owned()
            } else {
                read.join(", ")
            },
            self.units
        );
        if let Some(l) = &self.layer {
            let _ = write!(s, ", layer {l:?}");
        }
        let _ = write!(s, "; {} closed outline", self.outlines.len());
        if self.outlines.len() != 1 {
            s.push('s');
        }
        let e = self.extents();
        if !e.is_empty() {
            let _ = write!(
                s,
                ", extents ({:.4}, {:.4}) to ({:.4}, {:.4}) mm ({:.4} × {:.4} mm)",
                e.min.x,
                e.min.y,
                e.max.x,
                e.max.y,
                e.width(),
                e.height()
            );
        }
        for ((k, why), n) in &self.skipped {
            let _ = write!(s, "; skipped {n} {k} ({why})");
        }
        if self.degenerate > 0 {
            let _ = write!(s, "; dropped {} zero-length piece(s)", self.degenerate);
        }
        for c in self.open.iter().take(3) {
            let _ = write!(s, "; {}", c.describe());
        }
        if self.open.len() > 3 {
            let _ = write!(s, "; {} more open chains", self.open.len() - 3);
        }
        s
    }

    /// An open chain that looks like a broken outline rather than a construction line: at
    /// least three pieces whose ends come within 2 % of the chain's length.
    pub fn nearly_closed(&self) -> Option<&OpenChain> {
        self.open
            .iter()
            .filter(|c| c.pieces >= 3 && c.gap() <= 0.02 * c.length)
            .min_by(|a, b| a.gap().total_cmp(&b.gap()))
    }

    /// The outer outline and islands ([`classify`]); refused when nothing is closed, or when a
    /// chain of pieces almost closes (a gap wider than the join tolerance).
    pub fn into_loops(self, origin: &str, join_tolerance: f64) -> Result<Loops, InputError> {
        if let Some(c) = self.nearly_closed() {
            return Err(InputError::new("outline", c.describe())
                .at(origin)
                .expected(format!(
                    "closed outlines: ends within the join tolerance {join_tolerance} mm \
                     (--join-tolerance {:.4} would close this one); {}",
                    c.gap() * 1.01,
                    self.summary()
                )));
        }
        if self.outlines.is_empty() {
            return Err(self.nothing_closed(origin));
        }
        classify(self.outlines, origin)
    }

    /// The error for a drawing with no closed outline.
    pub fn nothing_closed(&self, origin: &str) -> InputError {
        InputError::new("closed outlines", format!("0 ({})", self.summary()))
            .at(origin)
            .expected("at least one closed outline")
    }
}
