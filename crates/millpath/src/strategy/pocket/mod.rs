//! Pocket strategies: zigzag, contour-offset, adaptive spiral.
//!
//! [`generate`] turns a [`PocketShape`], a [`Tool`] and [`PocketOptions`] into a
//! [`Toolpath`]: the strategy plans one level in the plane ([`levels::LevelPlan`]: cuts of
//! lines and exact arcs, each with its entry), [`levels::assemble`] repeats it at every
//! step-down with entries and heights, the stock simulation ([`crate::stock`]) measures the
//! engagement of every move and [`feed`] slows the feed where it exceeds the nominal one;
//! the same simulation and the exact gouge check give the [`Verification`].
//!
//! * [`zigzag`]: parallel passes at an angle plus a boundary clean-up pass;
//! * [`offset`]: contour-parallel offsets from the inside out;
//! * [`spiral`]: the adaptive spiral, a central spiral morphing harmonically into the
//!   boundary offset.

pub mod chain;
pub mod feed;
pub mod levels;
pub mod offset;
pub mod options;
pub mod samples;
pub mod shape;
pub mod spiral;
pub mod zigzag;

pub use options::{Direction, Entry, PocketOptions, Stepover, StrategyKind};
pub use shape::PocketShape;

use crate::error::Result;
use crate::stock::{self, SimOptions, StockSpec, Verification};
use crate::toolpath::{Tool, Toolpath};
use cavalier_contours::polyline::PlineSource;

/// A generated pocket toolpath and what the verifier measured on it.
#[derive(Debug, Clone)]
pub struct PocketResult {
    /// The toolpath, feeds modulated.
    pub toolpath: Toolpath,
    /// The verifier's findings.
    pub verification: Verification,
    /// The nominal engagement the stepover implies, degrees.
    pub nominal_engagement_deg: f64,
    /// The stepover in mm.
    pub stepover_mm: f64,
}

/// The nominal engagement angle (rad) for stepover `s` and tool radius `r`: `arccos(1 − s/r)`.
pub fn nominal_engagement(s: f64, r: f64) -> f64 {
    (1.0 - (s / r).clamp(0.0, 2.0)).acos()
}

/// Plans one level with `kind` (no feeds, no levels).
pub fn plan_level(
    kind: StrategyKind,
    shape: &PocketShape,
    tool: &Tool,
    opts: &PocketOptions,
) -> Result<levels::LevelPlan> {
    Ok(match kind {
        StrategyKind::Zigzag => zigzag::plan(shape, tool, opts)?,
        StrategyKind::Offset => offset::plan(shape, tool, opts)?,
        StrategyKind::Spiral => spiral::plan(shape, tool, opts)?,
    })
}

/// The toolpath without feed modulation or verification.
pub fn toolpath(
    kind: StrategyKind,
    shape: &PocketShape,
    tool: &Tool,
    opts: &PocketOptions,
) -> Result<Toolpath> {
    opts.validate(tool)?;
    let rough = plan_level(kind, shape, tool, opts)?;
    let finish = if opts.finish {
        let fo = PocketOptions {
            wall_stock: 0.0,
            ..opts.clone()
        };
        Some(finishing_plan(shape, tool, &fo)?)
    } else {
        None
    };
    Ok(levels::assemble(*tool, opts, &rough, finish.as_ref()))
}

/// Generates, modulates the feed and verifies.
pub fn generate(
    kind: StrategyKind,
    shape: &PocketShape,
    tool: &Tool,
    opts: &PocketOptions,
    sim: &SimOptions,
) -> Result<PocketResult> {
    let mut tp = toolpath(kind, shape, tool, opts)?;
    let s = opts.stepover_mm(tool);
    let nominal = nominal_engagement(s, tool.radius());
    // With a finishing pass the walls end at zero stock.
    let spec = StockSpec {
        outer: &shape.outer,
        islands: &shape.islands,
        wall_stock: if opts.finish { 0.0 } else { opts.wall_stock },
    };
    let simulation = stock::simulate(&tp, spec, nominal.to_degrees(), sim);
    if opts.modulate_feed {
        feed::modulate(&mut tp, &simulation.per_move, nominal, opts.slowdown);
    }
    let verification = stock::combine(&tp, spec, &simulation);
    Ok(PocketResult {
        toolpath: tp,
        verification,
        nominal_engagement_deg: nominal.to_degrees(),
        stepover_mm: s,
    })
}

/// The finishing pass: each boundary loop at `r` (no stock), entered from the roughing's last
/// loop.
fn finishing_plan(
    shape: &PocketShape,
    tool: &Tool,
    opts: &PocketOptions,
) -> Result<levels::LevelPlan> {
    let region = shape.offset(tool.radius());
    let rough = shape.offset(tool.radius() + opts.wall_stock.max(0.0));
    let mut cuts = Vec::new();
    for lp in region.loops() {
        let lp = if opts.direction == Direction::Climb {
            lp.clone()
        } else {
            shape::reversed(lp)
        };
        let first = lp.at(0).pos();
        let start = crate::geom::Point::new(first.x, first.y);
        let from = rough
            .loops()
            .filter_map(|l| l.closest_point(shape::v2(start), 1e-12))
            .min_by(|a, b| a.distance.total_cmp(&b.distance))
            .map_or(start, |c| shape::pt(c.seg_point));
        cuts.push(levels::Cut {
            entry: levels::CutEntry::Direct { from },
            path: chain::segs_from_vertices(&shape::closed_chain(&lp)),
        });
    }
    Ok(levels::LevelPlan { cuts })
}

/// What [`cycle_time`] computes, for reports.
pub const CYCLE_TIME_MODEL: &str = "jerk-limited look-ahead planner (motion::plan_toolpath)";

/// Cycle time of a toolpath on `machine`, s: the motion planner's total time.
pub fn cycle_time_on(tp: &Toolpath, machine: &crate::machine::Machine) -> Result<f64> {
    Ok(crate::motion::plan_toolpath(tp, machine)?.total_time())
}

/// Cycle time of a toolpath on the `hsm` preset, s.
pub fn cycle_time(tp: &Toolpath) -> Result<f64> {
    cycle_time_on(tp, &crate::machine::Machine::preset("hsm")?)
}
