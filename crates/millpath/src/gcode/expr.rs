//! RS274/NGC values and expressions, as LinuxCNC 2.9 reads them (`interp_read.cc`,
//! `interp_execute.cc`): a small recursive-descent evaluator over a line that has been
//! lower-cased with its spaces removed (LinuxCNC's own preprocessing).
//!
//! ```text
//! value      = number | '[' expression ']' | '#' parameter | ('+'|'-') value | function
//! expression = value (binary value)*            left to right within a precedence level
//! binary     = '**'                                        precedence 6 (highest)
//!            | '*' | '/' | 'mod'                           5
//!            | '+' | '-'                                   4
//!            | 'eq' | 'ne' | 'gt' | 'ge' | 'lt' | 'le'     3
//!            | 'and' | 'or' | 'xor'                        2
//! function   = name '[' expression ']' | 'atan' '[' e ']' '/' '[' e ']' | 'exists' '[' #<name> ']'
//! parameter  = integer-value | '<' name '>'     (`##2`, `#[1+2]`, `#<tool_dia>`)
//! ```
//! A sign before a digit or `.` is part of the number (`-2**2` is 4, as in LinuxCNC). `mod`
//! is always ≥ 0 (`-1 mod 3` = 2). Comparisons use LinuxCNC's tolerance
//! [`TOLERANCE_EQUAL`] = 1e-6 (EQ, NE, LE, GE; GT and LT are exact). Trigonometry is in
//! degrees; `round` rounds half away from zero; `fix`/`fup` are floor/ceil. Division by
//! zero, a negative number to a fractional power, `sqrt` of a negative, `ln` of a
//! non-positive, `acos`/`asin` outside [-1, 1] and results that are NaN or infinite are
//! errors, as in LinuxCNC.
//!
//! Why hand-written: the grammar is a dozen rules with LinuxCNC's own quirks (signs glued to
//! numbers, `atan[a]/[b]`, `exists`, left-associative `**`, bracket-only grouping); a
//! parser generator or an expression crate would need as much code to bend to them, and a
//! dependency for 300 lines is not worth it.

/// Two numbers compare equal when they differ by less than this (LinuxCNC's
/// `TOLERANCE_EQUAL`, `interp_internal.hh`).
pub const TOLERANCE_EQUAL: f64 = 1e-6;

/// Deepest nesting of brackets and parameters accepted (a guard against hostile input).
pub const MAX_DEPTH: usize = 64;

/// Where parameters come from.
pub(crate) trait Params {
    /// Numbered parameter `n` (already checked to be an integer).
    fn numbered(&self, n: f64) -> Result<f64, String>;
    /// Named parameter `name` (lower case, no spaces).
    fn named(&self, name: &str) -> Result<f64, String>;
    /// Whether named parameter `name` exists.
    fn exists(&self, name: &str) -> bool;
}

/// A reference to a parameter, as on the left of `=`.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum ParamRef {
    /// `#n`.
    Numbered(usize),
    /// `#<name>` (lower case, no spaces).
    Named(String),
}

/// A cursor over a preprocessed line.
pub(crate) struct Cursor<'a> {
    pub(crate) s: &'a [u8],
    pub(crate) i: usize,
    depth: usize,
}

type R<T> = Result<T, String>;

impl<'a> Cursor<'a> {
    pub(crate) fn new(s: &'a [u8], i: usize) -> Self {
        Cursor { s, i, depth: 0 }
    }

    pub(crate) fn peek(&self) -> Option<u8> {
        self.s.get(self.i).copied()
    }

    fn peek_at(&self, k: usize) -> Option<u8> {
        self.s.get(self.i + k).copied()
    }

    fn starts_with(&self, t: &[u8]) -> bool {
        self.s.get(self.i..).is_some_and(|r| r.starts_with(t))
    }

    fn expect(&mut self, c: u8) -> R<()> {
        if self.peek() == Some(c) {
            self.i += 1;
            Ok(())
        } else {
            Err(format!("'{}' expected at '{}'", char::from(c), self.rest()))
        }
    }

    /// The rest of the line (for messages), shortened.
    pub(crate) fn rest(&self) -> String {
        let r = self.s.get(self.i..).unwrap_or_default();
        String::from_utf8_lossy(r.get(..r.len().min(24)).unwrap_or(r)).to_string()
    }

    fn deeper(&mut self) -> R<()> {
        self.depth += 1;
        if self.depth > MAX_DEPTH {
            return Err(format!("expression nested deeper than {MAX_DEPTH}"));
        }
        Ok(())
    }

    /// A real value (LinuxCNC's `read_real_value`).
    pub(crate) fn value(&mut self, p: &dyn Params) -> R<f64> {
        self.deeper()?;
        let c = self
            .peek()
            .ok_or("a value expected at the end of the line")?;
        let c1 = self.peek_at(1);
        let sign_only = |c1: Option<u8>| c1.is_some_and(|d| !d.is_ascii_digit() && d != b'.');
        let v = match c {
            b'[' => self.bracketed(p)?,
            b'#' => {
                self.i += 1;
                let r = self.param_ref(p)?;
                read_param(p, &r)?
            }
            b'+' if sign_only(c1) => {
                self.i += 1;
                self.value(p)?
            }
            b'-' if sign_only(c1) => {
                self.i += 1;
                -self.value(p)?
            }
            b'a'..=b'z' => self.function(p)?,
            _ => self.number()?,
        };
        self.depth -= 1;
        if v.is_nan() {
            return Err("calculation resulted in 'not a number'".into());
        }
        if v.is_infinite() {
            return Err("calculation resulted in 'infinity'".into());
        }
        Ok(v)
    }

    /// A number: signs, then digits and points (LinuxCNC's `read_real_number`).
    fn number(&mut self) -> R<f64> {
        let start = self.i;
        while matches!(self.peek(), Some(b'+' | b'-')) {
            self.i += 1;
        }
        while matches!(self.peek(), Some(b'0'..=b'9' | b'.')) {
            self.i += 1;
        }
        let text = self.s.get(start..self.i).unwrap_or_default();
        scanned_number(text, || format!("a number expected at '{}'", self.rest()))
    }

    /// `[ expression ]`.
    pub(crate) fn bracketed(&mut self, p: &dyn Params) -> R<f64> {
        self.expect(b'[')?;
        let v = self.expression(p, 0)?;
        self.expect(b']')?;
        Ok(v)
    }

    /// Operators of precedence above `min`, left to right (precedence climbing: the same
    /// result as LinuxCNC's two-stack evaluator).
    fn expression(&mut self, p: &dyn Params, min: u8) -> R<f64> {
        let mut left = self.value(p)?;
        loop {
            let Some((op, len)) = self.operator() else {
                return Ok(left);
            };
            let prec = precedence(op);
            if prec <= min {
                return Ok(left);
            }
            self.i += len;
            self.deeper()?;
            let right = self.expression(p, prec)?;
            self.depth -= 1;
            left = binary(op, left, right)?;
        }
    }

    /// The binary operator at the cursor, and its length.
    fn operator(&self) -> Option<(Op, usize)> {
        const OPS: [(&[u8], Op); 15] = [
            (b"**", Op::Pow),
            (b"*", Op::Mul),
            (b"/", Op::Div),
            (b"mod", Op::Mod),
            (b"+", Op::Add),
            (b"-", Op::Sub),
            (b"eq", Op::Eq),
            (b"ne", Op::Ne),
            (b"gt", Op::Gt),
            (b"ge", Op::Ge),
            (b"lt", Op::Lt),
            (b"le", Op::Le),
            (b"and", Op::And),
            (b"or", Op::Or),
            (b"xor", Op::Xor),
        ];
        OPS.iter()
            .find(|(t, _)| self.starts_with(t))
            .map(|(t, op)| (*op, t.len()))
    }

    /// A function call (`sin[30]`, `atan[1]/[2]`, `exists[#<x>]`).
    fn function(&mut self, p: &dyn Params) -> R<f64> {
        const NAMES: [&[u8]; 14] = [
            b"abs", b"acos", b"asin", b"atan", b"cos", b"exists", b"exp", b"fix", b"fup", b"ln",
            b"round", b"sin", b"sqrt", b"tan",
        ];
        let Some(name) = NAMES
            .iter()
            .filter(|n| self.starts_with(n) && self.peek_at(n.len()) == Some(b'['))
            .max_by_key(|n| n.len())
        else {
            return Err(format!(
                "unknown function or word at '{}' (functions: ABS ACOS ASIN ATAN COS EXISTS EXP \
                 FIX FUP LN ROUND SIN SQRT TAN)",
                self.rest()
            ));
        };
        self.i += name.len();
        if *name == b"exists" {
            self.expect(b'[')?;
            self.expect(b'#')?;
            let r = self.param_ref(p)?;
            self.expect(b']')?;
            return Ok(match r {
                ParamRef::Named(n) => f64::from(u8::from(p.exists(&n))),
                ParamRef::Numbered(_) => 1.0,
            });
        }
        let x = self.bracketed(p)?;
        let deg = std::f64::consts::PI / 180.0;
        let domain = |ok: bool, what: &str| {
            if ok {
                Ok(())
            } else {
                Err(format!("{what} of {x}"))
            }
        };
        Ok(match *name {
            b"abs" => x.abs(),
            b"acos" => {
                domain((-1.0..=1.0).contains(&x), "ACOS")?;
                x.acos() / deg
            }
            b"asin" => {
                domain((-1.0..=1.0).contains(&x), "ASIN")?;
                x.asin() / deg
            }
            b"atan" => {
                self.expect(b'/')?;
                let y = self.bracketed(p)?;
                x.atan2(y) / deg
            }
            b"cos" => (x * deg).cos(),
            b"exp" => x.exp(),
            b"fix" => x.floor(),
            b"fup" => x.ceil(),
            b"ln" => {
                domain(x > 0.0, "LN")?;
                x.ln()
            }
            b"round" => x.round(),
            b"sin" => (x * deg).sin(),
            b"sqrt" => {
                domain(x >= 0.0, "SQRT")?;
                x.sqrt()
            }
            _ => (x * deg).tan(),
        })
    }

    /// After `#`: a parameter number (a value rounded to an integer) or `<name>`.
    pub(crate) fn param_ref(&mut self, p: &dyn Params) -> R<ParamRef> {
        if self.peek() == Some(b'<') {
            let start = self.i + 1;
            let end = self
                .s
                .get(start..)
                .and_then(|r| r.iter().position(|&c| c == b'>'))
                .ok_or("named parameter without its closing '>'")?;
            let name = String::from_utf8_lossy(self.s.get(start..start + end).unwrap_or_default())
                .to_string();
            if name.is_empty() {
                return Err("named parameter with an empty name".into());
            }
            self.i = start + end + 1;
            return Ok(ParamRef::Named(name));
        }
        let v = self.value(p)?;
        let n = v.round();
        if (v - n).abs() > 1e-4 || !(1.0..=f64::from(super::params::MAX_PARAM)).contains(&n) {
            return Err(format!(
                "parameter number {v} (1 to {})",
                super::params::MAX_PARAM
            ));
        }
        Ok(ParamRef::Numbered(n as usize))
    }
}

fn read_param(p: &dyn Params, r: &ParamRef) -> R<f64> {
    match r {
        ParamRef::Numbered(n) => p.numbered(*n as f64),
        ParamRef::Named(name) => p.named(name),
    }
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Op {
    Pow,
    Mul,
    Div,
    Mod,
    Add,
    Sub,
    Eq,
    Ne,
    Gt,
    Ge,
    Lt,
    Le,
    And,
    Or,
    Xor,
}

fn precedence(op: Op) -> u8 {
    match op {
        Op::Pow => 6,
        Op::Mul | Op::Div | Op::Mod => 5,
        Op::Add | Op::Sub => 4,
        Op::Eq | Op::Ne | Op::Gt | Op::Ge | Op::Lt | Op::Le => 3,
        Op::And | Op::Or | Op::Xor => 2,
    }
}

fn binary(op: Op, a: f64, b: f64) -> R<f64> {
    let t = |c: bool| if c { 1.0 } else { 0.0 };
    let close = (a - b).abs() < TOLERANCE_EQUAL;
    Ok(match op {
        Op::Pow => {
            if a < 0.0 && b.fract() != 0.0 {
                return Err(format!("{a} raised to the non-integer power {b}"));
            }
            a.powf(b)
        }
        Op::Mul => a * b,
        Op::Div => {
            if b == 0.0 {
                return Err("division by zero".into());
            }
            a / b
        }
        Op::Mod => {
            let r = a % b;
            if r < 0.0 { r + b.abs() } else { r }
        }
        Op::Add => a + b,
        Op::Sub => a - b,
        Op::Eq => t(close),
        Op::Ne => t(!close),
        Op::Gt => t(a > b),
        Op::Ge => t(close || a >= b),
        Op::Lt => t(a < b),
        Op::Le => t(close || a <= b),
        Op::And => t(a != 0.0 && b != 0.0),
        Op::Or => t(a != 0.0 || b != 0.0),
        Op::Xor => t((a != 0.0) != (b != 0.0)),
    })
}

/// The number scanned as `text` (signs, digits, points), finite; `nothing` gives the message
/// when nothing was scanned. Shared by the RS274/NGC and the macro B expression readers.
pub(crate) fn scanned_number(text: &[u8], nothing: impl FnOnce() -> String) -> Result<f64, String> {
    let text = std::str::from_utf8(text).unwrap_or_default();
    if text.is_empty() {
        return Err(nothing());
    }
    text.parse::<f64>()
        .ok()
        .filter(|v| v.is_finite())
        .ok_or_else(|| format!("bad number '{text}'"))
}

#[cfg(test)]
mod tests {
    use super::*;

    struct P;
    impl Params for P {
        fn numbered(&self, n: f64) -> Result<f64, String> {
            Ok(n * 10.0)
        }
        fn named(&self, name: &str) -> Result<f64, String> {
            if name == "d" {
                Ok(4.0)
            } else {
                Err(format!("#<{name}> not defined"))
            }
        }
        fn exists(&self, name: &str) -> bool {
            name == "d"
        }
    }

    fn ev(s: &str) -> Result<f64, String> {
        let mut c = Cursor::new(s.as_bytes(), 0);
        let v = c.value(&P)?;
        assert_eq!(c.i, s.len(), "{s}: stopped at {}", c.i);
        Ok(v)
    }

    #[test]
    fn precedence_and_associativity_follow_linuxcnc() {
        // Each case is worked by hand from the precedence table in the module doc.
        for (s, want) in [
            ("[1+2*3]", 7.0),
            ("[2**3**2]", 64.0), // left to right: (2**3)**2
            ("[-2**2]", 4.0),    // the sign is part of the number
            ("[10-4-3]", 3.0),
            ("[8/4/2]", 1.0),
            ("[7mod3]", 1.0),
            ("[-1mod3]", 2.0),
            ("[1+1eq2]", 1.0),
            ("[1lt2and3gt4]", 0.0),
            ("[1lt2or3gt4]", 1.0),
            ("[1xor1]", 0.0),
            ("[1.0000001eq1]", 1.0),
            ("[1.0000001gt1]", 1.0),
            ("#2", 20.0),
            ("##2", 200.0),
            ("#[1+1]", 20.0),
            ("-#<d>", -4.0),
            ("[#<d>*2]", 8.0),
            ("sqrt[16]", 4.0),
            ("abs[-3]", 3.0),
            ("fix[-1.5]", -2.0),
            ("fup[1.2]", 2.0),
            ("round[2.5]", 3.0),
            ("round[-2.5]", -3.0),
            ("exists[#<d>]", 1.0),
            ("exists[#<e>]", 0.0),
            ("[-.5]", -0.5),
        ] {
            let got = ev(s).unwrap_or_else(|e| panic!("{s}: {e}"));
            assert!((got - want).abs() < 1e-12, "{s}: {got} != {want}");
        }
        assert!((ev("sin[30]").unwrap() - 0.5).abs() < 1e-12);
        assert!((ev("atan[1]/[1]").unwrap() - 45.0).abs() < 1e-12);
        assert!((ev("acos[0]").unwrap() - 90.0).abs() < 1e-12);
        assert!((ev("[ln[exp[2]]]").unwrap() - 2.0).abs() < 1e-12);
    }

    #[test]
    fn refuses_what_linuxcnc_refuses() {
        for s in [
            "[1/0]",
            "[-8**0.5]",
            "sqrt[-1]",
            "ln[0]",
            "acos[2]",
            "[1+]",
            "[1+2",
            "#<e>",
            "#0",
            "#1.5",
            "foo[1]",
            "[1..2]",
        ] {
            let mut c = Cursor::new(s.as_bytes(), 0);
            assert!(c.value(&P).is_err(), "{s} accepted");
        }
        let deep = format!("{}1{}", "[".repeat(100), "]".repeat(100));
        let mut c = Cursor::new(deep.as_bytes(), 0);
        assert!(c.value(&P).unwrap_err().contains("nested"));
    }
}
