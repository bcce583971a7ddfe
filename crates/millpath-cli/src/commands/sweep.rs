//! `millpath sweep`: cycle time of the spiral against zigzag over transition ratios and
//! feeds (the paper's Table 1 and Figure 10).

use super::pocket::{CommonArgs, load_outline};
use millpath::Error;
use millpath::strategy::pocket::{self, PocketOptions, PocketShape, StrategyKind};
use std::path::PathBuf;

/// Arguments of `millpath sweep`.
#[derive(Debug, clap::Args)]
#[command(after_help = "Example:\n  millpath sweep sample:aerospace --depth 6.35 --csv sweep.csv")]
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
}

fn list(text: &str, flag: &str) -> Result<Vec<f64>, Error> {
    text.split(',')
        .map(|t| {
            t.trim()
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| {
                    millpath::InputError::new("list value", t)
                        .at(flag)
                        .expected("comma-separated numbers")
                        .into()
                })
        })
        .collect()
}

/// Runs the command.
pub fn run(args: &Args) -> Result<(), Error> {
    let (tool, base) = args.common.options()?;
    let ratios = list(&args.ratios, "--ratios")?;
    let feeds = list(&args.feeds, "--feeds")?;
    let loops = load_outline(&args.outline)?;
    let shape = PocketShape::new(loops.outer, loops.islands, &args.outline)?;
    let mut rows = vec!["feed_ipm,strategy,C,cycle_time_s,gain_pct".to_owned()];
    let mut header = "C \\ feed (in/min)".to_owned();
    for f in &feeds {
        header.push_str(&format!(" | {f:>6}"));
    }
    super::print(&header);
    let machine = millpath::machine::Machine::preset(&args.common.machine)?;
    let time = |kind: StrategyKind, opts: &PocketOptions| -> Result<f64, Error> {
        let tp = pocket::toolpath(kind, &shape, &tool, opts)?;
        pocket::cycle_time_on(&tp, &machine)
    };
    let mut zig = Vec::new();
    let mut line = "zigzag".to_owned();
    for f in &feeds {
        let o = PocketOptions {
            feed: f * 25.4 / 60.0,
            ..base.clone()
        };
        let t = time(StrategyKind::Zigzag, &o)?;
        zig.push(t);
        line.push_str(&format!(" | {t:>6.1}"));
        rows.push(format!("{f},zigzag,,{t:.3},"));
    }
    super::print(&line);
    for c in &ratios {
        let mut line = format!("C = {:.0}%", 100.0 * c);
        for (f, tz) in feeds.iter().zip(&zig) {
            let o = PocketOptions {
                feed: f * 25.4 / 60.0,
                transition: *c,
                ..base.clone()
            };
            let t = time(StrategyKind::Spiral, &o)?;
            let gain = 100.0 * (tz - t) / tz;
            line.push_str(&format!(" | {t:>6.1} ({gain:+.1}%)"));
            rows.push(format!("{f},spiral,{c},{t:.3},{gain:.2}"));
        }
        super::print(&line);
    }
    super::print(&format!("cycle time model: {}", pocket::CYCLE_TIME_MODEL));
    if let Some(path) = &args.csv {
        millpath::io::write_atomic(path, (rows.join("\n") + "\n").as_bytes())?;
    }
    Ok(())
}
