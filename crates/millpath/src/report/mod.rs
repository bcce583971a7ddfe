//! Reports: SVG previews of toolpaths ([`svg`]), plots over plain data series ([`plots`]) and a
//! self-contained interactive HTML report ([`html`]).

pub mod html;
pub mod plots;
mod svg;

pub use svg::{PreviewOptions, toolpath_svg};
