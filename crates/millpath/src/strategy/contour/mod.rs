//! Contour strategy: the free-form outline cut at its cutter offset, layer by layer.
//!
//! Pipeline (Mohamed's die-cavity method, made exact): closed curve ([`crate::curve`]) →
//! exact offset by tool radius + finish allowance (`offset`) → fewest chords within the
//! tolerance (the greedy exact-deviation flattener, run on the *offset* curve) → loop trimming
//! → roughing layers at each step-down, then a finishing pass at full depth, with lead arcs.
//!
//! # Tolerance budget
//! The user's tolerance `T` bounds the distance between the programmed path (after G-code
//! rounding) and the exact offset of the exact curve. Output rounding of `dec` decimals moves
//! an XY point by at most `ρ = √2·½·10^−dec` (in mm; the G-code writer's
//! `rounding_error_mm`), and a segment moves by at most `ρ` (its points are convex
//! combinations of its ends). The path is kept **one-sided**, on the free side of the nominal
//! offset `d`, so it never gouges: the offset is computed at `d + ρ + t` and flattened within
//! `t = (T − 2ρ)/2`. Every chord point is then within `[d + ρ, d + ρ + 2t]` of the outline
//! before rounding and within `[d, d + T]` after it. `T ≤ 2ρ` is refused (the caller raises
//! the decimals first). For `--side on` (d = 0) the budget is two-sided: `t = T − ρ`.
//!
//! With `--arcs` the biarcs are fitted within `t − ρ` (at least `t/2`,
//! [`ContourOptions::arc_tolerance`]): the G-code writer writes an arc whose sagitta is at
//! most `ρ` as its chord, which lies within the sagitta of the arc, so a written chord too
//! stays within `t` of the offset curve. (Below `t/2`, i.e. `T < 6ρ` with the decimals
//! given by hand, such a chord may come up to `ρ − t/2` nearer the outline.)
//!
//! # The paper's example
//! [`sample`] reproduces Mohamed's die cavity: the Table 1 outline on a 400 × 450 × 50 mm
//! block, 10 mm end mill, 2.5 mm step-down, T = 0.00004 mm. The paper reports "1900 steps
//! per layer". At that T the outline alone needs 3555 chords by the exact greedy (the
//! asymptotic optimum ∫√(|κ|/8T) ds is 3556, kurbo's flatten takes 3852), so 1900 chords
//! cannot hold 0.00004 mm on this outline at this scale; the one-sided, rounding-aware
//! offset pass takes about 4700.
//!
//! # Where the tool cannot reach
//! Where the concave curvature radius is below `d` (`1 − dκ ≤ 0`) or at concave corners, the
//! raw offset loops; those loops are trimmed and reported in [`ContourResult::warnings`]
//! with their position on the outline. The library never prints.

pub(crate) mod leads;
pub(crate) mod offset;
mod pass;
pub(crate) mod report;

pub use leads::layer_depths;
use leads::{Lead, loop_moves};
pub use pass::{Pass, offset_pass};
pub use report::{ContourReport, LayerReport};

use crate::curve::{self, CompositeCurve};
use crate::error::{InputError, require_positive};
use crate::geom::{Point, Point3};
use crate::toolpath::{Level, LevelKind, Move, Tool, Toolpath};
use serde::{Deserialize, Serialize};

/// Which side of the outline the tool runs on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Side {
    /// Inside the outline (a cavity, as in the paper's blanking die).
    #[default]
    Inside,
    /// Outside the outline (a boss or a punch).
    Outside,
    /// Tool centre on the outline (engraving).
    On,
}

/// Options of [`contour`], built from [`Default`] with the `with_*` methods
/// (`#[non_exhaustive]`: new settings do not break callers).
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct ContourOptions {
    /// The flat end mill.
    pub tool: Tool,
    /// Path tolerance `T` in mm (see the module docs: chord deviation + rounding ≤ T).
    pub tolerance: f64,
    /// Output rounding allowance `ρ` in mm (from the G-code decimals).
    pub rounding: f64,
    /// Which side of the outline.
    pub side: Side,
    /// Top of the stock (Z, mm).
    pub top_z: f64,
    /// Depth of the contour below `top_z` (mm, > 0).
    pub depth: f64,
    /// Step-down per roughing layer (mm, > 0).
    pub step_down: f64,
    /// Radial stock left by the roughing layers (mm, ≥ 0).
    pub finish_allowance: f64,
    /// Safe height for rapid traverses (mm above `top_z`).
    pub safe_height: f64,
    /// Clearance height: rapids stop here before feeding down (mm above `top_z`).
    pub clearance_height: f64,
    /// Cutting feed in mm/s.
    pub feed: f64,
    /// Plunge feed in mm/s.
    pub plunge_feed: f64,
    /// Lead-in/lead-out arc radius in mm (0: no lead arcs).
    pub lead_radius: f64,
    /// Rapid speed used for the time at programmed feed (mm/s).
    pub rapid_speed: f64,
    /// Emit biarcs (G2/G3) instead of lines.
    pub arcs: bool,
}

impl Default for ContourOptions {
    fn default() -> Self {
        ContourOptions {
            tool: Tool::default(),
            tolerance: 0.01,
            rounding: 0.5e-4 * std::f64::consts::SQRT_2,
            side: Side::Inside,
            top_z: 0.0,
            depth: 20.0,
            step_down: 2.5,
            finish_allowance: 0.2,
            safe_height: 10.0,
            clearance_height: 2.0,
            feed: 1000.0 / 60.0,
            plunge_feed: 300.0 / 60.0,
            lead_radius: 2.0,
            rapid_speed: 10_000.0 / 60.0,
            arcs: false,
        }
    }
}

impl ContourOptions {
    /// Sets the flat end mill ([`ContourOptions::tool`]).
    #[must_use]
    pub fn with_tool(mut self, value: Tool) -> Self {
        self.tool = value;
        self
    }

    /// Sets the path tolerance `T`, mm ([`ContourOptions::tolerance`]).
    #[must_use]
    pub fn with_tolerance(mut self, value: f64) -> Self {
        self.tolerance = value;
        self
    }

    /// Sets the rounding allowance `ρ`, mm ([`ContourOptions::rounding`]).
    #[must_use]
    pub fn with_rounding(mut self, value: f64) -> Self {
        self.rounding = value;
        self
    }

    /// Sets the side of the outline ([`ContourOptions::side`]).
    #[must_use]
    pub fn with_side(mut self, value: Side) -> Self {
        self.side = value;
        self
    }

    /// Sets the stock top, mm ([`ContourOptions::top_z`]).
    #[must_use]
    pub fn with_top_z(mut self, value: f64) -> Self {
        self.top_z = value;
        self
    }

    /// Sets the depth below the top, mm ([`ContourOptions::depth`]).
    #[must_use]
    pub fn with_depth(mut self, value: f64) -> Self {
        self.depth = value;
        self
    }

    /// Sets the step-down, mm ([`ContourOptions::step_down`]).
    #[must_use]
    pub fn with_step_down(mut self, value: f64) -> Self {
        self.step_down = value;
        self
    }

    /// Sets the roughing layers' radial stock, mm ([`ContourOptions::finish_allowance`]).
    #[must_use]
    pub fn with_finish_allowance(mut self, value: f64) -> Self {
        self.finish_allowance = value;
        self
    }

    /// Sets the safe height, mm ([`ContourOptions::safe_height`]).
    #[must_use]
    pub fn with_safe_height(mut self, value: f64) -> Self {
        self.safe_height = value;
        self
    }

    /// Sets the clearance height, mm ([`ContourOptions::clearance_height`]).
    #[must_use]
    pub fn with_clearance_height(mut self, value: f64) -> Self {
        self.clearance_height = value;
        self
    }

    /// Sets the cutting feed, mm/s ([`ContourOptions::feed`]).
    #[must_use]
    pub fn with_feed(mut self, value: f64) -> Self {
        self.feed = value;
        self
    }

    /// Sets the plunge feed, mm/s ([`ContourOptions::plunge_feed`]).
    #[must_use]
    pub fn with_plunge_feed(mut self, value: f64) -> Self {
        self.plunge_feed = value;
        self
    }

    /// Sets the lead arc radius, mm ([`ContourOptions::lead_radius`]).
    #[must_use]
    pub fn with_lead_radius(mut self, value: f64) -> Self {
        self.lead_radius = value;
        self
    }

    /// Sets the rapid speed, mm/s ([`ContourOptions::rapid_speed`]).
    #[must_use]
    pub fn with_rapid_speed(mut self, value: f64) -> Self {
        self.rapid_speed = value;
        self
    }

    /// Sets biarcs instead of lines ([`ContourOptions::arcs`]).
    #[must_use]
    pub fn with_arcs(mut self, value: bool) -> Self {
        self.arcs = value;
        self
    }
}

/// The most Z layers a contour may have (`depth / step-down`).
pub const MAX_LAYERS: f64 = 10_000.0;

impl ContourOptions {
    /// Checks every value; errors name the option.
    pub fn validate(&self) -> Result<(), InputError> {
        self.tool.validate("tool")?;
        require_positive("tolerance", self.tolerance, "contour options")?;
        require_positive("depth", self.depth, "contour options")?;
        require_positive("step-down", self.step_down, "contour options")?;
        // The layer count `depth / step-down` is allocated: bounded (a depth of 1e300 asked
        // for a capacity overflow in `layer_depths`; found by the `contour` fuzzer).
        if self.depth / self.step_down > MAX_LAYERS {
            return Err(InputError::new("step-down", self.step_down)
                .at("contour options")
                .expected(format!(
                    "at most {MAX_LAYERS} layers: a step-down >= depth / {MAX_LAYERS} = {} mm",
                    self.depth / MAX_LAYERS
                )));
        }
        require_positive("feed", self.feed, "contour options")?;
        require_positive("plunge feed", self.plunge_feed, "contour options")?;
        require_positive("rapid speed", self.rapid_speed, "contour options")?;
        for (what, v) in [
            ("finish allowance", self.finish_allowance),
            ("lead radius", self.lead_radius),
            ("rounding allowance", self.rounding),
            ("clearance height", self.clearance_height),
        ] {
            if !(v.is_finite() && v >= 0.0) {
                return Err(InputError::new(what, v)
                    .at("contour options")
                    .expected("a finite number >= 0"));
            }
        }
        crate::error::require_finite("top Z", self.top_z, "contour options")?;
        // Lengths beyond ±1e6 mm (1 km) mean nothing on a machine and make the work explode
        // (a lead radius of 1e300 took seconds; a tool of 1e300 mm asked the corner join for
        // 3e9 points; found by the `contour` fuzzer).
        let max = crate::geom::MAX_COORDINATE_MM;
        for (what, v) in [
            ("tool diameter", self.tool.diameter),
            ("top Z", self.top_z),
            ("depth", self.depth),
            ("finish allowance", self.finish_allowance),
            ("lead radius", self.lead_radius),
            ("safe height", self.safe_height),
            ("clearance height", self.clearance_height),
            ("tolerance", self.tolerance),
        ] {
            if v.abs() > max {
                return Err(InputError::new(what, v)
                    .at("contour options")
                    .expected(format!("a length within ±{max} mm")));
            }
        }
        if !(self.safe_height.is_finite() && self.safe_height >= self.clearance_height) {
            return Err(InputError::new("safe height", self.safe_height)
                .at("contour options")
                .expected(format!(
                    "a finite number >= the clearance height {}",
                    self.clearance_height
                )));
        }
        if self.tolerance <= 2.0 * self.rounding {
            return Err(InputError::new("tolerance", self.tolerance)
                .at("contour options")
                .expected(format!(
                    "more than twice the output rounding {:.3e} mm (raise the G-code decimals)",
                    self.rounding
                )));
        }
        Ok(())
    }

    /// The biarc tolerance of `--arcs` for an offset of `d` mm: `t − ρ`, at least `t/2`
    /// (see the module docs: a written arc flatter than `ρ` becomes its chord).
    pub fn arc_tolerance(&self, d: f64) -> f64 {
        let t = self.chord_tolerance(d);
        t - self.rounding.min(0.5 * t)
    }

    /// The chord tolerance `t` of the budget (module docs) for an offset of `d` mm.
    pub fn chord_tolerance(&self, d: f64) -> f64 {
        if d == 0.0 {
            self.tolerance - self.rounding
        } else {
            0.5 * (self.tolerance - 2.0 * self.rounding)
        }
    }
}

/// What [`contour`] produced.
#[derive(Debug, Clone)]
pub struct ContourResult {
    /// The toolpath (levels: roughing layers, then the finishing pass).
    pub toolpath: Toolpath,
    /// The report (block and line counts are the toolpath's; the CLI replaces them with the
    /// written program's).
    pub report: ContourReport,
    /// Places the tool cannot reach, and other things the user should know.
    pub warnings: Vec<ContourWarning>,
}

fn signed_offset(side: Side, d: f64) -> f64 {
    match side {
        Side::Inside => d,
        Side::Outside => -d,
        Side::On => 0.0,
    }
}

/// Runs the contour strategy on a closed curve.
pub fn contour(
    curve: &CompositeCurve,
    opt: &ContourOptions,
) -> Result<ContourResult, crate::Error> {
    opt.validate()?;
    let r = opt.tool.radius();
    let rough_d = signed_offset(opt.side, r + opt.finish_allowance);
    let finish_d = signed_offset(opt.side, r);
    let finish = offset_pass(curve, finish_d, opt)?;
    let rough = if opt.finish_allowance > 0.0 && opt.side != Side::On {
        offset_pass(curve, rough_d, opt)?
    } else {
        finish.clone()
    };
    let mut warnings = finish.warnings.clone();
    let zs = layer_depths(opt.top_z, opt.depth, opt.step_down);
    let mut tp = Toolpath::new(opt.tool, Point3::new(0.0, 0.0, opt.top_z + opt.safe_height));
    let mut layers = Vec::new();
    let plan: Vec<(f64, &Pass, LevelKind)> = zs
        .iter()
        .map(|z| (*z, &rough, LevelKind::Roughing))
        .chain(std::iter::once((
            opt.top_z - opt.depth,
            &finish,
            LevelKind::Finishing,
        )))
        .collect();
    let safe = opt.top_z + opt.safe_height;
    let clear = opt.top_z + opt.clearance_height;
    tp.start = Point3::new(tp.start.x, tp.start.y, safe);
    // The free side: left of travel inside (towards the cavity's middle), right outside.
    let lead = Lead {
        radius: opt.lead_radius,
        left: opt.side != Side::Outside,
        feed: opt.feed,
    };
    for (li, (z, pass, kind)) in plan.iter().enumerate() {
        let start = tp.moves.len();
        for (k, lp) in pass.loops.iter().enumerate() {
            let arcs = pass.arcs.get(k).map(Vec::as_slice);
            let (entry, path) = loop_moves(lp, arcs, *z, &lead, curve.len());
            let here = tp.end();
            // The first approach comes down from the safe height; between passes the tool
            // stays at the clearance height (above the stock top) to reach the next entry.
            if here.xy().distance(entry) > 1e-9 {
                tp.push(Move::rapid(Point3::from_xy(entry, here.z.max(clear))));
            }
            tp.push(Move::rapid(Point3::from_xy(entry, clear)));
            tp.push(Move::line(Point3::from_xy(entry, *z), opt.plunge_feed));
            tp.moves.extend(path);
            tp.push(Move::rapid(Point3::from_xy(tp.end().xy(), clear)));
        }
        let end = tp.moves.len();
        tp.levels.push(Level {
            z: *z,
            kind: *kind,
            start,
            end,
        });
        let sub = Toolpath {
            moves: tp.moves[start..end].to_vec(),
            start: if start > 0 {
                tp.moves[start - 1].to
            } else {
                tp.start
            },
            ..tp.clone()
        };
        layers.push(LayerReport {
            index: li + 1,
            z: *z,
            kind: *kind,
            offset_mm: pass.distance.abs(),
            segments: pass.segments(),
            max_deviation_mm: pass.max_deviation,
            cut_length_mm: sub.cut_length(),
        });
    }
    tp.push(Move::rapid(Point3::from_xy(tp.end().xy(), safe)));
    if finish.loops.len() > 1 {
        warnings.push(ContourWarning::SplitLoops(finish.loops.len()));
    }
    let report = ContourReport::build(curve, opt, &finish, layers, &tp, &warnings);
    Ok(ContourResult {
        toolpath: tp,
        report,
        warnings,
    })
}

/// What a contour pass could not do as asked ([`ContourResult::warnings`]).
#[derive(Debug, Clone, PartialEq)]
pub enum ContourWarning {
    /// The tool cannot reach the outline between two places: a concave radius or corner
    /// tighter than the offset; that stretch is left uncut.
    Unreachable {
        /// The offset distance, mm.
        offset_mm: f64,
        /// Where the stretch starts and ends on the outline.
        from: Point,
        /// See `from`.
        to: Point,
        /// The curve parameters of its ends.
        params: (f64, f64),
    },
    /// The offset splits into this many separate loops (necks narrower than the tool); each
    /// is cut.
    SplitLoops(usize),
}

impl std::fmt::Display for ContourWarning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ContourWarning::Unreachable {
                offset_mm,
                from,
                to,
                params,
            } => write!(
                f,
                "the tool (offset {offset_mm:.4} mm) cannot reach the outline between ({:.3}, {:.3}) and ({:.3}, {:.3}) (curve parameter {:.4} to {:.4}): concave radius or corner tighter than the offset; left uncut",
                from.x, from.y, to.x, to.y, params.0, params.1
            ),
            ContourWarning::SplitLoops(n) => write!(
                f,
                "the offset splits into {n} separate loops (the outline has necks narrower than the tool); each is cut"
            ),
        }
    }
}

/// The paper's example as a built-in sample: its outline scaled onto the 400 × 450 × 50 mm
/// die block ([`curve::paper_outline`]), a 10 mm flat end mill, 2.5 mm step-down, 8 layers
/// (20 mm deep), cut inside (the blanking die cavity) at the paper's T = 0.00004 mm.
pub fn sample() -> Result<(CompositeCurve, ContourOptions), InputError> {
    let c = curve::paper_outline()?;
    let opt = ContourOptions::default()
        .with_tool(Tool::flat(10.0)?)
        .with_tolerance(4e-5)
        .with_rounding(0.5e-6 * std::f64::consts::SQRT_2)
        .with_depth(20.0)
        .with_step_down(2.5)
        .with_top_z(0.0);
    Ok((c, opt))
}

/// Centre of the paper's die block (mm), for previews.
pub const SAMPLE_BLOCK: (f64, f64, f64) = (400.0, 450.0, 50.0);

/// Point helper for tests and previews: the block's corner points.
pub fn sample_block_corners() -> [Point; 4] {
    let (w, h, _) = SAMPLE_BLOCK;
    [
        Point::new(0.0, 0.0),
        Point::new(w, 0.0),
        Point::new(w, h),
        Point::new(0.0, h),
    ]
}
