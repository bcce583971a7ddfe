//! Importers (point lists, DXF, SVG, JSON outlines) and atomic file output.
//!
//! The DXF and SVG readers share `drawing` (options, what was read and skipped),
//! `affine` (block and `transform` maps) and `join` (open pieces chained into outlines).

pub(crate) mod affine;
pub(crate) mod arcs;
mod atomic;
pub(crate) mod drawing;
pub(crate) mod join;
pub mod points;

pub use atomic::{write_atomic, write_atomic_with};
pub use drawing::{Drawing, ReadOptions};
pub use outline_source::{
    ImportSettings, mm_per_unit, read_outline_bytes, read_outline_file, read_outlines, read_text,
};
pub mod dxf;
pub(crate) mod dxf_out;
pub mod outline_json;
mod outline_source;
pub mod svg;

pub use drawing::{DEFAULT_JOIN_TOLERANCE_MM, DEFAULT_TOLERANCE_MM};
pub use dxf_out::write_outlines as write_dxf;
