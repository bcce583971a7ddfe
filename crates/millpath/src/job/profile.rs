//! The profile job behind `millpath profile`: a drawing's closed outlines (or the paper's die
//! cavity) → each given its side (by nesting, or as asked) → checked profile options → the
//! profile planned (`strategy::profile`) → verified before anything is written → the program
//! text → its cycle time read back from that text → the report. Each refusal names the flag
//! it came from.
//!
//! # Verification before writing
//! - the finishing loops against the drawn outline by the dense independent check
//!   ([`crate::strategy::profile::dense_band_check`]): within `[d, d + T]` of the outline (before rounding: within
//!   `[d + 2ρ, d + T − ρ]`, so that the written program is in the band);
//! - every move below the stock top against every outside and inside outline by the exact
//!   clearance of [`crate::stock::min_clearance`]: at least the tool radius (no gouge), and
//!   every feed move's end out of the part's material (winding numbers);
//! - every tab: no move below its top comes within the tool radius of its middle line (the
//!   outline's stretch under the tab, moved to the path: lines and concentric arcs), each
//!   move's part below the tab's top measured whole and exactly against it, at any scale;
//! - with tabs asked for, the bridge verdict: the whole program cut into a height-field stock
//!   ([`crate::stock::HeightField`]) and the material left in each outline's slot read as
//!   bridges ([`crate::stock::held_by`]): each tab matched by exactly one bridge holding the
//!   piece to the stock and no other bridge, so the piece is held by exactly its tabs and
//!   falls free without them.
//!
//! A program that fails any of these is not written: the job returns an internal error.
//!
//! ```text
//! let (loops, _) = job::load_outline("part.dxf", &ImportSettings::default())?;
//! let run = job::profile::run(ProfileSource::Drawing { loops: &loops, name: "part.dxf" },
//!                             &ProfileSettings::default(), &ProgramSettings::default())?;
//! run.gcode  // the bytes `millpath profile part.dxf -o` writes
//! ```

pub use super::profile_check::{TabVerdict, TargetReport};
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
    TabOptions, TabShape,
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
    let (outlines, min_clearance) = super::profile_check::verify(&targets, &result, &tool, &opts)?;
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
