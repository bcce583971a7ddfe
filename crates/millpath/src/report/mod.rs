//! Reports: SVG previews of toolpaths (plots and the HTML report build on these).

mod svg;

pub use svg::{PreviewOptions, toolpath_svg};
