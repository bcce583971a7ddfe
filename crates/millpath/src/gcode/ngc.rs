//! One line of RS274/NGC with parameters, expressions and O-words → words with their values,
//! parameter settings and an O-word command (LinuxCNC 2.9's `read_items`).
//!
//! The line is first brought to LinuxCNC's canonical form: lower case and without spaces
//! outside comments (`G1 X [#<tool dia> / 2]` reads as `g1x[#<tooldia>/2]`). Comments are
//! kept aside: `(MSG, …)`, `(DEBUG, …)` and `(PRINT, …)` become messages, the last two with
//! `#n` and `#<name>` replaced by their values (`%f`: six decimals). A word is a letter and a
//! value ([`super::expr`]); `#… = value` sets a parameter after the line has been read; an
//! `O` word (`o<name>` or `o123`) followed by a keyword is a control command (module
//! `oword`), alone on its line. Lines without `#`, `[`, an O word or a message comment
//! take the plain lexer ([`super::lexer`]), whose speed this path does not touch.

use super::expr::{Cursor, ParamRef, Params};
use super::lexer::Token;

/// The O-word keywords.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Kw {
    Sub,
    Endsub,
    Call,
    Return,
    If,
    Elseif,
    Else,
    Endif,
    While,
    Endwhile,
    Do,
    Repeat,
    Endrepeat,
    Break,
    Continue,
}

const KEYWORDS: [(&[u8], Kw); 15] = [
    (b"endsub", Kw::Endsub),
    (b"endwhile", Kw::Endwhile),
    (b"endrepeat", Kw::Endrepeat),
    (b"endif", Kw::Endif),
    (b"elseif", Kw::Elseif),
    (b"else", Kw::Else),
    (b"sub", Kw::Sub),
    (b"call", Kw::Call),
    (b"return", Kw::Return),
    (b"if", Kw::If),
    (b"while", Kw::While),
    (b"do", Kw::Do),
    (b"repeat", Kw::Repeat),
    (b"break", Kw::Break),
    (b"continue", Kw::Continue),
];

impl Kw {
    /// The keyword as written (`endwhile`).
    pub(crate) fn word(self) -> &'static str {
        KEYWORDS
            .iter()
            .find(|(_, k)| *k == self)
            .and_then(|(w, _)| std::str::from_utf8(w).ok())
            .unwrap_or("")
    }
}

/// An O word's label as written: `o100` for a number, `o<name>` for a name.
pub(crate) fn o_label(name: &str) -> String {
    if name.bytes().all(|b| b.is_ascii_digit()) {
        format!("o{name}")
    } else {
        format!("o<{name}>")
    }
}

/// An O-word command: its name, keyword and the values of its bracketed arguments.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct OWord {
    pub(crate) name: String,
    pub(crate) kw: Kw,
    pub(crate) args: Vec<f64>,
}

/// A parsed line.
#[derive(Debug, Default)]
pub(crate) struct NgcLine {
    /// The line started with `/`.
    pub(crate) block_delete: bool,
    /// The canonical text (the words' `start..end` index it).
    pub(crate) text: String,
    pub(crate) tokens: Vec<Token>,
    pub(crate) assigns: Vec<(ParamRef, f64)>,
    pub(crate) oword: Option<OWord>,
    pub(crate) messages: Vec<String>,
}

/// Whether `line` needs this parser rather than the plain lexer. No allocation: every line
/// of a plain program passes here.
pub(crate) fn needed(line: &[u8]) -> bool {
    // One pass for parameters, expressions and comments.
    let mut comment = false;
    for &c in line {
        match c {
            b'#' | b'[' => return true,
            b'(' => comment = true,
            _ => {}
        }
    }
    if comment && message_comment(line) {
        return true;
    }
    starts_with_o(line) && o_header(line).is_some()
}

/// Whether the first word (after `/` and an N word) is an O word.
fn starts_with_o(line: &[u8]) -> bool {
    let mut it = line
        .iter()
        .copied()
        .filter(|c| !c.is_ascii_whitespace())
        .peekable();
    if it.peek() == Some(&b'/') {
        it.next();
    }
    if matches!(it.peek(), Some(b'n' | b'N')) {
        it.next();
        while it.peek().is_some_and(u8::is_ascii_digit) {
            it.next();
        }
    }
    matches!(it.peek(), Some(b'o' | b'O'))
}

/// Whether a comment starts with MSG, DEBUG or PRINT (any case, spaces allowed).
fn message_comment(line: &[u8]) -> bool {
    line.iter().enumerate().any(|(i, &c)| {
        c == b'(' && {
            let mut head = [0u8; 5];
            let mut n = 0;
            for &d in line.iter().skip(i + 1) {
                if n == head.len() || d == b')' {
                    break;
                }
                if !d.is_ascii_whitespace()
                    && let Some(h) = head.get_mut(n)
                {
                    *h = d.to_ascii_lowercase();
                    n += 1;
                }
            }
            head.starts_with(b"msg,") || head.starts_with(b"debug") || head.starts_with(b"print")
        }
    })
}

/// The canonical form of `line` (lower case, no spaces, no comments) and its comments.
pub(crate) fn canonical(line: &str) -> Result<(String, Vec<String>), String> {
    let mut out = String::with_capacity(line.len());
    let mut comments = Vec::new();
    let mut chars = line.char_indices();
    while let Some((i, c)) = chars.next() {
        match c {
            '(' => {
                let rest = line.get(i + 1..).unwrap_or("");
                let close = rest.find(')').ok_or("a comment not closed by ')'")?;
                let body = rest.get(..close).unwrap_or("");
                if body.contains('(') {
                    return Err("a comment with a nested '('".into());
                }
                comments.push(body.to_string());
                for _ in 0..body.chars().count() + 1 {
                    chars.next();
                }
            }
            ';' => break,
            c if c.is_whitespace() => {}
            c => out.push(c.to_ascii_lowercase()),
        }
    }
    Ok((out, comments))
}

/// The name and keyword of an O-word line, without evaluating anything (for skipping).
pub(crate) fn o_header(line: &[u8]) -> Option<(String, Kw)> {
    let mut s: Vec<u8> = Vec::with_capacity(line.len());
    for &c in line {
        if c == b'(' || c == b';' {
            break;
        }
        if !c.is_ascii_whitespace() {
            s.push(c.to_ascii_lowercase());
        }
    }
    let mut i = usize::from(s.first() == Some(&b'/'));
    if s.get(i) == Some(&b'n') {
        i += 1;
        while s.get(i).is_some_and(u8::is_ascii_digit) {
            i += 1;
        }
    }
    if s.get(i) != Some(&b'o') {
        return None;
    }
    let (name, j) = o_name(&s, i + 1)?;
    let rest = s.get(j..)?;
    KEYWORDS
        .iter()
        .find(|(k, _)| rest.starts_with(k))
        .map(|(_, kw)| (name, *kw))
}

/// `<name>` or digits at `i`; the name and the index after it. Numbers lose leading zeros.
fn o_name(s: &[u8], i: usize) -> Option<(String, usize)> {
    if s.get(i) == Some(&b'<') {
        let end = s.get(i + 1..)?.iter().position(|&c| c == b'>')?;
        let name = String::from_utf8_lossy(s.get(i + 1..i + 1 + end)?).to_string();
        return (!name.is_empty()).then_some((name, i + end + 2));
    }
    let mut j = i;
    while s.get(j).is_some_and(u8::is_ascii_digit) {
        j += 1;
    }
    let digits = std::str::from_utf8(s.get(i..j)?).ok()?;
    let n: u64 = digits.parse().ok()?;
    Some((n.to_string(), j))
}

/// Parses `line`, evaluating values with `p`. Errors name what is wrong and where.
pub(crate) fn parse(line: &str, p: &dyn Params, out: &mut NgcLine) -> Result<(), String> {
    out.tokens.clear();
    out.assigns.clear();
    out.oword = None;
    out.messages.clear();
    let (text, comments) = canonical(line)?;
    for c in &comments {
        message(c, p, &mut out.messages);
    }
    out.text = text;
    let s = out.text.as_bytes();
    let mut c = Cursor::new(s, 0);
    out.block_delete = c.peek() == Some(b'/');
    if out.block_delete {
        c.i += 1;
    }
    while let Some(l) = c.peek() {
        let start = c.i;
        match l {
            b'o' => {
                let (name, j) = o_name(s, c.i + 1)
                    .ok_or_else(|| format!("an O word needs <name> or a number: '{}'", c.rest()))?;
                c.i = j;
                let (k, kw) = KEYWORDS
                    .iter()
                    .find(|(k, _)| s.get(c.i..).is_some_and(|r| r.starts_with(k)))
                    .ok_or_else(|| {
                        format!(
                            "o{name} without a keyword (sub endsub call return if elseif else \
                             endif while endwhile do repeat endrepeat break continue): '{}'",
                            c.rest()
                        )
                    })?;
                c.i += k.len();
                let mut args = Vec::new();
                while c.peek() == Some(b'[') {
                    args.push(c.bracketed(p)?);
                }
                if c.peek().is_some() {
                    return Err(format!("unexpected '{}' after o{name} {kw:?}", c.rest()));
                }
                if !out
                    .tokens
                    .iter()
                    .all(|t| matches!(t, Token::Word { letter: b'N', .. }))
                    || !out.assigns.is_empty()
                {
                    return Err(format!("o{name} {kw:?} must be alone on its line"));
                }
                out.tokens.clear();
                out.oword = Some(OWord {
                    name,
                    kw: *kw,
                    args,
                });
                return Ok(());
            }
            b'#' => {
                c.i += 1;
                let r = c.param_ref(p)?;
                if c.peek() != Some(b'=') {
                    return Err(format!(
                        "'=' expected after the parameter at '{}'",
                        c.rest()
                    ));
                }
                c.i += 1;
                let v = c.value(p)?;
                out.assigns.push((r, v));
            }
            b'a'..=b'z' | b'@' | b'^' => {
                c.i += 1;
                let value = c.value(p)?;
                out.tokens.push(Token::Word {
                    letter: l.to_ascii_uppercase(),
                    value,
                    start,
                    end: c.i,
                });
            }
            _ => return Err(format!("a word, '#' or 'o' expected at '{}'", c.rest())),
        }
    }
    Ok(())
}

/// A `(MSG,…)`, `(DEBUG,…)` or `(PRINT,…)` comment's message.
fn message(comment: &str, p: &dyn Params, out: &mut Vec<String>) {
    let t = comment.trim_start();
    let lower = t.to_ascii_lowercase();
    let (kind, substitute) = if lower.starts_with("msg,") {
        ("MSG", false)
    } else if lower.starts_with("debug,") {
        ("DEBUG", true)
    } else if lower.starts_with("print,") {
        ("PRINT", true)
    } else {
        return;
    };
    let body = t.split_once(',').map_or("", |(_, b)| b);
    let text = if substitute {
        substitute_params(body, p)
    } else {
        body.to_string()
    };
    out.push(format!("{kind}: {text}"));
}

/// `#n`, `#<name>` in a message replaced by their values (LinuxCNC prints `%lf`).
fn substitute_params(body: &str, p: &dyn Params) -> String {
    let b = body.as_bytes();
    let mut out = String::new();
    let mut i = 0;
    while let Some(&ch) = b.get(i) {
        if ch == b'#' {
            if b.get(i + 1) == Some(&b'<')
                && let Some(end) = body.get(i + 2..).and_then(|r| r.find('>'))
            {
                let name: String = body
                    .get(i + 2..i + 2 + end)
                    .unwrap_or("")
                    .chars()
                    .filter(|c| !c.is_whitespace())
                    .map(|c| c.to_ascii_lowercase())
                    .collect();
                match p.named(&name) {
                    Ok(v) => out.push_str(&format!("{v:.6}")),
                    Err(_) => out.push_str("######"),
                }
                i += end + 3;
                continue;
            }
            let mut j = i + 1;
            while b.get(j).is_some_and(u8::is_ascii_digit) {
                j += 1;
            }
            if j > i + 1
                && let Some(n) = body.get(i + 1..j).and_then(|d| d.parse::<f64>().ok())
            {
                match p.numbered(n) {
                    Ok(v) => out.push_str(&format!("{v:.6}")),
                    Err(_) => out.push_str("######"),
                }
                i = j;
                continue;
            }
        }
        let len = body
            .get(i..)
            .and_then(|r| r.chars().next())
            .map_or(1, char::len_utf8);
        out.push_str(body.get(i..i + len).unwrap_or(""));
        i += len;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    struct P;
    impl Params for P {
        fn numbered(&self, n: f64) -> Result<f64, String> {
            Ok(n)
        }
        fn named(&self, name: &str) -> Result<f64, String> {
            if name == "tooldia" {
                Ok(6.0)
            } else {
                Err(format!("#<{name}> not defined"))
            }
        }
        fn exists(&self, name: &str) -> bool {
            name == "tooldia"
        }
    }

    #[test]
    fn words_settings_and_owords() {
        let mut l = NgcLine::default();
        parse(
            "N10 G1 X [#<tool dia> / 2] y-#2 #3 = [1+2] (DEBUG, d=#<tool dia>)",
            &P,
            &mut l,
        )
        .unwrap();
        let w: Vec<(u8, f64)> = l
            .tokens
            .iter()
            .filter_map(|t| match t {
                Token::Word { letter, value, .. } => Some((*letter, *value)),
                _ => None,
            })
            .collect();
        assert_eq!(
            w,
            vec![(b'N', 10.0), (b'G', 1.0), (b'X', 3.0), (b'Y', -2.0)]
        );
        assert_eq!(l.assigns, vec![(ParamRef::Numbered(3), 3.0)]);
        assert_eq!(l.messages, vec!["DEBUG:  d=6.000000".to_string()]);
        parse("o<Loop> while [#1 lt 3]", &P, &mut l).unwrap();
        assert_eq!(
            l.oword,
            Some(OWord {
                name: "loop".into(),
                kw: Kw::While,
                args: vec![1.0]
            })
        );
        parse("o0100 call [1] [2]", &P, &mut l).unwrap();
        assert_eq!(
            l.oword.as_ref().map(|o| (o.name.as_str(), o.args.len())),
            Some(("100", 2))
        );
        assert_eq!(o_header(b"  O<x> EndIf"), Some(("x".into(), Kw::Endif)));
        assert_eq!(o_header(b"G1 X1"), None);
        assert!(needed(b"(msg, hello)") && needed(b"o1 sub") && !needed(b"G1 X1 (note)"));
        for bad in [
            "G1 X1 o1 endif",
            "o1 whilst",
            "#1 5",
            "G1 X[1",
            "o<> sub",
            "G1 X1 @",
        ] {
            assert!(parse(bad, &P, &mut l).is_err(), "{bad}");
        }
    }
}
