//! The verify job behind `millpath verify`: a G-code program read back and checked against
//! pocket outlines by the material-removal simulation (`stock::verify_part`: gouge, uncut
//! material, rapids through material, engagement), with the gouge test allowing for the
//! program's own rounding (2·½·10^−d·√2 mm at d decimals).

use super::estimate::{Choosing, Failure};
use crate::gcode::{Dialect, DialectChoice, ReaderOptions, read_str};
use crate::io::outline_json::Loops;
use crate::stock::{self, PartVerification, Problem, StockSpec};
use crate::strategy::pocket::{PocketShape, Stepover, engagement_floor, nominal_engagement};
use crate::toolpath::{Tool, Toolpath};
use crate::{Error, InputError};

/// A verify job's settings, named and defaulted as `millpath verify`'s flags.
#[derive(Debug, Clone, PartialEq)]
pub struct VerifySettings {
    /// Tool diameter, mm.
    pub tool_diameter: f64,
    /// Wall stock the program must leave, mm.
    pub wall_stock: f64,
    /// The nominal stepover, for the share above the nominal engagement.
    pub stepover: String,
    /// Raster cell, mm (`None`: 0.05 mm up to a 12.7 mm tool, 1/254 of the diameter above,
    /// [`crate::stock::DEFAULT_CELL`]).
    pub cell: Option<f64>,
    /// Decimals the program was written with (`None`: the most found in it).
    pub decimals: Option<u32>,
    /// Check only these pockets of the drawing: `1,3`, `2-4` (all when `None`).
    pub select: Option<String>,
    /// Folders searched for RS274/NGC subroutine files, after the program's own folder.
    pub subroutine_path: Vec<std::path::PathBuf>,
    /// A LinuxCNC tool table for G43 and T words.
    pub tool_table: Option<std::path::PathBuf>,
    /// Lines the program may run again before it is refused as endless
    /// ([`ReaderOptions::step_budget`]).
    pub step_budget: u64,
    /// The program's dialect: `linuxcnc`, `fanuc`, `sinumerik`, `grbl`, or `auto` (found from
    /// its extension and first lines, [`crate::gcode::DialectGuess`], with the fallback to
    /// the next candidate when the first one's reader refuses the program).
    pub dialect: String,
    /// A machine (preset name or TOML file) to plan the program on, for the cycle time, the
    /// time not cutting and the removal rate (`None`: not planned).
    pub machine: Option<String>,
}

impl Default for VerifySettings {
    fn default() -> Self {
        VerifySettings {
            tool_diameter: 12.7,
            wall_stock: 0.0,
            stepover: "0.4".into(),
            cell: None,
            decimals: None,
            select: None,
            subroutine_path: Vec::new(),
            tool_table: None,
            step_budget: crate::gcode::DEFAULT_STEP_BUDGET,
            dialect: "auto".into(),
            machine: None,
        }
    }
}

/// What the verify job found.
#[derive(Debug)]
pub struct VerifyRun {
    /// The program read back, levels inferred.
    pub toolpath: Toolpath,
    /// The whole part's findings, each pocket's and the cuts outside every pocket.
    pub part: PartVerification,
    /// Problems beyond the gouge resolution (empty: the program passes).
    pub problems: Vec<Problem>,
    /// Decimals the gouge test allowed for.
    pub decimals: u32,
    /// The gouge resolution at those decimals, mm.
    pub gouge_resolution_mm: f64,
    /// The pockets checked (indices in the drawing, 1-based).
    pub selected: Vec<usize>,
    /// The dialect the program was read in, and why.
    pub dialect: DialectChoice,
    /// The engagement the sharpest corner of the checked pockets' tool-centre regions forces
    /// on any program, degrees (`pocket::engagement_floor`).
    pub engagement_floor_deg: f64,
    /// The program planned on [`VerifySettings::machine`], when one was given.
    pub timing: Option<VerifyTiming>,
}

/// A verified program planned on a machine.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct VerifyTiming {
    /// The machine, as given.
    pub machine: String,
    /// Cycle time, s.
    pub cycle_time_s: f64,
    /// Time in moves that remove no material, the entries aside, s
    /// (`pocket_report::air_times`).
    pub air_time_s: f64,
    /// The rapids' part of it, s.
    pub rapid_time_s: f64,
    /// Time in the entries (descents by helix or ramp and the flat turns on their track), s.
    pub entry_time_s: f64,
    /// Material removed per second of the cycle time, mm³/s.
    pub removal_rate_mm3_s: f64,
}

impl VerifyRun {
    /// The JSON `millpath verify --json` prints (without its `pictures`).
    pub fn json(&self) -> serde_json::Value {
        serde_json::json!({
            "passed": self.problems.is_empty(),
            "problems": self.problems.iter().map(ToString::to_string).collect::<Vec<_>>(),
            "levels": self.toolpath.levels.len(),
            "verification": self.part.total,
            "pockets": self.part.pockets,
            "cuts_outside": self.part.cuts_outside,
            "unreachable_pockets": self.part.unreachable.iter().map(|k| k + 1).collect::<Vec<_>>(),
            "decimals": self.decimals,
            "gouge_resolution_mm": self.gouge_resolution_mm,
            "engagement_floor_deg": self.engagement_floor_deg,
            "timing": self.timing,
        })
    }
}

/// Checks the program `text` (named `origin`) against the pockets of `loops`.
pub fn run(
    loops: &Loops,
    text: &str,
    origin: &str,
    settings: &VerifySettings,
) -> Result<VerifyRun, Error> {
    let (tool, s) = settings.check()?;
    let machine = match &settings.machine {
        Some(m) => Some((m, super::load_machine(m)?)),
        None => None,
    };
    let choosing = Choosing::new(&settings.dialect, Some(std::path::Path::new(origin)), text)?;
    let ropts = |d: Dialect| {
        ReaderOptions::default()
            .with_dialect(d)
            .with_step_budget(settings.step_budget)
            .with_origin(origin)
            .with_program_files(
                std::path::Path::new(origin),
                &settings.subroutine_path,
                settings.tool_table.as_deref(),
            )
    };
    ropts(Dialect::LinuxCnc)?;
    let read = |d: Dialect| {
        let o = ropts(d).map_err(|error| Failure {
            error,
            by_reader: false,
        })?;
        read_str(text, o).map_err(|error| Failure {
            error,
            by_reader: true,
        })
    };
    let ((mut tp, _warnings), dialect) = choosing.run(read, |d| read(d).is_ok())?;
    tp.tool = tool;
    stock::infer_levels(&mut tp);
    let decimals = settings.decimals.unwrap_or_else(|| program_decimals(text));
    let resolution = stock::gouge_resolution(decimals);
    let selected = super::pocket::parse_select(settings.select.as_deref(), loops.len())?;
    let pockets = loops.pockets();
    let specs: Vec<StockSpec<'_>> = selected
        .iter()
        .map(|&i| StockSpec {
            outer: &pockets[i - 1].outer,
            islands: &pockets[i - 1].islands,
            wall_stock: settings.wall_stock,
        })
        .collect();
    let sim = super::pocket::sim_options(settings.cell, tool.diameter);
    let part = stock::verify_part(
        &tp,
        &specs,
        nominal_engagement(s, tool.radius()).to_degrees(),
        &sim,
    );
    let problems = part.problems_within(resolution);
    let engagement_floor_deg = selected
        .iter()
        .filter_map(|&i| {
            let p = &pockets[i - 1];
            PocketShape::new(p.outer.clone(), p.islands.clone(), origin).ok()
        })
        .map(|sh| engagement_floor(&sh, &tool, settings.wall_stock).to_degrees())
        .fold(0.0, f64::max);
    let timing = match machine {
        Some((name, m)) => {
            let plan = crate::motion::plan_toolpath(&tp, &m)?;
            let times = super::pocket_report::air_times(
                &plan,
                &part.cutting_moves,
                &stock::entry_moves(&tp),
            );
            let t = plan.total_time;
            Some(VerifyTiming {
                machine: name.clone(),
                cycle_time_s: t,
                air_time_s: times.air,
                rapid_time_s: times.rapid,
                entry_time_s: times.entry,
                removal_rate_mm3_s: if t > 0.0 {
                    part.total.removed_mm3 / t
                } else {
                    0.0
                },
            })
        }
        None => None,
    };
    Ok(VerifyRun {
        engagement_floor_deg,
        timing,
        toolpath: tp,
        part,
        problems,
        decimals,
        gouge_resolution_mm: resolution,
        selected,
        dialect,
    })
}

impl VerifySettings {
    /// Checks the settings before anything is read: the tool, the wall stock, the cell and
    /// the stepover; returns the tool and the stepover in mm.
    pub fn check(&self) -> Result<(Tool, f64), Error> {
        let tool = Tool::flat(self.tool_diameter).map_err(|e| e.at("--tool-diameter"))?;
        if !(self.wall_stock.is_finite() && self.wall_stock >= 0.0) {
            return Err(InputError::new("wall stock", self.wall_stock)
                .at("--wall-stock")
                .expected("a stock >= 0 mm")
                .into());
        }
        super::pocket::check_cell(self.cell)?;
        let s = Stepover::parse(&self.stepover)?.distance(tool.diameter);
        Ok((tool, s))
    }
}

/// Lines at the top of a program where its header's tool lines are looked for.
const HEADER_LINES: usize = 40;

/// The tool diameters our programs' header names, in order: the lines `(tool T1: flat end
/// mill D12.7 mm, 3 flutes)` among the first lines (any case, as Fanuc's capitals write it;
/// any comment form), one per tool of the program.
pub fn header_diameters(text: &str) -> Vec<f64> {
    text.lines()
        .take(HEADER_LINES)
        .filter_map(|l| {
            let l = l.to_ascii_lowercase();
            let rest = l.split("flat end mill d").nth(1)?;
            rest.split(" mm").next()?.trim().parse().ok()
        })
        .filter(|d: &f64| d.is_finite() && *d > 0.0)
        .collect()
}

/// The first tool diameter our programs' header names ([`header_diameters`]).
pub fn header_diameter(text: &str) -> Option<f64> {
    header_diameters(text).first().copied()
}

/// The diameter a program `origin` (its text `text`) is judged with: `flag`
/// (`--tool-diameter`) when given, else the one tool its header names
/// ([`header_diameters`]). A refusal naming `--tool-diameter` when the header names no tool,
/// or tools of several diameters.
pub fn tool_diameter(flag: Option<f64>, text: &str, origin: &str) -> Result<f64, Error> {
    if let Some(d) = flag {
        return Ok(d);
    }
    let mut named = header_diameters(text);
    named.dedup_by(|a, b| (*a - *b).abs() <= 1e-9);
    match named.as_slice() {
        [d] => Ok(*d),
        [] => Err(InputError::new("tool diameter", "none")
            .at(format!("{origin}'s header"))
            .expected(
                "--tool-diameter D, the tool that cut the program: the header names no tool \
                 (millpath's programs name theirs in a comment \"tool T1: flat end mill D6 mm\")",
            )
            .into()),
        several => Err(InputError::new(
            "tool diameter",
            several
                .iter()
                .map(|d| format!("D{d}"))
                .collect::<Vec<_>>()
                .join(", "),
        )
        .at(format!("{origin}'s header"))
        .expected(
            "--tool-diameter D, the tool whose cuts to judge: the header names several \
             (a job's program is verified with --job)",
        )
        .into()),
    }
}

/// The most decimals written in the program's coordinate words (X, Y, Z, I, J, K, R), 3 when
/// none has any.
pub fn program_decimals(text: &str) -> u32 {
    let mut best = 0u32;
    for line in text.lines() {
        let code = line.split([';', '(']).next().unwrap_or("");
        let b = code.as_bytes();
        for (i, &c) in b.iter().enumerate() {
            if !matches!(
                c.to_ascii_uppercase(),
                b'X' | b'Y' | b'Z' | b'I' | b'J' | b'K' | b'R'
            ) {
                continue;
            }
            let rest = &b[i + 1..];
            let num: Vec<u8> = rest
                .iter()
                .copied()
                .take_while(|d| d.is_ascii_digit() || matches!(d, b'.' | b'-' | b'+' | b' '))
                .filter(|d| *d != b' ')
                .collect();
            if let Some(dot) = num.iter().position(|&d| d == b'.') {
                let digits = num[dot + 1..]
                    .iter()
                    .take_while(|d| d.is_ascii_digit())
                    .count();
                best = best.max(digits as u32);
            }
        }
    }
    if best == 0 { 3 } else { best }
}
