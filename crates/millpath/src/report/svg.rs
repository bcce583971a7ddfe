//! SVG preview of a toolpath over its outlines.
//!
//! The picture is in the workpiece frame (Y up): the SVG's own Y axis points down, so the
//! drawing is wrapped in a group that flips Y. Arcs are drawn as SVG elliptical arcs with
//! equal radii, so what the picture shows is exactly what the G2/G3 blocks command.
//!
//! Cutting moves are coloured by feed in five equal bins between the slowest and the fastest
//! feed of the picture. The feed is the **achieved** peak feed of each move when the planner's
//! per-move peaks are given ([`PreviewOptions::achieved_feed`], e.g. `Plan::blocks[i].peak_feed`),
//! the programmed feed otherwise; the legend says which. Rapids are dashed grey; entries (a run
//! of consecutive descending feed moves with XY motion: a helix of one or many arcs, a ramp)
//! get one magenta ring at their start and plunges (Z-only descending feed moves) a magenta
//! cross; the legend counts both.
//!
//! With [`PreviewOptions::side_view`] a side view (X horizontal at the plan's scale, Z up)
//! is drawn in a strip under the plan: it shows the levels, the entries going down and the
//! retracts. Its Z scale is the plan's, stretched when the depth range would be under 60 px
//! (the strip says by how much); helices are drawn as their true projection (sampled at 16
//! points per turn and more for large radii), not as chords.
//!
//! [`level_previews`] draws one picture per level (the CLI writes them as `NAME.level1.svg`, ...).
//!
//! Structure for the HTML viewer: each level is a `<g class="mp-level" data-level="i">`
//! (moves outside every level are in `data-level="-1"`), and the Y-flipped drawing group holds
//! a hidden `<circle class="mp-tool">` whose `cx`/`cy` are workpiece millimetres, so a script
//! can move the tool marker without knowing the transform.

use crate::geom::{Aabb, Outline, Point};
use crate::toolpath::{Move, MoveKind, Plane, Toolpath};
use std::fmt::Write;

/// Options of [`toolpath_svg`]. Built from [`Default`] with the `with_*` methods (the struct is
/// `#[non_exhaustive]`: new settings do not break callers).
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct PreviewOptions {
    /// Width of the picture in pixels (the height follows the aspect ratio).
    pub width_px: f64,
    /// Margin around the drawing, in mm.
    pub margin_mm: f64,
    /// Title drawn at the top; with [`Self::level`] the level's number, kind and depth are
    /// appended.
    pub title: Option<String>,
    /// Only the moves of this level (index into `Toolpath::levels`); all levels when `None`.
    pub level: Option<usize>,
    /// Achieved peak feed of each move in mm/s (index = move index), from the planner; moves
    /// without an entry (or a non-finite one) fall back to their programmed feed.
    pub achieved_feed: Option<Vec<f64>>,
    /// Draw the side view (X–Z) strip under the plan.
    pub side_view: bool,
}

impl Default for PreviewOptions {
    fn default() -> Self {
        PreviewOptions {
            width_px: 900.0,
            margin_mm: 5.0,
            title: None,
            level: None,
            achieved_feed: None,
            side_view: false,
        }
    }
}

option_builders! {
    PreviewOptions;
    /// Sets [`PreviewOptions::width_px`], px.
    with_width_px => width_px: f64;
    /// Sets [`PreviewOptions::margin_mm`], mm.
    with_margin_mm => margin_mm: f64;
    /// Sets [`PreviewOptions::title`].
    with_title => title: Option<String>;
    /// Sets [`PreviewOptions::level`].
    with_level => level: Option<usize>;
    /// Sets [`PreviewOptions::achieved_feed`], mm/s.
    with_achieved_feed => achieved_feed: Option<Vec<f64>>;
    /// Sets [`PreviewOptions::side_view`].
    with_side_view => side_view: bool;
}

/// Colours of cutting moves, from slowest to fastest feed.
const FEED_COLOURS: [&str; 5] = ["#2c7bb6", "#00a6ca", "#90c53f", "#f9a12b", "#d7191c"];

/// Draws `toolpath` over `outlines`: outlines black, cutting moves coloured by achieved (or
/// programmed) feed with a legend at the bottom, rapids dashed grey, entries marked magenta.
pub fn toolpath_svg(toolpath: &Toolpath, outlines: &[Outline], opts: &PreviewOptions) -> String {
    let range = opts
        .level
        .and_then(|i| toolpath.levels.get(i))
        .map_or(0..toolpath.moves.len(), |l| l.start..l.end);
    let achieved = opts.achieved_feed.as_deref();
    let feed_of = |i: usize, m: &Move| -> f64 {
        achieved
            .and_then(|a| a.get(i))
            .copied()
            .filter(|f| f.is_finite() && *f >= 0.0)
            .unwrap_or(m.feed)
    };
    let (mut zmin, mut zmax) = (f64::INFINITY, f64::NEG_INFINITY);
    let mut bounds = outlines
        .iter()
        .map(Outline::bounds)
        .fold(Aabb::EMPTY, Aabb::union);
    let (mut fmin, mut fmax) = (f64::INFINITY, f64::NEG_INFINITY);
    for (i, (from, m)) in toolpath.segments().enumerate() {
        if range.contains(&i) {
            bounds = bounds.with_point(from.xy()).with_point(m.to.xy());
            for z in [from.z, m.to.z] {
                if z.is_finite() {
                    zmin = zmin.min(z);
                    zmax = zmax.max(z);
                }
            }
            if let MoveKind::Arc { center, .. } = m.kind {
                let r = from.xy().distance(center.xy());
                if r.is_finite() {
                    bounds = bounds
                        .with_point(Point::new(center.x - r, center.y - r))
                        .with_point(Point::new(center.x + r, center.y + r));
                }
            }
            let f = feed_of(i, m);
            if m.is_feed() && f > 0.0 && f.is_finite() {
                fmin = fmin.min(f);
                fmax = fmax.max(f);
            }
        }
    }
    if bounds.is_empty() || !(bounds.width().is_finite() && bounds.height().is_finite()) {
        bounds = Aabb::from_points([Point::ORIGIN, Point::new(1.0, 1.0)]);
    }
    let b = bounds.inflate(opts.margin_mm.max(1e-3));
    let width_px = if opts.width_px.is_finite() && opts.width_px > 10.0 {
        opts.width_px
    } else {
        PreviewOptions::default().width_px
    };
    let scale = width_px / b.width().max(1e-9);
    let legend_px = 40.0;
    let title = match (
        &opts.title,
        opts.level.and_then(|i| level_label(toolpath, i)),
    ) {
        (Some(t), Some(l)) => Some(format!("{t} — {l}")),
        (t, l) => t.clone().or(l),
    };
    let title_px = if title.is_some() { 24.0 } else { 0.0 };
    let plan_px = b.height() * scale;
    // Side strip: label row, drawing, gap. Z at the plan's scale unless that is under 60 px.
    let side = (opts.side_view && zmin.is_finite() && zmax.is_finite()).then(|| {
        let depth = (zmax - zmin).max(1e-3);
        let draw_px = (depth * scale).clamp(60.0, 240.0);
        SideStrip {
            top: title_px + plan_px + 26.0,
            height: draw_px,
            zmax,
            zscale: draw_px / depth,
        }
    });
    let side_px = side.as_ref().map_or(0.0, |st| st.height + 36.0);
    let height_px = plan_px + side_px + legend_px + title_px;
    let stroke = 1.2 / scale;
    let mut s = String::new();
    let _ = write!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" class="mp-preview" width="{w:.0}" height="{h:.0}" viewBox="0 0 {w:.0} {h:.0}" font-family="sans-serif" font-size="12">"#,
        w = width_px,
        h = height_px
    );
    s.push_str(r##"<rect width="100%" height="100%" fill="#ffffff"/>"##);
    let _ = write!(
        s,
        r#"<g transform="translate(0 {ty:.4}) scale({scale:.6} {neg:.6}) translate({tx:.6} {ty2:.6})" fill="none" stroke-linecap="round" stroke-linejoin="round">"#,
        ty = b.height() * scale + title_px,
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
    // Level of each move (-1: outside every level).
    let level_of = |i: usize| -> i64 {
        toolpath
            .levels
            .iter()
            .position(|l| (l.start..l.end).contains(&i))
            .map_or(-1, |k| k as i64)
    };
    let mut open_level: Option<i64> = None;
    let mut entries = String::new();
    // Entries: a run of consecutive descending feed moves with XY motion (a helix of several
    // turns, a ramp of several lines) is one entry, ringed at its start; a Z-only descending
    // feed move is a plunge, crossed.
    let mut n_entries = 0usize;
    let mut n_plunges = 0usize;
    let mut in_entry = false;
    for (i, (from, m)) in toolpath.segments().enumerate() {
        if !range.contains(&i) || matches!(m.kind, MoveKind::Dwell { .. }) {
            continue;
        }
        let lv = level_of(i);
        if open_level != Some(lv) {
            if open_level.is_some() {
                s.push_str("</g>");
            }
            let _ = write!(s, r#"<g class="mp-level" data-level="{lv}">"#);
            open_level = Some(lv);
        }
        let descends = m.to.z < from.z - 1e-9;
        let xy_len = from.xy().distance(m.to.xy());
        let entering = m.is_feed() && descends && (is_arc(m) || xy_len >= 1e-9);
        if entering && !in_entry {
            n_entries += 1;
            let _ = write!(
                entries,
                r##"<circle cx="{:.4}" cy="{:.4}" r="{:.5}" stroke="#c000c0" stroke-width="{:.5}"/>"##,
                from.x,
                from.y,
                5.0 * stroke,
                1.5 * stroke
            );
        } else if m.is_feed() && descends && !entering {
            n_plunges += 1;
            let k = 4.0 * stroke;
            let _ = write!(
                entries,
                r##"<path d="M{:.4} {:.4}l{k:.5} {k:.5}m0 {:.5}l{:.5} {k:.5}" stroke="#c000c0" stroke-width="{:.5}"/>"##,
                from.x - k / 2.0,
                from.y - k / 2.0,
                -k,
                -k,
                1.5 * stroke
            );
        }
        in_entry = entering;
        if xy_len < 1e-12 && !is_arc(m) {
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
            _ => (feed_colour(feed_of(i, m), fmin, fmax), String::new()),
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
    if open_level.is_some() {
        s.push_str("</g>");
    }
    s.push_str(&entries);
    let _ = write!(
        s,
        r##"<circle class="mp-tool" cx="{:.4}" cy="{:.4}" r="{:.5}" fill="#ff2020" fill-opacity="0.6" stroke="#000000" stroke-width="{:.5}" visibility="hidden"/>"##,
        toolpath.start.x,
        toolpath.start.y,
        (toolpath.tool.diameter / 2.0).max(4.0 * stroke),
        stroke
    );
    s.push_str("</g>");
    if let Some(st) = &side {
        side_view(&mut s, toolpath, &range, st, b.min.x, scale, &|i, m| {
            feed_colour(feed_of(i, m), fmin, fmax)
        });
    }
    // Legend.
    let y = height_px - 15.0;
    let mut x = 10.0;
    if let Some(t) = &title {
        let _ = write!(s, r#"<text x="10" y="16">{}</text>"#, xml_escape(t));
    }
    if fmax.is_finite() {
        let what = if achieved.is_some() {
            "achieved feed (mm/min):"
        } else {
            "programmed feed (mm/min):"
        };
        let _ = write!(s, r#"<text x="{x}" y="{y}">{what}</text>"#);
        x += text_px(what) + 10.0;
        for (k, c) in FEED_COLOURS.iter().enumerate() {
            let n = FEED_COLOURS.len() as f64;
            let lo = fmin + (fmax - fmin) * k as f64 / n;
            let hi = fmin + (fmax - fmin) * (k as f64 + 1.0) / n;
            let label = format!("{:.0}–{:.0}", lo * 60.0, hi * 60.0);
            let _ = write!(
                s,
                r#"<rect x="{x:.1}" y="{ry}" width="14" height="10" fill="{c}"/><text x="{tx:.1}" y="{y}">{label}</text>"#,
                ry = y - 10.0,
                tx = x + 18.0,
            );
            x += 18.0 + text_px(&label) + 14.0;
        }
    }
    let _ = write!(
        s,
        r##"<line x1="{x:.1}" y1="{ly}" x2="{x2:.1}" y2="{ly}" stroke="#999999" stroke-dasharray="4 3"/><text x="{tx:.1}" y="{y}">rapid</text>"##,
        ly = y - 5.0,
        x2 = x + 25.0,
        tx = x + 30.0
    );
    x += 30.0 + text_px("rapid") + 14.0;
    if n_entries > 0 {
        let label = format!("entry ({n_entries})");
        let _ = write!(
            s,
            r##"<circle cx="{cx:.1}" cy="{cy}" r="5" fill="none" stroke="#c000c0" stroke-width="1.5"/><text x="{tx:.1}" y="{y}">{label}</text>"##,
            cx = x + 6.0,
            cy = y - 5.0,
            tx = x + 16.0
        );
        x += 16.0 + text_px(&label) + 14.0;
    }
    if n_plunges > 0 {
        let _ = write!(
            s,
            r##"<path d="M{:.1} {:.1}l8 8m0 -8l-8 8" stroke="#c000c0" stroke-width="1.5"/><text x="{tx:.1}" y="{y}">plunge ({n_plunges})</text>"##,
            x + 2.0,
            y - 9.0,
            tx = x + 16.0
        );
    }
    s.push_str("</svg>\n");
    s
}

/// Where the side view goes and its Z scale (pixels per mm).
struct SideStrip {
    top: f64,
    height: f64,
    zmax: f64,
    zscale: f64,
}

/// Draws the side view (X right, Z up) of the moves in `range` into `s`, in pixel coordinates
/// (no transform, so dashes and strokes keep their pixel size).
fn side_view(
    s: &mut String,
    tp: &Toolpath,
    range: &std::ops::Range<usize>,
    st: &SideStrip,
    x0: f64,
    scale: f64,
    colour_of: &dyn Fn(usize, &Move) -> &'static str,
) {
    let px = |x: f64| (x - x0) * scale;
    let py = |z: f64| st.top + (st.zmax - z) * st.zscale;
    let stretch = st.zscale / scale;
    let label = if stretch > 1.05 {
        format!("side view (X–Z), Z stretched ×{}", short_ratio(stretch))
    } else {
        "side view (X–Z)".to_owned()
    };
    let _ = write!(
        s,
        r##"<text x="10" y="{:.1}" fill="#444444">{label}</text><g class="mp-side" fill="none" stroke-linecap="round" stroke-linejoin="round">"##,
        st.top - 8.0
    );
    // The path being built: colour, dash, path data, its last point (mm).
    let mut open: Option<(&'static str, &'static str, String, (f64, f64))> = None;
    for (i, (from, m)) in tp.segments().enumerate() {
        if !range.contains(&i) || matches!(m.kind, MoveKind::Dwell { .. }) {
            continue;
        }
        let pts: Vec<(f64, f64)> = match (m.kind, m.sweep_from(from)) {
            (
                MoveKind::Arc {
                    center,
                    plane: Plane::Xy,
                    ccw,
                    ..
                },
                Some((r, sweep)),
            ) if r.is_finite() && sweep.is_finite() => {
                // Sample the helix: x = cx + r cos(a0 ± θ), z linear in θ.
                let a0 = (from.xy() - center.xy()).angle();
                let n = ((sweep.abs() / std::f64::consts::TAU * 16.0).ceil() as usize)
                    .max((sweep.abs() * r * scale / 4.0).ceil() as usize)
                    .clamp(2, 2048);
                let dir = if ccw { 1.0 } else { -1.0 };
                (0..=n)
                    .map(|k| {
                        let u = k as f64 / n as f64;
                        let a = a0 + dir * sweep.abs() * u;
                        (center.x + r * a.cos(), from.z + (m.to.z - from.z) * u)
                    })
                    .collect()
            }
            _ => vec![(from.x, from.z), (m.to.x, m.to.z)],
        };
        if pts.iter().any(|(x, z)| !(x.is_finite() && z.is_finite())) {
            continue;
        }
        let (colour, dash) = match m.kind {
            MoveKind::Rapid => ("#999999", r#" stroke-dasharray="4 3""#),
            _ => (colour_of(i, m), ""),
        };
        // Consecutive moves of one style that join are one path (a pass of thousands of
        // segments at one feed is one element, not thousands).
        let joins = open.as_ref().is_some_and(|(c, da, _, end)| {
            *c == colour
                && *da == dash
                && pts
                    .first()
                    .is_some_and(|p| (p.0 - end.0).abs() < 1e-6 && (p.1 - end.1).abs() < 1e-6)
        });
        if !joins && let Some((c, da, d, _)) = open.take() {
            let _ = write!(s, r#"<path d="{d}" stroke="{c}" stroke-width="1"{da}/>"#);
        }
        let (_, _, d, end) = open.get_or_insert_with(|| {
            let (x, z) = pts.first().copied().unwrap_or_default();
            (colour, dash, format!("M{:.2} {:.2}", px(x), py(z)), (x, z))
        });
        for (x, z) in pts.iter().skip(1) {
            let _ = write!(d, "L{:.2} {:.2}", px(*x), py(*z));
            *end = (*x, *z);
        }
    }
    if let Some((c, da, d, _)) = open.take() {
        let _ = write!(s, r#"<path d="{d}" stroke="{c}" stroke-width="1"{da}/>"#);
    }
    s.push_str("</g>");
}

/// A stretch factor for the label: whole numbers above 10, one decimal below.
fn short_ratio(r: f64) -> String {
    if r >= 10.0 {
        format!("{r:.0}")
    } else {
        format!("{r:.1}")
    }
}

/// One preview per level of `toolpath` (all of them when it has none), each titled with the
/// level's number, kind and depth after `opts.title` (as [`toolpath_svg`] does for any
/// `opts.level`); `opts.level` is ignored.
pub fn level_previews(
    toolpath: &Toolpath,
    outlines: &[Outline],
    opts: &PreviewOptions,
) -> Vec<String> {
    let n = toolpath.levels.len();
    if n == 0 {
        return vec![toolpath_svg(toolpath, outlines, opts)];
    }
    toolpath
        .levels
        .iter()
        .enumerate()
        .map(|(i, _)| {
            toolpath_svg(
                toolpath,
                outlines,
                &PreviewOptions {
                    level: Some(i),
                    ..opts.clone()
                },
            )
        })
        .collect()
}

/// "level 2 of 9: roughing at z = -5.000 mm" for level `i` of `tp`, if it exists.
fn level_label(tp: &Toolpath, i: usize) -> Option<String> {
    let l = tp.levels.get(i)?;
    Some(format!(
        "level {} of {}: {} at z = {:.3} mm",
        i + 1,
        tp.levels.len(),
        match l.kind {
            crate::toolpath::LevelKind::Roughing => "roughing",
            crate::toolpath::LevelKind::Finishing => "finishing",
            crate::toolpath::LevelKind::Other => "other",
        },
        l.z
    ))
}

/// Width of `text` at the legend's 12 px sans-serif, a little generous (DejaVu Sans digits
/// are 0.64 em, the widest letters 0.8 em), so labels never run into each other.
fn text_px(text: &str) -> f64 {
    7.4 * text.chars().count() as f64
}

fn is_arc(m: &Move) -> bool {
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
    use crate::toolpath::Tool;

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
            1 + 3 + 1 + 1,
            "outline + rapid + line + arc + plunge cross + the legend's cross"
        );
        assert!(svg.contains("plunge (1)") && !svg.contains("entry ("));
        assert!(svg.contains("programmed feed"));
    }

    #[test]
    fn achieved_feed_colours_helix_marked_levels_grouped() {
        use crate::toolpath::{Level, LevelKind};
        let mut tp = Toolpath::new(Tool::default(), Point3::new(0.0, 0.0, 5.0));
        tp.push(Move::rapid(Point3::new(10.0, 0.0, 1.0)));
        // Helical entry: a full turn about the origin descending to z = -1.
        tp.push(Move::arc_xy(
            Point3::new(10.0, 0.0, -1.0),
            Point3::new(0.0, 0.0, 0.0),
            true,
            10.0,
        ));
        tp.push(Move::line(Point3::new(20.0, 0.0, -1.0), 10.0));
        tp.push(Move::line(Point3::new(30.0, 0.0, -1.0), 10.0));
        tp.levels.push(Level {
            z: -1.0,
            kind: LevelKind::Roughing,
            start: 1,
            end: 4,
        });
        let opts = PreviewOptions {
            // Same programmed feed, but the planner reached only 2 mm/s on the second line.
            achieved_feed: Some(vec![0.0, 8.0, 10.0, 2.0]),
            title: Some("a <b> & c".into()),
            ..PreviewOptions::default()
        };
        let svg = toolpath_svg(&tp, &[], &opts);
        assert!(svg.contains("achieved feed"));
        assert!(svg.contains("a &lt;b&gt; &amp; c"));
        assert!(svg.contains(r#"class="mp-level" data-level="-1""#));
        assert!(svg.contains(r#"class="mp-level" data-level="0""#));
        assert!(svg.contains("entry (1)"));
        assert!(svg.contains(r#"<circle class="mp-tool""#));
        // Slowest and fastest bins both used although the programmed feeds are equal.
        assert!(svg.contains(&format!("stroke=\"{}\"", FEED_COLOURS[0])));
        assert!(svg.contains(&format!("stroke=\"{}\"", FEED_COLOURS[4])));
        // The full helix circle lies inside the picture: x from -10 mm (minus the 5 mm margin) is visible.
        assert!(svg.contains("translate(15.0"), "{svg}");
    }

    #[test]
    fn side_view_and_level_pictures() {
        use crate::toolpath::{Level, LevelKind};
        let mut tp = Toolpath::new(Tool::default(), Point3::new(0.0, 0.0, 5.0));
        tp.push(Move::rapid(Point3::new(10.0, 0.0, 1.0)));
        tp.push(Move::arc_xy(
            Point3::new(10.0, 0.0, -2.0),
            Point3::new(0.0, 0.0, 0.0),
            true,
            10.0,
        ));
        tp.push(Move::line(Point3::new(30.0, 0.0, -2.0), 10.0));
        tp.push(Move::rapid(Point3::new(30.0, 0.0, 5.0)));
        tp.push(Move::line(Point3::new(30.0, 0.0, -4.0), 10.0));
        tp.push(Move::line(Point3::new(0.0, 0.0, -4.0), 10.0));
        tp.levels.push(Level {
            z: -2.0,
            kind: LevelKind::Roughing,
            start: 1,
            end: 3,
        });
        tp.levels.push(Level {
            z: -4.0,
            kind: LevelKind::Finishing,
            start: 4,
            end: 6,
        });
        let opts = PreviewOptions {
            side_view: true,
            title: Some("t".into()),
            ..PreviewOptions::default()
        };
        let svg = toolpath_svg(&tp, &[], &opts);
        let side = &svg[svg.find(r#"class="mp-side""#).expect("side view drawn")..];
        let side = &side[..side.find("</g>").expect("side group closed")];
        // Paths of one style that join are merged: rapid | helix + line (one feed) | rapid |
        // plunge + line.
        assert_eq!(side.matches("<path").count(), 4, "{side}");
        // The helix is sampled (a full turn: at least 16 points), not drawn as a chord.
        let helix = side.split("<path").nth(2).unwrap();
        assert!(helix.matches('L').count() > 16, "{helix}");
        // z spans 9 mm: at 900 px over 50 mm that is 162 px, no stretch needed.
        assert!(svg.contains("side view (X–Z)<"), "{svg}");
        assert!(
            svg.contains("entry (1)") && svg.contains("plunge (1)"),
            "{svg}"
        );
        // A helix of two arcs is one entry.
        let mut two = Toolpath::new(Tool::default(), Point3::new(10.0, 0.0, 0.0));
        for z in [-1.0, -2.0] {
            two.push(Move::arc_xy(
                Point3::new(10.0, 0.0, z),
                Point3::new(0.0, 0.0, 0.0),
                true,
                10.0,
            ));
        }
        two.push(Move::line(Point3::new(20.0, 0.0, -2.0), 10.0));
        assert!(toolpath_svg(&two, &[], &PreviewOptions::default()).contains("entry (1)"));
        let pics = level_previews(&tp, &[], &opts);
        assert_eq!(pics.len(), 2);
        assert!(pics[0].contains("t — level 1 of 2: roughing at z = -2.000 mm"));
        assert!(pics[1].contains("level 2 of 2: finishing at z = -4.000 mm"));
        // The second picture holds only the second level's moves.
        assert!(!pics[1].contains(r#"data-level="0""#));
        assert!(pics[1].contains(r#"data-level="1""#));
    }

    #[test]
    fn bad_numbers_do_not_panic() {
        let mut tp = Toolpath::new(Tool::default(), Point3::new(f64::NAN, 0.0, 0.0));
        tp.push(Move::line(Point3::new(f64::INFINITY, 1.0, 0.0), f64::NAN));
        tp.push(Move::line(Point3::new(1.0, 1.0, 0.0), -3.0));
        let opts = PreviewOptions {
            width_px: f64::NAN,
            margin_mm: f64::NAN,
            level: Some(99),
            achieved_feed: Some(vec![f64::NAN]),
            side_view: true,
            ..PreviewOptions::default()
        };
        let svg = toolpath_svg(&tp, &[], &opts);
        assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
    }
}
