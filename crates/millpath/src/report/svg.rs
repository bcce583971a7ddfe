//! SVG preview of a toolpath over its outlines.
//!
//! The picture is in the workpiece frame (Y up): the SVG's own Y axis points down, so the
//! drawing is wrapped in a group that flips Y. Arcs are drawn as SVG elliptical arcs with
//! equal radii, so what the picture shows is exactly what the G2/G3 blocks command.

use crate::geom::{Aabb, Outline, Point};
use crate::toolpath::{MoveKind, Plane, Toolpath};
use std::fmt::Write;

/// Options of [`toolpath_svg`].
#[derive(Debug, Clone)]
pub struct PreviewOptions {
    /// Width of the picture in pixels (the height follows the aspect ratio).
    pub width_px: f64,
    /// Margin around the drawing, in mm.
    pub margin_mm: f64,
    /// Title drawn at the top.
    pub title: Option<String>,
    /// Only the moves of this level (index into `Toolpath::levels`); all levels when `None`.
    pub level: Option<usize>,
}

impl Default for PreviewOptions {
    fn default() -> Self {
        PreviewOptions {
            width_px: 900.0,
            margin_mm: 5.0,
            title: None,
            level: None,
        }
    }
}

/// Colours of cutting moves, from slowest to fastest feed.
const FEED_COLOURS: [&str; 5] = ["#2c7bb6", "#00a6ca", "#90c53f", "#f9a12b", "#d7191c"];

/// Draws `toolpath` over `outlines`: outlines black, cutting moves coloured by programmed feed
/// (legend at the bottom), rapids dashed grey.
pub fn toolpath_svg(toolpath: &Toolpath, outlines: &[Outline], opts: &PreviewOptions) -> String {
    let range = opts
        .level
        .and_then(|i| toolpath.levels.get(i))
        .map_or(0..toolpath.moves.len(), |l| l.start..l.end);
    let mut bounds = outlines
        .iter()
        .map(Outline::bounds)
        .fold(Aabb::EMPTY, Aabb::union);
    let mut feeds: Vec<f64> = Vec::new();
    for (i, (from, m)) in toolpath.segments().enumerate() {
        if range.contains(&i) {
            bounds = bounds.with_point(from.xy()).with_point(m.to.xy());
            if m.is_feed() && m.feed > 0.0 {
                feeds.push(m.feed);
            }
        }
    }
    if bounds.is_empty() {
        bounds = Aabb::from_points([Point::ORIGIN, Point::new(1.0, 1.0)]);
    }
    let b = bounds.inflate(opts.margin_mm.max(1e-3));
    let (fmin, fmax) = feeds
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), f| {
            (lo.min(*f), hi.max(*f))
        });
    let scale = opts.width_px / b.width().max(1e-9);
    let legend_px = 40.0;
    let height_px = b.height() * scale + legend_px;
    let stroke = 1.2 / scale;
    let mut s = String::new();
    let _ = write!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w:.0}" height="{h:.0}" viewBox="0 0 {w:.0} {h:.0}" font-family="sans-serif" font-size="12">"#,
        w = opts.width_px,
        h = height_px
    );
    s.push_str(r##"<rect width="100%" height="100%" fill="#ffffff"/>"##);
    let _ = write!(
        s,
        r#"<g transform="translate(0 {ty:.4}) scale({scale:.6} {neg:.6}) translate({tx:.6} {ty2:.6})" fill="none" stroke-linecap="round" stroke-linejoin="round">"#,
        ty = b.height() * scale,
        neg = -scale,
        tx = -b.min.x,
        ty2 = -b.min.y,
    );
    for o in outlines {
        let _ = write!(
            s,
            r##"<path d="{}" stroke="#000000" stroke-width="{:.5}"/>"##,
            outline_path(o),
            2.0 * stroke
        );
    }
    for (i, (from, m)) in toolpath.segments().enumerate() {
        if !range.contains(&i) || from.xy().distance(m.to.xy()) < 1e-12 && !is_arc(m) {
            continue;
        }
        let (colour, dash) = match m.kind {
            MoveKind::Rapid => (
                "#999999",
                format!(
                    r#" stroke-dasharray="{:.4} {:.4}""#,
                    4.0 * stroke,
                    3.0 * stroke
                ),
            ),
            MoveKind::Dwell { .. } => continue,
            _ => (feed_colour(m.feed, fmin, fmax), String::new()),
        };
        let d = match m.kind {
            MoveKind::Arc {
                center,
                plane: Plane::Xy,
                ccw,
                ..
            } => arc_path(from.xy(), m.to.xy(), center.xy(), ccw),
            _ => format!("M{:.4} {:.4}L{:.4} {:.4}", from.x, from.y, m.to.x, m.to.y),
        };
        let _ = write!(
            s,
            r#"<path d="{d}" stroke="{colour}" stroke-width="{stroke:.5}"{dash}/>"#
        );
    }
    s.push_str("</g>");
    // Legend.
    let y = b.height() * scale + 25.0;
    let mut x = 10.0;
    if let Some(t) = &opts.title {
        let _ = write!(s, r#"<text x="10" y="16">{}</text>"#, xml_escape(t));
    }
    if fmax.is_finite() {
        let _ = write!(s, r#"<text x="{x}" y="{y}">feed (mm/min):</text>"#);
        x += 95.0;
        for (k, c) in FEED_COLOURS.iter().enumerate() {
            let f = fmin + (fmax - fmin) * (k as f64 + 0.5) / FEED_COLOURS.len() as f64;
            let _ = write!(
                s,
                r#"<rect x="{x}" y="{ry}" width="14" height="10" fill="{c}"/><text x="{tx}" y="{y}">{f:.0}</text>"#,
                ry = y - 10.0,
                tx = x + 18.0,
                f = f * 60.0
            );
            x += 70.0;
        }
    }
    let _ = write!(
        s,
        r##"<line x1="{x}" y1="{ly}" x2="{x2}" y2="{ly}" stroke="#999999" stroke-dasharray="4 3"/><text x="{tx}" y="{y}">rapid</text>"##,
        ly = y - 5.0,
        x2 = x + 25.0,
        tx = x + 30.0
    );
    s.push_str("</svg>\n");
    s
}

fn is_arc(m: &crate::toolpath::Move) -> bool {
    matches!(m.kind, MoveKind::Arc { .. })
}

fn feed_colour(feed: f64, fmin: f64, fmax: f64) -> &'static str {
    if fmax.partial_cmp(&fmin) != Some(std::cmp::Ordering::Greater) {
        return FEED_COLOURS[FEED_COLOURS.len() - 1];
    }
    let t = ((feed - fmin) / (fmax - fmin)).clamp(0.0, 1.0);
    let k = ((t * FEED_COLOURS.len() as f64) as usize).min(FEED_COLOURS.len() - 1);
    FEED_COLOURS[k]
}

/// SVG path data of an XY arc from `a` to `b` about `c` (a full circle when `a == b`).
fn arc_path(a: Point, b: Point, c: Point, ccw: bool) -> String {
    let r = a.distance(c);
    // In the flipped frame the sweep flag keeps its meaning (y-up, ccw = positive angle).
    let sweep = u8::from(ccw);
    if a.distance(b) < 1e-9 {
        // Full circle: two half arcs.
        let m = c + (c - a);
        return format!(
            "M{:.4} {:.4}A{r:.4} {r:.4} 0 0 {sweep} {:.4} {:.4}A{r:.4} {r:.4} 0 0 {sweep} {:.4} {:.4}",
            a.x, a.y, m.x, m.y, a.x, a.y
        );
    }
    let va = a - c;
    let vb = b - c;
    let mut ang = vb.angle() - va.angle();
    if ccw {
        ang = ang.rem_euclid(std::f64::consts::TAU);
    } else {
        ang = (-ang).rem_euclid(std::f64::consts::TAU);
    }
    let large = u8::from(ang > std::f64::consts::PI);
    format!(
        "M{:.4} {:.4}A{r:.4} {r:.4} 0 {large} {sweep} {:.4} {:.4}",
        a.x, a.y, b.x, b.y
    )
}

fn outline_path(o: &Outline) -> String {
    let v: Vec<(Point, f64)> = o.vertices().collect();
    let mut d = String::new();
    for (i, (p, bulge)) in v.iter().enumerate() {
        if i == 0 {
            let _ = write!(d, "M{:.4} {:.4}", p.x, p.y);
        }
        let (q, _) = v[(i + 1) % v.len()];
        if bulge.abs() < 1e-12 {
            let _ = write!(d, "L{:.4} {:.4}", q.x, q.y);
        } else {
            // bulge = tan(θ/4); chord c; radius r = c (1 + b²) / (4 |b|).
            let c = p.distance(q);
            let r = c * (1.0 + bulge * bulge) / (4.0 * bulge.abs());
            let large = u8::from(bulge.abs() > 1.0);
            let sweep = u8::from(*bulge > 0.0);
            let _ = write!(d, "A{r:.4} {r:.4} 0 {large} {sweep} {:.4} {:.4}", q.x, q.y);
        }
    }
    d.push('Z');
    d
}

fn xml_escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Point3;
    use crate::toolpath::{Move, Tool};

    #[test]
    fn preview_draws_outline_cuts_and_rapids() {
        let o = Outline::from_points(
            &[
                Point::new(0.0, 0.0),
                Point::new(20.0, 0.0),
                Point::new(20.0, 10.0),
                Point::new(0.0, 10.0),
            ],
            "t",
        )
        .unwrap();
        let mut tp = Toolpath::new(Tool::default(), Point3::new(0.0, 0.0, 5.0));
        tp.push(Move::rapid(Point3::new(5.0, 5.0, 5.0)));
        tp.push(Move::line(Point3::new(5.0, 5.0, -1.0), 5.0));
        tp.push(Move::line(Point3::new(15.0, 5.0, -1.0), 20.0));
        tp.push(Move::arc_xy(
            Point3::new(5.0, 5.0, -1.0),
            Point3::new(10.0, 5.0, -1.0),
            true,
            20.0,
        ));
        let svg = toolpath_svg(&tp, &[o], &PreviewOptions::default());
        assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
        assert!(svg.contains("stroke-dasharray"), "rapid not dashed");
        assert!(
            svg.contains("M15.0000 5.0000A5.0000 5.0000 0 "),
            "half-circle arc missing: {svg}"
        );
        assert_eq!(
            svg.matches("<path").count(),
            1 + 3,
            "outline + rapid + line + arc"
        );
    }
}
