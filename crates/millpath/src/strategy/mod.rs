//! Strategies: turn geometry into toolpaths (contour, pockets, facing).

pub mod contour;
pub mod face;
pub mod pocket;
