//! A whole part: every pocket of a drawing cut in one program.
//!
//! [`generate_part`] plans each pocket on its own ([`super::generate`], or [`super::auto`]
//! per pocket: each pocket gets the fastest verified strategy), with its own entry, levels
//! and feed profile, orders the pockets to keep the rapids between them short
//! ([`order_pockets`]) and joins their toolpaths: the tool leaves a pocket at the clearance
//! height (every pocket's toolpath ends with a retract there and starts there), and a rapid at
//! that height takes it to the next pocket's start. The joined program is verified as a whole
//! by [`crate::stock::verify_part`], which finds from the geometry alone which moves cut
//! which pocket (a single pocket's program is its toolpath, verified by `generate` already).
//!
//! A pocket a strategy refuses as bad input is left out with a [`PartPocket::skipped`]
//! reason, so the rest of the part is still cut, when the verifier's reach map
//! ([`stock::reachable`]) finds no place in it for the tool (narrower than the tool, say);
//! otherwise the refusal is the part's (its program would leave material `verify` finds).
//! When every pocket is refused the first pocket's error is returned, naming the largest
//! tool diameter that fits the widest pocket (the reach map again, by bisection).
//!
//! **Order.** The cost of going from pocket `i` to pocket `j` is the rapid from the end of
//! `i`'s toolpath to the start of `j`'s (`d(e_i, s_j)`, not symmetric); the tour starts at the
//! origin (where the program starts) and is made short by [`crate::strategy::order_tour`]
//! (nearest neighbour, then 2-opt and segment moves).

use super::auto;
use super::{PocketOptions, PocketResult, PocketShape, StrategyKind};
use crate::error::{Error, Result};
use crate::geom::{Point, Point3};
use crate::stock::{self, PartVerification, SimOptions, StockSpec};
use crate::strategy::order::order_tour;
use crate::toolpath::{Move, Tool, Toolpath};
use rayon::prelude::*;

/// One pocket of a part.
#[derive(Debug, Clone)]
pub struct PartPocket {
    /// Its index in the drawing's list (1-based, as `--select` takes it).
    pub index: usize,
    /// Area of material, mm².
    pub area_mm2: f64,
    /// The strategy that cut it.
    pub kind: StrategyKind,
    /// Its toolpath and verification (`None` when skipped).
    pub result: Option<PocketResult>,
    /// Its cycle time alone, s (`None` when skipped).
    pub cycle_time_s: Option<f64>,
    /// Why it was left out (`None` when cut).
    pub skipped: Option<String>,
    /// With `auto`: every strategy tried on it.
    pub auto: Option<Vec<auto::Candidate>>,
}

/// A whole part's program.
#[derive(Debug, Clone)]
pub struct PartResult {
    /// The pockets, in cutting order (skipped ones last).
    pub pockets: Vec<PartPocket>,
    /// The joined toolpath.
    pub toolpath: Toolpath,
    /// The whole program's verification, against the pockets cut.
    pub verification: PartVerification,
}

/// What to cut each pocket with.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PartStrategy {
    /// One strategy for every pocket.
    One(StrategyKind),
    /// The fastest verified of the three, per pocket (`auto`).
    Auto,
}

/// Plans, orders, joins and verifies every pocket of `shapes` (each with its 1-based index in
/// the drawing); `time` gives a toolpath's cycle time on the machine (the strategy layer does
/// not plan motion).
pub fn generate_part(
    shapes: &[(usize, PocketShape)],
    strategy: PartStrategy,
    tool: &Tool,
    opts: &PocketOptions,
    sim: &SimOptions,
    time: &(dyn Fn(&Toolpath) -> Result<f64> + Sync),
) -> Result<PartResult> {
    let stock_left = if opts.finish { 0.0 } else { opts.wall_stock };
    let mut cut: Vec<PartPocket> = Vec::new();
    let mut skipped: Vec<PartPocket> = Vec::new();
    let mut first_error: Option<Error> = None;
    // Each pocket is planned and timed on its own, side by side; the results are taken in
    // the drawing's order below (the first failure in that order is the one reported).
    let plans: Vec<_> = shapes
        .par_iter()
        .map(|(_, shape)| {
            let planned = plan_one(shape, strategy, tool, opts, sim, time);
            let timed = planned.as_ref().ok().map(|(_, r, _)| time(&r.toolpath));
            (planned, timed)
        })
        .collect();
    for ((index, shape), (planned, timed)) in shapes.iter().zip(plans) {
        let area = crate::geom::area_less_islands(&shape.outer, &shape.islands);
        match planned {
            Ok((kind, r, cands)) => {
                let t = timed
                    .unwrap_or_else(|| Err(Error::internal("an untimed pocket")))
                    .map_err(|e| e.engine_made(&format!("timing pocket {index}")))?;
                cut.push(PartPocket {
                    index: *index,
                    area_mm2: area,
                    kind,
                    result: Some(r),
                    cycle_time_s: Some(t),
                    skipped: None,
                    auto: cands,
                });
            }
            // Left out only where the verifier's reach map finds no place for the tool: a
            // pocket the tool could cut and the strategy refused is the whole part's refusal.
            Err(Error::Input(e))
                if !stock::reachable(
                    spec_of(shape, stock_left),
                    tool.radius(),
                    sim.cell_for(tool),
                ) =>
            {
                if shapes.len() == 1 {
                    return Err(largest_tool(e, shapes, stock_left).into());
                }
                skipped.push(PartPocket {
                    index: *index,
                    area_mm2: area,
                    kind: match strategy {
                        PartStrategy::One(k) => k,
                        PartStrategy::Auto => StrategyKind::Offset,
                    },
                    result: None,
                    cycle_time_s: None,
                    skipped: Some(e.to_string()),
                    auto: None,
                });
                first_error.get_or_insert(Error::Input(e));
            }
            Err(e) => return Err(e),
        }
    }
    if cut.is_empty() {
        return Err(match first_error {
            Some(Error::Input(e)) => largest_tool(e, shapes, stock_left).into(),
            Some(e) => e,
            None => Error::internal("a part without pockets reached the planner"),
        });
    }
    let ends: Vec<(Point, Point)> = cut
        .iter()
        .filter_map(|p| p.result.as_ref())
        .map(|r| (r.toolpath.start.xy(), r.toolpath.end().xy()))
        .collect();
    let order = order_tour(&ends, Point::ORIGIN);
    let mut slots: Vec<Option<PartPocket>> = cut.into_iter().map(Some).collect();
    let mut ordered: Vec<PartPocket> = order.iter().filter_map(|&i| slots[i].take()).collect();
    let toolpath = join(
        ordered
            .iter()
            .filter_map(|p| p.result.as_ref().map(|r| &r.toolpath)),
        *tool,
        opts.clearance_height,
    );
    let shapes_cut: Vec<&PocketShape> = ordered
        .iter()
        .filter_map(|p| shapes.iter().find(|(i, _)| *i == p.index).map(|(_, s)| s))
        .collect();
    let specs: Vec<StockSpec<'_>> = shapes_cut.iter().map(|s| spec_of(s, stock_left)).collect();
    let nominal = super::nominal_engagement(opts.stepover_mm(tool), tool.radius()).to_degrees();
    // One pocket: the program is its toolpath, which `generate` verified already (level by
    // level against its sections, inclined walls included).
    let single = match ordered.as_slice() {
        [only] => only
            .result
            .as_ref()
            .map(|r| (r.verification.clone(), r.cutting_moves.clone())),
        _ => None,
    };
    let verification = match single {
        Some((v, cutting_moves)) => PartVerification {
            total: v.clone(),
            cutting_moves,
            pockets: vec![v],
            cuts_outside: 0,
            unreachable: Vec::new(),
        },
        None => stock::verify_part(&toolpath, &specs, nominal, sim),
    };
    ordered.extend(skipped);
    Ok(PartResult {
        pockets: ordered,
        toolpath,
        verification,
    })
}

/// Joins toolpaths that each start and end at the clearance height `clear`: a rapid at that
/// height from the end of one to the start of the next; levels and canned cycles kept,
/// renumbered.
pub fn join<'a>(paths: impl IntoIterator<Item = &'a Toolpath>, tool: Tool, clear: f64) -> Toolpath {
    let mut out: Option<Toolpath> = None;
    for tp in paths {
        let joined = out.get_or_insert_with(|| Toolpath::new(tool, tp.start));
        let end = joined.end();
        if end != tp.start {
            // Up first where the last path did not end at the clearance height.
            if end.z < clear {
                joined.push(Move::rapid(Point3::new(end.x, end.y, clear)));
            }
            joined.push(Move::rapid(Point3::from_xy(
                tp.start.xy(),
                clear.max(tp.start.z),
            )));
            if tp.start.z < clear {
                joined.push(Move::rapid(tp.start));
            }
        }
        joined.append(tp);
    }
    out.unwrap_or_else(|| Toolpath::new(tool, Point3::new(0.0, 0.0, clear)))
}

/// One pocket planned with `strategy` (module docs of [`generate_part`]).
fn plan_one(
    shape: &PocketShape,
    strategy: PartStrategy,
    tool: &Tool,
    opts: &PocketOptions,
    sim: &SimOptions,
    time: &(dyn Fn(&Toolpath) -> Result<f64> + Sync),
) -> Result<(StrategyKind, PocketResult, Option<Vec<auto::Candidate>>)> {
    match strategy {
        PartStrategy::One(kind) => {
            auto::arcs_or_chords(kind, shape, tool, opts, sim, time).map(|(r, _)| (kind, r, None))
        }
        PartStrategy::Auto => {
            let cands = auto::plan_all(shape, tool, opts, sim, time);
            match auto::choose(&cands).and_then(|i| {
                cands
                    .get(i)
                    .and_then(|c| c.result().cloned().map(|r| (c.kind, r)))
            }) {
                Some((kind, r)) => Ok((kind, r, Some(cands))),
                None => Err(auto::none_verified(&cands)),
            }
        }
    }
}

/// `e` (a tool that fits none of `shapes`) with the largest tool diameter that fits the
/// widest of them, as the verifier's reach map finds it ([`stock::reachable`], on a grid of
/// a 200th of the pocket's size, by bisection to 0.5 % from a thousandth of its width),
/// rounded down to 0.01 mm; or that none fits with the wall stock.
fn largest_tool(
    e: crate::error::InputError,
    shapes: &[(usize, PocketShape)],
    wall_stock: f64,
) -> crate::error::InputError {
    // Widest box first: a pocket is bisected only when it beats the best so far by the
    // bisection's own 0.5 % (one reach map for each of many like pockets), and the search
    // ends at the first box too narrow to beat it.
    let mut order: Vec<(usize, &PocketShape, f64)> = shapes
        .iter()
        .map(|(i, shape)| {
            let b = shape.outer.bounds();
            (*i, shape, 0.5 * b.width().min(b.height()))
        })
        .collect();
    order.sort_by(|a, b| b.2.total_cmp(&a.2).then(a.0.cmp(&b.0)));
    let mut best: Option<(usize, f64)> = None;
    for (i, shape, bound) in order {
        let spec = spec_of(shape, wall_stock);
        let b = shape.outer.bounds();
        let cell = b.width().max(b.height()) / 200.0;
        let mut hi = bound;
        let mut lo = best.map_or(1e-3 * bound, |(_, r)| 1.005 * r);
        if hi <= lo {
            break;
        }
        if !stock::reachable(spec, lo, cell) {
            continue;
        }
        for _ in 0..40 {
            if hi - lo <= 0.005 * hi {
                break;
            }
            let mid = 0.5 * (lo + hi);
            if stock::reachable(spec, mid, cell) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        best = Some((i, lo));
    }
    let (index, d) = best.map_or((0, 0.0), |(i, r)| (i, 2.0 * r));
    let d = (d * 100.0).floor() / 100.0;
    let room = if d <= 0.0 {
        if wall_stock <= 0.0 {
            return e;
        }
        format!("no tool fits with a wall stock of {wall_stock} mm")
    } else if shapes.len() == 1 {
        format!("the largest that fits is {d} mm")
    } else {
        format!(
            "the largest that fits one of these {} pockets is {d} mm (pocket {index})",
            shapes.len()
        )
    };
    let expected = match &e.expected {
        Some(x) => format!("{x}; {room}"),
        None => room,
    };
    e.expected(expected)
}

/// The stock simulation's view of `shape`, `wall_stock` left on its walls.
fn spec_of(shape: &PocketShape, wall_stock: f64) -> StockSpec<'_> {
    StockSpec {
        outer: &shape.outer,
        islands: &shape.islands,
        wall_stock,
    }
}
