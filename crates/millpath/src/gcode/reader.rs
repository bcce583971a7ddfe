//! The streaming reader: lines of a [`BufRead`] → [`ReadMove`]s, one block at a time.
//!
//! Memory is bounded for a program without loops: one line (at most [`MAX_LINE_BYTES`]), its
//! tokens, the modal state, the parameters, at most two pending moves (plus those cutter
//! compensation holds until the next move in the plane) and at most
//! [`MAX_WARNINGS`] stored warnings and messages (all are counted). Subroutines and the lines
//! of an open loop are kept while they may run again (module `oword`).
//!
//! In the LinuxCNC dialect a line with parameters, expressions, an O word or a message
//! comment goes through the RS274/NGC parser (module `ngc`); every other line, and every
//! line of the other dialects, through the plain lexer. In the Fanuc dialect the lines come
//! from module `fanuc` (program numbers, M98/M99/G65; a block the plain lexer refuses is
//! handed back to it: a macro statement runs there, NC words with macro values come back
//! evaluated), and the whole file is kept once read.

use super::dialect::Dialect;
use super::expr::ParamRef;
use super::fanuc::{self, Fanuc};
use super::interp::{Block, ReadMove, ReaderOptions, Scope, State};
use super::lexer::{LineKind, Token, lex};
use super::ngc::{self, NgcLine};
use super::oword::Program;
use super::params::Store;
use crate::error::{Error, InputError};
use crate::geom::Point3;
use crate::toolpath::{Tool, Toolpath};
use std::io::BufRead;
use std::rc::Rc;

/// Longest line accepted, in bytes.
pub const MAX_LINE_BYTES: u64 = 64 * 1024;

/// Warnings kept (further ones are only counted).
pub const MAX_WARNINGS: usize = 1000;

/// A skipped word (lenient mode) or another remark about the program.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Warning {
    /// Line number (1-based).
    pub line: usize,
    /// What was skipped and why.
    pub message: String,
}

/// Where lines come from: RS274/NGC's O-word flow, or a Fanuc program's.
#[derive(Debug)]
enum Source<R> {
    Ngc(Program<R>),
    Fanuc(Box<Fanuc<R>>),
}

/// Reads G-code from `src`, yielding moves as they are interpreted. After the first error it
/// yields nothing more.
#[derive(Debug)]
pub struct Reader<R> {
    source: Source<R>,
    params: Store,
    ngc: NgcLine,
    /// The file of the line being run when it is not the main program's.
    file: Option<Rc<str>>,
    messages: Vec<Warning>,
    opts: ReaderOptions,
    state: State,
    bytes: Vec<u8>,
    tokens: Vec<Token>,
    block: Block,
    pending: Vec<ReadMove>,
    line_no: usize,
    bytes_read: u64,
    done: bool,
    warnings: Vec<Warning>,
    warning_count: usize,
}

impl<R: BufRead> Reader<R> {
    /// A reader over `src`.
    pub fn new(src: R, opts: ReaderOptions) -> Self {
        let mut state = State::new(&opts);
        let params = State::initial_params(&opts);
        state.load_origin(&params);
        let source = if opts.dialect == Dialect::Fanuc {
            Source::Fanuc(Box::new(Fanuc::new(
                src,
                opts.subroutine_path.clone(),
                opts.step_budget,
                MAX_LINE_BYTES,
                opts.block_delete,
            )))
        } else {
            Source::Ngc(Program::new(
                src,
                opts.subroutine_path.clone(),
                opts.step_budget,
                MAX_LINE_BYTES,
            ))
        };
        Reader {
            source,
            params,
            ngc: NgcLine::default(),
            file: None,
            messages: Vec::new(),
            opts,
            state,
            bytes: Vec::with_capacity(128),
            tokens: Vec::with_capacity(16),
            block: Block::default(),
            pending: Vec::with_capacity(2),
            line_no: 0,
            bytes_read: 0,
            done: false,
            warnings: Vec::new(),
            warning_count: 0,
        }
    }

    /// Warnings so far (at most [`MAX_WARNINGS`]).
    pub fn warnings(&self) -> &[Warning] {
        &self.warnings
    }

    /// The program's messages so far (`(MSG,…)`, `(DEBUG,…)`, `(PRINT,…)`, with parameters
    /// replaced by their values), at most [`MAX_WARNINGS`].
    pub fn messages(&self) -> &[Warning] {
        &self.messages
    }

    /// Number of warnings so far, including those not stored.
    pub fn warning_count(&self) -> usize {
        self.warning_count
    }

    /// Lines read so far.
    pub fn lines_read(&self) -> usize {
        self.line_no
    }

    /// Bytes read so far (for a progress bar over a file of known size).
    pub fn bytes_read(&self) -> u64 {
        self.bytes_read
    }

    /// Whether the program ended with M2/M30.
    pub fn ended(&self) -> bool {
        self.state.ended
    }

    /// The current position (machine coordinates, mm).
    pub fn position(&self) -> Point3 {
        self.state_pos()
    }

    fn state_pos(&self) -> Point3 {
        self.pending
            .last()
            .map_or_else(|| self.state.position(), |m| m.mv.to)
    }

    fn origin(&self) -> String {
        match &self.file {
            Some(f) if !f.is_empty() => format!("{f}:{}", self.line_no),
            _ => format!("{}:{}", self.opts.origin, self.line_no),
        }
    }

    fn warn(&mut self, message: String) {
        self.warning_count += 1;
        if self.warnings.len() < MAX_WARNINGS {
            self.warnings.push(Warning {
                line: self.line_no,
                message,
            });
        }
    }

    /// Gets the next line to run into `self.bytes`; `false` at the end of the program.
    fn read_line(&mut self) -> Result<bool, Error> {
        let next = match &mut self.source {
            Source::Ngc(p) => p.next_line(&mut self.bytes),
            Source::Fanuc(f) => f.next_line(&mut self.bytes),
        };
        match next {
            Ok(Some(at)) => {
                self.line_no = at.line;
                self.bytes_read += self.bytes.len() as u64;
                self.file = at.origin;
                Ok(true)
            }
            Ok(None) => Ok(false),
            Err(m) => match &self.source {
                Source::Fanuc(f) => {
                    let at = f.at().clone();
                    self.line_no = at.line;
                    self.file = at.origin;
                    Err(self.fanuc_error(m))
                }
                Source::Ngc(p) => {
                    if let Some(line) = p.unread_line() {
                        self.line_no = line;
                        self.file = None;
                    }
                    let expected = if p.over_budget() {
                        p.budget_expected()
                    } else {
                        "a program LinuxCNC runs (see millpath::gcode::oword)".to_string()
                    };
                    Err(InputError::new("G-code program", m)
                        .at(self.origin())
                        .expected(expected)
                        .into())
                }
            },
        }
    }

    /// Reads and executes lines until one produces moves or the program ends.
    fn advance(&mut self) -> Result<(), Error> {
        while self.pending.is_empty() && !self.state.ended {
            if !self.read_line()? {
                // Moves still waiting for cutter compensation keep their ends.
                self.state.cutter_comp_end(&mut self.pending);
                self.done = true;
                return Ok(());
            }
            if self.opts.dialect == Dialect::LinuxCnc && ngc::needed(&self.bytes) {
                self.run_ngc_line()?;
                continue;
            }
            let text = match std::str::from_utf8(&self.bytes) {
                Ok(t) => t,
                Err(_) => {
                    return Err(InputError::new("G-code line", "not UTF-8 text")
                        .at(self.origin())
                        .expected("ASCII G-code")
                        .into());
                }
            };
            let lexed = lex(text, &mut self.tokens);
            if lexed.is_err()
                && let Source::Fanuc(f) = &mut self.source
                && fanuc::candidate(&self.bytes)
            {
                // A macro statement (run by the line source) or NC words with macro values.
                let bytes = std::mem::take(&mut self.bytes);
                let r = f.macro_block(&bytes);
                self.bytes = bytes;
                match r {
                    Ok(Some((tokens, text))) => self.run_fanuc_block(tokens, Some(&text))?,
                    Ok(None) => {}
                    Err(m) => return Err(self.fanuc_error(m)),
                }
                continue;
            }
            let kind = lexed.map_err(|e| {
                InputError::new(
                    "G-code text",
                    format!("'{}' at column {}", e.text, e.column + 1),
                )
                .at(self.origin())
                .expected(e.expected)
            })?;
            match kind {
                LineKind::Percent => continue,
                LineKind::Block { block_delete } if block_delete && self.opts.block_delete => {
                    continue;
                }
                LineKind::Block { .. } => {}
            }
            let tokens = std::mem::take(&mut self.tokens);
            if matches!(self.source, Source::Fanuc(_)) {
                self.run_fanuc_block(tokens, None)?;
                continue;
            }
            let r = self.run_block(&tokens, None);
            self.tokens = tokens;
            r?;
        }
        Ok(())
    }

    fn fanuc_error(&self, m: String) -> Error {
        let expected = match &self.source {
            Source::Fanuc(f) if f.over_budget() => f.budget_expected(),
            _ => "a program a Fanuc control with custom macro B runs (see millpath::gcode::fanuc)"
                .to_string(),
        };
        InputError::new("G-code program", m)
            .at(self.origin())
            .expected(expected)
            .into()
    }

    /// A Fanuc block: its M98/M99/G65 taken out, its other words run, then the call or
    /// return. `text` is the words' text when it is not `self.bytes`.
    fn run_fanuc_block(&mut self, mut tokens: Vec<Token>, text: Option<&str>) -> Result<(), Error> {
        let control = fanuc::take_control(&mut tokens).map_err(|m| self.fanuc_error(m));
        let r = match control {
            Ok(Some(fanuc::Control::Call { args: Some(_), .. })) => Ok(()),
            Ok(_) => self.run_block(&tokens, text),
            Err(_) => Ok(()),
        };
        if text.is_none() {
            self.tokens = tokens;
        }
        r?;
        let control = control?;
        if let (Some(c), Source::Fanuc(f)) = (control, &mut self.source)
            && !self.state.ended
        {
            let r = f.apply(c);
            if let Err(m) = r {
                return Err(self.fanuc_error(m));
            }
        }
        Ok(())
    }

    /// A line through the RS274/NGC parser: messages, then an O word or the block and its
    /// parameter settings.
    fn run_ngc_line(&mut self) -> Result<(), Error> {
        let text = String::from_utf8_lossy(&self.bytes).to_string();
        let scope = Scope {
            store: &self.params,
            state: &self.state,
            call_level: self.params.call_level(),
        };
        let parsed = ngc::parse(&text, &scope, &mut self.ngc);
        for m in std::mem::take(&mut self.ngc.messages) {
            self.message(m);
        }
        if let Err(m) = parsed {
            return Err(InputError::new("G-code line", super::lexer::shown(&text))
                .at(self.origin())
                .expected(format!("RS274/NGC as LinuxCNC reads it: {m}"))
                .into());
        }
        if self.ngc.block_delete && self.opts.block_delete {
            return Ok(());
        }
        if let Some(o) = self.ngc.oword.take() {
            let origin = self.origin();
            let file = self.file.as_deref().unwrap_or("").to_string();
            let level = self.params.call_level();
            let Source::Ngc(program) = &mut self.source else {
                return Err(Error::internal(
                    "an O word outside RS274/NGC (please report)",
                ));
            };
            program
                .run(&o, &self.bytes, self.line_no, &file, &mut self.params)
                .map_err(|m| {
                    let (what, expected) = if program.over_budget() {
                        ("G-code program", program.budget_expected())
                    } else {
                        (
                            "O word",
                            "O-word control flow as LinuxCNC runs it".to_string(),
                        )
                    };
                    Error::from(InputError::new(what, m).at(origin).expected(expected))
                })?;
            // A return: the state M73 saved at the level left is restored.
            if self.params.call_level() < level {
                self.state.auto_restore(level, &self.params);
            }
            return Ok(());
        }
        // Settings take effect after the line is read, before it runs.
        for (r, v) in std::mem::take(&mut self.ngc.assigns) {
            match r {
                ParamRef::Numbered(n) => self.params.set(n, v),
                ParamRef::Named(name) => self.params.set_named(&name, v),
            }
        }
        let tokens = std::mem::take(&mut self.ngc.tokens);
        let line = std::mem::take(&mut self.ngc.text);
        let r = self.run_block(&tokens, Some(&line));
        self.ngc.tokens = tokens;
        self.ngc.text = line;
        r
    }

    fn message(&mut self, text: String) {
        if self.messages.len() < MAX_WARNINGS {
            self.messages.push(Warning {
                line: self.line_no,
                message: text,
            });
        }
    }

    /// Gathers and executes one block's tokens; `line` is their text when it is not
    /// `self.bytes`.
    fn run_block(&mut self, tokens: &[Token], line: Option<&str>) -> Result<(), Error> {
        let text = match line {
            Some(l) => l,
            None => std::str::from_utf8(&self.bytes).unwrap_or(""),
        };
        let mut skipped = Vec::new();
        let gathered = self.block.gather(
            tokens,
            text,
            self.opts.dialect,
            |e| skipped.push(format!("skipped {} ({})", e.value, e.expected)),
            self.opts.lenient,
        );
        if let Err(e) = gathered {
            return Err(e.into_input(self.origin()).into());
        }
        for s in skipped {
            self.warn(s);
        }
        let r = self.state.execute(
            &mut self.block,
            self.line_no,
            &self.opts,
            &mut self.params,
            &mut self.pending,
        );
        match r {
            Err(e) if e.unsupported && self.opts.lenient => {
                self.warn(format!("skipped {} ({})", e.value, e.expected));
            }
            Err(e) => return Err(e.into_input(self.origin()).into()),
            Ok(()) => {}
        }
        for note in std::mem::take(&mut self.state.notes) {
            self.warn(note);
        }
        Ok(())
    }
}

impl<R: BufRead> Iterator for Reader<R> {
    type Item = Result<ReadMove, Error>;

    fn next(&mut self) -> Option<Self::Item> {
        if self.pending.is_empty() {
            if self.done {
                return None;
            }
            if let Err(e) = self.advance() {
                self.done = true;
                self.pending.clear();
                return Some(Err(e));
            }
        }
        if self.pending.is_empty() {
            self.done = true;
            return None;
        }
        Some(Ok(self.pending.remove(0)))
    }
}

impl ReaderOptions {
    /// The files a program may need: subroutine folders (the program's own folder first, then
    /// `subroutine_path`, LinuxCNC's `SUBROUTINE_PATH`) and a LinuxCNC tool table (in mm).
    /// Errors name the folder or file and the flag it came from.
    pub fn with_program_files(
        mut self,
        program: &std::path::Path,
        subroutine_path: &[std::path::PathBuf],
        tool_table: Option<&std::path::Path>,
    ) -> Result<Self, Error> {
        for d in subroutine_path {
            if !d.is_dir() {
                return Err(InputError::new("subroutine folder", d.display())
                    .at("--subroutine-path")
                    .expected("existing folders, separated by ':'")
                    .into());
            }
        }
        self.subroutine_path = program
            .parent()
            .map(|d| {
                if d.as_os_str().is_empty() {
                    std::path::Path::new(".")
                } else {
                    d
                }
            })
            .map(std::path::Path::to_path_buf)
            .into_iter()
            .chain(subroutine_path.iter().cloned())
            .collect();
        if let Some(t) = tool_table {
            let table = super::tools::ToolTable::read(t, super::dialect::Units::Mm)
                .map_err(|e| e.at(format!("--tool-table {}", t.display())))?;
            self.tool_table = Some(std::sync::Arc::new(table));
        }
        Ok(self)
    }
}

/// Reads a whole program into a [`Toolpath`] (with `tool` and the reader's start), plus the
/// warnings. For tests and small programs; the estimator streams with [`Reader`].
pub fn read_toolpath<R: BufRead>(
    src: R,
    opts: ReaderOptions,
    tool: Tool,
) -> Result<(Toolpath, Vec<Warning>), Error> {
    let start = opts.start;
    let mut reader = Reader::new(src, opts);
    let mut tp = Toolpath::new(tool, start);
    for m in &mut reader {
        tp.push(m?.mv);
    }
    Ok((tp, reader.warnings().to_vec()))
}

/// [`read_toolpath`] over a string.
pub fn read_str(text: &str, opts: ReaderOptions) -> Result<(Toolpath, Vec<Warning>), Error> {
    read_toolpath(text.as_bytes(), opts, Tool::default())
}
