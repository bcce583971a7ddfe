//! What LinuxCNC's canonical layer (`src/emc/task/emccanon.cc`) sends to the planner: the
//! speed and acceleration of each line and arc, and the naive-CAM detector that merges runs of
//! G1 points into one line.
//!
//! # Naive-CAM merging (`see_segment`, `linkable`, `flush_segments`)
//! In `G64` with a merge tolerance `Q` (which defaults to `P`; `G64` alone has none), G1 end
//! points are held while every held point stays within `Q` of the straight line from the last
//! sent point to the newest point (at most 101 points); the first point that would break this
//! sends the held run as one line to its last point. A change of feed or path mode, a rapid or
//! an arc sends the run first. An arc in the XY plane whose chord deviates less than `Q` from
//! it is taken as two such points (its middle and its end).
//!
//! # Rotary axes (`getStraightVelocity`, `getStraightAcceleration`, `see_segment`)
//! A move is *cartesian* when X, Y or Z moves and *angular* when A, B or C does. Its length
//! (`dtot`, the segment's `target`) is the X Y Z distance when it is cartesian, else the
//! rotary chord `√(ΔA² + ΔB² + ΔC²)`. Each moving axis `i` needs at least `|dᵢ|/vᵢ` s at its
//! velocity limit and `|dᵢ|/aᵢ` s² at its acceleration limit, so the path speed is
//! `dtot / maxᵢ(|dᵢ|/vᵢ)` and the path acceleration `dtot / maxᵢ(|dᵢ|/aᵢ)` over all six
//! axes: a rotary axis that must turn far on a short X Y Z move bounds it. The feed caps the
//! speed (on an angular-only move the angular feed, degrees per minute). A G1 point that
//! turns a rotary axis is never merged: it goes alone as one line. A rotary axis the
//! machine has no limits for does not bound anything. A rotary-only segment is measured in
//! degrees here (its length, speed and acceleration), LinuxCNC's units for it: the blend
//! rules compare its speeds with its neighbours' mm/s as LinuxCNC does.

use super::circle::Circle;
use super::queue::{ROT_FUZZ, Shape, Tc, Term, turn};
use crate::geom::Point3;
use crate::machine::{AxisLimits, Machine};
use crate::motion::path::BlockGeometry;
use crate::toolpath::{Corner, Move, MoveKind, Plane, Rotary};

/// `CART_FUZZ`: axis displacements below it do not count.
const CART_FUZZ: f64 = 1e-9;
/// `chained_points.size() > 100` stops a run.
const MAX_CHAIN: usize = 100;

/// The path mode of a move: LinuxCNC's termination condition, `G64 P` and `G64 Q`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Mode {
    pub term: Term,
    pub tolerance: f64,
    pub merge: f64,
}

impl Mode {
    /// The mode of `corner`; `Corner::Machine` is `G64 P` with the machine's path tolerance.
    pub fn of(corner: Corner, machine: &Machine) -> Mode {
        let blend = |tolerance: f64, merge: f64| Mode {
            term: Term::Parabolic,
            tolerance,
            merge,
        };
        match corner {
            Corner::ExactStop => Mode {
                term: Term::Stop,
                tolerance: 0.0,
                merge: 0.0,
            },
            Corner::ExactPath => Mode {
                term: Term::Exact,
                tolerance: 0.0,
                merge: 0.0,
            },
            Corner::Machine => blend(machine.path_tolerance, machine.path_tolerance),
            Corner::Blend(t) => blend(t, t),
            Corner::BlendMerge { tolerance, merge } => blend(tolerance, merge),
        }
    }
}

/// `getStraightVelocity` / `getStraightAcceleration`: the largest path speed and
/// acceleration of a straight displacement `d` (X Y Z in mm) turning the rotary axes by `r`
/// (rad) under per-axis bounds (`None` for a rotary axis without one), along `dtot` (the X Y Z
/// length, or the rotary chord when X Y Z do not move); 0 when no axis bounds it.
fn straight(d: [f64; 3], r: [f64; 3], bounds: [f64; 3], rot: [Option<f64>; 3]) -> f64 {
    let tmax = time_of(d, bounds).max(rotary_time(r, rot));
    let dtot = length(d, r);
    if tmax > 0.0 { dtot / tmax } else { 0.0 }
}

/// The segment's length (`dtot`, `pmLine9Target`): X Y Z, or the rotary chord.
fn length(d: [f64; 3], r: [f64; 3]) -> f64 {
    let cartesian = d.iter().any(|x| x.abs() >= CART_FUZZ);
    let v = if cartesian { d } else { r };
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

/// The largest `|rᵢ|/bᵢ` over the rotary axes that turn and have a bound.
fn rotary_time(r: [f64; 3], bounds: [Option<f64>; 3]) -> f64 {
    r.iter()
        .zip(bounds)
        .filter(|(x, _)| x.abs() >= ROT_FUZZ)
        .filter_map(|(x, b)| b.map(|b| x.abs() / b))
        .fold(0.0, f64::max)
}

fn rotary_bounds(m: &Machine, f: impl Fn(&AxisLimits) -> f64) -> [Option<f64>; 3] {
    m.rotary.map(|r| r.as_ref().map(&f))
}

/// The segment of a straight move from `from` (rotary axes at `r0`) to `to` (at `r1`)
/// (`flush_segments` for feeds, `STRAIGHT_TRAVERSE` for rapids), or `None` when it does not
/// move. `feed` is mm/s, or rad/s on a rotary-only move.
pub(super) fn line(
    (from, r0): (Point3, Rotary),
    (to, r1): (Point3, Rotary),
    feed: f64,
    rapid: bool,
    m: &Machine,
) -> Option<Tc> {
    let d = (to - from).to_array();
    let r = turn(r0, r1);
    let vb = if rapid {
        m.rapid
    } else {
        m.axes.map(|a| a.max_velocity)
    };
    let rv = rotary_bounds(m, |a| a.max_velocity);
    let ra = rotary_bounds(m, |a| a.max_acceleration);
    let ini_maxvel = straight(d, r, vb, rv);
    let acc = straight(d, r, m.axes.map(|a| a.max_acceleration), ra);
    let vel = if rapid {
        ini_maxvel
    } else {
        feed.min(ini_maxvel)
    };
    let mut target = length(d, r);
    let (mut vel, mut ini_maxvel, mut acc) = (vel, ini_maxvel, acc);
    if !d.iter().any(|x| x.abs() >= CART_FUZZ) {
        // A rotary-only segment in LinuxCNC's user units, degrees: its speeds meet its
        // neighbours' mm/s in the blend rules as they do in LinuxCNC.
        for x in [&mut target, &mut vel, &mut ini_maxvel, &mut acc] {
            *x = x.to_degrees();
        }
    }
    if vel <= 0.0 || acc <= 0.0 || target < 1e-12 {
        return None;
    }
    let mut tc = Tc::new(
        Shape::Line {
            start: from,
            end: to,
        },
        target,
        vel,
        ini_maxvel,
        acc,
    );
    tc.traverse = rapid;
    tc.rot = (r0, r1);
    Some(tc)
}

/// The segment of an arc (`ARC_FEED` and `tpAddCircle`) turning the rotary axes from `r0`
/// to `r1` (they bound its speed and acceleration as on a line).
pub(super) fn arc(
    g: &BlockGeometry,
    (from, rot0): (Point3, Rotary),
    (to, rot1): (Point3, Rotary),
    feed: f64,
    m: &Machine,
) -> Option<Tc> {
    let BlockGeometry::Helix {
        plane,
        sweep,
        r0,
        r1,
        dw,
        ..
    } = *g
    else {
        return None;
    };
    let c = Circle::of(g)?;
    let (i1, i2, _) = match plane {
        Plane::Xy => (0, 1, 2),
        Plane::Zx => (2, 0, 1),
        Plane::Yz => (1, 2, 0),
    };
    let full = sweep.abs();
    let spiral = r1 - r0;
    let dr = spiral / full;
    let min_radius = r0.min(r1);
    let r_eff = dr.hypot(min_radius);
    let v_axes = m.axes[i1].max_velocity.min(m.axes[i2].max_velocity);
    let a_axes = m.axes[i1].max_acceleration.min(m.axes[i2].max_acceleration);
    let a_normal = a_axes * 3f64.sqrt() / 2.0;
    let v_planar = (a_normal * r_eff).sqrt().min(v_axes);
    let d = (to - from).to_array();
    let r = turn(rot0, rot1);
    let t_motion = time_of(d, m.axes.map(|a| a.max_velocity))
        .max(rotary_time(r, rotary_bounds(m, |a| a.max_velocity)));
    let spiral_length = (min_radius * full).hypot(spiral);
    let total = spiral_length.hypot(dw);
    let t_max = t_motion.max(spiral_length / v_planar);
    let v_max = total / t_max;
    let tt_motion = time_of(d, m.axes.map(|a| a.max_acceleration))
        .max(rotary_time(r, rotary_bounds(m, |a| a.max_acceleration)));
    let tt_max = tt_motion.max(spiral_length / a_axes);
    let a_max = total / tt_max;
    let vel = feed.min(v_max);
    if !(vel > 0.0 && a_max > 0.0 && v_max.is_finite()) {
        return None;
    }
    let mut tc = Tc::new(Shape::Circle(c), g.length(), vel, v_max, a_max);
    tc.rot = (rot0, rot1);
    Some(tc)
}

/// The largest `|dᵢ|/bᵢ` over the axes that move.
fn time_of(d: [f64; 3], bounds: [f64; 3]) -> f64 {
    d.iter()
        .zip(bounds)
        .filter(|(x, _)| x.abs() >= CART_FUZZ)
        .map(|(x, b)| x.abs() / b)
        .fold(0.0, f64::max)
}

/// `chord_deviation` of an XY arc: (deviation of the chord, middle point).
pub(super) fn chord_deviation(from: Point3, m: &Move) -> Option<(f64, Point3)> {
    let MoveKind::Arc {
        center,
        plane: Plane::Xy,
        ccw,
        ..
    } = m.kind
    else {
        return None;
    };
    let (sx, sy, ex, ey, cx, cy) = (from.x, from.y, m.to.x, m.to.y, center.x, center.y);
    let th1 = (sy - cy).atan2(sx - cx);
    let mut th2 = (ey - cy).atan2(ex - cx);
    let r = (sy - cy).hypot(sx - cx);
    let tau = 2.0 * std::f64::consts::PI;
    if ccw {
        for _ in 0..2 {
            if th2 - th1 <= 1e-5 {
                th2 += tau;
            }
        }
    } else {
        for _ in 0..2 {
            if th2 - th1 >= -1e-5 {
                th2 -= tau;
            }
        }
    }
    let included = (th2 - th1).abs();
    let mid = (th2 + th1) / 2.0;
    let p = Point3::new(
        cx + r * mid.cos(),
        cy + r * mid.sin(),
        (from.z + m.to.z) / 2.0,
    );
    Some((r * (1.0 - (included / 2.0).cos()), p))
}

/// The run of G1 points held by the naive-CAM detector.
#[derive(Debug, Clone, Default)]
pub(super) struct Chain {
    /// The last point sent (`canon.endPoint`), with its rotary axes.
    pub start: (Point3, Rotary),
    /// Held points (with their rotary axes) and the move each came from.
    pub points: Vec<((Point3, Rotary), usize, Move)>,
}

impl Chain {
    /// `linkable`: may `p` (rotary axes at `r`) join the run under merge tolerance `tol`?
    /// Not when it turns the rotary axes from the last held point.
    pub fn linkable(&self, (p, r): (Point3, Rotary), tol: f64) -> bool {
        let start = self.start.0;
        if tol == 0.0 || self.points.len() > MAX_CHAIN || p == start {
            return false;
        }
        if self.points.last().is_some_and(|((_, lr), _, _)| *lr != r) {
            return false;
        }
        let mv = p - start;
        let mm = mv.dot(mv);
        self.points.iter().all(|((q, _), _, _)| {
            let t0 = (mv.dot(*q - start) / mm).clamp(0.0, 1.0);
            (*q - (start + mv * t0)).length() <= tol
        })
    }
}
