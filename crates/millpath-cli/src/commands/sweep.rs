//! `millpath sweep`: cycle time of the spiral against zigzag over transition ratios and
//! feeds (the adaptive-spiral paper's Table 1 and Figure 10).
//!
//! The sweep itself is [`millpath::job::sweep`], shared with `millpath demo`.

use super::pocket::{CommonArgs, load_outline};
use millpath::Error;
use millpath::report::plots;
use millpath::strategy::pocket::PocketShape;
use std::path::PathBuf;

/// Arguments of `millpath sweep`.
#[derive(Debug, clap::Args)]
#[command(
    after_help = "Examples:\n  millpath sweep sample:aerospace --depth 6.35 --csv sweep.csv\n  millpath sweep sample:aerospace --ratios 0.2,0.5,0.7 --feeds 200,600 --plot fig10.svg --json"
)]
pub struct Args {
    /// Outline file or `sample:aerospace`.
    pub outline: String,
    #[command(flatten)]
    pub common: CommonArgs,
    /// Transition ratios C, comma separated.
    #[arg(long, default_value = "0.2,0.3,0.4,0.5,0.6,0.7")]
    pub ratios: String,
    /// Feeds in in/min, comma separated.
    #[arg(long, default_value = "200,300,350,400,450,500,600")]
    pub feeds: String,
    /// Also write the table as CSV.
    #[arg(long)]
    pub csv: Option<PathBuf>,
    /// Draw cycle time against C, one curve per feed, zigzag dashed (the paper's Figure 10):
    /// an .svg or .png file.
    #[arg(long)]
    pub plot: Option<PathBuf>,
    /// Print the table as one JSON object on stdout.
    #[arg(long)]
    pub json: bool,
}

/// Parses the comma-separated list given to `flag`; an entry that is not a number accepted by
/// `ok` is refused by name, as typed (not a converted value), with the flag.
fn list(
    text: &str,
    flag: &str,
    what: &str,
    ok: fn(f64) -> bool,
    expected: &str,
) -> Result<Vec<f64>, Error> {
    text.split(',')
        .map(|t| {
            t.trim()
                .parse::<f64>()
                .ok()
                .filter(|v| ok(*v))
                .ok_or_else(|| {
                    millpath::InputError::new(what, t.trim())
                        .at(flag)
                        .expected(format!("comma-separated {expected}"))
                        .into()
                })
        })
        .collect()
}

/// Writes `chart` as SVG or PNG by the extension of `path`.
pub fn write_chart(chart: &plots::Chart, path: &std::path::Path) -> Result<(), Error> {
    let opts = plots::PlotOptions::default();
    match path.extension().and_then(|e| e.to_str()) {
        Some(e) if e.eq_ignore_ascii_case("png") => plots::render_png(chart, &opts, path),
        Some(e) if e.eq_ignore_ascii_case("svg") => {
            millpath::io::write_atomic(path, plots::render_svg(chart, &opts)?.as_bytes())
        }
        _ => Err(millpath::InputError::new("plot file", path.display())
            .at("--plot")
            .expected("a file name ending in .svg or .png")
            .into()),
    }
}

/// Runs the command.
pub fn run(args: &Args) -> Result<(), Error> {
    let (tool, base) = args.common.options()?;
    let ratios = list(
        &args.ratios,
        "--ratios",
        "transition ratio",
        |c| (0.0..=1.0).contains(&c),
        "ratios in [0, 1]",
    )?;
    let feeds = list(
        &args.feeds,
        "--feeds",
        "feed",
        |f| f.is_finite() && f > 0.0,
        "finite feeds > 0 in/min",
    )?;
    let loops = load_outline(&args.outline, &args.common.import)?;
    if loops.len() > 1 {
        return Err(millpath::InputError::new("pockets", loops.len())
            .at(args.outline.clone())
            .expected("a drawing of one pocket for the sweep (`pocket --list` shows them)")
            .into());
    }
    // `--draft` / `--bottom-outline` give each level its own section, as in `pocket`.
    let shape =
        args.common
            .with_walls(PocketShape::new(loops.outer, loops.islands, &args.outline)?)?;
    let machine = super::load_machine(&args.common.machine)?;
    let table = millpath::job::sweep::sweep(
        &shape,
        &tool,
        &base,
        &machine,
        &ratios,
        &feeds,
        &mut |_, _| {},
    )?;
    if let Some(path) = &args.csv {
        millpath::io::write_atomic(path, table.csv().as_bytes())?;
    }
    if let Some(path) = &args.plot {
        write_chart(&table.chart(), path)?;
    }
    if args.json {
        return super::print_json(&table);
    }
    let mut header = "C \\ feed (in/min)".to_owned();
    for f in &feeds {
        header.push_str(&format!(" | {f:>6}"));
    }
    super::print(&header);
    let mut line = "zigzag".to_owned();
    for t in &table.zigzag_s {
        line.push_str(&format!(" | {t:>6.1}"));
    }
    super::print(&line);
    for (c, ratio) in ratios.iter().enumerate() {
        let mut line = format!("C = {:.0}%", 100.0 * ratio);
        for f in 0..feeds.len() {
            line.push_str(&format!(
                " | {:>6.1} ({:+.1}%)",
                table.spiral_s[c][f],
                table.gain(c, f)
            ));
        }
        super::print(&line);
    }
    super::print(&format!("cycle time model: {}", table.cycle_time_model));
    Ok(())
}
