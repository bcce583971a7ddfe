//! Reports: SVG previews of toolpaths (`svg`), plots over plain data series (`plots`) and a
//! self-contained interactive HTML report ([`html`]); [`series`] extracts plot data from plans.

pub mod five_axis_plots;
pub mod html;
pub mod plots;
pub mod series;
mod svg;

pub use svg::{PreviewOptions, level_previews, toolpath_svg};
