//! `millpath sweep`: cycle time of the spiral against zigzag over transition ratios and
//! feeds (the adaptive-spiral paper's Table 1 and Figure 10).
//!
//! [`sweep`] is shared with `millpath demo`, which draws the paper's Figure 10 from it.

use super::pocket::{CommonArgs, load_outline};
use millpath::Error;
use millpath::machine::Machine;
use millpath::report::plots;
use millpath::strategy::pocket::{self, PocketOptions, PocketShape, SpiralMorph, StrategyKind};
use millpath::toolpath::Tool;
use serde::Serialize;
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

/// The result of a sweep: zigzag's time per feed and the spiral's per (C, feed).
#[derive(Debug, Clone, Serialize)]
pub struct Sweep {
    /// Machine whose planner timed every toolpath.
    pub machine: String,
    /// Transition ratios C.
    pub ratios: Vec<f64>,
    /// Feeds, in/min.
    pub feeds_ipm: Vec<f64>,
    /// Zigzag cycle time per feed, s.
    pub zigzag_s: Vec<f64>,
    /// Spiral cycle time, `spiral_s[c][f]` for `ratios[c]` and `feeds_ipm[f]`, s.
    pub spiral_s: Vec<Vec<f64>>,
    /// How the times were computed.
    pub cycle_time_model: String,
}

impl Sweep {
    /// Gain of the spiral over zigzag in %, positive when the spiral is faster.
    pub fn gain(&self, c: usize, f: usize) -> f64 {
        match (
            self.spiral_s.get(c).and_then(|r| r.get(f)),
            self.zigzag_s.get(f),
        ) {
            (Some(t), Some(z)) if *z > 0.0 => 100.0 * (z - t) / z,
            _ => f64::NAN,
        }
    }

    /// The paper's Figure 10: one curve per feed, zigzag dashed in the same colour.
    pub fn chart(&self) -> plots::Chart {
        let curves: Vec<(String, Vec<(f64, f64)>)> = self
            .feeds_ipm
            .iter()
            .enumerate()
            .map(|(f, feed)| {
                (
                    format!("{feed:.0} in/min"),
                    self.ratios
                        .iter()
                        .enumerate()
                        .filter_map(|(c, r)| Some((*r, *self.spiral_s.get(c)?.get(f)?)))
                        .collect(),
                )
            })
            .collect();
        let refs: Vec<(String, f64)> = self
            .feeds_ipm
            .iter()
            .zip(&self.zigzag_s)
            .map(|(_, t)| (String::new(), *t))
            .collect();
        let mut chart = plots::cycle_time_vs_transition_with(&curves, &refs);
        chart.title = format!(
            "Cycle time against C on {}: spiral solid, zigzag dashed",
            self.machine
        );
        chart
    }
}

/// Times zigzag at every feed and the spiral at every (C, feed) on `machine`; `base` gives
/// everything else. `progress` is called after each toolpath with (done, total).
pub fn sweep(
    shape: &PocketShape,
    tool: &Tool,
    base: &PocketOptions,
    machine: &Machine,
    ratios: &[f64],
    feeds_ipm: &[f64],
    progress: &mut dyn FnMut(usize, usize),
) -> Result<Sweep, Error> {
    let total = feeds_ipm.len() * (1 + ratios.len());
    let mut done = 0;
    // The transition C is the paper's central spiral's, which the fronts and harmonic morphs
    // draw; the default (offsets) morph has none.
    let morph = match base.morph {
        SpiralMorph::Offsets => SpiralMorph::Fronts,
        m => m,
    };
    let mut time = |kind: StrategyKind, feed: f64, c: f64| -> Result<f64, Error> {
        let o = PocketOptions {
            feed: feed * 25.4 / 60.0,
            transition: c,
            morph,
            ..base.clone()
        };
        let tp = pocket::toolpath(kind, shape, tool, &o)?;
        let t = millpath::motion::cycle_time(&tp, machine)
            .map_err(|e| e.engine_made("timing the pocket toolpath"))?;
        done += 1;
        progress(done, total);
        Ok(t)
    };
    let zigzag_s = feeds_ipm
        .iter()
        .map(|f| time(StrategyKind::Zigzag, *f, base.transition))
        .collect::<Result<Vec<_>, _>>()?;
    let spiral_s = ratios
        .iter()
        .map(|c| {
            feeds_ipm
                .iter()
                .map(|f| time(StrategyKind::Spiral, *f, *c))
                .collect::<Result<Vec<_>, _>>()
        })
        .collect::<Result<Vec<_>, _>>()?;
    Ok(Sweep {
        machine: machine.name.clone(),
        ratios: ratios.to_vec(),
        feeds_ipm: feeds_ipm.to_vec(),
        zigzag_s,
        spiral_s,
        cycle_time_model: millpath::motion::CYCLE_TIME_MODEL.to_owned(),
    })
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
    let table = sweep(
        &shape,
        &tool,
        &base,
        &machine,
        &ratios,
        &feeds,
        &mut |_, _| {},
    )?;
    let mut rows = vec!["feed_ipm,strategy,C,cycle_time_s,gain_pct".to_owned()];
    for (f, t) in feeds.iter().zip(&table.zigzag_s) {
        rows.push(format!("{f},zigzag,,{t:.3},"));
    }
    for (c, ratio) in ratios.iter().enumerate() {
        for (f, feed) in feeds.iter().enumerate() {
            let t = table.spiral_s[c][f];
            rows.push(format!(
                "{feed},spiral,{ratio},{t:.3},{:.2}",
                table.gain(c, f)
            ));
        }
    }
    if let Some(path) = &args.csv {
        millpath::io::write_atomic(path, (rows.join("\n") + "\n").as_bytes())?;
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
