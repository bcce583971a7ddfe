//! Passing near the pole within a tilt tolerance: the tool axes moved by at most `τ` so that
//! the free rotary axis (C on table-table and head-head machines) does not whip round.
//!
//! # The problem
//! At the pole (the tool along the C axis) C is free; a path passing at a distance `ε` from
//! it needs C to turn by nearly 180° over the few poses closest to it, however small `ε` is.
//! The tilting sweep through the pole runs at 1.03 × its length ÷ feed; the same sweep
//! passing 0.2° beside the pole takes four times as long, C at its limits.
//!
//! # The tolerance band
//! For a fixed C the reachable axes form a great circle through the pole (the tilt axis
//! turns the tool in the plane C sets). A pose whose axis lies at the pole distance `d` from
//! the pole, in the plane of C = `ψ`, is reached with C = `c` and the best tilt at the angle
//! `asin(sin d · |sin(c − ψ)|)` from its axis. So the axes within `τ` of the given one are
//! reached with any C in `ψ ± w` (mod π, the tilt taking either sign), `w = asin(sin τ / sin
//! d)`, and with any C at all where `d ≤ τ`.
//!
//! # The straightest C
//! Over a window of poses C is taken as the *taut string* through these bands: the shortest
//! curve `C(s)` over the path's arc length `s` from the C before the window to the C after
//! it that stays in every band ([`taut_string`]: straight lines bent only at band edges).
//! The bands' branch (mod π) is placed two ways and the one with the smaller largest C step
//! kept: each nearest the line between the ends, the end nearest the C before (the tilt
//! changes sign instead of C turning round), or each nearest the band before it (C turns
//! with the path, the turn cut short). Each pose then takes its best tilt for that C and the
//! linear axes that keep its tip. The whole path (its ends fixed) is tried as one window
//! first: a window's edges bend C where the bands are narrow, and the knot optimiser plans
//! such a bend badly. Where that is not kept, windows of the poses within
//! [`WINDOW_TOLERANCES`] `τ` of the pole are tried. A window is kept only if its largest C
//! step between poses is smaller than before; the axes and tips of the kept poses are
//! checked through the forward kinematics (angle ≤ `τ`, tip within 1e-6 mm), so the band's
//! model is never trusted blind: a machine where it does not hold keeps its poses.

use crate::error::InputError;
use crate::geom::Vec3;
use crate::machine::kinematics::{
    IkOptions, IkWarning, Joints, Kinematics, Pose, inverse_path, wrap,
};
use serde::{Deserialize, Serialize};
use std::f64::consts::{FRAC_PI_2, PI};

/// Poses within this many tolerances of the pole form a window.
pub const WINDOW_TOLERANCES: f64 = 30.0;
/// The largest tilt tolerance, rad (15°).
pub const MAX_TILT_TOLERANCE: f64 = 15.0 * PI / 180.0;

/// Where a path's axes were moved to pass the pole.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PoleWindow {
    /// First pose moved, 0-based.
    pub first_pose: usize,
    /// Last pose moved.
    pub last_pose: usize,
    /// Largest angle between a moved axis and the given one, rad (at most the tolerance).
    pub max_axis_change_rad: f64,
    /// Largest C step between two poses of the window (and into the pose after it) before,
    /// rad.
    pub max_c_step_before_rad: f64,
    /// The same after.
    pub max_c_step_after_rad: f64,
}

/// Poses, joints and warnings after straightening.
pub(crate) type Straightened = (
    Vec<Pose>,
    Vec<Joints>,
    Vec<(usize, IkWarning)>,
    Vec<PoleWindow>,
);

/// The joints of `poses` (as [`inverse_path`]), the axes within `tol` rad of the pole moved by
/// at most `tol` where that keeps the free axis from whipping round (module docs). `tol ≤ 0`
/// or a machine whose free axis is not its last joint: the poses as given.
pub(crate) fn straighten(
    kin: &dyn Kinematics,
    poses: &[Pose],
    ik: &IkOptions,
    tol: f64,
) -> Result<Straightened, InputError> {
    let (joints0, warnings0) = inverse_path(kin, poses, ik)?;
    if tol <= 0.0 || kin.free_axis() != 4 || poses.len() < 3 {
        return Ok((poses.to_vec(), joints0, warnings0, Vec::new()));
    }
    let pd: Vec<f64> = poses
        .iter()
        .map(|p| kin.orientation(p.axis, 0.0).pole_distance)
        .collect();
    let reach = (WINDOW_TOLERANCES * tol).min(FRAC_PI_2);
    // Arc length along the tips, the axes' turning (10 mm per rad) breaking ties.
    let mut s = vec![0.0; poses.len()];
    for i in 1..poses.len() {
        let turn = poses[i].axis.dot(poses[i - 1].axis).clamp(-1.0, 1.0).acos();
        s[i] = s[i - 1] + poses[i].tip.distance(poses[i - 1].tip) + 10.0 * turn + 1e-9;
    }
    let mut out_poses = poses.to_vec();
    let n = poses.len();
    // The whole path as one window first: no window edge where C would bend.
    if let Some((qs, w)) = window(
        kin,
        poses,
        &pd,
        &s,
        &joints0[..1],
        &joints0,
        (1, n - 2),
        tol,
        ik,
    ) {
        let mut joints = vec![joints0[0]];
        joints.extend(qs);
        let last = kin.inverse_near(&poses[n - 1], joints.last(), ik)?.joints;
        joints.push(last);
        for (p, q) in out_poses.iter_mut().zip(&joints) {
            p.axis = kin.forward(q).axis;
        }
        out_poses[0].axis = poses[0].axis;
        out_poses[n - 1].axis = poses[n - 1].axis;
        let (_, warnings) = inverse_path(kin, &out_poses, ik)?;
        return Ok((out_poses, joints, warnings, vec![w]));
    }
    let mut joints: Vec<Joints> = Vec::with_capacity(n);
    let mut windows = Vec::new();
    // Poses up to this index are solved one by one (a window tried and not kept).
    let mut plain_until = 0;
    let mut i = 0;
    while i < poses.len() {
        if i >= plain_until && i > 0 && i + 1 < poses.len() && pd[i] < reach {
            let mut b = i;
            while b + 2 < poses.len() && pd[b + 1] < reach {
                b += 1;
            }
            match window(kin, poses, &pd, &s, &joints, &joints0, (i, b), tol, ik) {
                Some((qs, w)) => {
                    for (k, q) in qs.into_iter().enumerate() {
                        out_poses[i + k].axis = kin.forward(&q).axis;
                        joints.push(q);
                    }
                    windows.push(w);
                    i = b + 1;
                    continue;
                }
                None => plain_until = b + 1,
            }
        }
        let q = match joints.last() {
            Some(p) => kin.inverse_near(&poses[i], Some(p), ik)?.joints,
            None => joints0[i],
        };
        joints.push(q);
        i += 1;
    }
    if windows.is_empty() {
        return Ok((poses.to_vec(), joints0, warnings0, windows));
    }
    // Warnings of the path as planned (the moved poses no longer pass beside the pole).
    let (_, warnings) = inverse_path(kin, &out_poses, ik)?;
    Ok((out_poses, joints, warnings, windows))
}

/// The joints of the window `a..=b` (poses `a − 1` and `b + 1` outside it), or `None` where
/// straightening does not shorten the largest C step or leaves the tolerance. Two ways of
/// placing the bands (mod π) are tried and the one with the smaller largest step kept: each
/// band nearest the line from the C before to the C after (that C nearest the one before:
/// the tilt changes sign where the path passes within the tolerance of the pole), and each
/// band nearest the one before it (C turns round the pole as the path does, the string
/// cutting the turn short where the bands allow).
#[allow(clippy::too_many_arguments)]
fn window(
    kin: &dyn Kinematics,
    poses: &[Pose],
    pd: &[f64],
    s: &[f64],
    done: &[Joints],
    joints0: &[Joints],
    (a, b): (usize, usize),
    tol: f64,
    ik: &IkOptions,
) -> Option<(Vec<Joints>, PoleWindow)> {
    let prev = *done.last()?;
    let bands = Bands {
        kin,
        poses,
        pd,
        s,
        tol,
    };
    [true, false]
        .into_iter()
        .filter_map(|flip| {
            let (xs, lo, hi) = bands.gates(prev[4], (a, b), flip)?;
            let cs = taut_string(&xs, &lo, &hi);
            joints_along(kin, poses, joints0, prev, &cs, (a, b), tol, ik)
        })
        .min_by(|x, y| {
            x.1.max_c_step_after_rad
                .total_cmp(&y.1.max_c_step_after_rad)
        })
}

/// The poses' tolerance bands for C.
struct Bands<'a> {
    kin: &'a dyn Kinematics,
    poses: &'a [Pose],
    pd: &'a [f64],
    s: &'a [f64],
    tol: f64,
}

impl Bands<'_> {
    /// The band centre of pose `i` nearest `near` (mod π).
    fn centre(&self, i: usize, near: f64) -> Option<f64> {
        let psi = self
            .kin
            .orientation(self.poses[i].axis, near)
            .pairs
            .first()?
            .1;
        Some(psi + ((near - psi) / PI).round() * PI)
    }

    /// The half-width of pose `i`'s band; `None` where every C is within the tolerance.
    fn half_width(&self, i: usize) -> Option<f64> {
        let w = if self.pd[i] <= self.tol {
            return None;
        } else {
            (self.tol.sin() / self.pd[i].sin()).min(1.0).asin() * (1.0 - 1e-9)
        };
        (w < FRAC_PI_2 * (1.0 - 1e-9)).then_some(w)
    }

    /// The gates of the window `a..=b` from the C `c_in` before it: abscissas, lower and
    /// upper bounds, the ends fixed (see [`window`] for `flip`).
    fn gates(&self, c_in: f64, (a, b): (usize, usize), flip: bool) -> Option<Gates> {
        let (x0, x1) = (self.s[a - 1], self.s[b + 1]);
        let c_flip = self.centre(b + 1, c_in)?;
        let mut xs = vec![x0];
        let mut lo = vec![c_in];
        let mut hi = vec![c_in];
        let mut last = c_in;
        for i in a..=b {
            xs.push(self.s[i]);
            match self.half_width(i) {
                None => {
                    lo.push(f64::NEG_INFINITY);
                    hi.push(f64::INFINITY);
                }
                Some(w) => {
                    let near = if flip {
                        c_in + (c_flip - c_in) * (self.s[i] - x0) / (x1 - x0)
                    } else {
                        last
                    };
                    let c = self.centre(i, near)?;
                    last = c;
                    lo.push(c - w);
                    hi.push(c + w);
                }
            }
        }
        let c_out = if flip {
            c_flip
        } else {
            self.centre(b + 1, last)?
        };
        xs.push(x1);
        lo.push(c_out);
        hi.push(c_out);
        Some((xs, lo, hi))
    }
}

/// Abscissas, lower and upper bounds.
type Gates = (Vec<f64>, Vec<f64>, Vec<f64>);

/// The joints of the window's poses with C from the string `cs` (its ends outside the
/// window), each its best tilt and the linear axes keeping its tip; checked through the
/// forward kinematics; `None` where a pose leaves the tolerance or the ranges, or the
/// largest C step is not smaller than the given path's.
#[allow(clippy::too_many_arguments)]
fn joints_along(
    kin: &dyn Kinematics,
    poses: &[Pose],
    joints0: &[Joints],
    prev: Joints,
    cs: &[f64],
    (a, b): (usize, usize),
    tol: f64,
    ik: &IkOptions,
) -> Option<(Vec<Joints>, PoleWindow)> {
    let [tilt_range, c_range] = kin.rotary_ranges();
    let mut qs = Vec::with_capacity(b - a + 1);
    let mut last = prev;
    let mut max_change: f64 = 0.0;
    for (k, i) in (a..=b).enumerate() {
        let c = cs[k + 1];
        if !c_range.contains(c) {
            return None;
        }
        let e0 = kin.forward(&[0.0, 0.0, 0.0, 0.0, c]).axis;
        let e1 = kin.forward(&[0.0, 0.0, 0.0, FRAC_PI_2, c]).axis;
        let k_axis = poses[i].axis;
        let t = wrap(k_axis.dot(e1).atan2(k_axis.dot(e0)));
        let t = tilt_range
            .replicas(t)
            .into_iter()
            .min_by(|x, y| (x - last[3]).abs().total_cmp(&(y - last[3]).abs()))?;
        let [x, y, z] = kin.linear(poses[i].tip, t, c)?;
        let q = [x, y, z, t, c];
        let got = kin.forward(&q);
        let change = angle(got.axis, k_axis);
        if !(change <= tol * (1.0 + 1e-9) && got.tip.distance(poses[i].tip) <= 1e-6) {
            return None;
        }
        max_change = max_change.max(change);
        qs.push(q);
        last = q;
    }
    let after = kin
        .inverse_near(&poses[b + 1], Some(&last), ik)
        .ok()?
        .joints;
    let step = |qs: &mut dyn Iterator<Item = f64>| {
        let v: Vec<f64> = qs.collect();
        v.windows(2)
            .map(|w| (w[1] - w[0]).abs())
            .fold(0.0, f64::max)
    };
    let now = step(
        &mut std::iter::once(prev[4])
            .chain(qs.iter().map(|q| q[4]))
            .chain(std::iter::once(after[4])),
    );
    // The given path's own steps (an earlier window may have changed its family).
    let before = step(&mut (a - 1..=b + 1).map(|i| joints0[i][4]));
    (now < before).then_some((
        qs,
        PoleWindow {
            first_pose: a,
            last_pose: b,
            max_axis_change_rad: max_change,
            max_c_step_before_rad: before,
            max_c_step_after_rad: now,
        },
    ))
}

fn angle(u: Vec3, v: Vec3) -> f64 {
    u.cross(v).length().atan2(u.dot(v))
}

/// The taut string through gates: the shortest polyline from `(x₀, lo₀)` to
/// `(x_{n−1}, lo_{n−1})` passing at every `xᵢ` between `loᵢ` and `hiᵢ` (infinite bounds allowed;
/// the first and last gates are points, `x` increasing); its value at every `xᵢ`. Straight
/// from each bend to the next; it bends only at a gate's end: at the upper end of the gate
/// that caps it when a later gate forces it higher, at the lower end in the other case (the
/// funnel of string pulling, restarted at each bend).
pub(crate) fn taut_string(x: &[f64], lo: &[f64], hi: &[f64]) -> Vec<f64> {
    let n = x.len();
    let mut y = vec![0.0; n];
    if n == 0 {
        return y;
    }
    let (mut a, mut ya) = (0, lo[0]);
    y[0] = ya;
    while a + 1 < n {
        let (mut smin, mut smax) = (f64::NEG_INFINITY, f64::INFINITY);
        let (mut jmin, mut jmax) = (a, a);
        let mut bend = None;
        for i in a + 1..n {
            let dx = x[i] - x[a];
            let (l, h) = ((lo[i] - ya) / dx, (hi[i] - ya) / dx);
            if l > smax {
                bend = Some((jmax, hi[jmax]));
                break;
            }
            if h < smin {
                bend = Some((jmin, lo[jmin]));
                break;
            }
            if l > smin {
                (smin, jmin) = (l, i);
            }
            if h < smax {
                (smax, jmax) = (h, i);
            }
        }
        let (j, yj) = bend.unwrap_or((n - 1, lo[n - 1]));
        for k in a + 1..=j {
            y[k] = ya + (yj - ya) * (x[k] - x[a]) / (x[j] - x[a]);
        }
        y[j] = yj;
        (a, ya) = (j, yj);
    }
    y
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The string stays in its gates, is straight where no gate binds, and is no longer than
    /// any of many random polylines through the same gates.
    #[test]
    fn the_taut_string_is_in_its_gates_and_shortest() {
        let mut seed = 7u64;
        let mut rnd = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        let len = |x: &[f64], y: &[f64]| {
            x.windows(2)
                .zip(y.windows(2))
                .map(|(a, b)| (a[1] - a[0]).hypot(b[1] - b[0]))
                .sum::<f64>()
        };
        for _ in 0..200 {
            let n = 3 + (rnd() * 20.0) as usize;
            let mut x = vec![0.0];
            for _ in 1..n {
                x.push(x.last().unwrap() + 0.1 + rnd());
            }
            let mut lo = Vec::new();
            let mut hi = Vec::new();
            for i in 0..n {
                let c = 3.0 * (rnd() - 0.5);
                let w = if rnd() < 0.2 { f64::INFINITY } else { rnd() };
                if i == 0 || i == n - 1 {
                    lo.push(c);
                    hi.push(c);
                } else {
                    lo.push(c - w);
                    hi.push(c + w);
                }
            }
            let y = taut_string(&x, &lo, &hi);
            for i in 0..n {
                assert!(y[i] >= lo[i] - 1e-9 && y[i] <= hi[i] + 1e-9, "{i}: {y:?}");
            }
            let best = len(&x, &y);
            for _ in 0..50 {
                let z: Vec<f64> = (0..n)
                    .map(|i| {
                        let (l, h) = (lo[i].max(y[i] - 1.0), hi[i].min(y[i] + 1.0));
                        l + (h - l) * rnd()
                    })
                    .collect();
                assert!(len(&x, &z) >= best - 1e-9);
            }
        }
        // No gate binds: straight.
        let x = [0.0, 1.0, 2.0, 4.0];
        let y = taut_string(&x, &[0.0, -9.0, -9.0, 4.0], &[0.0, 9.0, 9.0, 4.0]);
        assert!((y[1] - 1.0).abs() < 1e-12 && (y[2] - 2.0).abs() < 1e-12);
    }
}
