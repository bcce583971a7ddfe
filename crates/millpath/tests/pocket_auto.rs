//! `--strategy auto`: the chosen path is the fastest verified of the three, checked against
//! the three strategies generated and timed again one by one; a strategy that fails
//! verification is never chosen (with a finishing pass, measured 2026-11-25: the spiral is
//! the fastest and fails verification, its finishing lead-in feeding into the 5 µm its last
//! lap leaves; `auto`'s unit tests hold a synthetic case of this too).

use millpath::machine::Machine;
use millpath::motion::plan_toolpath;
use millpath::stock::SimOptions;
use millpath::strategy::pocket::{self, PocketOptions, StrategyKind, builtin};
use millpath::toolpath::{Tool, Toolpath};

/// The aerospace pocket, its 12.7 mm tool and a 0.1 mm simulation raster.
fn aerospace() -> (pocket::PocketShape, Tool, SimOptions) {
    let sim = SimOptions::default().with_cell(0.1).with_step(0.2);
    (builtin::aerospace_pocket(), Tool::flat(12.7).unwrap(), sim)
}

#[test]
fn auto_writes_the_fastest_verified_strategy() {
    let (shape, tool, sim) = aerospace();
    let hsm = Machine::preset("hsm").unwrap();
    let time = |tp: &Toolpath| millpath::motion::cycle_time(tp, &hsm);
    for finish in [false, true] {
        let opts = PocketOptions::default()
            .with_depth(5.0)
            .with_step_down(5.0)
            .with_finish(finish);
        let cands = pocket::plan_all(&shape, &tool, &opts, &sim, &time);
        assert_eq!(
            cands.iter().map(|c| c.kind).collect::<Vec<_>>(),
            pocket::AUTO_ORDER.to_vec()
        );
        let chosen = pocket::choose(&cands).expect("a verified strategy");
        // Each strategy again, on its own, timed by the planner directly.
        let mut best: Option<(StrategyKind, f64, Toolpath)> = None;
        for (c, kind) in cands.iter().zip(pocket::AUTO_ORDER) {
            let r = pocket::generate(kind, &shape, &tool, &opts, &sim).unwrap();
            let t = plan_toolpath(&r.toolpath, &hsm).unwrap().total_time();
            let verified = r.verification.problems().is_empty();
            assert_eq!(c.verified(), verified, "{kind:?} finish {finish}");
            assert!((c.cycle_time_s().unwrap() - t).abs() < 1e-9, "{kind:?}");
            if !verified {
                assert!(c.why_not().is_some());
                continue;
            }
            if best.as_ref().is_none_or(|b| t < b.1) {
                best = Some((kind, t, r.toolpath));
            }
        }
        let (kind, t, tp) = best.unwrap();
        let c = &cands[chosen];
        assert_eq!(c.kind, kind, "finish {finish}");
        assert!(c.verified());
        assert!((c.cycle_time_s().unwrap() - t).abs() < 1e-9);
        assert_eq!(c.result().unwrap().toolpath, tp, "the very toolpath");
        // Nothing unverified is faster and chosen; anything faster is unverified.
        for o in &cands {
            if o.cycle_time_s().is_some_and(|u| u < t) {
                assert!(!o.verified(), "{:?} is faster and verified", o.kind);
            }
        }
    }
}

/// `--arcs` keeps the faster of the arcs and the chords on each machine, checked against both
/// forms generated and timed again by the planner directly: on `hsm` (jerk-limited, the chords
/// with curvature ramps) the chords win and the note gives both times; on the LinuxCNC model
/// (trapezoidal) the arcs win and are kept without a note.
#[test]
fn arcs_request_keeps_the_faster_form_on_each_machine() {
    let (shape, tool, sim) = aerospace();
    let arcs_in = |tp: &Toolpath| {
        tp.moves
            .iter()
            .filter(|m| matches!(m.kind, millpath::toolpath::MoveKind::Arc { .. }))
            .count()
    };
    for (name, ramps) in [("hsm", true), ("linuxcnc-time", false)] {
        let m = Machine::preset(name).unwrap();
        let time = |tp: &Toolpath| millpath::motion::cycle_time(tp, &m);
        let opts = PocketOptions::default()
            .with_depth(5.0)
            .with_step_down(5.0)
            .with_arcs(true)
            .with_curvature_ramps(ramps);
        let (r, t) =
            pocket::arcs_or_chords(StrategyKind::Spiral, &shape, &tool, &opts, &sim, &time)
                .unwrap();
        let t = t.unwrap();
        assert!(r.verification.problems().is_empty(), "{name}");
        let a = pocket::generate(StrategyKind::Spiral, &shape, &tool, &opts, &sim).unwrap();
        let chord_opts = opts.clone().with_arcs(false);
        let c = pocket::generate(StrategyKind::Spiral, &shape, &tool, &chord_opts, &sim).unwrap();
        let ta = plan_toolpath(&a.toolpath, &m).unwrap().total_time();
        let tc = plan_toolpath(&c.toolpath, &m).unwrap().total_time();
        assert!(
            (t - ta.min(tc)).abs() < 1e-9,
            "{name}: kept {t}, arcs {ta}, chords {tc}"
        );
        let kept_chords = tc < ta;
        assert_eq!(kept_chords, name == "hsm", "{name}: arcs {ta}, chords {tc}");
        if kept_chords {
            assert_eq!(r.toolpath, c.toolpath);
            assert!(
                r.notes.iter().any(|n| matches!(
                    n,
                    pocket::PocketNote::ChordsInsteadOfArcs { faster: Some((c, a)) } if c < a
                )),
                "{:?}",
                r.notes
            );
        } else {
            assert_eq!(r.toolpath, a.toolpath);
            assert!(arcs_in(&r.toolpath) > arcs_in(&c.toolpath), "{name}");
            assert!(r.notes.is_empty(), "{:?}", r.notes);
        }
    }
}
