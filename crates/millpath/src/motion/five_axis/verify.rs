//! The verifier: an independent check of a planned five-axis trajectory.
//!
//! It shares no code with the optimiser's check ([`super::min_time::check`]): it reads only the
//! polynomial coefficients and durations, evaluates them with its own formulas, and
//! * samples every interval densely (`samples` points) for joint velocity, acceleration and
//!   jerk, and for the feed, computed by **central finite differences of the forward
//!   kinematics** (not the Jacobian), step `h = 1e-5·T`: the truncation error is
//!   `h²/6·|tip'''|`, below 1e-9 relative for these paths;
//! * adds the analytic extrema: the roots of the acceleration cubic by **Cardano's formula**
//!   (the optimiser isolates them by bisection instead), the vertex of the jerk parabola and
//!   the ends;
//! * checks position, velocity and acceleration continuity between consecutive intervals.
//!
//! A value counts as a violation when it exceeds its limit by more than a relative 1e-9
//! (motors, exact) or 1e-7 (feed, finite differences).

use super::min_time::{Limits, Segment};
use crate::machine::kinematics::Kinematics;
use serde::{Deserialize, Serialize};

/// One limit exceeded.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Violation {
    /// Interval index.
    pub interval: usize,
    /// `feed`, `velocity`, `acceleration`, `jerk` or `continuity`.
    pub quantity: String,
    /// Joint name, if any.
    pub axis: Option<String>,
    /// Time within the interval, s.
    pub t: f64,
    /// Value found.
    pub value: f64,
    /// Limit.
    pub limit: f64,
}

/// What the verifier found.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct VerifyReport {
    /// Every limit exceeded (empty when the plan is valid).
    pub violations: Vec<Violation>,
    /// Smallest `1 − value/limit` over all constraints and intervals.
    pub tightest_margin: f64,
    /// Which constraint that is.
    pub tightest: String,
    /// Largest feed found, mm/s.
    pub max_feed: f64,
    /// Largest jump of position, velocity or acceleration between intervals.
    pub continuity_error: f64,
}

fn horner(c: &[f64], t: f64) -> f64 {
    let mut acc = 0.0;
    for &x in c.iter().rev() {
        acc = acc * t + x;
    }
    acc
}

fn derivs(c: &[f64; 6]) -> ([f64; 5], [f64; 4], [f64; 3]) {
    (
        [c[1], 2.0 * c[2], 3.0 * c[3], 4.0 * c[4], 5.0 * c[5]],
        [2.0 * c[2], 6.0 * c[3], 12.0 * c[4], 20.0 * c[5]],
        [6.0 * c[3], 24.0 * c[4], 60.0 * c[5]],
    )
}

/// Real roots of `a x³ + b x² + c x + d` (Cardano / trigonometric form).
fn cubic_roots(a: f64, b: f64, c: f64, d: f64) -> Vec<f64> {
    let scale = a.abs().max(b.abs()).max(c.abs()).max(d.abs());
    if scale == 0.0 {
        return vec![];
    }
    if a.abs() < 1e-14 * scale {
        if b.abs() < 1e-14 * scale {
            return if c != 0.0 { vec![-d / c] } else { vec![] };
        }
        let disc = c * c - 4.0 * b * d;
        if disc < 0.0 {
            return vec![];
        }
        let s = disc.sqrt();
        return vec![(-c + s) / (2.0 * b), (-c - s) / (2.0 * b)];
    }
    let (b, c, d) = (b / a, c / a, d / a);
    let p = c - b * b / 3.0;
    let q = 2.0 * b * b * b / 27.0 - b * c / 3.0 + d;
    let shift = -b / 3.0;
    let disc = q * q / 4.0 + p * p * p / 27.0;
    if disc > 0.0 {
        let s = disc.sqrt();
        vec![(-q / 2.0 + s).cbrt() + (-q / 2.0 - s).cbrt() + shift]
    } else {
        let r = (-p / 3.0).max(0.0).sqrt();
        if r == 0.0 {
            return vec![shift];
        }
        let arg = (-q / (2.0 * r * r * r)).clamp(-1.0, 1.0);
        let th = arg.acos() / 3.0;
        (0..3)
            .map(|k| 2.0 * r * (th - std::f64::consts::TAU * f64::from(k) / 3.0).cos() + shift)
            .collect()
    }
}

/// Verifies `segments` (consecutive intervals) against `lim`, sampling each at `samples`
/// points.
pub fn verify(
    segments: &[Segment],
    kin: &dyn Kinematics,
    lim: &Limits,
    samples: usize,
) -> VerifyReport {
    let names = kin.axis_names();
    let mut rep = VerifyReport {
        violations: vec![],
        tightest_margin: f64::INFINITY,
        tightest: String::new(),
        max_feed: 0.0,
        continuity_error: 0.0,
    };
    let n = samples.max(8);
    for (si, seg) in segments.iter().enumerate() {
        let t_end = seg.duration;
        let note = |rep: &mut VerifyReport,
                    q: &str,
                    axis: Option<usize>,
                    t: f64,
                    value: f64,
                    limit: f64,
                    tol: f64| {
            let m = 1.0 - value / limit;
            if m < rep.tightest_margin || m.is_nan() {
                rep.tightest_margin = m;
                rep.tightest = format!(
                    "{q}{} in interval {si}",
                    axis.map(|a| format!(" {}", names[a])).unwrap_or_default()
                );
            }
            if value.is_nan() || value > limit * (1.0 + tol) {
                rep.violations.push(Violation {
                    interval: si,
                    quantity: q.to_owned(),
                    axis: axis.map(|a| names[a].to_owned()),
                    t,
                    value,
                    limit,
                });
            }
        };
        for (ai, ax) in seg.axes.iter().enumerate() {
            let (dv, da, dj) = derivs(&ax.c);
            let mut ts: Vec<f64> = (0..=n).map(|i| t_end * i as f64 / n as f64).collect();
            ts.extend(
                cubic_roots(da[3], da[2], da[1], da[0])
                    .into_iter()
                    .filter(|t| *t > 0.0 && *t < t_end),
            );
            if dj[2] != 0.0 {
                let tv = -dj[1] / (2.0 * dj[2]);
                if tv > 0.0 && tv < t_end {
                    ts.push(tv);
                }
            }
            let mut worst = [(0.0f64, 0.0f64); 3];
            for &t in &ts {
                for (k, p) in [&dv[..], &da[..], &dj[..]].into_iter().enumerate() {
                    let v = horner(p, t).abs();
                    if v > worst[k].0 {
                        worst[k] = (v, t);
                    }
                }
            }
            for (k, (q, lim_k)) in [
                ("velocity", lim.vel[ai]),
                ("acceleration", lim.acc[ai]),
                ("jerk", lim.jerk[ai]),
            ]
            .into_iter()
            .enumerate()
            {
                note(&mut rep, q, Some(ai), worst[k].1, worst[k].0, lim_k, 1e-9);
            }
        }
        let h = 1e-5 * t_end;
        let tip = |t: f64| {
            let q: [f64; 5] = std::array::from_fn(|i| horner(&seg.axes[i].c, t));
            kin.forward(&q).tip
        };
        let mut worst = (0.0f64, 0.0f64);
        for i in 0..=n {
            let t = t_end * i as f64 / n as f64;
            let f = (tip(t + h) - tip(t - h)).length() / (2.0 * h);
            if f > worst.0 {
                worst = (f, t);
            }
        }
        rep.max_feed = rep.max_feed.max(worst.0);
        note(&mut rep, "feed", None, worst.1, worst.0, lim.feed, 1e-7);
        if let Some(next) = segments.get(si + 1) {
            for (a, b) in seg.axes.iter().zip(&next.axes) {
                let (dv, da, _) = derivs(&a.c);
                let end = [horner(&a.c, t_end), horner(&dv, t_end), horner(&da, t_end)];
                let start = [b.c[0], b.c[1], 2.0 * b.c[2]];
                for k in 0..3 {
                    let e = (end[k] - start[k]).abs() / (1.0 + start[k].abs());
                    rep.continuity_error = rep.continuity_error.max(e);
                    if e > 1e-7 {
                        rep.violations.push(Violation {
                            interval: si,
                            quantity: "continuity".into(),
                            axis: None,
                            t: t_end,
                            value: e,
                            limit: 1e-7,
                        });
                    }
                }
            }
        }
    }
    rep
}

#[cfg(test)]
mod tests {
    use super::cubic_roots;

    #[test]
    fn cardano_finds_three_roots() {
        let mut r = cubic_roots(1.0, -1.6, 0.73, -0.09);
        r.sort_by(f64::total_cmp);
        for (x, w) in r.iter().zip([0.2, 0.5, 0.9]) {
            assert!((x - w).abs() < 1e-9, "{r:?}");
        }
    }
}
