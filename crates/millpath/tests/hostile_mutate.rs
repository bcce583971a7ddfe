//! The seeded half of CI's bounded fuzz pass: deterministic mutants of the committed corpus
//! (`fuzz/corpus-min/TARGET/*`) through the fuzz targets' own bodies (`fuzz/harness/mod.rs`),
//! on stable Rust and without libFuzzer. `hostile_corpus.rs` replays the corpus as it is;
//! this pass changes each input the way libFuzzer's mutators do (bit and byte changes,
//! interesting integers and floats, inserted, erased, repeated and copied bytes, ASCII
//! numbers changed, two inputs spliced, the tokens of `fuzz/dicts/TARGET.dict` inserted where a
//! target has a dictionary), one to five changes stacked, from a fixed seed, so
//! that a regression just beside the corpus fails `cargo test` too, the same way on every run.
//!
//! Every mutant that panics is reported with its target, the corpus file it came from, the
//! mutant's number and its bytes; `MILLPATH_MUTATE_SEED=N` changes the seed and
//! `MILLPATH_MUTATE_SCALE=K` runs K times as many mutants (a longer run, README: Long runs).

#[path = "../../../fuzz/harness/mod.rs"]
mod harness;
mod hostile_common;

use hostile_common::{Harness, corpus, dictionary, env_or, rng};
use rand::RngExt;
use rand_chacha::ChaCha8Rng;

/// Integers libFuzzer also tries: boundaries of the signed and unsigned widths.
const INTERESTING: [u64; 12] = [
    0,
    1,
    0x7f,
    0x80,
    0xff,
    0x7fff,
    0x8000,
    0xffff,
    0x7fff_ffff,
    0x8000_0000,
    0xffff_ffff,
    u64::MAX,
];

/// Floats that break arithmetic: NaN, infinities, signed zero, extremes, subnormals.
const FLOATS: [f64; 9] = [
    f64::NAN,
    f64::INFINITY,
    f64::NEG_INFINITY,
    -0.0,
    f64::MAX,
    f64::MIN_POSITIVE,
    5e-324,
    1e300,
    -1e-300,
];

/// One change to `d` (`other`: another corpus input, for splicing; `dict`: the target's
/// dictionary tokens, for the twelfth kind of change, drawn only when there are any, so that a
/// target without a dictionary sees the same mutants as before dictionaries existed).
fn mutate_once(
    d: &mut Vec<u8>,
    other: &[u8],
    dict: &[Vec<u8>],
    r: &mut ChaCha8Rng,
    max_len: usize,
) {
    let len = d.len();
    let kinds = if dict.is_empty() { 11u32 } else { 12 };
    match r.random_range(0..kinds) {
        // Flip a bit.
        0 if len > 0 => {
            let i = r.random_range(0..len);
            d[i] ^= 1 << r.random_range(0..8u32);
        }
        // Replace a byte.
        1 if len > 0 => {
            let i = r.random_range(0..len);
            d[i] = r.random();
        }
        // Insert a byte.
        2 => {
            let i = r.random_range(0..=len);
            d.insert(i, r.random());
        }
        // Insert a run of one repeated byte.
        3 => {
            let i = r.random_range(0..=len);
            let n = r.random_range(1..=64usize);
            let b: u8 = if r.random_bool(0.5) { 0 } else { r.random() };
            d.splice(i..i, std::iter::repeat_n(b, n));
        }
        // Erase a range.
        4 if len > 1 => {
            let i = r.random_range(0..len);
            let n = r.random_range(1..=(len - i).min(16));
            d.drain(i..i + n);
        }
        // Overwrite with an interesting integer (1, 2, 4 or 8 bytes, either endianness).
        5 if len > 0 => {
            let v = INTERESTING[r.random_range(0..INTERESTING.len())];
            let w = [1usize, 2, 4, 8][r.random_range(0..4usize)].min(len);
            let bytes = if r.random_bool(0.5) {
                v.to_le_bytes()
            } else {
                v.to_be_bytes()
            };
            let i = r.random_range(0..=len - w);
            d[i..i + w].copy_from_slice(&bytes[..w]);
        }
        // Overwrite 8 bytes with a hostile float.
        6 if len >= 8 => {
            let v = FLOATS[r.random_range(0..FLOATS.len())].to_le_bytes();
            let i = r.random_range(0..=len - 8);
            d[i..i + 8].copy_from_slice(&v);
        }
        // Change an ASCII number: the digits of the first run after a random point.
        7 if len > 0 => {
            let from = r.random_range(0..len);
            if let Some(s) = (from..len).find(|&i| d[i].is_ascii_digit()) {
                let e = (s..len).find(|&i| !d[i].is_ascii_digit()).unwrap_or(len);
                let text = match r.random_range(0..5u32) {
                    0 => "0".to_owned(),
                    1 => "99999999999999999999".to_owned(),
                    2 => format!("{}", r.random::<u32>()),
                    3 => "1e309".to_owned(),
                    _ => format!("{}", r.random_range(0..10u32)),
                };
                d.splice(s..e, text.into_bytes());
            }
        }
        // Copy a part of the input over another place in it.
        8 if len > 1 => {
            let a = r.random_range(0..len);
            let n = r.random_range(1..=(len - a).min(32));
            let part = d[a..a + n].to_vec();
            let b = r.random_range(0..=len - n);
            d[b..b + n].copy_from_slice(&part);
        }
        // Splice: a prefix of this input and a suffix of another.
        9 if !other.is_empty() => {
            let cut = r.random_range(0..=len);
            let from = r.random_range(0..other.len());
            d.truncate(cut);
            d.extend_from_slice(&other[from..]);
        }
        // Insert a dictionary token (a keyword of the format) or write it over the input
        // (libFuzzer's -dict mutations).
        11 => {
            let t = &dict[r.random_range(0..dict.len())];
            let i = r.random_range(0..=len);
            if r.random_bool(0.5) || i + t.len() > len {
                d.splice(i..i, t.iter().copied());
            } else {
                d[i..i + t.len()].copy_from_slice(t);
            }
        }
        // Swap two bytes.
        _ if len > 1 => {
            let (i, j) = (r.random_range(0..len), r.random_range(0..len));
            d.swap(i, j);
        }
        _ => d.push(r.random()),
    }
    d.truncate(max_len);
}

/// `count` mutants (times the scale) of the `target` corpus through `f`; the corpus files are
/// taken in turn, so every file gets mutants when `count` is at least the corpus size.
fn pass(target: &'static str, salt: u64, count: usize, f: fn(&[u8])) {
    let files: Vec<Vec<u8>> = corpus(target).into_iter().map(|(_, d)| d).collect();
    assert!(!files.is_empty(), "{target}: empty corpus");
    let count = count * env_or("MILLPATH_MUTATE_SCALE", 1usize);
    let mut r = rng(env_or("MILLPATH_MUTATE_SEED", 20_261_122u64) ^ salt);
    let dict = dictionary(target);
    let mut h = Harness::new(target);
    for k in 0..count {
        let src = k % files.len();
        let mut d = files[src].clone();
        let other = &files[r.random_range(0..files.len())];
        for _ in 0..r.random_range(1..=5u32) {
            mutate_once(&mut d, other, &dict, &mut r, 4096);
        }
        let label = format!("{target} mutant {k} of corpus file #{src} (sorted): {d:?}");
        h.run(&label, || f(&d));
    }
    h.finish(count);
}

/// The dictionary reader decodes libFuzzer's escapes (a DXF token holds newlines, an SVG one
/// quotes), so the mutants carry the same tokens as the libFuzzer runs.
#[test]
fn outline_importers_dictionary_decodes() {
    let d = dictionary("outline_importers");
    assert!(d.len() > 100, "{} tokens", d.len());
    assert!(d.iter().any(|t| t == b"0\nSECTION\n"));
    assert!(d.iter().any(|t| t == b" d=\""));
    assert!(d.iter().any(|t| t == b"AutoCAD Binary DXF\r\n\x1a\x00"));
    assert!(dictionary("no-such-target").is_empty());
}

#[test]
fn mutants_gcode_reader() {
    pass("gcode_reader", 1, 3_000, harness::gcode_reader);
}

#[test]
fn mutants_outline_importers() {
    pass("outline_importers", 2, 3_000, harness::outline_importers);
}

#[test]
fn mutants_points() {
    pass("points", 3, 1_000, harness::points);
}

#[test]
fn mutants_pocket() {
    pass("pocket", 4, 120, harness::pocket);
}

#[test]
fn mutants_adaptive() {
    pass("adaptive", 7, 96, harness::adaptive);
}

#[test]
fn mutants_contour() {
    pass("contour", 5, 120, harness::contour);
}

/// Strict, as the corpus replay: every plan must also pass the independent verifier.
#[test]
fn mutants_planner() {
    harness::STRICT_VERIFY.store(true, std::sync::atomic::Ordering::Relaxed);
    pass("planner", 6, 1_000, harness::planner);
}
