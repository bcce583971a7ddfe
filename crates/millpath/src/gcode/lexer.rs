//! The lexer: one line of G-code → words.
//!
//! A line is `[/] [N…] word*` with comments `( … )` (not nested) and `;` to the end of the
//! line. A word is a letter and a number (`G1`, `X-1.5`, `x .5`: case and spaces between
//! letter and number do not matter, as in RS274/NGC). Numbers are decimal without exponent:
//! `[+-]? digits [. digits]` or `[+-]? . digits`; anything else (`NaN`, `1e5` (refused as
//! the word it is in, not read as `1` and a word `E5`), `#1`,
//! `[1+2]`) is an error naming the column and the text. Two Sinumerik forms are lexed too:
//! assignments `NAME=number` (`TURN=2`) and calls `NAME(args)` (`CYCLE832(0.01,_FINISH,1)`).
//! A `%` line (Fanuc framing) is reported as such.

/// Longest part of a line quoted in a message, in characters.
const QUOTED_CHARS: usize = 80;

/// `line` trimmed, as a message quotes it: its first [`QUOTED_CHARS`] characters and `…`
/// when longer (a 64 KiB line is not repeated in full).
pub(crate) fn shown(line: &str) -> String {
    let t = line.trim();
    match t.char_indices().nth(QUOTED_CHARS) {
        Some((k, _)) => format!("{}…", t.get(..k).unwrap_or(t)),
        None => t.to_string(),
    }
}

/// One token of a line.
#[derive(Debug, Clone, PartialEq)]
pub enum Token {
    /// A letter (upper case) and its number; `start..end` is its text in the line.
    Word {
        /// The letter, upper case.
        letter: u8,
        /// The number.
        value: f64,
        /// Byte offset of the letter.
        start: usize,
        /// Byte offset one past the number.
        end: usize,
    },
    /// `NAME=number` (upper case name).
    Assign {
        /// The name.
        name: String,
        /// The value.
        value: f64,
    },
    /// `NAME(args)` (upper case name; `args` as written).
    Call {
        /// The name.
        name: String,
        /// The text between the parentheses.
        args: String,
    },
}

/// What kind of line was lexed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LineKind {
    /// A block (possibly empty: blank or comment only).
    Block {
        /// The line started with `/` (block delete).
        block_delete: bool,
    },
    /// A `%` line.
    Percent,
}

/// A lexing error: where and what.
#[derive(Debug, Clone, PartialEq)]
pub struct LexError {
    /// Byte offset in the line.
    pub column: usize,
    /// The offending text.
    pub text: String,
    /// What would be accepted.
    pub expected: &'static str,
}

/// Lexes `line` into `tokens` (cleared first).
pub fn lex(line: &str, tokens: &mut Vec<Token>) -> Result<LineKind, LexError> {
    tokens.clear();
    let b = line.as_bytes();
    let trimmed = line.trim();
    if trimmed.starts_with('%') {
        return if trimmed == "%" {
            Ok(LineKind::Percent)
        } else {
            Err(LexError {
                column: 0,
                text: trimmed.to_string(),
                expected: "a line with '%' alone",
            })
        };
    }
    let mut i = skip_ws(b, 0);
    let block_delete = b.get(i) == Some(&b'/');
    if block_delete {
        i += 1;
    }
    loop {
        i = skip_ws(b, i);
        let Some(&c) = b.get(i) else { break };
        match c {
            b';' => break,
            b'(' => {
                let close = line.get(i..).and_then(|s| s.find(')'));
                let Some(close) = close else {
                    return Err(err(line, i, "a comment closed by ')'"));
                };
                if line.get(i + 1..i + close).is_some_and(|s| s.contains('(')) {
                    return Err(err(line, i, "a comment without nested '('"));
                }
                i += close + 1;
            }
            c if c.is_ascii_alphabetic() => {
                let start = i;
                let j = skip_ws(b, i + 1);
                if b.get(j)
                    .is_some_and(|n| n.is_ascii_alphabetic() || *n == b'_')
                {
                    i = keyword(line, start, tokens)?;
                } else {
                    let (value, end) = number(line, j)
                        .ok_or_else(|| err(line, start, "a letter followed by a number"))?;
                    // `X1e400` is not `X1` and a word `E400`: G-code has no exponent, and a
                    // number in exponent notation is refused as the word it was typed in.
                    let mut k = end;
                    if matches!(b.get(k), Some(b'e' | b'E')) {
                        k += 1;
                        if matches!(b.get(k), Some(b'+' | b'-')) {
                            k += 1;
                        }
                        if b.get(k).is_some_and(u8::is_ascii_digit) {
                            return Err(err(
                                line,
                                start,
                                "a decimal number without exponent notation, of magnitude at \
                                 most 1e9",
                            ));
                        }
                    }
                    tokens.push(Token::Word {
                        letter: c.to_ascii_uppercase(),
                        value,
                        start,
                        end,
                    });
                    i = end;
                }
            }
            // LinuxCNC's polar words: `@` radius, `^` angle (degrees).
            b'@' | b'^' => {
                let start = i;
                let (value, end) = number(line, skip_ws(b, i + 1))
                    .ok_or_else(|| err(line, start, "a letter followed by a number"))?;
                tokens.push(Token::Word {
                    letter: c,
                    value,
                    start,
                    end,
                });
                i = end;
            }
            _ => return Err(err(line, i, "a word (letter and number), a comment or ';'")),
        }
    }
    Ok(LineKind::Block { block_delete })
}

fn skip_ws(b: &[u8], mut i: usize) -> usize {
    while b.get(i).is_some_and(|c| c.is_ascii_whitespace()) {
        i += 1;
    }
    i
}

/// The text from `at` to the next space (for messages).
fn err(line: &str, at: usize, expected: &'static str) -> LexError {
    let rest = line.get(at..).unwrap_or("");
    let text: String = rest
        .chars()
        .take_while(|c| !c.is_whitespace())
        .take(24)
        .collect();
    LexError {
        column: at,
        text,
        expected,
    }
}

/// A number at `i` (after optional spaces): `[+-]? digits [. digits]` or `[+-]? . digits`.
fn number(line: &str, i: usize) -> Option<(f64, usize)> {
    let b = line.as_bytes();
    let mut j = skip_ws(b, i);
    let negative = b.get(j) == Some(&b'-');
    if matches!(b.get(j), Some(b'+' | b'-')) {
        j = skip_ws(b, j + 1);
    }
    let start = j;
    let mut digits = 0;
    // The digits as an integer (while it fits) and how many follow the point.
    let mut mantissa: u64 = 0;
    let mut fraction = 0;
    while let Some(d) = b.get(j).filter(|c| c.is_ascii_digit()) {
        mantissa = mantissa.wrapping_mul(10).wrapping_add(u64::from(d - b'0'));
        j += 1;
        digits += 1;
    }
    if b.get(j) == Some(&b'.') {
        j += 1;
        while let Some(d) = b.get(j).filter(|c| c.is_ascii_digit()) {
            mantissa = mantissa.wrapping_mul(10).wrapping_add(u64::from(d - b'0'));
            j += 1;
            digits += 1;
            fraction += 1;
        }
    }
    if digits == 0 {
        return None;
    }
    let value = match exact_decimal(mantissa, digits, fraction) {
        Some(v) => v,
        None => {
            // A number glued to a letter other than the next word's (`1e5`, `1x`) is still
            // fine: the letter starts the next word. Rust's parser accepts every form we let
            // through.
            let text = line.get(start..j)?;
            text.parse().ok()?
        }
    };
    let value = if negative { -value } else { value };
    value.is_finite().then_some((value, j))
}

/// Powers of ten that are exact in f64 (10²² is the last: 5²² < 2⁵³).
const EXACT_POWERS_OF_TEN: [f64; 23] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16,
    1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
];

/// The value of the decimal `mantissa · 10^−fraction` (`digits` digits in all) when it is
/// computed exactly by one division (Clinger's fast path): the mantissa at most 2⁵³ (exact in
/// f64; at most 19 digits, so the integer did not wrap) and `10^fraction` exact. The quotient
/// of two exact numbers rounded once is the correctly rounded decimal, the value Rust's
/// parser returns; other numbers (`None`) go to that parser.
fn exact_decimal(mantissa: u64, digits: usize, fraction: usize) -> Option<f64> {
    const MAX_EXACT: u64 = 1 << 53;
    if digits > 19 || mantissa > MAX_EXACT {
        return None;
    }
    let power = EXACT_POWERS_OF_TEN.get(fraction)?;
    // The mantissa is at most 2⁵³: the conversion is exact.
    #[allow(clippy::cast_precision_loss)]
    let m = mantissa as f64;
    Some(m / power)
}

/// `NAME=number` or `NAME(args)` at `start`.
fn keyword(line: &str, start: usize, tokens: &mut Vec<Token>) -> Result<usize, LexError> {
    let b = line.as_bytes();
    let mut j = start;
    while b
        .get(j)
        .is_some_and(|c| c.is_ascii_alphanumeric() || *c == b'_')
    {
        j += 1;
    }
    let name = line.get(start..j).unwrap_or("").to_ascii_uppercase();
    let k = skip_ws(b, j);
    match b.get(k) {
        Some(b'=') => {
            let (value, end) =
                number(line, k + 1).ok_or_else(|| err(line, start, "NAME=number"))?;
            tokens.push(Token::Assign { name, value });
            Ok(end)
        }
        Some(b'(') => {
            let close = line
                .get(k..)
                .and_then(|s| s.find(')'))
                .ok_or_else(|| err(line, start, "NAME(arguments)"))?;
            let args = line.get(k + 1..k + close).unwrap_or("").to_string();
            tokens.push(Token::Call { name, args });
            Ok(k + close + 1)
        }
        _ => Err(err(line, start, "a word: one letter and a number")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn words(line: &str) -> Vec<(char, f64)> {
        let mut t = Vec::new();
        lex(line, &mut t).unwrap();
        t.iter()
            .filter_map(|t| match t {
                Token::Word { letter, value, .. } => Some((char::from(*letter), *value)),
                _ => None,
            })
            .collect()
    }

    #[test]
    fn lexes_words_comments_and_spacing() {
        assert_eq!(
            words("N10 g1x-1.5 Y .5 (comment) Z+2 ; rest X9"),
            vec![('N', 10.0), ('G', 1.0), ('X', -1.5), ('Y', 0.5), ('Z', 2.0)]
        );
        assert_eq!(words("X10."), vec![('X', 10.0)]);
        assert_eq!(words("G 1 X - 3"), vec![('G', 1.0), ('X', -3.0)]);
        let mut t = Vec::new();
        assert_eq!(lex(" % ", &mut t), Ok(LineKind::Percent));
        assert_eq!(
            lex("/G0 X1", &mut t),
            Ok(LineKind::Block { block_delete: true })
        );
    }

    #[test]
    fn lexes_sinumerik_calls_and_assignments() {
        let mut t = Vec::new();
        lex("CYCLE832(0.01,_FINISH,1)", &mut t).unwrap();
        assert_eq!(
            t,
            vec![Token::Call {
                name: "CYCLE832".into(),
                args: "0.01,_FINISH,1".into()
            }]
        );
        lex("G2 X1 I1 TURN=3", &mut t).unwrap();
        assert_eq!(
            t.last(),
            Some(&Token::Assign {
                name: "TURN".into(),
                value: 3.0
            })
        );
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(20000))]
        /// The fast path gives the value Rust's parser gives, to the bit, on 20 000 decimals
        /// of every shape G-code has (up to 22 digits, up to 22 after the point, leading
        /// zeros, no digits before or after the point).
        #[test]
        fn fast_decimals_are_the_parsers(
            int in proptest::collection::vec(0u8..10, 0..12),
            frac in proptest::option::of(proptest::collection::vec(0u8..10, 0..23)),
        ) {
            let digit = |d: &u8| char::from(b'0' + d);
            let mut text: String = int.iter().map(digit).collect();
            if let Some(f) = &frac {
                text.push('.');
                text.extend(f.iter().map(digit));
            }
            let parsed: Option<f64> = text.parse().ok();
            let lexed = number(&text, 0).map(|(v, _)| v);
            proptest::prop_assert_eq!(lexed.map(f64::to_bits), parsed.map(f64::to_bits), "{}", text);
            let neg = format!("-{text}");
            let lexed = number(&neg, 0).map(|(v, _)| v);
            proptest::prop_assert_eq!(lexed.map(f64::to_bits), parsed.map(|v| (-v).to_bits()), "{}", neg);
        }
    }

    /// The fast path's edges: 2⁵³ and 2⁵³ + 1 (the first not exact), 19 and 20 digits,
    /// 10⁻²² and 10⁻²³, halfway cases, against Rust's parser.
    #[test]
    fn fast_decimal_edges_are_the_parsers() {
        for text in [
            "9007199254740992",
            "9007199254740993",
            "900719925474099.3",
            "1234567890123456789",
            "12345678901234567890",
            "0.0000000000000000000001",
            "0.00000000000000000000001",
            "1.0000000000000002220446049250313080847263336181640625",
            "0.1",
            "0.3",
            "2.675",
            "000000000000000000000000000001.5",
            "123.",
            ".5",
        ] {
            let parsed: f64 = text.parse().unwrap();
            let lexed = number(text, 0).unwrap().0;
            assert_eq!(lexed.to_bits(), parsed.to_bits(), "{text}");
        }
    }

    #[test]
    fn refuses_garbage_with_the_column() {
        let mut t = Vec::new();
        for (line, col) in [
            ("G1 XNaN", 3),
            ("G1 X#1", 3),
            ("G1 X[1+2]", 3),
            ("G1 X1 (open", 6),
            ("G1 X", 3),
            ("G1 X1 @", 6),
            ("G1 X-", 3),
        ] {
            let e = lex(line, &mut t).unwrap_err();
            assert_eq!(e.column, col, "{line}: {e:?}");
        }
        // Exponent notation is refused as the word it was typed in (`X1e400` was lexed as
        // X1 and a word E400; the error named `e400`), with the word's column.
        for line in ["G1 X1e400 F600", "G1 X1E5", "G1 X-2.5e-3"] {
            let e = lex(line, &mut t).unwrap_err();
            assert_eq!(e.column, 3, "{line}: {e:?}");
            assert!(
                e.text.starts_with('X') && e.expected.contains("exponent"),
                "{e:?}"
            );
        }
        // A word E after a number with no digits after it is still a word of its own.
        assert!(lex("G1 X1 E", &mut t).is_err());
        // A number too large for f64 is garbage, not infinity.
        let big = format!("X1{}", "0".repeat(400));
        assert!(lex(&big, &mut t).is_err());
    }
}
