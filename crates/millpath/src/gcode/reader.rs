//! The streaming reader: lines of a [`BufRead`] → [`ReadMove`]s, one block at a time.
//!
//! Memory is bounded: one line (at most [`MAX_LINE_BYTES`]), its tokens, the modal state, at
//! most two pending moves and at most [`MAX_WARNINGS`] stored warnings (all are counted).

use super::interp::{Block, ReadMove, ReaderOptions, State};
use super::lexer::{LineKind, Token, lex};
use crate::error::{Error, InputError};
use crate::geom::Point3;
use crate::toolpath::{Tool, Toolpath};
use std::io::{BufRead, Read};

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

/// Reads G-code from `src`, yielding moves as they are interpreted. After the first error it
/// yields nothing more.
#[derive(Debug)]
pub struct Reader<R> {
    src: R,
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
        let state = State::new(&opts);
        Reader {
            src,
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
        format!("{}:{}", self.opts.origin, self.line_no)
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

    /// Reads the next line into `self.bytes`; `false` at the end of the input.
    fn read_line(&mut self) -> Result<bool, Error> {
        self.bytes.clear();
        let n = (&mut self.src)
            .take(MAX_LINE_BYTES + 1)
            .read_until(b'\n', &mut self.bytes)
            .map_err(|e| {
                InputError::new("G-code input", e)
                    .at(self.origin())
                    .expected("a readable file")
            })?;
        if n == 0 {
            return Ok(false);
        }
        self.line_no += 1;
        self.bytes_read += n as u64;
        if n as u64 > MAX_LINE_BYTES && self.bytes.last() != Some(&b'\n') {
            return Err(InputError::new(
                "G-code line",
                format!("longer than {MAX_LINE_BYTES} bytes"),
            )
            .at(self.origin())
            .expected("lines of ordinary length")
            .into());
        }
        Ok(true)
    }

    /// Reads and executes lines until one produces moves or the program ends.
    fn advance(&mut self) -> Result<(), Error> {
        while self.pending.is_empty() && !self.state.ended {
            if !self.read_line()? {
                self.done = true;
                return Ok(());
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
            let kind = lex(text, &mut self.tokens).map_err(|e| {
                InputError::new(
                    "G-code text",
                    format!("'{}' at column {}", e.text, e.column + 1),
                )
                .at(format!("{}:{}", self.opts.origin, self.line_no))
                .expected(e.expected)
            })?;
            match kind {
                LineKind::Percent => continue,
                LineKind::Block { block_delete } if block_delete && self.opts.block_delete => {
                    continue;
                }
                LineKind::Block { .. } => {}
            }
            let mut skipped = Vec::new();
            let gathered = self.block.gather(
                &self.tokens,
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
            let r =
                self.state
                    .execute(&mut self.block, self.line_no, &self.opts, &mut self.pending);
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
