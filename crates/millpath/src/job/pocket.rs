//! The pocket job behind `millpath pocket`: settings as the command's flags give them →
//! checked pocketing options → every selected pocket planned, verified and joined
//! (`strategy::pocket::part`) → the program text → its cycle time read back from that text →
//! the report. Each refusal names the flag it came from (`--tool-diameter`, `--feed`, …), so
//! a caller binding the same names (the Python package) shows the same message.
//!
//! ```text
//! let (loops, _) = job::load_outline("sample:aerospace", &ImportSettings::default())?;
//! let run = job::pocket::run(&loops, "sample:aerospace", &PocketSettings::default(),
//!                            &ProgramSettings::default(), None, &mut |_| {})?;
//! run.gcode        // the bytes `millpath pocket … -o` writes
//! run.report       // the JSON of `--report`
//! ```

use super::pocket_report::{Report, air_times, auto_line, report};
use super::program::{ProgramSettings, program_times};
use crate::gcode::{WriterOptions, write_program};
use crate::io::ImportSettings;
use crate::io::outline_json::Loops;
use crate::machine::Machine;
use crate::stock::SimOptions;
use crate::strategy::pocket::part::{PartResult, PartStrategy, generate_part};
use crate::strategy::pocket::{
    self, Direction, Entry, PocketOptions, PocketShape, SpiralMorph, Stepover, StrategyKind, Walls,
};
use crate::toolpath::Tool;
use crate::{Error, InputError};

/// The paper's transition C when none is given (its Table 1 and Figure 10 go from 0.2 to
/// 0.7; 0.5 is their middle).
pub const DEFAULT_TRANSITION: f64 = 0.5;

/// A pocket job's settings, named and defaulted as `millpath pocket`'s flags.
#[derive(Debug, Clone, PartialEq)]
pub struct PocketSettings {
    /// How a DXF or SVG drawing is read (also the bottom outline).
    pub import: ImportSettings,
    /// Strategy: spiral, offset, zigzag, or auto.
    pub strategy: String,
    /// Tool diameter, mm.
    pub tool_diameter: f64,
    /// Flute length, mm; `None`: 3 × the diameter. No level is deeper.
    pub flute_length: Option<f64>,
    /// Stepover: a fraction of the diameter (`0.4`) or a distance (`5mm`).
    pub stepover: String,
    /// Pocket depth, mm.
    pub depth: f64,
    /// Step-down per level, mm.
    pub step_down: f64,
    /// Wall stock, mm.
    pub wall_stock: f64,
    /// Floor stock, mm.
    pub floor_stock: f64,
    /// Conventional milling instead of climb.
    pub conventional: bool,
    /// Entry: helix or ramp.
    pub entry: String,
    /// Helix radius, mm; `None`: 0.45 × the tool diameter (the largest helix that leaves no
    /// pillar at its centre, less a tenth), and the spiral's up to 0.75 × where its path
    /// takes the pillar ([`crate::strategy::pocket::SpiralOptions::wide_helix`]). The pocket
    /// shrinks it where it does not fit.
    pub helix_radius: Option<f64>,
    /// Ramp angle, degrees.
    pub ramp_angle: f64,
    /// Safe height above the level's top, mm.
    pub safe_height: f64,
    /// Clearance height above the stock, mm.
    pub clearance_height: f64,
    /// Feed: mm/min (`1500`) or in/min (`600ipm`).
    pub feed: String,
    /// Fraction of the feed at full slotting.
    pub slowdown: f64,
    /// Zigzag angle, degrees, from the pocket's principal axis.
    pub angle: f64,
    /// Spiral transition ratio C in [0, 1] (selects the `fronts` morph unless `morph` is given).
    pub transition: Option<f64>,
    /// Smallest curvature radius wanted on the spiral's interior loops, mm.
    pub min_radius: f64,
    /// Spiral morph: offsets, fronts or harmonic.
    pub morph: Option<String>,
    /// Spiral laps as G2/G3 biarcs instead of G1 chords.
    pub arcs: bool,
    /// Adaptive passes may run either way
    /// ([`crate::strategy::pocket::AdaptiveOptions::both_ways`]).
    pub both_ways: bool,
    /// How far adaptive links through cleared material rise over the floor, mm
    /// ([`crate::strategy::pocket::AdaptiveOptions::lift`]).
    pub lift: f64,
    /// Finishing pass along the walls.
    pub finish: bool,
    /// Keep the programmed feed (no engagement-based modulation).
    pub no_feed_modulation: bool,
    /// Machine for the cycle time: a preset name or a TOML machine profile.
    pub machine: String,
    /// Raster cell of the stock simulation, mm (`None`: 0.05 mm up to a 12.7 mm tool, 1/254
    /// of the diameter above, [`crate::stock::DEFAULT_CELL`]).
    pub cell: Option<f64>,
    /// Draft angle of the walls, degrees.
    pub draft: Option<f64>,
    /// Outline of the pocket's bottom (same vertex count and islands as the top).
    pub bottom_outline: Option<String>,
    /// The program's path tolerance, mm (`--tolerance`): the largest deviation the
    /// controller may blend corners by (`G64 P`), `0` for exact stop; `None`: the machine's
    /// where above 0, else [`DEFAULT_PATH_TOLERANCE`] ([`PocketSettings::program_machine`]).
    pub tolerance: Option<f64>,
}

/// The path tolerance of a pocket program for a machine whose own is 0 (exact stop at every
/// corner, which the LinuxCNC model reads as `G64` without `P`), mm: the `hsm` preset's.
pub const DEFAULT_PATH_TOLERANCE: f64 = 0.01;

/// The default helix radius as a fraction of the tool's diameter: 0.45, so the helix (of
/// diameter 0.9·D) clears a disc of 1.9·D with no pillar left at its centre. A larger helix
/// runs faster (the feed a controller holds on a circle of radius ρ grows as √(a·ρ)).
pub const DEFAULT_HELIX_RADIUS_PER_DIAMETER: f64 = 0.45;

/// Where the entries take more than this share of a pocket program's planned time, the
/// report says so in a note (what shortens them).
pub const ENTRY_NOTE_SHARE: f64 = 0.5;

/// The stepover a strategy takes when none is given: `0.1` for `adaptive` (the engagement
/// of a cut a tenth of the diameter wide, at the whole flute length), else `0.4`.
pub fn default_stepover(strategy: &str) -> &'static str {
    if strategy == "adaptive" { "0.1" } else { "0.4" }
}

/// The step-down a strategy takes when none is given, mm: for `adaptive` the flute length
/// (one level per flute length), `3·D` where it is not given; else half the diameter (6.35 mm
/// for the default 12.7 mm tool), at most the flute length.
pub fn default_step_down(strategy: &str, tool_diameter: f64, flute_length: Option<f64>) -> f64 {
    let flutes = flute_length.unwrap_or(3.0 * tool_diameter);
    if strategy == "adaptive" {
        flutes
    } else {
        (0.5 * tool_diameter).min(flutes)
    }
}

impl PocketSettings {
    /// Sets the stepover and the step-down to the strategy's defaults ([`default_stepover`],
    /// [`default_step_down`]) for the strategy, tool and flute length already set: the
    /// front ends call it before they read the user's stepover and step-down, so that a
    /// given value wins.
    pub fn apply_strategy_defaults(&mut self) {
        self.stepover = default_stepover(&self.strategy).to_owned();
        self.step_down = default_step_down(&self.strategy, self.tool_diameter, self.flute_length);
    }
}

impl Default for PocketSettings {
    fn default() -> Self {
        PocketSettings {
            import: ImportSettings::default(),
            strategy: "spiral".into(),
            tool_diameter: 12.7,
            flute_length: None,
            stepover: "0.4".into(),
            depth: 25.0,
            step_down: 6.35,
            wall_stock: 0.0,
            floor_stock: 0.0,
            conventional: false,
            entry: "helix".into(),
            helix_radius: None,
            ramp_angle: 3.0,
            safe_height: 1.0,
            clearance_height: 5.0,
            feed: "600ipm".into(),
            slowdown: 0.75,
            angle: 0.0,
            transition: None,
            min_radius: 1.0,
            morph: None,
            arcs: false,
            both_ways: false,
            lift: 0.0,
            finish: false,
            no_feed_modulation: false,
            machine: "hsm".into(),
            cell: None,
            draft: None,
            bottom_outline: None,
            tolerance: None,
        }
    }
}

/// Parses a feed: `600ipm` / `600in/min` in inches per minute, else mm/min; returns mm/s.
pub fn parse_feed(text: &str) -> Result<f64, InputError> {
    let t = text.trim();
    let (num, scale) = if let Some(n) = t.strip_suffix("ipm").or_else(|| t.strip_suffix("in/min")) {
        (n, 25.4 / 60.0)
    } else if let Some(n) = t.strip_suffix("mm/min") {
        (n, 1.0 / 60.0)
    } else {
        (t, 1.0 / 60.0)
    };
    num.trim()
        .parse::<f64>()
        .ok()
        .filter(|v| v.is_finite() && *v > 0.0)
        .map(|v| v * scale)
        .ok_or_else(|| {
            InputError::new("feed", text)
                .at("--feed")
                .expected("a feed > 0 in mm/min (1500) or in/min (600ipm)")
        })
}

/// What the strategy setting asks for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Choice {
    /// One strategy.
    One(StrategyKind),
    /// All three, the fastest verified one written (`pocket::auto`).
    Auto,
}

/// The strategy setting: a strategy or `auto`.
pub fn parse_choice(s: &str) -> Result<Choice, InputError> {
    match s {
        "spiral" => Ok(Choice::One(StrategyKind::Spiral)),
        "offset" => Ok(Choice::One(StrategyKind::Offset)),
        "zigzag" => Ok(Choice::One(StrategyKind::Zigzag)),
        "adaptive" => Ok(Choice::One(StrategyKind::Adaptive)),
        "auto" => Ok(Choice::Auto),
        _ => Err(InputError::new("strategy", s)
            .at("--strategy")
            .expected("spiral, offset, zigzag, adaptive or auto")),
    }
}

impl PocketSettings {
    /// The tool and the pocketing options.
    pub fn options(&self) -> Result<(Tool, PocketOptions), Error> {
        let mut tool = Tool::flat(self.tool_diameter).map_err(|e| e.at("--tool-diameter"))?;
        if let Some(f) = self.flute_length {
            if !(f.is_finite() && f > 0.0 && f <= 1e6) {
                return Err(InputError::new("flute length", f)
                    .at("--flute-length")
                    .expected("a flute length > 0 mm")
                    .into());
            }
            tool.flute_length = f;
        }
        let ramp = self.ramp_angle.to_radians();
        let entry = match self.entry.as_str() {
            "helix" => Entry::Helix {
                radius: self
                    .helix_radius
                    .unwrap_or(DEFAULT_HELIX_RADIUS_PER_DIAMETER * self.tool_diameter),
                ramp_angle: ramp,
            },
            "ramp" => Entry::Ramp { ramp_angle: ramp },
            e => {
                return Err(InputError::new("entry", e)
                    .at("--entry")
                    .expected("helix or ramp")
                    .into());
            }
        };
        let feed = parse_feed(&self.feed)?;
        let mut opts = PocketOptions::default()
            .with_stepover(Stepover::parse(&self.stepover)?)
            .with_depth(self.depth)
            .with_step_down(self.step_down)
            .with_wall_stock(self.wall_stock)
            .with_floor_stock(self.floor_stock)
            .with_direction(if self.conventional {
                Direction::Conventional
            } else {
                Direction::Climb
            })
            .with_entry(entry)
            .with_safe_height(self.safe_height)
            .with_clearance_height(self.clearance_height)
            .with_feed(feed)
            .with_plunge_feed(feed / 3.0)
            .with_slowdown(self.slowdown)
            .with_zigzag_angle(self.angle.to_radians())
            .with_transition(self.transition.unwrap_or(DEFAULT_TRANSITION))
            .with_min_radius(self.min_radius)
            .with_morph(self.morph()?)
            .with_arcs(self.arcs)
            .with_both_ways(self.both_ways)
            .with_lift(self.lift)
            .with_auto_step_down(self.flute_length.filter(|_| self.strategy == "auto"))
            .with_curvature_ramps(true)
            .with_finish(self.finish)
            .with_modulate_feed(!self.no_feed_modulation);
        // A helix radius the user gives is the helix they get (where it fits).
        if self.helix_radius.is_some() {
            opts.spiral.wide_helix = 0.0;
        }
        opts.validate(&tool)?;
        check_cell(self.cell)?;
        Ok((tool, opts))
    }

    /// The spiral's morph: `morph`, else `fronts` when a transition is given (the paper's
    /// central spiral is the fronts' and harmonic morphs'), else `offsets`.
    fn morph(&self) -> Result<SpiralMorph, Error> {
        match (self.morph.as_deref(), self.transition) {
            (None | Some("offsets"), None) => Ok(SpiralMorph::Offsets),
            (None | Some("fronts"), _) => Ok(SpiralMorph::Fronts),
            (Some("harmonic"), _) => Ok(SpiralMorph::Harmonic),
            (Some("offsets"), Some(c)) => Err(InputError::new("transition", c)
                .at("--transition with --morph offsets")
                .expected(
                    "no --transition with the offsets morph (its spiral has no central circle); \
                     --morph fronts or harmonic for the paper's transition C",
                )
                .into()),
            (Some(other), _) => Err(InputError::new("morph", other)
                .at("--morph")
                .expected("offsets, fronts or harmonic")
                .into()),
        }
    }

    /// The pocket with the walls asked for (`draft`, `bottom_outline`); the bottom outline's
    /// drawing note goes to `note`.
    pub fn with_walls(
        &self,
        shape: PocketShape,
        note: &mut dyn FnMut(String),
    ) -> Result<PocketShape, Error> {
        if let Some(deg) = self.draft {
            return Ok(shape.with_walls(Walls::Draft(deg.to_radians()), "--draft")?);
        }
        if let Some(path) = &self.bottom_outline {
            let (b, n) = super::load_outline(path, &self.import)?;
            if let Some(n) = n {
                note(n);
            }
            return Ok(shape.with_walls(
                Walls::Bottom {
                    outer: b.outer,
                    islands: b.islands,
                },
                &format!("--bottom-outline {path}"),
            )?);
        }
        Ok(shape)
    }

    /// Simulation options: [`SimOptions::default`] (scaled with the tool) unless a cell is
    /// given ([`sim_options`]).
    pub fn sim(&self) -> SimOptions {
        sim_options(self.cell, self.tool_diameter)
    }

    /// The checks made before the outline is read (an error at once, before a drawing is
    /// parsed): the strategy, the machine and the output settings.
    pub fn check_before_loading(&self, program: &ProgramSettings) -> Result<(), Error> {
        parse_choice(&self.strategy)?;
        let machine = self.program_machine(&super::load_machine(&self.machine)?)?;
        program_options("spiral", &machine, program)?;
        Ok(())
    }

    /// `machine` with the program's path tolerance: [`PocketSettings::tolerance`] where
    /// given (a length ≥ 0, `--tolerance`), else the machine's where above 0, else
    /// [`DEFAULT_PATH_TOLERANCE`]. The program states it (`G64 P t`; exact stop for 0) and
    /// its cycle time is planned with it.
    pub fn program_machine(&self, machine: &Machine) -> Result<Machine, InputError> {
        let t = match self.tolerance {
            Some(t) if !(t.is_finite() && t >= 0.0) => {
                return Err(InputError::new("path tolerance", t)
                    .at("--tolerance")
                    .expected("a path tolerance ≥ 0 mm (0: exact stop at every corner)"));
            }
            Some(t) => t,
            None if machine.path_tolerance > 0.0 => machine.path_tolerance,
            None => DEFAULT_PATH_TOLERANCE,
        };
        Ok(Machine {
            path_tolerance: t,
            ..machine.clone()
        })
    }
}

/// The stock simulation of a job with `cell` (`None`: the defaults, which scale with the
/// tool, [`SimOptions`]) and a tool of `diameter` mm: a cell given is used as given, with the
/// tool positions two cells apart (no closer than the default spacing for the tool).
pub fn sim_options(cell: Option<f64>, diameter: f64) -> SimOptions {
    match cell {
        None => SimOptions::default(),
        Some(c) => SimOptions::default().with_cell(c).with_step(
            (2.0 * c).max(crate::stock::DEFAULT_STEP * crate::toolpath::tolerance_scale(diameter)),
        ),
    }
}

/// Refuses a cell given that is not a length > 0 (`--cell`).
pub fn check_cell(cell: Option<f64>) -> Result<(), InputError> {
    match cell {
        Some(c) if !(c.is_finite() && c > 0.0) => Err(InputError::new("cell", c)
            .at("--cell")
            .expected("a cell > 0 mm")),
        _ => Ok(()),
    }
}

/// How the pocket program is written: the dialect, units, tool, spindle and coolant of
/// `out`, stating the machine's path tolerance (`G64 P t`, `CYCLE832(t,_FINISH,1)`, Fanuc's
/// `G05.1 Q1` with t in a comment, a comment on Grbl), the tolerance its cycle time was
/// planned with and the one `millpath estimate` reads back; `name` is the strategy's (or
/// `mixed`). The decimals keep the rounding within the pocket's own resolution (arcs flatter
/// than [`pocket::segments::ARC_AS_LINE_SAGITTA`], 0.0007 mm, are lines in the toolpath: 3
/// decimals in mm, 5 in inches) and within 10 % of the path tolerance; fewer decimals are
/// refused.
pub fn program_options(
    name: &str,
    machine: &Machine,
    out: &ProgramSettings,
) -> Result<WriterOptions, Error> {
    let t = machine.path_tolerance;
    let mut max_rounding = pocket::segments::ARC_AS_LINE_SAGITTA;
    let mut why = "the pocket's resolution".to_owned();
    if t > 0.0 && crate::gcode::format::ROUNDING_SHARE * t < max_rounding {
        max_rounding = crate::gcode::format::ROUNDING_SHARE * t;
        why = format!("10 % of the machine's path tolerance {t} mm");
    }
    let decimals = out.decimals_within(max_rounding, &why)?;
    Ok(out
        .writer_options(decimals, format!("millpath pocket {name}"))?
        .with_path_tolerance(t))
}

/// The indices a selection asks for (1-based, sorted, each once) among `n` pockets; all
/// when not given.
pub fn parse_select(text: Option<&str>, n: usize) -> Result<Vec<usize>, InputError> {
    let Some(text) = text else {
        return Ok((1..=n).collect());
    };
    let bad = || {
        InputError::new("pocket selection", text)
            .at("--select")
            .expected(format!(
                "pocket indices from 1 to {n} (as pocket --list shows them), separated by commas, \
                 or ranges: 1,3 or 2-4"
            ))
    };
    let mut out = Vec::new();
    for item in text.split(',') {
        let item = item.trim();
        let (a, b) = match item.split_once('-') {
            Some((a, b)) => (a.trim(), b.trim()),
            None => (item, item),
        };
        let (Ok(a), Ok(b)) = (a.parse::<usize>(), b.parse::<usize>()) else {
            return Err(bad());
        };
        if a == 0 || b < a || b > n {
            return Err(bad());
        }
        out.extend(a..=b);
    }
    out.sort_unstable();
    out.dedup();
    Ok(out)
}

/// One line per pocket of the drawing (index, area, islands, bounds), as `--list` prints
/// them.
pub fn list_lines(loops: &Loops) -> Vec<String> {
    loops
        .pockets()
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let b = p.outer.bounds();
            format!(
                "pocket {}: area {:.3} mm², {} islands, bounds ({:.3}, {:.3}) to ({:.3}, {:.3})",
                i + 1,
                p.area(),
                p.islands.len(),
                b.min.x,
                b.min.y,
                b.max.x,
                b.max.y
            )
        })
        .collect()
}

/// What a pocket job made.
#[derive(Debug)]
pub struct PocketRun {
    /// The program text, as written to the `-o` file.
    pub gcode: Vec<u8>,
    /// The report (`--report`), with the cycle time of the written program.
    pub report: Report,
    /// The planned part: its toolpath, each pocket's result and the verification.
    pub part: PartResult,
    /// The pockets cut: their index in the drawing and their shape.
    pub shapes: Vec<(usize, PocketShape)>,
    /// The strategy's name, or `mixed`.
    pub name: String,
    /// The machine the cycle time is for.
    pub machine: Machine,
}

impl PocketRun {
    /// The part's toolpath planned on [`PocketRun::machine`] (for playback and the feed plot).
    pub fn plan(&self) -> Result<crate::motion::Plan, Error> {
        crate::motion::plan_toolpath(&self.part.toolpath, &self.machine)
            .map_err(|e| e.engine_made("timing the pocket toolpath"))
    }

    /// The `--html` report of the run on `outline` (the drawing's name): summary (machine,
    /// strategy, cycle time, path, engagement, the removal rate and the time not cutting, the
    /// verifier's figures, its problems, `auto`'s table), the viewer with playback on the
    /// machine, the feed plot.
    pub fn html(&self, outline: &str) -> Result<crate::report::html::HtmlReport, Error> {
        let (rep, name, m) = (&self.report, &self.name, &self.machine);
        let plan = self.plan()?;
        let mut summary = vec![
            crate::report::html::machine_row(m),
            ("strategy".to_owned(), name.clone()),
            (
                "cycle time".to_owned(),
                format!("{:.2} s", rep.cycle_time_s),
            ),
            (
                "path length".to_owned(),
                format!("{:.1} mm", rep.path_length_mm),
            ),
            (
                "levels, moves".to_owned(),
                format!("{}, {}", rep.levels, rep.moves),
            ),
            (
                "engagement".to_owned(),
                format!(
                    "max {:.1}°, mean {:.1}°, nominal {:.1}°, {:.1}% of the path above nominal",
                    rep.max_engagement_deg,
                    rep.mean_engagement_deg,
                    rep.nominal_engagement_deg,
                    100.0 * rep.share_above_nominal
                ),
            ),
            (
                "outside the entries".to_owned(),
                format!(
                    "engagement mean {:.1}°, p95 {:.1}°, max {:.1}°; the sharpest corner forces {:.1}°",
                    rep.verification.engagement.mean_deg,
                    rep.verification.engagement.p95_deg,
                    rep.verification.engagement.max_deg,
                    rep.engagement_floor_deg
                ),
            ),
            (
                "removal".to_owned(),
                format!(
                    "{:.0} mm³ at {:.0} mm³/s; entries {:.2} s; not cutting {:.2} s (rapids \
                     {:.2} s)",
                    rep.verification.removed_mm3,
                    rep.removal_rate_mm3_s,
                    rep.entry_time_s,
                    rep.air_time_s,
                    rep.rapid_time_s
                ),
            ),
            (
                "verifier".to_owned(),
                format!(
                    "min clearance {:.6} mm (needs {:.6}), uncut {:.3} mm², rapids through material {}",
                    rep.verification.min_clearance_mm,
                    rep.verification.required_clearance_mm,
                    rep.verification.uncut_area_mm2,
                    rep.verification.rapids_through_material
                ),
            ),
        ];
        summary.extend(
            rep.problems
                .iter()
                .map(|p| ("problem".to_owned(), p.clone())),
        );
        summary.extend(
            rep.auto
                .iter()
                .flatten()
                .map(|e| ("--strategy auto".to_owned(), auto_line(e))),
        );
        crate::report::html::toolpath_report(
            &format!("millpath pocket {outline} {name}"),
            summary,
            &self.part.toolpath,
            &self.outlines(),
            &plan,
        )
    }

    /// Every outline of the pockets cut: each outer outline followed by its islands.
    pub fn outlines(&self) -> Vec<crate::geom::Outline> {
        self.shapes
            .iter()
            .flat_map(|(_, s)| std::iter::once(s.outer.clone()).chain(s.islands.iter().cloned()))
            .collect()
    }
}

/// Plans the pockets of `loops` (named `outline` in messages) selected by `select` (`1,3`,
/// `2-4`; all when `None`), writes the program and reports it; a drawing note of the bottom
/// outline goes to `note`.
pub fn run(
    loops: &Loops,
    outline: &str,
    settings: &PocketSettings,
    program: &ProgramSettings,
    select: Option<&str>,
    note: &mut dyn FnMut(String),
) -> Result<PocketRun, Error> {
    let choice = parse_choice(&settings.strategy)?;
    let machine = settings.program_machine(&super::load_machine(&settings.machine)?)?;
    program_options("spiral", &machine, program)?;
    let (tool, opts) = settings.options()?;
    let selected = parse_select(select, loops.len())?;
    if selected.len() > 1 && (settings.draft.is_some() || settings.bottom_outline.is_some()) {
        return Err(InputError::new("pockets", selected.len())
            .at(format!("{outline} with --draft or --bottom-outline"))
            .expected("one pocket with inclined walls: --select one of them")
            .into());
    }
    let all = loops.pockets();
    let mut shapes = Vec::with_capacity(selected.len());
    for &i in &selected {
        let p = &all[i - 1];
        let origin = if all.len() > 1 {
            format!("{outline}, pocket {i}")
        } else {
            outline.to_owned()
        };
        let shape = PocketShape::new(p.outer.clone(), p.islands.clone(), &origin)?;
        shapes.push((i, settings.with_walls(shape, note)?));
    }
    // Each toolpath timed as its program runs: from the origin, where the G-code reader
    // (and a controller after homing at the work zero) starts, to its first move; the
    // toolpath's own start is not written.
    let time = |tp: &crate::toolpath::Toolpath| {
        let mut from_origin = tp.clone();
        from_origin.start = crate::geom::Point3::ORIGIN;
        crate::motion::cycle_time(&from_origin, &machine)
    };
    let strategy = match choice {
        Choice::One(kind) => PartStrategy::One(kind),
        Choice::Auto => PartStrategy::Auto,
    };
    let part = generate_part(&shapes, strategy, &tool, &opts, &settings.sim(), &time)?;
    let name = match part.pockets.iter().find(|p| p.result.is_some()) {
        Some(f)
            if part
                .pockets
                .iter()
                .filter(|p| p.result.is_some())
                .all(|p| p.kind == f.kind) =>
        {
            f.kind.name().to_owned()
        }
        _ => "mixed".to_owned(),
    };
    let wopts = program_options(&name, &machine, program)?;
    let mut gcode = Vec::new();
    write_program(&part.toolpath, &wopts, &mut gcode)
        .map_err(|e| e.engine_made("writing the pocket program"))?;
    let (t, programmed) = program_times(
        &gcode,
        wopts.dialect,
        "the written pocket program",
        &machine,
    )
    .map_err(|e| e.engine_made("timing the written pocket program"))?;
    let mut rep = report(&part, t, programmed);
    let plan = crate::motion::plan_toolpath(&part.toolpath, &machine)
        .map_err(|e| e.engine_made("timing the pocket toolpath"))?;
    let entries = crate::stock::entry_moves(&part.toolpath);
    let times = air_times(&plan, &part.verification.cutting_moves, &entries);
    (rep.air_time_s, rep.rapid_time_s, rep.entry_time_s) = (times.air, times.rapid, times.entry);
    if times.entry > ENTRY_NOTE_SHARE * plan.total_time {
        let descents = entries
            .iter()
            .zip(std::iter::once(&false).chain(&entries))
            .filter(|(now, before)| **now && !**before)
            .count();
        rep.notes.push(format!(
            "the entries take {:.0} s of the {:.0} s planned ({descents} descents at {:.1}° \
             to the levels, each with the room its region leaves): a smaller tool reaches \
             more of the pocket from one entry, and pre-drilled holes or a steeper \
             --ramp-angle shorten each",
            times.entry, plan.total_time, settings.ramp_angle
        ));
    }
    let floor_stock = if opts.finish { 0.0 } else { opts.wall_stock };
    rep.engagement_floor_deg = shapes
        .iter()
        .map(|(_, s)| pocket::engagement_floor(s, &tool, floor_stock).to_degrees())
        .fold(0.0, f64::max);
    if part.pockets.len() == 1 {
        rep.auto = rep.pockets.first_mut().and_then(|p| p.auto.take());
    }
    Ok(PocketRun {
        gcode,
        report: rep,
        part,
        shapes,
        name,
        machine,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::{Outline, Point};
    use crate::motion::verify::{VerifyOptions, verify_plan};

    fn square(x0: f64, y0: f64, side: f64, name: &str) -> Outline {
        let pts = [(0.0, 0.0), (side, 0.0), (side, side), (0.0, side)]
            .map(|(x, y)| Point::new(x0 + x, y0 + y));
        Outline::from_points(&pts, name).unwrap()
    }

    /// A 60 mm square pocket round a 12 mm island: the part's plan passes the limit
    /// verifier and takes the time the written program is read back with (within the
    /// rounding of its coordinates); the outlines are the pocket's and its island's.
    #[test]
    fn plan_and_outlines_of_a_pocket_with_an_island() {
        let loops = Loops::single(
            square(0.0, 0.0, 60.0, "outer"),
            vec![square(24.0, 24.0, 12.0, "island")],
        );
        let settings = PocketSettings {
            strategy: "offset".into(),
            tool_diameter: 6.0,
            depth: 3.0,
            step_down: 3.0,
            ..PocketSettings::default()
        };
        let run = run(
            &loops,
            "square",
            &settings,
            &ProgramSettings::default(),
            None,
            &mut |_| {},
        )
        .unwrap();
        assert!(run.report.problems.is_empty(), "{:?}", run.report.problems);
        let plan = run.plan().unwrap();
        let moves: Vec<_> = run.part.toolpath.segments().map(|(f, m)| (f, *m)).collect();
        let v = verify_plan(&plan, &moves, &run.machine, &VerifyOptions::default()).unwrap();
        assert_eq!(v.violations, 0);
        let (t, r) = (plan.total_time(), run.report.cycle_time_s);
        assert!((t - r).abs() < 0.01 * r, "{t} vs {r}");
        let outlines = run.outlines();
        assert_eq!(outlines.len(), 2);
        let areas: Vec<f64> = outlines.iter().map(|o| o.signed_area().abs()).collect();
        assert!((areas[0] - 3600.0).abs() < 1e-9 && (areas[1] - 144.0).abs() < 1e-9);
    }
}
