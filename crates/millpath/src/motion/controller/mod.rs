//! Controller models: how a given controller's trajectory planner treats corners, arcs, short
//! blocks and look-ahead, as a small piece the planner is given.
//!
//! The planner ([`super::plan`], [`super::stream`]) groups blocks into spans and times them
//! with jerk-limited (or, with unlimited jerk, trapezoidal) profiles under a whole-program
//! look-ahead. What differs from controller to controller is *what the blocks are* and *what
//! bounds them*; a controller model turns the program's moves into prepared blocks, each with
//! * its geometry (the move itself, or what the controller makes of it: trimmed by a blend,
//!   merged with its neighbours, a blend arc inserted at a corner),
//! * its path limits (speed, tangential acceleration and jerk: the arc rule, the per-cycle
//!   cap on short blocks, the acceleration fractions),
//! * the speed cap at its junction with the previous block (the corner rule, the blend rule,
//!   the controller's finite look-ahead).
//!
//! The machine profile chooses the model (`controller = "generic" | "sinumerik" |
//! "linuxcnc"`, [`crate::machine::Controller`]):
//!
//! | model | geometry | limits | junctions |
//! |---|---|---|---|
//! | `generic` | as programmed | [`super::limits`]: axis limits projected, arcs share `η_a`, `η_j` | [`super::limits`]: blend within the tolerance, curvature step over one IPO cycle |
//! | `sinumerik` | as programmed | as `generic` | [`sinumerik`]: G64/G642 rounding, curvature steps smoothed within the tolerance |
//! | `linuxcnc` | [`linuxcnc`]: LinuxCNC 2.9's queue: naive-CAM merging, blend arcs, trims | LinuxCNC's arc cap, ½ tangential acceleration, `L/T` per-cycle cap | LinuxCNC's tangent (kink) test, parabolic blends, stops, 50-segment look-ahead |

pub(crate) mod linuxcnc;
pub(crate) mod sinumerik;

use super::limits::{JunctionMode, block_limits, junction_cap, junction_mode};
use super::path::BlockGeometry;
use super::path::check_move;
use super::profile::Limits1;
use crate::error::Error;
use crate::geom::Point3;
use crate::machine::{Controller, Machine};
use crate::toolpath::{Corner, Move};

/// One block as the planner times it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Prepared {
    /// Start point.
    pub from: Point3,
    /// The move (kind, feed and corner of the input move it comes from; `to` is this block's
    /// end).
    pub mv: Move,
    /// Geometry (`None` for dwells and zero-length moves).
    pub geom: Option<BlockGeometry>,
    /// Path limits (ignored without geometry).
    pub limits: Limits1,
    /// Speed cap at the junction with the previous block with geometry.
    pub cap_in: f64,
    /// Index of the input move.
    pub origin: usize,
    /// The controller runs each block at its own acceleration: blocks share a span only
    /// with equal limits.
    pub exact_limits: bool,
    /// Time the controller waits at rest before this block (settling at an exact stop).
    pub settle_before: f64,
}

/// The controller model of a machine, fed one move at a time.
pub(crate) enum Shaper<'m> {
    /// Per-block rules (`generic`, `sinumerik`): one block per move.
    Rules(Box<RuleShaper<'m>>),
    /// LinuxCNC's segment queue.
    LinuxCnc(Box<linuxcnc::Queue<'m>>),
}

impl<'m> Shaper<'m> {
    /// The model of `machine`.
    pub(crate) fn new(machine: &'m Machine) -> Self {
        match machine.controller {
            Controller::LinuxCnc => Shaper::LinuxCnc(Box::new(linuxcnc::Queue::new(machine))),
            c => Shaper::Rules(Box::new(RuleShaper {
                machine,
                sinumerik: (c == Controller::Sinumerik).then(sinumerik::Curvature::default),
                last: None,
            })),
        }
    }

    /// Takes move `i` from `from`; appends the blocks that are ready to `out`.
    pub(crate) fn push(
        &mut self,
        i: usize,
        from: Point3,
        m: &Move,
        out: &mut Vec<Prepared>,
    ) -> Result<(), Error> {
        let g = check_move(i, from, m)?;
        match self {
            Shaper::Rules(r) => {
                out.push(r.prepare(i, from, m, g));
                Ok(())
            }
            Shaper::LinuxCnc(q) => q.push(i, from, m, g, out),
        }
    }

    /// The end of the program: appends the blocks still held; returns the time the
    /// controller then waits at rest (exact-stop settling: the program ends in an exact
    /// stop).
    pub(crate) fn finish(&mut self, out: &mut Vec<Prepared>) -> Result<f64, Error> {
        match self {
            Shaper::Rules(r) => Ok(if r.last.is_some() {
                r.machine.exact_stop_time
            } else {
                0.0
            }),
            Shaper::LinuxCnc(q) => q.finish(out).map(|()| 0.0),
        }
    }
}

/// The per-block rules of the `generic` and `sinumerik` models. Both wait
/// [`Machine::exact_stop_time`] at rest at every exact stop and at the program's end (the
/// `linuxcnc` model waits for none: LinuxCNC's planner has no exact-stop window).
pub(crate) struct RuleShaper<'m> {
    machine: &'m Machine,
    /// The sinumerik model's curvature state (`None`: generic).
    sinumerik: Option<sinumerik::Curvature>,
    /// The last block with geometry: its geometry, move and path limits.
    last: Option<(BlockGeometry, Move, Limits1)>,
}

impl RuleShaper<'_> {
    fn prepare(&mut self, i: usize, from: Point3, m: &Move, g: Option<BlockGeometry>) -> Prepared {
        let machine = self.machine;
        let zero = Limits1 {
            v: 0.0,
            a: 1.0,
            j: 1.0,
        };
        let mut settle_before = 0.0;
        let (limits, cap_in) = match &g {
            Some(g) => {
                let lim = block_limits(g, m, machine);
                let cap = match &self.last {
                    Some((pg, pm, pl)) => {
                        let mode = junction_mode(pm.corner, machine);
                        // The planner keeps min(cap, the blocks' speed limits).
                        let ceiling = pl.v.min(lim.v);
                        let mut cap = match &mut self.sinumerik {
                            Some(c) => c.junction_cap(pg, g, mode, machine, ceiling),
                            None => junction_cap(pg, g, mode, machine),
                        };
                        // An exact stop (G61.1, G60, G9, G09, Fanuc's G61) stops at the end
                        // of its move even where the next one goes on in the same direction.
                        if pm.corner == Corner::ExactStop {
                            cap = 0.0;
                        }
                        // Every stop of an exact-stop mode settles, whatever dialect the
                        // program is in: the move's `Corner::ExactStop`, or a corner under a
                        // zero tolerance (which the axes pass at speed where it is tangent).
                        if mode == JunctionMode::Stop && cap <= 0.0 {
                            settle_before = machine.exact_stop_time;
                        }
                        cap
                    }
                    None => 0.0,
                };
                self.last = Some((*g, *m, lim));
                (lim, cap)
            }
            None => {
                if m.is_feed() || matches!(m.kind, crate::toolpath::MoveKind::Rapid) {
                    // A zero-length move keeps the previous block's junction.
                } else {
                    // A dwell after an exact stop waits for it to settle first.
                    if self
                        .last
                        .as_ref()
                        .is_some_and(|(_, pm, _)| pm.corner == Corner::ExactStop)
                    {
                        settle_before = machine.exact_stop_time;
                    }
                    self.last = None;
                    if let Some(c) = &mut self.sinumerik {
                        *c = sinumerik::Curvature::default();
                    }
                    // (a dwell: the curvature history starts again)
                }
                (zero, 0.0)
            }
        };
        Prepared {
            from,
            mv: *m,
            geom: g,
            limits,
            cap_in,
            origin: i,
            exact_limits: false,
            settle_before,
        }
    }
}
