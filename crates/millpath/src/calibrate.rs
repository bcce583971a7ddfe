//! Calibration: a machine profile fitted to cycle times measured on the machine.
//!
//! A user runs a few programs on their machine, notes each cycle time (a CSV with the header
//! `program,seconds`, program paths relative to the CSV) and gives a starting profile. The
//! fit keeps the start's controller model, feeds, axis velocities and rapids, and adjusts
//! * the axis accelerations (one factor for all axes: their ratios are kept),
//! * the axis jerks (one factor; only where the start's jerk is finite),
//! * the path tolerance (what `G64` / `G642` without a tolerance blends within),
//! * the interpolation cycle (the `linuxcnc` model's servo period: the per-cycle speed cap
//!   `L/T` of short segments; the other models' curvature-step and exact-path cycle),
//!
//! to minimise the mean squared relative error `((t_model − t_measured)/t_measured)²` over
//! the programs: a coordinate-wise grid search in `(ln k_a, ln k_j, ε, ln T)` (factors
//! `2^(−2 … 2)` in quarter octaves, then finer grids around the best point; tolerances 0 and
//! ¼ … 4 times the start's), then Nelder–Mead from the best point (300 evaluations at most).
//! A fitted tolerance that times every program as 0 does is reported as 0.
//!
//! # What can be fitted
//! A parameter no program's time depends on (within 1e-4 relative when it is changed by
//! 20 %, or the tolerance between its fitted value and 0 and twice that) is not fitted: it
//! keeps the start's value and the result says so ([`ParamFit::Kept`]). Programs that run
//! at their programmed feed most of the time (long moves) fix little; short segments fix the
//! interpolation cycle, exact stops and short moves the acceleration (and the jerk), `G64`
//! without a tolerance the tolerance.

use crate::error::{Error, InputError};
use crate::gcode::{ReaderOptions, read_str};
use crate::geom::Point3;
use crate::machine::{Controller, Machine};
use crate::motion::{PlanOptions, plan_moves};
use crate::toolpath::Move;
use std::path::{Path, PathBuf};

/// One program with its measured cycle time.
#[derive(Debug, Clone)]
pub struct Measured {
    /// The program's path as the CSV gives it.
    pub name: String,
    /// Its moves (as read for the start's controller).
    pub moves: Vec<(Point3, Move)>,
    /// The measured cycle time in s.
    pub seconds: f64,
}

/// Options of [`calibrate`]. Built from [`Default`] with the `with_*` methods (the struct is
/// `#[non_exhaustive]`: new settings do not break callers).
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct CalibrateOptions {
    /// Objective evaluations per Nelder–Mead run.
    pub max_evaluations: usize,
}

impl Default for CalibrateOptions {
    fn default() -> Self {
        CalibrateOptions {
            max_evaluations: 300,
        }
    }
}

option_builders! {
    CalibrateOptions;
    /// Sets [`CalibrateOptions::max_evaluations`].
    with_max_evaluations => max_evaluations: usize;
}

/// What became of one parameter.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
#[serde(rename_all = "snake_case", tag = "outcome")]
pub enum ParamFit {
    /// Fitted to this value.
    Fitted {
        /// The value (mm/s², mm/s³, mm or s; the smallest axis value for a per-axis limit).
        value: f64,
    },
    /// Kept at the start's value: no program's time depends on it.
    Kept {
        /// The start's value.
        value: f64,
    },
    /// Not a parameter of the start profile (unlimited jerk).
    NotApplicable,
}

/// One program's residual.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Residual {
    /// The program as the CSV names it.
    pub program: String,
    /// Measured time, s.
    pub measured: f64,
    /// Time with the fitted profile, s.
    pub fitted: f64,
}

impl Residual {
    /// Relative error of the fitted time.
    pub fn error(&self) -> f64 {
        (self.fitted - self.measured) / self.measured
    }
}

/// The result of [`calibrate`].
#[derive(Debug, Clone, PartialEq)]
pub struct Calibration {
    /// The fitted machine.
    pub machine: Machine,
    /// Axis acceleration.
    pub acceleration: ParamFit,
    /// Axis jerk.
    pub jerk: ParamFit,
    /// Path tolerance.
    pub tolerance: ParamFit,
    /// Interpolation cycle.
    pub ipo_cycle: ParamFit,
    /// Per program, in the CSV's order.
    pub residuals: Vec<Residual>,
    /// Objective evaluations made.
    pub evaluations: usize,
}

/// Reads a `program,seconds` CSV (`origin` names it in errors): the programs' paths (as
/// written) and times.
pub fn read_times(text: &str, origin: &str) -> Result<Vec<(String, f64)>, InputError> {
    let mut lines = text
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty());
    match lines.next() {
        Some((_, h)) if h.trim().eq_ignore_ascii_case("program,seconds") => {}
        other => {
            return Err(InputError::new(
                "times CSV header",
                other.map_or("(empty file)", |(_, l)| l.trim()),
            )
            .at(origin)
            .expected("the header `program,seconds`"));
        }
    }
    let mut out = Vec::new();
    for (i, line) in lines {
        let at = format!("{origin}:{}", i + 1);
        let Some((p, s)) = line.split_once(',') else {
            return Err(InputError::new("times CSV line", line.trim())
                .at(at)
                .expected("program,seconds"));
        };
        let secs: f64 = s.trim().parse().map_err(|_| {
            InputError::new("cycle time", s.trim())
                .at(at.clone())
                .expected("a number of seconds")
        })?;
        if !(secs.is_finite() && secs > 0.0) {
            return Err(InputError::new("cycle time", secs)
                .at(at)
                .expected("a finite time > 0 s"));
        }
        out.push((p.trim().to_string(), secs));
    }
    if out.is_empty() {
        return Err(InputError::new("times CSV", "no programs")
            .at(origin)
            .expected("at least one line `program,seconds`"));
    }
    Ok(out)
}

/// Reads the CSV at `csv` and every program it names (relative to its folder), the way the
/// planner reads them for `machine`'s controller.
pub fn load(csv: &Path, machine: &Machine) -> Result<Vec<Measured>, Error> {
    let origin = csv.display().to_string();
    let text = std::fs::read_to_string(csv).map_err(|e| {
        InputError::new("times CSV", &origin).expected(format!("a readable CSV file ({e})"))
    })?;
    let base = csv.parent().map_or_else(PathBuf::new, Path::to_path_buf);
    let mut out = Vec::new();
    for (name, seconds) in read_times(&text, &origin)? {
        let path = base.join(&name);
        let program = std::fs::read_to_string(&path).map_err(|e| {
            InputError::new("program", path.display())
                .at(&origin)
                .expected(format!("a readable G-code file, relative to the CSV ({e})"))
        })?;
        let opts = ReaderOptions::default()
            .with_origin(path.display().to_string())
            .with_sync_points(
                (machine.controller == Controller::LinuxCnc).then_some(machine.sync_wait),
            );
        let (tp, _) = read_str(&program, opts)?;
        out.push(Measured {
            name,
            moves: tp.segments().map(|(f, m)| (f, *m)).collect(),
            seconds,
        });
    }
    Ok(out)
}

/// The machine of parameters `x = (ln k_a, ln k_j, ε, ln T)` relative to `start`.
fn machine_at(start: &Machine, x: &[f64; 4]) -> Machine {
    let mut m = start.clone();
    let (ka, kj) = (x[0].exp(), x[1].exp());
    for a in &mut m.axes {
        a.max_acceleration *= ka;
        if a.max_jerk.is_finite() {
            a.max_jerk *= kj;
        }
    }
    m.path_tolerance = x[2].max(0.0);
    m.ipo_cycle = x[3].exp();
    m
}

/// The planned cycle times of `programs` on `m` (`None` if a limit left the valid range).
fn times(m: &Machine, programs: &[Measured]) -> Result<Option<Vec<f64>>, Error> {
    if m.validate(&m.name).is_err() {
        return Ok(None);
    }
    let opts = PlanOptions::default()
        .with_keep_geometry(false)
        .with_check_profiles(false);
    let mut out = Vec::with_capacity(programs.len());
    for p in programs {
        match plan_moves(p.moves.iter().map(|x| Ok(*x)), m, &opts) {
            Ok(plan) => out.push(plan.total_time()),
            Err(Error::Input(_)) => return Ok(None),
            Err(e) => return Err(e),
        }
    }
    Ok(Some(out))
}

fn objective(start: &Machine, programs: &[Measured], x: &[f64; 4]) -> Result<f64, Error> {
    Ok(match times(&machine_at(start, x), programs)? {
        None => f64::INFINITY,
        Some(t) => {
            t.iter()
                .zip(programs)
                .map(|(t, p)| ((t - p.seconds) / p.seconds).powi(2))
                .sum::<f64>()
                / programs.len() as f64
        }
    })
}

/// Nelder–Mead on `f` from `x0` with initial steps `step` (0: the coordinate is fixed).
fn nelder_mead(
    f: &mut dyn FnMut(&[f64; 4]) -> Result<f64, Error>,
    x0: [f64; 4],
    step: [f64; 4],
    max_evals: usize,
) -> Result<([f64; 4], f64, usize), Error> {
    let free: Vec<usize> = (0..4).filter(|&i| step[i] != 0.0).collect();
    let mut evals = 0;
    let mut eval = |x: &[f64; 4], evals: &mut usize| {
        *evals += 1;
        f(x)
    };
    let mut pts = vec![x0];
    for &i in &free {
        let mut x = x0;
        x[i] += step[i];
        pts.push(x);
    }
    let mut vals = Vec::with_capacity(pts.len());
    for p in &pts {
        vals.push(eval(p, &mut evals)?);
    }
    let n = free.len();
    if n == 0 {
        return Ok((x0, vals[0], evals));
    }
    while evals < max_evals {
        let mut order: Vec<usize> = (0..=n).collect();
        order.sort_by(|&a, &b| vals[a].total_cmp(&vals[b]));
        pts = order.iter().map(|&i| pts[i]).collect();
        vals = order.iter().map(|&i| vals[i]).collect();
        if (vals[n] - vals[0]).abs() <= 1e-12 * (1.0 + vals[0].abs()) {
            break;
        }
        let mut c = [0.0; 4];
        for p in &pts[..n] {
            for i in 0..4 {
                c[i] += p[i] / n as f64;
            }
        }
        let along = |t: f64| {
            let mut x = [0.0; 4];
            for i in 0..4 {
                x[i] = c[i] + t * (c[i] - pts[n][i]);
            }
            x
        };
        let xr = along(1.0);
        let fr = eval(&xr, &mut evals)?;
        if fr < vals[0] {
            let xe = along(2.0);
            let fe = eval(&xe, &mut evals)?;
            (pts[n], vals[n]) = if fe < fr { (xe, fe) } else { (xr, fr) };
        } else if fr < vals[n - 1] {
            (pts[n], vals[n]) = (xr, fr);
        } else {
            let xc = along(-0.5);
            let fc = eval(&xc, &mut evals)?;
            if fc < vals[n] {
                (pts[n], vals[n]) = (xc, fc);
            } else {
                let best = pts[0];
                for k in 1..=n {
                    for (x, b) in pts[k].iter_mut().zip(best) {
                        *x = b + 0.5 * (*x - b);
                    }
                    vals[k] = eval(&pts[k], &mut evals)?;
                }
            }
        }
    }
    let best = (0..=n)
        .min_by(|&a, &b| vals[a].total_cmp(&vals[b]))
        .unwrap_or(0);
    Ok((pts[best], vals[best], evals))
}

/// Fits `start`'s acceleration, jerk, tolerance and interpolation cycle to `programs` (see
/// the module docs).
pub fn calibrate(
    start: &Machine,
    programs: &[Measured],
    opts: &CalibrateOptions,
) -> Result<Calibration, Error> {
    start.validate(&start.name)?;
    if programs.is_empty() {
        return Err(InputError::new("measured programs", 0)
            .expected("at least one program with its time")
            .into());
    }
    let base = times(start, programs)?.ok_or_else(|| {
        Error::Input(
            InputError::new("start machine", &start.name)
                .expected("a profile that plans every program"),
        )
    })?;
    let jerk_finite = start.axes.iter().all(|a| a.max_jerk.is_finite());
    let x0 = [0.0, 0.0, start.path_tolerance, start.ipo_cycle.ln()];
    // Which parameters the programs' times depend on.
    let depends = |x: &[f64; 4]| -> Result<bool, Error> {
        let t = times(&machine_at(start, x), programs)?;
        Ok(t.is_none_or(|t| t.iter().zip(&base).any(|(a, b)| (a - b).abs() > 1e-4 * b)))
    };
    let probe = |i: usize, v: f64| {
        let mut x = x0;
        x[i] = v;
        x
    };
    let tol_probe = if start.path_tolerance > 0.0 {
        2.0 * start.path_tolerance
    } else {
        0.01
    };
    let fit = [
        depends(&probe(0, 0.2f64.ln_1p()))?,
        jerk_finite && depends(&probe(1, 0.2f64.ln_1p()))?,
        depends(&probe(2, tol_probe))? || depends(&probe(2, 0.0))?,
        depends(&probe(3, x0[3] + 0.2f64.ln_1p()))?,
    ];
    let step = [
        if fit[0] { 0.3 } else { 0.0 },
        if fit[1] { 0.3 } else { 0.0 },
        if fit[2] { tol_probe } else { 0.0 },
        if fit[3] { 0.3 } else { 0.0 },
    ];
    let mut f = |x: &[f64; 4]| objective(start, programs, x);
    let mut evaluations = 0;
    // The objective is piecewise smooth at best (a controller's choices between blend, stop
    // and tangent change with the limits): a coordinate-wise grid search first over factors
    // of the acceleration, jerk and cycle (after a joint grid over ±2 octaves): ±½ octave in
    // eighths, then ±¼ in sixteenths, then ±⅛ in thirty-seconds, each around the best point
    // so far; then Nelder–Mead from the best point.
    let rounds = [(4, 0.125), (4, 0.0625), (4, 0.03125)];
    let tolerances: Vec<f64> = if start.path_tolerance > 0.0 {
        [0.0, 0.25, 0.5, 1.0, 2.0, 4.0]
            .iter()
            .map(|k| k * start.path_tolerance)
            .collect()
    } else {
        vec![0.0, 0.001, 0.003, 0.01, 0.03, 0.1]
    };
    // The tolerance interacts with the acceleration (which corners blend how), so the
    // search runs once from each tolerance candidate, the tolerance held, and keeps the best.
    let mut best: Option<([f64; 4], f64)> = None;
    let starts = if fit[2] {
        tolerances.clone()
    } else {
        vec![x0[2]]
    };
    // The continuous parameters that are fitted, and a first grid over all of them at once
    // (9 points each over ±2 octaves; 5 with three of them).
    let dims: Vec<usize> = [0, 1, 3].into_iter().filter(|&i| fit[i]).collect();
    let per: usize = if dims.len() >= 3 { 5 } else { 9 };
    let offset = |k: usize| (k as f64 / (per - 1) as f64 * 4.0 - 2.0) * std::f64::consts::LN_2;
    for t in starts {
        let mut x = x0;
        x[2] = t;
        let mut fx = f(&x)?;
        evaluations += 1;
        let cells = per.pow(u32::try_from(dims.len()).unwrap_or(0));
        let x_start = x;
        for cell in 0..cells {
            let mut y = x_start;
            let mut c = cell;
            for &i in &dims {
                y[i] = x_start[i] + offset(c % per);
                c /= per;
            }
            let fy = f(&y)?;
            evaluations += 1;
            if fy < fx {
                (x, fx) = (y, fy);
            }
        }
        for (half, octave) in rounds {
            for (i, free) in fit.iter().enumerate() {
                if !free || i == 2 {
                    continue;
                }
                for k in -half..=half {
                    let mut y = x;
                    y[i] = x[i] + f64::from(k) * octave * std::f64::consts::LN_2;
                    let fy = f(&y)?;
                    evaluations += 1;
                    if fy < fx {
                        (x, fx) = (y, fy);
                    }
                }
            }
        }
        if best.is_none_or(|(_, fb)| fx < fb) {
            best = Some((x, fx));
        }
    }
    let x = best.map_or(x0, |(x, _)| x);
    let step = step.map(|s| 0.1 * s);
    let (mut x, fx, n) = nelder_mead(&mut f, x, step, opts.max_evaluations)?;
    evaluations += n;
    // A tolerance that times every program as 0 does is 0 (beyond what the programs'
    // segments allow, any tolerance blends alike).
    if fit[2] && x[2] > 0.0 {
        let mut y = x;
        y[2] = 0.0;
        evaluations += 1;
        if f(&y)? <= fx * (1.0 + 1e-9) {
            x = y;
        }
    }
    let machine = machine_at(start, &x);
    let fitted = times(&machine, programs)?
        .ok_or_else(|| Error::internal("calibration: the fitted machine plans no program"))?;
    let amin = |m: &Machine, f: fn(&crate::machine::AxisLimits) -> f64| {
        m.axes.iter().map(f).fold(f64::INFINITY, f64::min)
    };
    let outcome = |fitted: bool, v_fit: f64, v_start: f64| {
        if fitted {
            ParamFit::Fitted { value: v_fit }
        } else {
            ParamFit::Kept { value: v_start }
        }
    };
    Ok(Calibration {
        acceleration: outcome(
            fit[0],
            amin(&machine, |a| a.max_acceleration),
            amin(start, |a| a.max_acceleration),
        ),
        jerk: if jerk_finite {
            outcome(
                fit[1],
                amin(&machine, |a| a.max_jerk),
                amin(start, |a| a.max_jerk),
            )
        } else {
            ParamFit::NotApplicable
        },
        tolerance: outcome(fit[2], machine.path_tolerance, start.path_tolerance),
        ipo_cycle: outcome(fit[3], machine.ipo_cycle, start.ipo_cycle),
        residuals: programs
            .iter()
            .zip(fitted)
            .map(|(p, t)| Residual {
                program: p.name.clone(),
                measured: p.seconds,
                fitted: t,
            })
            .collect(),
        machine,
        evaluations,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A times CSV must have its header, a number of seconds > 0 on each line, and a line at
    /// least; errors name the line.
    #[test]
    fn times_csv_errors_name_the_line() {
        let ok = read_times("program,seconds\na.ngc, 1.5\n\nb/c.ngc,2\n", "t.csv").unwrap();
        assert_eq!(ok, vec![("a.ngc".into(), 1.5), ("b/c.ngc".into(), 2.0)]);
        for (text, needle) in [
            ("a.ngc,1.5\n", "header"),
            ("program,seconds\n", "no programs"),
            ("program,seconds\na.ngc,fast\n", "t.csv:2"),
            ("program,seconds\na.ngc,-1\n", "t.csv:2"),
            ("program,seconds\na.ngc\n", "t.csv:2"),
        ] {
            let e = read_times(text, "t.csv").unwrap_err().to_string();
            assert!(e.contains(needle) && e.contains("t.csv"), "{text:?}: {e}");
        }
    }
}
