//! Built-in sample pockets.
//!
//! * [`aerospace_pocket`]: the paper's test pocket, 150 × 100 mm with 6 mm corner radii
//!   (cut 25 mm deep with a 12.7 mm end mill at 40% stepover and 600 in/min).
//! * [`structural_part`]: a part with several pockets of a wing rib, after the paper's
//!   Figure 17: rectangles, a trapezoid, an L and a triangle-like pocket, with rounded corners.
//! * [`shape_suite`]: pockets whose medial axis branches or which have islands (L, T, U, a
//!   crescent with 30° tips, a star, a 6:1 slot, a dumbbell, two islands), each with the tool
//!   it is cut with; the strategies are compared on them (BENCHMARKS.md).

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

/// A pocket of [`shape_suite`]: its name, the pocket and the tool diameter it is cut with, mm.
#[derive(Debug, Clone)]
pub struct SuitePocket {
    /// Short name.
    pub name: &'static str,
    /// The pocket.
    pub shape: PocketShape,
    /// Tool diameter, mm.
    pub tool_diameter: f64,
}

/// Pockets whose medial axis branches, with sharp tips, long and thin, pinched, or with
/// islands; each with a 10 mm tool (the aerospace pocket, with its 12.7 mm tool, first).
pub fn shape_suite() -> Vec<SuitePocket> {
    let p = Point::new;
    let mut out = vec![SuitePocket {
        name: "aerospace",
        shape: aerospace_pocket(),
        tool_diameter: 12.7,
    }];
    let polys: [(&'static str, Vec<Point>); 5] = [
        (
            "L",
            vec![
                p(0.0, 0.0),
                p(120.0, 0.0),
                p(120.0, 40.0),
                p(40.0, 40.0),
                p(40.0, 100.0),
                p(0.0, 100.0),
            ],
        ),
        (
            "T",
            vec![
                p(40.0, 0.0),
                p(80.0, 0.0),
                p(80.0, 80.0),
                p(140.0, 80.0),
                p(140.0, 120.0),
                p(-20.0, 120.0),
                p(-20.0, 80.0),
                p(40.0, 80.0),
            ],
        ),
        (
            "U",
            vec![
                p(0.0, 0.0),
                p(120.0, 0.0),
                p(120.0, 100.0),
                p(85.0, 100.0),
                p(85.0, 35.0),
                p(35.0, 35.0),
                p(35.0, 100.0),
                p(0.0, 100.0),
            ],
        ),
        ("star", star(5, 65.0, 30.0)),
        (
            "dumbbell",
            vec![
                p(0.0, 0.0),
                p(70.0, 0.0),
                p(70.0, 25.0),
                p(120.0, 25.0),
                p(120.0, 0.0),
                p(190.0, 0.0),
                p(190.0, 70.0),
                p(120.0, 70.0),
                p(120.0, 45.0),
                p(70.0, 45.0),
                p(70.0, 70.0),
                p(0.0, 70.0),
            ],
        ),
    ];
    for (name, corners) in polys {
        let rc = if name == "star" { 2.0 } else { 6.0 };
        if let Some(o) = rounded_polygon(&corners, rc, name) {
            out.push(SuitePocket {
                name,
                shape: PocketShape::simple(o),
                tool_diameter: 10.0,
            });
        }
    }
    if let Some(o) = crescent(60.0, 50.0, 30f64.to_radians()) {
        out.push(SuitePocket {
            name: "crescent",
            shape: PocketShape::simple(o),
            tool_diameter: 10.0,
        });
    }
    out.push(SuitePocket {
        name: "slot 6:1",
        shape: PocketShape::simple(rounded_rectangle(0.0, 0.0, 180.0, 30.0, 8.0)),
        tool_diameter: 10.0,
    });
    let circle = |c: Point, r: f64| {
        Outline::new(
            &[(p(c.x - r, c.y), 1.0), (p(c.x + r, c.y), 1.0)],
            "built-in island",
        )
    };
    if let (Ok(a), Ok(b)) = (circle(p(45.0, 50.0), 15.0), circle(p(115.0, 50.0), 15.0))
        && let Ok(shape) = PocketShape::new(
            rounded_rectangle(0.0, 0.0, 160.0, 100.0, 6.0),
            vec![a, b],
            "built-in two-island pocket",
        )
    {
        out.push(SuitePocket {
            name: "two islands",
            shape,
            tool_diameter: 10.0,
        });
    }
    out
}

/// The corners of an `n`-pointed star, tips at radius `ro`, notches at `ri`, counter-clockwise.
fn star(n: usize, ro: f64, ri: f64) -> Vec<Point> {
    (0..2 * n)
        .map(|k| {
            let a = std::f64::consts::PI * k as f64 / n as f64 + std::f64::consts::FRAC_PI_2;
            let r = if k % 2 == 0 { ro } else { ri };
            Point::new(r * a.cos(), r * a.sin())
        })
        .collect()
}

/// The crescent inside the circle of radius `r1` about the origin and outside the circle of
/// radius `r2` about `(d, 0)`, with `d` chosen so that its two tips have interior angle
/// `tip` (the angle between the circles where they cross: `cos tip = (r1² + r2² − d²) /
/// (2·r1·r2)`).
fn crescent(r1: f64, r2: f64, tip: f64) -> Option<Outline> {
    let d = (r1 * r1 + r2 * r2 - 2.0 * r1 * r2 * tip.cos()).sqrt();
    let x = (d * d + r1 * r1 - r2 * r2) / (2.0 * d);
    let y = (r1 * r1 - x * x).sqrt();
    let top = Point::new(x, y);
    let bottom = Point::new(x, -y);
    // Outer arc counter-clockwise from the top tip round the left to the bottom tip.
    let sweep_outer = std::f64::consts::TAU - 2.0 * y.atan2(x);
    // Inner arc clockwise about (d, 0) from the bottom tip round its leftmost point to the top.
    let sweep_inner = std::f64::consts::TAU - 2.0 * y.atan2(x - d);
    Outline::new(
        &[
            (top, (0.25 * sweep_outer).tan()),
            (bottom, -(0.25 * sweep_inner).tan()),
        ],
        "built-in crescent",
    )
    .ok()
}
