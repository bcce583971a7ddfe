//! The two error families.
//!
//! * [`InputError`]: the user's input is wrong. It names the value, where it came from (file
//!   and line, vertex index, command-line flag) and what would be accepted. The CLI exits with 2.
//! * [`InternalError`]: an invariant of the engine broke. This is a bug to report; the CLI exits
//!   with 1.
//!
//! Neither is ever shown as a panic.

use std::fmt;

/// Result alias used across the engine.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// Any error the engine can return.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Error {
    /// The user's input is wrong.
    #[error(transparent)]
    Input(#[from] InputError),
    /// A bug in millpath.
    #[error(transparent)]
    Internal(#[from] InternalError),
}

impl Error {
    /// The process exit code the CLI uses for this error: 2 for bad input, 1 for internal errors.
    pub fn exit_code(&self) -> i32 {
        match self {
            Error::Input(_) => 2,
            Error::Internal(_) => 1,
        }
    }

    /// Shorthand for an internal error.
    pub fn internal(message: impl Into<String>) -> Self {
        Error::Internal(InternalError::new(message))
    }

    /// This error as an internal one when it is an input error: for a value the engine made
    /// itself (a toolpath a strategy planned, given to the motion planner or the G-code
    /// writer), whose refusal is a bug, never the user's input to fix. `doing` says what was
    /// done with it ("timing the pocket toolpath"); the input error's text follows.
    #[must_use]
    pub fn engine_made(self, doing: &str) -> Self {
        match self {
            Error::Input(e) => Error::internal(format!(
                "{doing}: a value millpath made itself was refused: {e}"
            )),
            e @ Error::Internal(_) => e,
        }
    }
}

/// The user's input is wrong.
///
/// Build one with [`InputError::new`] and refine it with [`InputError::at`] and
/// [`InputError::expected`]:
///
/// ```
/// use millpath::InputError;
/// let e = InputError::new("tolerance", -1.0)
///     .at("--tolerance")
///     .expected("a finite number > 0 mm");
/// assert_eq!(
///     e.to_string(),
///     "invalid tolerance = -1 (from --tolerance): expected a finite number > 0 mm"
/// );
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct InputError {
    /// What the value is (`"tolerance"`, `"point"`, `"G-code word"`).
    pub what: String,
    /// The offending value as the user wrote it, or as it was read.
    pub value: String,
    /// Where it came from: a flag, `file:line`, a vertex index.
    pub origin: Option<String>,
    /// What would be accepted, or why the value is wrong.
    pub expected: Option<String>,
}

impl InputError {
    /// A new input error about `what`, whose value was `value`.
    ///
    /// Numbers that `f64`'s `Display` wrote out in full (1e300 is 301 digits, 1e-300 is 302
    /// characters) are shown in exponent form, here and in [`InputError::expected`]:
    ///
    /// ```
    /// use millpath::InputError;
    /// let e = InputError::new("point", format!("({}, {})", 1e300, -1e-300));
    /// assert_eq!(e.value, "(1e300, -1e-300)");
    /// ```
    pub fn new(what: impl Into<String>, value: impl fmt::Display) -> Self {
        InputError {
            what: what.into(),
            value: compact_numbers(&value.to_string()),
            origin: None,
            expected: None,
        }
    }

    /// Where the value came from (a flag, `file:line`, `vertex 12`).
    #[must_use]
    pub fn at(mut self, origin: impl Into<String>) -> Self {
        self.origin = Some(origin.into());
        self
    }

    /// What would be accepted (or a short explanation of what is wrong).
    #[must_use]
    pub fn expected(mut self, expected: impl Into<String>) -> Self {
        self.expected = Some(compact_numbers(&expected.into()));
        self
    }
}

/// Longest number `f64`'s `Display` writes that is still shown as written (20 characters:
/// 1e19 has 20 digits, 1e-18 is `0.000000000000000001`).
const LONGEST_PLAIN_NUMBER: usize = 20;

/// Rewrites every run of digits and points longer than [`LONGEST_PLAIN_NUMBER`] that is
/// exactly how `f64`'s `Display` writes some value into exponent form (`1e300`). Any other
/// run (a 24-digit line number as the user wrote it) is kept as it is.
fn compact_numbers(s: &str) -> String {
    let mut out = String::with_capacity(s.len().min(256));
    let mut rest = s;
    while let Some(start) = rest.find(|c: char| c.is_ascii_digit() || c == '.') {
        out.push_str(&rest[..start]);
        let run = &rest[start..];
        let len = run
            .find(|c: char| !(c.is_ascii_digit() || c == '.'))
            .unwrap_or(run.len());
        let (number, tail) = run.split_at(len);
        match number.parse::<f64>() {
            Ok(v) if len > LONGEST_PLAIN_NUMBER && v.to_string() == number => {
                out.push_str(&format!("{v:e}"));
            }
            _ => out.push_str(number),
        }
        rest = tail;
    }
    out.push_str(rest);
    out
}

impl fmt::Display for InputError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "invalid {} = {}", self.what, self.value)?;
        if let Some(origin) = &self.origin {
            write!(f, " (from {origin})")?;
        }
        if let Some(expected) = &self.expected {
            write!(f, ": expected {expected}")?;
        }
        Ok(())
    }
}

impl std::error::Error for InputError {}

/// An invariant of the engine broke: a bug to report.
#[derive(Debug, Clone, PartialEq)]
pub struct InternalError {
    /// What broke.
    pub message: String,
}

impl InternalError {
    /// A new internal error.
    pub fn new(message: impl Into<String>) -> Self {
        InternalError {
            message: message.into(),
        }
    }
}

impl fmt::Display for InternalError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "internal error (a bug in millpath, please report it): {}",
            self.message
        )
    }
}

impl std::error::Error for InternalError {}

/// Checks that `value` is finite and strictly positive; otherwise an [`InputError`] naming it.
pub fn require_positive(what: &str, value: f64, origin: &str) -> Result<f64, InputError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(InputError::new(what, value)
            .at(origin)
            .expected("a finite number > 0"))
    }
}

/// Checks that `value` is finite; otherwise an [`InputError`] naming it.
pub fn require_finite(what: &str, value: f64, origin: &str) -> Result<f64, InputError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(InputError::new(what, value)
            .at(origin)
            .expected("a finite number"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exit_codes_separate_the_families() {
        assert_eq!(Error::from(InputError::new("x", 1)).exit_code(), 2);
        assert_eq!(Error::internal("broken").exit_code(), 1);
    }

    #[test]
    fn engine_made_values_refused_are_internal_errors() {
        let e = Error::from(InputError::new("arc centre", "(0, 1e7)").at("move 3"))
            .engine_made("timing the pocket toolpath");
        assert_eq!(e.exit_code(), 1);
        let text = e.to_string();
        assert!(text.contains("timing the pocket toolpath") && text.contains("arc centre"));
        assert!(text.contains("move 3") && text.contains("a bug"), "{text}");
        let i = Error::internal("broken");
        assert_eq!(i.clone().engine_made("x"), i);
    }

    #[test]
    fn long_display_numbers_are_shown_in_exponent_form() {
        let e = InputError::new("feed", 1e300)
            .at("--feed")
            .expected(format!("at most {}", 1e21));
        assert_eq!(
            e.to_string(),
            "invalid feed = 1e300 (from --feed): expected at most 1e21"
        );
        assert_eq!(InputError::new("x", 1e-300).value, "1e-300");
        assert_eq!(InputError::new("x", -2.5e40).value, "-2.5e40");
        // Short numbers, and long digit runs that no f64 displays as, stay as written.
        assert_eq!(InputError::new("x", 1e19).value, "10000000000000000000");
        assert_eq!(InputError::new("x", 0.001).value, "0.001");
        let line = "N123456789012345678901234 G1";
        assert_eq!(InputError::new("word", line).value, line);
        assert_eq!(InputError::new("x", "1..2 .").value, "1..2 .");
        assert_eq!(InputError::new("x", "").value, "");
    }

    #[test]
    fn require_positive_rejects_nan_zero_negative() {
        assert!(require_positive("feed", f64::NAN, "--feed").is_err());
        assert!(require_positive("feed", 0.0, "--feed").is_err());
        assert!(require_positive("feed", -1.0, "--feed").is_err());
        assert_eq!(require_positive("feed", 2.0, "--feed"), Ok(2.0));
        let msg = require_positive("feed", -1.0, "--feed")
            .unwrap_err()
            .to_string();
        assert!(msg.contains("feed = -1") && msg.contains("--feed"), "{msg}");
    }
}
