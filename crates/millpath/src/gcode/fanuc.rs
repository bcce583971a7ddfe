//! Fanuc programs: program numbers, subprograms (M98/M99), macro calls (G65) and macro B
//! control flow (GOTO, IF, WHILE/DO/END): where the next block comes from (Fanuc 0i/30i
//! operator's manuals, "Subprogram control" and "Custom macro").
//!
//! ```text
//! %                      leader (a later '%' ends the file)
//! O0001 (MAIN)           the main program: the file's first program
//! G65 P9010 A3. R20.     macro call: #1=3 #18=20 at a new level of locals
//! M98 P1000 L2           subprogram O1000 twice (also M98 P21000: count above 4 digits)
//! M30
//! O1000                  a subprogram: from its number to M99
//! G91 G1 X10. F600
//! M99                    return (M99 P20: to the caller's block N20)
//! %
//! ```
//! * **Programs** start at `O1234` or `:1234` lines. The main program is the file's first;
//!   it ends at M2/M30, at the next program number or at the end of the file. Subprograms
//!   are found by number in the file (after the main program, read on when called), then
//!   as files `O1234.nc`, `o1234.nc`, `O1234.NC`, `O1234`, `1234.nc` in the program's folder
//!   and on `--subroutine-path`
//!   ([`ReaderOptions::subroutine_path`](super::ReaderOptions::subroutine_path)); a file
//!   may hold one program without its number, or several with theirs.
//! * **M98 P L** runs the subprogram L times (L0: not at all). Without L, a P of more than
//!   four digits carries the count above its last four (`M98 P31000` = O1000 three times, as
//!   on the 0i). The block's other words run first. M98 shares the caller's locals.
//! * **M99** returns after the block's motion; `M99 P n` returns to the caller's block N n
//!   (searched forward from the call, then from the program's start). M99 in the main
//!   program goes back to its start (or to N n): an endless loop unless `/M99` is skipped
//!   (block delete) — bounded by the step budget like every repeated block.
//! * **G65 P L args** calls a macro with argument specification I (A→#1 B→#2 C→#3 I→#4
//!   J→#5 K→#6 D→#7 E→#8 F→#9 H→#11 M→#13 Q→#17 R→#18 S→#19 T→#20 U→#21 V→#22 W→#23
//!   X→#24 Y→#25 Z→#26; a repeated I, J or K switches to specification II: I J K of the n-th
//!   set → #(1+3n) #(2+3n) #(3+3n), a later argument for the same local wins). Each
//!   repetition starts with the arguments again. G66/G66.1/G67 (modal calls) are refused.
//! * **Nesting:** up to [`MAX_SUBPROGRAM_DEPTH`] M98 levels and [`MAX_MACRO_DEPTH`] G65
//!   levels (the 30i's limits; the 0i allows 4 of each), counted apart as Fanuc counts
//!   them; deeper calls are refused naming the call.
//! * **GOTO n** jumps to the block N n of the running program (forward first, then from
//!   its start); `WHILE [c] DO m` … `END m` (m = 1, 2, 3) loops, `DO m` alone loops for ever;
//!   DO/END pairs must nest in the program text (checked when the first loop statement of a
//!   program runs: an END without its DO, a DO without its END and crossed pairs are refused).
//! * **Memory:** the file's lines are kept once read (a Fanuc control holds its programs in
//!   memory too); a jump or a call never reads a file twice.
//! * **Step budget:** every block run inside a subprogram, or run again in the main program
//!   (after a backward GOTO, END or M99), counts against
//!   [`ReaderOptions::step_budget`](super::ReaderOptions::step_budget) (module `budget`);
//!   past it the program is refused naming the backward jump, repetition or call that ran
//!   most often, never hangs.
//! * **No recursion:** programs, calls and loops are vectors and indices; an expression's
//!   brackets nest at most 64 deep (module `macro_b`).

use super::budget::Budget;
use super::lexer::Token;
use super::macro_b::{self, Locals, Stmt, Vars};
use super::ngc::canonical;
use super::oword::At;
use std::collections::HashMap;
use std::io::BufRead;
use std::path::PathBuf;
use std::rc::Rc;

mod call;
pub(crate) use call::{Control, take_control};

/// Deepest M98 nesting (Fanuc 30i: 10 levels).
pub const MAX_SUBPROGRAM_DEPTH: usize = 10;

/// Deepest G65 nesting (Fanuc 30i: 5 levels of locals above the main program's).
pub const MAX_MACRO_DEPTH: usize = 5;

type R2<T> = Result<T, String>;

/// A file's lines, read when needed and kept.
#[derive(Debug)]
struct Text<S> {
    src: S,
    data: Vec<u8>,
    /// End offset of each line in `data`.
    ends: Vec<usize>,
    eof: bool,
    /// A line other than blank or `%` has been read.
    content: bool,
    /// Program numbers and their lines.
    headers: Vec<(u32, usize)>,
    max: u64,
}

impl<S: BufRead> Text<S> {
    fn new(src: S, max: u64) -> Self {
        Text {
            src,
            data: Vec::new(),
            ends: Vec::new(),
            eof: false,
            content: false,
            headers: Vec::new(),
            max,
        }
    }

    fn line(&mut self, i: usize) -> R2<Option<&[u8]>> {
        while self.ends.len() <= i && !self.eof {
            self.read()?;
        }
        let Some(&end) = self.ends.get(i) else {
            return Ok(None);
        };
        let start = i.checked_sub(1).and_then(|k| self.ends.get(k)).copied();
        Ok(self.data.get(start.unwrap_or(0)..end))
    }

    fn read(&mut self) -> R2<()> {
        let start = self.data.len();
        let n = std::io::Read::take(&mut self.src, self.max + 1)
            .read_until(b'\n', &mut self.data)
            .map_err(|e| format!("unreadable ({e})"))?;
        if n == 0 {
            self.eof = true;
            return Ok(());
        }
        if n as u64 > self.max && self.data.last() != Some(&b'\n') {
            return Err(format!("a line longer than {} bytes", self.max));
        }
        while matches!(self.data.last(), Some(b'\n' | b'\r')) && self.data.len() > start {
            self.data.pop();
        }
        let line = self.data.get(start..).unwrap_or_default();
        let t = line.trim_ascii();
        if t == b"%" && self.content {
            // The closing '%': the end of the file for the control.
            self.data.truncate(start);
            self.eof = true;
            return Ok(());
        }
        self.content |= !t.is_empty() && t != b"%";
        if let Some(n) = header(line) {
            self.headers.push((n, self.ends.len()));
        }
        self.ends.push(self.data.len());
        Ok(())
    }

    fn find(&mut self, number: u32) -> R2<Option<usize>> {
        loop {
            if let Some(&(_, i)) = self.headers.iter().find(|h| h.0 == number) {
                return Ok(Some(i));
            }
            if self.eof {
                return Ok(None);
            }
            self.read()?;
        }
    }
}

/// `O1234` or `:1234` (spaces and a comment allowed): the program number.
pub(crate) fn header(line: &[u8]) -> Option<u32> {
    let t = line.trim_ascii_start();
    let rest = t
        .strip_prefix(b"O")
        .or_else(|| t.strip_prefix(b"o"))
        .or_else(|| t.strip_prefix(b":"))?;
    let digits = rest.iter().take_while(|c| c.is_ascii_digit()).count();
    let tail = rest.get(digits..)?.trim_ascii();
    if digits == 0 || digits > 9 || !(tail.is_empty() || tail.starts_with(b"(")) {
        return None;
    }
    std::str::from_utf8(rest.get(..digits)?).ok()?.parse().ok()
}

/// Whether a block the plain lexer refused may be a macro statement or carry macro values:
/// a `#`, a `[` or two letters in a row outside comments (`IF`, `GOTO`, `WHILE`, `DO1`,
/// `END1`). Plain blocks never come here: the lexer reads them first.
pub(crate) fn candidate(b: &[u8]) -> bool {
    let (mut prev_alpha, mut comment) = (false, false);
    for &c in b {
        if comment {
            comment = c != b')';
            continue;
        }
        match c {
            b'(' => {
                comment = true;
                prev_alpha = false;
            }
            b';' => return false,
            b'#' | b'[' => return true,
            c if c.is_ascii_alphabetic() => {
                if prev_alpha {
                    return true;
                }
                prev_alpha = true;
            }
            c if c == b' ' || c == b'\t' => {}
            _ => prev_alpha = false,
        }
    }
    false
}

/// The canonical block without its N word.
fn skip_n(s: &str) -> &str {
    match s.strip_prefix('n') {
        Some(r) => r.trim_start_matches(|c: char| c.is_ascii_digit()),
        None => s,
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
enum Src {
    Main,
    File(usize),
}

#[derive(Debug)]
struct Frame {
    src: Src,
    /// The program's first line (its number, or 0).
    start: usize,
    pc: usize,
    /// Repetitions left after this one.
    left: u32,
    number: u32,
    /// A G65 call's arguments (its level of locals).
    args: Option<Box<Locals>>,
}

/// Sequence numbers and loop statements of one program.
#[derive(Debug, Default)]
struct Index {
    seq: HashMap<u32, Vec<usize>>,
    dos: [Vec<usize>; 3],
    ends: [Vec<usize>; 3],
    problem: Option<String>,
}

/// A Fanuc program being run.
#[derive(Debug)]
pub(crate) struct Fanuc<R> {
    main: Text<R>,
    files: Vec<(Text<std::io::BufReader<std::fs::File>>, Rc<str>)>,
    frames: Vec<Frame>,
    vars: Vars,
    index: HashMap<(Src, usize), Rc<Index>>,
    search: Vec<PathBuf>,
    block_delete: bool,
    budget: Budget,
    /// Main-program lines below this have run (a line below it runs again).
    high: usize,
    started: bool,
    /// The line being run.
    at: At,
}

impl<R: BufRead> Fanuc<R> {
    pub(crate) fn new(
        src: R,
        search: Vec<PathBuf>,
        budget: u64,
        max_line: u64,
        block_delete: bool,
    ) -> Self {
        Fanuc {
            main: Text::new(src, max_line),
            files: Vec::new(),
            frames: vec![Frame {
                src: Src::Main,
                start: 0,
                pc: 0,
                left: 0,
                number: 0,
                args: None,
            }],
            vars: Vars::new(),
            index: HashMap::new(),
            search,
            block_delete,
            budget: Budget::new(budget, "blocks run in subprograms and loops"),
            high: 0,
            started: false,
            at: At {
                line: 0,
                origin: None,
            },
        }
    }

    /// The line being run (for messages).
    pub(crate) fn at(&self) -> &At {
        &self.at
    }

    /// Whether the step budget ran out (the last error is its refusal).
    pub(crate) fn over_budget(&self) -> bool {
        self.budget.exhausted()
    }

    /// What the step budget's refusal expects.
    pub(crate) fn budget_expected(&self) -> String {
        self.budget.expected()
    }

    /// Tallies a backward jump, repetition or call made at line `line` (1-based) of the
    /// running program's file.
    fn jumped(&mut self, line: usize, what: impl FnOnce() -> String) {
        let origin = self.at.origin.clone();
        self.budget
            .jump(origin.as_deref().unwrap_or(""), line, what);
    }

    fn line(&mut self, src: Src, i: usize, buf: &mut Vec<u8>) -> R2<bool> {
        let l = match src {
            Src::Main => self.main.line(i)?,
            Src::File(k) => match self.files.get_mut(k) {
                Some((t, _)) => t.line(i)?,
                None => None,
            },
        };
        buf.clear();
        match l {
            Some(l) => {
                buf.extend_from_slice(l);
                Ok(true)
            }
            None => Ok(false),
        }
    }

    fn origin(&self, src: Src) -> Option<Rc<str>> {
        match src {
            Src::Main => None,
            Src::File(k) => self.files.get(k).map(|(_, o)| Rc::clone(o)),
        }
    }

    fn name(&self, f: usize) -> String {
        match self.frames.get(f) {
            Some(fr) if f > 0 => format!("O{:04}", fr.number),
            _ => "the main program".into(),
        }
    }

    /// The main program starts at its number when only blank and `%` lines precede it.
    fn init(&mut self) -> R2<()> {
        self.started = true;
        let mut buf = Vec::new();
        let mut i = 0;
        while self.line(Src::Main, i, &mut buf)? {
            let t = buf.trim_ascii();
            if header(&buf).is_some() {
                if let Some(f) = self.frames.first_mut() {
                    f.start = i;
                }
                break;
            }
            if !(t.is_empty() || t == b"%") {
                break;
            }
            i += 1;
        }
        Ok(())
    }

    /// The next NC block to run into `buf` (macro statements run here), `None` at the end.
    pub(crate) fn next_line(&mut self, buf: &mut Vec<u8>) -> R2<Option<At>> {
        if !self.started {
            self.init()?;
        }
        loop {
            let f = self.frames.len() - 1;
            let (src, pc, start) = match self.frames.last() {
                Some(fr) => (fr.src, fr.pc, fr.start),
                None => return Ok(None),
            };
            self.at = At {
                line: pc + 1,
                origin: self.origin(src),
            };
            let got = self.line(src, pc, buf)?;
            let is_header = got && header(buf).is_some();
            if !got || (is_header && pc != start) {
                if f == 0 {
                    return Ok(None);
                }
                return Err(format!(
                    "{} ends (at line {} of its file) without M99",
                    self.name(f),
                    pc + 1
                ));
            }
            if let Some(fr) = self.frames.last_mut() {
                fr.pc += 1;
            }
            self.count(f, pc)?;
            // The program's own number; `%` lines go to the lexer, which skips them.
            if is_header {
                continue;
            }
            return Ok(Some(self.at.clone()));
        }
    }

    /// Runs the block just returned when the plain lexer refused it: a macro statement (runs
    /// here: `None`), or NC words with macro values (evaluated, vacant ones left out).
    pub(crate) fn macro_block(&mut self, line: &[u8]) -> R2<Option<(Vec<Token>, String)>> {
        let f = self.frames.len() - 1;
        let pc = self.frames.last().map_or(0, |fr| fr.pc.saturating_sub(1));
        let text = String::from_utf8_lossy(line).into_owned();
        let (canon, comments) = canonical(&text)?;
        let mut s = canon.as_str();
        if let Some(r) = s.strip_prefix('/') {
            if self.block_delete {
                return Ok(None);
            }
            s = r;
        }
        let s = skip_n(s);
        let stmt = macro_b::statement(s, &self.vars)
            .map_err(|e| format!("{e} in '{}'", super::lexer::shown(&text)))?;
        match stmt {
            Stmt::Nc(tokens) => return Ok(Some((tokens, s.to_string()))),
            Stmt::Nothing => {}
            Stmt::Assign(list) => {
                for (n, v) in list {
                    if n == 3000 {
                        return Err(format!(
                            "the program raised alarm #3000={} ({})",
                            v.unwrap_or(0.0),
                            comments.join(" ").trim()
                        ));
                    }
                    self.vars.set(n, v)?;
                }
            }
            Stmt::Goto(n) => {
                let target = self.seq_line(f, n, pc + 1, "GOTO")?;
                if target <= pc {
                    self.jumped(pc + 1, || format!("GOTO {n}"));
                }
                self.set_pc(f, target);
            }
            Stmt::While(c, m) => {
                let ix = self.index(f)?;
                if !c {
                    let end = ends_after(&ix, m, pc).ok_or_else(|| {
                        format!("WHILE … DO{m} at line {} without its END{m}", pc + 1)
                    })?;
                    self.set_pc(f, end + 1);
                }
            }
            Stmt::Do(_) => {
                self.index(f)?;
            }
            Stmt::End(m) => {
                let ix = self.index(f)?;
                let k = usize::from(m - 1);
                let d = ix
                    .dos
                    .get(k)
                    .and_then(|d| d.iter().rev().find(|&&d| d < pc))
                    .copied()
                    .ok_or_else(|| format!("END{m} at line {} without its DO{m}", pc + 1))?;
                self.jumped(pc + 1, || format!("END{m}"));
                self.set_pc(f, d);
            }
        }
        Ok(None)
    }

    fn set_pc(&mut self, f: usize, pc: usize) {
        if let Some(fr) = self.frames.get_mut(f) {
            fr.pc = pc;
        }
    }

    /// Counts a block run in a subprogram or run again in the main program.
    fn count(&mut self, f: usize, pc: usize) -> R2<()> {
        if f == 0 && pc >= self.high {
            self.high = pc + 1;
            return Ok(());
        }
        self.budget.step()
    }

    /// The line of block N `n` in frame `f`'s program: the first at or after `from`, else
    /// the first from the program's start.
    fn seq_line(&mut self, f: usize, n: f64, from: usize, what: &str) -> R2<usize> {
        let k = n.round();
        if (n - k).abs() > 1e-6 || !(0.0..=99_999_999.0).contains(&k) {
            return Err(format!("{what} {n}: a sequence number is a whole number"));
        }
        let ix = self.index(f)?;
        let lines = ix.seq.get(&(k as u32)).cloned().unwrap_or_default();
        lines
            .iter()
            .find(|&&l| l >= from)
            .or_else(|| lines.first())
            .copied()
            .ok_or_else(|| format!("{what} {k}: no block N{k} in {}", self.name(f)))
    }

    /// Frame `f`'s program index (built on first use; its loop problems are errors).
    fn index(&mut self, f: usize) -> R2<Rc<Index>> {
        let (src, start) = match self.frames.get(f) {
            Some(fr) => (fr.src, fr.start),
            None => return Err("internal error: no program running (please report)".into()),
        };
        if let Some(ix) = self.index.get(&(src, start)) {
            return Ok(Rc::clone(ix));
        }
        let mut ix = Index::default();
        let mut open: Vec<(u8, usize)> = Vec::new();
        let mut buf = Vec::new();
        let mut i = start;
        while self.line(src, i, &mut buf)? && (i == start || header(&buf).is_none()) {
            let text = String::from_utf8_lossy(&buf);
            if let Ok((canon, _)) = canonical(&text) {
                let s = canon.strip_prefix('/').unwrap_or(&canon);
                if let Some(r) = s.strip_prefix('n') {
                    let d: String = r.chars().take_while(char::is_ascii_digit).collect();
                    if let Ok(n) = d.parse::<u32>() {
                        ix.seq.entry(n).or_default().push(i);
                    }
                }
                let s = skip_n(s);
                let loop_id = |t: &str| t.parse::<u8>().ok().filter(|m| (1..=3).contains(m));
                let do_m = if s.starts_with("while[") {
                    s.rfind("do")
                        .and_then(|k| loop_id(s.get(k + 2..).unwrap_or("")))
                } else {
                    s.strip_prefix("do").and_then(loop_id)
                };
                if let Some(m) = do_m {
                    if ix.problem.is_none() && open.iter().any(|o| o.0 == m) {
                        ix.problem = Some(format!("DO{m} at line {} inside another DO{m}", i + 1));
                    }
                    open.push((m, i));
                    if let Some(v) = ix.dos.get_mut(usize::from(m - 1)) {
                        v.push(i);
                    }
                }
                if let Some(m) = s.strip_prefix("end").and_then(loop_id) {
                    match open.pop() {
                        Some((o, _)) if o == m => {}
                        Some((o, l)) if ix.problem.is_none() => {
                            ix.problem = Some(format!(
                                "END{m} at line {} closes DO{o} of line {} (DO/END pairs must \
                                 nest)",
                                i + 1,
                                l + 1
                            ));
                        }
                        None if ix.problem.is_none() => {
                            ix.problem =
                                Some(format!("END{m} at line {} without its DO{m}", i + 1));
                        }
                        _ => {}
                    }
                    if let Some(v) = ix.ends.get_mut(usize::from(m - 1)) {
                        v.push(i);
                    }
                }
            }
            i += 1;
        }
        if let (None, Some((m, l))) = (&ix.problem, open.first()) {
            ix.problem = Some(format!("DO{m} at line {} without its END{m}", l + 1));
        }
        if let Some(p) = &ix.problem {
            return Err(format!("{} in {}", p, self.name(f)));
        }
        let ix = Rc::new(ix);
        self.index.insert((src, start), Rc::clone(&ix));
        Ok(ix)
    }

    /// Runs what an NC block asked for after its motion.
    pub(crate) fn apply(&mut self, c: Control) -> R2<()> {
        match c {
            Control::Call {
                program,
                count,
                args,
            } => self.call(program, count, args),
            Control::Return { seq } => self.ret(seq),
        }
    }

    fn call(&mut self, program: u32, count: u32, args: Option<Box<Locals>>) -> R2<()> {
        if count == 0 {
            return Ok(());
        }
        let macros = self.frames.iter().filter(|f| f.args.is_some()).count();
        let subs = self.frames.len() - 1 - macros;
        let word = if args.is_some() { "G65" } else { "M98" };
        if args.is_some() && macros >= MAX_MACRO_DEPTH {
            return Err(format!(
                "G65 P{program}: macro calls nested deeper than {MAX_MACRO_DEPTH} levels \
                 (Fanuc 30i's limit)"
            ));
        }
        if args.is_none() && subs >= MAX_SUBPROGRAM_DEPTH {
            return Err(format!(
                "M98 P{program}: subprogram calls nested deeper than {MAX_SUBPROGRAM_DEPTH} \
                 levels (Fanuc 30i's limit)"
            ));
        }
        let (src, start) = self.find(program, word)?;
        let line = self.at.line;
        self.jumped(line, || format!("{word} P{program}"));
        if let Some(a) = &args {
            self.vars.push(**a);
        }
        self.frames.push(Frame {
            src,
            start,
            pc: start,
            left: count - 1,
            number: program,
            args,
        });
        Ok(())
    }

    fn ret(&mut self, seq: Option<u32>) -> R2<()> {
        let f = self.frames.len() - 1;
        let line = self.at.line;
        if f == 0 {
            let target = match seq {
                Some(s) => self.seq_line(0, f64::from(s), 0, "M99 P")?,
                None => self.frames.first().map_or(0, |fr| fr.start),
            };
            self.jumped(line, || "M99".to_string());
            self.set_pc(0, target);
            return Ok(());
        }
        if let Some(top) = self.frames.last_mut()
            && top.left > 0
        {
            top.left -= 1;
            top.pc = top.start;
            let number = top.number;
            if let Some(a) = &top.args {
                self.vars.reset(**a);
            }
            self.jumped(line, || format!("M99 of O{number:04}"));
            return Ok(());
        }
        if let Some(fr) = self.frames.pop()
            && fr.args.is_some()
        {
            self.vars.pop();
        }
        if let Some(s) = seq {
            let caller = self.frames.len() - 1;
            let from = self.frames.last().map_or(0, |fr| fr.pc);
            let t = self.seq_line(caller, f64::from(s), from, "M99 P")?;
            if t < from {
                self.jumped(line, || format!("M99 P{s}"));
            }
            self.set_pc(caller, t);
        }
        Ok(())
    }

    /// Program `n`: in the program's file, then as a file on the search path.
    fn find(&mut self, n: u32, word: &str) -> R2<(Src, usize)> {
        if let Some(i) = self.main.find(n)? {
            return Ok((Src::Main, i));
        }
        for (k, (t, _)) in self.files.iter_mut().enumerate() {
            if let Some(i) = t.find(n)? {
                return Ok((Src::File(k), i));
            }
        }
        let names = [
            format!("O{n:04}.nc"),
            format!("o{n:04}.nc"),
            format!("O{n:04}.NC"),
            format!("O{n:04}"),
            format!("{n}.nc"),
        ];
        let Some(path) = self
            .search
            .iter()
            .flat_map(|d| names.iter().map(move |f| d.join(f)))
            .find(|p| p.is_file())
        else {
            return Err(format!(
                "{word} P{n}: no program O{n:04} in the program's file, and no file O{n:04}.nc \
                 or {n}.nc in the program's folder or on the subroutine path"
            ));
        };
        let file = std::fs::File::open(&path)
            .map_err(|e| format!("{word} P{n}: {}: {e}", path.display()))?;
        let mut t = Text::new(std::io::BufReader::new(file), self.main.max);
        let start = match t.find(n)? {
            Some(i) => i,
            None if t.headers.is_empty() => 0,
            None => {
                return Err(format!(
                    "{word} P{n}: {} holds other programs but not O{n:04}",
                    path.display()
                ));
            }
        };
        let origin: Rc<str> = Rc::from(path.display().to_string().as_str());
        self.files.push((t, origin));
        Ok((Src::File(self.files.len() - 1), start))
    }
}

fn ends_after(ix: &Index, m: u8, pc: usize) -> Option<usize> {
    ix.ends
        .get(usize::from(m - 1))?
        .iter()
        .find(|&&e| e > pc)
        .copied()
}
