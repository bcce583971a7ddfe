//! Fanuc custom macro B: variables, expressions and the statements of one block (Fanuc
//! 0i/16i/30i operator's manuals, "Custom macro" chapter).
//!
//! A block is first brought to the canonical form of module `ngc` (lower case, no spaces,
//! comments aside); then it is one of
//! ```text
//! #i = expr  [#j = expr …]            assignment (after the whole block is read: no)
//! IF [cond] GOTO n | IF [cond] THEN #i = expr
//! WHILE [cond] DO m     DO m     END m     GOTO n
//! NC words                            G1 X#24 Y[#25+1.] F#9
//! ```
//! # Values
//! A variable is a number or **vacant** (`#0` is always vacant; locals not passed by G65 and
//! commons never set are vacant). `#i = #j` copies vacancy; any operation reads vacant as 0
//! (`#2 = #1 + #1` is 0); in a condition EQ and NE tell vacant from 0 (`[#1 EQ #0]` is true
//! only for vacant), GT GE LT LE read vacant as 0. An NC word whose value is a vacant
//! variable is left out of the block (`G0 X#1 Y5.` with #1 vacant is `G0 Y5.`).
//!
//! Variables: locals `#1–#33` (one set per G65 level), commons `#100–#199` and
//! `#500–#999` (vacant at the start), `#0`, and `#3000 = n (MESSAGE)` which stops the
//! program with its alarm. Other system variables (`#1000…`, `#2000…`, `#4000…`, `#5000…`)
//! are refused with their number.
//!
//! # Expressions
//! ```text
//! expr  = term  { ('+' | '-' | OR | XOR) term }
//! term  = unary { ('*' | '/' | AND | MOD) unary }
//! unary = ('+' | '-') unary | number | '#' (digits | '[' expr ']') | '[' body ']' | f '[' expr ']'
//! body  = expr [ rel expr { (AND | OR | XOR) expr rel expr } ]      rel = EQ NE GT GE LT LE
//! f     = SIN COS TAN ASIN ACOS ATAN SQRT ABS ROUND FIX FUP LN EXP; ATAN[a]/[b] = ATAN[a,b]
//! ```
//! Fanuc's precedence: functions, then `* / AND MOD`, then `+ - OR XOR`, left to right.
//! AND, OR, XOR are bitwise on integers (values rounded); after a comparison in a bracket
//! they join comparisons (`[#1 GT 0 AND #2 LT 5]`, as the 30i reads it). Angles are degrees;
//! with Fanuc's default (parameter NAT = 0) ATAN gives 0°–360° and ASIN 270°–90° (a negative
//! result + 360°), ACOS 0°–180°. ROUND rounds half away from zero, FIX truncates towards
//! zero, FUP away from zero (`FIX[-1.2]` = -1, `FUP[-1.2]` = -2), MOD is the remainder with
//! the sign of the dividend. Comparisons are exact (the manuals advise GE/LE for decimals).
//! Division by zero, SQRT of a negative, LN of a non-positive, ASIN/ACOS outside [-1, 1]
//! and results beyond f64 are errors, as the control raises alarms for them.

use super::lexer::Token;

/// Local variables per level (`#1–#33`).
pub(crate) const LOCALS: usize = 33;

/// Deepest bracket nesting accepted (Fanuc allows 5; a guard against hostile input).
const MAX_DEPTH: usize = 64;

/// A variable's value: `None` is vacant.
pub(crate) type Value = Option<f64>;

/// A G65 call's locals.
pub(crate) type Locals = [Value; LOCALS];

/// The variables of a running program.
#[derive(Debug, Clone)]
pub(crate) struct Vars {
    locals: Vec<Locals>,
    common: Vec<Value>,
}

type R<T> = Result<T, String>;

impl Vars {
    pub(crate) fn new() -> Self {
        Vars {
            locals: vec![[None; LOCALS]],
            common: vec![None; 1000],
        }
    }

    /// `#n`.
    pub(crate) fn get(&self, n: i64) -> R<Value> {
        match n {
            0 => Ok(None),
            1..=33 => Ok(self
                .locals
                .last()
                .and_then(|l| l.get(n as usize - 1))
                .copied()
                .flatten()),
            100..=199 | 500..=999 => Ok(self.common.get(n as usize).copied().flatten()),
            _ => Err(unsupported_var(n)),
        }
    }

    /// `#n = v` (`#3000` is the caller's: it needs the block's comment).
    pub(crate) fn set(&mut self, n: i64, v: Value) -> R<()> {
        let slot = match n {
            0 => return Err("#0 is always vacant and cannot be set".into()),
            1..=33 => self
                .locals
                .last_mut()
                .and_then(|l| l.get_mut(n as usize - 1)),
            100..=199 | 500..=999 => self.common.get_mut(n as usize),
            _ => None,
        };
        match slot {
            Some(s) => {
                *s = v;
                Ok(())
            }
            None => Err(unsupported_var(n)),
        }
    }

    /// A G65 call: a new level of locals.
    pub(crate) fn push(&mut self, args: Locals) {
        self.locals.push(args);
    }

    /// Sets the current level's locals (a G65 repetition starts with its arguments again).
    pub(crate) fn reset(&mut self, args: Locals) {
        if let Some(l) = self.locals.last_mut() {
            *l = args;
        }
    }

    /// The return from a G65 call.
    pub(crate) fn pop(&mut self) {
        if self.locals.len() > 1 {
            self.locals.pop();
        }
    }
}

fn unsupported_var(n: i64) -> String {
    format!(
        "variable #{n} is not supported (supported: #0, locals #1-#33, commons #100-#199 and \
         #500-#999, #3000 alarm)"
    )
}

/// The G65 argument letters (specification I) and their locals.
pub(crate) fn argument_index(letter: u8) -> Option<usize> {
    Some(match letter {
        b'A' => 1,
        b'B' => 2,
        b'C' => 3,
        b'I' => 4,
        b'J' => 5,
        b'K' => 6,
        b'D' => 7,
        b'E' => 8,
        b'F' => 9,
        b'H' => 11,
        b'M' => 13,
        b'Q' => 17,
        b'R' => 18,
        b'S' => 19,
        b'T' => 20,
        b'U' => 21,
        b'V' => 22,
        b'W' => 23,
        b'X' => 24,
        b'Y' => 25,
        b'Z' => 26,
        _ => return None,
    })
}

/// One block, parsed (and its values evaluated, conditions first).
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Stmt {
    /// Words of an NC block (vacant ones left out).
    Nc(Vec<Token>),
    /// `#i = v`, in order.
    Assign(Vec<(i64, Value)>),
    /// `GOTO n` (or a true `IF … GOTO n`).
    Goto(f64),
    /// `WHILE [c] DO m` with the condition's value.
    While(bool, u8),
    /// `DO m` (an endless loop).
    Do(u8),
    /// `END m`.
    End(u8),
    /// A false `IF`, or nothing.
    Nothing,
}

/// Parses the canonical block `s` (after `/` and the N word have been removed).
pub(crate) fn statement(s: &str, vars: &Vars) -> R<Stmt> {
    let b = s.as_bytes();
    let mut c = Cur {
        s: b,
        i: 0,
        depth: 0,
        vars,
    };
    if c.eat(b"if[") {
        c.i -= 1;
        let cond = truthy(c.bracket()?);
        if c.eat(b"goto") {
            let n = c.unary()?;
            c.end()?;
            return Ok(if cond {
                Stmt::Goto(n.unwrap_or(0.0))
            } else {
                Stmt::Nothing
            });
        }
        if c.eat(b"then") {
            if !cond {
                return Ok(Stmt::Nothing);
            }
            return c.assignments();
        }
        return Err(format!(
            "IF [..] GOTO n or IF [..] THEN #i=.. expected at '{}'",
            c.rest()
        ));
    }
    if c.eat(b"while[") {
        c.i -= 1;
        let cond = truthy(c.bracket()?);
        if !c.eat(b"do") {
            return Err(format!("WHILE [..] DO m expected at '{}'", c.rest()));
        }
        let m = c.loop_id()?;
        return Ok(Stmt::While(cond, m));
    }
    if c.s.get(c.i + 2).is_some_and(u8::is_ascii_digit) && c.eat(b"do") {
        return Ok(Stmt::Do(c.loop_id()?));
    }
    if c.eat(b"end") {
        return Ok(Stmt::End(c.loop_id()?));
    }
    if c.eat(b"goto") {
        let n = c.unary()?;
        c.end()?;
        return Ok(Stmt::Goto(n.unwrap_or(0.0)));
    }
    if c.peek() == Some(b'#') {
        return c.assignments();
    }
    c.words()
}

fn truthy(v: Value) -> bool {
    v.is_some_and(|x| x != 0.0)
}

struct Cur<'a> {
    s: &'a [u8],
    i: usize,
    depth: usize,
    vars: &'a Vars,
}

#[derive(Clone, Copy, PartialEq)]
enum Rel {
    Eq,
    Ne,
    Gt,
    Ge,
    Lt,
    Le,
}

impl Cur<'_> {
    fn peek(&self) -> Option<u8> {
        self.s.get(self.i).copied()
    }

    fn eat(&mut self, t: &[u8]) -> bool {
        let ok = self.s.get(self.i..).is_some_and(|r| r.starts_with(t));
        if ok {
            self.i += t.len();
        }
        ok
    }

    fn rest(&self) -> String {
        let r = self.s.get(self.i..).unwrap_or_default();
        String::from_utf8_lossy(r.get(..r.len().min(24)).unwrap_or(r)).to_uppercase()
    }

    fn end(&self) -> R<()> {
        match self.peek() {
            None => Ok(()),
            Some(_) => Err(format!("unexpected '{}'", self.rest())),
        }
    }

    fn loop_id(&mut self) -> R<u8> {
        let n = self.number()?;
        self.end()?;
        if [1.0, 2.0, 3.0].contains(&n) {
            Ok(n as u8)
        } else {
            Err(format!("loop identifier {n} (DO and END take 1, 2 or 3)"))
        }
    }

    fn assignments(&mut self) -> R<Stmt> {
        let mut out = Vec::new();
        while self.peek() == Some(b'#') {
            self.i += 1;
            let n = self.var_number()?;
            if !self.eat(b"=") {
                return Err(format!("'=' expected after #{n} at '{}'", self.rest()));
            }
            let v = self.expr(true)?;
            out.push((n, v));
        }
        if self.peek().is_some() {
            return Err(format!(
                "'{}' after an assignment (an assignment is a block of its own: no NC words \
                 with it)",
                self.rest()
            ));
        }
        Ok(Stmt::Assign(out))
    }

    fn words(&mut self) -> R<Stmt> {
        let mut out = Vec::new();
        while let Some(l) = self.peek() {
            if !l.is_ascii_lowercase() {
                return Err(format!(
                    "a word (letter and value) expected at '{}'",
                    self.rest()
                ));
            }
            let start = self.i;
            self.i += 1;
            if self.peek().is_some_and(|c| c.is_ascii_lowercase()) {
                let mut j = self.i;
                while self.s.get(j).is_some_and(u8::is_ascii_lowercase) {
                    j += 1;
                }
                let word = String::from_utf8_lossy(self.s.get(start..j).unwrap_or_default())
                    .to_uppercase();
                return Err(format!(
                    "'{word}' is not supported (macro statements: #i=, IF [..] GOTO, IF [..] \
                     THEN, WHILE [..] DO m, DO m, END m, GOTO n; functions SIN COS TAN ASIN \
                     ACOS ATAN SQRT ABS ROUND FIX FUP LN EXP)"
                ));
            }
            let v = self.unary()?;
            if let Some(mut value) = v {
                if l == b'm' {
                    value = value.round();
                }
                out.push(Token::Word {
                    letter: l.to_ascii_uppercase(),
                    value,
                    start,
                    end: self.i,
                });
            }
        }
        Ok(Stmt::Nc(out))
    }

    /// After `#`: a number or a bracketed expression, rounded to an integer.
    fn var_number(&mut self) -> R<i64> {
        let v = if self.peek() == Some(b'[') {
            self.bracket()?.unwrap_or(0.0)
        } else if self.peek().is_some_and(|c| c.is_ascii_digit()) {
            self.number()?
        } else {
            return Err(format!(
                "a variable number or [expression] expected after '#' at '{}'",
                self.rest()
            ));
        };
        let n = v.round();
        if !(0.0..=99_999.0).contains(&n) {
            return Err(format!("variable number {v}"));
        }
        Ok(n as i64)
    }

    fn number(&mut self) -> R<f64> {
        let start = self.i;
        while self.peek().is_some_and(|c| c.is_ascii_digit() || c == b'.') {
            self.i += 1;
        }
        let text = self.s.get(start..self.i).unwrap_or_default();
        super::expr::scanned_number(text, || format!("a value expected at '{}'", self.rest()))
    }

    fn deeper(&mut self) -> R<()> {
        self.depth += 1;
        if self.depth > MAX_DEPTH {
            return Err(format!("expression nested deeper than {MAX_DEPTH}"));
        }
        Ok(())
    }

    fn unary(&mut self) -> R<Value> {
        self.deeper()?;
        let c = self
            .peek()
            .ok_or("a value expected at the end of the block")?;
        let v = match c {
            b'-' => {
                self.i += 1;
                Some(-self.unary()?.unwrap_or(0.0))
            }
            b'+' => {
                self.i += 1;
                Some(self.unary()?.unwrap_or(0.0))
            }
            b'#' => {
                self.i += 1;
                let n = self.var_number()?;
                self.vars.get(n)?
            }
            b'[' => self.bracket()?,
            b'a'..=b'z' => Some(self.function()?),
            _ => Some(self.number()?),
        };
        self.depth -= 1;
        finite(v)
    }

    fn bracket(&mut self) -> R<Value> {
        if !self.eat(b"[") {
            return Err(format!("'[' expected at '{}'", self.rest()));
        }
        self.deeper()?;
        let a = self.expr(true)?;
        let v = match self.rel() {
            None => a,
            Some(r) => {
                let b = self.expr(false)?;
                let mut acc = compare(r, a, b);
                while let Some(op) = self.logic_op() {
                    let l = self.expr(false)?;
                    let r = self.rel().ok_or_else(|| {
                        format!("a comparison expected after {op:?} at '{}'", self.rest())
                    })?;
                    let rv = self.expr(false)?;
                    let c = compare(r, l, rv);
                    acc = match op {
                        Logic::And => acc && c,
                        Logic::Or => acc || c,
                        Logic::Xor => acc != c,
                    };
                }
                Some(f64::from(u8::from(acc)))
            }
        };
        if !self.eat(b"]") {
            return Err(format!("']' expected at '{}'", self.rest()));
        }
        self.depth -= 1;
        Ok(v)
    }

    fn rel(&mut self) -> Option<Rel> {
        for (t, r) in [
            (b"eq", Rel::Eq),
            (b"ne", Rel::Ne),
            (b"gt", Rel::Gt),
            (b"ge", Rel::Ge),
            (b"lt", Rel::Lt),
            (b"le", Rel::Le),
        ] {
            if self.eat(t) {
                return Some(r);
            }
        }
        None
    }

    fn logic_op(&mut self) -> Option<Logic> {
        if self.eat(b"and") {
            Some(Logic::And)
        } else if self.eat(b"or") {
            Some(Logic::Or)
        } else if self.eat(b"xor") {
            Some(Logic::Xor)
        } else {
            None
        }
    }

    /// `+ - OR XOR` (OR, XOR only when `logic`: else they join comparisons).
    fn expr(&mut self, logic: bool) -> R<Value> {
        let mut a = self.term(logic)?;
        loop {
            let op = if self.eat(b"+") {
                b'+'
            } else if self.eat(b"-") {
                b'-'
            } else if logic && self.eat(b"or") {
                b'|'
            } else if logic && self.eat(b"xor") {
                b'^'
            } else {
                return Ok(a);
            };
            let b = self.term(logic)?;
            let (x, y) = (a.unwrap_or(0.0), b.unwrap_or(0.0));
            a = finite(Some(match op {
                b'+' => x + y,
                b'-' => x - y,
                b'|' => (int(x) | int(y)) as f64,
                _ => (int(x) ^ int(y)) as f64,
            }))?;
        }
    }

    /// `* / AND MOD` (AND only when `logic`).
    fn term(&mut self, logic: bool) -> R<Value> {
        let mut a = self.unary()?;
        loop {
            let op = if self.eat(b"*") {
                b'*'
            } else if self.eat(b"/") {
                b'/'
            } else if logic && self.eat(b"and") {
                b'&'
            } else if self.eat(b"mod") {
                b'%'
            } else {
                return Ok(a);
            };
            let b = self.unary()?;
            let (x, y) = (a.unwrap_or(0.0), b.unwrap_or(0.0));
            a = finite(Some(match op {
                b'*' => x * y,
                b'/' | b'%' if y == 0.0 => return Err("division by zero".into()),
                b'/' => x / y,
                b'%' => x % y,
                _ => (int(x) & int(y)) as f64,
            }))?;
        }
    }

    fn function(&mut self) -> R<f64> {
        const NAMES: [&[u8]; 13] = [
            b"abs", b"acos", b"asin", b"atan", b"cos", b"exp", b"fix", b"fup", b"ln", b"round",
            b"sin", b"sqrt", b"tan",
        ];
        let Some(name) = NAMES.iter().find(|n| {
            self.s.get(self.i..).is_some_and(|r| r.starts_with(n))
                && self.s.get(self.i + n.len()) == Some(&b'[')
        }) else {
            return Err(format!(
                "unknown function at '{}' (functions: SIN COS TAN ASIN ACOS ATAN SQRT ABS ROUND \
                 FIX FUP LN EXP)",
                self.rest()
            ));
        };
        self.i += name.len() + 1;
        self.deeper()?;
        let x = self.expr(true)?.unwrap_or(0.0);
        let second = if *name == b"atan" && self.eat(b",") {
            Some(self.expr(true)?.unwrap_or(0.0))
        } else {
            None
        };
        if !self.eat(b"]") {
            return Err(format!("']' expected at '{}'", self.rest()));
        }
        self.depth -= 1;
        let domain = |ok: bool, what: &str| {
            if ok {
                Ok(())
            } else {
                Err(format!("{what}[{x}]: outside its domain"))
            }
        };
        let deg = |r: f64| r.to_degrees();
        Ok(match *name {
            b"abs" => x.abs(),
            b"acos" => {
                domain((-1.0..=1.0).contains(&x), "ACOS")?;
                deg(x.acos())
            }
            b"asin" => {
                domain((-1.0..=1.0).contains(&x), "ASIN")?;
                let a = deg(x.asin());
                if a < 0.0 { a + 360.0 } else { a }
            }
            b"atan" => {
                let y = match second {
                    Some(y) => y,
                    None if self.eat(b"/[") => {
                        self.i -= 1;
                        self.bracket()?.unwrap_or(0.0)
                    }
                    None => return Err("ATAN needs two values: ATAN[a]/[b] or ATAN[a,b]".into()),
                };
                let a = deg(x.atan2(y));
                if a < 0.0 { a + 360.0 } else { a }
            }
            b"cos" => x.to_radians().cos(),
            b"exp" => x.exp(),
            b"fix" => x.trunc(),
            b"fup" => {
                if x >= 0.0 {
                    x.ceil()
                } else {
                    x.floor()
                }
            }
            b"ln" => {
                domain(x > 0.0, "LN")?;
                x.ln()
            }
            b"round" => x.round(),
            b"sin" => x.to_radians().sin(),
            b"sqrt" => {
                domain(x >= 0.0, "SQRT")?;
                x.sqrt()
            }
            _ => x.to_radians().tan(),
        })
    }
}

#[derive(Debug, Clone, Copy)]
enum Logic {
    And,
    Or,
    Xor,
}

fn int(x: f64) -> i64 {
    x.round() as i64
}

fn finite(v: Value) -> R<Value> {
    match v {
        Some(x) if !x.is_finite() => Err("a result beyond the range of numbers".into()),
        _ => Ok(v),
    }
}

/// EQ and NE tell vacant from 0; the others read vacant as 0.
fn compare(r: Rel, a: Value, b: Value) -> bool {
    let (x, y) = (a.unwrap_or(0.0), b.unwrap_or(0.0));
    match r {
        // Exact, as the control compares (its manuals advise GE/LE for decimals).
        Rel::Eq => a.is_some() == b.is_some() && (x - y).abs() <= 0.0,
        Rel::Ne => !(a.is_some() == b.is_some() && (x - y).abs() <= 0.0),
        Rel::Gt => x > y,
        Rel::Ge => x >= y,
        Rel::Lt => x < y,
        Rel::Le => x <= y,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ev(s: &str, vars: &Vars) -> Value {
        match statement(&format!("#1={s}"), vars).unwrap() {
            Stmt::Assign(a) => a[0].1,
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn precedence_functions_and_vacancy() {
        let mut v = Vars::new();
        v.set(2, Some(3.0)).unwrap();
        // Worked by hand from the grammar in the module docs.
        for (s, want) in [
            ("1+2*3", 7.0),
            ("10-4-3", 3.0),
            ("8/4/2", 1.0),
            ("-2*3", -6.0),
            ("[1+2]*3", 9.0),
            ("7mod3", 1.0),
            ("-7mod3", -1.0),
            ("6and3", 2.0),
            ("6or1", 7.0),
            ("6xor3", 5.0),
            ("#2*#3", 0.0),
            ("#3+#3", 0.0),
            ("fix[-1.2]", -1.0),
            ("fup[-1.2]", -2.0),
            ("fup[1.2]", 2.0),
            ("round[-2.5]", -3.0),
            ("atan[-1]/[-1]", 225.0),
            ("atan[1,1]", 45.0),
            ("asin[-0.5]", 330.0),
            ("acos[-1]", 180.0),
            ("sqrt[16]+abs[-1]", 5.0),
            ("[#2gt0and#2lt5]", 1.0),
            ("[#3eq#0]", 1.0),
            ("[#3eq0]", 0.0),
            ("[#3ne0]", 1.0),
            ("[#3ge#0]", 1.0),
            ("[#3gt0]", 0.0),
            ("#[#2-1]", 3.0),
        ] {
            let got = ev(s, &v).unwrap_or(0.0);
            assert!((got - want).abs() < 1e-9, "{s}: {got} != {want}");
        }
        assert!((ev("sin[30]", &v).unwrap() - 0.5).abs() < 1e-12);
        assert_eq!(ev("#3", &v), None, "a bare vacant variable stays vacant");
        assert_eq!(ev("#0", &v), None);
        for bad in [
            "1/0", "sqrt[-1]", "ln[0]", "acos[2]", "[1+2", "foo[1]", "#1000", "atan[1]",
        ] {
            assert!(statement(&format!("#1={bad}"), &v).is_err(), "{bad}");
        }
        assert!(statement("#0=1", &v).is_ok(), "refused when applied");
        assert!(v.clone().set(0, Some(1.0)).is_err());
        assert_eq!(
            statement("g0x#3y5.", &v).unwrap(),
            Stmt::Nc(vec![
                Token::Word {
                    letter: b'G',
                    value: 0.0,
                    start: 0,
                    end: 2
                },
                Token::Word {
                    letter: b'Y',
                    value: 5.0,
                    start: 5,
                    end: 8
                },
            ])
        );
        assert_eq!(
            statement("while[#2lt3]do1", &v).unwrap(),
            Stmt::While(false, 1)
        );
        assert_eq!(statement("if[#2eq3]goto20", &v).unwrap(), Stmt::Goto(20.0));
        assert_eq!(statement("if[#2ne3]goto20", &v).unwrap(), Stmt::Nothing);
        assert_eq!(
            statement("if[#2eq3]then#5=[#2*2]", &v).unwrap(),
            Stmt::Assign(vec![(5, Some(6.0))])
        );
        assert_eq!(statement("end2", &v).unwrap(), Stmt::End(2));
        assert!(statement("do4", &v).is_err());
        assert!(statement("#1=1g0x1", &v).is_err());
        assert!(statement("g0x1pow[2,3]", &v).is_err());
    }
}
