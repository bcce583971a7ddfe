//! Fuzz target `pocket`: the body is `harness::pocket` (fuzz/harness/mod.rs), shared with the corpus
//! replay test `crates/millpath/tests/hostile_corpus.rs`.
//!
//! libfuzzer-sys installs a panic hook that aborts the process at the panic, before any
//! unwinding, so a panic the library catches on purpose (cavalier_contours' shape offset,
//! `strategy::pocket::shape`) would be reported as a crash. The `init` block puts Rust's default
//! hook back (it prints the message and lets the unwind go on): a caught panic is then what it
//! is in `millpath pocket`, and one that escapes the target still aborts, in libfuzzer-sys'
//! `catch_unwind` around every input.
#![no_main]

#[path = "../harness/mod.rs"]
mod harness;

use libfuzzer_sys::fuzz_target;

fuzz_target!(
    init: {
        let _abort_at_the_panic = std::panic::take_hook();
    },
    |data: &[u8]| harness::pocket(data)
);
