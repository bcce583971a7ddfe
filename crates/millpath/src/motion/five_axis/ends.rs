//! Starting and stopping: the jerk-limited ramp of the path speed at each end, the knots it
//! adds to the path, and the starting durations it gives the knot optimiser.
//!
//! # Why more knots at the ends
//! One quintic per interval cannot take the tool from rest to the feed efficiently: with both
//! ends' accelerations zero, its speed is a quartic whose mean is at most 0.6 of its final
//! value, so an interval of length `L` started from rest costs at least `L / (0.6 F)`. On the
//! paper's case (5 mm intervals) that is 0.11 s at each end, against the `√(F/J)` a
//! jerk-limited start really needs. So the ramp is planned first and knots are added along
//! it, where its speed changes.
//!
//! # The ramp
//! At an end, the path's joint derivatives per unit of tool-tip path are taken from the end
//! interval, `q_s ≈ Δq / Δs` (`Δs` its chord), and give the path's limits
//! `V = min(F, minᵢ vᵢ/|q_s,i|)`, `A = minᵢ aᵢ/|q_s,i|`, `J = minᵢ jᵢ/|q_s,i|` (the
//! curvature terms `q_ss ṡ²` are left out: the knot optimiser checks the exact limits). The
//! ramp is the jerk-limited profile from rest to `V`: jerk `J` for `t₁`, acceleration held at
//! `A` for `t₂` if `V J > A²`, jerk `−J` for `t₁`, with `t₁ = min(√(V/J), A/J)` and
//! `t₂ = V/A − A/J` (or 0); its duration is `2t₁ + t₂` and its length `V (2t₁ + t₂) / 2`.
//!
//! # The knots
//! [`refine_ends`] adds a knot at the ramp's position at `t_r · j / m`, `j = 1..m`, from each
//! end (`m` = [`super::FiveAxisOptions::end_knots`]), in joint space: on the cubic Hermite
//! curve of the joints between the two given knots around it (derivatives the central
//! differences of the knot index, the quadratic through the three end knots at an end), at
//! the chord fraction. Its pose is the forward kinematics of those joints. (Poses
//! interpolated in the workpiece frame and solved by inverse kinematics put the added knots
//! off the smooth joint curve by up to about 1e-5 rad, which at intervals of 10 ms is a jerk
//! of hundreds of rad/s³.) After the ramp, knots at doubling distances follow up to 0.75 of
//! the first given pose's distance, so that no interval is much more than twice the one
//! before it (the states come from finite differences over neighbouring intervals). A
//! position closer to a given pose than 0.3 of its distance to the previous position, or
//! past the middle of the path, adds nothing.

use super::segment::Limits;
use crate::machine::kinematics::{Joints, Kinematics, Pose};

/// A jerk-limited ramp of the path speed from rest (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Ramp {
    /// Final speed, mm/s.
    pub v: f64,
    /// Phases `(duration, jerk)`.
    phases: [(f64, f64); 3],
}

impl Ramp {
    /// The ramp of an end interval from `q0` (the end) to `q1` whose tips are `chord` apart.
    pub fn at_end(q0: &Joints, q1: &Joints, chord: f64, lim: &Limits) -> Option<Ramp> {
        if !(chord.is_finite() && chord > 0.0) {
            return None;
        }
        let (mut v, mut a, mut j) = (lim.feed, f64::INFINITY, f64::INFINITY);
        for i in 0..5 {
            let qs = (q1[i] - q0[i]).abs() / chord;
            if qs > 0.0 {
                v = v.min(lim.vel[i] / qs);
                a = a.min(lim.acc[i] / qs);
                j = j.min(lim.jerk[i] / qs);
            }
        }
        if !(v > 0.0 && v.is_finite() && a > 0.0 && j > 0.0) {
            return None;
        }
        let t1 = (v / j).sqrt().min(a / j);
        let t2 = if a.is_finite() {
            (v / a - a / j).max(0.0)
        } else {
            0.0
        };
        Some(Ramp {
            v,
            phases: [(t1, j), (t2, 0.0), (t1, -j)],
        })
    }

    /// Duration of the ramp, s.
    pub fn duration(&self) -> f64 {
        self.phases.iter().map(|p| p.0).sum()
    }

    /// Length of the ramp, mm.
    pub fn length(&self) -> f64 {
        self.s_at(self.duration())
    }

    /// Distance covered `t` s after the start (at the final speed after the ramp).
    pub fn s_at(&self, t: f64) -> f64 {
        let (mut s, mut v, mut a) = (0.0, 0.0, 0.0);
        let mut left = t.max(0.0);
        for &(d, j) in &self.phases {
            let h = d.min(left);
            s += v * h + a * h * h / 2.0 + j * h * h * h / 6.0;
            v += a * h + j * h * h / 2.0;
            a += j * h;
            left -= h;
            if left <= 0.0 {
                return s;
            }
        }
        s + self.v * left
    }

    /// Time to cover `s` from the start (the inverse of [`Ramp::s_at`], by bisection).
    pub fn t_at(&self, s: f64) -> f64 {
        if s <= 0.0 {
            return 0.0;
        }
        let (mut lo, mut hi) = (0.0, self.duration() + s / self.v);
        for _ in 0..100 {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            if self.s_at(mid) < s {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        hi
    }
}

/// Cumulative chord length of `tips` at each point.
fn arc(tips: &[crate::geom::Point3]) -> Vec<f64> {
    let mut s = vec![0.0; tips.len()];
    for k in 1..tips.len() {
        s[k] = s[k - 1] + tips[k - 1].distance(tips[k]);
    }
    s
}

/// The ramps at the start and at the end of the knot sequence `q` (tips by forward
/// kinematics), and the cumulative chord length at every knot.
pub(crate) fn ramps(
    q: &[Joints],
    kin: &dyn Kinematics,
    lim: &Limits,
) -> (Option<Ramp>, Option<Ramp>, Vec<f64>) {
    let tips: Vec<_> = q.iter().map(|q| kin.forward(q).tip).collect();
    let s = arc(&tips);
    let n = q.len();
    if n < 2 {
        return (None, None, s);
    }
    let start = Ramp::at_end(&q[0], &q[1], s[1], lim);
    let end = Ramp::at_end(&q[n - 1], &q[n - 2], s[n - 1] - s[n - 2], lim);
    (start, end, s)
}

/// Starting durations of the knot optimiser: each interval's moving lower bound
/// `max(chord / F, maxᵢ |Δqᵢ| / vᵢ)` times `1 + slack`, or (with `use_ramps`) the time the
/// ramps from the two ends take over it, whichever is longer.
pub(crate) fn starting_times(
    q: &[Joints],
    kin: &dyn Kinematics,
    lim: &Limits,
    slack: f64,
    use_ramps: bool,
) -> Vec<f64> {
    let (start, end, s) = if use_ramps {
        ramps(q, kin, lim)
    } else {
        (
            None,
            None,
            arc(&q.iter().map(|q| kin.forward(q).tip).collect::<Vec<_>>()),
        )
    };
    let total = s.last().copied().unwrap_or(0.0);
    q.windows(2)
        .zip(s.windows(2))
        .map(|(w, sw)| {
            let mut t = ((sw[1] - sw[0]) / lim.feed).max(1e-9);
            for ((a, b), v) in w[0].iter().zip(&w[1]).zip(&lim.vel) {
                t = t.max((b - a).abs() / v);
            }
            t *= 1.0 + slack;
            if let Some(r) = start
                && sw[0] < r.length()
            {
                t = t.max(r.t_at(sw[1]) - r.t_at(sw[0]));
            }
            if let Some(r) = end
                && total - sw[1] < r.length()
            {
                t = t.max(r.t_at(total - sw[0]) - r.t_at(total - sw[1]));
            }
            t
        })
        .collect()
}

/// An end interval at least this many ramp lengths long gets [`AUTO_END_KNOTS`] knots added
/// along its ramp when the caller leaves the count to the planner.
pub const AUTO_END_RATIO: f64 = 4.0;

/// Knots added at each end where the end intervals are long against their ramps (the paper's
/// case: 5 mm against 0.37 mm).
pub const AUTO_END_KNOTS: usize = 3;

/// How many knots [`refine_ends`] adds at each end when the caller does not say:
/// [`AUTO_END_KNOTS`] where both end intervals are at least [`AUTO_END_RATIO`] times their
/// ramp's length, else none (where the poses are close, the end intervals are already about
/// a ramp long and added knots only crowd them; the figures are in BENCHMARKS.md).
pub fn auto_end_knots(joints: &[Joints], kin: &dyn Kinematics, lim: &Limits) -> usize {
    let (start, end, s) = ramps(joints, kin, lim);
    let n = s.len();
    match (start, end) {
        (Some(a), Some(b))
            if n >= 3
                && s[1] >= AUTO_END_RATIO * a.length()
                && s[n - 1] - s[n - 2] >= AUTO_END_RATIO * b.length() =>
        {
            AUTO_END_KNOTS
        }
        _ => 0,
    }
}

/// The knots with `per_end` added along the ramp at each end (see the module docs):
/// `joints` are the poses' inverse kinematics. Returns the poses (an added one is the
/// forward kinematics of its joints), their joints, and for every pose its index among
/// `poses` (`None` for an added one).
pub fn refine_ends(
    poses: &[Pose],
    joints: &[Joints],
    kin: &dyn Kinematics,
    lim: &Limits,
    per_end: usize,
) -> (Vec<Pose>, Vec<Joints>, Vec<Option<usize>>) {
    let n = poses.len();
    let keep = || (poses.to_vec(), joints.to_vec(), (0..n).map(Some).collect());
    if per_end == 0 || n < 3 || joints.len() != n {
        return keep();
    }
    let tips: Vec<_> = poses.iter().map(|p| p.tip).collect();
    let s = arc(&tips);
    let total = s[n - 1];
    // Joint derivatives per interval of the index: central differences inside, the
    // quadratic through the first (last) three knots at the ends.
    let m = |k: usize, i: usize| -> f64 {
        let q = |k: usize| joints[k][i];
        if k == 0 {
            0.5 * (-3.0 * q(0) + 4.0 * q(1) - q(2))
        } else if k == n - 1 {
            0.5 * (3.0 * q(n - 1) - 4.0 * q(n - 2) + q(n - 3))
        } else {
            0.5 * (q(k + 1) - q(k - 1))
        }
    };
    // The ramps from the joint curve's end derivatives: the direction the first (last)
    // added interval will have.
    let end_ramp = |k: usize, len: f64| {
        let d: Joints = std::array::from_fn(|i| joints[k][i] + m(k, i));
        Ramp::at_end(&joints[k], &d, len, lim)
    };
    let (start, end) = (end_ramp(0, s[1]), end_ramp(n - 1, total - s[n - 2]));
    let mut at: Vec<(f64, f64)> = Vec::new();
    for (ramp, from_end) in [(start, false), (end, true)] {
        let Some(r) = ramp else { continue };
        let mut before = 0.0;
        let mut push = |d: f64, before: f64| {
            if d < 0.5 * total {
                at.push((if from_end { total - d } else { d }, 0.3 * (d - before)));
            }
        };
        for j in 1..=per_end {
            let d = r.s_at(r.duration() * j as f64 / per_end as f64);
            push(d, before);
            before = d;
        }
        // Then doubling distances up to the first given pose, so that no interval is more
        // than about twice as long as the one before it.
        let first = if from_end { total - s[n - 2] } else { s[1] };
        while before > 0.0 && 2.0 * before < 0.75 * first {
            push(2.0 * before, before);
            before *= 2.0;
        }
    }
    at.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut out = keep();
    out.0.clear();
    out.1.clear();
    out.2.clear();
    let mut next = at.iter().peekable();
    for k in 0..n {
        out.0.push(poses[k]);
        out.1.push(joints[k]);
        out.2.push(Some(k));
        if k + 1 == n {
            break;
        }
        let len = s[k + 1] - s[k];
        while let Some(&&(x, gap)) = next.peek() {
            if x >= s[k + 1] {
                break;
            }
            next.next();
            if x - s[k] < gap || s[k + 1] - x < gap {
                continue;
            }
            // The cubic Hermite of the joints between knots k and k + 1, at the chord
            // fraction.
            let u = (x - s[k]) / len;
            let (h00, h10) = (
                2.0 * u * u * u - 3.0 * u * u + 1.0,
                u * u * u - 2.0 * u * u + u,
            );
            let (h01, h11) = (-2.0 * u * u * u + 3.0 * u * u, u * u * u - u * u);
            let q: Joints = std::array::from_fn(|i| {
                h00 * joints[k][i] + h10 * m(k, i) + h01 * joints[k + 1][i] + h11 * m(k + 1, i)
            });
            out.0.push(kin.forward(&q));
            out.1.push(q);
            out.2.push(None);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ramp_reaches_its_speed_with_its_length() {
        let mut lim = Limits::paper();
        lim.feed = 30.0;
        let q0 = [0.0; 5];
        let mut q1 = [0.0; 5];
        q1[0] = 1.0;
        // Linear only: V = 30, A = 20 000, J = 200 000 per mm of path: no constant-acceleration
        // phase (V J = 6e6 < A² = 4e8), t_r = 2√(V/J), length V t_r / 2.
        let r = Ramp::at_end(&q0, &q1, 1.0, &lim).unwrap();
        let tr = 2.0 * (30.0f64 / 200_000.0).sqrt();
        assert!((r.duration() - tr).abs() < 1e-15);
        assert!((r.s_at(tr) - 15.0 * tr).abs() < 1e-12);
        // After the ramp, the speed is V.
        assert!((r.s_at(tr + 1.0) - r.s_at(tr) - 30.0).abs() < 1e-9);
        let t = r.t_at(0.2);
        assert!((r.s_at(t) - 0.2).abs() < 1e-12);
    }
}
