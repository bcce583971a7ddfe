//! Holes: a drawing's circles drilled with canned cycles or helix-bored, in a short order.
//!
//! * **Finding** (`find`): every closed outline of the drawing that is a circle within a
//!   tolerance ([`Hole::from_outline`]: exact arcs, or a polygon from a spline) is a hole,
//!   unless it holds other outlines; [`select_holes`] keeps a diameter range. Layers are the
//!   readers' (`--layer`).
//! * **Which operation:** a hole whose diameter is the tool's within
//!   [`HoleOptions::diameter_tolerance`] is **drilled** with the canned cycle of
//!   [`HoleOptions::cycle`] (G81, G82 with a dwell, G83 pecks out to R, G73 chip-breaking
//!   pecks; the toolpath carries it as a [`Cycle`] so the writer
//!   writes the dialect's cycle while the planner and the simulation see its moves); a
//!   larger one is **bored** (`bore`: helix rings and a finishing circle with tangent
//!   leads); a smaller one is left out, as is a larger one with
//!   [`HoleOptions::drill_only`]. [`plan_holes`] does all three; [`drill`] and [`bore`]
//!   refuse a hole that is not theirs, naming it.
//! * **Pecks.** The peck asked for is the largest: when the depth from R to the bottom is
//!   within a rounding margin (`(2 + n)·0.002 mm` for `n` pecks) of a whole number of
//!   pecks, the peck is shortened to make the last one half a peck, so that the number of
//!   pecks a controller counts from the written (rounded) R, Z and Q is the one planned.
//! * **Order** ([`crate::strategy::order_tour`]): from the origin, nearest neighbour, then
//!   2-opt and segment moves, over the holes' centres.
//! * **Heights:** the tool travels between holes at the clearance level; a drilling cycle
//!   starts there and returns there (G98), or stays at the R plane between drilled holes
//!   (G99, [`HoleOptions::retract`]); a bore goes down to the R plane above its first ring.
//!   The toolpath starts at the clearance level above the origin and ends at that level.
//!
//! The result is checked by `crate::stock::verify_holes` (the job layer does it on the
//! program read back), which shares none of this code.

pub(crate) mod bore;
mod find;
mod options;

pub use crate::geom::{CIRCLE_TOLERANCE, Hole};
pub use bore::MIN_LEAD_RADIUS;
pub use find::{find_holes, select_holes};
pub use options::{DrillCycle, HoleOptions, MAX_TURNS, MIN_DIAMETER_TOLERANCE};

use crate::error::{Error, InputError};
use crate::geom::{Point, Point3};
use crate::strategy::order::order_tour;
use crate::toolpath::{Cycle, CycleKind, CycleRetract, Move, Tool, Toolpath};

/// What was done with a hole.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum HoleOp {
    /// Drilled with this canned cycle.
    Drill(CycleKind),
    /// Helix-bored.
    Bore {
        /// Helix rings (1 unless the hole is more than twice the tool's diameter).
        rings: usize,
        /// Helix turns per ring.
        turns: usize,
    },
    /// Left out: smaller than the tool.
    SmallerThanTool,
    /// Left out: larger than the tool, with drilling only.
    LargerThanTool,
}

impl HoleOp {
    /// True when the hole is cut.
    pub fn is_cut(&self) -> bool {
        matches!(self, HoleOp::Drill(_) | HoleOp::Bore { .. })
    }

    /// A short name: `drill`, `bore` or `skipped`.
    pub fn name(&self) -> &'static str {
        match self {
            HoleOp::Drill(_) => "drill",
            HoleOp::Bore { .. } => "bore",
            _ => "skipped",
        }
    }
}

impl std::fmt::Display for HoleOp {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            HoleOp::Drill(k) => write!(f, "{k}"),
            HoleOp::Bore { rings, turns } => write!(
                f,
                "helix bore, {rings} ring{} of {turns} turn{} and a finishing circle",
                if *rings == 1 { "" } else { "s" },
                if *turns == 1 { "" } else { "s" }
            ),
            HoleOp::SmallerThanTool => write!(f, "left out: smaller than the tool"),
            HoleOp::LargerThanTool => {
                write!(f, "left out: larger than the tool (drilling only)")
            }
        }
    }
}

/// One hole of a plan.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlannedHole {
    /// Its index among the holes found (1-based).
    pub index: usize,
    /// The hole.
    pub hole: Hole,
    /// What was done with it.
    pub op: HoleOp,
}

/// The holes' toolpath and what was done with each.
#[derive(Debug, Clone)]
pub struct HoleResult {
    /// The toolpath: from the clearance level, every hole cut, back at the clearance level.
    pub toolpath: Toolpath,
    /// The holes in cutting order, those left out last.
    pub holes: Vec<PlannedHole>,
}

/// Which holes an entry point takes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Mode {
    /// Each hole drilled, bored or left out.
    Auto,
    /// Every hole drilled.
    Drill,
    /// Every hole bored.
    Bore,
}

/// Plans every hole of `holes` (each with its 1-based index): drilled, bored or left out
/// (module docs). Refused when none can be cut, naming the first hole and why.
pub fn plan_holes(
    holes: &[(usize, Hole)],
    tool: &Tool,
    opts: &HoleOptions,
) -> Result<HoleResult, Error> {
    plan(holes, tool, opts, Mode::Auto)
}

/// Drills every hole of `holes` with the canned cycle; a hole whose diameter is not the
/// tool's is refused, naming it.
pub fn drill(
    holes: &[(usize, Hole)],
    tool: &Tool,
    opts: &HoleOptions,
) -> Result<HoleResult, Error> {
    plan(holes, tool, opts, Mode::Drill)
}

/// Helix-bores every hole of `holes`; a hole not larger than the tool is refused, naming it.
pub fn bore(holes: &[(usize, Hole)], tool: &Tool, opts: &HoleOptions) -> Result<HoleResult, Error> {
    plan(holes, tool, opts, Mode::Bore)
}

/// `Hole 3: ⌀5.000 mm at (10.000, 20.000)`.
pub fn describe(index: usize, hole: &Hole) -> String {
    format!(
        "hole {index}: ⌀{:.3} mm at ({:.3}, {:.3})",
        hole.diameter, hole.center.x, hole.center.y
    )
}

fn plan(
    holes: &[(usize, Hole)],
    tool: &Tool,
    opts: &HoleOptions,
    mode: Mode,
) -> Result<HoleResult, Error> {
    opts.validate(tool)?;
    if holes.is_empty() {
        return Err(InputError::new("holes", 0)
            .at("the drawing and --min-diameter / --max-diameter")
            .expected("at least one circle to drill or bore")
            .into());
    }
    let tol = opts.diameter_tolerance;
    let mut cut: Vec<PlannedHole> = Vec::new();
    let mut left: Vec<PlannedHole> = Vec::new();
    for &(index, hole) in holes {
        if !(hole.center.is_finite() && hole.diameter.is_finite() && hole.diameter > 0.0) {
            return Err(InputError::new("hole", describe(index, &hole))
                .expected("a finite centre and a diameter > 0")
                .into());
        }
        let d = hole.diameter - tool.diameter;
        let op = if d < -tol {
            HoleOp::SmallerThanTool
        } else if d <= tol {
            HoleOp::Drill(cycle_kind(opts))
        } else if opts.drill_only && mode == Mode::Auto {
            HoleOp::LargerThanTool
        } else {
            HoleOp::Bore { rings: 0, turns: 0 }
        };
        let refused = match (mode, op) {
            (Mode::Drill, HoleOp::Drill(_)) | (Mode::Bore, HoleOp::Bore { .. }) => None,
            (Mode::Drill, _) => Some(format!(
                "a hole of the tool's diameter {} mm (within {tol} mm) to drill",
                tool.diameter
            )),
            (Mode::Bore, _) => Some(format!(
                "a hole larger than the tool (⌀{} mm, by more than {tol} mm) to bore",
                tool.diameter
            )),
            (Mode::Auto, _) => None,
        };
        if let Some(expected) = refused {
            return Err(InputError::new("hole", describe(index, &hole))
                .at("--tool-diameter")
                .expected(expected)
                .into());
        }
        let planned = PlannedHole { index, hole, op };
        if op.is_cut() {
            cut.push(planned);
        } else {
            left.push(planned);
        }
    }
    if cut.is_empty() {
        let first = left.first().copied();
        let (what, why) = first.map_or((String::new(), String::new()), |p| {
            (describe(p.index, &p.hole), p.op.to_string())
        });
        return Err(InputError::new("holes to cut", 0)
            .at("--tool-diameter")
            .expected(format!(
                "a hole the tool ⌀{} mm can drill or bore ({what}: {why})",
                tool.diameter
            ))
            .into());
    }
    let ends: Vec<(Point, Point)> = cut.iter().map(|p| (p.hole.center, p.hole.center)).collect();
    let order = order_tour(&ends, Point::ORIGIN);
    let clear = opts.clearance();
    let mut tp = Toolpath::new(*tool, Point3::new(0.0, 0.0, clear));
    let mut ordered: Vec<PlannedHole> = Vec::with_capacity(cut.len());
    for &i in &order {
        let mut p = cut[i];
        match p.op {
            HoleOp::Drill(kind) => {
                // G99 keeps the tool at R between drilled holes; otherwise up first.
                let at_r = opts.retract == CycleRetract::R
                    && ordered
                        .last()
                        .is_some_and(|q| matches!(q.op, HoleOp::Drill(_)));
                if !at_r {
                    up_to(&mut tp, clear);
                }
                tp.push_cycle(Cycle {
                    kind: adjusted(kind, opts),
                    at: p.hole.center,
                    r: opts.r_plane(),
                    bottom: opts.bottom(),
                    retract: opts.retract,
                    feed: opts.drill_feed,
                    start: 0,
                    end: 0,
                });
            }
            HoleOp::Bore { .. } => {
                up_to(&mut tp, clear);
                let b = bore::bore_hole(&mut tp, &p.hole, tool, opts);
                p.op = HoleOp::Bore {
                    rings: b.rings,
                    turns: b.turns,
                };
            }
            _ => {}
        }
        ordered.push(p);
    }
    up_to(&mut tp, clear);
    ordered.extend(left);
    tp.check_cycles()
        .map_err(|e| Error::from(e).engine_made("planning the holes"))?;
    Ok(HoleResult {
        toolpath: tp,
        holes: ordered,
    })
}

/// A rapid straight up to `z` when the tool is below it.
fn up_to(tp: &mut Toolpath, z: f64) {
    let e = tp.end();
    if e.z < z {
        tp.push(Move::rapid(Point3::new(e.x, e.y, z)));
    }
}

/// The cycle of the options (pecks as asked; [`adjusted`] shortens them).
fn cycle_kind(opts: &HoleOptions) -> CycleKind {
    match opts.cycle {
        DrillCycle::Drill => CycleKind::Drill,
        DrillCycle::Dwell { seconds } => CycleKind::Dwell { seconds },
        DrillCycle::Peck { step } => CycleKind::Peck { step },
        DrillCycle::ChipBreak { step } => CycleKind::ChipBreak { step },
    }
}

/// The cycle with its peck shortened where the depth is nearly a whole number of pecks
/// (module docs).
fn adjusted(kind: CycleKind, opts: &HoleOptions) -> CycleKind {
    let span = opts.r_plane() - opts.bottom();
    let fix = |step: f64| {
        let x = span / step;
        let margin = ((2.0 + x) * 0.002 / step).min(0.25);
        if (x - x.round()).abs() < margin {
            span / (x.round() + 0.5)
        } else {
            step
        }
    };
    match kind {
        CycleKind::Peck { step } => CycleKind::Peck { step: fix(step) },
        CycleKind::ChipBreak { step } => CycleKind::ChipBreak { step: fix(step) },
        k => k,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn holes() -> Vec<(usize, Hole)> {
        [
            (10.0, 10.0, 6.0),
            (40.0, 12.0, 6.0),
            (25.0, 30.0, 10.0),
            (60.0, 5.0, 4.0),
        ]
        .iter()
        .enumerate()
        .map(|(i, &(x, y, d))| (i + 1, Hole::new(Point::new(x, y), d)))
        .collect()
    }

    #[test]
    fn holes_are_drilled_bored_or_left_out() {
        let tool = Tool::flat(6.0).unwrap();
        let r = plan_holes(&holes(), &tool, &HoleOptions::default()).unwrap();
        let ops: Vec<(usize, &str)> = r.holes.iter().map(|p| (p.index, p.op.name())).collect();
        assert_eq!(ops.len(), 4);
        assert_eq!(ops[3], (4, "skipped"));
        assert_eq!(r.toolpath.cycles.len(), 2);
        r.toolpath.check_cycles().unwrap();
        assert!(ops.contains(&(3, "bore")));
        // Drill only: the bore is left out too.
        let only = HoleOptions::default().with_drill_only(true);
        let r = plan_holes(&holes(), &tool, &only).unwrap();
        assert_eq!(r.holes.iter().filter(|p| p.op.is_cut()).count(), 2);
        // The strict entry points name the hole that is not theirs.
        let e = drill(&holes(), &tool, &HoleOptions::default()).unwrap_err();
        assert!(e.to_string().contains("hole 3"), "{e}");
        let e = bore(&holes(), &tool, &HoleOptions::default()).unwrap_err();
        assert!(e.to_string().contains("hole 1"), "{e}");
        let big = Tool::flat(20.0).unwrap();
        let e = plan_holes(&holes(), &big, &HoleOptions::default()).unwrap_err();
        assert!(e.to_string().contains("smaller than the tool"), "{e}");
    }

    #[test]
    fn pecks_near_a_whole_number_are_shortened_to_leave_half_a_peck() {
        // R 1 to bottom −9: 10 mm, pecks of 2.5 would be exactly 4.
        let opts = HoleOptions::default()
            .with_depth(9.0)
            .with_retract_height(1.0);
        let CycleKind::Peck { step } = adjusted(CycleKind::Peck { step: 2.5 }, &opts) else {
            panic!()
        };
        assert!((step - 10.0 / 4.5).abs() < 1e-12);
        let CycleKind::Peck { step } = adjusted(CycleKind::Peck { step: 3.0 }, &opts) else {
            panic!()
        };
        assert!((step - 3.0).abs() < 1e-15);
    }
}
