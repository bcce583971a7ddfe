//! `--html OUT.html` for the commands: one self-contained report per run, built from the
//! engine's report pieces (`millpath::report`).

use millpath::geom::Outline;
use millpath::machine::Machine;
use millpath::motion::Plan;
use millpath::report::html::HtmlReport;
use millpath::report::{self, plots};
use millpath::{Error, Toolpath};
use std::path::Path;

/// A report with a summary table, the toolpath viewer (preview coloured by achieved feed,
/// playback along `plan`) and the feed-along-path plot.
pub fn toolpath_report(
    title: &str,
    summary: Vec<(String, String)>,
    tp: &Toolpath,
    outlines: &[Outline],
    plan: &Plan,
) -> Result<HtmlReport, Error> {
    let mut html = HtmlReport::new(title);
    html.section("summary", summary);
    html.toolpath_viewer(title, tp, outlines, plan)?;
    html.plot(
        "Feed along the cutting path (rapids left out): achieved by the planner against programmed",
        &plots::render_svg(&report::feed_chart(plan)?, &plots::PlotOptions::default())?,
    )?;
    Ok(html)
}

/// The machine's limits as one summary row.
pub fn machine_row(m: &Machine) -> (String, String) {
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

/// Writes `html` to `path` atomically.
pub fn write(path: &Path, html: &HtmlReport) -> Result<(), Error> {
    millpath::io::write_atomic(path, html.to_html().as_bytes())
}
