//! Fuzz target `adaptive`: the body is `harness::adaptive` (fuzz/harness/mod.rs), shared with the
//! corpus replay test `crates/millpath/tests/hostile_corpus.rs`: the `pocket` target's inputs,
//! planned by the adaptive strategy. The `init` block is the `pocket` target's (see there).
#![no_main]

#[path = "../harness/mod.rs"]
mod harness;

use libfuzzer_sys::fuzz_target;

fuzz_target!(
    init: {
        let _abort_at_the_panic = std::panic::take_hook();
    },
    |data: &[u8]| harness::adaptive(data)
);
