//! Importers (point lists, DXF, SVG) and atomic file output.

mod atomic;
pub mod points;

pub use atomic::{write_atomic, write_atomic_with};
pub mod dxf;
pub mod dxf_out;
pub mod outline_json;
pub mod svg;
