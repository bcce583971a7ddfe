//! Motion planning: jerk-limited profiles, look-ahead planner, sampling and limit verification.
//!
//! The planner turns a [`Toolpath`] (or any stream of moves, e.g.
//! the G-code reader's) and a [`Machine`] into a timed [`Plan`]:
//! the cycle time every strategy in millpath is judged by.
//!
//! ```
//! use millpath::machine::Machine;
//! use millpath::motion::plan_toolpath;
//! use millpath::motion::table2::square;
//! let plan = plan_toolpath(&square(25.4, 100.0), &Machine::preset("hsm").unwrap()).unwrap();
//! assert!(plan.total_time() > 4.0 * 25.4 / 100.0);
//! ```
//!
//! # Pipeline
//! 0. **Controller model** (`controller`, chosen by the machine profile: `generic`,
//!    `sinumerik`, `linuxcnc`): what the blocks are (the moves, or what LinuxCNC makes of
//!    them: merged, trimmed, blend arcs) and which limits, corner rules and look-ahead apply.
//!    Steps 1–2 below are the `generic` model's rules; steps 3–4 are shared by all models.
//!    The `linuxcnc` model also plans the rotary axes A, B, C of a move
//!    ([`crate::toolpath::Move::rotary`]) in joint space, each its own joint (trivkins), with
//!    the machine's rotary limits; the others plan the X Y Z path.
//! 1. **Geometry** (`path`): lines and arcs/helices exactly as programmed (no flattening),
//!    parametrised by arc length with their first three derivatives.
//! 2. **Limits** (`limits`): each block's path velocity, acceleration and jerk limits — the
//!    axis limits projected onto the path direction on lines; on arcs and helices the
//!    centripetal acceleration `κv²` and the jerk it implies (`κ√(κ²+τ²)v³ + 3κ·v·a_t`)
//!    bound the speed, with a documented share of the axis limits kept for the tangential
//!    direction; the programmed feed and the machine's maximum feed bound the speed. Each
//!    junction gets a speed cap: exact stop, exact path (velocity step within one
//!    interpolation cycle), a circular blend within the path tolerance, or the curvature
//!    step at tangent line→arc junctions spread over one interpolation cycle.
//! 3. **Look-ahead** (`plan`): blocks are grouped into spans joined by knots; a backward and
//!    a forward pass over the whole program with the closed-form inverse of the S-curve
//!    distance make every span feasible.
//! 4. **Profiles** (`profile`): each span gets the time-optimal 7-phase jerk-limited
//!    S-curve between its knot speeds (closed forms for every degenerate case: no cruise,
//!    acceleration limit not reached, trapezoid when jerk is unlimited), checked against its
//!    limits before it is accepted.
//! 5. **Sampling** (`sample`): position, feed and per-axis v/a/j at any time.
//! 6. **Verification** (`verify`): an independent sampler checks every per-axis limit, the
//!    feed and the corner rules; tests require 0 violations.
//!
//! # Precision and range
//! * A rest-to-rest straight move's time equals rsruckig's minimum duration within 1e-9 s
//!   (`tests/motion_ruckig.rs`, 3000 seeded moves, distances 1 µm–2 m, v 1–2000 mm/s,
//!   a 50–50 000 mm/s², j 500–5·10⁶ mm/s³); so does every span between junction speeds,
//!   from `(v0, a = 0)` to `(v1, a = 0)` over any feasible distance (2000 seeded cases,
//!   relative 1e-9).
//! * Span profiles end within 1e-8 (relative) of their length and 1e-9 of their end speed,
//!   and never exceed the span's limits by more than 1e-9 relative ([`profile::SpanProfile::check`]).
//! * With jerk unlimited, plans of exact-stop polylines and tangent line–arc paths are within
//!   1% of an independent time-optimal reference (`tests/motion_topp.rs`).
//! * Every plan of the test corpus sampled at 1 kHz has 0 violations of per-axis v/a/j
//!   (relative 1e-6), feed, and corner rules (`tests/motion_verify.rs`).
//! * Speed: time linear in the number of blocks and, for the verifier, in the cycle time
//!   (samples at its rate); the figures are in BENCHMARKS.md (`benches/planner.rs`,
//!   `benches/estimate.rs`: a 1,000,000-line program read, planned and verified beside
//!   LinuxCNC's interpreter reading it).
//! * Input range: lengths from 1e-12 mm (shorter moves are skipped with zero time), limits
//!   any finite positive values (jerk may be infinite), arcs with radius > 1e-12 mm.
//!
//! # Known conservatism (the time is an upper bound of the model's optimum)
//! * Zero acceleration is forced at knots (see `plan`): exact where the speed touches a cap,
//!   conservative when a short span accelerates through a knot whose cap it does not reach.
//! * On arcs, a fixed share of the axis acceleration and jerk is reserved for the curvature
//!   terms (as the 840D's `CURV_EFFECT_ON_PATH_ACCEL` does): the arc speed cap is
//!   `√(η_a·A·r)` instead of `√(A·r)`, and tangential acceleration on arcs is `(1 − η_a)·A`.
//! * Blends are timed along the sharp corner (longer than the blend) at the blend's speed.
//!
//! The five-axis helpers live in [`five_axis`].

pub(crate) mod controller;
pub mod five_axis;
pub(crate) mod limits;
pub(crate) mod path;
pub(crate) mod plan;
pub(crate) mod profile;
pub(crate) mod sample;
pub(crate) mod stream;
pub mod table2;
pub(crate) mod verify;

pub use plan::{BlockPlan, Plan, PlanOptions, Span, plan_moves, plan_toolpath, plan_toolpath_opt};
pub use profile::{Limits1, SpanProfile, change_distance, rest_to_rest_time};
pub use sample::Sample;
pub use stream::{Chunk, StreamOptions, StreamSummary, plan_stream};
pub use verify::{VerifyOptions, VerifyReport, Violation, ViolationKind, verify_plan};

use crate::error::Result;
use crate::machine::Machine;
use crate::toolpath::Toolpath;

/// What [`cycle_time`] computes, for reports.
pub const CYCLE_TIME_MODEL: &str = "jerk-limited look-ahead planner (motion::plan_toolpath)";

/// Cycle time of a toolpath on `machine`, s: the planner's total time ([`plan_toolpath`]).
pub fn cycle_time(tp: &Toolpath, machine: &Machine) -> Result<f64> {
    Ok(plan_toolpath(tp, machine)?.total_time())
}
