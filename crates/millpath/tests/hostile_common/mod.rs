//! Shared pieces of the `hostile_*` tests: a seeded generator of hostile values and a harness
//! that runs a call under `catch_unwind` and records the input of every panic.
//!
//! The harness collects every panic of a pass (not only the first) and fails the test at the
//! end with the inputs printed, so one run shows everything that is wrong.

#![allow(dead_code)]

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::fmt::Debug;
use std::panic::{AssertUnwindSafe, catch_unwind};

/// The committed fuzz corpus of `target` (`fuzz/corpus-min/TARGET/*`): names and bytes, sorted
/// by name (the replay and the mutation pass see the same order on every machine).
pub fn corpus(target: &str) -> Vec<(String, Vec<u8>)> {
    let dir = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../fuzz/corpus-min")
        .join(target);
    let mut files: Vec<(String, Vec<u8>)> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("corpus {} missing: {e}", dir.display()))
        .map(|e| {
            let e = e.expect("corpus entry");
            let name = e.file_name().to_string_lossy().into_owned();
            (name, std::fs::read(e.path()).expect("corpus file"))
        })
        .collect();
    files.sort();
    files
}

/// The libFuzzer dictionary of `target` (`fuzz/dicts/TARGET.dict`), decoded, or nothing when
/// the target has none. The format: one `name="value"` a line, `#` comments, the escapes `\\`,
/// `\"` and `\xNN` in the value. A line that does not parse fails the test (a broken dictionary
/// would also be refused by libFuzzer).
pub fn dictionary(target: &str) -> Vec<Vec<u8>> {
    let path = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../fuzz/dicts")
        .join(format!("{target}.dict"));
    let Ok(text) = std::fs::read_to_string(&path) else {
        return Vec::new();
    };
    let mut tokens = Vec::new();
    for (n, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let quoted = line
            .split_once('=')
            .map(|(_, v)| v)
            .and_then(|v| v.strip_prefix('"'))
            .and_then(|v| v.strip_suffix('"'))
            .unwrap_or_else(|| panic!("{}:{}: not name=\"value\"", path.display(), n + 1));
        let b = quoted.as_bytes();
        let mut token = Vec::with_capacity(b.len());
        let mut i = 0;
        while i < b.len() {
            match (b[i], b.get(i + 1)) {
                (b'\\', Some(b'x')) => {
                    let hex = std::str::from_utf8(&b[(i + 2).min(b.len())..(i + 4).min(b.len())])
                        .ok()
                        .and_then(|h| u8::from_str_radix(h, 16).ok())
                        .unwrap_or_else(|| panic!("{}:{}: bad \\x escape", path.display(), n + 1));
                    token.push(hex);
                    i += 4;
                }
                (b'\\', Some(&c)) => {
                    token.push(c);
                    i += 2;
                }
                (c, _) => {
                    token.push(c);
                    i += 1;
                }
            }
        }
        tokens.push(token);
    }
    tokens
}

/// The environment variable `var` parsed, or `default` when it is unset or does not parse
/// (sizes, seeds and scales of the long runs).
pub fn env_or<T: std::str::FromStr>(var: &str, default: T) -> T {
    std::env::var(var)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

/// The deterministic RNG of a pass (`seed` differs per test so the passes do not correlate).
pub fn rng(seed: u64) -> ChaCha8Rng {
    ChaCha8Rng::seed_from_u64(seed)
}

/// Collects the inputs that made a call panic.
#[derive(Default)]
pub struct Harness {
    name: &'static str,
    cases: usize,
    panics: Vec<String>,
}

impl Harness {
    pub fn new(name: &'static str) -> Self {
        Harness {
            name,
            cases: 0,
            panics: Vec::new(),
        }
    }

    /// Runs `f` and returns its value; a panic is recorded (and `None` returned) with `input` (its `Debug` form, cut to 2000 characters).
    /// With `HOSTILE_TRACE` set, each input is printed before its call (to find an input that
    /// hangs or exhausts memory rather than panicking).
    #[allow(clippy::print_stderr)]
    pub fn run<T>(&mut self, input: &dyn Debug, f: impl FnOnce() -> T) -> Option<T> {
        self.cases += 1;
        if std::env::var_os("HOSTILE_TRACE").is_some() {
            eprintln!("{} case {}: {input:?}", self.name, self.cases);
        }
        match catch_unwind(AssertUnwindSafe(f)) {
            Ok(v) => Some(v),
            Err(e) => {
                let msg = e
                    .downcast_ref::<String>()
                    .cloned()
                    .or_else(|| e.downcast_ref::<&str>().map(|s| (*s).to_string()))
                    .unwrap_or_default();
                let mut shown = format!("{input:?}");
                if shown.len() > 2000 {
                    let mut cut = 2000;
                    while !shown.is_char_boundary(cut) {
                        cut -= 1;
                    }
                    shown.truncate(cut);
                    shown.push_str("...");
                }
                self.panics.push(format!("panic `{msg}` on input {shown}"));
                None
            }
        }
    }

    /// Fails when anything panicked; also checks that the pass ran at least `min_cases`.
    pub fn finish(self, min_cases: usize) {
        assert!(
            self.cases >= min_cases,
            "{}: only {} cases ran",
            self.name,
            self.cases
        );
        assert!(
            self.panics.is_empty(),
            "{}: {} of {} cases panicked:\n{}",
            self.name,
            self.panics.len(),
            self.cases,
            self.panics
                .iter()
                .take(20)
                .cloned()
                .collect::<Vec<_>>()
                .join("\n")
        );
    }
}

/// A hostile f64: specials, extremes, tiny and ordinary magnitudes of both signs.
pub fn hostile_f64(rng: &mut ChaCha8Rng) -> f64 {
    match rng.random_range(0..14) {
        0 => f64::NAN,
        1 => f64::INFINITY,
        2 => f64::NEG_INFINITY,
        3 => 0.0,
        4 => -0.0,
        5 => f64::MAX,
        6 => f64::MIN_POSITIVE,
        7 => 1e-300,
        8 => 1e300 * if rng.random_bool(0.5) { 1.0 } else { -1.0 },
        9 => rng.random_range(-1e-9..1e-9),
        10 => rng.random_range(-1e9..1e9),
        _ => rng.random_range(-100.0..100.0),
    }
}

/// Mostly ordinary values with a hostile one now and then (`p_bad` is its probability).
pub fn mostly_sane(rng: &mut ChaCha8Rng, lo: f64, hi: f64, p_bad: f64) -> f64 {
    if rng.random_bool(p_bad) {
        hostile_f64(rng)
    } else {
        rng.random_range(lo..hi)
    }
}

/// A number as text the way a hostile file writes it.
pub fn hostile_number_text(rng: &mut ChaCha8Rng) -> String {
    match rng.random_range(0..16) {
        0 => String::new(),
        1 => "-".into(),
        2 => ".".into(),
        3 => "nan".into(),
        4 => "inf".into(),
        5 => "1e400".into(),
        6 => "-1e400".into(),
        7 => "99999999999999999999999999999".into(),
        8 => "1e-400".into(),
        9 => "--1".into(),
        10 => "1.2.3".into(),
        11 => format!("{}", hostile_f64(rng)),
        _ => format!("{:.3}", rng.random_range(-500.0..500.0)),
    }
}

/// Random bytes: printable ASCII mostly, with control bytes, NULs and invalid UTF-8.
pub fn random_bytes(rng: &mut ChaCha8Rng, max_len: usize) -> Vec<u8> {
    let n = rng.random_range(0..=max_len);
    (0..n)
        .map(|_| match rng.random_range(0..10) {
            0 => rng.random::<u8>(),
            1 => b'\n',
            _ => rng.random_range(b' '..=b'~'),
        })
        .collect()
}
