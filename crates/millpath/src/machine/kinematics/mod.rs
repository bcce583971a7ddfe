//! Kinematics of five-axis machines: forward, inverse (all solutions) and analytic Jacobian.
//!
//! # Conventions
//! * Joint vectors are [`Joints`] = `[x, y, z, r1, r2]`: three linear axes in millimetres, then
//!   two rotary axes in radians. Which rotary axes `r1`, `r2` are (A/B, A/C, B/C) is given by
//!   [`Kinematics::axis_names`].
//! * A [`Pose`] is the tool tip position (mm) and the unit tool axis, pointing from the tip
//!   towards the spindle, both in the **workpiece frame**.
//! * The Jacobian is the 6 × 5 matrix `∂(tip, axis)/∂(joints)`: rows 0–2 the tip (mm per unit
//!   joint), rows 3–5 the axis (per unit joint).
//!
//! # Inverse kinematics
//! Every machine here has the same structure: the tool axis in the workpiece frame depends on
//! the two rotary angles only, and for given angles the tip depends affinely on the linear axes.
//! So the inverse is solved in two steps:
//! 1. the orientation: the machine's closed form gives the principal `(r1, r2)` pairs for the
//!    axis (two families, the "tilt" angle and its mirror; see each machine's docs). Every pair
//!    is then replicated by multiples of 2π into the rotary ranges;
//! 2. the linear axes: closed form for the chosen angles.
//!
//! At a **pole** (the tilt angle such that the tool axis lies on the outer rotary axis — `A = 0`
//! for an AC table, `B = 0` for a BC table or head, `A = ±90°` for the paper's machine) the
//! other rotary angle is free: any value gives the same pose. [`Kinematics::inverse_near`]
//! then keeps the previous value of the free angle (least rotary travel) and returns
//! [`IkWarning::AtPole`]. Near a pole (tilt within [`IkOptions::pole_warn`]) the free angle is
//! ill-conditioned: [`IkWarning::NearPole`]. Whenever the chosen solution moves a rotary axis by
//! more than [`IkOptions::flip_threshold`] from the previous pose (the classic 180° flip when a
//! path crosses the pole), [`IkWarning::Flip`] says so. The library never prints: warnings are
//! part of the [`IkOutcome`].
//!
//! # Derivative bounds (used to certify the feed limit)
//! On every machine here the tip is affine in the linear joints with coefficients that are
//! products of rotation matrices, and each rotary joint enters through one rotation about a
//! fixed axis (`dR/dθ = G R` with `|G| = 1` as an operator). Hence, anywhere in a joint box:
//! * a partial derivative of the tip of any order with **two or more linear** indices is 0;
//! * one with **exactly one linear** index has norm ≤ 1 (a unit column rotated, each rotary
//!   derivative multiplying by a generator of norm 1);
//! * one with **only rotary** indices (order 1 to 3) has norm ≤ `R`, the largest lever arm
//!   over the box: [`Kinematics::lever_bound`] (each machine derives its `R` in its docs).
//!
//! These three facts bound the tip's second and third time derivatives along any joint
//! trajectory by the joints' velocity, acceleration and jerk bounds (see
//! `motion::five_axis::certify`).

mod head_head;
mod paper_ab;
mod trt;

pub use head_head::HeadHead;
pub use paper_ab::PaperAb;
pub use trt::{TableTable, TrtKind};

use crate::error::InputError;
use crate::geom::{Point3, Vec3};
use serde::{Deserialize, Serialize};
use std::f64::consts::{PI, TAU};

/// Joint positions `[x, y, z, r1, r2]`: mm, mm, mm, rad, rad.
pub type Joints = [f64; 5];

/// Analytic Jacobian `∂(tip_x, tip_y, tip_z, axis_i, axis_j, axis_k)/∂(joints)`.
pub type Jacobian = [[f64; 5]; 6];

/// A tool pose in the workpiece frame.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Pose {
    /// Tool tip, mm.
    pub tip: Point3,
    /// Unit tool axis, from the tip towards the spindle.
    pub axis: Vec3,
}

impl Pose {
    /// A pose; the axis is normalised. A zero or non-finite axis or tip is an [`InputError`].
    pub fn new(tip: Point3, axis: Vec3) -> Result<Pose, InputError> {
        if !tip.is_finite() {
            return Err(
                InputError::new("tool tip", format!("{tip:?}")).expected("finite coordinates")
            );
        }
        let axis = axis.normalize().filter(|a| a.is_finite()).ok_or_else(|| {
            InputError::new("tool axis", format!("({}, {}, {})", axis.x, axis.y, axis.z))
                .expected("a finite non-zero vector")
        })?;
        Ok(Pose { tip, axis })
    }
}

/// Closed range of a rotary axis, radians.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct RotaryRange {
    /// Lower limit, rad.
    pub min: f64,
    /// Upper limit, rad.
    pub max: f64,
}

impl RotaryRange {
    /// A range `[min, max]`.
    pub const fn new(min: f64, max: f64) -> Self {
        RotaryRange { min, max }
    }

    /// Whether `v` lies in the range (with a 1e-12 rad allowance for rounding).
    pub fn contains(&self, v: f64) -> bool {
        v >= self.min - 1e-12 && v <= self.max + 1e-12
    }

    /// All values `v + 2πk` inside the range.
    pub fn replicas(&self, v: f64) -> Vec<f64> {
        let mut out = Vec::new();
        if !v.is_finite() {
            return out;
        }
        let k0 = ((self.min - v) / TAU).ceil();
        let mut k = k0 - 1.0;
        while v + k * TAU <= self.max + 1e-12 {
            let c = v + k * TAU;
            if self.contains(c) {
                out.push(c.clamp(self.min, self.max));
            }
            k += 1.0;
            if out.len() > 64 {
                break;
            }
        }
        out
    }
}

/// Principal orientation solutions of one tool axis.
#[derive(Debug, Clone, PartialEq)]
pub struct Orientation {
    /// `(r1, r2)` pairs, each angle in (−π, π].
    pub pairs: Vec<(f64, f64)>,
    /// The tilt angle's distance from the pole, rad (0 at the pole).
    pub pole_distance: f64,
}

/// A five-axis machine's kinematics.
pub trait Kinematics: std::fmt::Debug + Send + Sync {
    /// Short name (`paper-ab`, `ac-trt`, `bc-trt`, `head-head`).
    fn name(&self) -> &'static str;
    /// G-code letters of the five joints, e.g. `["X", "Y", "Z", "A", "C"]`.
    fn axis_names(&self) -> [&'static str; 5];
    /// Ranges of the two rotary joints.
    fn rotary_ranges(&self) -> [RotaryRange; 2];
    /// Joint positions → tool tip and axis in the workpiece frame.
    fn forward(&self, q: &Joints) -> Pose;
    /// Analytic Jacobian of [`Kinematics::forward`].
    fn jacobian(&self, q: &Joints) -> Jacobian;
    /// Principal rotary solutions for a unit tool axis; `free` is used for the free angle at
    /// the pole.
    fn orientation(&self, axis: Vec3, free: f64) -> Orientation;
    /// Linear joints placing the tip at `tip` for rotary angles `(r1, r2)`; `None` where the
    /// machine cannot reach the point with these angles.
    fn linear(&self, tip: Point3, r1: f64, r2: f64) -> Option<[f64; 3]>;
    /// The structural constant `R` of the derivative bounds over the joint box `[lo, hi]`
    /// (see "Derivative bounds" in the module docs): every partial derivative of the tip of
    /// order 1 to 3 taken in the rotary joints only has norm ≤ `R` anywhere in the box.
    fn lever_bound(&self, lo: &Joints, hi: &Joints) -> f64;

    /// All joint solutions of `pose` inside the rotary ranges (free angle 0 at a pole).
    /// No solution is an [`InputError`] naming the pose.
    fn inverse(&self, pose: &Pose) -> Result<Vec<Joints>, InputError> {
        self.inverse_with_free(pose, 0.0).map(|(s, _)| s)
    }

    /// All solutions, with `free` as the free angle at a pole; also returns the pole distance.
    fn inverse_with_free(&self, pose: &Pose, free: f64) -> Result<(Vec<Joints>, f64), InputError> {
        let o = self.orientation(pose.axis, free);
        let [ra, rb] = self.rotary_ranges();
        let mut out = Vec::new();
        for &(p1, p2) in &o.pairs {
            for r1 in ra.replicas(p1) {
                for r2 in rb.replicas(p2) {
                    if let Some([x, y, z]) = self.linear(pose.tip, r1, r2)
                        && [x, y, z].iter().all(|v| v.is_finite())
                    {
                        let q = [x, y, z, r1, r2];
                        if !out.iter().any(|s: &Joints| max_abs_diff(s, &q) < 1e-12) {
                            out.push(q);
                        }
                    }
                }
            }
        }
        if out.is_empty() {
            let n = self.axis_names();
            return Err(InputError::new(
                "tool pose",
                format!(
                    "tip ({:.6}, {:.6}, {:.6}) mm, axis ({:.6}, {:.6}, {:.6})",
                    pose.tip.x, pose.tip.y, pose.tip.z, pose.axis.x, pose.axis.y, pose.axis.z
                ),
            )
            .at(self.name())
            .expected(format!(
                "a pose reachable with {} in [{:.4}, {:.4}] rad and {} in [{:.4}, {:.4}] rad",
                n[3], ra.min, ra.max, n[4], rb.min, rb.max
            )));
        }
        Ok((out, o.pole_distance))
    }

    /// The solution nearest `prev` (least rotary travel, then least linear travel), with
    /// warnings at or near a pole and on large rotary jumps. See the module docs.
    fn inverse_near(
        &self,
        pose: &Pose,
        prev: Option<&Joints>,
        opts: &IkOptions,
    ) -> Result<IkOutcome, InputError> {
        let free_prev = prev.map_or(0.0, |p| p[self.free_axis()]);
        let (sols, pole_distance) = self.inverse_with_free(pose, free_prev)?;
        let best = match prev {
            None => sols
                .iter()
                .min_by(|a, b| (a[3].abs() + a[4].abs()).total_cmp(&(b[3].abs() + b[4].abs())))
                .copied(),
            Some(p) => sols
                .iter()
                .min_by(|a, b| travel(a, p).total_cmp(&travel(b, p)))
                .copied(),
        };
        let Some(joints) = best else {
            return Err(InputError::new("tool pose", format!("{pose:?}")).at(self.name()));
        };
        let mut warnings = Vec::new();
        if pole_distance <= opts.pole_eps {
            warnings.push(IkWarning::AtPole {
                free_axis: self.axis_names()[self.free_axis()].to_owned(),
                kept: joints[self.free_axis()],
            });
        } else if pole_distance < opts.pole_warn {
            warnings.push(IkWarning::NearPole {
                pole_distance,
                free_axis: self.axis_names()[self.free_axis()].to_owned(),
            });
        }
        if let Some(p) = prev {
            for i in 3..5 {
                let d = joints[i] - p[i];
                if d.abs() > opts.flip_threshold {
                    warnings.push(IkWarning::Flip {
                        axis: self.axis_names()[i].to_owned(),
                        delta: d,
                    });
                }
            }
        }
        Ok(IkOutcome { joints, warnings })
    }

    /// Index (3 or 4) of the rotary joint that is free at the pole.
    fn free_axis(&self) -> usize {
        4
    }
}

/// Rotary travel first (weighted heavily), then linear travel, between two joint vectors.
fn travel(a: &Joints, b: &Joints) -> f64 {
    let rot = (a[3] - b[3]).abs() + (a[4] - b[4]).abs();
    let lin = (a[0] - b[0]).abs() + (a[1] - b[1]).abs() + (a[2] - b[2]).abs();
    rot * 1e6 + lin
}

fn max_abs_diff(a: &Joints, b: &Joints) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// Options of [`Kinematics::inverse_near`]. Built from [`Default`] with the `with_*` methods (the
/// struct is `#[non_exhaustive]`: new settings do not break callers).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[non_exhaustive]
pub struct IkOptions {
    /// Pole distance (rad of tilt) below which the free angle is taken as undetermined and kept
    /// from the previous pose. Default 1e-9 rad.
    pub pole_eps: f64,
    /// Pole distance (rad) below which a [`IkWarning::NearPole`] is returned. Default 1°.
    pub pole_warn: f64,
    /// Rotary jump (rad) from the previous pose that is reported as a flip. Default 90°.
    pub flip_threshold: f64,
}

impl Default for IkOptions {
    fn default() -> Self {
        IkOptions {
            pole_eps: 1e-9,
            pole_warn: 1f64.to_radians(),
            flip_threshold: PI / 2.0,
        }
    }
}

option_builders! {
    IkOptions;
    /// Sets [`IkOptions::pole_eps`], rad.
    with_pole_eps => pole_eps: f64;
    /// Sets [`IkOptions::pole_warn`], rad.
    with_pole_warn => pole_warn: f64;
    /// Sets [`IkOptions::flip_threshold`], rad.
    with_flip_threshold => flip_threshold: f64;
}

/// The chosen solution and what the caller should know about it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct IkOutcome {
    /// Joint positions.
    pub joints: Joints,
    /// Warnings (empty in the regular case).
    pub warnings: Vec<IkWarning>,
}

/// Something the caller should know about an inverse-kinematics solution.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum IkWarning {
    /// Exactly at the pole: the free axis is undetermined and kept at its previous value.
    AtPole {
        /// The free rotary axis.
        free_axis: String,
        /// The value kept, rad.
        kept: f64,
    },
    /// Near the pole: the free axis moves fast for small changes of the tool axis.
    NearPole {
        /// Tilt distance from the pole, rad.
        pole_distance: f64,
        /// The ill-conditioned rotary axis.
        free_axis: String,
    },
    /// A rotary axis jumps by more than the flip threshold from the previous pose.
    Flip {
        /// The axis.
        axis: String,
        /// The jump, rad.
        delta: f64,
    },
}

impl std::fmt::Display for IkWarning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            IkWarning::AtPole { free_axis, kept } => write!(
                f,
                "at the pole: {free_axis} is undetermined, kept at {:.4}°",
                kept.to_degrees()
            ),
            IkWarning::NearPole {
                pole_distance,
                free_axis,
            } => write!(
                f,
                "{:.4}° from the pole: {free_axis} moves fast for small tool-axis changes",
                pole_distance.to_degrees()
            ),
            IkWarning::Flip { axis, delta } => {
                write!(f, "{axis} flips by {:.4}°", delta.to_degrees())
            }
        }
    }
}

/// An inverse-kinematics warning at one pose of a path.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PoseWarning {
    /// The pose, 0-based.
    pub pose: usize,
    /// What happened there.
    pub warning: IkWarning,
}

impl std::fmt::Display for PoseWarning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "point {}: {}", self.pose, self.warning)
    }
}

/// Joints along a path and `(pose index, warning)` pairs.
pub type PathIk = (Vec<Joints>, Vec<(usize, IkWarning)>);

/// Inverse kinematics along a path of poses, each solution nearest its predecessor (the first
/// nearest the first off-pole pose when the path starts at a pole). Returns the joints and
/// `(pose index, warning)` pairs.
pub fn inverse_path(
    kin: &dyn Kinematics,
    poses: &[Pose],
    opts: &IkOptions,
) -> Result<PathIk, InputError> {
    let mut out: Vec<Joints> = Vec::with_capacity(poses.len());
    let mut warnings = Vec::new();
    // A path that starts at the pole takes the free angle from its first pose off the pole
    // (looking ahead), so the free axis does not have to swing round in the first interval.
    let mut seed: Option<Joints> = None;
    if let Some(first) = poses.first()
        && kin.orientation(first.axis, 0.0).pole_distance <= opts.pole_eps
        && let Some(next) = poses
            .iter()
            .find(|p| kin.orientation(p.axis, 0.0).pole_distance > opts.pole_eps)
    {
        seed = kin.inverse_near(next, None, opts).ok().map(|o| o.joints);
    }
    for (i, p) in poses.iter().enumerate() {
        let prev = out.last().or(seed.as_ref());
        let o = kin
            .inverse_near(p, prev, opts)
            .map_err(|e| e.at(format!("{} (path point {i})", kin.name())))?;
        warnings.extend(o.warnings.into_iter().map(|w| (i, w)));
        out.push(o.joints);
    }
    Ok((out, warnings))
}

// ---- small 3-D helpers shared by the machines -------------------------------------------

pub(crate) type M3 = [[f64; 3]; 3];
pub(crate) type V3 = [f64; 3];

pub(crate) fn rot_x(t: f64) -> M3 {
    let (s, c) = t.sin_cos();
    [[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]]
}
pub(crate) fn rot_y(t: f64) -> M3 {
    let (s, c) = t.sin_cos();
    [[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]]
}
pub(crate) fn rot_z(t: f64) -> M3 {
    let (s, c) = t.sin_cos();
    [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]]
}
/// Generators `G` with `dR(θ)/dθ = G·R(θ)` (the cross-product matrices of the unit axes).
pub(crate) const GEN_X: M3 = [[0.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]];
pub(crate) const GEN_Y: M3 = [[0.0, 0.0, 1.0], [0.0, 0.0, 0.0], [-1.0, 0.0, 0.0]];
pub(crate) const GEN_Z: M3 = [[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 0.0]];

pub(crate) fn mm(a: &M3, b: &M3) -> M3 {
    let mut r = [[0.0; 3]; 3];
    for (i, row) in r.iter_mut().enumerate() {
        for (j, v) in row.iter_mut().enumerate() {
            *v = (0..3).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    r
}
pub(crate) fn mv(a: &M3, v: &V3) -> V3 {
    [
        a[0][0] * v[0] + a[0][1] * v[1] + a[0][2] * v[2],
        a[1][0] * v[0] + a[1][1] * v[1] + a[1][2] * v[2],
        a[2][0] * v[0] + a[2][1] * v[1] + a[2][2] * v[2],
    ]
}
pub(crate) fn add(a: V3, b: V3) -> V3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
pub(crate) fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
pub(crate) fn scale(a: V3, s: f64) -> V3 {
    [a[0] * s, a[1] * s, a[2] * s]
}
pub(crate) fn p3(v: V3) -> Point3 {
    Point3::new(v[0], v[1], v[2])
}
pub(crate) fn v3(v: V3) -> Vec3 {
    Vec3::new(v[0], v[1], v[2])
}
pub(crate) fn arr_p(p: Point3) -> V3 {
    [p.x, p.y, p.z]
}

/// Fills Jacobian column `j` from a tip derivative and an axis derivative.
pub(crate) fn set_col(jac: &mut Jacobian, j: usize, dtip: V3, daxis: V3) {
    for r in 0..3 {
        jac[r][j] = dtip[r];
        jac[r + 3][j] = daxis[r];
    }
}

/// Wraps an angle into (−π, π].
pub(crate) fn wrap(a: f64) -> f64 {
    let mut r = a.rem_euclid(TAU);
    if r > PI {
        r -= TAU;
    }
    r
}

/// The tilt/swivel closed form shared by all machines. The tool axis is
/// `k = (s_t·f(θ), s_t·g(θ), cos t)`-like: callers pass the cosine of the tilt (`ct`, the
/// component of `k` along the pole) and the two components `(u, v)` that equal
/// `sin t · (cos θ, sin θ)`. Returns the pairs `(t, θ)` and `(−t, θ + π)` and the pole
/// distance `|sin t|` measured as an angle.
pub(crate) fn tilt_swivel(ct: f64, u: f64, v: f64, free: f64) -> (Vec<(f64, f64)>, f64) {
    let st = u.hypot(v);
    let t = st.atan2(ct);
    let pole_distance = t.abs().min((PI - t).abs());
    let th = if st <= 1e-15 { free } else { v.atan2(u) };
    let mut pairs = vec![(wrap(t), wrap(th))];
    if st > 1e-15 {
        pairs.push((wrap(-t), wrap(th + PI)));
    }
    (pairs, pole_distance)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn replicas_cover_the_range() {
        let r = RotaryRange::new(-2.0 * TAU, 2.0 * TAU);
        assert_eq!(r.replicas(0.5).len(), 4);
        let r = RotaryRange::new(-1.0, 1.0);
        assert_eq!(r.replicas(0.5), vec![0.5]);
        assert!(r.replicas(2.0).is_empty());
    }

    #[test]
    fn zero_axis_is_input_error() {
        assert!(Pose::new(Point3::ORIGIN, Vec3::new(0.0, 0.0, 0.0)).is_err());
        assert!(Pose::new(Point3::ORIGIN, Vec3::new(f64::NAN, 0.0, 1.0)).is_err());
        assert!(
            Pose::new(
                Point3::new(f64::INFINITY, 0.0, 0.0),
                Vec3::new(0.0, 0.0, 1.0)
            )
            .is_err()
        );
    }
}
