//! Fuzz target `contour`: the body is `harness::contour` (fuzz/harness/mod.rs), shared with the corpus
//! replay test `crates/millpath/tests/hostile_corpus.rs`.
#![no_main]

#[path = "../harness/mod.rs"]
mod harness;

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| harness::contour(data));
