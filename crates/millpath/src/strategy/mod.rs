//! Strategies: turn geometry into toolpaths (contour, pockets).

pub mod contour;
pub mod pocket;
pub mod profile;
