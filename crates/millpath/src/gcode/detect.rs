//! Which dialect a program is written in: clues from its file name and first lines, scored,
//! and a fallback to the next candidate when the first one's reader refuses the program.
//!
//! # Clues
//! Each [`ClueRule`] found in the program (its first occurrence, in the first
//! [`DETECT_BYTES`] of the text) adds its weight to the dialects that have it; LinuxCNC, the
//! reference dialect that reads most programs, starts one point ahead, and ties go to
//! LinuxCNC, Fanuc, Sinumerik, Grbl in that order:
//!
//! | rule | what | LinuxCNC | Fanuc | Sinumerik | Grbl |
//! |---|---|---|---|---|---|
//! | [`Extension`](ClueRule::Extension) | `.ngc`; `.mpf`/`.spf` (`.nc`, `.tap`, `.gcode` tell nothing) | 5 | | 5 | |
//! | [`OWord`](ClueRule::OWord) | `o<name> sub`, `o100 while`, … | 10 | | | |
//! | [`NamedParameter`](ClueRule::NamedParameter) | `#<name>` | 10 | | | |
//! | [`LinuxCncWord`](ClueRule::LinuxCncWord) | `G64 P`, `G61.1`, `G33.1`, `G5.2`, `M62`–`M66`, `(MSG,…)`, `(DEBUG,…)` | 4 | | | |
//! | [`NotGrbl`](ClueRule::NotGrbl) | `M6`, `G43`, `G64`, `G61.1`: words Grbl lacks | 2 | | | |
//! | [`Expression`](ClueRule::Expression) | `#1`, `[…]` | 2 | 2 | | |
//! | [`ProgramNumber`](ClueRule::ProgramNumber) | a line `O1234` or `:1234` | | 8 | | |
//! | [`MacroB`](ClueRule::MacroB) | `WHILE [..] DO1`, `END1`, `IF [..] GOTO`, `GOTO 10` | | 8 | | |
//! | [`FanucCall`](ClueRule::FanucCall) | `M98`, `M99`, `G65`, `G66` | | 8 | | |
//! | [`FanucWord`](ClueRule::FanucWord) | `G05.1` (AI contour control) | | 4 | | |
//! | [`Percent`](ClueRule::Percent) | a `%` line (LinuxCNC allows it too) | | 3 | | |
//! | [`SinumerikCycle`](ClueRule::SinumerikCycle) | `CYCLE832(…)`, `CYCLE81(…)`, `MCALL`, `POCKET3(…)` | | | 10 | |
//! | [`SinumerikUnits`](ClueRule::SinumerikUnits) | `G700`/`G710`, `G70`/`G71` without a lathe cycle's words (P Q U W R D I K) | | | 8 | |
//! | [`SinumerikWord`](ClueRule::SinumerikWord) | `G60`, `G641`–`G645`, `TURN=`, `MSG(`, `DEF`, `R1=`, `X=`, `GOTOF`, `M17`, `TRANS`, `$P_…` | | | 6 | |
//! | [`Semicolons`](ClueRule::Semicolons) | `;` comments (LinuxCNC reads them too) | | | 1 | 2 |
//!
//! The weights order the candidates; they need not be right, because of the fallback.
//!
//! # Fallback
//! A dialect must never be chosen when its reader refuses what another reads. The first
//! candidate is read (the estimate streams it); when its reader refuses the program, the
//! others are tried in order, each reading the whole program (reading only: no planning), and
//! the first that reads it all is chosen ([`DialectReason::Fallback`]). A program every
//! candidate refuses keeps the first one's refusal. The common case, a program its first
//! candidate reads, costs nothing more than the scan of its head.

use super::dialect::Dialect;
use super::interp::ReaderOptions;
use super::reader::Reader;
use crate::error::Error;
use std::fmt;
use std::io::BufRead;
use std::path::Path;

/// Bytes of a program's head scanned for clues (cut at a character boundary).
pub const DETECT_BYTES: usize = 64 * 1024;

/// A kind of clue to a program's dialect (the rows of the table in the module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum ClueRule {
    /// The file extension: `.ngc` (LinuxCNC), `.mpf`/`.spf` (Sinumerik).
    Extension,
    /// An O-word command (`o<name> sub`, `o100 while`): LinuxCNC.
    OWord,
    /// A named parameter `#<name>`: LinuxCNC.
    NamedParameter,
    /// A word only LinuxCNC has (`G64 P`, `G61.1`, `M62`–`M66`, `(MSG,…)`).
    LinuxCncWord,
    /// A word Grbl lacks (`M6`, `G43`, `G64`, `G61.1`): LinuxCNC rather than Grbl.
    NotGrbl,
    /// A numbered parameter or a bracketed expression: LinuxCNC or Fanuc macro B.
    Expression,
    /// A program number line `O1234` or `:1234`: Fanuc.
    ProgramNumber,
    /// A custom macro B statement (`WHILE [..] DO1`, `END1`, `IF [..] GOTO n`, `GOTO n`).
    MacroB,
    /// A Fanuc subprogram or macro call (`M98`, `M99`, `G65`, `G66`).
    FanucCall,
    /// A word only Fanuc has (`G05.1`).
    FanucWord,
    /// A `%` line: Fanuc's tape framing (LinuxCNC allows it too).
    Percent,
    /// A Sinumerik cycle call (`CYCLE832(…)`, `MCALL`).
    SinumerikCycle,
    /// Sinumerik's unit codes (`G700`/`G710`, `G70`/`G71` without a lathe cycle's words).
    SinumerikUnits,
    /// A word only Sinumerik has (`G60`, `G642`, `TURN=`, `MSG(`, `R1=`, `GOTOF`, …).
    SinumerikWord,
    /// `;` comments: Grbl or Sinumerik (LinuxCNC reads them too).
    Semicolons,
}

impl ClueRule {
    /// Every rule, in the order of the table.
    pub const ALL: [ClueRule; 15] = [
        ClueRule::Extension,
        ClueRule::OWord,
        ClueRule::NamedParameter,
        ClueRule::LinuxCncWord,
        ClueRule::NotGrbl,
        ClueRule::Expression,
        ClueRule::ProgramNumber,
        ClueRule::MacroB,
        ClueRule::FanucCall,
        ClueRule::FanucWord,
        ClueRule::Percent,
        ClueRule::SinumerikCycle,
        ClueRule::SinumerikUnits,
        ClueRule::SinumerikWord,
        ClueRule::Semicolons,
    ];

    /// Points for LinuxCNC, Fanuc, Sinumerik, Grbl ([`Dialect::ALL`]'s order). The
    /// extension's depend on which extension: see [`Clue::weights`].
    fn weights(self) -> [i32; 4] {
        match self {
            ClueRule::Extension => [0; 4],
            ClueRule::OWord | ClueRule::NamedParameter => [10, 0, 0, 0],
            ClueRule::LinuxCncWord => [4, 0, 0, 0],
            ClueRule::NotGrbl => [2, 0, 0, 0],
            ClueRule::Expression => [2, 2, 0, 0],
            ClueRule::ProgramNumber | ClueRule::MacroB | ClueRule::FanucCall => [0, 8, 0, 0],
            ClueRule::FanucWord => [0, 4, 0, 0],
            ClueRule::Percent => [0, 3, 0, 0],
            ClueRule::SinumerikCycle => [0, 0, 10, 0],
            ClueRule::SinumerikUnits => [0, 0, 8, 0],
            ClueRule::SinumerikWord => [0, 0, 6, 0],
            ClueRule::Semicolons => [0, 0, 1, 2],
        }
    }
}

impl fmt::Display for ClueRule {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            ClueRule::Extension => "the file extension",
            ClueRule::OWord => "an O word, LinuxCNC's subroutines and loops",
            ClueRule::NamedParameter => "a named parameter, LinuxCNC's",
            ClueRule::LinuxCncWord => "a word only LinuxCNC has",
            ClueRule::NotGrbl => "a word Grbl lacks",
            ClueRule::Expression => "a parameter or expression, LinuxCNC's or Fanuc macro B's",
            ClueRule::ProgramNumber => "a program number, Fanuc's",
            ClueRule::MacroB => "a custom macro B statement, Fanuc's",
            ClueRule::FanucCall => "a subprogram or macro call, Fanuc's",
            ClueRule::FanucWord => "a word only Fanuc has",
            ClueRule::Percent => "a % line, Fanuc's tape framing",
            ClueRule::SinumerikCycle => "a Sinumerik cycle",
            ClueRule::SinumerikUnits => "Sinumerik's units",
            ClueRule::SinumerikWord => "a word only Sinumerik has",
            ClueRule::Semicolons => "; comments, Grbl's or Sinumerik's",
        })
    }
}

/// One clue found in a program: its rule, where (line 1-based; 0 for the file name) and the
/// text that showed it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Clue {
    /// The rule.
    pub rule: ClueRule,
    /// The line (0: the file name).
    pub line: usize,
    /// The text that showed it (`o<factorial> sub`, `G70`, `.mpf`).
    pub text: String,
}

impl Clue {
    /// Points for LinuxCNC, Fanuc, Sinumerik, Grbl.
    fn weights(&self) -> [i32; 4] {
        match self.rule {
            ClueRule::Extension if self.text == ".ngc" => [5, 0, 0, 0],
            ClueRule::Extension => [0, 0, 5, 0],
            r => r.weights(),
        }
    }

    /// Points for `d`.
    fn weight(&self, d: Dialect) -> i32 {
        let k = Dialect::ALL.iter().position(|&x| x == d).unwrap_or(0);
        self.weights().get(k).copied().unwrap_or(0)
    }
}

impl fmt::Display for Clue {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.line == 0 {
            write!(f, "{} {}", self.rule, self.text)
        } else {
            write!(f, "`{}` at line {} ({})", self.text, self.line, self.rule)
        }
    }
}

/// The clues of a program and the dialects they suggest, best first.
#[derive(Debug, Clone, PartialEq)]
pub struct DialectGuess {
    clues: Vec<Clue>,
    ranked: [Dialect; 4],
}

/// Why a dialect was chosen.
#[derive(Debug, Clone, PartialEq)]
pub enum DialectReason {
    /// Named by the caller (`--dialect`).
    Named,
    /// The clues that scored for it, strongest first.
    Clues(Vec<Clue>),
    /// No clue: LinuxCNC, the reference dialect.
    NoClue,
    /// The clues suggested `suggested`, whose reader refused the program (`refusal`); this
    /// one, the first of the other candidates, reads it all.
    Fallback {
        /// The dialect the clues suggested.
        suggested: Dialect,
        /// Its clues.
        clues: Vec<Clue>,
        /// Its reader's refusal.
        refusal: String,
    },
}

/// A dialect and why it was chosen.
#[derive(Debug, Clone, PartialEq)]
pub struct DialectChoice {
    /// The dialect.
    pub dialect: Dialect,
    /// Why.
    pub reason: DialectReason,
}

fn list(clues: &[Clue]) -> String {
    clues
        .iter()
        .map(ToString::to_string)
        .collect::<Vec<_>>()
        .join(", ")
}

impl fmt::Display for DialectReason {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            DialectReason::Named => f.write_str("named with --dialect"),
            DialectReason::Clues(c) => write!(f, "found from {}", list(c)),
            DialectReason::NoClue => {
                f.write_str("no word of another dialect: LinuxCNC's, the reference dialect")
            }
            DialectReason::Fallback {
                suggested,
                clues,
                refusal,
            } => {
                let why = if clues.is_empty() {
                    "the default".to_string()
                } else {
                    format!("suggested by {}", list(clues))
                };
                write!(
                    f,
                    "{suggested} ({why}) refuses the program ({refusal}); this dialect reads \
                     all of it"
                )
            }
        }
    }
}

impl fmt::Display for DialectChoice {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "dialect {}: {}", self.dialect, self.reason)
    }
}

impl DialectGuess {
    /// The clues of the program named `name` (its extension is a clue; `None` for text
    /// without a file) whose text starts with `head` (the first [`DETECT_BYTES`] are read).
    pub fn new(name: Option<&Path>, head: &str) -> Self {
        let mut clues = Vec::new();
        if let Some(ext) = name.and_then(Path::extension).and_then(|e| e.to_str()) {
            let ext = ext.to_ascii_lowercase();
            if matches!(ext.as_str(), "ngc" | "mpf" | "spf") {
                clues.push(Clue {
                    rule: ClueRule::Extension,
                    line: 0,
                    text: format!(".{ext}"),
                });
            }
        }
        let mut end = head.len().min(DETECT_BYTES);
        while !head.is_char_boundary(end) {
            end -= 1;
        }
        for (i, line) in head.get(..end).unwrap_or("").lines().enumerate() {
            scan_line(line, i + 1, &mut clues);
        }
        let score = |d: Dialect| -> i32 {
            i32::from(d == Dialect::LinuxCnc) + clues.iter().map(|c| c.weight(d)).sum::<i32>()
        };
        let mut ranked = Dialect::ALL;
        // Stable: ties keep the order of Dialect::ALL.
        ranked.sort_by_key(|&d| std::cmp::Reverse(score(d)));
        DialectGuess { clues, ranked }
    }

    /// The candidates, best first (all four dialects).
    pub fn ranked(&self) -> [Dialect; 4] {
        self.ranked
    }

    /// The best candidate.
    pub fn best(&self) -> Dialect {
        self.ranked[0]
    }

    /// Every clue found (one per rule, its first occurrence).
    pub fn clues(&self) -> &[Clue] {
        &self.clues
    }

    /// The clues that score for `d`, strongest first.
    pub fn clues_for(&self, d: Dialect) -> Vec<Clue> {
        let mut c: Vec<Clue> = self
            .clues
            .iter()
            .filter(|c| c.weight(d) > 0)
            .cloned()
            .collect();
        c.sort_by_key(|c| std::cmp::Reverse(c.weight(d)));
        c
    }

    /// The best candidate and its clues.
    pub fn choice(&self) -> DialectChoice {
        let clues = self.clues_for(self.best());
        DialectChoice {
            dialect: self.best(),
            reason: if clues.is_empty() {
                DialectReason::NoClue
            } else {
                DialectReason::Clues(clues)
            },
        }
    }

    /// After the best candidate's reader refused the program with `refusal`: the first other
    /// candidate for which `reads` (which reads the whole program in that dialect) is true.
    /// `None` when none reads it.
    pub fn fall_back(
        &self,
        refusal: &Error,
        mut reads: impl FnMut(Dialect) -> bool,
    ) -> Option<DialectChoice> {
        let first = self.best();
        let d = self.ranked.into_iter().skip(1).find(|&d| reads(d))?;
        Some(DialectChoice {
            dialect: d,
            reason: DialectReason::Fallback {
                suggested: first,
                clues: self.clues_for(first),
                refusal: refusal.to_string(),
            },
        })
    }
}

impl Dialect {
    /// The dialect a program's text most likely is, from its first lines `head` (a few KiB
    /// are plenty): the best candidate of [`DialectGuess`], whose module tables the clues and
    /// their weights. Without a file name, so without its extension; and without the
    /// fallback to another dialect when this one's reader refuses the program (the estimate
    /// and verify jobs do both).
    pub fn detect(head: &str) -> Dialect {
        DialectGuess::new(None, head).best()
    }
}

/// Whether the reader with `opts` reads the whole program `src` (moves read and dropped).
pub fn reads_whole<R: BufRead>(src: R, opts: ReaderOptions) -> bool {
    Reader::new(src, opts).all(|m| m.is_ok())
}

/// The clues of one line, pushed when their rule has not been seen yet.
fn scan_line(raw: &str, line: usize, clues: &mut Vec<Clue>) {
    let mut add = |rule: ClueRule, text: &str| {
        if !clues.iter().any(|c| c.rule == rule) {
            clues.push(Clue {
                rule,
                line,
                text: text.trim().chars().take(40).collect(),
            });
        }
    };
    let trimmed = raw.trim();
    if trimmed == "%" {
        add(ClueRule::Percent, "%");
        return;
    }
    // Comments: `( … )` set aside (message comments are LinuxCNC's), `;` to the end.
    let mut code = String::with_capacity(raw.len());
    let mut depth = 0usize;
    let mut semicolon = false;
    for (k, c) in raw.char_indices() {
        match c {
            // `CYCLE832(`, `MSG(`: a call (two letters or more before it), not a comment.
            '(' if depth == 0 && is_call(&code) => code.push('('),
            '(' if depth == 0 => {
                depth = 1;
                let body: String = raw
                    .get(k + 1..)
                    .unwrap_or("")
                    .chars()
                    .filter(|c| !c.is_whitespace())
                    .take(6)
                    .collect::<String>()
                    .to_ascii_uppercase();
                if ["MSG,", "DEBUG,", "PRINT,"]
                    .iter()
                    .any(|m| body.starts_with(m))
                {
                    add(ClueRule::LinuxCncWord, raw.get(k..).unwrap_or(""));
                }
            }
            ')' if depth > 0 => depth = 0,
            ';' if depth == 0 => {
                semicolon = true;
                break;
            }
            c if depth == 0 => code.push(c.to_ascii_uppercase()),
            _ => {}
        }
    }
    if semicolon {
        add(ClueRule::Semicolons, ";");
    }
    let code = code.trim();
    if code.is_empty() {
        return;
    }
    if let Some((name, kw)) = super::ngc::o_header(raw.as_bytes()) {
        add(
            ClueRule::OWord,
            &format!("{} {}", super::ngc::o_label(&name), kw.word()),
        );
        return;
    }
    if super::fanuc::header(raw.as_bytes()).is_some() {
        add(ClueRule::ProgramNumber, code);
        return;
    }
    let compact: String = code.chars().filter(|c| !c.is_whitespace()).collect();
    if compact.contains("#<") {
        add(ClueRule::NamedParameter, &compact);
    }
    if compact.contains('[') || has_numbered_parameter(&compact) {
        add(ClueRule::Expression, &compact);
    }
    let body = strip_n(&compact);
    if let Some(m) = macro_b(body) {
        add(ClueRule::MacroB, m);
    }
    if let Some(s) = sinumerik_text(code, &compact) {
        add(ClueRule::SinumerikWord, s);
    }
    if let Some(c) = sinumerik_cycle(&compact) {
        add(ClueRule::SinumerikCycle, c);
    }
    let words = words(body);
    let has = |l: char| words.iter().any(|(w, _)| *w == l);
    for (letter, num) in &words {
        let code10 = code_times_ten(num);
        let word = format!("{letter}{num}");
        match (letter, code10) {
            ('G', Some(640)) if has('P') => add(ClueRule::LinuxCncWord, "G64 P"),
            ('G', Some(611 | 331 | 52 | 53 | 431)) | ('M', Some(620..=660)) => {
                add(ClueRule::LinuxCncWord, &word);
            }
            ('G', Some(51)) if num.starts_with('0') || has('Q') => {
                add(ClueRule::FanucWord, &word);
            }
            ('M', Some(980 | 990)) | ('G', Some(650 | 660 | 661 | 670)) => {
                add(ClueRule::FanucCall, &word);
            }
            ('G', Some(7000 | 7100)) => add(ClueRule::SinumerikUnits, &word),
            ('G', Some(700 | 710)) if !"PQUWRDIK".chars().any(has) => {
                add(ClueRule::SinumerikUnits, &word);
            }
            ('G', Some(600 | 6410 | 6420 | 6430 | 6440 | 6450)) | ('M', Some(170)) => {
                add(ClueRule::SinumerikWord, &word);
            }
            _ => {}
        }
        if matches!(
            (letter, code10),
            ('M', Some(60)) | ('G', Some(430 | 640 | 611))
        ) {
            add(ClueRule::NotGrbl, &word);
        }
    }
}

/// Whether the text before a `(` ends in a name of two letters or more (`CYCLE832`, `MSG`).
fn is_call(before: &str) -> bool {
    let name: Vec<char> = before
        .chars()
        .rev()
        .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
        .collect();
    let letters = name
        .iter()
        .rev()
        .take_while(|c| c.is_ascii_alphabetic())
        .count();
    letters >= 2
}

/// The line without its block-delete slash and N word.
fn strip_n(s: &str) -> &str {
    let s = s.strip_prefix('/').unwrap_or(s);
    match s.strip_prefix('N') {
        Some(r) if r.starts_with(|c: char| c.is_ascii_digit()) => {
            r.trim_start_matches(|c: char| c.is_ascii_digit())
        }
        _ => s,
    }
}

/// `#` followed by a digit (`#1`, `#100=`).
fn has_numbered_parameter(s: &str) -> bool {
    s.as_bytes()
        .windows(2)
        .any(|w| w[0] == b'#' && w[1].is_ascii_digit())
}

/// A macro B statement at the start of a block (upper case, no spaces).
fn macro_b(s: &str) -> Option<&str> {
    let loop_id = |r: &str| matches!(r, "1" | "2" | "3");
    let goto_target = |r: &str| r.starts_with(|c: char| c.is_ascii_digit() || c == '#' || c == '[');
    let hit = s.starts_with("WHILE[")
        || (s.starts_with("IF[") && (s.contains("GOTO") || s.contains("THEN")))
        || s.strip_prefix("GOTO").is_some_and(goto_target)
        || s.strip_prefix("DO").is_some_and(loop_id)
        || s.strip_prefix("END").is_some_and(loop_id);
    hit.then_some(s)
}

/// Sinumerik's language words: `TURN=`, `MSG(`, `DEF`, `R1=`, `X=`, `GOTOF`, … (`code` upper
/// case with spaces, `compact` without).
fn sinumerik_text<'a>(code: &'a str, compact: &'a str) -> Option<&'a str> {
    const STARTS: [&str; 12] = [
        "DEF ", "PROC ", "EXTERN ", "GOTOF ", "GOTOB ", "TRANS ", "ATRANS ", "ROT ", "AROT ",
        "STOPRE", "ENDWHILE", "ENDIF",
    ];
    const CONTAINS: [&str; 8] = [
        "TURN=", "MSG(", "GOTOF", "GOTOB", "$P_", "$A_", "$AA_", "$TC_",
    ];
    let body = strip_n(code).trim_start();
    if STARTS
        .iter()
        .any(|s| body.starts_with(s) || body == s.trim())
    {
        return Some(code);
    }
    if CONTAINS.iter().any(|s| compact.contains(s)) {
        return Some(compact);
    }
    // `R1=…` or an axis, feed or spindle word with `=` (`X=R1+2`, `F=100`): a letter (not
    // the end of a longer name), then digits for an R parameter or none for an address.
    if compact.starts_with(['#', '$']) {
        return None;
    }
    let b = compact.as_bytes();
    let assigns = b.iter().enumerate().any(|(i, &c)| {
        let head = b.get(..i).unwrap_or_default();
        let digits = head.iter().rev().take_while(|c| c.is_ascii_digit()).count();
        let before = head.len() - digits;
        let letter = before.checked_sub(1).and_then(|k| head.get(k));
        let alone = before
            .checked_sub(2)
            .and_then(|k| head.get(k))
            .is_none_or(|c| !c.is_ascii_alphabetic());
        c == b'='
            && alone
            && match letter {
                Some(b'R') => digits > 0,
                Some(l) => digits == 0 && b"XYZABCFSIJK".contains(l),
                None => false,
            }
    });
    assigns.then_some(compact)
}

/// A Sinumerik cycle call: `CYCLE` and digits, `POCKET`/`SLOT` and digits, then `(`; `MCALL`.
fn sinumerik_cycle(compact: &str) -> Option<&str> {
    let b = compact.as_bytes();
    for name in ["CYCLE", "POCKET", "SLOT", "LONGHOLE", "HOLES"] {
        let mut from = 0;
        while let Some(k) = compact.get(from..).and_then(|r| r.find(name)) {
            let at = from + k + name.len();
            let digits = b
                .get(at..)
                .unwrap_or_default()
                .iter()
                .take_while(|c| c.is_ascii_digit())
                .count();
            if digits > 0 && b.get(at + digits) == Some(&b'(') {
                return Some(compact);
            }
            from = at;
        }
    }
    compact.starts_with("MCALL").then_some(compact)
}

/// The letter-and-number words of a block (upper case, no spaces); runs of letters
/// (`GOTO`, `CYCLE`) are skipped.
fn words(s: &str) -> Vec<(char, &str)> {
    let b = s.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while let Some(&c) = b.get(i) {
        if !c.is_ascii_uppercase() {
            i += 1;
            continue;
        }
        if b.get(i + 1).is_some_and(u8::is_ascii_uppercase) {
            while b.get(i).is_some_and(u8::is_ascii_uppercase) {
                i += 1;
            }
            continue;
        }
        let start = i + 1;
        let mut j = start;
        while b
            .get(j)
            .is_some_and(|c| c.is_ascii_digit() || matches!(c, b'.' | b'-' | b'+'))
        {
            j += 1;
        }
        out.push((char::from(c), s.get(start..j).unwrap_or("")));
        i = j.max(i + 1);
    }
    out
}

/// A G or M number times ten (`61.1` → 611), when it is one.
fn code_times_ten(num: &str) -> Option<u32> {
    let v: f64 = num.parse().ok()?;
    let c = (v * 10.0).round();
    ((v * 10.0 - c).abs() < 1e-6 && (0.0..1e6).contains(&c)).then_some(c as u32)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn words_and_codes() {
        assert_eq!(
            words("G61.1X-1.5GOTO10M6"),
            vec![('G', "61.1"), ('X', "-1.5"), ('M', "6")]
        );
        assert_eq!(code_times_ten("05.1"), Some(51));
        assert_eq!(code_times_ten("x"), None);
        assert_eq!(macro_b("WHILE[#1LT3]DO1"), Some("WHILE[#1LT3]DO1"));
        assert_eq!(macro_b("ENDWHILE"), None);
        assert_eq!(macro_b("GOTOLABEL"), None);
        assert!(sinumerik_cycle("CYCLE832(0.01,_FINISH,1)").is_some());
        assert!(sinumerik_cycle("CYCLE(").is_none());
        assert!(sinumerik_text("R1=5", "R1=5").is_some());
        assert!(sinumerik_text("G1 X=R1+2", "G1X=R1+2").is_some());
        assert!(sinumerik_text("#1=5", "#1=5").is_none());
    }
}
