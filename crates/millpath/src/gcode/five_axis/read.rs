//! Reading five-axis joint programs back: the words [`super::write_five_axis`] writes, in
//! each of its dialects, to joint positions and block times.
//!
//! The main [`Reader`](crate::gcode::Reader) reads LinuxCNC's rotary words onto its moves
//! ([`crate::toolpath::Move::rotary`]) and refuses them in the other dialects; this one reads a
//! table-table joint program in every dialect that has rotary axes: `G0`/`G1` with `X Y Z` and two rotary words, `G93`
//! (`F` in 1/min on every feed block, the block takes `1/F` minutes) or `G94` (the RS274NGC
//! rule: `F` in units per minute along the XYZ chord, or along the rotary chord in degrees
//! when only rotary axes move; Fanuc's: along the chord of all five words), dwells (`G4 P` s, Fanuc `G04 X` s, Sinumerik `G4 F` s), the
//! units words (`G20`/`G21`, Sinumerik `G700`/`G710`) and the header's words (tool change,
//! spindle, coolant, work offset, framing). Anything else — incremental `G91`, a word it does
//! not know, a `G93` feed block without `F` — is refused with the line and the word, so that
//! a program it reads is timed as written.

use crate::error::{Error, InputError};
use crate::gcode::Dialect;
use crate::gcode::format::MM_PER_INCH;
use crate::gcode::lexer::{LineKind, Token, lex};

/// One block of a five-axis joint program.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JointBlock {
    /// Line number in the program (from 1).
    pub line: usize,
    /// Joint position after the block: X, Y, Z in mm, the two rotaries in rad.
    pub q: [f64; 5],
    /// The block's time in s by its feed word (0 for a rapid, whose time is the machine's).
    pub seconds: f64,
    /// A `G0` block.
    pub rapid: bool,
}

fn refuse(origin: &str, line: usize, what: &str, value: impl std::fmt::Display) -> Error {
    InputError::new(what, value)
        .at(format!("{origin}:{line}"))
        .expected(
            "a five-axis joint program: G0/G1 with X Y Z and the machine's two rotary words, \
             G93 or G94 feeds, G4 dwells, absolute coordinates",
        )
        .into()
}

/// Reads a five-axis joint program written in `dialect` for a machine whose axes are called
/// `names` (`["X", "Y", "Z", "A", "C"]`); `origin` names the source in messages.
pub fn read_five_axis(
    text: &str,
    dialect: Dialect,
    names: [&str; 5],
    origin: &str,
) -> Result<Vec<JointBlock>, Error> {
    let letters: Vec<u8> = names
        .iter()
        .map(|n| n.as_bytes().first().copied().unwrap_or(b'X'))
        .collect();
    let mut unit = 1.0;
    let mut inverse_time = false;
    let mut feed: Option<f64> = None;
    let mut motion: Option<bool> = None; // Some(true): G0
    let mut pos: Option<[f64; 5]> = None; // program units and degrees
    let mut out = Vec::new();
    let mut tokens = Vec::new();
    for (k, line) in text.lines().enumerate() {
        let n = k + 1;
        match lex(line, &mut tokens) {
            Ok(LineKind::Percent) => continue,
            Ok(LineKind::Block { .. }) => {}
            Err(e) => return Err(refuse(origin, n, "text", e.text)),
        }
        let mut gs = Vec::new();
        let mut axes: [Option<f64>; 5] = [None; 5];
        let (mut f, mut p, mut x_word) = (None, None, None);
        for t in &tokens {
            let Token::Word { letter, value, .. } = t else {
                return Err(refuse(origin, n, "word", format!("{t:?}")));
            };
            let (letter, value) = (*letter, *value);
            if let Some(i) = letters.iter().position(|&l| l == letter) {
                if letter == b'X' {
                    x_word = Some(value);
                }
                if let Some(a) = axes.get_mut(i) {
                    *a = Some(value);
                }
                continue;
            }
            match letter {
                b'N' | b'T' | b'S' => {}
                b'O' if dialect == Dialect::Fanuc => {}
                b'G' => gs.push((value * 10.0).round() as i64),
                b'M' if [2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0, 30.0].contains(&value) => {}
                b'F' => f = Some(value),
                b'P' => p = Some(value),
                _ => {
                    return Err(refuse(
                        origin,
                        n,
                        "word",
                        format!("{}{value}", char::from(letter)),
                    ));
                }
            }
        }
        let mut dwell = false;
        for g in &gs {
            match (*g, dialect) {
                (0, _) => motion = Some(true),
                (10, _) => motion = Some(false),
                (40, _) => dwell = true,
                (170 | 400 | 490 | 540..=590 | 800 | 900, _) => {}
                (911, Dialect::LinuxCnc) => {}
                (930, _) => inverse_time = true,
                (940, _) => inverse_time = false,
                (200, d) if d != Dialect::Sinumerik => unit = MM_PER_INCH,
                (210, d) if d != Dialect::Sinumerik => unit = 1.0,
                (7000, Dialect::Sinumerik) => unit = MM_PER_INCH,
                (7100, Dialect::Sinumerik) => unit = 1.0,
                (g, _) => return Err(refuse(origin, n, "G code", g as f64 / 10.0)),
            }
        }
        if dwell {
            let s = match dialect {
                Dialect::Fanuc => x_word,
                Dialect::Sinumerik => f,
                Dialect::LinuxCnc | Dialect::Grbl => p,
            };
            let Some(s) = s.filter(|s| s.is_finite() && *s >= 0.0) else {
                return Err(refuse(origin, n, "dwell", line.trim()));
            };
            let q = pos.ok_or_else(|| refuse(origin, n, "dwell before the first move", s))?;
            out.push(JointBlock {
                line: n,
                q: to_joints(&q, unit),
                seconds: s,
                rapid: false,
            });
            continue;
        }
        if let Some(f) = f {
            feed = Some(f);
        }
        if axes.iter().all(Option::is_none) {
            continue;
        }
        let Some(rapid) = motion else {
            return Err(refuse(origin, n, "axis words without G0/G1", line.trim()));
        };
        let prev = pos;
        let q: [f64; 5] = match prev {
            Some(p) => std::array::from_fn(|i| axes[i].unwrap_or(p[i])),
            None if axes.iter().all(Option::is_some) => {
                std::array::from_fn(|i| axes[i].unwrap_or(0.0))
            }
            None => return Err(refuse(origin, n, "first move", "not all five axes")),
        };
        pos = Some(q);
        let seconds = match (rapid, prev) {
            (true, _) | (false, None) => 0.0,
            (false, Some(p)) => {
                let fv = if inverse_time { f } else { feed };
                let Some(fv) = fv.filter(|v| v.is_finite() && *v > 0.0) else {
                    return Err(refuse(origin, n, "feed", "missing or not > 0"));
                };
                if inverse_time {
                    60.0 / fv
                } else {
                    let lin =
                        ((q[0] - p[0]).powi(2) + (q[1] - p[1]).powi(2) + (q[2] - p[2]).powi(2))
                            .sqrt();
                    let rot = ((q[3] - p[3]).powi(2) + (q[4] - p[4]).powi(2)).sqrt();
                    let chord = match dialect {
                        Dialect::Fanuc => lin.hypot(rot),
                        _ if lin > 0.0 => lin,
                        _ => rot,
                    };
                    60.0 * chord / fv
                }
            }
        };
        out.push(JointBlock {
            line: n,
            q: to_joints(&q, unit),
            seconds,
            rapid,
        });
    }
    Ok(out)
}

/// Program units and degrees → mm and rad.
fn to_joints(q: &[f64; 5], unit: f64) -> [f64; 5] {
    std::array::from_fn(|i| {
        if i < 3 {
            q[i] * unit
        } else {
            q[i].to_radians()
        }
    })
}
