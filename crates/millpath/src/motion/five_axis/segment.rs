//! The five-axis planner's shared vocabulary: the feed and joint [`Limits`], a [`KnotState`]
//! (joint positions, velocities, accelerations at a knot) and a [`Segment`] (five quintics of
//! one duration between two knots). [`super::min_time`] plans with them and
//! [`super::certify`] proves bounds on them; both import this file, neither the other's types.

use super::quintic::{End, Quintic};
use crate::error::{InputError, require_positive};
use crate::machine::kinematics::{Joints, Kinematics};
use serde::{Deserialize, Serialize};

/// Feed and per-joint limits (mm, rad, s).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Limits {
    /// Tool-tip speed in the workpiece frame, mm/s.
    pub feed: f64,
    /// Joint velocity limits (mm/s ×3, rad/s ×2).
    pub vel: [f64; 5],
    /// Joint acceleration limits.
    pub acc: [f64; 5],
    /// Joint jerk limits.
    pub jerk: [f64; 5],
}

impl Limits {
    /// The paper's equation (11), in mm: feed 30 mm/s; linear 500 mm/s, 20 000 mm/s²,
    /// 200 000 mm/s³; rotary 0.5 rad/s, 20 rad/s², 200 rad/s³.
    pub fn paper() -> Self {
        Limits {
            feed: 30.0,
            vel: [500.0, 500.0, 500.0, 0.5, 0.5],
            acc: [20_000.0, 20_000.0, 20_000.0, 20.0, 20.0],
            jerk: [200_000.0, 200_000.0, 200_000.0, 200.0, 200.0],
        }
    }

    /// Every limit finite and > 0, or an [`InputError`] naming it.
    pub fn validate(&self, origin: &str) -> Result<(), InputError> {
        require_positive("feed limit", self.feed, origin)?;
        for (name, arr) in [
            ("velocity", &self.vel),
            ("acceleration", &self.acc),
            ("jerk", &self.jerk),
        ] {
            for (i, &v) in arr.iter().enumerate() {
                require_positive(&format!("{name} limit of joint {i}"), v, origin)?;
            }
        }
        Ok(())
    }
}

/// Position, velocity and acceleration of all five joints.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct KnotState {
    /// Joint positions.
    pub q: Joints,
    /// Joint velocities.
    pub v: Joints,
    /// Joint accelerations.
    pub a: Joints,
}

/// One interval: five quintics of a common duration.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Segment {
    /// Per-joint quintics.
    pub axes: [Quintic; 5],
    /// Duration, s.
    pub duration: f64,
}

impl Segment {
    /// The interval from `s0` to `s1` in `duration` seconds.
    pub fn new(s0: &KnotState, s1: &KnotState, duration: f64) -> Segment {
        let axes = std::array::from_fn(|i| {
            Quintic::from_ends(
                End {
                    q: s0.q[i],
                    v: s0.v[i],
                    a: s0.a[i],
                },
                End {
                    q: s1.q[i],
                    v: s1.v[i],
                    a: s1.a[i],
                },
                duration,
            )
        });
        Segment { axes, duration }
    }

    /// `[pos, vel, acc, jerk]` of every joint at `t`.
    pub fn eval(&self, t: f64) -> [Joints; 4] {
        let mut out = [[0.0; 5]; 4];
        for (i, ax) in self.axes.iter().enumerate() {
            let e = ax.eval(t);
            for k in 0..4 {
                out[k][i] = e[k];
            }
        }
        out
    }

    /// Tool-tip speed in the workpiece frame at `t`, mm/s.
    pub fn feed(&self, kin: &dyn Kinematics, t: f64) -> f64 {
        let [q, v, _, _] = self.eval(t);
        let j = kin.jacobian(&q);
        let mut s2 = 0.0;
        for row in j.iter().take(3) {
            let d: f64 = row.iter().zip(&v).map(|(a, b)| a * b).sum();
            s2 += d * d;
        }
        s2.sqrt()
    }
}
