//! RS274/NGC parameters, as LinuxCNC 2.9 keeps them: numbered `#1..#5601`, named local
//! `#<x>` (one scope per subroutine call) and named global `#<_x>`.
//!
//! * Numbered parameters start at 0. `#1..#30` are a subroutine's arguments: a call saves the
//!   caller's and sets its own, the return restores them. `#31..#5000` are global.
//!   `#5001..#5601` hold the machine's state (work offsets `#5221..#5390`, G92 `#5211..#5219`,
//!   the coordinate system `#5220`, …); the reader keeps those it uses in step with the
//!   program (see `interp`), in mm.
//! * The persistent range is read from a LinuxCNC `.var` file when one is given
//!   ([`ParamFile`]: lines `number value`, anything else a comment); every number it holds
//!   is set before the program starts, so that `G55` finds the offsets the machine had.
//! * A named parameter must be set before it is read (LinuxCNC: "Named parameter not
//!   defined"); names are lower case without spaces. Names starting with `_` are global,
//!   others local to the subroutine call (the main program is call level 0).
//! * Setting a parameter takes effect after the whole line has been read (`#1=1 #2=#1`
//!   sets #2 to the old #1); the line parser collects the settings and applies them after.

use crate::error::InputError;
use std::collections::HashMap;

/// Highest parameter number (LinuxCNC's `RS274NGC_MAX_PARAMETERS` − 1).
pub const MAX_PARAM: u16 = 5601;

/// Number of subroutine arguments (`#1..#30`).
pub const ARGS: usize = 30;

/// Values of numbered parameters read from a LinuxCNC `.var` file.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ParamFile {
    values: Vec<(u16, f64)>,
}

impl ParamFile {
    /// Parses a `.var` file: `number value` a line (LinuxCNC's `restore_parameters`); lines
    /// that do not start with a number are comments.
    pub fn parse(text: &str, origin: &str) -> Result<Self, InputError> {
        let mut values = Vec::new();
        for (i, line) in text.lines().enumerate() {
            let mut it = line.split_whitespace();
            let Some(n) = it.next().and_then(|n| n.parse::<u32>().ok()) else {
                continue;
            };
            let at = || format!("{origin}:{}", i + 1);
            if !(1..=u32::from(MAX_PARAM)).contains(&n) {
                return Err(InputError::new("parameter number", n)
                    .at(at())
                    .expected(format!("1 to {MAX_PARAM}")));
            }
            let v = it
                .next()
                .and_then(|v| v.parse::<f64>().ok())
                .filter(|v| v.is_finite())
                .ok_or_else(|| {
                    InputError::new("parameter line", line.trim())
                        .at(at())
                        .expected("a parameter number and a finite value")
                })?;
            values.push((n as u16, v));
        }
        Ok(ParamFile { values })
    }

    /// Reads a `.var` file.
    pub fn read(path: &std::path::Path) -> Result<Self, InputError> {
        let text = std::fs::read_to_string(path).map_err(|e| {
            InputError::new("parameter file", path.display())
                .expected(format!("a readable LinuxCNC .var file ({e})"))
        })?;
        Self::parse(&text, &path.display().to_string())
    }

    /// The values, in file order.
    pub fn values(&self) -> &[(u16, f64)] {
        &self.values
    }
}

/// The parameter store.
#[derive(Debug, Clone)]
pub(crate) struct Store {
    numbered: Vec<f64>,
    globals: HashMap<String, f64>,
    /// Local scopes; the last is the current call's.
    locals: Vec<HashMap<String, f64>>,
    /// The callers' `#1..#30`, saved by each call.
    saved_args: Vec<[f64; ARGS]>,
}

impl Store {
    pub(crate) fn new(file: Option<&ParamFile>) -> Self {
        let mut numbered = vec![0.0; usize::from(MAX_PARAM) + 1];
        if let Some(f) = file {
            for &(n, v) in &f.values {
                if let Some(x) = numbered.get_mut(usize::from(n)) {
                    *x = v;
                }
            }
        }
        Store {
            numbered,
            globals: HashMap::new(),
            locals: vec![HashMap::new()],
            saved_args: Vec::new(),
        }
    }

    pub(crate) fn get(&self, n: usize) -> f64 {
        self.numbered.get(n).copied().unwrap_or(0.0)
    }

    pub(crate) fn set(&mut self, n: usize, v: f64) {
        if let Some(x) = self.numbered.get_mut(n) {
            *x = v;
        }
    }

    /// A user-set named parameter (`None` when never set).
    pub(crate) fn named(&self, name: &str) -> Option<f64> {
        if name.starts_with('_') {
            self.globals.get(name).copied()
        } else {
            self.locals.last().and_then(|l| l.get(name)).copied()
        }
    }

    pub(crate) fn set_named(&mut self, name: &str, v: f64) {
        if name.starts_with('_') {
            self.globals.insert(name.to_string(), v);
        } else if let Some(l) = self.locals.last_mut() {
            l.insert(name.to_string(), v);
        }
    }

    /// Enters a subroutine: saves `#1..#30`, sets them to `args` (the rest 0), opens a local
    /// scope.
    pub(crate) fn call(&mut self, args: &[f64]) {
        let mut saved = [0.0; ARGS];
        for (k, s) in saved.iter_mut().enumerate() {
            *s = self.get(k + 1);
            self.set(k + 1, args.get(k).copied().unwrap_or(0.0));
        }
        self.saved_args.push(saved);
        self.locals.push(HashMap::new());
    }

    /// Leaves a subroutine: restores the caller's `#1..#30` and scope.
    pub(crate) fn ret(&mut self) {
        if let Some(saved) = self.saved_args.pop() {
            for (k, s) in saved.iter().enumerate() {
                self.set(k + 1, *s);
            }
        }
        if self.locals.len() > 1 {
            self.locals.pop();
        }
    }

    /// The call level (0 in the main program).
    pub(crate) fn call_level(&self) -> usize {
        self.saved_args.len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn calls_scope_arguments_and_locals() {
        let mut s = Store::new(None);
        s.set(1, 5.0);
        s.set(31, 7.0);
        s.set_named("a", 1.0);
        s.set_named("_g", 2.0);
        s.call(&[9.0]);
        assert_eq!(s.call_level(), 1);
        assert!((s.get(1) - 9.0).abs() < 1e-12 && s.get(2).abs() < 1e-12);
        assert!(s.named("a").is_none(), "a caller's local is not visible");
        assert!(s.named("_g").is_some());
        s.set_named("a", 3.0);
        s.set(31, 8.0);
        s.ret();
        assert!((s.get(1) - 5.0).abs() < 1e-12);
        assert!((s.get(31) - 8.0).abs() < 1e-12, "#31 is global");
        assert!((s.named("a").unwrap_or(0.0) - 1.0).abs() < 1e-12);
    }

    #[test]
    fn reads_var_files() {
        let f = ParamFile::parse("5161 1.5\n5220\t2.000000\n# note\n", "x.var").unwrap();
        assert_eq!(f.values().len(), 2);
        let s = Store::new(Some(&f));
        assert!((s.get(5220) - 2.0).abs() < 1e-12);
        assert!(ParamFile::parse("9999 1", "x.var").is_err());
        let e = ParamFile::parse("5161 abc", "x.var").unwrap_err();
        assert!(e.to_string().contains("x.var:1"), "{e}");
    }
}
