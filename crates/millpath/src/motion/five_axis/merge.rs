//! Dense poses: which of the given poses become knots.
//!
//! # Why not every pose
//! A quintic interval of duration `T` whose end states disagree with its chord by `ε` (per
//! unit of the chord) has a jerk of about `60 ε Δq / T³`. The states are taken from the knots'
//! finite differences, so a knot off the smooth path by `δ` — the rounding of the file's
//! decimals is enough — gives a jerk of order `60 δ / T³`. Six decimals of the tool axis
//! (`δ ≈ 5e-7` rad) at `T = 3.3` ms (0.1 mm apart at 30 mm/s) make 800 rad/s³, four times the
//! paper's rotary jerk limit: intervals end up slowed or at rest, and a 1,000-pose sweep ran
//! at seven times its length ÷ feed. At `T ≥ 10` ms the same rounding costs 30 rad/s³.
//!
//! # The rule
//! Each interval's moving lower bound is `τ = max(chord/F, maxᵢ |Δqᵢ|/vᵢ)`; `τ` summed along
//! the path is the parameter below. From the last kept knot `a`, the poses after it are
//! merged into the next interval while that interval's `τ` stays under
//! [`MergeOptions::min_interval_s`]; the pose where it reaches it is kept. A pose is merged
//! only if the joints' cubic Hermite between the kept knots `a` and `b`, in `τ`, with the
//! derivatives `dq/dτ` of the given poses (non-uniform central differences), puts the tool tip
//! within [`MergeOptions::tip_tolerance_mm`] of it and the tool axis within
//! [`MergeOptions::axis_tolerance_rad`]; otherwise the interval ends at the pose before. The
//! first and last poses are always kept, and so is a pose where the path stops (`τ` = 0 on
//! one side: a duplicate pose).
//!
//! # The check after planning
//! [`pose_deviation`] measures every given pose against the planned tip path (the planned
//! interval around it, sampled) and the planned axis there: that is the verifier of the merge.
//! [`super::plan`] keeps any pose that it finds out of tolerance and plans again.

use super::segment::{Limits, Segment};
use crate::machine::kinematics::{Joints, Kinematics, Pose};
use serde::{Deserialize, Serialize};

/// Options of the merge of dense poses. Built from [`Default`] with the `with_*` methods.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[non_exhaustive]
pub struct MergeOptions {
    /// Shortest interval, s, as its moving lower bound `max(chord/F, maxᵢ|Δqᵢ|/vᵢ)`: poses
    /// closer than this are merged into one interval (see the module docs); 0 plans every
    /// pose as a knot. Default 0.01 s.
    pub min_interval_s: f64,
    /// Largest distance of a merged pose's tip from the path planned through the knots, mm.
    /// Default 0.005 mm.
    pub tip_tolerance_mm: f64,
    /// Largest angle between a merged pose's axis and the planned one, rad. Default 1e-4 rad
    /// (0.0057°).
    pub axis_tolerance_rad: f64,
}

impl Default for MergeOptions {
    fn default() -> Self {
        MergeOptions {
            min_interval_s: 0.01,
            tip_tolerance_mm: 0.005,
            axis_tolerance_rad: 1e-4,
        }
    }
}

option_builders! {
    MergeOptions;
    /// Sets [`MergeOptions::min_interval_s`].
    with_min_interval_s => min_interval_s: f64;
    /// Sets [`MergeOptions::tip_tolerance_mm`].
    with_tip_tolerance_mm => tip_tolerance_mm: f64;
    /// Sets [`MergeOptions::axis_tolerance_rad`].
    with_axis_tolerance_rad => axis_tolerance_rad: f64;
}

/// The moving lower bound of the interval between two knots, s.
fn lower_bound(kin: &dyn Kinematics, lim: &Limits, a: &Joints, b: &Joints) -> f64 {
    let mut t = kin.forward(a).tip.distance(kin.forward(b).tip) / lim.feed;
    for i in 0..5 {
        t = t.max((b[i] - a[i]).abs() / lim.vel[i]);
    }
    t
}

/// Angle between two unit vectors, rad.
fn angle(a: crate::geom::Vec3, b: crate::geom::Vec3) -> f64 {
    a.cross(b).length().atan2(a.dot(b))
}

/// The first and the last interval are at least this many jerk-limited ramps long (see
/// [`knots`]).
const END_RAMPS: f64 = 1.5;

/// The indices of the poses to plan through as knots (increasing, the first and the last
/// included); `joints` are the poses' inverse kinematics, `keep` poses that must stay.
pub(crate) fn knots(
    poses: &[Pose],
    joints: &[Joints],
    kin: &dyn Kinematics,
    lim: &Limits,
    opts: &MergeOptions,
    keep: &[bool],
) -> Vec<usize> {
    let n = joints.len();
    if n < 3 || opts.min_interval_s <= 0.0 || poses.len() != n {
        return (0..n).collect();
    }
    let mut tau = vec![0.0; n];
    for k in 1..n {
        tau[k] = tau[k - 1] + lower_bound(kin, lim, &joints[k - 1], &joints[k]);
    }
    // dq/dτ at each pose: non-uniform central differences, one-sided at the ends; zero where
    // the path stops.
    let deriv = |k: usize| -> Joints {
        let (lo, hi) = (k.saturating_sub(1), (k + 1).min(n - 1));
        let (d0, d1) = (tau[k] - tau[lo], tau[hi] - tau[k]);
        std::array::from_fn(|i| {
            let s0 = if d0 > 0.0 {
                (joints[k][i] - joints[lo][i]) / d0
            } else {
                0.0
            };
            let s1 = if d1 > 0.0 {
                (joints[hi][i] - joints[k][i]) / d1
            } else {
                0.0
            };
            if d0 > 0.0 && d1 > 0.0 {
                (s0 * d1 + s1 * d0) / (d0 + d1)
            } else {
                s0 + s1
            }
        })
    };
    let fits = |a: usize, b: usize| -> bool {
        let h = tau[b] - tau[a];
        if h <= 0.0 {
            return false;
        }
        let (ma, mb) = (deriv(a), deriv(b));
        (a + 1..b).all(|j| {
            let u = (tau[j] - tau[a]) / h;
            let (u2, u3) = (u * u, u * u * u);
            let (h00, h10, h01, h11) = (
                2.0 * u3 - 3.0 * u2 + 1.0,
                u3 - 2.0 * u2 + u,
                -2.0 * u3 + 3.0 * u2,
                u3 - u2,
            );
            let q: Joints = std::array::from_fn(|i| {
                h00 * joints[a][i] + h10 * h * ma[i] + h01 * joints[b][i] + h11 * h * mb[i]
            });
            let p = kin.forward(&q);
            p.tip.distance(poses[j].tip) <= opts.tip_tolerance_mm
                && angle(p.axis, poses[j].axis) <= opts.axis_tolerance_rad
        })
    };
    // The first and last intervals start and stop the tool: a single quintic from rest over a
    // chord shorter than about the jerk-limited ramp's length must back up to reach the
    // feed at its far end. They are made at least `END_RAMPS` ramp lengths long where the
    // poses allow.
    let (start, end, s) = super::ends::ramps(joints, kin, lim);
    let total = s[n - 1];
    let end_len = |r: Option<super::ends::Ramp>| r.map_or(0.0, |r| END_RAMPS * r.length());
    let (l0, l1) = (end_len(start), end_len(end));
    let short = |a: usize, b: usize| (a == 0 && s[b] < l0) || total - s[b] < l1;
    let stops = |k: usize| {
        k > 0 && k + 1 < n && (tau[k] - tau[k - 1] <= 1e-12 || tau[k + 1] - tau[k] <= 1e-12)
    };
    let mut out = vec![0];
    let mut a = 0;
    let mut b = 1;
    while b < n {
        if b + 1 == n || keep.get(b).copied().unwrap_or(false) || stops(b) {
            if !fits(a, b) {
                // The last pose that fits is kept first (at worst the one after `a`).
                let mut c = b - 1;
                while c > a + 1 && !fits(a, c) {
                    c -= 1;
                }
                if c > a {
                    out.push(c);
                    a = c;
                    b = c + 1;
                    continue;
                }
            }
            out.push(b);
            a = b;
            b += 1;
            continue;
        }
        if tau[b] - tau[a] >= opts.min_interval_s && !short(a, b) {
            if fits(a, b) {
                out.push(b);
                a = b;
                b += 1;
            } else {
                let mut c = b - 1;
                while c > a + 1 && !fits(a, c) {
                    c -= 1;
                }
                out.push(c);
                a = c;
                b = c + 1;
            }
            continue;
        }
        b += 1;
    }
    out
}

/// Deviation of a given pose from the plan: tip distance, mm, and axis angle, rad.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct PoseDeviation {
    /// The pose, 0-based among the given poses.
    pub pose: usize,
    /// Distance from its tip to the planned tip path, mm.
    pub tip_mm: f64,
    /// Angle between its axis and the planned axis at the nearest point, rad.
    pub axis_rad: f64,
}

/// Every given pose that is not a knot, against the planned interval between the knots
/// around it (`knot_of[k]`: the given pose of knot `k`, or `None` for an added one): its
/// tip's distance to the interval's tip path (`per` chords) and the axis angle at the nearest
/// point (nearest by tip distance plus `mm_per_rad` × axis angle).
pub(crate) fn pose_deviation(
    segments: &[Segment],
    knot_of: &[Option<usize>],
    poses: &[Pose],
    kin: &dyn Kinematics,
    per: usize,
    mm_per_rad: f64,
) -> Vec<PoseDeviation> {
    let mut out = Vec::new();
    let per = per.max(1);
    let mut last: Option<(usize, usize)> = None; // (knot, pose) of the last given-pose knot
    for (k, idx) in knot_of.iter().enumerate() {
        let Some(p) = *idx else { continue };
        if let Some((ka, pa)) = last
            && p > pa + 1
        {
            let samples: Vec<Pose> = segments[ka..k]
                .iter()
                .flat_map(|s| {
                    (0..=per)
                        .map(move |j| s.duration * j as f64 / per as f64)
                        .map(move |t| (s, t))
                })
                .map(|(s, t)| kin.forward(&s.eval(t)[0]))
                .collect();
            for (j, pose) in poses.iter().enumerate().take(p).skip(pa + 1) {
                // The nearest point by tip distance plus `mm_per_rad` × axis angle, so that a
                // pose along a rotation of a still tip finds its own angle.
                let mut best = (f64::INFINITY, f64::INFINITY, 0.0);
                for w in samples.windows(2) {
                    let (a, b) = (w[0].tip, w[1].tip);
                    let ab = b - a;
                    let l2 = ab.dot(ab);
                    let mut us = vec![0.0, 1.0];
                    if l2 > 0.0 {
                        us.push(((pose.tip - a).dot(ab) / l2).clamp(0.0, 1.0));
                    }
                    for u in us {
                        let d = a.lerp(b, u).distance(pose.tip);
                        let axis = (w[0].axis * (1.0 - u) + w[1].axis * u)
                            .normalize()
                            .unwrap_or(w[0].axis);
                        let ang = angle(axis, pose.axis);
                        let score = d + mm_per_rad * ang;
                        if score < best.0 {
                            best = (score, d, ang);
                        }
                    }
                }
                out.push(PoseDeviation {
                    pose: j,
                    tip_mm: best.1,
                    axis_rad: best.2,
                });
            }
        }
        last = Some((k, p));
    }
    out
}
