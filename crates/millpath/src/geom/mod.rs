//! Geometry: positions and directions, bounding boxes, outlines as arc polylines, holes
//! (circles recognised among outlines).
//!
//! Positions ([`Point`], [`Point3`]) and directions ([`Vec2`], [`Vec3`]) are separate types:
//! `Point - Point = Vec2`, `Point + Vec2 = Point`, and there is no `Point + Point`.

mod aabb;
mod hole;
mod loops;
pub(crate) mod nesting;
mod outline;
pub(crate) mod overlap;
mod point;
pub(crate) mod region;
mod vec3;

pub use aabb::Aabb;
pub use hole::{CIRCLE_TOLERANCE, Hole};
pub use nesting::{Pocket, nest};
pub use outline::{MAX_BULGE, MAX_COORDINATE_MM, Outline, Winding, area_less_islands};
pub use point::{Point, Vec2};
pub use vec3::{Point3, Vec3};

/// Tolerance below which two lengths in millimetres are considered equal when deciding
/// topology (coincident points, closed outlines). It is far below any machining tolerance
/// (the smallest the engine accepts is 1e-5 mm) and far above f64 rounding at part sizes.
pub const LENGTH_EPS: f64 = 1e-9;

/// Millimetres per inch (exact, by definition).
pub const MM_PER_INCH: f64 = 25.4;
