//! SVG path data (`d`) to pieces with bulges, in user units.
//!
//! Path data is read with `svgtypes`. Lines stay lines; circular arcs (`A` with `rx = ry`,
//! radius scaled up per the SVG rules when too small for the chord) stay exact arcs: with
//! chord `c` and radius `R`, the smaller sweep is `θ = 2·asin(c/2R)`, the larger `2π − θ`,
//! and the bulge is `±tan(θ/4)`, positive for SVG's sweep flag 1 (the angle-increasing
//! direction). Elliptical arcs and Bézier curves are flattened within `tolerance` (kurbo).
//! Every curve's points are checked against [`MAX_COORDINATE_MM`] before flattening (kurbo's
//! subdivision count overflows on control points near 1e308).

use crate::error::InputError;
use crate::geom::{MAX_COORDINATE_MM, Point};
use crate::io::affine::Piece;
use kurbo::{BezPath, PathEl, Shape as _};
use svgtypes::{PathParser, PathSegment};

/// The smallest flattening tolerance, mm: with coordinates within
/// [`MAX_COORDINATE_MM`] it bounds the points a curve flattens to
/// (kurbo's subdivision count grows like `sqrt(size / tolerance)`) to about a million.
pub const MIN_TOLERANCE_MM: f64 = 1e-6;

/// The subpaths of path data `d`, in user units: a closed one (`Z`, or ending on its start)
/// with its first vertex repeated at the end, an open one as it is.
pub fn subpaths(d: &str, tol: f64, at: &str) -> Result<Vec<Piece>, InputError> {
    let mut out = Vec::new();
    let mut cur: Piece = Vec::new();
    let mut pos = Point::ORIGIN;
    let mut start = Point::ORIGIN;
    let mut last_ctrl: Option<Point> = None;
    let bad = |e: String| {
        InputError::new("SVG path data", e)
            .at(at.to_owned())
            .expected("valid SVG path data")
    };
    let close = |cur: &mut Piece, out: &mut Vec<Piece>| {
        if cur.len() > 1 {
            out.push(std::mem::take(cur));
        } else {
            cur.clear();
        }
    };
    // Curves are checked before flattening: kurbo's subdivision count overflows (a panic in
    // `Vec::with_capacity`) on control points at 1e308 or beyond.
    let flatten_into = |cur: &mut Piece, path: &BezPath| -> Result<(), InputError> {
        for el in path.iter() {
            for p in el_points(&el) {
                if !(p.x.abs() <= MAX_COORDINATE_MM && p.y.abs() <= MAX_COORDINATE_MM) {
                    return Err(
                        InputError::new("SVG curve point", format!("({}, {})", p.x, p.y))
                            .at(at.to_owned())
                            .expected(format!("finite coordinates within ±{MAX_COORDINATE_MM} mm")),
                    );
                }
            }
        }
        kurbo::flatten(path.iter(), tol, |el| {
            if let PathEl::LineTo(p) = el {
                cur.push((Point::new(p.x, p.y), 0.0));
            }
        });
        Ok(())
    };
    for seg in PathParser::from(d) {
        let seg = seg.map_err(|e| bad(e.to_string()))?;
        let rel = |abs: bool, x: f64, y: f64| {
            if abs {
                Point::new(x, y)
            } else {
                Point::new(pos.x + x, pos.y + y)
            }
        };
        let mut ctrl_next = None;
        match seg {
            PathSegment::MoveTo { abs, x, y } => {
                close(&mut cur, &mut out);
                pos = rel(abs, x, y);
                start = pos;
                cur = vec![(pos, 0.0)];
            }
            PathSegment::LineTo { abs, x, y } => {
                pos = rel(abs, x, y);
                cur.push((pos, 0.0));
            }
            PathSegment::HorizontalLineTo { abs, x } => {
                pos = if abs {
                    Point::new(x, pos.y)
                } else {
                    Point::new(pos.x + x, pos.y)
                };
                cur.push((pos, 0.0));
            }
            PathSegment::VerticalLineTo { abs, y } => {
                pos = if abs {
                    Point::new(pos.x, y)
                } else {
                    Point::new(pos.x, pos.y + y)
                };
                cur.push((pos, 0.0));
            }
            PathSegment::CurveTo {
                abs,
                x1,
                y1,
                x2,
                y2,
                x,
                y,
            } => {
                let (c1, c2, e) = (rel(abs, x1, y1), rel(abs, x2, y2), rel(abs, x, y));
                let mut p = BezPath::new();
                p.move_to((pos.x, pos.y));
                p.curve_to((c1.x, c1.y), (c2.x, c2.y), (e.x, e.y));
                flatten_into(&mut cur, &p)?;
                pos = e;
                ctrl_next = Some(c2);
            }
            PathSegment::SmoothCurveTo { abs, x2, y2, x, y } => {
                let c1 =
                    last_ctrl.map_or(pos, |c| Point::new(2.0 * pos.x - c.x, 2.0 * pos.y - c.y));
                let (c2, e) = (rel(abs, x2, y2), rel(abs, x, y));
                let mut p = BezPath::new();
                p.move_to((pos.x, pos.y));
                p.curve_to((c1.x, c1.y), (c2.x, c2.y), (e.x, e.y));
                flatten_into(&mut cur, &p)?;
                pos = e;
                ctrl_next = Some(c2);
            }
            PathSegment::Quadratic { abs, x1, y1, x, y } => {
                let (c, e) = (rel(abs, x1, y1), rel(abs, x, y));
                let mut p = BezPath::new();
                p.move_to((pos.x, pos.y));
                p.quad_to((c.x, c.y), (e.x, e.y));
                flatten_into(&mut cur, &p)?;
                pos = e;
                ctrl_next = Some(c);
            }
            PathSegment::SmoothQuadratic { abs, x, y } => {
                let c = last_ctrl.map_or(pos, |c| Point::new(2.0 * pos.x - c.x, 2.0 * pos.y - c.y));
                let e = rel(abs, x, y);
                let mut p = BezPath::new();
                p.move_to((pos.x, pos.y));
                p.quad_to((c.x, c.y), (e.x, e.y));
                flatten_into(&mut cur, &p)?;
                pos = e;
                ctrl_next = Some(c);
            }
            PathSegment::EllipticalArc {
                abs,
                rx,
                ry,
                x_axis_rotation,
                large_arc,
                sweep,
                x,
                y,
            } => {
                let e = rel(abs, x, y);
                let (rx, ry) = (rx.abs(), ry.abs());
                let chord = pos.distance(e);
                if chord < 1e-12 {
                } else if rx < 1e-12 || ry < 1e-12 {
                    cur.push((e, 0.0));
                } else if (rx - ry).abs() <= 1e-9 * rx.max(ry) {
                    let r = rx.max(0.5 * chord);
                    let small = 2.0 * (chord / (2.0 * r)).clamp(-1.0, 1.0).asin();
                    let theta = if large_arc {
                        std::f64::consts::TAU - small
                    } else {
                        small
                    };
                    let bulge = (theta / 4.0).tan() * if sweep { 1.0 } else { -1.0 };
                    if let Some(last) = cur.last_mut() {
                        last.1 = bulge;
                    }
                    cur.push((e, 0.0));
                } else {
                    let arc = kurbo::SvgArc {
                        from: (pos.x, pos.y).into(),
                        to: (e.x, e.y).into(),
                        radii: (rx, ry).into(),
                        x_rotation: x_axis_rotation.to_radians(),
                        large_arc,
                        sweep,
                    };
                    match kurbo::Arc::from_svg_arc(&arc) {
                        Some(a) => {
                            // kurbo cuts an arc into about (1.1163·R/t)^(1/6)·|sweep|/2π
                            // cubics (R the larger radius, t = tol/10): a half turn of radius
                            // 1e55 mm was ~2·10⁹ of them (7.5 GB, an abort found by the
                            // `outline_importers` fuzzer). An arc within ±MAX_COORDINATE_MM
                            // needs a few hundred; more than a million is refused.
                            let r = a.radii.x.max(a.radii.y);
                            let cubics = (1.1163 * r / (0.1 * tol)).powf(1.0 / 6.0)
                                * a.sweep_angle.abs()
                                / std::f64::consts::TAU;
                            if cubics.is_nan() || cubics > 1e6 {
                                return Err(InputError::new(
                                    "SVG arc",
                                    format!(
                                        "radii ({rx}, {ry}) sweeping {:.1}°",
                                        a.sweep_angle.to_degrees()
                                    ),
                                )
                                .at(at.to_owned())
                                .expected(format!(
                                    "an elliptical arc within ±{MAX_COORDINATE_MM} mm"
                                )));
                            }
                            let p = a.to_path(0.1 * tol);
                            flatten_into(&mut cur, &p)?;
                        }
                        None => cur.push((e, 0.0)),
                    }
                }
                pos = e;
            }
            PathSegment::ClosePath { .. } => {
                // The closing segment (or, on the start already, the last vertex moved
                // exactly onto it).
                match cur.last_mut() {
                    Some(l) if l.0.distance(start) <= 1e-9 => l.0 = start,
                    _ => cur.push((start, 0.0)),
                }
                pos = start;
                close(&mut cur, &mut out);
                cur = vec![(pos, 0.0)];
            }
        }
        last_ctrl = ctrl_next;
    }
    close(&mut cur, &mut out);
    Ok(out)
}

/// The points of a path element.
fn el_points(el: &PathEl) -> Vec<kurbo::Point> {
    match *el {
        PathEl::MoveTo(p) | PathEl::LineTo(p) => vec![p],
        PathEl::QuadTo(a, b) => vec![a, b],
        PathEl::CurveTo(a, b, c) => vec![a, b, c],
        PathEl::ClosePath => Vec::new(),
    }
}
