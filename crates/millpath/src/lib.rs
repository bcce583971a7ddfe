//! # millpath — a CAM engine
//!
//! millpath turns part outlines and a machine description into G-code, a cycle time that a
//! real controller will reproduce, and pictures of what will happen.
//!
//! The crate is layered; every arrow points one way:
//!
//! ```text
//! io (DXF, SVG, CSV, JSON, G-code)
//!   → geom (points, vectors, outlines as arc polylines)
//!   → curve (four-point cubics, blends, splines, flattening, biarcs)
//!   → strategy (contour, pockets) → toolpath (moves with feeds)
//!   → motion (machine limits, jerk-limited look-ahead planning) → gcode (dialects)
//!   → report (JSON, SVG, plots, HTML)
//! ```
//!
//! Verifiers ([`stock`], the limit checks in [`motion`], dense deviation sampling in [`curve`])
//! read toolpaths and plans and share no code with what made them.
//!
//! ## Units and conventions
//! Millimetres, seconds and radians inside, all `f64`. Feeds are stored in mm/s; inches and
//! mm/min or in/min appear only at the edges (G-code, CLI, machine files). Outlines are
//! counter-clockwise and islands clockwise once imported.
//!
//! ## Errors
//! Two families, see [`Error`]: [`InputError`] is the user's to fix (it names the value, where
//! it came from and what would be accepted), [`InternalError`] is a bug to report.

/// `with_*` builders of an options struct, one per line `NAME => FIELD(.FIELD)* : TYPE;`
/// (with its doc): each sets the field and returns the options. Declared before the modules,
/// so every module may use it without an import.
macro_rules! option_builders {
    ($opts:ty; $($(#[$doc:meta])* $name:ident => $($field:ident).+ : $ty:ty;)*) => {
        impl $opts {
            $(
                $(#[$doc])*
                #[must_use]
                pub fn $name(mut self, value: $ty) -> Self {
                    self.$($field).+ = value;
                    self
                }
            )*
        }
    };
}

pub mod calibrate;
pub mod curve;
pub mod error;
pub mod gcode;
pub mod geom;
pub mod io;
pub mod job;
pub mod machine;
pub mod motion;
pub mod report;
pub mod stock;
pub mod strategy;
pub mod toolpath;

pub use error::{Error, InputError, InternalError, Result};
pub use geom::{Point, Point3, Vec2, Vec3};
pub use toolpath::{Move, MoveKind, Tool, Toolpath};
