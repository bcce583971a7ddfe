//! One block's words, gathered and checked before the interpreter executes them: which G
//! and M codes a dialect has, each letter's value within [`MAX_WORD_VALUE`].

use crate::error::InputError;
use crate::gcode::dialect::Dialect;
use crate::gcode::lexer::Token;

/// One block's words, gathered before execution.
#[derive(Debug, Default)]
pub(crate) struct Block {
    pub(crate) g: Vec<(u16, usize)>,
    pub(crate) m: Vec<u16>,
    pub(crate) words: [Option<f64>; 26],
    pub(crate) turn: Option<f64>,
    pub(crate) cycle832: Option<String>,
    /// A Sinumerik drilling cycle call: its name and arguments.
    pub(crate) drill_cycle: Option<(String, String)>,
    /// LinuxCNC's polar words `@` (radius) and `^` (angle, degrees).
    pub(crate) polar: [Option<f64>; 2],
}

/// What went wrong in a block: the word (or what) and what would be accepted.
pub(crate) struct BlockError {
    pub(crate) what: String,
    pub(crate) value: String,
    pub(crate) expected: String,
    /// True when `lenient` may skip it (an unsupported word).
    pub(crate) unsupported: bool,
}

impl BlockError {
    pub(crate) fn new(
        what: &str,
        value: impl std::fmt::Display,
        expected: impl Into<String>,
    ) -> Self {
        BlockError {
            what: what.to_string(),
            value: value.to_string(),
            expected: expected.into(),
            unsupported: false,
        }
    }

    pub(crate) fn unsupported(value: impl std::fmt::Display, expected: &str) -> Self {
        BlockError {
            unsupported: true,
            ..BlockError::new("G-code word", value, expected)
        }
    }

    pub(crate) fn into_input(self, origin: String) -> InputError {
        InputError::new(self.what, self.value)
            .at(origin)
            .expected(self.expected)
    }
}

/// Largest magnitude of a word's number: a kilometre in µm, far beyond any machine, and small
/// enough that squares of it (arc geometry) stay finite.
pub const MAX_WORD_VALUE: f64 = 1e9;

/// The letters every dialect's words may have besides G and M: D F H I J K L N O P Q R S T X
/// Y Z.
fn letter_ok(l: u8) -> bool {
    matches!(
        l,
        b'D' | b'F'
            | b'H'
            | b'I'
            | b'J'
            | b'K'
            | b'L'
            | b'N'
            | b'O'
            | b'P'
            | b'Q'
            | b'R'
            | b'S'
            | b'T'
            | b'X'
            | b'Y'
            | b'Z'
    )
}

pub(crate) fn letter_index(l: u8) -> usize {
    usize::from(l.saturating_sub(b'A')).min(25)
}

impl Block {
    pub(crate) fn take(&mut self, l: u8) -> Option<f64> {
        self.words.get_mut(letter_index(l)).and_then(Option::take)
    }

    /// A word the block gathered but nothing used (N and O are always fine).
    pub(crate) fn leftover(&self) -> Option<(u8, f64)> {
        (b'A'..=b'Z')
            .zip(self.words.iter())
            .find_map(|(l, w)| w.filter(|_| l != b'N' && l != b'O').map(|v| (l, v)))
    }

    pub(crate) fn has_g(&self, code: u16) -> bool {
        self.g.iter().any(|&(g, _)| g == code)
    }

    /// Gathers `tokens` into a block; unsupported words are refused (or, with `skip`, left
    /// out and reported through `warn`).
    pub(crate) fn gather(
        &mut self,
        tokens: &[Token],
        line: &str,
        dialect: Dialect,
        mut warn: impl FnMut(BlockError),
        lenient: bool,
    ) -> Result<(), BlockError> {
        self.g.clear();
        self.m.clear();
        self.words = [None; 26];
        self.turn = None;
        self.cycle832 = None;
        self.drill_cycle = None;
        self.polar = [None; 2];
        for t in tokens {
            let r = self.gather_one(t, line, dialect);
            match r {
                Err(e) if e.unsupported && lenient => warn(e),
                other => other?,
            }
        }
        Ok(())
    }

    fn gather_one(&mut self, t: &Token, line: &str, dialect: Dialect) -> Result<(), BlockError> {
        match t {
            Token::Word {
                letter,
                value,
                start,
                end,
            } => {
                // The word's text, for messages only.
                let text = || line.get(*start..*end).unwrap_or("?").trim();
                if value.abs() > MAX_WORD_VALUE {
                    return Err(BlockError::new(
                        "G-code number",
                        text(),
                        format!("a magnitude of at most {MAX_WORD_VALUE:e}"),
                    ));
                }
                match letter {
                    b'G' => {
                        let code = (value * 10.0).round();
                        if (value * 10.0 - code).abs() > 1e-6 || !(0.0..=9999.0).contains(&code) {
                            return Err(BlockError::unsupported(text(), "a supported G code"));
                        }
                        let code = code as u16;
                        if dialect == Dialect::LinuxCnc && is_refused_cycle(code) {
                            return Err(BlockError::unsupported(
                                text(),
                                "a canned cycle the reader expands: G73, G81, G82, G83, G85, G89 \
                                 (not G74/G76/G84 tapping and threading, G86/G87/G88)",
                            ));
                        }
                        if !g_supported(code, dialect) {
                            return Err(BlockError::unsupported(
                                text(),
                                "a supported G code (see the reader docs)",
                            ));
                        }
                        self.g.push((code, *start));
                    }
                    b'M' => {
                        let code = value.round();
                        if (value - code).abs() > 1e-9
                            || !matches!(code as i64, 0..=9 | 30 | 48..=53 | 61..=66 | 70..=73)
                        {
                            return Err(BlockError::unsupported(
                                text(),
                                "M0–M9, M30, M48–M53, M61–M66 or M70–M73",
                            ));
                        }
                        self.m.push(code as u16);
                    }
                    b'@' | b'^' if dialect == Dialect::LinuxCnc => {
                        let k = usize::from(*letter == b'^');
                        match self.polar.get_mut(k) {
                            Some(Some(_)) => {
                                return Err(BlockError::new(
                                    "G-code word",
                                    text(),
                                    format!("one {} word per block", char::from(*letter)),
                                ));
                            }
                            Some(s) => *s = Some(*value),
                            None => {}
                        }
                    }
                    l if letter_ok(*l)
                        || (dialect == Dialect::LinuxCnc && matches!(l, b'A' | b'B' | b'C')) =>
                    {
                        let slot = self.words.get_mut(letter_index(*l));
                        match slot {
                            Some(Some(_)) => {
                                return Err(BlockError::new(
                                    "G-code word",
                                    text(),
                                    format!("one {} word per block", char::from(*l)),
                                ));
                            }
                            Some(s) => *s = Some(*value),
                            None => {}
                        }
                    }
                    _ => {
                        return Err(BlockError::unsupported(
                            text(),
                            "words G, M, N, O, X, Y, Z, I, J, K, R, F, S, T, P, Q, H, D \
                             (and A, B, C in LinuxCNC programs)",
                        ));
                    }
                }
            }
            Token::Assign { name, value } if name == "TURN" && dialect == Dialect::Sinumerik => {
                self.turn = Some(*value);
            }
            Token::Call { name, args } if name == "CYCLE832" && dialect == Dialect::Sinumerik => {
                self.cycle832 = Some(args.clone());
            }
            Token::Call { name, args }
                if matches!(name.as_str(), "CYCLE81" | "CYCLE82" | "CYCLE83")
                    && dialect == Dialect::Sinumerik =>
            {
                if self.drill_cycle.is_some() {
                    return Err(BlockError::new(
                        "Sinumerik cycle",
                        format!("{name}({args})"),
                        "one drilling cycle per block",
                    ));
                }
                self.drill_cycle = Some((name.clone(), args.clone()));
            }
            Token::Assign { name, value } => {
                return Err(BlockError::unsupported(
                    format!("{name}={value}"),
                    "TURN= (sinumerik)",
                ));
            }
            Token::Call { name, args } => {
                return Err(BlockError::unsupported(
                    format!("{name}({args})"),
                    "CYCLE832, CYCLE81, CYCLE82 or CYCLE83 (sinumerik)",
                ));
            }
        }
        Ok(())
    }
}

/// G codes (×10) the reader understands in `dialect`.
pub(crate) fn g_supported(code: u16, dialect: Dialect) -> bool {
    const COMMON: &[u16] = &[
        0, 10, 20, 30, 40, 90, 170, 180, 190, 400, 430, 490, 530, 540, 550, 560, 570, 580, 590,
        610, 640, 800, 900, 910, 930, 940,
    ];
    // LinuxCNC: also G5, G5.1, G5.2/G5.3, G6.2 (LinuxCNC master), G7/G8, G10, G28/G30,
    // G33/G33.1, G38.2–G38.5, G41/G42/G41.1/G42.1, G59.1–.3, G61.1, G73, G81–G83, G85, G89,
    // G90.1/G91.1, G92–G92.3, G95, G96/G97, G98/G99.
    const LINUXCNC: &[u16] = &[
        50, 51, 52, 53, 62, 70, 80, 100, 200, 210, 280, 300, 330, 331, 382, 383, 384, 385, 410,
        411, 420, 421, 591, 592, 593, 611, 730, 810, 820, 830, 850, 890, 901, 911, 920, 921, 922,
        923, 950, 960, 970, 980, 990,
    ];
    COMMON.contains(&code)
        || match dialect {
            Dialect::LinuxCnc => LINUXCNC.contains(&code),
            Dialect::Grbl => matches!(code, 200 | 210 | 911),
            Dialect::Fanuc => matches!(
                code,
                200 | 210 | 51 | 90 | 730 | 810 | 820 | 830 | 980 | 990
            ),
            Dialect::Sinumerik => matches!(code, 90 | 600 | 6420 | 700 | 710 | 7000 | 7100),
        }
}

/// Canned cycles recognised but refused (G74, G76, G84, G86–G88).
fn is_refused_cycle(code: u16) -> bool {
    matches!(code, 740 | 760 | 840 | 860 | 870 | 880)
}
