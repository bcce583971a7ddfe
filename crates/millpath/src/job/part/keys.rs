//! Reading a job file's tables key by key, with the line of every value for messages.
//!
//! A job file is TOML. Its tables are read here rather than through a derived deserializer so
//! that every refusal names the key, the table and the line (`part.toml line 12,
//! [[operation]] 2`), and a key that is not one of the table's (a misspelt setting, which
//! would otherwise fall back to its default without a word) is refused with the keys the
//! table takes.

use crate::error::InputError;
use toml::Spanned;
use toml::de::{DeTable, DeValue};

/// One table of a job file: its entries, the file's text (for line numbers) and the name
/// messages give it.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Keys<'a, 'i> {
    table: &'a DeTable<'i>,
    text: &'a str,
    origin: &'a str,
    /// `[stock]`, `[[tool]] 2`, `[[operation]] 3 (pocket)`; empty for the top level.
    name: &'a str,
    /// Line of the table's header (1-based).
    line: usize,
}

/// The 1-based line of byte offset `at` in `text`.
pub(crate) fn line_of(text: &str, at: usize) -> usize {
    text.as_bytes()
        .iter()
        .take(at.min(text.len()))
        .filter(|&&b| b == b'\n')
        .count()
        + 1
}

impl<'a, 'i> Keys<'a, 'i> {
    pub(crate) fn new(
        table: &'a DeTable<'i>,
        text: &'a str,
        origin: &'a str,
        name: &'a str,
        line: usize,
    ) -> Self {
        Keys {
            table,
            text,
            origin,
            name,
            line,
        }
    }

    /// The line of the table's header.
    pub(crate) fn line(&self) -> usize {
        self.line
    }

    /// The file's text (for the keys of a sub-table).
    pub(crate) fn text_ref(&self) -> &'a str {
        self.text
    }

    /// The file's name.
    pub(crate) fn origin_ref(&self) -> &'a str {
        self.origin
    }

    /// Where a value is, for messages: `part.toml line 12, [[operation]] 2 (pocket)`.
    pub(crate) fn at_line(&self, line: usize) -> String {
        if self.name.is_empty() {
            format!("{} line {line}", self.origin)
        } else {
            format!("{} line {line}, {}", self.origin, self.name)
        }
    }

    fn entry(&self, key: &str) -> Option<&'a Spanned<DeValue<'i>>> {
        self.table
            .iter()
            .find(|(k, _)| k.get_ref().as_ref() == key)
            .map(|(_, v)| v)
    }

    /// Whether the table has `key`.
    pub(crate) fn has(&self, key: &str) -> bool {
        self.entry(key).is_some()
    }

    /// The line of `key`'s value (the table's line when it is absent).
    pub(crate) fn line_of(&self, key: &str) -> usize {
        self.entry(key)
            .map_or(self.line, |v| line_of(self.text, v.span().start))
    }

    /// An input error about `key`'s value `shown`, at its line.
    pub(crate) fn error(&self, key: &str, shown: impl std::fmt::Display) -> InputError {
        InputError::new(key, shown).at(self.at_line(self.line_of(key)))
    }

    /// Refuses a key that is not in `allowed`, naming it, its line and the keys the table
    /// takes.
    pub(crate) fn only(&self, allowed: &[&str]) -> Result<(), InputError> {
        let mut unknown: Vec<(usize, String)> = self
            .table
            .iter()
            .filter(|(k, _)| !allowed.contains(&k.get_ref().as_ref()))
            .map(|(k, _)| (line_of(self.text, k.span().start), k.get_ref().to_string()))
            .collect();
        unknown.sort();
        match unknown.first() {
            None => Ok(()),
            Some((line, key)) => Err(InputError::new("unknown key", key)
                .at(self.at_line(*line))
                .expected(format!("one of: {}", allowed.join(", ")))),
        }
    }

    /// A number (integer or float), if given.
    pub(crate) fn f64(&self, key: &str) -> Result<Option<f64>, InputError> {
        let Some(v) = self.entry(key) else {
            return Ok(None);
        };
        number(v.get_ref())
            .map(Some)
            .ok_or_else(|| self.error(key, shown(v.get_ref())).expected("a number"))
    }

    /// A number that must be finite and > 0, if given.
    pub(crate) fn positive(&self, key: &str, unit: &str) -> Result<Option<f64>, InputError> {
        match self.f64(key)? {
            Some(x) if !(x.is_finite() && x > 0.0) => Err(self
                .error(key, x)
                .expected(format!("a finite number > 0 {unit}"))),
            x => Ok(x),
        }
    }

    /// A number that must be finite and >= 0, if given.
    pub(crate) fn non_negative(&self, key: &str, unit: &str) -> Result<Option<f64>, InputError> {
        match self.f64(key)? {
            Some(x) if !(x.is_finite() && x >= 0.0) => Err(self
                .error(key, x)
                .expected(format!("a finite number >= 0 {unit}"))),
            x => Ok(x),
        }
    }

    /// A whole number in `range`, if given.
    pub(crate) fn u32(
        &self,
        key: &str,
        range: std::ops::RangeInclusive<u32>,
    ) -> Result<Option<u32>, InputError> {
        let Some(x) = self.f64(key)? else {
            return Ok(None);
        };
        if x.fract() == 0.0 && x >= f64::from(*range.start()) && x <= f64::from(*range.end()) {
            Ok(Some(x as u32))
        } else {
            Err(self.error(key, x).expected(format!(
                "a whole number from {} to {}",
                range.start(),
                range.end()
            )))
        }
    }

    /// A string, if given.
    pub(crate) fn str(&self, key: &str) -> Result<Option<String>, InputError> {
        let Some(v) = self.entry(key) else {
            return Ok(None);
        };
        match v.get_ref() {
            DeValue::String(s) => Ok(Some(s.to_string())),
            other => Err(self.error(key, shown(other)).expected("a string in quotes")),
        }
    }

    /// A string or a number, as text (`feed = 1500` or `feed = "60ipm"`), if given.
    pub(crate) fn text(&self, key: &str) -> Result<Option<String>, InputError> {
        let Some(v) = self.entry(key) else {
            return Ok(None);
        };
        match v.get_ref() {
            DeValue::String(s) => Ok(Some(s.to_string())),
            DeValue::Integer(i) if i.radix() == 10 => Ok(Some(i.as_str().to_owned())),
            DeValue::Float(f) => Ok(Some(f.as_str().to_owned())),
            other => Err(self
                .error(key, shown(other))
                .expected("a number or a string")),
        }
    }

    /// A boolean, if given.
    pub(crate) fn bool(&self, key: &str) -> Result<Option<bool>, InputError> {
        let Some(v) = self.entry(key) else {
            return Ok(None);
        };
        match v.get_ref() {
            DeValue::Boolean(b) => Ok(Some(*b)),
            other => Err(self.error(key, shown(other)).expected("true or false")),
        }
    }

    /// An array of `n` numbers, if given.
    pub(crate) fn numbers(&self, key: &str, n: usize) -> Result<Option<Vec<f64>>, InputError> {
        let Some(v) = self.entry(key) else {
            return Ok(None);
        };
        let bad = || {
            self.error(key, shown(v.get_ref())).expected(format!(
                "an array of {n} numbers, e.g. [{}]",
                vec!["0"; n].join(", ")
            ))
        };
        let DeValue::Array(a) = v.get_ref() else {
            return Err(bad());
        };
        if a.len() != n {
            return Err(bad());
        }
        a.iter()
            .map(|x| {
                number(x.get_ref())
                    .filter(|x| x.is_finite())
                    .ok_or_else(bad)
            })
            .collect::<Result<Vec<_>, _>>()
            .map(Some)
    }

    /// A fraction of the tool's diameter in (0, 1], if given.
    pub(crate) fn fraction(&self, key: &str) -> Result<Option<f64>, InputError> {
        match self.f64(key)? {
            Some(x) if !(x > 0.0 && x <= 1.0) => Err(self
                .error(key, x)
                .expected("a fraction of the tool's diameter in (0, 1]")),
            x => Ok(x),
        }
    }

    /// A sub-table, if given (`[stock]`).
    pub(crate) fn table(&self, key: &str) -> Result<Option<(&'a DeTable<'i>, usize)>, InputError> {
        let Some(v) = self.entry(key) else {
            return Ok(None);
        };
        match v.get_ref() {
            DeValue::Table(t) => Ok(Some((t, line_of(self.text, v.span().start)))),
            other => Err(self
                .error(key, shown(other))
                .expected(format!("a table [{key}]"))),
        }
    }

    /// An array of tables (`[[tool]]`), each with its line; empty when absent.
    pub(crate) fn tables(&self, key: &str) -> Result<Vec<(&'a DeTable<'i>, usize)>, InputError> {
        let Some(v) = self.entry(key) else {
            return Ok(Vec::new());
        };
        let DeValue::Array(a) = v.get_ref() else {
            return Err(self
                .error(key, shown(v.get_ref()))
                .expected(format!("tables [[{key}]]")));
        };
        a.iter()
            .map(|x| match x.get_ref() {
                DeValue::Table(t) => Ok((t, line_of(self.text, x.span().start))),
                other => Err(self
                    .error(key, shown(other))
                    .expected(format!("tables [[{key}]]"))),
            })
            .collect()
    }
}

/// A TOML number as f64.
fn number(v: &DeValue<'_>) -> Option<f64> {
    match v {
        DeValue::Integer(i) => i64::from_str_radix(i.as_str(), i.radix())
            .ok()
            .map(|x| x as f64),
        DeValue::Float(f) => f.as_str().replace('_', "").parse().ok(),
        _ => None,
    }
}

/// A value as a message shows it.
fn shown(v: &DeValue<'_>) -> String {
    match v {
        DeValue::String(s) => format!("\"{s}\""),
        DeValue::Integer(i) => i.as_str().to_owned(),
        DeValue::Float(f) => f.as_str().to_owned(),
        DeValue::Boolean(b) => b.to_string(),
        DeValue::Datetime(d) => d.to_string(),
        DeValue::Array(_) => "an array".to_owned(),
        DeValue::Table(_) => "a table".to_owned(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn with<T>(text: &str, f: impl FnOnce(Keys<'_, '_>) -> T) -> T {
        let doc = DeTable::parse(text).unwrap();
        f(Keys::new(doc.get_ref(), text, "job.toml", "", 1))
    }

    /// Values of every kind are read with their lines; a wrong kind names the key and line.
    #[test]
    fn values_and_lines() {
        let text =
            "a = 1\nb = 2.5e1\nc = \"x\"\nd = [1, 2.0]\ne = true\nf = \"60ipm\"\ng = 1_500\n";
        with(text, |k| {
            assert_eq!(k.f64("a").unwrap(), Some(1.0));
            assert_eq!(k.f64("b").unwrap(), Some(25.0));
            assert_eq!(k.f64("g").unwrap(), Some(1500.0));
            assert_eq!(k.str("c").unwrap().as_deref(), Some("x"));
            assert_eq!(k.numbers("d", 2).unwrap(), Some(vec![1.0, 2.0]));
            assert_eq!(k.bool("e").unwrap(), Some(true));
            assert_eq!(k.text("f").unwrap().as_deref(), Some("60ipm"));
            assert_eq!(k.text("a").unwrap().as_deref(), Some("1"));
            assert_eq!(k.f64("missing").unwrap(), None);
            let e = k.f64("c").unwrap_err().to_string();
            assert!(e.contains("job.toml line 3") && e.contains("\"x\""), "{e}");
            let e = k.numbers("d", 3).unwrap_err().to_string();
            assert!(e.contains("line 4") && e.contains("3 numbers"), "{e}");
            let e = k
                .only(&["a", "b", "c", "d", "e", "f"])
                .unwrap_err()
                .to_string();
            assert!(
                e.contains("unknown key") && e.contains('g') && e.contains("line 7"),
                "{e}"
            );
            assert!(k.only(&["a", "b", "c", "d", "e", "f", "g"]).is_ok());
            let e = k.u32("b", 0..=10).unwrap_err().to_string();
            assert!(e.contains("whole number from 0 to 10"), "{e}");
        });
    }
}
