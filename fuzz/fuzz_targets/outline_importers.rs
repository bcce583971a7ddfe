//! Fuzz target `outline_importers`: the body is `harness::outline_importers` (fuzz/harness/mod.rs), shared with the corpus
//! replay test `crates/millpath/tests/hostile_corpus.rs`.
#![no_main]

#[path = "../harness/mod.rs"]
mod harness;

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| harness::outline_importers(data));
