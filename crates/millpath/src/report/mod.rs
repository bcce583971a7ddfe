//! Reports: SVG previews of toolpaths (`svg`), plots over plain data series (`plots`) and a
//! self-contained interactive HTML report ([`html`]); `series` extracts plot data from plans.

pub(crate) mod five_axis_plots;
pub mod html;
pub mod plots;
pub(crate) mod series;
mod svg;

pub use five_axis_plots::{axis_charts, deflection_charts, deflection_path, deflection_profiles};
pub use series::{
    FeedPoints, axis_series, feed_along_cut, feed_along_path as feed_points, feed_chart,
};
pub use svg::{PreviewOptions, level_previews, toolpath_svg};
