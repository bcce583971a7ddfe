//! The adaptive strategy's share of the bounded fuzz pass of CI (as `hostile_corpus` for the
//! other targets): its corpus (`fuzz/corpus-min/adaptive`, inputs of the `pocket` decoding)
//! and the inputs its fuzz runs found, replayed through the `adaptive` target's own body
//! (`fuzz/harness/mod.rs`), strict.

#[path = "../../../fuzz/harness/mod.rs"]
mod harness;
mod hostile_common;

use hostile_common::{Harness, corpus};
use std::path::PathBuf;

/// Strict, as `hostile_corpus::corpus_pocket`: the adaptive plans of its own corpus (inputs of the
/// `pocket` decoding), with `--both-ways` and `--lift` drawn.
#[test]
fn corpus_adaptive() {
    harness::STRICT_VERIFY.store(true, std::sync::atomic::Ordering::Relaxed);
    let files = corpus("adaptive");
    let mut h = Harness::new("adaptive");
    for (name, data) in &files {
        h.run(&(name, String::from_utf8_lossy(data)), || {
            harness::adaptive(data);
        });
    }
    h.finish(20);
}

/// The adaptive crossed walls thinner than a cell until 2026-11-30 (a slit where two edges
/// of the outline run back along each other, an island drawn as a needle): its grid
/// measured the distance to the cells outside the pocket, and no cell centre lies outside
/// there, so it took points beside such a wall for inside for sure (`Field::thin` now sees
/// them). The `adaptive` fuzz target's first runs found these 41 gouges, each
/// refused by the verifier (an internal error, nothing written); each now verifies
/// (`harness::adaptive`, strict: no gouge, nothing uncut, no internal error).
#[test]
fn adaptive_keeps_off_walls_thinner_than_a_cell() {
    harness::STRICT_VERIFY.store(true, std::sync::atomic::Ordering::Relaxed);
    let dir =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../fuzz/regressions/adaptive-thin-wall");
    let mut names: Vec<_> = std::fs::read_dir(&dir)
        .expect("regressions dir")
        .map(|e| e.expect("entry").path())
        .collect();
    names.sort();
    assert_eq!(names.len(), 41, "{names:?}");
    for f in &names {
        harness::adaptive(&std::fs::read(f).expect("file"));
    }
}
