//! Pocketing options, with defaults and validation.
//!
//! Every length is in millimetres, feeds in mm/s, angles in radians. [`PocketOptions::validate`]
//! checks every field against the tool and names the offending value.

use crate::error::InputError;
use crate::toolpath::Tool;

/// Largest length accepted in the options, mm (as for outlines' coordinates).
const MAX_LENGTH_MM: f64 = 1e6;
/// Most levels a pocket may have.
const MAX_LEVELS: f64 = 10_000.0;

/// The radial depth of cut between neighbouring passes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Stepover {
    /// A fraction of the tool diameter, in (0, 1].
    Fraction(f64),
    /// A distance in mm, in (0, diameter].
    Distance(f64),
}

impl Stepover {
    /// Parses `0.4` (fraction of the diameter) or `5mm` (a distance).
    pub fn parse(text: &str) -> Result<Self, InputError> {
        let t = text.trim();
        let bad = || {
            InputError::new("stepover", text)
                .at("--stepover")
                .expected("a fraction of the tool diameter such as 0.4, or a distance such as 5mm")
        };
        if let Some(mm) = t.strip_suffix("mm") {
            mm.trim()
                .parse::<f64>()
                .map(Stepover::Distance)
                .map_err(|_| bad())
        } else {
            t.parse::<f64>().map(Stepover::Fraction).map_err(|_| bad())
        }
    }

    /// The stepover in mm for a tool of `diameter` mm.
    pub fn distance(self, diameter: f64) -> f64 {
        match self {
            Stepover::Fraction(f) => f * diameter,
            Stepover::Distance(d) => d,
        }
    }
}

/// Which way the tool runs relative to the material.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Direction {
    /// Climb milling (material on the right of travel with a clockwise spindle): pockets
    /// cleared from the inside out run counter-clockwise.
    #[default]
    Climb,
    /// Conventional milling: the mirror image, clockwise.
    Conventional,
}

/// How the tool goes down into the material at the start of a region.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Entry {
    /// A helix of `radius` mm descending at `ramp_angle` rad (falls back to a ramp along the
    /// first loop where the helix does not fit).
    Helix {
        /// Helix radius in mm (tool centre).
        radius: f64,
        /// Descent angle in rad.
        ramp_angle: f64,
    },
    /// A ramp along the first loop of the region, descending at `ramp_angle` rad.
    Ramp {
        /// Descent angle in rad.
        ramp_angle: f64,
    },
}

/// The three pocketing strategies.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StrategyKind {
    /// Parallel passes at an angle, with a boundary clean-up pass.
    Zigzag,
    /// Contour-parallel offsets from the inside out.
    Offset,
    /// The adaptive spiral: a central spiral morphing into the boundary offset.
    Spiral,
    /// Adaptive clearing: the engagement held at the stepover's at every step
    /// (`crate::strategy::adaptive`).
    Adaptive,
}

impl StrategyKind {
    /// Lower-case name, as on the command line.
    pub fn name(self) -> &'static str {
        match self {
            StrategyKind::Zigzag => "zigzag",
            StrategyKind::Offset => "offset",
            StrategyKind::Spiral => "spiral",
            StrategyKind::Adaptive => "adaptive",
        }
    }
}

/// How the spiral morphs from its central circle into the boundary offset.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SpiralMorph {
    /// The contour-parallel loops, rounded, each chain of them joined into one spiral by
    /// curvature-continuous lane changes (`spiral::offsets`).
    #[default]
    Offsets,
    /// The central disc united with the boundary offset's inward offsets (`spiral::fronts`): as
    /// many laps as contour-parallel offsets, smoothed corners; at convex corners of the
    /// boundary the loops are up to `s/sin(α/2)` apart along the bisector, as offsets are.
    /// Falls back to [`SpiralMorph::Harmonic`] where the fronts do not reach the boundary.
    Fronts,
    /// Level sets of a harmonic function (`spiral::harmonic`): the stepover holds everywhere,
    /// corners included, at the price of laps crowding where the pocket is narrow.
    Harmonic,
}

/// Everything a pocketing strategy needs besides the outline and the tool: the settings every
/// strategy shares, then the spiral's and the zigzag's own ([`SpiralOptions`],
/// [`ZigzagOptions`]). Built from [`Default`] with the `with_*` methods (the struct is
/// `#[non_exhaustive]`: new settings do not break callers).
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct PocketOptions {
    /// Maximum radial depth of cut.
    pub stepover: Stepover,
    /// Total pocket depth in mm (positive; the top of the stock is z = 0).
    pub depth: f64,
    /// Maximum depth of one level in mm.
    pub step_down: f64,
    /// Material left on the walls, mm.
    pub wall_stock: f64,
    /// Material left on the floor, mm.
    pub floor_stock: f64,
    /// Climb or conventional.
    pub direction: Direction,
    /// Helix or ramp entry.
    pub entry: Entry,
    /// Height above the top of the stock (or the level above) where feeding down starts, mm.
    pub safe_height: f64,
    /// Height above the top of the stock for rapid traverses, mm.
    pub clearance_height: f64,
    /// Cutting feed in mm/s.
    pub feed: f64,
    /// Feed straight down, mm/s; helical and ramp entries descend at it (along the ramp at
    /// `plunge_feed / sin α`, at most the feed).
    pub plunge_feed: f64,
    /// Fraction of the feed at full slotting (180° engagement); see `super::feed`.
    pub slowdown: f64,
    /// A finishing pass along the walls at the last level (no wall stock).
    pub finish: bool,
    /// Modulate the feed with the engagement measured by the stock simulation.
    pub modulate_feed: bool,
    /// The spiral's own settings.
    pub spiral: SpiralOptions,
    /// The zigzag's own settings.
    pub zigzag: ZigzagOptions,
    /// The adaptive's own settings.
    pub adaptive: AdaptiveOptions,
}

/// The spiral strategy's settings ([`PocketOptions::spiral`]).
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct SpiralOptions {
    /// Transition ratio C in [0, 1]: the central circular spiral reaches C times the
    /// inscribed radius of the boundary offset.
    pub transition: f64,
    /// Smallest radius of curvature wanted on the interior loops, mm.
    pub min_radius: f64,
    /// How the spiral morphs from its central circle into the boundary offset.
    pub morph: SpiralMorph,
    /// Output the laps as tangent-continuous arcs (G2/G3, biarcs within
    /// `spiral::ARC_TOLERANCE`) instead of G1 chords (`--arcs`). The other strategies'
    /// paths are lines and exact arcs already.
    pub arcs: bool,
    /// The interior smoothed into curvature ramps (`spiral::smooth`): a jerk-limited
    /// controller must slow where the curvature steps, and LinuxCNC's trapezoidal planner
    /// runs the smoothed spiral faster too (on LinuxCNC 2.9 itself, e.g. the aerospace
    /// pocket's level 14.84 s against 15.25 s with the rounded loops left as they are):
    /// on by default for every machine.
    pub curvature_ramps: bool,
    /// The widest helix the spiral enters by, in tool radii: wider than the tool
    /// (`ρ > r`), the helix leaves a pillar of radius `ρ − r` at its centre, so such a
    /// helix is taken only where the spiral's own path then passes over the whole pillar
    /// (see `spiral::offsets`); else the entry's radius, at most 0.9·r. A wider helix runs
    /// faster: a controller holds the feed `v` on a circle of radius `ρ` only while
    /// `v²/ρ` is within its acceleration. `0` keeps the entry's radius (set when the user
    /// gives one).
    pub wide_helix: f64,
}

impl Default for SpiralOptions {
    fn default() -> Self {
        SpiralOptions {
            transition: 0.5,
            min_radius: 1.0,
            morph: SpiralMorph::default(),
            arcs: false,
            curvature_ramps: true,
            wide_helix: 1.5,
        }
    }
}

/// The zigzag strategy's settings ([`PocketOptions::zigzag`]).
#[derive(Debug, Clone, PartialEq, Default)]
#[non_exhaustive]
pub struct ZigzagOptions {
    /// Pass angle in rad from the pocket's principal axis (its long direction; see
    /// `super::zigzag`).
    pub angle: f64,
    /// Turn between rows at two corners along a straight link instead of on half circles
    /// (`generate` plans the zigzag so again where the half circles leave material).
    pub straight_turns: bool,
    /// Enter by ramping back along the first row and cutting it again at the level, instead
    /// of ramping along it as it is cut with the passes beside it taking what the ramp left
    /// (`generate` plans the zigzag so again where the stock simulation finds material
    /// left).
    pub ramp_recut: bool,
}

/// The adaptive strategy's settings ([`PocketOptions::adaptive`]).
#[derive(Debug, Clone, PartialEq, Default)]
#[non_exhaustive]
pub struct AdaptiveOptions {
    /// Passes may run either way (`--both-ways`): a pass runs against the chosen direction
    /// ([`PocketOptions::direction`]) where that starts it nearer the tool by more than the
    /// tool's radius, so that short passes ending at a wall (in a corner) are cut to and
    /// fro instead of each followed by a link back. The engagement's bound holds either way.
    pub both_ways: bool,
    /// How far the tool rises over the floor on a link through cleared material, mm
    /// (`--lift`; 0, the default: the link runs at the level). The link rises and settles
    /// again at the entry's ramp angle, so it stays a smooth move for the controller; a link
    /// too short to reach the whole lift at that angle rises half its length.
    pub lift: f64,
    /// With `--strategy auto`: the step-down of the adaptive candidate, mm (the flute length
    /// the user gave; `None`, the default: `auto` leaves the adaptive out). Its stepover is
    /// [`AdaptiveOptions::AUTO_STEPOVER`], the adaptive's own default; the other settings are
    /// the other candidates'.
    pub auto_step_down: Option<f64>,
}

impl AdaptiveOptions {
    /// The stepover of `auto`'s adaptive candidate, a fraction of the tool's diameter.
    pub const AUTO_STEPOVER: f64 = 0.1;
}

impl Default for PocketOptions {
    fn default() -> Self {
        PocketOptions {
            stepover: Stepover::Fraction(0.4),
            depth: 10.0,
            step_down: 5.0,
            wall_stock: 0.0,
            floor_stock: 0.0,
            direction: Direction::Climb,
            entry: Entry::Helix {
                radius: 2.5,
                ramp_angle: 3f64.to_radians(),
            },
            safe_height: 1.0,
            clearance_height: 5.0,
            feed: 600.0 * 25.4 / 60.0,
            plunge_feed: 200.0 * 25.4 / 60.0,
            slowdown: 0.75,
            finish: false,
            modulate_feed: true,
            spiral: SpiralOptions::default(),
            zigzag: ZigzagOptions::default(),
            adaptive: AdaptiveOptions::default(),
        }
    }
}

option_builders! {
    PocketOptions;
    /// Sets [`PocketOptions::stepover`].
    with_stepover => stepover: Stepover;
    /// Sets [`PocketOptions::depth`], mm.
    with_depth => depth: f64;
    /// Sets [`PocketOptions::step_down`], mm.
    with_step_down => step_down: f64;
    /// Sets [`PocketOptions::wall_stock`], mm.
    with_wall_stock => wall_stock: f64;
    /// Sets [`PocketOptions::floor_stock`], mm.
    with_floor_stock => floor_stock: f64;
    /// Sets [`PocketOptions::direction`].
    with_direction => direction: Direction;
    /// Sets [`PocketOptions::entry`].
    with_entry => entry: Entry;
    /// Sets [`PocketOptions::safe_height`], mm.
    with_safe_height => safe_height: f64;
    /// Sets [`PocketOptions::clearance_height`], mm.
    with_clearance_height => clearance_height: f64;
    /// Sets [`PocketOptions::feed`], mm/s.
    with_feed => feed: f64;
    /// Sets [`PocketOptions::plunge_feed`], mm/s.
    with_plunge_feed => plunge_feed: f64;
    /// Sets [`PocketOptions::slowdown`].
    with_slowdown => slowdown: f64;
    /// Sets [`PocketOptions::finish`].
    with_finish => finish: bool;
    /// Sets [`PocketOptions::modulate_feed`].
    with_modulate_feed => modulate_feed: bool;
    /// Sets all of [`PocketOptions::spiral`].
    with_spiral => spiral: SpiralOptions;
    /// Sets all of [`PocketOptions::zigzag`].
    with_zigzag => zigzag: ZigzagOptions;
    /// Sets all of [`PocketOptions::adaptive`].
    with_adaptive => adaptive: AdaptiveOptions;
    /// Sets [`AdaptiveOptions::both_ways`].
    with_both_ways => adaptive.both_ways: bool;
    /// Sets [`AdaptiveOptions::lift`], mm.
    with_lift => adaptive.lift: f64;
    /// Sets [`AdaptiveOptions::auto_step_down`], mm.
    with_auto_step_down => adaptive.auto_step_down: Option<f64>;
    /// Sets [`SpiralOptions::transition`].
    with_transition => spiral.transition: f64;
    /// Sets [`SpiralOptions::min_radius`], mm.
    with_min_radius => spiral.min_radius: f64;
    /// Sets [`SpiralOptions::morph`].
    with_morph => spiral.morph: SpiralMorph;
    /// Sets [`SpiralOptions::arcs`].
    with_arcs => spiral.arcs: bool;
    /// Sets [`SpiralOptions::curvature_ramps`].
    with_curvature_ramps => spiral.curvature_ramps: bool;
    /// Sets [`SpiralOptions::wide_helix`], tool radii.
    with_wide_helix => spiral.wide_helix: f64;
    /// Sets [`ZigzagOptions::angle`], rad.
    with_zigzag_angle => zigzag.angle: f64;
    /// Sets [`ZigzagOptions::ramp_recut`].
    with_zigzag_ramp_recut => zigzag.ramp_recut: bool;
}

fn check(what: &str, v: f64, ok: bool, flag: &str, expected: &str) -> Result<(), InputError> {
    if v.is_finite() && ok {
        Ok(())
    } else {
        // `InputError::new` shows 1e300 in exponent form, not as 301 digits.
        Err(InputError::new(what, v).at(flag).expected(expected))
    }
}

impl PocketOptions {
    /// The stepover in mm for `tool`.
    pub fn stepover_mm(&self, tool: &Tool) -> f64 {
        self.stepover.distance(tool.diameter)
    }

    /// Checks every option against `tool`.
    pub fn validate(&self, tool: &Tool) -> Result<(), InputError> {
        tool.validate("--tool-diameter")?;
        let d = tool.diameter;
        let s = self.stepover_mm(tool);
        check(
            "stepover",
            s,
            s > 0.0 && s <= d * (1.0 + 1e-12),
            "--stepover",
            "a stepover > 0 and at most one tool diameter",
        )?;
        check(
            "depth",
            self.depth,
            self.depth > 0.0 && self.depth <= MAX_LENGTH_MM,
            "--depth",
            "a depth > 0 mm and at most 1e6 mm",
        )?;
        check(
            "step-down",
            self.step_down,
            self.step_down > 0.0 && self.step_down <= tool.flute_length,
            "--step-down",
            &format!(
                "a step-down > 0 mm and at most the flute length, {} mm",
                (tool.flute_length * 1e4).round() / 1e4
            ),
        )?;
        check(
            "wall stock",
            self.wall_stock,
            (0.0..=MAX_LENGTH_MM).contains(&self.wall_stock),
            "--wall-stock",
            "a stock >= 0 mm and at most 1e6 mm",
        )?;
        check(
            "floor stock",
            self.floor_stock,
            self.floor_stock >= 0.0 && self.floor_stock < self.depth,
            "--floor-stock",
            "a stock >= 0 mm and below the depth",
        )?;
        check(
            "lift",
            self.adaptive.lift,
            self.adaptive.lift >= 0.0 && self.adaptive.lift <= self.safe_height,
            "--lift",
            "a lift >= 0 mm and at most the safe height",
        )?;
        check(
            "safe height",
            self.safe_height,
            self.safe_height > 0.0 && self.safe_height <= MAX_LENGTH_MM,
            "--safe-height",
            "a height > 0 mm and at most 1e6 mm",
        )?;
        check(
            "clearance height",
            self.clearance_height,
            self.clearance_height >= self.safe_height && self.clearance_height <= MAX_LENGTH_MM,
            "--clearance-height",
            "a height at least the safe height and at most 1e6 mm",
        )?;
        let levels = (self.depth - self.floor_stock) / self.step_down;
        check(
            "levels (depth / step-down)",
            levels,
            levels <= MAX_LEVELS,
            "--depth and --step-down",
            "at most 10000 levels",
        )?;
        check("feed", self.feed, self.feed > 0.0, "--feed", "a feed > 0")?;
        check(
            "plunge feed",
            self.plunge_feed,
            self.plunge_feed > 0.0,
            "--plunge-feed",
            "a feed > 0",
        )?;
        check(
            "slowdown",
            self.slowdown,
            self.slowdown > 0.0 && self.slowdown <= 1.0,
            "--slowdown",
            "a fraction in (0, 1]",
        )?;
        check(
            "zigzag angle",
            self.zigzag.angle,
            true,
            "--angle",
            "a finite angle",
        )?;
        check(
            "transition",
            self.spiral.transition,
            (0.0..=1.0).contains(&self.spiral.transition),
            "--transition",
            "a ratio in [0, 1]",
        )?;
        check(
            "min radius",
            self.spiral.min_radius,
            (0.0..=MAX_LENGTH_MM).contains(&self.spiral.min_radius),
            "--min-radius",
            "a radius >= 0 mm and at most 1e6 mm",
        )?;
        check(
            "wide helix",
            self.spiral.wide_helix,
            (0.0..=MAX_WIDE_HELIX).contains(&self.spiral.wide_helix),
            "--helix-radius",
            "a ratio to the tool radius in [0, 2]",
        )?;
        match self.entry {
            Entry::Helix { radius, ramp_angle } => {
                check(
                    "helix radius",
                    radius,
                    radius > 0.0 && radius <= MAX_LENGTH_MM,
                    "--helix-radius",
                    "a radius > 0 mm and at most 1e6 mm",
                )?;
                check_ramp(ramp_angle)?;
            }
            Entry::Ramp { ramp_angle } => check_ramp(ramp_angle)?,
        }
        Ok(())
    }
}

/// The largest [`SpiralOptions::wide_helix`], tool radii: the pillar of a helix of radius
/// 2·r is as wide as the tool.
pub const MAX_WIDE_HELIX: f64 = 2.0;

fn check_ramp(a: f64) -> Result<(), InputError> {
    check(
        "ramp angle",
        a.to_degrees(),
        a > 0.0 && a <= 45f64.to_radians(),
        "--ramp-angle",
        "an angle in (0, 45] degrees",
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Heights, stocks and radii of 1e300 mm are refused, named in exponent form (the
    /// `pocket` fuzzer's safe height of 1e300 mm made a helix entry of 1e300 turns).
    #[test]
    fn huge_lengths_are_refused_in_exponent_form() {
        let tool = Tool::flat(10.0).unwrap();
        for (flag, opts) in [
            (
                "--safe-height",
                PocketOptions::default()
                    .with_safe_height(1e300)
                    .with_clearance_height(1e300),
            ),
            (
                "--clearance-height",
                PocketOptions::default().with_clearance_height(2e6),
            ),
            (
                "--wall-stock",
                PocketOptions::default().with_wall_stock(1e300),
            ),
            (
                "--min-radius",
                PocketOptions::default().with_min_radius(1e300),
            ),
            (
                "--helix-radius",
                PocketOptions::default().with_entry(Entry::Helix {
                    radius: 1e300,
                    ramp_angle: 0.05,
                }),
            ),
        ] {
            let e = opts.validate(&tool).unwrap_err().to_string();
            assert!(e.contains(flag) && e.contains("at most 1e6 mm"), "{e}");
            assert!(e.len() < 200, "{e}");
        }
        assert!(PocketOptions::default().validate(&tool).is_ok());
    }

    #[test]
    fn stepover_parses_fraction_and_distance() {
        assert_eq!(Stepover::parse("0.4").unwrap(), Stepover::Fraction(0.4));
        assert_eq!(Stepover::parse("5mm").unwrap(), Stepover::Distance(5.0));
        assert!(Stepover::parse("abc").is_err());
        assert!((Stepover::Fraction(0.4).distance(10.0) - 4.0).abs() < 1e-12);
    }

    #[test]
    fn validation_rejects_bad_stepovers() {
        let tool = Tool::flat(10.0).unwrap();
        for s in [0.0, -0.1, 1.5, f64::NAN] {
            let o = PocketOptions::default().with_stepover(Stepover::Fraction(s));
            let e = o.validate(&tool).unwrap_err();
            assert!(e.to_string().contains("stepover"), "{e}");
        }
        assert!(PocketOptions::default().validate(&tool).is_ok());
    }
}
