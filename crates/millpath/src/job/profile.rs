//! The profile job behind `millpath profile`: a drawing's closed outlines (or the paper's die
//! cavity) → each given its side (by nesting, or as asked) → checked profile options → the
//! profile planned (`strategy::profile`) → verified before anything is written → the program
//! text → its cycle time read back from that text → the report. Each refusal names the flag
//! it came from.
//!
//! # Verification before writing
//! - the finishing loops against the drawn outline by the dense independent check
//!   ([`dense_band_check`]): within `[d, d + T]` of the outline (before rounding: within
//!   `[d + 2ρ, d + T − ρ]`, so that the written program is in the band);
//! - every move below the stock top against every outside and inside outline by the exact
//!   clearance of [`crate::stock::min_clearance`]: at least the tool radius (no gouge), and
//!   every feed move's end out of the part's material (winding numbers);
//! - every tab: no move below its top comes within the tool radius of its middle line (the
//!   outline's stretch under the tab, moved to the path), sampled every 0.01 mm.
//!
//! A program that fails any of these is not written: the job returns an internal error.
//!
//! ```text
//! let (loops, _) = job::load_outline("part.dxf", &ImportSettings::default())?;
//! let run = job::profile::run(ProfileSource::Drawing { loops: &loops, name: "part.dxf" },
//!                             &ProfileSettings::default(), &ProgramSettings::default())?;
//! run.gcode  // the bytes `millpath profile part.dxf -o` writes
//! ```

use super::program::{ProgramSettings, program_time};
use crate::curve::{self, ArcSeg};
use crate::gcode::{self, rounding_error_mm};
use crate::geom::{Outline, Point};
use crate::io::ImportSettings;
use crate::io::outline_json::Loops;
use crate::machine::Machine;
use crate::strategy::pocket::Direction;
use crate::strategy::profile::{
    self, ProfileEntry, ProfileOptions, ProfileResult, ProfileSide, ProfileTarget, TabCount,
    TabOptions, TabShape, dense_band_check,
};
use crate::toolpath::{Tool, Toolpath};
use crate::{Error, InputError};
use serde::Serialize;

/// A profile job's settings, named and defaulted as `millpath profile`'s flags (`None`: the
/// sample's or the drawing default).
#[derive(Debug, Clone, PartialEq)]
pub struct ProfileSettings {
    /// How a DXF or SVG drawing is read.
    pub import: ImportSettings,
    /// `auto` (by nesting), `outside`, `inside` or `on`.
    pub side: String,
    /// Tool diameter, mm (6; the sample's 10).
    pub tool_diameter: Option<f64>,
    /// Depth of the cut, mm (6; the sample's 20).
    pub depth: Option<f64>,
    /// Stock thickness, mm (`None`: the depth: the profile cuts through).
    pub stock_thickness: Option<f64>,
    /// Step-down per level, mm (2; the sample's 2.5).
    pub step_down: Option<f64>,
    /// Radial stock left for the finishing pass, mm (0; the sample's 0.2).
    pub stock_to_leave: Option<f64>,
    /// Conventional milling instead of climb.
    pub conventional: bool,
    /// Lead arc radius, mm.
    pub lead_radius: f64,
    /// Entry: ramp or helix.
    pub entry: String,
    /// Helix radius, mm.
    pub helix_radius: f64,
    /// Ramp angle, degrees.
    pub ramp_angle: f64,
    /// Path tolerance, mm (0.01; the sample's 0.00004).
    pub tolerance: Option<f64>,
    /// Feed: mm/min (`1000`) or in/min (`40ipm`).
    pub feed: String,
    /// Plunge feed, mm/min.
    pub plunge_feed: f64,
    /// Safe height above the top, mm.
    pub safe_height: f64,
    /// Clearance height above the top, mm.
    pub clearance_height: f64,
    /// Tabs: a count, `auto`, or 0.
    pub tabs: String,
    /// Tab width, mm.
    pub tab_width: f64,
    /// Tab height, mm.
    pub tab_height: f64,
    /// Tab shape: square or ramped.
    pub tab_shape: String,
    /// Machine for the cycle time: a preset name or a TOML profile.
    pub machine: String,
}

impl Default for ProfileSettings {
    fn default() -> Self {
        ProfileSettings {
            import: ImportSettings::default(),
            side: "auto".into(),
            tool_diameter: None,
            depth: None,
            stock_thickness: None,
            step_down: None,
            stock_to_leave: None,
            conventional: false,
            lead_radius: 2.0,
            entry: "ramp".into(),
            helix_radius: 2.0,
            ramp_angle: 3.0,
            tolerance: None,
            feed: "1000".into(),
            plunge_feed: 300.0,
            safe_height: 10.0,
            clearance_height: 2.0,
            tabs: "0".into(),
            tab_width: 6.0,
            tab_height: 2.0,
            tab_shape: "square".into(),
            machine: "hsm".into(),
        }
    }
}

/// Where the outlines come from.
#[derive(Debug, Clone, Copy)]
pub enum ProfileSource<'a> {
    /// A drawing's outlines, nested, and the drawing's name.
    Drawing {
        /// The outlines.
        loops: &'a Loops,
        /// The name in messages and the program.
        name: &'a str,
    },
    /// The paper's die cavity (as `contour --sample`), its curve fitted by arcs.
    Sample,
}

/// One outline in the report.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TargetReport {
    /// 1-based index, in cutting order.
    pub index: usize,
    /// Side cut.
    pub side: String,
    /// Perimeter of the drawn outline, mm.
    pub perimeter_mm: f64,
    /// Nominal distance of the finished path from the outline, mm.
    pub offset_mm: f64,
    /// Loops cut.
    pub loops: usize,
    /// Arcs and lines of one finishing pass.
    pub arcs: usize,
    /// See `arcs`.
    pub lines: usize,
    /// The dense check: least and greatest distance of the finishing path from the outline.
    pub band_min_mm: f64,
    /// See `band_min_mm`.
    pub band_max_mm: f64,
    /// Samples of the dense check.
    pub band_samples: usize,
}

/// One tab in the report.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TabReport {
    /// The outline (1-based index).
    pub outline: usize,
    /// Centre by arc length from the outline's first vertex, mm.
    pub s_mm: f64,
    /// Centre on the outline.
    pub x: f64,
    /// See `x`.
    pub y: f64,
    /// Top width, mm.
    pub width_mm: f64,
    /// Z of its top and its foot.
    pub top_z: f64,
    /// See `top_z`.
    pub bottom_z: f64,
}

/// The `--report` of a profile.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ProfileReport {
    /// The drawing's name.
    pub input: String,
    /// Every outline cut.
    pub outlines: Vec<TargetReport>,
    /// Every tab.
    pub tabs: Vec<TabReport>,
    /// Path tolerance and the rounding of the written coordinates, mm.
    pub tolerance_mm: f64,
    /// See `tolerance_mm`.
    pub rounding_mm: f64,
    /// Decimals written.
    pub decimals: u32,
    /// Least clearance of the tool centre to an outline below the stock top, mm (exact).
    pub min_clearance_mm: f64,
    /// Tool radius: the clearance required, mm.
    pub required_clearance_mm: f64,
    /// Levels, moves and cut length.
    pub levels: usize,
    /// See `levels`.
    pub moves: usize,
    /// See `levels`.
    pub cut_length_mm: f64,
    /// Cycle time of the written program on the machine (as `millpath estimate` reads it), s.
    pub cycle_time_s: f64,
    /// The machine.
    pub machine: String,
    /// What was done differently from what was asked.
    pub notes: Vec<String>,
}

/// What a profile job made.
#[derive(Debug)]
pub struct ProfileRun {
    /// The program text, as written to the `-o` file.
    pub gcode: String,
    /// The report.
    pub report: ProfileReport,
    /// The strategy's result (toolpath, tabs, cuts, notes).
    pub result: ProfileResult,
    /// The outlines cut, in order.
    pub targets: Vec<ProfileTarget>,
    /// The options used.
    pub options: ProfileOptions,
    /// The machine the program is timed on.
    pub machine: Machine,
}

impl ProfileRun {
    /// The toolpath.
    pub fn toolpath(&self) -> &Toolpath {
        &self.result.toolpath
    }
}

fn input(what: &str, v: impl std::fmt::Display, flag: &str, expected: &str) -> Error {
    InputError::new(what, v).at(flag).expected(expected).into()
}

fn positive(what: &str, v: f64, flag: &str) -> Result<f64, Error> {
    if v.is_finite() && v > 0.0 && v <= crate::geom::MAX_COORDINATE_MM {
        Ok(v)
    } else {
        Err(input(what, v, flag, "a finite number > 0"))
    }
}

fn non_negative(what: &str, v: f64, flag: &str) -> Result<f64, Error> {
    if v.is_finite() && (0.0..=crate::geom::MAX_COORDINATE_MM).contains(&v) {
        Ok(v)
    } else {
        Err(input(what, v, flag, "a finite number >= 0"))
    }
}

/// The side named by `--side`: `None` for auto.
pub fn parse_side(s: &str) -> Result<Option<ProfileSide>, InputError> {
    match s {
        "auto" => Ok(None),
        "outside" => Ok(Some(ProfileSide::Outside)),
        "inside" => Ok(Some(ProfileSide::Inside)),
        "on" => Ok(Some(ProfileSide::On)),
        _ => Err(InputError::new("side", s)
            .at("--side")
            .expected("auto, outside, inside or on")),
    }
}

/// The tab count named by `--tabs`: a whole number (0: none) or `auto`.
pub fn parse_tabs(s: &str) -> Result<TabCount, InputError> {
    let bad = || {
        InputError::new("tabs", s).at("--tabs").expected(format!(
            "a whole number of tabs per outline from 0 to {} or auto",
            profile::MAX_TABS
        ))
    };
    match s.trim() {
        "auto" => Ok(TabCount::Auto),
        "0" | "none" => Ok(TabCount::None),
        t => match t.parse::<usize>() {
            Ok(n) if n <= profile::MAX_TABS => Ok(TabCount::Count(n)),
            _ => Err(bad()),
        },
    }
}

impl ProfileSettings {
    /// The tool, the checked options (`rounding` still to be set from the decimals) and the
    /// side asked (`None`: auto), with the sample's defaults where `sample`.
    pub fn options(
        &self,
        sample: bool,
    ) -> Result<(Tool, ProfileOptions, Option<ProfileSide>), Error> {
        let pick = |v: Option<f64>, drawing: f64, paper: f64| {
            v.unwrap_or(if sample { paper } else { drawing })
        };
        let d = positive(
            "tool diameter",
            pick(self.tool_diameter, 6.0, 10.0),
            "--tool-diameter",
        )?;
        let tool = Tool::flat(d).map_err(|e| e.at("--tool-diameter"))?;
        let depth = positive("depth", pick(self.depth, 6.0, 20.0), "--depth")?;
        let step = positive("step-down", pick(self.step_down, 2.0, 2.5), "--step-down")?;
        if depth / step > profile::MAX_LEVELS {
            return Err(input(
                "step-down",
                step,
                "--step-down",
                &format!(
                    "at least depth / {} = {} mm",
                    profile::MAX_LEVELS,
                    depth / profile::MAX_LEVELS
                ),
            ));
        }
        let thickness = self
            .stock_thickness
            .map(|t| positive("stock thickness", t, "--stock-thickness"))
            .transpose()?;
        let stock = non_negative(
            "stock to leave",
            pick(self.stock_to_leave, 0.0, 0.2),
            "--stock-to-leave",
        )?;
        let tolerance = positive("tolerance", pick(self.tolerance, 0.01, 4e-5), "--tolerance")?;
        let lead = non_negative("lead radius", self.lead_radius, "--lead-radius")?;
        let entry = match self.entry.as_str() {
            "ramp" => ProfileEntry::Ramp,
            "helix" => ProfileEntry::Helix,
            e => return Err(input("entry", e, "--entry", "ramp or helix")),
        };
        let helix = positive("helix radius", self.helix_radius, "--helix-radius")?;
        if !(self.ramp_angle.is_finite() && self.ramp_angle > 0.0 && self.ramp_angle < 90.0) {
            return Err(input(
                "ramp angle",
                self.ramp_angle,
                "--ramp-angle",
                "an angle in degrees, > 0 and < 90",
            ));
        }
        let feed = super::pocket::parse_feed(&self.feed)?;
        let plunge = positive("plunge feed", self.plunge_feed, "--plunge-feed")? / 60.0;
        let clear = non_negative(
            "clearance height",
            self.clearance_height,
            "--clearance-height",
        )?;
        if !(self.safe_height.is_finite()
            && self.safe_height >= clear
            && self.safe_height <= crate::geom::MAX_COORDINATE_MM)
        {
            return Err(input(
                "safe height",
                self.safe_height,
                "--safe-height",
                &format!("a finite number >= the clearance height {clear}"),
            ));
        }
        let count = parse_tabs(&self.tabs)?;
        let width = positive("tab width", self.tab_width, "--tab-width")?;
        let height = positive("tab height", self.tab_height, "--tab-height")?;
        let shape = match self.tab_shape.as_str() {
            "square" => TabShape::Square,
            "ramped" => TabShape::Ramped,
            s => return Err(input("tab shape", s, "--tab-shape", "square or ramped")),
        };
        if count != TabCount::None && height >= thickness.unwrap_or(depth) {
            return Err(input(
                "tab height",
                height,
                "--tab-height",
                &format!(
                    "less than the stock's thickness {} mm",
                    thickness.unwrap_or(depth)
                ),
            ));
        }
        let side = if sample && self.side == "auto" {
            Some(ProfileSide::Inside)
        } else {
            parse_side(&self.side)?
        };
        let opts = ProfileOptions::default()
            .with_depth(depth)
            .with_stock_thickness(thickness)
            .with_step_down(step)
            .with_stock_to_leave(stock)
            .with_direction(if self.conventional {
                Direction::Conventional
            } else {
                Direction::Climb
            })
            .with_lead_radius(lead)
            .with_entry(entry)
            .with_helix_radius(helix)
            .with_ramp_angle(self.ramp_angle.to_radians())
            .with_tolerance(tolerance)
            .with_feed(feed)
            .with_plunge_feed(plunge)
            .with_safe_height(self.safe_height)
            .with_clearance_height(clear)
            .with_tabs(
                TabOptions::default()
                    .with_count(count)
                    .with_width(width)
                    .with_height(height)
                    .with_shape(shape),
            );
        Ok((tool, opts, side))
    }
}

/// The paper's die cavity (the curve of `contour --sample`) as an outline of arcs: biarcs
/// fitted within `tol` mm on each smooth stretch between its corners.
pub fn die_cavity_outline(tol: f64) -> Result<Outline, Error> {
    let c = curve::paper_outline()?;
    let n = c.len();
    let mut cuts: Vec<usize> = c.corners().to_vec();
    if cuts.is_empty() {
        cuts.push(0);
    }
    cuts.sort_unstable();
    let mut arcs: Vec<ArcSeg> = Vec::new();
    for (i, &a) in cuts.iter().enumerate() {
        let b = if i + 1 < cuts.len() {
            cuts[i + 1]
        } else {
            cuts[0] + n
        };
        arcs.extend(curve::fit_biarcs(&c, a as f64, b as f64, tol));
    }
    let v: Vec<(Point, f64)> = arcs
        .iter()
        .map(|a| (a.start, (a.sweep() / 4.0).tan()))
        .collect();
    Ok(Outline::new(&v, "paper die cavity")?)
}

/// The fit tolerance of the die cavity's arcs for a path tolerance `t`: a tenth of it.
pub const SAMPLE_FIT_SHARE: f64 = 0.1;

/// Runs the profile on `source` with `settings`, written as `program` says.
pub fn run(
    source: ProfileSource<'_>,
    settings: &ProfileSettings,
    program: &ProgramSettings,
) -> Result<ProfileRun, Error> {
    let sample = matches!(source, ProfileSource::Sample);
    let (tool, mut opts, side) = settings.options(sample)?;
    let machine = super::load_machine(&settings.machine)?;
    let decimals = program.decimals_within(0.25 * opts.tolerance, "a quarter of --tolerance")?;
    opts.rounding = rounding_error_mm(decimals, program.units);
    let (targets, name) = match source {
        ProfileSource::Drawing { loops, name } => {
            let mut t = profile::sides_from_nesting(&loops.pockets());
            if let Some(s) = side {
                for x in &mut t {
                    x.side = s;
                }
            }
            (t, name.to_owned())
        }
        ProfileSource::Sample => {
            let o = die_cavity_outline(SAMPLE_FIT_SHARE * opts.tolerance)?;
            (
                vec![ProfileTarget {
                    outline: o,
                    side: side.unwrap_or(ProfileSide::Inside),
                }],
                "paper sample".to_owned(),
            )
        }
    };
    let result = profile::generate(&targets, &tool, &opts)?;
    let (outlines, min_clearance) = verify(&targets, &result, &tool, &opts)?;
    let machine = super::contour::program_machine(&machine, opts.tolerance);
    let mut wopt = program.writer_options(decimals, format!("millpath profile {name}"))?;
    wopt.path_tolerance = Some(machine.path_tolerance);
    let (text, _) = gcode::write_to_string(&result.toolpath, &wopt)
        .map_err(|e| e.engine_made("writing the profile program"))?;
    let t = program_time(
        text.as_bytes(),
        wopt.dialect,
        "the written profile program",
        &machine,
    )
    .map_err(|e| e.engine_made("timing the written profile program"))?;
    let report = ProfileReport {
        input: name,
        outlines,
        tabs: result
            .tabs
            .iter()
            .map(|t| TabReport {
                outline: t.target + 1,
                s_mm: t.s,
                x: t.at.x,
                y: t.at.y,
                width_mm: t.width,
                top_z: t.top_z,
                bottom_z: t.bottom_z,
            })
            .collect(),
        tolerance_mm: opts.tolerance,
        rounding_mm: opts.rounding,
        decimals,
        min_clearance_mm: min_clearance,
        required_clearance_mm: tool.radius(),
        levels: result.toolpath.levels.len(),
        moves: result.toolpath.moves.len(),
        cut_length_mm: result.toolpath.cut_length(),
        cycle_time_s: t,
        machine: machine.name.clone(),
        notes: result.notes.iter().map(ToString::to_string).collect(),
    };
    Ok(ProfileRun {
        gcode: text,
        report,
        result,
        targets,
        options: opts,
        machine,
    })
}

/// Spacing of the dense check's samples, mm: an eighth of the tolerance, no finer than the
/// outline's length over 200,000.
fn band_step(t: f64, perimeter: f64) -> f64 {
    (t / 8.0).max(perimeter / 200_000.0)
}

/// The checks of the module docs; the report's rows and the least clearance.
fn verify(
    targets: &[ProfileTarget],
    res: &ProfileResult,
    tool: &Tool,
    opts: &ProfileOptions,
) -> Result<(Vec<TargetReport>, f64), Error> {
    let r = tool.radius();
    let rho = opts.rounding;
    let tp = &res.toolpath;
    let mut rows = Vec::new();
    for cut in &res.cuts {
        let t = &targets[cut.target];
        let step = band_step(opts.tolerance, t.outline.length());
        let (mut lo, mut hi, mut samples) = (f64::INFINITY, 0.0_f64, 0);
        for range in &cut.finish_moves {
            let b = dense_band_check(&t.outline, tp, range.clone(), step);
            lo = lo.min(b.min_mm);
            hi = hi.max(b.max_mm);
            samples += b.samples;
        }
        let d = cut.offset_mm;
        let (want_lo, want_hi) = if t.side == ProfileSide::On {
            (0.0, opts.tolerance - 2.0 * rho)
        } else {
            (d + 2.0 * rho, d + opts.tolerance - rho)
        };
        // The sampling bound (module docs of the check): half a step either way.
        let slack = 0.5 * step + 1e-9;
        let ok_lo = t.side == ProfileSide::On || lo + slack >= want_lo;
        if !(ok_lo && hi - slack <= want_hi) {
            return Err(Error::internal(format!(
                "the profile of outline {} leaves the band [{want_lo:.6}, {want_hi:.6}] mm of its outline: the dense check finds {lo:.6} to {hi:.6} mm; not written",
                cut.target + 1
            )));
        }
        rows.push(TargetReport {
            index: cut.target + 1,
            side: t.side.to_string(),
            perimeter_mm: t.outline.length(),
            offset_mm: d,
            loops: cut.loops,
            arcs: cut.arcs,
            lines: cut.lines,
            band_min_mm: lo,
            band_max_mm: hi,
            band_samples: samples,
        });
    }
    // The walls: every outside and inside outline, exactly, for every move below the top.
    let walls: Vec<(usize, &ProfileTarget)> = targets
        .iter()
        .enumerate()
        .filter(|(_, t)| t.side != ProfileSide::On)
        .collect();
    let mut min_clearance = f64::INFINITY;
    if !walls.is_empty() {
        let shifted = shift_to_zero_top(tp, opts.top_z);
        // A finishing loop that passes within the tool radius of another outline: the two
        // outlines are closer than the tool can pass between (the drawing's, not a bug).
        for cut in &res.cuts {
            for range in &cut.finish_moves {
                let part = Toolpath {
                    start: if range.start > 0 {
                        shifted.moves[range.start - 1].to
                    } else {
                        shifted.start
                    },
                    moves: shifted.moves[range.clone()].to_vec(),
                    levels: Vec::new(),
                    ..shifted.clone()
                };
                for (j, w) in walls.iter().filter(|(j, _)| *j != cut.target) {
                    let spec = crate::stock::StockSpec {
                        outer: &w.outline,
                        islands: &[],
                        wall_stock: 0.0,
                    };
                    let c = crate::stock::min_clearance(&part, spec);
                    if c.distance < r {
                        return Err(InputError::new("tool diameter", 2.0 * r)
                            .at("--tool-diameter")
                            .expected(format!(
                                "a tool that passes between outlines {} and {}: cutting outline {} {} brings the tool centre {:.4} mm from outline {} at ({:.3}, {:.3})",
                                cut.target + 1, j + 1, cut.target + 1, cut.side, c.distance, j + 1, c.at.x, c.at.y
                            ))
                            .into());
                    }
                }
            }
        }
        for (_, w) in &walls {
            let spec = crate::stock::StockSpec {
                outer: &w.outline,
                islands: &[],
                wall_stock: 0.0,
            };
            let c = crate::stock::min_clearance(&shifted, spec);
            min_clearance = min_clearance.min(c.distance);
            if c.distance < r - 1e-9 {
                return Err(Error::internal(format!(
                    "the profile would gouge: the tool centre comes {:.6} mm from an outline at ({:.4}, {:.4}, {:.4}) (move {}), less than the tool radius {r} mm; not written",
                    c.distance, c.at.x, c.at.y, c.at.z, c.move_index
                )));
            }
        }
        let material = |p: Point| {
            let outside = walls
                .iter()
                .filter(|(_, w)| w.side == ProfileSide::Outside && w.outline.contains(p))
                .count();
            let inside = walls
                .iter()
                .filter(|(_, w)| w.side == ProfileSide::Inside && w.outline.contains(p))
                .count();
            outside > inside
        };
        for (k, m) in tp.moves.iter().enumerate() {
            if m.is_feed() && m.to.z < opts.top_z - 1e-9 && material(m.to.xy()) {
                return Err(Error::internal(format!(
                    "the profile would cut into the part at ({:.4}, {:.4}, {:.4}) (move {k}); not written",
                    m.to.x, m.to.y, m.to.z
                )));
            }
        }
    }
    check_tabs(targets, res, r)?;
    Ok((rows, min_clearance))
}

/// The toolpath with Z moved so that the stock top is at 0 (the clearance check measures
/// moves below Z = 0).
fn shift_to_zero_top(tp: &Toolpath, top: f64) -> Toolpath {
    if top == 0.0 {
        return tp.clone();
    }
    let mut t = tp.clone();
    t.start.z -= top;
    for m in &mut t.moves {
        m.to.z -= top;
        if let crate::toolpath::MoveKind::Arc { ref mut center, .. } = m.kind {
            center.z -= top;
        }
    }
    t
}

/// No move below a tab's top comes within the tool radius of the tab's middle line.
fn check_tabs(targets: &[ProfileTarget], res: &ProfileResult, r: f64) -> Result<(), Error> {
    let tp = &res.toolpath;
    for tab in &res.tabs {
        let o = &targets[tab.target].outline;
        let d = res
            .cuts
            .iter()
            .find(|c| c.target == tab.target)
            .map_or(r, |c| c.offset_used_mm);
        let line = tab_line(o, tab.s, tab.width, d, targets[tab.target].side);
        for (k, (from, m)) in tp.segments().enumerate() {
            if !m.is_feed() || (from.z >= tab.top_z - 1e-9 && m.to.z >= tab.top_z - 1e-9) {
                continue;
            }
            let len = m.length_from(from);
            let n = (len / 0.01).ceil().max(1.0) as usize;
            for j in 0..=n {
                let q = m.point_at(from, len * j as f64 / n as f64);
                if q.z >= tab.top_z - 1e-9 {
                    continue;
                }
                let near = line
                    .iter()
                    .map(|p| p.distance(q.xy()))
                    .fold(f64::INFINITY, f64::min);
                if near < r - 1e-6 {
                    return Err(Error::internal(format!(
                        "the profile would cut the tab at ({:.4}, {:.4}) of outline {} (move {k} at z {:.4}); not written",
                        tab.at.x,
                        tab.at.y,
                        tab.target + 1,
                        q.z
                    )));
                }
            }
        }
    }
    Ok(())
}

/// The tab's middle line: the outline's stretch under it, every 0.01 mm, moved `d` to the free
/// side (the outline's own geometry: points and normals by arc length).
fn tab_line(o: &Outline, s: f64, w: f64, d: f64, side: ProfileSide) -> Vec<Point> {
    let n = (w / 0.01).ceil().max(2.0) as usize;
    let ccw = o.signed_area() > 0.0;
    let free_left = match side {
        ProfileSide::Inside => ccw,
        _ => !ccw,
    };
    let h = 1e-4;
    (0..=n)
        .map(|j| {
            let sj = s - 0.5 * w + w * j as f64 / n as f64;
            let p = point_at_length(o, sj);
            let t = (point_at_length(o, sj + h) - point_at_length(o, sj - h))
                .normalize()
                .unwrap_or(crate::geom::Vec2::new(1.0, 0.0));
            p + if free_left { t.perp() } else { -t.perp() } * d
        })
        .collect()
}

/// The point of the outline at arc length `s` from its first vertex (the outline's own
/// sampling, [`Outline::sample`] style, by walking its segments).
fn point_at_length(o: &Outline, s: f64) -> Point {
    let v: Vec<(Point, f64)> = o.vertices().collect();
    let n = v.len();
    let total = o.length();
    let mut s = s.rem_euclid(total);
    for i in 0..n {
        let (a, b) = v[i];
        let e = v[(i + 1) % n].0;
        let chord = e.distance(a);
        let sweep = 4.0 * b.atan();
        let len = if b.abs() < 1e-12 {
            chord
        } else {
            chord * 0.5 * sweep.abs() / (0.5 * sweep).sin().abs()
        };
        if s <= len || i + 1 == n {
            let f = if len > 0.0 {
                (s / len).clamp(0.0, 1.0)
            } else {
                0.0
            };
            if b.abs() < 1e-12 {
                return a.lerp(e, f);
            }
            // Rotate the start about the centre by the swept fraction.
            let u = (e - a)
                .normalize()
                .unwrap_or(crate::geom::Vec2::new(1.0, 0.0));
            let centre = a.lerp(e, 0.5) + u.perp() * (chord * (1.0 - b * b) / (4.0 * b));
            return centre + (a - centre).rotate(sweep * f);
        }
        s -= len;
    }
    v[0].0
}
