//! Built-in sample pockets.
//!
//! * [`aerospace_pocket`]: the paper's test pocket, 150 × 100 mm with 6 mm corner radii
//!   (cut 25 mm deep with a 12.7 mm end mill at 40% stepover and 600 in/min).
//! * [`structural_part`]: a part with several pockets of a wing rib, after the paper's
//!   Figure 17: rectangles, a trapezoid, an L and a triangle-like pocket, with rounded corners.

use super::PocketShape;
use crate::geom::{Outline, Point};

/// Bulge of a 90° counter-clockwise arc: tan(90°/4).
const QUARTER: f64 = 0.414_213_562_373_095_03;

/// A rectangle `w × h` with lower-left corner `(x, y)` and corner radius `rc`.
pub fn rounded_rectangle(x: f64, y: f64, w: f64, h: f64, rc: f64) -> Outline {
    let v = [
        (Point::new(x + rc, y), 0.0),
        (Point::new(x + w - rc, y), QUARTER),
        (Point::new(x + w, y + rc), 0.0),
        (Point::new(x + w, y + h - rc), QUARTER),
        (Point::new(x + w - rc, y + h), 0.0),
        (Point::new(x + rc, y + h), QUARTER),
        (Point::new(x, y + h - rc), 0.0),
        (Point::new(x, y + rc), QUARTER),
    ];
    // The literal sample is valid; fall back to a plain rectangle if it ever were not.
    Outline::new(&v, "built-in rounded rectangle").unwrap_or_else(|_| plain(x, y, w, h))
}

fn plain(x: f64, y: f64, w: f64, h: f64) -> Outline {
    let pts = [
        Point::new(x, y),
        Point::new(x + w, y),
        Point::new(x + w, y + h),
        Point::new(x, y + h),
    ];
    match Outline::from_points(&pts, "built-in rectangle") {
        Ok(o) => o,
        Err(_) => unreachable_outline(),
    }
}

#[allow(clippy::panic)]
fn unreachable_outline() -> Outline {
    // A unit square is always valid; this is never reached.
    panic!("built-in sample outline rejected")
}

/// A polygon with every corner rounded to `rc` (convex corners only need `rc` below half the
/// shortest edge). Corners are given counter-clockwise.
pub fn rounded_polygon(corners: &[Point], rc: f64, origin: &str) -> Option<Outline> {
    let n = corners.len();
    let mut v = Vec::with_capacity(2 * n);
    for i in 0..n {
        let p = corners[i];
        let prev = corners[(i + n - 1) % n];
        let next = corners[(i + 1) % n];
        let a = (prev - p).normalize()?;
        let b = (next - p).normalize()?;
        let turn = (-a).cross(b); // > 0: left (convex for CCW)
        let half = 0.5 * (-a).dot(b).clamp(-1.0, 1.0).acos(); // half the turning angle
        let t = rc * half.tan();
        let bulge = (half * 2.0 / 4.0).tan() * turn.signum();
        v.push((p + a * t, bulge));
        v.push((p + b * t, 0.0));
    }
    Outline::new(&v, origin).ok()
}

/// The paper's aerospace test pocket: 150 × 100 mm, 6 mm corner radii, centred at the origin.
pub fn aerospace_pocket() -> PocketShape {
    PocketShape::simple(rounded_rectangle(-75.0, -50.0, 150.0, 100.0, 6.0))
}

/// Several pockets of a structural part (after the paper's Figure 17), each simply connected.
pub fn structural_part() -> Vec<(String, PocketShape)> {
    let mut out = vec![
        (
            "bay-1 rectangle 120x80".to_owned(),
            PocketShape::simple(rounded_rectangle(0.0, 0.0, 120.0, 80.0, 8.0)),
        ),
        (
            "bay-2 square 80x80".to_owned(),
            PocketShape::simple(rounded_rectangle(130.0, 0.0, 80.0, 80.0, 8.0)),
        ),
        (
            "bay-3 slot 150x40".to_owned(),
            PocketShape::simple(rounded_rectangle(0.0, 90.0, 150.0, 40.0, 6.0)),
        ),
    ];
    let trapezoid = [
        Point::new(160.0, 90.0),
        Point::new(260.0, 90.0),
        Point::new(240.0, 150.0),
        Point::new(180.0, 150.0),
    ];
    if let Some(o) = rounded_polygon(&trapezoid, 8.0, "built-in trapezoid") {
        out.push(("bay-4 trapezoid".to_owned(), PocketShape::simple(o)));
    }
    let ell = [
        Point::new(0.0, 140.0),
        Point::new(110.0, 140.0),
        Point::new(110.0, 180.0),
        Point::new(45.0, 180.0),
        Point::new(45.0, 240.0),
        Point::new(0.0, 240.0),
    ];
    if let Some(o) = rounded_polygon(&ell, 8.0, "built-in L") {
        out.push(("bay-5 L".to_owned(), PocketShape::simple(o)));
    }
    let tri = [
        Point::new(130.0, 170.0),
        Point::new(250.0, 170.0),
        Point::new(140.0, 250.0),
    ];
    if let Some(o) = rounded_polygon(&tri, 10.0, "built-in triangle") {
        out.push(("bay-6 triangle".to_owned(), PocketShape::simple(o)));
    }
    out
}
