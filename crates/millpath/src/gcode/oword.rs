//! O-word control flow: where the next line comes from (LinuxCNC 2.9's `interp_o_word.cc`).
//!
//! The program is a stack of frames: the main program (streamed from its reader) at the
//! bottom, one frame per subroutine call above it. Each frame has its own control stack
//! (`if`/`while`/`do`/`repeat`) and may be skipping forward to an O word of a given name
//! (a false condition, `break`, a taken branch). O words match by name, as in LinuxCNC.
//!
//! * `o<n> sub … o<n> endsub` defines a subroutine where it is met (its lines are kept;
//!   execution continues after `endsub`). `o<n> call [a] [b] …` runs it with `#1..#30` set to
//!   the arguments; a subroutine not yet defined is searched as the file `n.ngc` in the
//!   folders of [`ReaderOptions::subroutine_path`](super::ReaderOptions::subroutine_path)
//!   (the program's own folder first). A call before the definition in the same file is
//!   refused, as LinuxCNC 2.9's rs274 refuses it ("sub found in illegal location").
//!   `return [v]`/`endsub [v]` set `#<_value>` and
//!   `#<_value_returned>`.
//! * `if [c]`/`elseif [c]`/`else`/`endif`; `while [c]`/`endwhile`; `do`/`while [c]`;
//!   `repeat [n]`/`endrepeat`; `break`; `continue`.
//! * Memory: the main program is streamed; only from the start of an open loop on are its
//!   lines kept, until the loop ends.
//! * Every line run inside a loop or a subroutine counts against the step budget
//!   ([`ReaderOptions::step_budget`](super::ReaderOptions::step_budget), module `budget`):
//!   a program that loops for ever is refused naming the loop end (or call) that ran most
//!   often, never hangs. Calls nest at most [`MAX_CALL_DEPTH`] deep, and `if`/`while`/`do`/
//!   `repeat` at most [`MAX_NESTING`] deep within one subroutine (or the main program): the
//!   control stacks are vectors (no recursion), and what each line checks of them is kept
//!   as a count, so a line costs the same at any depth.

use super::budget::Budget;
use super::ngc::{Kw, OWord, o_header, o_label};
use super::params::Store;
use std::collections::{HashMap, VecDeque};
use std::io::BufRead;
use std::path::PathBuf;
use std::rc::Rc;

/// Deepest subroutine nesting.
pub const MAX_CALL_DEPTH: usize = 100;

/// Deepest nesting of `if`, `while`, `do` and `repeat` within one subroutine or the main
/// program (real programs nest a handful; LinuxCNC sets no limit of its own).
pub const MAX_NESTING: usize = 1000;

/// A subroutine's lines.
#[derive(Debug)]
struct Body {
    /// (line number in its file, text).
    lines: Vec<(usize, String)>,
    origin: Rc<str>,
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum CtlKind {
    If { taken: bool },
    While { at: usize },
    Do { start: usize },
    Repeat { start: usize, left: f64 },
}

#[derive(Debug, Clone)]
struct Ctl {
    name: String,
    kind: CtlKind,
}

impl CtlKind {
    fn is_loop(&self) -> bool {
        !matches!(self, CtlKind::If { .. })
    }
}

#[derive(Debug, Clone)]
struct Skip {
    name: String,
    to: &'static [Kw],
    /// Continue after the target line instead of running it.
    past: bool,
    /// Where the skip started (for messages).
    from_line: usize,
}

#[derive(Debug)]
struct Frame {
    body: Option<Rc<Body>>,
    /// Index of the next line (in `body`, or the main program's line index).
    pc: usize,
    ctl: Vec<Ctl>,
    /// Loops in `ctl` (its entries other than `if`).
    loops: usize,
    /// The next line runs again (a `while` line after its `endwhile` or `continue`).
    again: bool,
    skip: Option<Skip>,
    name: String,
}

/// The main program's lines: streamed, with the lines of open loops kept.
#[derive(Debug)]
struct Main<R> {
    src: R,
    kept: VecDeque<Vec<u8>>,
    /// Index of `kept[0]`.
    first: usize,
    eof: bool,
    /// Lines read from `src` so far.
    read: usize,
    /// Reading the line after them failed.
    failed: bool,
}

/// Where a line came from.
#[derive(Debug, Clone)]
pub(crate) struct At {
    pub(crate) line: usize,
    /// `None` for the main program.
    pub(crate) origin: Option<Rc<str>>,
}

/// The program: main stream, subroutines, frames.
#[derive(Debug)]
pub(crate) struct Program<R> {
    main: Main<R>,
    frames: Vec<Frame>,
    subs: HashMap<String, Rc<Body>>,
    search: Vec<PathBuf>,
    budget: Budget,
    max_line: u64,
}

type R2<T> = Result<T, String>;

impl<R: BufRead> Main<R> {
    /// Line `i` into `buf`; `false` past the end. `keep`: keep it for going back.
    fn get(&mut self, i: usize, buf: &mut Vec<u8>, keep: bool, max: u64) -> R2<bool> {
        if i < self.first {
            // A bug, not the program's fault: never run a later line in its place.
            return Err(format!(
                "internal error: line {} is no longer kept (please report)",
                i + 1
            ));
        }
        while self.first + self.kept.len() < i {
            // Lines between (a forward read) are always kept.
            let mut b = Vec::new();
            if !self.read(&mut b, max)? {
                return Ok(false);
            }
            self.kept.push_back(b);
        }
        if let Some(l) = i.checked_sub(self.first).and_then(|k| self.kept.get(k)) {
            buf.clear();
            buf.extend_from_slice(l);
            return Ok(true);
        }
        buf.clear();
        if !self.read(buf, max)? {
            return Ok(false);
        }
        if keep || !self.kept.is_empty() {
            self.kept.push_back(buf.clone());
        } else {
            self.first = i + 1;
        }
        Ok(true)
    }

    fn read(&mut self, buf: &mut Vec<u8>, max: u64) -> R2<bool> {
        if self.eof {
            return Ok(false);
        }
        self.failed = true;
        let n = std::io::Read::take(&mut self.src, max + 1)
            .read_until(b'\n', buf)
            .map_err(|e| format!("unreadable ({e})"))?;
        if n == 0 {
            self.eof = true;
            self.failed = false;
            return Ok(false);
        }
        if n as u64 > max && buf.last() != Some(&b'\n') {
            return Err(format!("a line longer than {max} bytes"));
        }
        self.failed = false;
        self.read += 1;
        Ok(true)
    }

    /// Keeps line `i` (just read, with text `raw`) to run it again.
    fn retain(&mut self, i: usize, raw: &[u8]) {
        if self.kept.is_empty() {
            self.first = i;
            self.kept.push_back(raw.to_vec());
        } else if self.first == i + 1 {
            self.first = i;
            self.kept.push_front(raw.to_vec());
        }
    }

    /// Forgets kept lines before `i`.
    fn forget_before(&mut self, i: usize) {
        while self.first < i && !self.kept.is_empty() {
            self.kept.pop_front();
            self.first += 1;
        }
        if self.kept.is_empty() && self.first < i {
            self.first = i;
        }
    }
}

impl<R: BufRead> Program<R> {
    pub(crate) fn new(src: R, search: Vec<PathBuf>, budget: u64, max_line: u64) -> Self {
        Program {
            main: Main {
                src,
                kept: VecDeque::new(),
                first: 0,
                eof: false,
                read: 0,
                failed: false,
            },
            frames: vec![Frame {
                body: None,
                pc: 0,
                ctl: Vec::new(),
                loops: 0,
                again: false,
                skip: None,
                name: String::new(),
            }],
            subs: HashMap::new(),
            search,
            budget: Budget::new(budget, "lines run in loops and subroutines"),
            max_line,
        }
    }

    fn top(&mut self) -> &mut Frame {
        let n = self.frames.len();
        // The main frame is never popped.
        &mut self.frames[n - 1]
    }

    /// Whether the step budget ran out (the last error is its refusal).
    pub(crate) fn over_budget(&self) -> bool {
        self.budget.exhausted()
    }

    /// The main program's line whose reading failed (too long, unreadable), if one did.
    pub(crate) fn unread_line(&self) -> Option<usize> {
        self.main.failed.then_some(self.main.read + 1)
    }

    /// What the step budget's refusal expects.
    pub(crate) fn budget_expected(&self) -> String {
        self.budget.expected()
    }

    /// Counts a line of frame `f` against the step budget when it runs in a subroutine or
    /// an open loop, or runs again (a `while` line).
    #[inline]
    fn count(&mut self, f: usize) -> R2<()> {
        let again = match self.frames.get_mut(f) {
            Some(fr) => std::mem::take(&mut fr.again) || fr.loops > 0,
            None => false,
        };
        if f > 0 || again {
            self.budget.step()?;
        }
        Ok(())
    }

    /// Opens an `if` or a loop in the running frame.
    fn push_ctl(&mut self, name: &str, kind: CtlKind) -> R2<()> {
        let top = self.top();
        if top.ctl.len() >= MAX_NESTING {
            return Err(format!(
                "o{name}: if, while, do and repeat nested deeper than {MAX_NESTING}"
            ));
        }
        top.loops += usize::from(kind.is_loop());
        top.ctl.push(Ctl {
            name: name.to_string(),
            kind,
        });
        Ok(())
    }

    /// Closes the innermost `if` or loop of the running frame.
    fn pop_ctl(&mut self) -> Option<Ctl> {
        let top = self.top();
        let c = top.ctl.pop()?;
        top.loops -= usize::from(c.kind.is_loop());
        Some(c)
    }

    /// Tallies a backward jump (or a call) made by `o` at `line` of `origin`.
    fn jumped(&mut self, o: &OWord, origin: &str, line: usize) {
        self.budget.jump(origin, line, || {
            format!("{} {}", o_label(&o.name), o.kw.word())
        });
    }

    /// Whether main-program lines must be kept (an open loop in the main frame).
    fn main_keep_from(&self) -> Option<usize> {
        self.frames.first().filter(|f| f.loops > 0).and_then(|f| {
            f.ctl
                .iter()
                .filter_map(|c| match c.kind {
                    CtlKind::While { at } => Some(at),
                    CtlKind::Do { start } | CtlKind::Repeat { start, .. } => Some(start),
                    CtlKind::If { .. } => None,
                })
                .min()
        })
    }

    /// Line `i` of frame `f` into `buf`.
    fn fetch(&mut self, f: usize, i: usize, buf: &mut Vec<u8>) -> R2<Option<At>> {
        let body = self.frames.get(f).and_then(|fr| fr.body.clone());
        match body {
            Some(b) => Ok(b.lines.get(i).map(|(n, t)| {
                buf.clear();
                buf.extend_from_slice(t.as_bytes());
                At {
                    line: *n,
                    origin: Some(Rc::clone(&b.origin)),
                }
            })),
            None => {
                let keep = self.main_keep_from().is_some();
                let got = self.main.get(i, buf, keep, self.max_line)?;
                Ok(got.then_some(At {
                    line: i + 1,
                    origin: None,
                }))
            }
        }
    }

    /// The next line to run into `buf`, or `None` at the end of the program.
    pub(crate) fn next_line(&mut self, buf: &mut Vec<u8>) -> R2<Option<At>> {
        loop {
            let f = self.frames.len() - 1;
            let pc = self.top().pc;
            if f == 0 {
                let keep = self.main_keep_from().unwrap_or(pc).min(pc);
                self.main.forget_before(keep);
            }
            let Some(at) = self.fetch(f, pc, buf)? else {
                let fr = self.top();
                if let Some(s) = &fr.skip {
                    return Err(format!(
                        "o{} at line {}: no matching {:?} before the end",
                        s.name, s.from_line, s.to
                    ));
                }
                if f > 0 {
                    return Err(format!("subroutine o<{}> has no endsub", fr.name));
                }
                return Ok(None);
            };
            self.top().pc += 1;
            self.count(f)?;
            let Some(skip) = self.top().skip.clone() else {
                return Ok(Some(at));
            };
            if let Some((name, kw)) = o_header(buf)
                && name == skip.name
                && skip.to.contains(&kw)
            {
                self.top().skip = None;
                if !skip.past {
                    return Ok(Some(at));
                }
            }
        }
    }

    /// The line index of the line just returned.
    fn current(&mut self) -> usize {
        self.top().pc.saturating_sub(1)
    }

    fn skip_to(&mut self, name: &str, to: &'static [Kw], past: bool, line: usize) {
        self.top().skip = Some(Skip {
            name: name.to_string(),
            to,
            past,
            from_line: line,
        });
    }

    /// Runs an O-word command read at `line` of `origin`.
    /// `raw` is the command's line as read.
    pub(crate) fn run(
        &mut self,
        o: &OWord,
        raw: &[u8],
        line: usize,
        origin: &str,
        params: &mut Store,
    ) -> R2<()> {
        let cond = |o: &OWord| {
            o.args
                .first()
                .copied()
                .ok_or_else(|| format!("o{} {:?} needs a [condition]", o.name, o.kw))
        };
        match o.kw {
            Kw::Sub => self.define(&o.name, origin)?,
            Kw::Endsub | Kw::Return => {
                if self.frames.len() == 1 {
                    return Err(format!("o{} {:?} outside a subroutine", o.name, o.kw));
                }
                self.frames.pop();
                params.ret();
                let v = o.args.first().copied();
                params.set_named("_value", v.unwrap_or(0.0));
                params.set_named("_value_returned", f64::from(u8::from(v.is_some())));
            }
            Kw::Call => {
                self.call(o, params)?;
                self.jumped(o, origin, line);
            }
            Kw::If => {
                let c = cond(o)? != 0.0;
                self.push_ctl(&o.name, CtlKind::If { taken: c })?;
                if !c {
                    self.skip_to(&o.name, &[Kw::Elseif, Kw::Else, Kw::Endif], false, line);
                }
            }
            Kw::Elseif | Kw::Else => {
                let Some(Ctl {
                    kind: CtlKind::If { taken },
                    ..
                }) = self.top().ctl.last().filter(|c| c.name == o.name).cloned()
                else {
                    return Err(format!("o{} {:?} without its if", o.name, o.kw));
                };
                let take = !taken && (o.kw == Kw::Else || cond(o)? != 0.0);
                if taken {
                    self.pop_ctl();
                    self.skip_to(&o.name, &[Kw::Endif], true, line);
                } else if take {
                    if let Some(c) = self.top().ctl.last_mut() {
                        c.kind = CtlKind::If { taken: true };
                    }
                } else {
                    self.skip_to(&o.name, &[Kw::Elseif, Kw::Else, Kw::Endif], false, line);
                }
            }
            Kw::Endif => {
                self.pop_named(o, |k| matches!(k, CtlKind::If { .. }))?;
            }
            Kw::While => {
                let closes_do = matches!(
                    self.top().ctl.last(),
                    Some(Ctl { name, kind: CtlKind::Do { .. } }) if *name == o.name
                );
                let c = cond(o)? != 0.0;
                if closes_do {
                    if c {
                        if let Some(Ctl {
                            kind: CtlKind::Do { start },
                            ..
                        }) = self.top().ctl.last().cloned()
                        {
                            self.top().pc = start;
                            self.jumped(o, origin, line);
                        }
                    } else {
                        self.pop_ctl();
                    }
                } else if c {
                    let at = self.current();
                    if self.frames.len() == 1 {
                        self.main.retain(at, raw);
                    }
                    self.push_ctl(&o.name, CtlKind::While { at })?;
                } else {
                    self.skip_to(&o.name, &[Kw::Endwhile], true, line);
                }
            }
            Kw::Endwhile => {
                let k = self.pop_named(o, |k| matches!(k, CtlKind::While { .. }))?;
                if let CtlKind::While { at } = k {
                    self.top().pc = at;
                    self.top().again = true;
                    self.jumped(o, origin, line);
                }
            }
            Kw::Do => {
                let start = self.top().pc;
                self.push_ctl(&o.name, CtlKind::Do { start })?;
            }
            Kw::Repeat => {
                let n = cond(o)?.round();
                if n >= 1.0 {
                    let start = self.top().pc;
                    self.push_ctl(&o.name, CtlKind::Repeat { start, left: n })?;
                } else {
                    self.skip_to(&o.name, &[Kw::Endrepeat], true, line);
                }
            }
            Kw::Endrepeat => self.end_repeat(o, origin, line)?,
            Kw::Break | Kw::Continue => self.break_continue(o, origin, line)?,
        }
        Ok(())
    }

    fn end_repeat(&mut self, o: &OWord, origin: &str, line: usize) -> R2<()> {
        let top = self.top();
        let again = match top.ctl.last_mut() {
            Some(Ctl {
                name,
                kind: CtlKind::Repeat { start, left },
            }) if *name == o.name => {
                *left -= 1.0;
                if *left >= 1.0 {
                    top.pc = *start;
                    true
                } else {
                    false
                }
            }
            _ => return Err(format!("o{} endrepeat without its repeat", o.name)),
        };
        if again {
            self.jumped(o, origin, line);
        } else {
            self.pop_ctl();
        }
        Ok(())
    }

    /// Pops the control entry named `o.name` (it must be the innermost and of the right kind).
    fn pop_named(&mut self, o: &OWord, kind: impl Fn(&CtlKind) -> bool) -> R2<CtlKind> {
        match self.top().ctl.last() {
            Some(c) if c.name == o.name && kind(&c.kind) => {
                let k = c.kind;
                self.pop_ctl();
                Ok(k)
            }
            _ => Err(format!("o{} {:?} without its opening word", o.name, o.kw)),
        }
    }

    fn break_continue(&mut self, o: &OWord, origin: &str, line: usize) -> R2<()> {
        let top = self.top();
        let Some(k) = top
            .ctl
            .iter()
            .rposition(|c| c.name == o.name && c.kind.is_loop())
        else {
            return Err(format!(
                "o{} {:?} outside a loop of that name",
                o.name, o.kw
            ));
        };
        while self.top().ctl.len() > k + 1 {
            self.pop_ctl();
        }
        let kind = self.top().ctl.last().map(|c| c.kind);
        match (o.kw, kind) {
            (Kw::Break, Some(CtlKind::While { .. })) => {
                self.pop_ctl();
                self.skip_to(&o.name, &[Kw::Endwhile], true, line);
            }
            (Kw::Break, Some(CtlKind::Do { .. })) => {
                self.pop_ctl();
                self.skip_to(&o.name, &[Kw::While], true, line);
            }
            (Kw::Break, _) => {
                self.pop_ctl();
                self.skip_to(&o.name, &[Kw::Endrepeat], true, line);
            }
            (_, Some(CtlKind::While { at })) => {
                self.pop_ctl();
                self.top().pc = at;
                self.top().again = true;
                self.jumped(o, origin, line);
            }
            (_, Some(CtlKind::Do { .. })) => self.skip_to(&o.name, &[Kw::While], false, line),
            _ => self.skip_to(&o.name, &[Kw::Endrepeat], false, line),
        }
        Ok(())
    }

    /// At `o<name> sub`: keeps the lines up to `endsub` and goes on after it. Inside a loop
    /// or a subroutine the lines count against the step budget (a definition run again).
    fn define(&mut self, name: &str, origin: &str) -> R2<()> {
        let f = self.frames.len() - 1;
        let origin: Rc<str> = Rc::from(origin);
        let mut lines = Vec::new();
        let mut buf = Vec::new();
        loop {
            let pc = self.top().pc;
            let Some(at) = self.fetch(f, pc, &mut buf)? else {
                return Err(format!("o<{name}> sub without endsub"));
            };
            self.top().pc += 1;
            self.count(f)?;
            if let Some((n, Kw::Endsub)) = o_header(&buf)
                && n == name
            {
                lines.push((at.line, String::from_utf8_lossy(&buf).to_string()));
                break;
            }
            lines.push((at.line, String::from_utf8_lossy(&buf).to_string()));
        }
        self.subs
            .insert(name.to_string(), Rc::new(Body { lines, origin }));
        Ok(())
    }

    fn call(&mut self, o: &OWord, params: &mut Store) -> R2<()> {
        if self.frames.len() > MAX_CALL_DEPTH {
            return Err(format!(
                "calls nested deeper than {MAX_CALL_DEPTH} (o<{}>)",
                o.name
            ));
        }
        if o.args.len() > super::params::ARGS {
            return Err(format!(
                "o<{}> call with {} arguments (at most {})",
                o.name,
                o.args.len(),
                super::params::ARGS
            ));
        }
        let body = match self.subs.get(&o.name) {
            Some(b) => Rc::clone(b),
            None => self.in_file(&o.name)?.ok_or_else(|| {
                format!(
                    "subroutine o<{0}>: not defined before the call, and no file {0}.ngc in the \
                     program's folder or on the subroutine path",
                    o.name
                )
            })?,
        };
        params.call(&o.args);
        self.frames.push(Frame {
            body: Some(body),
            pc: 0,
            ctl: Vec::new(),
            loops: 0,
            again: false,
            skip: None,
            name: o.name.clone(),
        });
        Ok(())
    }

    /// `name.ngc` on the search path: its `o<name> sub … endsub`.
    fn in_file(&mut self, name: &str) -> R2<Option<Rc<Body>>> {
        let Some(path) = self
            .search
            .iter()
            .map(|d| d.join(format!("{name}.ngc")))
            .find(|p| p.is_file())
        else {
            return Ok(None);
        };
        let text = std::fs::read_to_string(&path)
            .map_err(|e| format!("subroutine file {}: {e}", path.display()))?;
        let origin: Rc<str> = Rc::from(path.display().to_string().as_str());
        let mut lines = Vec::new();
        let mut inside = false;
        for (i, l) in text.lines().enumerate() {
            let h = o_header(l.as_bytes());
            if !inside {
                inside = matches!(&h, Some((n, Kw::Sub)) if n == name);
                continue;
            }
            lines.push((i + 1, l.to_string()));
            if matches!(&h, Some((n, Kw::Endsub)) if n == name) {
                let b = Rc::new(Body { lines, origin });
                self.subs.insert(name.to_string(), Rc::clone(&b));
                return Ok(Some(b));
            }
        }
        Err(format!(
            "{}: no o<{name}> sub … o<{name}> endsub in it",
            path.display()
        ))
    }
}
