//! M98, M99 and G65 taken out of a block: what the block asks of the program flow (see
//! the parent module for their meaning), and G66/G66.1/G67 refused.

use super::super::lexer::Token;
use super::super::macro_b::{self, LOCALS, Locals};

type R2<T> = Result<T, String>;

/// A G or M word's code times ten (`G66.1` → 661), when it is one.
fn code(v: f64) -> Option<i64> {
    let c = (v * 10.0).round();
    ((v * 10.0 - c).abs() < 1e-6).then_some(c as i64)
}

/// What an NC block asks of the program flow.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Control {
    /// M98 (no arguments) or G65 (arguments).
    Call {
        program: u32,
        count: u32,
        args: Option<Box<Locals>>,
    },
    /// M99 [P seq].
    Return { seq: Option<u32> },
}

/// Takes M98/M99/G65 and their words out of a block; refuses G66/G67.
pub(crate) fn take_control(tokens: &mut Vec<Token>) -> R2<Option<Control>> {
    let (mut m98, mut m99, mut g65) = (false, false, false);
    for t in tokens.iter() {
        if let Token::Word { letter, value, .. } = t
            && matches!(letter, b'G' | b'M')
        {
            match (letter, code(*value)) {
                (b'M', Some(980)) => m98 = true,
                (b'M', Some(990)) => m99 = true,
                (b'G', Some(650)) => g65 = true,
                (b'G', Some(660 | 661 | 670)) => {
                    let v = value;
                    return Err(format!(
                        "G{v} (modal macro call) is not supported: the reader runs G65 macro \
                         calls and M98/M99 subprograms"
                    ));
                }
                _ => {}
            }
        }
    }
    if !(m98 || m99 || g65) {
        return Ok(None);
    }
    if usize::from(m98) + usize::from(m99) + usize::from(g65) > 1 {
        return Err("one of M98, M99 and G65 in a block".into());
    }
    let mut p = None;
    let mut l = None;
    let mut args: Locals = [None; LOCALS];
    let mut spec2 = (0usize, None::<usize>);
    let ijk_repeats = {
        let n = |c: u8| {
            tokens
                .iter()
                .filter(|t| matches!(t, Token::Word { letter, .. } if *letter == c))
                .count()
        };
        n(b'I') > 1 || n(b'J') > 1 || n(b'K') > 1
    };
    let mut keep = Vec::with_capacity(tokens.len());
    for t in tokens.drain(..) {
        let Token::Word { letter, value, .. } = t else {
            keep.push(t);
            continue;
        };
        match letter {
            b'M' if matches!(code(value), Some(980 | 990)) => {}
            b'G' if code(value) == Some(650) => {}
            b'P' => p = Some(value),
            b'L' if !m99 => l = Some(value),
            b'N' | b'O' => keep.push(t),
            b'G' if g65 => {
                return Err(format!(
                    "G{value} with G65: a G65 block holds only P, L and arguments"
                ));
            }
            _ if g65 => {
                let k = match letter {
                    b'I' | b'J' | b'K' if ijk_repeats => {
                        let pos = usize::from(letter - b'I');
                        if spec2.1.is_some_and(|last| pos <= last) {
                            spec2.0 += 1;
                        }
                        spec2.1 = Some(pos);
                        if spec2.0 >= 10 {
                            return Err("more than 10 sets of I J K arguments".into());
                        }
                        4 + 3 * spec2.0 + pos
                    }
                    _ => macro_b::argument_index(letter).unwrap_or(0),
                };
                if let Some(slot) = k.checked_sub(1).and_then(|k| args.get_mut(k)) {
                    *slot = Some(value);
                }
            }
            _ => keep.push(t),
        }
    }
    *tokens = keep;
    let whole = |v: f64, what: &str| {
        if v >= 0.0 && v.fract() == 0.0 && v <= 99_999_999.0 {
            Ok(v as u32)
        } else {
            Err(format!("{what}{v}: a whole number from 0 to 99999999"))
        }
    };
    if m99 {
        return Ok(Some(Control::Return {
            seq: p.map(|p| whole(p, "M99 P")).transpose()?,
        }));
    }
    let word = if g65 { "G65" } else { "M98" };
    let p = whole(
        p.ok_or_else(|| format!("{word} without P (the program number)"))?,
        &format!("{word} P"),
    )?;
    let (program, count) = match l {
        Some(l) => (p, whole(l, &format!("{word} L"))?),
        None if !g65 && p > 9999 => (p % 10_000, p / 10_000),
        None => (p, 1),
    };
    Ok(Some(Control::Call {
        program,
        count,
        args: g65.then(|| Box::new(args)),
    }))
}
