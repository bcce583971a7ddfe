//! Profile strategy: a drawing's closed outlines cut out, outside (a part), inside (a hole or
//! a window) or on the line, level by level, with lead arcs, ramp or helix entries and
//! holding tabs.
//!
//! # Pipeline
//! Outline of lines and arcs ([`Outline`]) → its exact offset (`cavalier_contours`, arcs stay
//! arcs) at the cutter radius plus the stock to leave → the loop in the cutting direction,
//! started in the middle of its longest stretch clear of tabs → levels at each step-down
//! (entry by a helix beside the loop where it fits, else by a ramp along the loop) → a
//! finishing pass at full depth when stock is left. The moves of a pass with its tangent lead
//! arcs are the contour strategy's ([`super::contour::layer_depths`], its lead arcs), so both
//! strategies lay out levels and leads alike.
//!
//! # Tolerance budget
//! The offset of lines and arcs is exact, so the only departures from it are the G-code's:
//! rounding of the written coordinates moves a point by at most `ρ` and an arc whose sagitta
//! is at most `ρ` is written as its chord (up to `ρ` nearer the wall). The loop is offset
//! `T/2` beyond the nominal distance `d` (tool radius plus stock), so the written path lies
//! within `[d + T/2 − 2ρ, d + T/2 + ρ]` of the outline: inside the band `[d, d + T]` (never
//! nearer the wall) when `T ≥ 4ρ`, which [`ProfileOptions::validate`] demands. On the line
//! (`d = 0`) the path is the outline itself, within `2ρ ≤ T` of it either way.
//!
//! # Sides and direction
//! Outlines are cut counter-clockwise or clockwise so that the wall is on the right of travel
//! when climb milling with a clockwise spindle: an outside profile runs clockwise, a hole
//! counter-clockwise; conventional milling reverses both; on the line the outline runs
//! counter-clockwise for climb. [`sides_from_nesting`] gives each outline its side from the
//! drawing's nesting: a pocket boundary (even depth) is a part cut outside, its islands are
//! holes cut inside; holes are listed before their part, so a part is freed last.
//!
//! ```text
//!   outside profile (climb: clockwise)      hole (climb: counter-clockwise)
//!      ┌──────────◄─────────┐                  ┌─────────┐
//!      │  ┌──────────────┐  │                  │ ┌──►──┐ │
//!      ▼  │     part     │  ▲                  │ │slug │ │
//!      │  └──────────────┘  │                  │ └─────┘ │
//!      └──────────►─────────┘                  └─────────┘
//! ```
//!
//! # Tabs
//! See [`TabOptions`] and the `tabs` module: tabs are placed on the drawn outline by arc
//! length, evenly, on lines and long arcs only, where no other outline's slot nor entry
//! reaches the material the tab leaves across its slot (the `bridges` module), and every
//! level below a tab's top lifts over it. They are placed only where the profile cuts through the stock (outside and inside
//! profiles whose depth reaches the stock's thickness); elsewhere a [`ProfileNote`] says why
//! there are none.

mod bridges;
mod check;
mod elements;
mod passes;
mod placing;
mod tabs;
mod zpath;

pub use check::{BandCheck, dense_band_check, outline_distance};
pub use tabs::{BEND_MAX, MAX_TABS, PERIMETER_PER_TAB, TAB_RAMP_RUN, auto_tab_count, tab_places};

use super::pocket::Direction;
use crate::error::{Error, InputError, require_positive};
use crate::geom::{Outline, Pocket, Point};
use crate::toolpath::{Tool, Toolpath};

/// Which side of an outline the tool cuts on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ProfileSide {
    /// Outside the outline: a part cut free of its sheet.
    Outside,
    /// Inside the outline: a hole or a window.
    Inside,
    /// Tool centre on the outline (engraving, a cut of the tool's width).
    On,
}

impl std::fmt::Display for ProfileSide {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            ProfileSide::Outside => "outside",
            ProfileSide::Inside => "inside",
            ProfileSide::On => "on",
        })
    }
}

/// One outline to cut and its side.
#[derive(Debug, Clone)]
pub struct ProfileTarget {
    /// The drawn outline (either winding).
    pub outline: Outline,
    /// The side the tool cuts on.
    pub side: ProfileSide,
}

/// The targets of a drawing's nested outlines: each pocket boundary cut outside, after its
/// islands cut inside (holes first, so a part is freed last).
pub fn sides_from_nesting(pockets: &[Pocket]) -> Vec<ProfileTarget> {
    let mut out = Vec::new();
    for p in pockets {
        for h in &p.islands {
            out.push(ProfileTarget {
                outline: h.clone(),
                side: ProfileSide::Inside,
            });
        }
        out.push(ProfileTarget {
            outline: p.outer.clone(),
            side: ProfileSide::Outside,
        });
    }
    out
}

/// How the tool goes down to each level.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ProfileEntry {
    /// A ramp along the loop itself, ending where the level's loop starts.
    #[default]
    Ramp,
    /// A helix beside the loop on its free side, then the lead-in arc; a ramp where the helix
    /// does not fit.
    Helix,
}

/// How many tabs to place on an outline.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum TabCount {
    /// No tabs.
    #[default]
    None,
    /// This many, evenly spaced (fewer where the outline has no room, with a note).
    Count(usize),
    /// From the perimeter ([`auto_tab_count`]).
    Auto,
}

/// The shape of a tab along the path.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum TabShape {
    /// The tool goes straight up before the tab and straight down after it.
    #[default]
    Square,
    /// The tool ramps up and down at 26.6° (1 in 2) outside the tab's top width: a ramp, not a plunge.
    Ramped,
}

/// Holding tabs.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct TabOptions {
    /// How many.
    pub count: TabCount,
    /// Width of a tab's top along the outline, mm.
    pub width: f64,
    /// Height of a tab above the stock's bottom, mm.
    pub height: f64,
    /// Square or ramped.
    pub shape: TabShape,
}

impl Default for TabOptions {
    fn default() -> Self {
        TabOptions {
            count: TabCount::None,
            width: 6.0,
            height: 2.0,
            shape: TabShape::Square,
        }
    }
}

option_builders! {
    TabOptions;
    /// Sets [`TabOptions::count`].
    with_count => count: TabCount;
    /// Sets [`TabOptions::width`], mm.
    with_width => width: f64;
    /// Sets [`TabOptions::height`], mm.
    with_height => height: f64;
    /// Sets [`TabOptions::shape`].
    with_shape => shape: TabShape;
}

/// Options of [`generate`], built from [`Default`] with the `with_*` methods.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct ProfileOptions {
    /// Top of the stock (Z, mm).
    pub top_z: f64,
    /// Depth of the cut below `top_z`, mm.
    pub depth: f64,
    /// Thickness of the stock, mm (`None`: the depth, i.e. the profile cuts through). Tabs are
    /// placed only when the depth reaches it.
    pub stock_thickness: Option<f64>,
    /// Step-down per level, mm.
    pub step_down: f64,
    /// Radial stock the levels leave for the finishing pass, mm (0: no finishing pass).
    pub stock_to_leave: f64,
    /// Climb or conventional milling.
    pub direction: Direction,
    /// Lead-in and lead-out arc radius, mm (0: none).
    pub lead_radius: f64,
    /// Entry at each level.
    pub entry: ProfileEntry,
    /// Ramp and helix descent angle, radians.
    pub ramp_angle: f64,
    /// Helix radius (tool centre), mm.
    pub helix_radius: f64,
    /// Path tolerance `T`, mm: the written path lies within `[d, d + T]` of the outline (module
    /// docs).
    pub tolerance: f64,
    /// Output rounding `ρ` of the written coordinates, mm (from the G-code decimals).
    pub rounding: f64,
    /// Cutting feed, mm/s.
    pub feed: f64,
    /// Plunge feed, mm/s.
    pub plunge_feed: f64,
    /// Safe height above `top_z` for rapids between outlines, mm.
    pub safe_height: f64,
    /// Clearance height above `top_z` where feeding down starts, mm.
    pub clearance_height: f64,
    /// Holding tabs.
    pub tabs: TabOptions,
}

impl Default for ProfileOptions {
    fn default() -> Self {
        ProfileOptions {
            top_z: 0.0,
            depth: 6.0,
            stock_thickness: None,
            step_down: 2.0,
            stock_to_leave: 0.0,
            direction: Direction::Climb,
            lead_radius: 2.0,
            entry: ProfileEntry::Ramp,
            ramp_angle: 3f64.to_radians(),
            helix_radius: 2.0,
            tolerance: 0.01,
            rounding: 0.5e-3 * std::f64::consts::SQRT_2,
            feed: 1000.0 / 60.0,
            plunge_feed: 300.0 / 60.0,
            safe_height: 10.0,
            clearance_height: 2.0,
            tabs: TabOptions::default(),
        }
    }
}

option_builders! {
    ProfileOptions;
    /// Sets [`ProfileOptions::top_z`], mm.
    with_top_z => top_z: f64;
    /// Sets [`ProfileOptions::depth`], mm.
    with_depth => depth: f64;
    /// Sets [`ProfileOptions::stock_thickness`], mm.
    with_stock_thickness => stock_thickness: Option<f64>;
    /// Sets [`ProfileOptions::step_down`], mm.
    with_step_down => step_down: f64;
    /// Sets [`ProfileOptions::stock_to_leave`], mm.
    with_stock_to_leave => stock_to_leave: f64;
    /// Sets [`ProfileOptions::direction`].
    with_direction => direction: Direction;
    /// Sets [`ProfileOptions::lead_radius`], mm.
    with_lead_radius => lead_radius: f64;
    /// Sets [`ProfileOptions::entry`].
    with_entry => entry: ProfileEntry;
    /// Sets [`ProfileOptions::ramp_angle`], radians.
    with_ramp_angle => ramp_angle: f64;
    /// Sets [`ProfileOptions::helix_radius`], mm.
    with_helix_radius => helix_radius: f64;
    /// Sets [`ProfileOptions::tolerance`], mm.
    with_tolerance => tolerance: f64;
    /// Sets [`ProfileOptions::rounding`], mm.
    with_rounding => rounding: f64;
    /// Sets [`ProfileOptions::feed`], mm/s.
    with_feed => feed: f64;
    /// Sets [`ProfileOptions::plunge_feed`], mm/s.
    with_plunge_feed => plunge_feed: f64;
    /// Sets [`ProfileOptions::safe_height`], mm.
    with_safe_height => safe_height: f64;
    /// Sets [`ProfileOptions::clearance_height`], mm.
    with_clearance_height => clearance_height: f64;
    /// Sets [`ProfileOptions::tabs`].
    with_tabs => tabs: TabOptions;
}

/// The most levels a profile may have (`depth / step-down`).
pub const MAX_LEVELS: f64 = 10_000.0;

fn bad(what: &str, v: impl std::fmt::Display, expected: impl Into<String>) -> InputError {
    InputError::new(what, v)
        .at("profile options")
        .expected(expected.into())
}

impl ProfileOptions {
    /// Checks every value (the job layer checks them first with the flags' names).
    pub fn validate(&self, tool: &Tool) -> Result<(), InputError> {
        tool.validate("tool")?;
        let at = "profile options";
        for (what, v) in [
            ("depth", self.depth),
            ("step-down", self.step_down),
            ("tolerance", self.tolerance),
            ("feed", self.feed),
            ("plunge feed", self.plunge_feed),
            ("ramp angle", self.ramp_angle),
            ("helix radius", self.helix_radius),
            ("tab width", self.tabs.width),
            ("tab height", self.tabs.height),
        ] {
            require_positive(what, v, at)?;
        }
        let max = crate::geom::MAX_COORDINATE_MM;
        for (what, v) in [
            ("stock to leave", self.stock_to_leave),
            ("lead radius", self.lead_radius),
            ("rounding", self.rounding),
            ("clearance height", self.clearance_height),
        ] {
            if !(v.is_finite() && (0.0..=max).contains(&v)) {
                return Err(bad(what, v, format!("a finite number from 0 to {max}")));
            }
        }
        crate::error::require_finite("top Z", self.top_z, at)?;
        for (what, v) in [
            ("depth", self.depth),
            ("top Z", self.top_z),
            ("helix radius", self.helix_radius),
            ("tab width", self.tabs.width),
        ] {
            if v.abs() > max {
                return Err(bad(what, v, format!("a length within ±{max} mm")));
            }
        }
        if self.depth / self.step_down > MAX_LEVELS {
            return Err(bad(
                "step-down",
                self.step_down,
                format!("at most {MAX_LEVELS} levels: a step-down >= depth / {MAX_LEVELS}"),
            ));
        }
        if self.ramp_angle >= std::f64::consts::FRAC_PI_2 {
            return Err(bad(
                "ramp angle",
                self.ramp_angle,
                "an angle below 90° (π/2 rad)",
            ));
        }
        if let Some(t) = self.stock_thickness {
            if !(t.is_finite() && t > 0.0 && t <= max) {
                return Err(bad("stock thickness", t, "a finite number > 0 mm"));
            }
        }
        if !(self.safe_height.is_finite() && self.safe_height >= self.clearance_height) {
            return Err(bad(
                "safe height",
                self.safe_height,
                format!("at least the clearance height {}", self.clearance_height),
            ));
        }
        if self.tolerance < 4.0 * self.rounding {
            return Err(bad(
                "tolerance",
                self.tolerance,
                format!(
                    "at least 4 × the output rounding {:.3e} mm (raise the G-code decimals)",
                    self.rounding
                ),
            ));
        }
        if let TabCount::Count(n) = self.tabs.count {
            if n > MAX_TABS {
                return Err(bad(
                    "tab count",
                    n,
                    format!("at most {} tabs per outline", MAX_TABS),
                ));
            }
        }
        Ok(())
    }

    /// Z of the stock's bottom.
    pub fn bottom_z(&self) -> f64 {
        self.top_z - self.stock_thickness.unwrap_or(self.depth)
    }

    /// True when the cut reaches the stock's bottom (to a nanometre).
    pub fn cuts_through(&self) -> bool {
        self.top_z - self.depth <= self.bottom_z() + 1e-9
    }
}

/// A tab placed on an outline.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlacedTab {
    /// The target it holds (index into the targets given to [`generate`]).
    pub target: usize,
    /// Its centre by arc length along the target's outline, from the outline's first vertex
    /// in the outline's own direction, mm.
    pub s: f64,
    /// Its centre on the outline.
    pub at: Point,
    /// The width of its top along the outline, mm.
    pub width: f64,
    /// Z of its top.
    pub top_z: f64,
    /// Z of its foot (the stock's bottom).
    pub bottom_z: f64,
}

/// What the profile could not do as asked, or did differently.
#[derive(Debug, Clone, PartialEq)]
pub enum ProfileNote {
    /// The tool does not fit: nothing cut for this target.
    NoRoom {
        /// The target.
        target: usize,
        /// The offset distance (tool radius plus stock), mm.
        offset_mm: f64,
    },
    /// The offset left parts of the outline the tool cannot reach (necks, bays, corners
    /// tighter than the tool).
    SplitLoops {
        /// The target.
        target: usize,
        /// The separate loops cut.
        loops: usize,
    },
    /// Fewer tabs than asked fit on the outline's straight stretches and long arcs.
    FewerTabs {
        /// The target.
        target: usize,
        /// Tabs asked for.
        asked: usize,
        /// Tabs placed.
        placed: usize,
    },
    /// No tabs: the profile does not cut through, or is on the line.
    NoTabs {
        /// The target.
        target: usize,
        /// Why.
        reason: &'static str,
    },
    /// The helix entry did not fit beside the loop (or would take more than 1000 turns a
    /// level): ramp entry instead.
    HelixToRamp {
        /// The target.
        target: usize,
    },
    /// The loop is too short for the ramp angle: the ramp descends over the whole loop,
    /// more steeply.
    SteepRamp {
        /// The target.
        target: usize,
        /// The ramp's angle, degrees.
        angle_deg: f64,
    },
    /// The lead arcs did not fit beside the loop: their radius was reduced.
    LeadReduced {
        /// The target.
        target: usize,
        /// The radius used, mm.
        radius: f64,
    },
}

impl std::fmt::Display for ProfileNote {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ProfileNote::NoRoom { target, offset_mm } => write!(
                f,
                "outline {}: the tool (offset {offset_mm:.4} mm) does not fit; not cut",
                target + 1
            ),
            ProfileNote::SplitLoops { target, loops } => write!(
                f,
                "outline {}: the offset splits into {loops} loops (necks narrower than the tool); each is cut",
                target + 1
            ),
            ProfileNote::FewerTabs {
                target,
                asked,
                placed,
            } => write!(
                f,
                "outline {}: {placed} of {asked} tabs fit on its straight stretches and long arcs",
                target + 1
            ),
            ProfileNote::NoTabs { target, reason } => {
                write!(f, "outline {}: no tabs: {reason}", target + 1)
            }
            ProfileNote::HelixToRamp { target } => write!(
                f,
                "outline {}: no room for the helix beside the loop (or over 1000 turns a level); ramp entry along the loop",
                target + 1
            ),
            ProfileNote::SteepRamp { target, angle_deg } => write!(
                f,
                "outline {}: loop too short for the ramp angle; ramp at {angle_deg:.2}° over the whole loop",
                target + 1
            ),
            ProfileNote::LeadReduced { target, radius } => write!(
                f,
                "outline {}: lead arcs reduced to radius {radius:.3} mm to stay clear of the wall",
                target + 1
            ),
        }
    }
}

/// One target's cut, for reports and checks.
#[derive(Debug, Clone)]
pub struct TargetCut {
    /// The target's index.
    pub target: usize,
    /// The side cut.
    pub side: ProfileSide,
    /// The nominal distance of the final path from the outline (tool radius; 0 on the line), mm.
    pub offset_mm: f64,
    /// The distance the finishing loops were offset by (nominal + `T/2`), mm.
    pub offset_used_mm: f64,
    /// Loops cut.
    pub loops: usize,
    /// Arcs (G2/G3) and lines in one finishing pass round the loops.
    pub arcs: usize,
    /// See `arcs`.
    pub lines: usize,
    /// Index range of the target's moves in the toolpath.
    pub moves: std::ops::Range<usize>,
    /// Index range of the finishing pass's loop moves (leads excluded) in the toolpath, one
    /// per loop: the path the tolerance band applies to.
    pub finish_moves: Vec<std::ops::Range<usize>>,
}

/// What [`generate`] produced.
#[derive(Debug, Clone)]
pub struct ProfileResult {
    /// The toolpath: every target, its levels and finishing pass.
    pub toolpath: Toolpath,
    /// The tabs placed.
    pub tabs: Vec<PlacedTab>,
    /// One entry per target.
    pub cuts: Vec<TargetCut>,
    /// What was done differently from what was asked.
    pub notes: Vec<ProfileNote>,
}

/// Per target, how many tabs [`generate`] places with these options and how many were asked
/// for: the placement rule of `generate` (spacing, corners, other targets' slots, the
/// outline's own cut across narrow channels) before any entry is made, whose disc may still
/// take a tab away. Cheap beside `generate`: no path is made.
pub fn tab_counts(
    targets: &[ProfileTarget],
    tool: &Tool,
    opts: &ProfileOptions,
) -> Vec<(usize, usize)> {
    passes::tab_counts(targets, tool, opts)
}

/// Cuts `targets` with `tool` as `opts` says (see the module docs).
pub fn generate(
    targets: &[ProfileTarget],
    tool: &Tool,
    opts: &ProfileOptions,
) -> Result<ProfileResult, Error> {
    opts.validate(tool)?;
    passes::generate(targets, tool, opts)
}
