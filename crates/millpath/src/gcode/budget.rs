//! The step budget: what keeps a program that never ends from hanging the reader.
//!
//! A real control runs `o100 while [1]`, `N10 GOTO 10` or a main program ending in `M99` for
//! ever; an estimator must answer. Every line the reader runs *again* counts one step:
//!
//! * RS274/NGC (module `oword`): every line read inside an open loop (`while`, `do`,
//!   `repeat`, also the lines skipped by a false condition, a `break` or a `continue`, and
//!   a subroutine defined inside a loop) or inside a called subroutine;
//! * Fanuc (module `fanuc`): every block run in a subprogram or macro, or run again in the
//!   main program after a backward `GOTO`, `END m` or `M99`.
//!
//! Lines read once (a plain program of any length) never count: the budget bounds the work
//! that does not come from the file's size. A loop with an empty body counts its own
//! control lines, so it stops too. Past [`ReaderOptions::step_budget`] steps (default
//! [`DEFAULT_STEP_BUDGET`]) the program is refused as an input error that names the place
//! that kept the program going (the backward jump or call that ran most often, with its line
//! and how often it ran) and the number of steps run. Counting is one increment and one
//! comparison per step; jumps and calls are tallied by site (a few hundred sites at most are
//! kept; later new sites are counted but not named).
//!
//! What one step costs is the reading of one line plus what the line makes: the default is
//! set so that an endless loop whose body moves the tool ends within seconds in a release
//! build, with the planner and the limit verifier behind the reader, while no real program
//! comes near it (LinuxCNC's own programs with loops run at most a few thousand lines
//! again). Recursion is bounded apart, by the call depth (`oword::MAX_CALL_DEPTH`,
//! `fanuc::MAX_SUBPROGRAM_DEPTH`, `fanuc::MAX_MACRO_DEPTH`).
//!
//! [`ReaderOptions::step_budget`]: super::ReaderOptions::step_budget
//! [`DEFAULT_STEP_BUDGET`]: super::DEFAULT_STEP_BUDGET

use std::collections::HashMap;

/// Jump and call sites named at most (further new sites are not tallied).
const MAX_SITES: usize = 256;

/// A place that sends the program back (a loop's end, a `GOTO`, a call).
#[derive(Debug)]
struct Site {
    /// The file, empty for the main program.
    origin: String,
    /// What it is (`o100 endwhile`, `GOTO 10`).
    what: String,
    count: u64,
}

/// Steps run, the limit, and the sites that sent the program back.
#[derive(Debug)]
pub(crate) struct Budget {
    steps: u64,
    limit: u64,
    exhausted: bool,
    /// Kept apart: only jumps and the message use them.
    sites: Box<Sites>,
}

/// The sites tallied, and what a step is.
#[derive(Debug)]
struct Sites {
    /// Sites by line number (lines of different files share a key).
    by_line: HashMap<usize, Vec<Site>>,
    n: usize,
    /// What a step is, for the message (`lines run in loops and subroutines`).
    unit: &'static str,
}

impl Budget {
    pub(crate) fn new(limit: u64, unit: &'static str) -> Self {
        Budget {
            steps: 0,
            limit,
            exhausted: false,
            sites: Box::new(Sites {
                by_line: HashMap::new(),
                n: 0,
                unit,
            }),
        }
    }

    /// Counts one step; past the limit, the refusal (see [`Budget::message`]).
    #[inline]
    pub(crate) fn step(&mut self) -> Result<(), String> {
        self.steps += 1;
        if self.steps > self.limit {
            self.exhausted = true;
            return Err(self.message());
        }
        Ok(())
    }

    /// Whether the last error was the budget's.
    pub(crate) fn exhausted(&self) -> bool {
        self.exhausted
    }

    /// Tallies a backward jump or a call at `line` of `origin` (empty: the main program);
    /// `what` names it (only called for a site not yet tallied).
    pub(crate) fn jump(&mut self, origin: &str, line: usize, what: impl FnOnce() -> String) {
        let sites = &mut *self.sites;
        if let Some(at) = sites.by_line.get_mut(&line)
            && let Some(s) = at.iter_mut().find(|s| s.origin == origin)
        {
            s.count += 1;
            return;
        }
        if sites.n >= MAX_SITES {
            return;
        }
        sites.n += 1;
        sites.by_line.entry(line).or_default().push(Site {
            origin: origin.to_string(),
            what: what(),
            count: 1,
        });
    }

    /// `a loop that never ends? o100 endwhile at line 5 went back 3333333 times
    /// (10000001 lines run in loops and subroutines)`.
    pub(crate) fn message(&self) -> String {
        let top = self
            .sites
            .by_line
            .iter()
            .flat_map(|(line, v)| v.iter().map(move |s| (*line, s)))
            .max_by_key(|(line, s)| (s.count, std::cmp::Reverse(*line)));
        let site = match top {
            Some((line, s)) => {
                let file = if s.origin.is_empty() {
                    String::new()
                } else {
                    format!(" of {}", s.origin)
                };
                format!(" {} at line {line}{file} ran {} times", s.what, s.count)
            }
            None => String::new(),
        };
        format!(
            "a loop that never ends?{site} ({} {} before the step budget ran out)",
            self.steps, self.sites.unit
        )
    }

    /// What the refusal expects.
    pub(crate) fn expected(&self) -> String {
        format!(
            "a program that ends within the step budget of {} {} (--step-budget)",
            self.limit, self.sites.unit
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_the_site_that_ran_most_and_the_steps() {
        let mut b = Budget::new(10, "lines run in loops");
        b.jump("", 4, || "o1 endrepeat".into());
        for _ in 0..3 {
            b.jump("", 9, || "o2 endwhile".into());
        }
        b.jump("sub.ngc", 9, || "o3 endwhile".into());
        for _ in 0..10 {
            assert!(b.step().is_ok());
        }
        assert!(!b.exhausted());
        let e = b.step().unwrap_err();
        assert!(b.exhausted());
        assert!(
            e.contains("o2 endwhile at line 9 ran 3 times") && e.contains("11 lines run in loops"),
            "{e}"
        );
        assert!(b.expected().contains("step budget of 10 lines"));
        // Sites beyond the cap are counted as steps, never stored.
        for l in 0..2 * MAX_SITES {
            b.jump("", 100 + l, || "o9 endwhile".into());
        }
        assert_eq!(b.sites.n, MAX_SITES);
    }
}
