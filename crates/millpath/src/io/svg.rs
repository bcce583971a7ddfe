//! Pocket outlines from SVG: `<path d="…">` and `<circle>` elements.
//!
//! Path data is read with `svgtypes`; every closed subpath (`Z`, or ending on its start) is a
//! loop. Lines stay lines; circular arcs (`A` with `rx = ry`, radius scaled up per the SVG
//! rules when too small for the chord) stay exact arcs: with chord `c` and radius `R`, the
//! smaller sweep is `θ = 2·asin(c/2R)`, the larger `2π − θ`, and the bulge is `±tan(θ/4)`,
//! positive for SVG's sweep flag 1 (the angle-increasing direction). Elliptical arcs and
//! Bézier curves are flattened within `tolerance` (kurbo). SVG's y axis points down, so the
//! result is mirrored (`y → −y`, bulges negated) to show the drawing the right way up; the
//! importer then normalises the windings. `transform` attributes are refused rather than
//! silently ignored.

use super::outline_json::{Loops, classify};
use crate::error::InputError;
use crate::geom::{MAX_COORDINATE_MM, Outline, Point};
use kurbo::{BezPath, PathEl, Shape as _};
use svgtypes::{PathParser, PathSegment};

/// Reads the loops of an SVG document; `tolerance` bounds the flattening of curves, mm.
pub fn parse(text: &str, origin: &str, tolerance: f64) -> Result<Loops, InputError> {
    if !(tolerance.is_finite() && tolerance >= MIN_TOLERANCE_MM) {
        return Err(InputError::new("SVG flattening tolerance", tolerance)
            .at(origin)
            .expected(format!("a finite number ≥ {MIN_TOLERANCE_MM} mm")));
    }
    let mut loops: Vec<Outline> = Vec::new();
    for (n, tag) in tags(text).enumerate() {
        let at = format!("{origin}, element {n} <{}>", tag.0);
        if attr(tag.1, "transform").is_some() {
            return Err(InputError::new(
                "SVG transform",
                attr(tag.1, "transform").unwrap_or_default(),
            )
            .at(at)
            .expected("outlines without transforms (apply them in the drawing program)"));
        }
        match tag.0 {
            "path" => {
                let Some(d) = attr(tag.1, "d") else { continue };
                for (k, v) in path_loops(&d, tolerance, &at)?.into_iter().enumerate() {
                    let flipped: Vec<(Point, f64)> =
                        v.iter().map(|(p, b)| (Point::new(p.x, -p.y), -b)).collect();
                    loops.push(Outline::new(&flipped, &format!("{at}, subpath {k}"))?);
                }
            }
            "circle" => {
                let num = |name: &str| -> Result<f64, InputError> {
                    attr(tag.1, name)
                        .and_then(|v| v.trim().trim_end_matches("px").parse::<f64>().ok())
                        .ok_or_else(|| {
                            InputError::new(format!("circle {name}"), "missing")
                                .at(at.clone())
                                .expected("a number")
                        })
                };
                let (cx, cy, r) = (
                    num("cx").unwrap_or(0.0),
                    num("cy").unwrap_or(0.0),
                    num("r")?,
                );
                loops.push(Outline::new(
                    &[
                        (Point::new(cx - r, -cy), 1.0),
                        (Point::new(cx + r, -cy), 1.0),
                    ],
                    &at,
                )?);
            }
            _ => {}
        }
    }
    classify(loops, origin)
}

/// `(name, attributes)` of the `<path` and `<circle` start tags.
fn tags(text: &str) -> impl Iterator<Item = (&'static str, &str)> {
    text.split('<').filter_map(|t| {
        let end = t.find('>').unwrap_or(t.len());
        let body = &t[..end];
        if let Some(rest) = body.strip_prefix("path") {
            Some(("path", rest))
        } else {
            body.strip_prefix("circle").map(|rest| ("circle", rest))
        }
    })
}

/// The value of attribute `name` in a start tag's attribute text.
fn attr(attrs: &str, name: &str) -> Option<String> {
    let mut rest = attrs;
    while let Some(i) = rest.find(name) {
        let before_ok = i == 0 || rest[..i].ends_with(|c: char| c.is_whitespace());
        let after = rest[i + name.len()..].trim_start();
        if before_ok && let Some(v) = after.strip_prefix('=') {
            let v = v.trim_start();
            let q = v.chars().next()?;
            if q == '"' || q == '\'' {
                let inner = &v[1..];
                return inner.find(q).map(|e| inner[..e].to_owned());
            }
        }
        rest = &rest[i + name.len()..];
    }
    None
}

type Piece = Vec<(Point, f64)>;

/// The smallest flattening tolerance, mm: with coordinates within
/// [`MAX_COORDINATE_MM`] it bounds the points a curve flattens to
/// (kurbo's subdivision count grows like `sqrt(size / tolerance)`) to about a million.
pub const MIN_TOLERANCE_MM: f64 = 1e-6;

/// The closed subpaths of path data `d`, in SVG coordinates.
fn path_loops(d: &str, tol: f64, at: &str) -> Result<Vec<Piece>, InputError> {
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
            if let (Some(f), Some(l)) = (cur.first(), cur.last())
                && f.0.distance(l.0) < 1e-9
            {
                cur.pop();
            }
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
                if cur.len() > 1 {
                    return Err(InputError::new(
                        "outline",
                        format!("open subpath ending at ({:.4}, {:.4})", pos.x, -pos.y),
                    )
                    .at(at.to_owned())
                    .expected("closed subpaths (end with Z)"));
                }
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
                if pos.distance(start) > 1e-9 {
                    cur.push((start, 0.0));
                }
                pos = start;
                close(&mut cur, &mut out);
                cur = vec![(pos, 0.0)];
            }
        }
        last_ctrl = ctrl_next;
    }
    if cur.len() > 1 {
        let closed = cur
            .first()
            .zip(cur.last())
            .is_some_and(|(f, l)| f.0.distance(l.0) < 1e-9);
        if !closed {
            return Err(InputError::new(
                "outline",
                format!("open subpath ending at ({:.4}, {:.4})", pos.x, -pos.y),
            )
            .at(at.to_owned())
            .expected("closed subpaths (end with Z)"));
        }
        close(&mut cur, &mut out);
    }
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rounded_square_keeps_arcs_and_islands() {
        let svg = r#"<svg><path d="M 0 0 H 10 A 5 5 0 0 1 10 10 H 0 Z"/>
                     <circle cx="4" cy="5" r="1"/></svg>"#;
        let l = parse(svg, "t.svg", 0.001).unwrap();
        let area = 100.0 + std::f64::consts::PI * 12.5;
        assert!(
            (l.outer.signed_area() - area).abs() < 1e-9,
            "{}",
            l.outer.signed_area()
        );
        assert_eq!(l.islands.len(), 1);
    }

    #[test]
    fn open_path_is_an_error() {
        let e = parse(r#"<path d="M 0 0 L 10 0 L 10 10"/>"#, "o.svg", 0.01).unwrap_err();
        assert!(e.to_string().contains("open"), "{e}");
    }

    /// The `outline_importers` fuzzer's abort (7.5 GB): an elliptical half turn of radius
    /// 1e55 mm. Refused by its radius and sweep before kurbo subdivides it; a legitimate
    /// elliptical arc, and a nearly straight one of a huge ellipse, still read.
    #[test]
    fn huge_elliptical_arcs_are_refused_before_subdivision() {
        let e = parse(
            r#"<path d="M 0 0 A 1e55 1e11 10 1 1 1000 0 Z"/>"#,
            "huge.svg",
            1e-6,
        )
        .unwrap_err();
        let msg = e.to_string();
        assert!(
            msg.contains("SVG arc") && msg.contains("1e55") && msg.contains("huge.svg"),
            "{msg}"
        );
        let ok = parse(
            r#"<path d="M 0 0 A 20 10 0 0 0 40 0 L 40 -10 L 0 -10 Z"/>"#,
            "ellipse.svg",
            0.001,
        )
        .unwrap();
        assert!(ok.outer.signed_area().abs() > 400.0);
        // A 10 mm chord of an ellipse with a 1e9 mm radius: a straight line, in bounds.
        let flat = parse(
            r#"<path d="M 0 0 A 1e9 5e8 0 0 1 10 0 L 10 -10 L 0 -10 Z"/>"#,
            "flat.svg",
            0.001,
        )
        .unwrap();
        assert!((flat.outer.signed_area().abs() - 100.0).abs() < 1e-3);
    }
}
