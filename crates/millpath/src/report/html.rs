//! One self-contained HTML report: summary tables, plots and an interactive toolpath viewer.
//!
//! The file needs no network: styles, SVG pictures, the sampled trajectory (JSON) and a small
//! script of our own are all inline. The only URL in it is the SVG namespace
//! `http://www.w3.org/2000/svg`, which is an identifier, not a resource.
//!
//! ## What goes in
//! - [`HtmlReport::section`]: a titled table of key/value rows (cycle time, path length,
//!   blocks, max engagement, max chordal deviation, verifier results, limits used...). Keys and
//!   values are escaped text.
//! - [`HtmlReport::plot`]: a caption and an SVG document (from [`super::plots::render_svg`]).
//! - [`HtmlReport::viewer`]: a toolpath preview SVG (from [`super::toolpath_svg`]), the names of
//!   its levels, and the planned trajectory as `(t, x, y, z)` points (see [`thin_trajectory`]).
//!
//! SVG documents are inserted as markup (that is their purpose); they are stripped of any XML
//! prolog and refused if they contain a `<script` or an external reference, so a report never
//! runs foreign code or fetches anything. All text is escaped with [`escape_html`]; the JSON
//! is escaped so that it cannot close its `<script>` element.
//!
//! ## The viewer's script
//! Pan (drag) and zoom (wheel, buttons) rewrite the preview's `viewBox`; the level selector
//! shows one `g.mp-level` group at a time; the time slider places the tool marker by linear
//! interpolation of the trajectory between the two samples around `t` (binary search), and
//! "play" advances the slider in real time. Errors are caught by a handler installed before
//! the main script and shown on the page (`body[data-mp-errors]` counts them). Opening the file
//! with `#selftest` moves the slider to the middle of the cycle and writes the outcome into the
//! document title (`MP-SELFTEST-OK t=… x=… y=… z=…` or `MP-SELFTEST-FAIL …`), which is how the
//! headless-browser test drives it.

use crate::error::{Error, InputError};
use std::fmt::Write;

/// A report with a summary table, the toolpath viewer (preview coloured by achieved feed,
/// playback along `plan`) and the feed-along-path plot (where the target draws plots,
/// [`super::plots::PLOTS_DRAWN`]): what `--html` writes for a toolpath.
pub fn toolpath_report(
    title: &str,
    summary: Vec<(String, String)>,
    tp: &crate::toolpath::Toolpath,
    outlines: &[crate::geom::Outline],
    plan: &crate::motion::Plan,
) -> Result<HtmlReport, Error> {
    let mut html = HtmlReport::new(title);
    html.section("summary", summary);
    html.toolpath_viewer(title, tp, outlines, plan)?;
    if super::plots::PLOTS_DRAWN {
        html.plot(
            "Feed along the cutting path (rapids left out): achieved by the planner against programmed",
            &super::plots::render_svg(
                &super::feed_chart(plan)?,
                &super::plots::PlotOptions::default(),
            )?,
        )?;
    }
    Ok(html)
}

/// The machine's limits as one summary row.
pub fn machine_row(m: &crate::machine::Machine) -> (String, String) {
    let a = &m.axes[0];
    let jerk = if a.max_jerk.is_finite() {
        format!("{:.0}", a.max_jerk)
    } else {
        "unlimited".to_owned()
    };
    (
        "machine".to_owned(),
        format!(
            "{}: X v {:.0} mm/s, a {:.0} mm/s², j {jerk} mm/s³, path tolerance {} mm",
            m.name, a.max_velocity, a.max_acceleration, m.path_tolerance
        ),
    )
}

/// Escapes text for HTML element content and quoted attribute values.
pub fn escape_html(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            _ => out.push(c),
        }
    }
    out
}

/// A titled table of key/value rows.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Section {
    /// Heading.
    pub title: String,
    /// (key, value) rows, as text.
    pub rows: Vec<(String, String)>,
}

/// A titled table of columns (the setup sheet's operations and tools).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Table {
    /// Heading.
    pub title: String,
    /// An `id` for the table element (letters, digits and `-`), for links and tests.
    pub id: String,
    /// Column headings.
    pub columns: Vec<String>,
    /// Rows of cells, as text.
    pub rows: Vec<Vec<String>>,
}

#[derive(Debug, Clone, PartialEq)]
struct Viewer {
    svg: String,
    levels: Vec<String>,
    trajectory: Vec<[f64; 4]>,
}

/// Builder of the report; [`HtmlReport::to_html`] writes the document.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct HtmlReport {
    title: String,
    sections: Vec<Section>,
    tables: Vec<Table>,
    plots: Vec<(String, String)>,
    viewers: Vec<(String, Viewer)>,
}

/// Removes an XML prolog and checks that `svg` is an inert SVG document.
fn clean_svg(svg: &str, origin: &str) -> Result<String, Error> {
    let mut s = svg.trim();
    if s.starts_with("<?xml") {
        s = s.find("?>").map_or(s, |k| s[k + 2..].trim_start());
    }
    let lower = s.to_ascii_lowercase();
    if !lower.starts_with("<svg") {
        return Err(
            InputError::new("SVG picture", s.chars().take(40).collect::<String>())
                .at(origin)
                .expected("an SVG document starting with <svg")
                .into(),
        );
    }
    for bad in [
        "<script",
        "href=\"http",
        "href='http",
        "url(http",
        "<foreignobject",
    ] {
        if lower.contains(bad) {
            return Err(InputError::new("SVG picture", bad)
                .at(origin)
                .expected("an SVG without scripts, foreign objects or external references")
                .into());
        }
    }
    Ok(s.to_string())
}

/// At most `max_points` samples `(t, x, y, z)` taken at evenly spaced indices of `points`,
/// always including the first and the last; non-finite samples are dropped. Linear
/// interpolation between kept samples then stays within the tool's travel between them.
pub fn thin_trajectory(points: &[[f64; 4]], max_points: usize) -> Vec<[f64; 4]> {
    let pts: Vec<[f64; 4]> = points
        .iter()
        .copied()
        .filter(|p| p.iter().all(|v| v.is_finite()))
        .collect();
    let max = max_points.max(2);
    if pts.len() <= max {
        return pts;
    }
    let n = pts.len();
    (0..max)
        .filter_map(|k| pts.get(k * (n - 1) / (max - 1)).copied())
        .collect()
}

/// The `(t, x, y, z)` trajectory of plan samples (see `millpath::motion::Plan::sample`).
pub fn trajectory_of(samples: &[crate::motion::Sample]) -> Vec<[f64; 4]> {
    samples
        .iter()
        .map(|s| [s.t, s.position.x, s.position.y, s.position.z])
        .collect()
}

impl HtmlReport {
    /// An empty report with a page title.
    pub fn new(title: impl Into<String>) -> Self {
        HtmlReport {
            title: title.into(),
            ..HtmlReport::default()
        }
    }

    /// Adds a summary table.
    pub fn section(
        &mut self,
        title: impl Into<String>,
        rows: impl IntoIterator<Item = (String, String)>,
    ) -> &mut Self {
        self.sections.push(Section {
            title: title.into(),
            rows: rows.into_iter().collect(),
        });
        self
    }

    /// Adds a table of columns; `id` keeps only ASCII letters, digits and `-`.
    pub fn table(&mut self, table: Table) -> &mut Self {
        let id = table
            .id
            .chars()
            .filter(|c| c.is_ascii_alphanumeric() || *c == '-')
            .collect();
        self.tables.push(Table { id, ..table });
        self
    }

    /// Adds a plot (an SVG document) with a caption.
    pub fn plot(&mut self, caption: impl Into<String>, svg: &str) -> Result<&mut Self, Error> {
        let caption = caption.into();
        let svg = clean_svg(svg, &format!("plot '{caption}'"))?;
        self.plots.push((caption, svg));
        Ok(self)
    }

    /// Adds an interactive viewer: a toolpath preview (from [`super::toolpath_svg`]), the
    /// names of its levels (index = `data-level`), and the trajectory `(t, x, y, z)` for
    /// playback, thinned to at most 4000 points. Times must not decrease.
    pub fn viewer(
        &mut self,
        name: impl Into<String>,
        preview_svg: &str,
        levels: Vec<String>,
        trajectory: &[[f64; 4]],
    ) -> Result<&mut Self, Error> {
        let name = name.into();
        let svg = clean_svg(preview_svg, &format!("viewer '{name}'"))?;
        let trajectory = thin_trajectory(trajectory, 4000);
        if let Some(w) = trajectory.windows(2).find(|w| w[1][0] < w[0][0]) {
            return Err(InputError::new("trajectory time", w[1][0])
                .at(format!("viewer '{name}'"))
                .expected(format!("times that do not decrease (previous {})", w[0][0]))
                .into());
        }
        self.viewers.push((
            name,
            Viewer {
                svg,
                levels,
                trajectory,
            },
        ));
        Ok(self)
    }

    /// Convenience for [`Self::viewer`]: previews `toolpath` over `outlines` coloured by the
    /// plan's achieved peak feeds, names the levels by kind and depth, and samples the plan
    /// for playback (about 4000 samples, never closer than 1 ms). Returns the preview SVG so
    /// it can also be written to a file.
    pub fn toolpath_viewer(
        &mut self,
        name: impl Into<String>,
        toolpath: &crate::toolpath::Toolpath,
        outlines: &[crate::geom::Outline],
        plan: &crate::motion::Plan,
    ) -> Result<String, Error> {
        let name = name.into();
        let preview = super::toolpath_svg(
            toolpath,
            outlines,
            &super::PreviewOptions {
                title: Some(name.clone()),
                achieved_feed: Some(plan.peak_feed_by_move(toolpath.moves.len())),
                ..super::PreviewOptions::default()
            },
        );
        let dt = (plan.total_time / 4000.0).max(1e-3);
        let samples = plan.sample(dt)?;
        let levels = toolpath
            .levels
            .iter()
            .enumerate()
            .map(|(i, l)| format!("{} {:?} z = {:.3} mm", i + 1, l.kind, l.z))
            .collect();
        self.viewer(name, &preview, levels, &trajectory_of(&samples))?;
        Ok(preview)
    }

    /// The HTML document.
    pub fn to_html(&self) -> String {
        let mut h = String::new();
        let title = escape_html(&self.title);
        let _ = write!(
            h,
            "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
             <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n\
             <title>{title}</title>\n<style>{CSS}</style>\n<script>{ERROR_HOOK}</script>\n\
             </head>\n<body data-mp-errors=\"0\">\n<h1>{title}</h1>\n\
             <pre id=\"mp-errors\" hidden></pre>\n"
        );
        if !self.sections.is_empty() {
            h.push_str("<section class=\"mp-summary\">\n");
            for s in &self.sections {
                let _ = write!(h, "<table>\n<caption>{}</caption>\n", escape_html(&s.title));
                for (k, v) in &s.rows {
                    let _ = writeln!(
                        h,
                        "<tr><th>{}</th><td>{}</td></tr>",
                        escape_html(k),
                        escape_html(v)
                    );
                }
                h.push_str("</table>\n");
            }
            h.push_str("</section>\n");
        }
        for t in &self.tables {
            let _ = write!(
                h,
                "<section class=\"mp-table\">\n<table id=\"{}\">\n<caption>{}</caption>\n<tr>",
                t.id,
                escape_html(&t.title)
            );
            for c in &t.columns {
                let _ = write!(h, "<th>{}</th>", escape_html(c));
            }
            h.push_str("</tr>\n");
            for r in &t.rows {
                h.push_str("<tr>");
                for c in r {
                    let _ = write!(h, "<td>{}</td>", escape_html(c));
                }
                h.push_str("</tr>\n");
            }
            h.push_str("</table>\n</section>\n");
        }
        for (i, (name, v)) in self.viewers.iter().enumerate() {
            let _ = write!(
                h,
                "<section class=\"mp-viewer\" id=\"mp-viewer-{i}\">\n<h2>{}</h2>\n\
                 <div class=\"mp-controls\">\
                 <label>level <select class=\"mp-level-select\"><option value=\"all\">all levels</option>",
                escape_html(name)
            );
            for (k, l) in v.levels.iter().enumerate() {
                let _ = write!(h, "<option value=\"{k}\">{}</option>", escape_html(l));
            }
            let tmax = v.trajectory.last().map_or(0.0, |p| p[0]);
            let _ = write!(
                h,
                "</select></label> \
                 <button type=\"button\" class=\"mp-zoom-in\">+</button>\
                 <button type=\"button\" class=\"mp-zoom-out\">−</button>\
                 <button type=\"button\" class=\"mp-reset\">reset view</button> \
                 <button type=\"button\" class=\"mp-play\">play</button> \
                 <input type=\"range\" class=\"mp-time\" min=\"0\" max=\"{tmax}\" step=\"any\" value=\"0\"> \
                 <output class=\"mp-readout\">t = 0 s</output></div>\n\
                 <div class=\"mp-canvas\">{}</div>\n\
                 <script type=\"application/json\" class=\"mp-trajectory\">{}</script>\n</section>\n",
                v.svg,
                json_for_script(&v.trajectory)
            );
        }
        if !self.plots.is_empty() {
            h.push_str("<section class=\"mp-plots\">\n");
            for (caption, svg) in &self.plots {
                let _ = writeln!(
                    h,
                    "<figure>{svg}<figcaption>{}</figcaption></figure>",
                    escape_html(caption)
                );
            }
            h.push_str("</section>\n");
        }
        let _ = write!(h, "<script>{SCRIPT}</script>\n</body>\n</html>\n");
        h
    }
}

/// JSON of the trajectory, with `<` escaped so it cannot end the `<script>` element.
fn json_for_script(traj: &[[f64; 4]]) -> String {
    let mut s = String::from("[");
    for (i, p) in traj.iter().enumerate() {
        if i > 0 {
            s.push(',');
        }
        let _ = write!(s, "[{},{},{},{}]", p[0], p[1], p[2], p[3]);
    }
    s.push(']');
    s.replace('<', "\\u003c")
}

const CSS: &str = "body{font-family:sans-serif;margin:1.5em;color:#222;background:#fafafa}\
h1{font-size:1.5em}h2{font-size:1.2em}\
.mp-summary{display:flex;flex-wrap:wrap;gap:1.5em}\
table{border-collapse:collapse;background:#fff}caption{font-weight:bold;text-align:left;padding:.3em 0}\
th,td{border:1px solid #ccc;padding:.25em .6em;text-align:left}th{background:#f0f0f0;font-weight:normal}\
.mp-controls{margin:.5em 0;display:flex;gap:.5em;align-items:center;flex-wrap:wrap}\
.mp-time{width:30em}\
.mp-canvas{border:1px solid #bbb;background:#fff;overflow:hidden;cursor:grab;max-width:100%}\
.mp-canvas svg{display:block;width:100%;height:auto}\
.mp-plots{display:flex;flex-wrap:wrap;gap:1em}figure{margin:0;background:#fff;border:1px solid #ddd}\
figcaption{padding:.3em;font-size:.9em}\
#mp-errors{color:#b00;background:#fee;padding:.5em}";

/// Installed before the main script so that even its errors are recorded.
const ERROR_HOOK: &str = "window.mpErrors=[];window.addEventListener('error',function(e){\
window.mpErrors.push(String(e.message));var b=document.body;if(b){b.setAttribute('data-mp-errors',\
String(window.mpErrors.length));var p=document.getElementById('mp-errors');if(p){p.hidden=false;\
p.textContent=window.mpErrors.join('\\n');}}document.title='MP-ERROR '+e.message;});";

const SCRIPT: &str = include_str!("viewer.js");

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig { cases: 64, rng_seed: proptest::test_runner::RngSeed::Fixed(6), ..ProptestConfig::default() })]
        /// Whatever text goes into a table, no markup character survives unescaped.
        #[test]
        fn escaped_text_has_no_markup(key in ".{0,40}", value in "[<>&\"' a-z]{0,40}") {
            let mut r = HtmlReport::new("t");
            r.section("s", vec![(key.clone(), value.clone())]);
            let h = r.to_html();
            let row = h.split("<tr><th>").nth(1).and_then(|s| s.split("</td></tr>").next()).unwrap();
            let text = row.replacen("</th><td>", "", 1);
            prop_assert!(!text.contains(['<', '>', '"', '\'']));
            prop_assert_eq!(text.matches('&').count(), text.matches(';').count() - (key.matches(';').count() + value.matches(';').count()));
        }
    }

    #[test]
    fn text_is_escaped_and_svg_checked() {
        let mut r = HtmlReport::new("<x> & \"y\"");
        r.section(
            "sum<mary>",
            vec![("cycle <time>".to_string(), "1 & 2".to_string())],
        );
        let h = r.to_html();
        assert!(h.contains("<title>&lt;x&gt; &amp; &quot;y&quot;</title>"));
        assert!(h.contains("<th>cycle &lt;time&gt;</th><td>1 &amp; 2</td>"));
        assert!(!h.contains("<x>"));
        let svg = r#"<svg xmlns="http://www.w3.org/2000/svg"><script>alert(1)</script></svg>"#;
        assert!(r.plot("p", svg).is_err());
        assert!(r.plot("p", "<div/>").is_err());
        let ok = r#"<?xml version="1.0"?><svg xmlns="http://www.w3.org/2000/svg"></svg>"#;
        r.plot("p", ok).unwrap();
        assert!(!r.to_html().contains("<?xml"));
    }

    #[test]
    fn toolpath_viewer_embeds_plan_and_levels() {
        use crate::geom::Point3;
        use crate::toolpath::{Level, LevelKind, Move, Tool, Toolpath};
        let mut tp = Toolpath::new(Tool::default(), Point3::ORIGIN);
        tp.push(Move::line(Point3::new(20.0, 0.0, -1.0), 30.0));
        tp.push(Move::line(Point3::new(20.0, 10.0, -1.0), 30.0));
        tp.levels.push(Level {
            z: -1.0,
            kind: LevelKind::Finishing,
            start: 0,
            end: 2,
        });
        let m = crate::machine::Machine::preset("hsm").unwrap();
        let plan = crate::motion::plan_toolpath(&tp, &m).unwrap();
        let mut r = HtmlReport::new("t");
        let svg = r.toolpath_viewer("square", &tp, &[], &plan).unwrap();
        assert!(svg.contains("achieved feed"));
        let h = r.to_html();
        assert!(h.contains("1 Finishing z = -1.000 mm"));
        let json = h
            .split("class=\"mp-trajectory\">")
            .nth(1)
            .and_then(|s| s.split("</script>").next())
            .unwrap();
        let traj: Vec<[f64; 4]> = serde_json::from_str(json).unwrap();
        let last = traj.last().unwrap();
        assert!((last[0] - plan.total_time).abs() < 1e-9);
        assert!((last[1] - 20.0).abs() < 1e-6 && (last[2] - 10.0).abs() < 1e-6);
        assert!(traj.len() <= 4000 && traj.len() > 100);
    }

    #[test]
    fn thinning_keeps_ends_and_bounds_size() {
        let pts: Vec<[f64; 4]> = (0..10_001).map(|i| [i as f64, 0.0, 0.0, 0.0]).collect();
        let t = thin_trajectory(&pts, 100);
        assert_eq!(t.len(), 100);
        assert!(t[0][0].abs() < 1e-12);
        assert!((t[99][0] - 10_000.0).abs() < 1e-12);
        assert!(t.windows(2).all(|w| w[1][0] > w[0][0]));
        let short = thin_trajectory(&pts[..5], 100);
        assert_eq!(short.len(), 5);
    }

    #[test]
    fn decreasing_time_is_refused_and_json_cannot_close_script() {
        let mut r = HtmlReport::new("t");
        let svg = r#"<svg xmlns="http://www.w3.org/2000/svg"></svg>"#;
        let e = r
            .viewer(
                "v",
                svg,
                vec![],
                &[[1.0, 0.0, 0.0, 0.0], [0.5, 0.0, 0.0, 0.0]],
            )
            .unwrap_err();
        assert!(e.to_string().contains("trajectory time"), "{e}");
        assert_eq!(json_for_script(&[[0.0, 1.5, -2.0, 3.0]]), "[[0,1.5,-2,3]]");
    }
}
