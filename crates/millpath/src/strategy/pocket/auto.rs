//! `--strategy auto`: every strategy planned, verified and timed; the fastest verified one
//! kept.
//!
//! [`plan_all`] plans the spiral, offset and zigzag (and the adaptive, at its own stepover
//! and a level per flute length, where the caller gives the flute length) with
//! [`super::generate`] (in parallel,
//! with rayon: each reads only the shared inputs and makes its own toolpath), which also runs
//! the material-removal verification; a candidate is **verified** when the verifier finds no
//! problem ([`crate::stock::Verification::problems`]: no gouge, no uncut material beyond
//! [`crate::stock::UNCUT_AREA_TOLERANCE`], no rapid through material, no plunge). Each
//! candidate is timed with the caller's `time` (the motion planner on the chosen machine:
//! the strategy layer does not plan motion itself). [`choose`] keeps the fastest verified
//! candidate (ties: the first in [`ORDER`]); a candidate that fails verification, or that the
//! strategy cannot plan, is never chosen.
//!
//! `--arcs` is a request for the faster form, not a promise of G2/G3: [`arcs_or_chords`]
//! plans the path with arcs and with G1 chords, verifies and times both, and keeps the arcs
//! unless the chords are verified and faster on the machine (then with a note). A
//! jerk-limited machine pays for the jump in curvature where an exact arc meets a line, which
//! the chords' curvature ramps ([`super::spiral`]) avoid; a trapezoidal planner such as
//! LinuxCNC's does not, and there the arcs' fewer, longer moves win.

use super::{PocketOptions, PocketResult, PocketShape, StrategyKind, generate};
use crate::error::{Error, Result};
use crate::stock::{Problem, SimOptions};
use crate::toolpath::{Tool, Toolpath};
use rayon::prelude::*;

/// The strategies `auto` tries, in the order ties are broken and reports list them.
pub const ORDER: [StrategyKind; 3] = [
    StrategyKind::Spiral,
    StrategyKind::Offset,
    StrategyKind::Zigzag,
];

/// What became of one strategy.
#[derive(Debug, Clone)]
pub enum Outcome {
    /// Planned, verified and timed.
    Verified {
        /// The toolpath and the verifier's findings.
        result: Box<PocketResult>,
        /// Cycle time on the machine, s.
        cycle_time_s: f64,
    },
    /// Planned, but the verifier found problems (or the path could not be timed).
    Unverified {
        /// The toolpath and the verifier's findings.
        result: Box<PocketResult>,
        /// Cycle time on the machine, s, when it could be timed.
        cycle_time_s: Option<f64>,
        /// What the verifier found wrong with it.
        problems: Vec<Problem>,
        /// Why it could not be timed, when it could not.
        timing_error: Option<Error>,
    },
    /// The strategy could not plan the pocket.
    Failed(Error),
}

/// One strategy's outcome.
#[derive(Debug, Clone)]
pub struct Candidate {
    /// The strategy.
    pub kind: StrategyKind,
    /// What became of it.
    pub outcome: Outcome,
}

impl Candidate {
    /// The planned toolpath and its verification, if the strategy planned one.
    pub fn result(&self) -> Option<&PocketResult> {
        match &self.outcome {
            Outcome::Verified { result, .. } | Outcome::Unverified { result, .. } => Some(result),
            Outcome::Failed(_) => None,
        }
    }

    /// Cycle time, s, if the strategy planned a path that could be timed.
    pub fn cycle_time_s(&self) -> Option<f64> {
        match &self.outcome {
            Outcome::Verified { cycle_time_s, .. } => Some(*cycle_time_s),
            Outcome::Unverified { cycle_time_s, .. } => *cycle_time_s,
            Outcome::Failed(_) => None,
        }
    }

    /// Cutting path length, mm, if the strategy planned a path.
    pub fn path_length_mm(&self) -> Option<f64> {
        self.result().map(|r| r.toolpath.cut_length())
    }

    /// True when the path passed the verification.
    pub fn verified(&self) -> bool {
        matches!(self.outcome, Outcome::Verified { .. })
    }

    /// Why the candidate cannot be chosen (`None` when verified).
    pub fn why_not(&self) -> Option<String> {
        match &self.outcome {
            Outcome::Verified { .. } => None,
            Outcome::Unverified {
                problems,
                timing_error,
                ..
            } => {
                let mut why: Vec<String> = problems.iter().map(ToString::to_string).collect();
                why.extend(timing_error.iter().map(ToString::to_string));
                Some(why.join("; "))
            }
            Outcome::Failed(e) => Some(e.to_string()),
        }
    }
}

/// Plans, verifies and times every strategy of [`ORDER`] (in parallel), and the adaptive
/// where `opts.adaptive.auto_step_down` is given (at that step-down and
/// [`super::AdaptiveOptions::AUTO_STEPOVER`]: one level per flute length, as the adaptive
/// runs alone); `time` gives a toolpath's cycle time on the chosen machine. A toolpath `time` refuses is the engine's
/// own, so its refusal is an internal error ([`Error::engine_made`]).
pub fn plan_all(
    shape: &PocketShape,
    tool: &Tool,
    opts: &PocketOptions,
    sim: &SimOptions,
    time: &(dyn Fn(&Toolpath) -> Result<f64> + Sync),
) -> Vec<Candidate> {
    let adaptive = opts.adaptive.auto_step_down.map(|d| {
        opts.clone()
            .with_stepover(super::Stepover::Fraction(
                super::AdaptiveOptions::AUTO_STEPOVER,
            ))
            .with_step_down(d)
    });
    let runs: Vec<(StrategyKind, &PocketOptions)> = ORDER
        .iter()
        .map(|&k| (k, opts))
        .chain(adaptive.as_ref().map(|o| (StrategyKind::Adaptive, o)))
        .collect();
    runs.par_iter()
        .map(|&(kind, opts)| {
            let planned = if opts.spiral.arcs {
                arcs_or_chords(kind, shape, tool, opts, sim, time).map(|(r, _)| r)
            } else {
                generate(kind, shape, tool, opts, sim)
            };
            let outcome = match planned {
                Err(e) => Outcome::Failed(e),
                Ok(result) => {
                    let timed = time(&result.toolpath).map_err(|e| {
                        e.engine_made(&format!("timing the {} toolpath", kind.name()))
                    });
                    let problems = result.verification.problems();
                    match timed {
                        Ok(t) if problems.is_empty() => Outcome::Verified {
                            result: Box::new(result),
                            cycle_time_s: t,
                        },
                        Ok(t) => Outcome::Unverified {
                            result: Box::new(result),
                            cycle_time_s: Some(t),
                            problems,
                            timing_error: None,
                        },
                        Err(e) => Outcome::Unverified {
                            result: Box::new(result),
                            cycle_time_s: None,
                            problems,
                            timing_error: Some(e),
                        },
                    }
                }
            };
            Candidate { kind, outcome }
        })
        .collect()
}

/// With `opts.arcs`: the path planned with arcs and with G1 chords (`arcs: false`), each
/// verified by [`generate`] and timed with `time`; the chords are kept, with a note giving
/// both times, when they are verified and faster (or when only they are verified), else the
/// arcs. Returns the kept path and its time (`None` when it could not be timed). Without
/// `opts.arcs` it is [`generate`] and `time`.
pub fn arcs_or_chords(
    kind: StrategyKind,
    shape: &PocketShape,
    tool: &Tool,
    opts: &PocketOptions,
    sim: &SimOptions,
    time: &(dyn Fn(&Toolpath) -> Result<f64> + Sync),
) -> Result<(PocketResult, Option<f64>)> {
    let timed = |r: PocketResult| {
        let t = time(&r.toolpath).ok();
        (r, t)
    };
    let (arcs, t_arcs) = timed(generate(kind, shape, tool, opts, sim)?);
    if !opts.spiral.arcs {
        return Ok((arcs, t_arcs));
    }
    let chord_opts = opts.clone().with_arcs(false);
    let Ok(chords) = generate(kind, shape, tool, &chord_opts, sim) else {
        return Ok((arcs, t_arcs));
    };
    let (mut chords, t_chords) = timed(chords);
    let ok = |r: &PocketResult, t: Option<f64>| r.verification.problems().is_empty() && t.is_some();
    let arcs_ok = ok(&arcs, t_arcs);
    let chords_ok = ok(&chords, t_chords);
    let chords_faster = match (t_chords, t_arcs) {
        (Some(c), Some(a)) => c < a,
        (Some(_), None) => true,
        _ => false,
    };
    if chords_ok && (!arcs_ok || chords_faster) {
        let faster = match (t_chords, t_arcs) {
            (Some(c), Some(a)) if arcs_ok => Some((c, a)),
            _ => None,
        };
        chords
            .notes
            .push(super::PocketNote::ChordsInsteadOfArcs { faster });
        return Ok((chords, t_chords));
    }
    Ok((arcs, t_arcs))
}

/// The index of the fastest verified candidate (the first of equal ones), `None` when none
/// is verified.
pub fn choose(candidates: &[Candidate]) -> Option<usize> {
    candidates
        .iter()
        .enumerate()
        .filter_map(|(i, c)| match c.outcome {
            Outcome::Verified { cycle_time_s, .. } => Some((i, cycle_time_s)),
            _ => None,
        })
        .min_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)))
        .map(|(i, _)| i)
}

/// The error when no candidate is verified: the user's input error when every strategy
/// refused the pocket as bad input (offset's, else zigzag's, else the spiral's, naming what
/// all three said), else an internal error naming what each strategy did (the verifier is
/// the engine's own check).
pub fn none_verified(candidates: &[Candidate]) -> Error {
    let each = candidates
        .iter()
        .map(|c| {
            format!(
                "{}: {}",
                c.kind.name(),
                c.why_not().unwrap_or_else(|| "verified".to_owned())
            )
        })
        .collect::<Vec<_>>()
        .join("; ");
    // Offset's refusal first: it cuts any pocket a tool fits in, so its reason is the
    // most general (the spiral's may only be that it takes no islands).
    let by_preference = [
        StrategyKind::Offset,
        StrategyKind::Zigzag,
        StrategyKind::Spiral,
    ];
    let first_input = by_preference.iter().find_map(|k| {
        candidates
            .iter()
            .filter(|c| c.kind == *k)
            .find_map(|c| match &c.outcome {
                Outcome::Failed(Error::Input(e)) => Some(e.clone()),
                _ => None,
            })
    });
    let all_input = candidates
        .iter()
        .all(|c| matches!(c.outcome, Outcome::Failed(Error::Input(_))));
    match first_input {
        Some(e) if all_input => {
            let own = e.expected.clone().unwrap_or_default();
            Error::Input(e.expected(format!(
                "{own} (--strategy auto: every strategy refused the pocket: {each})"
            )))
        }
        _ => Error::internal(format!(
            "--strategy auto: no strategy gave a verified path ({each}); nothing written"
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stock::Verification;

    fn result(uncut: f64) -> Box<PocketResult> {
        Box::new(PocketResult {
            toolpath: Toolpath::new(Tool::default(), crate::geom::Point3::ORIGIN),
            cutting_moves: Vec::new(),
            verification: Verification {
                min_clearance_mm: 5.0,
                required_clearance_mm: 5.0,
                uncut_area_mm2: uncut,
                uncut_at: None,
                rapids_through_material: 0,
                plunges: 0,
                max_engagement_deg: 90.0,
                mean_engagement_deg: 70.0,
                max_radial_depth_mm: 5.0,
                share_above_nominal: 0.1,
                cell_mm: 0.05,
                raster_cells: 0,
                tool_positions: 0,
                uncut_tolerance_mm2: crate::stock::UNCUT_AREA_TOLERANCE,
                engagement: crate::stock::EngagementStats::default(),
                removed_mm3: 0.0,
            },
            nominal_engagement_deg: 78.5,
            stepover_mm: 5.0,
            notes: Vec::new(),
        })
    }

    /// The fastest candidate fails verification and the second fastest cannot be planned:
    /// the third is chosen; with none verified there is no choice.
    #[test]
    fn an_unverified_candidate_is_never_chosen() {
        let bad = result(12.5);
        assert!(!bad.verification.problems().is_empty());
        let cands = vec![
            Candidate {
                kind: StrategyKind::Spiral,
                outcome: Outcome::Unverified {
                    result: bad.clone(),
                    cycle_time_s: Some(10.0),
                    problems: bad.verification.problems(),
                    timing_error: None,
                },
            },
            Candidate {
                kind: StrategyKind::Offset,
                outcome: Outcome::Failed(Error::internal("x")),
            },
            Candidate {
                kind: StrategyKind::Zigzag,
                outcome: Outcome::Verified {
                    result: result(0.0),
                    cycle_time_s: 30.0,
                },
            },
        ];
        assert_eq!(choose(&cands), Some(2));
        assert!(cands[0].why_not().unwrap().contains("uncut material"));
        assert_eq!(choose(&cands[..2]), None);
        let e = none_verified(&cands[..2]);
        assert_eq!(e.exit_code(), 1);
        assert!(e.to_string().contains("spiral: uncut material"), "{e}");
    }

    #[test]
    fn ties_go_to_the_first_and_input_refusals_stay_input_errors() {
        let v = |kind, t| Candidate {
            kind,
            outcome: Outcome::Verified {
                result: result(0.0),
                cycle_time_s: t,
            },
        };
        let cands = vec![
            v(StrategyKind::Spiral, 20.0),
            v(StrategyKind::Offset, 19.0),
            v(StrategyKind::Zigzag, 19.0),
        ];
        assert_eq!(choose(&cands), Some(1));
        let refused = |kind| Candidate {
            kind,
            outcome: Outcome::Failed(crate::InputError::new("tool diameter", 50).into()),
        };
        let all = vec![
            refused(StrategyKind::Spiral),
            refused(StrategyKind::Offset),
            refused(StrategyKind::Zigzag),
        ];
        let e = none_verified(&all);
        assert_eq!(e.exit_code(), 2);
        assert!(e.to_string().contains("--strategy auto"), "{e}");
        assert!(
            e.to_string().starts_with("invalid tool diameter = 50"),
            "{e}"
        );
    }
}
