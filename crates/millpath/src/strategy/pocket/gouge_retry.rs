//! [`super::generate`]'s gouge guard: a toolpath that cuts more than [`GOUGE_TOLERANCE`] into
//! the walls' clearance is planned again with other options, and the one that clears them is
//! returned with a note saying what changed and why.
//!
//! The fallbacks, in order: for the spiral's fronts morph, the harmonic morph instead; then G1
//! chords instead of arcs (with the morph asked for, then the harmonic one). The spiral keeps
//! its laps, chords and arcs inside its walls' loops itself ([`super::spiral`]), so these are
//! a safety net.

use super::options::SpiralMorph;
use super::{PocketOptions, PocketResult, StrategyKind};
use crate::error::Result;
use crate::stock::Verification;

/// The deepest gouge [`super::generate`] lets through, mm, for tools up to 12.7 mm
/// ([`gouge_tolerance`] for a tool): the tool centre may come this much closer to a wall than
/// the tool radius plus the wall stock. Above the offsets' rounding and the stock
/// simulation's sampling (nanometres to micrometres, which [`Verification::problems`] still
/// reports, from 1e-6 mm), below any machining tolerance.
pub const GOUGE_TOLERANCE: f64 = 0.01;

/// [`GOUGE_TOLERANCE`] for `tool`: times its
/// [`tolerance_scale`](crate::toolpath::Tool::tolerance_scale), as the spiral's margin and arc
/// tolerance it sits above.
pub fn gouge_tolerance(tool: &crate::toolpath::Tool) -> f64 {
    GOUGE_TOLERANCE * tool.tolerance_scale()
}

/// What [`first_clear`] found.
#[derive(Debug)]
pub enum Attempts {
    /// The first result that clears the walls to within [`gouge_tolerance`]: the one asked
    /// for, or a fallback with its note.
    Clears(PocketResult),
    /// Every attempt gouged: the one asked for.
    Gouges(PocketResult),
}

/// Runs `attempt` with `opts`, then with each fallback of `opts` while the result gouges by
/// more than [`gouge_tolerance`] of the tool. An error of the first attempt is returned; a
/// fallback that fails is skipped.
pub fn first_clear(
    kind: StrategyKind,
    opts: &PocketOptions,
    mut attempt: impl FnMut(&PocketOptions) -> Result<PocketResult>,
) -> Result<Attempts> {
    let r = attempt(opts)?;
    let tol = gouge_tolerance(&r.toolpath.tool);
    if gouge(&r.verification) <= tol {
        return Ok(Attempts::Clears(r));
    }
    for o in &fallbacks(kind, opts) {
        if let Ok(mut r2) = attempt(o)
            && gouge(&r2.verification) <= tol
        {
            r2.notes.push(note(kind, opts, o, gouge(&r.verification)));
            return Ok(Attempts::Clears(r2));
        }
    }
    Ok(Attempts::Gouges(r))
}

/// The options to try after `opts`, in order: the harmonic morph (a spiral with the fronts),
/// then the same without `--arcs` (any morph).
fn fallbacks(kind: StrategyKind, opts: &PocketOptions) -> Vec<PocketOptions> {
    let mut out = Vec::new();
    if kind == StrategyKind::Spiral && opts.spiral.morph == SpiralMorph::Fronts {
        out.push(opts.clone().with_morph(SpiralMorph::Harmonic));
    }
    if opts.spiral.arcs {
        let chords: Vec<PocketOptions> = std::iter::once(opts.clone())
            .chain(out.iter().cloned())
            .map(|o| o.with_arcs(false))
            .collect();
        out.extend(chords);
    }
    out
}

/// What the engine did to a pocket's toolpath beyond what was asked ([`PocketResult::notes`]).
#[derive(Debug, Clone, PartialEq)]
pub enum PocketNote {
    /// The toolpath as asked for cut into the walls' clearance by more than
    /// [`GOUGE_TOLERANCE`]; it was planned again with other options, which clear them.
    Replanned {
        /// The strategy.
        strategy: StrategyKind,
        /// How far the path asked for cut into the clearance, mm.
        gouge_mm: f64,
        /// The harmonic morph replaced the fronts.
        harmonic_morph: bool,
        /// G1 chords replaced arcs.
        chords: bool,
    },
    /// `--arcs` was asked for under automatic choice and the path is written as G1 chords:
    /// faster on the machine (`Some((chords_s, arcs_s))`, the two cycle times) or the path
    /// with arcs did not pass the verification (`None`).
    ChordsInsteadOfArcs {
        /// Cycle times with chords and with arcs, s, when the chords were faster.
        faster: Option<(f64, f64)>,
    },
}

impl std::fmt::Display for PocketNote {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            PocketNote::Replanned {
                strategy,
                gouge_mm,
                harmonic_morph,
                chords,
            } => {
                let mut changes = Vec::new();
                if *harmonic_morph {
                    changes.push("the harmonic morph instead of the fronts (`--morph harmonic`)");
                }
                if *chords {
                    changes.push("G1 chords instead of arcs (no `--arcs`)");
                }
                write!(
                    f,
                    "the {} toolpath as asked for cut {gouge_mm:.4} mm into the walls' clearance \
                     (more than the {GOUGE_TOLERANCE} mm allowed); planned again with {}, which \
                     clears them",
                    strategy.name(),
                    changes.join(" and ")
                )
            }
            PocketNote::ChordsInsteadOfArcs { faster } => match faster {
                Some((c, a)) => write!(
                    f,
                    "`--arcs`: written as G1 chords, faster on this machine: {c:.2} s against \
                     {a:.2} s with arcs"
                ),
                None => f.write_str(
                    "`--arcs`: written as G1 chords, the path with arcs did not pass the \
                     verification",
                ),
            },
        }
    }
}

/// The note of a fallback: what the path asked for did, and what replaced it.
fn note(kind: StrategyKind, asked: &PocketOptions, used: &PocketOptions, depth: f64) -> PocketNote {
    PocketNote::Replanned {
        strategy: kind,
        gouge_mm: depth,
        harmonic_morph: asked.spiral.morph != used.spiral.morph,
        chords: asked.spiral.arcs && !used.spiral.arcs,
    }
}

/// How far the tool centre comes inside the required clearance, mm (≤ 0: no gouge).
pub fn gouge(v: &Verification) -> f64 {
    v.required_clearance_mm - v.min_clearance_mm
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stock::SimOptions;
    use crate::strategy::pocket::{builtin, generate};
    use crate::toolpath::Tool;

    /// A real spiral (a 40 × 30 mm pocket, an 8 mm tool), made to look as if it gouged 0.02 mm whenever
    /// `gouges` says so of the options it was planned with; the options tried, in order.
    fn run(
        opts: &PocketOptions,
        gouges: impl Fn(&PocketOptions) -> bool,
    ) -> (Attempts, Vec<PocketOptions>) {
        let outline = builtin::rounded_rectangle(0.0, 0.0, 40.0, 30.0, 5.0);
        let opts = &opts.clone().with_morph(SpiralMorph::Fronts);
        let shape = crate::strategy::pocket::PocketShape::simple(outline);
        let tool = Tool::flat(8.0).expect("tool");
        let sim = SimOptions::default();
        let mut tried = Vec::new();
        let out = first_clear(StrategyKind::Spiral, opts, |o| {
            tried.push(o.clone());
            let mut r = generate(StrategyKind::Spiral, &shape, &tool, o, &sim)?;
            if gouges(o) {
                r.verification.min_clearance_mm = r.verification.required_clearance_mm - 0.02;
            }
            Ok(r)
        })
        .expect("plans");
        (out, tried)
    }

    #[test]
    fn a_path_that_clears_is_returned_without_a_note() {
        let (out, tried) = run(&PocketOptions::default(), |_| false);
        assert!(
            matches!(out, Attempts::Clears(ref r) if r.notes.is_empty()),
            "{out:?}"
        );
        assert_eq!(tried.len(), 1);
    }

    #[test]
    fn gouging_arcs_are_planned_again_as_chords_and_noted() {
        let opts = PocketOptions::default().with_arcs(true);
        let (out, tried) = run(&opts, |o| o.spiral.arcs);
        let Attempts::Clears(r) = out else {
            panic!("{out:?}")
        };
        // The harmonic morph with arcs first, then the fronts as chords.
        assert_eq!(tried.len(), 3);
        assert!(tried[1].spiral.arcs && tried[1].spiral.morph == SpiralMorph::Harmonic);
        assert!(!tried[2].spiral.arcs && tried[2].spiral.morph == SpiralMorph::Fronts);
        assert_eq!(r.notes.len(), 1, "{:?}", r.notes);
        assert!(
            r.notes[0].to_string().contains("G1 chords instead of arcs")
                && r.notes[0].to_string().contains("0.0200 mm")
                && !r.notes[0].to_string().contains("harmonic"),
            "{}",
            r.notes[0].to_string()
        );
    }

    #[test]
    fn a_gouging_fronts_morph_falls_back_to_the_harmonic_one() {
        let fronts = |o: &PocketOptions| o.spiral.morph == SpiralMorph::Fronts;
        let (out, tried) = run(&PocketOptions::default(), fronts);
        let Attempts::Clears(r) = out else {
            panic!("{out:?}")
        };
        assert_eq!(tried.len(), 2);
        assert!(
            r.notes[0]
                .to_string()
                .contains("the harmonic morph instead of the fronts")
        );
    }

    #[test]
    fn the_offsets_morph_falls_back_to_chords_only() {
        let opts = PocketOptions::default().with_arcs(true);
        assert_eq!(opts.spiral.morph, SpiralMorph::Offsets);
        let f = fallbacks(StrategyKind::Spiral, &opts);
        assert_eq!(f.len(), 1);
        assert!(!f[0].spiral.arcs && f[0].spiral.morph == SpiralMorph::Offsets);
        assert!(fallbacks(StrategyKind::Spiral, &PocketOptions::default()).is_empty());
    }

    #[test]
    fn what_gouges_whatever_the_options_is_returned_as_asked() {
        let opts = PocketOptions::default().with_arcs(true);
        let (out, tried) = run(&opts, |_| true);
        // Asked, harmonic, fronts as chords, harmonic as chords.
        assert_eq!(tried.len(), 4);
        let Attempts::Gouges(r) = out else {
            panic!("{out:?}")
        };
        assert!(r.notes.is_empty());
        assert!((gouge(&r.verification) - 0.02).abs() < 1e-12);
    }
}
