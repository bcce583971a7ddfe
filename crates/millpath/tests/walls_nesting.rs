//! The bottom-outline sections' nesting check (`PocketShape::within`, exact to 1 µm through
//! the pieces between the loops' meeting points) against a verifier that shares none of its
//! code path: 20,000 points sampled along every loop, each tested against the other region.
//! Over every input of the committed `pocket` fuzz corpus that decodes to a pocket with a
//! bottom outline, level by level, the two must agree. The sampled check `within` used
//! before 873cf0f (256 points a loop, the other region's islands only) accepted five of
//! these undercuts, one of which the spiral then gouged by 0.68 mm (fuzz/README.md).

#[path = "../../../fuzz/harness/mod.rs"]
mod harness;
mod hostile_common;

use hostile_common::corpus;
use millpath::strategy::pocket::{PocketShape, Walls, level_depths};

/// `a` within `b` by dense sampling: every sample of `a`'s loops in or on `b`, every sample
/// of `b`'s loops outside or on `a` (1 µm).
fn sampled_within(a: &PocketShape, b: &PocketShape, n: usize) -> bool {
    let on_or_in = |s: &PocketShape, p| s.contains(p) || s.distance_to(p) <= 1e-6;
    let outside = |s: &PocketShape, p| !s.contains(p) || s.distance_to(p) <= 1e-6;
    a.loops().flat_map(|l| l.sample(n)).all(|p| on_or_in(b, p))
        && b.loops().flat_map(|l| l.sample(n)).all(|p| outside(a, p))
}

#[test]
fn section_nesting_agrees_with_dense_sampling_over_the_corpus() {
    let (mut levels_checked, mut nested, mut undercut) = (0, 0, 0);
    for (name, data) in corpus("pocket") {
        let Some((_, shape, tool, opts, _)) = harness::pocket_case(&data) else {
            continue;
        };
        if !matches!(shape.walls, Walls::Bottom { .. }) || opts.validate(&tool).is_err() {
            continue;
        }
        let Ok(mut above) = shape.section(0.0, opts.depth) else {
            continue;
        };
        for z in level_depths(&opts) {
            let Ok(s) = shape.section(-z, opts.depth) else {
                break;
            };
            let exact = s.within(&above);
            assert_eq!(
                exact,
                sampled_within(&s, &above, 20_000),
                "{name}, the level {:.3} mm deep",
                -z
            );
            levels_checked += 1;
            if exact {
                nested += 1;
            } else {
                undercut += 1;
            }
            above = s;
        }
    }
    // Both outcomes occur in the corpus, so the agreement means something either way.
    assert!(
        levels_checked >= 50 && nested >= 20 && undercut >= 20,
        "{levels_checked} levels: {nested} nested, {undercut} undercuts"
    );
}
