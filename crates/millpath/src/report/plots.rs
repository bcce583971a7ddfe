//! Plots over plain data series, drawn with `plotters` (SVG string, or PNG written to a path).
//!
//! Every plot is first described as a [`Chart`] (title, axis labels, series, horizontal limit
//! lines), then rendered by [`render_svg`] or [`render_png`]. The builders below turn the data
//! of the papers' figures into charts; they take plain slices, so they are independent of the
//! strategies and of the planner:
//!
//! - [`feed_along_path`]: achieved (and programmed) feed against the distance travelled
//!   (the adaptive-spiral paper's Figure 15);
//! - [`cycle_time_vs_transition`]: cycle time against the transition parameter C, one curve per
//!   feed (its Figure 10);
//! - [`square_circle_gain`]: time gain of the circle over the square of equal area, in %,
//!   against the side length, measured and planned, one colour per feed (its Figures 22–23);
//! - [`axis_kinematics`]: per-axis velocity, acceleration or jerk against time with the
//!   ±limits drawn (the five-axis paper's Figures 6–7);
//! - [`chordal_deviation`]: chordal deviation per segment against the tolerance (the die-cavity
//!   paper's Figure 10).
//!
//! ## Text and fonts
//! Labels are measured and drawn with DejaVu Sans compiled into the library (the `dejavu`
//! crate, through plotters' `ab_glyph` text backend), registered once per process as
//! `sans-serif`: no system font, fontconfig or pkg-config is needed to build or to draw, and a
//! chart's pictures are the same on every machine. Non-finite values are dropped from series
//! before drawing; an empty chart is drawn with unit axes rather than failing.

use crate::error::Error;
use crate::motion::table2::Row;
use plotters::prelude::*;
use std::path::Path;

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SeriesStyle {
    /// Solid polyline.
    #[default]
    Line,
    /// Dashed polyline.
    Dashed,
    /// Markers only (measured points).
    Points,
}

/// One data series of a chart.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Series {
    /// Legend text.
    pub label: String,
    /// (x, y) points, in drawing order.
    pub points: Vec<(f64, f64)>,
    /// How to draw it.
    pub style: SeriesStyle,
    /// Colour index into the palette (series sharing a colour belong together, e.g. measured
    /// and planned at one feed).
    pub colour: usize,
}

/// A horizontal reference line (a limit, a tolerance).
#[derive(Debug, Clone, PartialEq)]
pub struct HLine {
    /// Legend text.
    pub label: String,
    /// Height in the chart's y unit.
    pub y: f64,
}

/// A chart described as data; render with [`render_svg`] or [`render_png`].
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Chart {
    /// Caption above the chart.
    pub title: String,
    /// Label of the x axis (with unit).
    pub x_label: String,
    /// Label of the y axis (with unit).
    pub y_label: String,
    /// The series.
    pub series: Vec<Series>,
    /// Horizontal reference lines, drawn red dashed.
    pub hlines: Vec<HLine>,
    /// A fixed y range `(bottom, top)` instead of the data's (e.g. from 0 to above a
    /// tolerance, so that the reader sees how much of it is used); ignored unless finite
    /// with `bottom < top`.
    pub y_range: Option<(f64, f64)>,
}

/// Size of a rendered chart. Built from [`Default`] with the `with_*` methods (the struct is
/// `#[non_exhaustive]`: new settings do not break callers).
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct PlotOptions {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
}

impl Default for PlotOptions {
    fn default() -> Self {
        PlotOptions {
            width: 800,
            height: 420,
        }
    }
}

option_builders! {
    PlotOptions;
    /// Sets [`PlotOptions::width`], px.
    with_width => width: u32;
    /// Sets [`PlotOptions::height`], px.
    with_height => height: u32;
}

/// Colour-blind-friendly palette (Okabe–Ito).
const PALETTE: [RGBColor; 7] = [
    RGBColor(0, 114, 178),
    RGBColor(230, 159, 0),
    RGBColor(0, 158, 115),
    RGBColor(204, 121, 167),
    RGBColor(86, 180, 233),
    RGBColor(213, 94, 0),
    RGBColor(0, 0, 0),
];

fn colour(i: usize) -> RGBColor {
    PALETTE[i % PALETTE.len()]
}

impl Chart {
    /// The data range (x0, x1, y0, y1) over the finite points and limit lines, padded by 5 %
    /// in y and never empty.
    pub fn ranges(&self) -> (f64, f64, f64, f64) {
        let mut x = (f64::INFINITY, f64::NEG_INFINITY);
        let mut y = (f64::INFINITY, f64::NEG_INFINITY);
        for s in &self.series {
            for &(px, py) in &s.points {
                if px.is_finite() && py.is_finite() {
                    x = (x.0.min(px), x.1.max(px));
                    y = (y.0.min(py), y.1.max(py));
                }
            }
        }
        for h in &self.hlines {
            if h.y.is_finite() {
                y = (y.0.min(h.y), y.1.max(h.y));
            }
        }
        let fix = |(lo, hi): (f64, f64)| {
            if !(lo.is_finite() && hi.is_finite()) {
                (0.0, 1.0)
            } else if hi - lo < 1e-12 * (1.0 + lo.abs()) {
                (lo - 0.5 - lo.abs() * 0.05, hi + 0.5 + hi.abs() * 0.05)
            } else {
                (lo, hi)
            }
        };
        let x = fix(x);
        if let Some((lo, hi)) = self.y_range
            && lo.is_finite()
            && hi.is_finite()
            && lo < hi
        {
            return (x.0, x.1, lo, hi);
        }
        let y = fix(y);
        let pad = 0.05 * (y.1 - y.0);
        (x.0, x.1, y.0 - pad, y.1 + pad)
    }
}

/// Tick label of `v` on an axis spanning `span`: as many decimals as the tick spacing
/// (about a tenth of the span) needs, so 0, 5000, 10000 rather than 0.0, 5000.0, 10000.0, and
/// 0.02, 0.04 rather than 0.020000000000000004.
fn tick_label(v: f64, span: f64) -> String {
    let step = span.abs() / 10.0;
    let decimals = if step.is_finite() && step > 0.0 {
        (-step.log10().floor()).clamp(0.0, 9.0) as usize
    } else {
        1
    };
    let s = format!("{v:.decimals$}");
    // No "-0".
    if s.trim_start_matches('-')
        .chars()
        .all(|c| c == '0' || c == '.')
    {
        s.trim_start_matches('-').to_owned()
    } else {
        s
    }
}

fn plot_err(e: impl std::fmt::Display) -> Error {
    Error::internal(format!("plot rendering failed: {e}"))
}

/// Whether this target draws plots: every target but `wasm32-unknown-unknown`, where
/// plotters measures text only with a browser page's canvas (its `ab_glyph` text backend is
/// native only) and a Web Worker has none; there [`render_svg`] and [`render_png`] refuse
/// with an internal error and the HTML report leaves its plots out.
pub const PLOTS_DRAWN: bool = !cfg!(all(target_arch = "wasm32", target_os = "unknown"));

/// The refusal to draw a plot on a target that draws none ([`PLOTS_DRAWN`]).
#[cfg(all(target_arch = "wasm32", target_os = "unknown"))]
fn register_font() -> Result<(), Error> {
    Err(Error::internal(
        "plot rendering: no plots are drawn on wasm32-unknown-unknown (no text backend)",
    ))
}

/// Registers the embedded DejaVu Sans as plotters' `sans-serif`, once per process.
#[cfg(not(all(target_arch = "wasm32", target_os = "unknown")))]
fn register_font() -> Result<(), Error> {
    static REGISTERED: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
    let ok = *REGISTERED.get_or_init(|| {
        plotters::style::register_font("sans-serif", FontStyle::Normal, dejavu::sans::regular())
            .is_ok()
    });
    if ok {
        Ok(())
    } else {
        Err(Error::internal(
            "plot rendering failed: the embedded DejaVu Sans font did not parse",
        ))
    }
}

fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, plotters::coord::Shift>,
    chart: &Chart,
) -> Result<(), Error>
where
    DB::ErrorType: 'static,
{
    register_font()?;
    root.fill(&WHITE).map_err(plot_err)?;
    let (x0, x1, y0, y1) = chart.ranges();
    let mut cc = ChartBuilder::on(root)
        .caption(&chart.title, ("sans-serif", 20))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(64)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(plot_err)?;
    let (xs, ys) = (x1 - x0, y1 - y0);
    let xf = move |v: &f64| tick_label(*v, xs);
    let yf = move |v: &f64| tick_label(*v, ys);
    cc.configure_mesh()
        .x_desc(&chart.x_label)
        .y_desc(&chart.y_label)
        .x_label_formatter(&xf)
        .y_label_formatter(&yf)
        .light_line_style(RGBColor(235, 235, 235))
        .draw()
        .map_err(plot_err)?;
    for s in &chart.series {
        let c = colour(s.colour);
        let pts: Vec<(f64, f64)> = s
            .points
            .iter()
            .copied()
            .filter(|(x, y)| x.is_finite() && y.is_finite())
            .collect();
        let legend_style = c.stroke_width(2);
        let anno = match s.style {
            SeriesStyle::Line => cc
                .draw_series(LineSeries::new(pts, c.stroke_width(2)))
                .map_err(plot_err)?,
            SeriesStyle::Dashed => cc
                .draw_series(DashedLineSeries::new(pts, 6, 4, c.stroke_width(2)))
                .map_err(plot_err)?,
            SeriesStyle::Points => {
                // Thousands of markers of radius 4 merge into a band: smaller when many.
                let r = if pts.len() > 300 { 2 } else { 4 };
                cc.draw_series(pts.into_iter().map(|p| Circle::new(p, r, c.filled())))
                    .map_err(plot_err)?
            }
        };
        if !s.label.is_empty() {
            let points = s.style == SeriesStyle::Points;
            anno.label(s.label.as_str()).legend(move |(x, y)| {
                let path = if points {
                    Vec::new()
                } else {
                    vec![(0, 0), (20, 0)]
                };
                EmptyElement::at((x, y))
                    + PathElement::new(path, legend_style)
                    + Circle::new((10, 0), if points { 4 } else { 0 }, c.filled())
            });
        }
    }
    for h in &chart.hlines {
        let red = RGBColor(200, 0, 0);
        let anno = cc
            .draw_series(DashedLineSeries::new(
                vec![(x0, h.y), (x1, h.y)],
                8,
                4,
                red.stroke_width(1),
            ))
            .map_err(plot_err)?;
        if !h.label.is_empty() {
            anno.label(h.label.as_str())
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], red));
        }
    }
    if chart.series.iter().any(|s| !s.label.is_empty()) || !chart.hlines.is_empty() {
        cc.configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .position(SeriesLabelPosition::UpperRight)
            .draw()
            .map_err(plot_err)?;
    }
    root.present().map_err(plot_err)?;
    Ok(())
}

/// Renders `chart` as an SVG document string.
pub fn render_svg(chart: &Chart, opts: &PlotOptions) -> Result<String, Error> {
    let mut s = String::new();
    {
        let root = SVGBackend::with_string(&mut s, (opts.width, opts.height)).into_drawing_area();
        draw(&root, chart)?;
    }
    Ok(s)
}

/// Renders `chart` as a PNG file at `path` (through plotters' bitmap backend).
pub fn render_png(chart: &Chart, opts: &PlotOptions, path: &Path) -> Result<(), Error> {
    #[cfg(not(all(target_arch = "wasm32", target_os = "unknown")))]
    {
        let root = BitMapBackend::new(path, (opts.width, opts.height)).into_drawing_area();
        draw(&root, chart)
    }
    #[cfg(all(target_arch = "wasm32", target_os = "unknown"))]
    {
        let _ = (chart, opts, path);
        register_font()
    }
}

/// Writes `stem.svg` and `stem.png` (the SVG atomically) and returns the SVG, for a report
/// that both embeds the plot and ships the pictures beside it.
pub fn render_files(chart: &Chart, opts: &PlotOptions, stem: &Path) -> Result<String, Error> {
    let svg = render_svg(chart, opts)?;
    crate::io::write_atomic(&stem.with_extension("svg"), svg.as_bytes())?;
    render_png(chart, opts, &stem.with_extension("png"))?;
    Ok(svg)
}

/// Feed along the path (adaptive-spiral paper, Figure 15): `achieved` are (distance travelled
/// in mm, achieved feed in mm/s) pairs, e.g. from plan samples; `programmed` the same for the
/// programmed feed (drawn dashed). Feeds are shown in mm/min.
pub fn feed_along_path(achieved: &[(f64, f64)], programmed: Option<&[(f64, f64)]>) -> Chart {
    let to_min = |p: &[(f64, f64)]| p.iter().map(|&(s, f)| (s, f * 60.0)).collect();
    // The programmed feed first, so the achieved feed is drawn over it where they agree.
    let mut series = Vec::new();
    if let Some(p) = programmed {
        series.push(Series {
            label: "programmed feed".into(),
            points: to_min(p),
            style: SeriesStyle::Dashed,
            colour: 5,
        });
    }
    series.push(Series {
        label: "achieved feed".into(),
        points: to_min(achieved),
        style: SeriesStyle::Line,
        colour: 0,
    });
    // From zero feed to a fifth above the fastest, so the legend sits above the curves.
    let top = series
        .iter()
        .flat_map(|s| s.points.iter().map(|p| p.1))
        .filter(|f| f.is_finite())
        .fold(0.0_f64, f64::max);
    Chart {
        title: "Feed along the path".into(),
        x_label: "path position (mm)".into(),
        y_label: "feed (mm/min)".into(),
        series,
        hlines: Vec::new(),
        y_range: (top > 0.0).then_some((0.0, 1.25 * top)),
    }
}

/// Cycle time against the transition parameter C (adaptive-spiral paper, Figure 10): one curve
/// per `(feed label, [(C, cycle time in s)])`.
pub fn cycle_time_vs_transition(curves: &[(String, Vec<(f64, f64)>)]) -> Chart {
    cycle_time_vs_transition_with(curves, &[])
}

/// [`cycle_time_vs_transition`] with a reference time per curve (e.g. zigzag at the same feed),
/// drawn dashed in the curve's colour over the C range: `references[i]` belongs to
/// `curves[i]`. A reference with an empty label gets no legend entry of its own (the colour
/// already names the feed; say "dashed: ..." in the title).
pub fn cycle_time_vs_transition_with(
    curves: &[(String, Vec<(f64, f64)>)],
    references: &[(String, f64)],
) -> Chart {
    let (c0, c1) = curves
        .iter()
        .flat_map(|(_, p)| p.iter().map(|q| q.0))
        .filter(|c| c.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), c| {
            (a.min(c), b.max(c))
        });
    let mut series: Vec<Series> = curves
        .iter()
        .enumerate()
        .map(|(i, (label, pts))| Series {
            label: label.clone(),
            points: pts.clone(),
            style: SeriesStyle::Line,
            colour: i,
        })
        .collect();
    if c0 < c1 {
        for (i, (label, t)) in references.iter().enumerate().take(curves.len()) {
            series.push(Series {
                label: label.clone(),
                points: vec![(c0, *t), (c1, *t)],
                style: SeriesStyle::Dashed,
                colour: i,
            });
        }
    }
    let top = series
        .iter()
        .flat_map(|s| s.points.iter().map(|p| p.1))
        .filter(|f| f.is_finite())
        .fold(0.0_f64, f64::max);
    Chart {
        title: "Cycle time against the transition C".into(),
        x_label: "transition C (share of the pocket)".into(),
        y_label: "cycle time (s)".into(),
        series,
        hlines: Vec::new(),
        // From zero: the paper's Figure 10 reads the feed effect and the C effect together.
        // The legend needs room above the slowest curve.
        y_range: (top > 0.0).then_some((0.0, 1.5 * top)),
    }
}

/// Time gain of the circle over the square (adaptive-spiral paper, Figures 22–23): gain in %
/// against the square's side in inches, one colour per feed; measured as points, ours
/// (planned) as lines. Rows are grouped by `feed_ipm` in order of first appearance.
pub fn square_circle_gain(rows: &[Row]) -> Chart {
    let mut feeds: Vec<f64> = Vec::new();
    for r in rows {
        if !feeds.iter().any(|f| f.to_bits() == r.feed_ipm.to_bits()) {
            feeds.push(r.feed_ipm);
        }
    }
    let mut series = Vec::new();
    for (i, f) in feeds.iter().enumerate() {
        let mut rs: Vec<&Row> = rows
            .iter()
            .filter(|r| r.feed_ipm.to_bits() == f.to_bits())
            .collect();
        rs.sort_by(|a, b| a.side_in.total_cmp(&b.side_in));
        series.push(Series {
            label: format!("{f:.0} in/min measured"),
            points: rs.iter().map(|r| (r.side_in, r.gain_measured)).collect(),
            style: SeriesStyle::Points,
            colour: i,
        });
        series.push(Series {
            label: format!("{f:.0} in/min ours"),
            points: rs.iter().map(|r| (r.side_in, r.gain_planned)).collect(),
            style: SeriesStyle::Line,
            colour: i,
        });
    }
    Chart {
        title: "Circle against square: time gain".into(),
        x_label: "side of the square (in)".into(),
        y_label: "gain (%)".into(),
        series,
        hlines: Vec::new(),
        y_range: None,
    }
}

/// A number with at most 4 significant decimals and no trailing zeros.
fn short(v: f64) -> String {
    let s = format!("{v:.4}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    s.to_string()
}

/// Which derivative [`axis_kinematics`] shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Quantity {
    /// Velocity (unit per s).
    Velocity,
    /// Acceleration (unit per s²).
    Acceleration,
    /// Jerk (unit per s³).
    Jerk,
}

impl Quantity {
    /// The quantity's name capitalised ("Velocity", ...). Titles and axis labels use this
    /// form: plotters' bitmap text drops the dot of a leading lower-case `j` (its glyph
    /// reaches left of its box), which turned "jerk" into "ȷerk" in the PNGs.
    pub fn title(self) -> &'static str {
        match self {
            Quantity::Velocity => "Velocity",
            Quantity::Acceleration => "Acceleration",
            Quantity::Jerk => "Jerk",
        }
    }

    /// The quantity for a (rotated) y-axis label. Plotters' bitmap text also clips a capital J
    /// when rotated, so jerk is labelled as what it is, the rate of change of acceleration.
    pub fn axis_label(self) -> &'static str {
        match self {
            Quantity::Velocity => "Velocity",
            Quantity::Acceleration => "Acceleration",
            Quantity::Jerk => "Acceleration rate",
        }
    }

    /// The quantity's name in lower case ("velocity", ...).
    pub fn name(self) -> &'static str {
        match self {
            Quantity::Velocity => "velocity",
            Quantity::Acceleration => "acceleration",
            Quantity::Jerk => "jerk",
        }
    }
    fn power(self) -> &'static str {
        match self {
            Quantity::Velocity => "s",
            Quantity::Acceleration => "s²",
            Quantity::Jerk => "s³",
        }
    }
}

/// One axis of [`axis_kinematics`]: its name (`"X"`, `"A"`...), unit (`"mm"`, `"rad"`), the
/// values at the common time stamps, and its limit (drawn as ±limit).
#[derive(Debug, Clone, PartialEq)]
pub struct AxisSeries {
    /// Axis name.
    pub name: String,
    /// Length unit of the axis.
    pub unit: String,
    /// Values, one per time stamp.
    pub values: Vec<f64>,
    /// The axis limit for this quantity, if any.
    pub limit: Option<f64>,
}

/// Per-axis velocity, acceleration or jerk against time with ±limits (five-axis paper,
/// Figures 6–7). `t` are the common time stamps; values beyond `t.len()` are ignored.
pub fn axis_kinematics(quantity: Quantity, t: &[f64], axes: &[AxisSeries]) -> Chart {
    let mut series = Vec::new();
    // Axes sharing a limit share one pair of lines: (limit, names).
    let mut limits: Vec<(f64, Vec<&str>)> = Vec::new();
    for (i, a) in axes.iter().enumerate() {
        series.push(Series {
            label: a.name.clone(),
            points: t.iter().copied().zip(a.values.iter().copied()).collect(),
            style: SeriesStyle::Line,
            colour: i,
        });
        if let Some(l) = a.limit.filter(|l| l.is_finite()).map(f64::abs) {
            match limits.iter_mut().find(|(v, _)| v.to_bits() == l.to_bits()) {
                Some((_, names)) => names.push(&a.name),
                None => limits.push((l, vec![&a.name])),
            }
        }
    }
    let mut hlines = Vec::new();
    for (l, names) in limits {
        hlines.push(HLine {
            label: format!("{} limit ±{}", names.join(", "), short(l)),
            y: l,
        });
        hlines.push(HLine {
            label: String::new(),
            y: -l,
        });
    }
    let units: Vec<&str> = {
        let mut u: Vec<&str> = axes.iter().map(|a| a.unit.as_str()).collect();
        u.dedup();
        u
    };
    Chart {
        title: format!("{} per axis", quantity.title()),
        x_label: "time (s)".into(),
        y_label: format!(
            "{} ({}/{})",
            quantity.axis_label(),
            units.join(", "),
            quantity.power()
        ),
        series,
        hlines,
        y_range: None,
    }
}

/// Chordal deviation per segment against the tolerance (die-cavity paper, Figure 10):
/// `deviation[i]` is the largest distance (mm) between segment `i` and the curve it
/// approximates; shown as markers, the tolerance as a limit line. The unit follows the
/// tolerance (µm, or nm below 1 µm: the paper's 0.00004 mm is 40 nm) and the y axis runs from
/// 0 to 1.4 × the tolerance, so the picture shows how much of the tolerance each segment uses.
pub fn chordal_deviation(deviation: &[f64], tolerance: f64) -> Chart {
    let (unit, scale) = if tolerance.is_finite() && tolerance > 0.0 && tolerance < 1e-3 {
        ("nm", 1e6)
    } else {
        ("µm", 1e3)
    };
    let tol = tolerance * scale;
    Chart {
        title: "Chordal deviation per segment".into(),
        x_label: "segment".into(),
        y_label: format!("deviation ({unit})"),
        series: vec![Series {
            label: "deviation".into(),
            points: deviation
                .iter()
                .enumerate()
                .map(|(i, d)| (i as f64, d * scale))
                .collect(),
            style: SeriesStyle::Points,
            colour: 0,
        }],
        hlines: vec![HLine {
            label: format!("tolerance {} {unit}", significant(tol, 3)),
            y: tol,
        }],
        y_range: (tol.is_finite() && tol > 0.0).then_some((0.0, 1.4 * tol)),
    }
}

/// `x` with `digits` significant digits, trailing zeros trimmed (0.04, 5, 12.5).
fn significant(x: f64, digits: i32) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let decimals = (digits - 1 - x.abs().log10().floor() as i32).max(0) as usize;
    let s = format!("{x:.decimals$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_owned()
    } else {
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tick_labels_have_the_decimals_the_spacing_needs() {
        assert_eq!(tick_label(5000.0, 40_000.0), "5000");
        assert_eq!(tick_label(0.02, 0.1), "0.02");
        assert_eq!(tick_label(0.020000000000000004, 0.1), "0.02");
        assert_eq!(tick_label(-0.0, 2.0), "0.0");
        assert_eq!(tick_label(-1e-17, 2.0), "0.0");
        assert_eq!(tick_label(-0.4, 2.0), "-0.4");
        assert_eq!(tick_label(3.0, f64::NAN), "3.0");
    }

    #[test]
    fn significant_digits() {
        assert_eq!(significant(0.04, 3), "0.04");
        assert_eq!(significant(5.0, 3), "5");
        assert_eq!(significant(12.345, 3), "12.3");
    }

    #[test]
    fn charts_render_to_svg_with_their_text() {
        let c = chordal_deviation(&[0.001, 0.004, f64::NAN, 0.002], 0.005);
        let svg = render_svg(&c, &PlotOptions::default()).unwrap();
        assert!(svg.starts_with("<svg") && svg.contains("</svg>"));
        assert!(svg.contains("Chordal deviation per segment"));
        assert!(svg.contains("tolerance 5 µm"));
        let (_, _, y0, y1) = c.ranges();
        assert!(y0.abs() < 1e-12 && (y1 - 7.0).abs() < 1e-9, "{y0} {y1}");
        let nm = chordal_deviation(&[3.9e-5], 4e-5);
        assert_eq!(nm.hlines[0].label, "tolerance 40 nm");
        // Three finite markers plus the legend marker.
        assert_eq!(svg.matches("<circle").count(), 3 + 1, "{svg}");
    }

    #[test]
    fn empty_and_constant_charts_have_valid_ranges() {
        let (x0, x1, y0, y1) = Chart::default().ranges();
        assert!(x1 > x0 && y1 > y0);
        let c = feed_along_path(&[(0.0, 10.0), (5.0, 10.0)], None);
        let (_, _, y0, y1) = c.ranges();
        assert!(y0 < 600.0 && y1 > 600.0);
        assert!(render_svg(&Chart::default(), &PlotOptions::default()).is_ok());
    }

    #[test]
    fn kinematics_limits_are_symmetric_lines() {
        let c = axis_kinematics(
            Quantity::Acceleration,
            &[0.0, 1.0],
            &[AxisSeries {
                name: "X".into(),
                unit: "mm".into(),
                values: vec![0.0, 100.0],
                limit: Some(500.0),
            }],
        );
        let ys: Vec<f64> = c.hlines.iter().map(|h| h.y).collect();
        assert_eq!(ys, vec![500.0, -500.0]);
        let (_, _, y0, y1) = c.ranges();
        assert!(y0 < -500.0 && y1 > 500.0);
    }

    #[test]
    fn png_is_written() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("c.png");
        let c = cycle_time_vs_transition(&[("100 mm/min".into(), vec![(0.1, 3.0), (0.5, 2.0)])]);
        render_png(&c, &PlotOptions::default(), &p).unwrap();
        let bytes = std::fs::read(&p).unwrap();
        assert_eq!(&bytes[1..4], b"PNG");
        let svg = render_files(&c, &PlotOptions::default(), &dir.path().join("both")).unwrap();
        assert_eq!(
            std::fs::read_to_string(dir.path().join("both.svg")).unwrap(),
            svg
        );
        assert!(dir.path().join("both.png").is_file());
    }

    /// Dark pixels in rows `rows` of an RGB raster `width` pixels wide.
    fn dark_pixels(rgb: &[u8], width: usize, rows: std::ops::Range<usize>) -> usize {
        rows.flat_map(|y| (0..width).map(move |x| (y * width + x) * 3))
            .filter(|&i| rgb[i..i + 3].iter().all(|&c| c < 128))
            .count()
    }

    #[test]
    fn text_is_drawn_with_the_embedded_font() {
        // The caption band of a raster with a title has the glyphs' pixels; without one, none.
        // Fails when no font is available to draw (the caption would be blank) or when text is
        // measured but not drawn.
        let (w, h) = (400_usize, 200_usize);
        let raster = |title: &str| {
            let mut buf = vec![255_u8; w * h * 3];
            {
                let root =
                    BitMapBackend::with_buffer(&mut buf, (w as u32, h as u32)).into_drawing_area();
                let c = Chart {
                    title: title.into(),
                    ..Chart::default()
                };
                draw(&root, &c).unwrap();
            }
            buf
        };
        let with = dark_pixels(&raster("Feed along the path"), w, 0..24);
        let without = dark_pixels(&raster(""), w, 0..24);
        assert_eq!(without, 0);
        assert!(with > 100, "{with} dark pixels in the caption band");
    }
}
