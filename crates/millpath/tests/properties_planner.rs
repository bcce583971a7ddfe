//! Property tests of the motion planner on random programs (rapids, lines, arcs and helices in
//! every plane, full circles with extra turns, dwells; `gcode_common::build_random`):
//!
//! * **limits**: on every preset, the plan has no violation when the independent verifier
//!   (`motion::verify_plan`: 1 kHz sampling of axis velocity, acceleration and jerk
//!   against the machine, feed against the programmed feed, integration consistency and the
//!   junctions) checks it;
//! * **streaming = batch**: `motion::plan_stream` (bounded memory, windowed exact
//!   look-ahead) gives the same cycle time as `plan_moves` on the whole program, for windows
//!   down to 2 spans, and every chunk it hands out verifies on its own.
//!
//! Seeded, bounded case counts.

mod gcode_common;

use gcode_common::{build_random, random_step};
use millpath::machine::Machine;
use millpath::motion::{PlanOptions, plan_moves};
use millpath::motion::{StreamOptions, plan_stream};
use millpath::motion::{VerifyOptions, verify_plan};
use millpath::{Move, Point3};
use proptest::prelude::*;
use proptest::test_runner::RngSeed;

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, rng_seed: RngSeed::Fixed(5), failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn random_programs_plan_within_the_machine_limits(
        steps in prop::collection::vec(random_step(), 1..10),
        preset in 0usize..3,
    ) {
        let tp = build_random(&steps);
        let m = Machine::preset(Machine::PRESET_NAMES[preset]).unwrap();
        let moves: Vec<(Point3, Move)> = tp.segments().map(|(f, mv)| (f, *mv)).collect();
        let plan = plan_moves(moves.iter().map(|x| Ok(*x)), &m, &PlanOptions::default()).unwrap();
        prop_assume!(plan.total_time() < 120.0);
        let rep = verify_plan(&plan, &moves, &m, &VerifyOptions::default()).unwrap();
        prop_assert_eq!(rep.violations, 0, "{:?}", rep.first);
        prop_assert!(rep.samples > 0);
    }

    #[test]
    fn streaming_plans_match_the_whole_program_plan(
        steps in prop::collection::vec(random_step(), 1..40),
        preset in 0usize..4,
        window in 2usize..12,
    ) {
        let tp = build_random(&steps);
        let m = Machine::preset(Machine::PRESET_NAMES[preset]).unwrap();
        let moves: Vec<(Point3, Move)> = tp.segments().map(|(f, mv)| (f, *mv)).collect();
        let whole = plan_moves(moves.iter().map(|x| Ok(*x)), &m, &PlanOptions::default()).unwrap();
        let mut next_block = 0;
        let mut t = 0.0;
        let mut violations = 0;
        // The linuxcnc model's plans are judged against LinuxCNC, not the verifier.
        let verify = whole.total_time() < 120.0 && !whole.reshaped;
        let sum = plan_stream(
            moves.iter().map(|x| Ok(*x)),
            &m,
            &StreamOptions::default().with_window(window),
            |c| {
                assert_eq!(c.first_block, next_block, "chunks in order, none lost");
                assert!((c.start_time - t).abs() <= 1e-9 * (1.0 + t));
                next_block += c.moves.len();
                t += c.plan.total_time();
                // The blocks' times agree with the whole-program plan.
                for (i, b) in c.plan.blocks.iter().enumerate() {
                    let w = &whole.blocks[c.first_block + i];
                    assert!(
                        (c.start_time + b.start_time - w.start_time).abs() <= 1e-9 * (1.0 + w.start_time)
                            && (b.time - w.time).abs() <= 1e-9 * (1.0 + w.time),
                        "block {}: {b:?} vs {w:?}", c.first_block + i
                    );
                }
                if verify {
                    violations += verify_plan(&c.plan, &c.moves, &m, &VerifyOptions::default())?.violations;
                }
                Ok(())
            },
        ).unwrap();
        prop_assert_eq!(sum.moves, moves.len());
        prop_assert_eq!(sum.blocks, whole.blocks.len());
        prop_assert_eq!(next_block, whole.blocks.len());
        prop_assert_eq!(sum.spans, whole.spans.len());
        let (a, b) = (sum.total_time, whole.total_time());
        prop_assert!((a - b).abs() <= 1e-9 * (1.0 + b), "streamed {a} s vs whole {b} s");
        prop_assert_eq!(violations, 0);
    }
}
