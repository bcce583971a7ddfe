//! Strategies: turn geometry into toolpaths (contour, pockets, facing, holes), and the order
//! to visit a part's pockets or holes in.

pub(crate) mod adaptive;
pub mod contour;
pub mod drill;
pub mod face;
pub(crate) mod order;
pub mod pocket;
pub mod profile;
pub mod rest;

pub use order::{MULTI_START_MAX, TWO_OPT_MAX, order_tour, tour_length};
