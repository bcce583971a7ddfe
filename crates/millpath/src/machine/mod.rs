//! Machines: per-axis limits, presets, TOML profiles, kinematics.
//!
//! A [`Machine`] is what the motion planner ([`crate::motion`]) needs to know about a
//! three-axis Cartesian machine: per-axis velocity, acceleration and jerk limits, the maximum
//! programmed feed, the rapid velocity per axis, the path tolerance used for corner blending
//! and the controller's interpolation cycle. Everything is stored in mm, s (feeds in mm/s).
//!
//! # Presets
//!
//! | preset | v_max x/y/z (mm/s) | a_max (mm/s²) | j_max (mm/s³) | max feed (mm/s) | rapid (mm/s) | tolerance (mm) | IPO (ms) | controller |
//! |---|---|---|---|---|---|---|---|---|
//! | `hsm` | 500 / 500 / 500 | 4500 | 175 000 | 500 | 500 | 0.01 | 2 | sinumerik |
//! | `linuxcnc-sim` | 101.6 (4 in/s) | 2540 (100 in/s²) | unlimited | 30.48 (1.2 in/s) | 30.48 | 0.0254 (0.001 in) | 1 | generic |
//! | `linuxcnc-time` | 500 | 2000 | unlimited | 866 (500·√3) | 500 | 0 (G64: no limit) | 1 | linuxcnc |
//! | `router` | 250 / 250 / 100 | 500 / 500 / 300 | 10 000 / 10 000 / 5 000 | 200 | 250 / 250 / 100 | 0.05 | 1 | generic |
//!
//! Where the numbers come from:
//!
//! * **`hsm`** — a Huron-class high-speed vertical mill with a Siemens 840D, the machine of the
//!   adaptive-spiral paper's Table 2, planned by the `sinumerik` controller model. Rapid
//!   30 m/min (500 mm/s) is the published class of such machines (Huron KX/MX high-speed
//!   series: 30–40 m/min rapids, 3–6 m/s²). Axis acceleration 4.5 m/s², jerk 175 m/s³ (within
//!   the 50–500 m/s³ the 840D's `MAX_AX_JERK`, MD32431, is set to on such machines), a 0.8
//!   share of the acceleration for the curvature on arcs (`CURV_EFFECT_ON_PATH_ACCEL`,
//!   MD20602) and 0.03 s of settling at each exact stop are fitted to Table 2 (see
//!   [`crate::motion::table2`] for the fit and its residuals: mean 2.7 %, max 9.9 %). Path
//!   tolerance 0.01 mm (a typical G642/`CYCLE832` finishing tolerance; the paper does not give
//!   the 840D's continuous-path settings). Interpolation cycle 2 ms (the 840D's IPO cycle is
//!   typically 2–4 ms, MD10071).
//! * **`linuxcnc-sim`** — LinuxCNC's sample simulator configuration
//!   `configs/sim/axis/axis.ini` (inch units): every axis `MAX_VELOCITY = 4` in/s,
//!   `MAX_ACCELERATION = 100.0` in/s², `[TRAJ] MAX_LINEAR_VELOCITY = 1.2` in/s (which caps
//!   every move, rapids included, so it is both the maximum feed and the rapid here),
//!   `SERVO_PERIOD = 1000000` ns. LinuxCNC's planner is trapezoidal: jerk unlimited. The path
//!   tolerance 0.001 in is the usual `G64 P0.001`.
//! * **`linuxcnc-time`** — the machine of `../shared/tools/linuxcnc-time` (LinuxCNC 2.9's own
//!   motion controller on a simulated trivkins XYZ machine): every axis `MAX_VELOCITY = 500`
//!   mm/s and `MAX_ACCELERATION = 2000` mm/s², `[TRAJ]` limits √3 times those (never binding
//!   on three axes; `max_feed` is `[TRAJ] MAX_LINEAR_VELOCITY`), servo period 1 ms, jerk
//!   unlimited (LinuxCNC's planner is trapezoidal), planned by the `linuxcnc` controller
//!   model. Path tolerance 0: a program's `G64` without P blends without a tolerance limit,
//!   as LinuxCNC does (a program that gives no path mode runs in G64). Rotary axes A, B and
//!   C, each its own joint, at 90 deg/s and 900 deg/s² (the tool's `LCNC_AXES=XYZAC` or
//!   `XYZBC` defaults).
//! * **`router`** — a low-acceleration hobby router (steel-belt or lead-screw gantry): 15 m/min
//!   rapids in XY, 6 m/min in Z, 0.5 m/s² in XY, 0.3 m/s² in Z, jerk 10 m/s³ (XY) and
//!   5 m/s³ (Z), the class of GRBL-based routers' `$120..$122` settings.
//!
//! # TOML profiles
//!
//! ```toml
//! name = "my-mill"
//! description = "…"       # optional
//! units = "mm"            # "mm" or "in": every length below is in these units
//! max_feed = 250.0        # units/s
//! path_tolerance = 0.01   # units; 0 = none stated (the controller's default)
//! ipo_cycle = 0.002       # s (optional, default 0.002)
//! curvature_accel_share = 0.75   # optional, default 0.75
//! curvature_jerk_share = 0.75    # optional, default 0.75
//! controller = "generic"  # optional: "generic" (default), "sinumerik" or "linuxcnc"
//! exact_stop_time = 0.0   # s, optional: settling at each exact stop (not linuxcnc)
//! sync_wait = 0.0         # s, optional: wait at spindle/coolant/tool commands (linuxcnc only)
//! tool_change_time = 0.0  # s, optional: a tool change (M6), from rest to rest
//!
//! [axes.x]
//! max_velocity = 500.0      # units/s
//! max_acceleration = 2000.0 # units/s²
//! max_jerk = 100000.0       # units/s³, or "unlimited"
//! rapid = 500.0             # units/s (optional, default max_velocity)
//! # [axes.y] and [axes.z] alike
//!
//! [axes.c]                  # optional rotary axes [axes.a], [axes.b], [axes.c]
//! max_velocity = 90.0       # deg/s (degrees whatever `units` says)
//! max_acceleration = 900.0  # deg/s²
//! max_jerk = "unlimited"    # deg/s³ (optional, default "unlimited")
//! ```
//! Every limit must be a finite number > 0 (jerk may be `"unlimited"`); errors name the key.
//! A key that is not one of these (a misspelt limit, which would otherwise fall back to its
//! default without a word) is refused, naming the key and the file.

pub mod kinematics;
pub(crate) mod rotary;

use crate::error::InputError;
use serde::{Deserialize, Serialize};

pub use crate::geom::MM_PER_INCH;
pub use rotary::{
    MAX_ROTARY_ACCELERATION_DEG, MAX_ROTARY_JERK_DEG, MAX_ROTARY_VELOCITY_DEG, ROTARY_NAMES,
    rotary_limits,
};

/// The limits of one axis (a rotary axis's in rad/s, rad/s², rad/s³).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct AxisLimits {
    /// Maximum axis velocity in mm/s.
    pub max_velocity: f64,
    /// Maximum axis acceleration in mm/s².
    pub max_acceleration: f64,
    /// Maximum axis jerk in mm/s³ (`f64::INFINITY` for unlimited: trapezoidal profiles).
    pub max_jerk: f64,
}

/// The controller whose trajectory planner a machine's cycle times reproduce: the rules for
/// corners, arcs, short blocks and look-ahead (see `crate::motion::controller`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Controller {
    /// millpath's own jerk-limited look-ahead planner (every limit kept, nothing else).
    #[default]
    Generic,
    /// A Siemens 840D-class controller: jerk-limited, G64/G642 rounding within the path
    /// tolerance, fitted to the adaptive-spiral paper's Table 2.
    Sinumerik,
    /// LinuxCNC 2.9's trajectory planner (trapezoidal, blend arcs, its look-ahead depth).
    #[serde(rename = "linuxcnc")]
    LinuxCnc,
}

impl Controller {
    /// The names a profile's `controller` key takes.
    pub const NAMES: [&'static str; 3] = ["linuxcnc", "sinumerik", "generic"];

    /// The controller of a profile's `controller` value.
    pub fn from_name(name: &str) -> Option<Controller> {
        match name {
            "generic" => Some(Controller::Generic),
            "sinumerik" => Some(Controller::Sinumerik),
            "linuxcnc" => Some(Controller::LinuxCnc),
            _ => None,
        }
    }

    /// The profile name of this controller.
    pub fn name(self) -> &'static str {
        match self {
            Controller::Generic => "generic",
            Controller::Sinumerik => "sinumerik",
            Controller::LinuxCnc => "linuxcnc",
        }
    }
}

/// A three-axis Cartesian machine as the motion planner sees it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Machine {
    /// Name (preset name or the profile's `name`).
    pub name: String,
    /// One-line description.
    pub description: String,
    /// X, Y, Z limits.
    pub axes: [AxisLimits; 3],
    /// Maximum programmed feed (path velocity of feed moves) in mm/s.
    pub max_feed: f64,
    /// Rapid velocity per axis in mm/s (G0 moves are interpolated linearly).
    pub rapid: [f64; 3],
    /// Corner blending tolerance in mm: the largest distance between the programmed corner
    /// and the blended path. 0 means the machine states none: a program that states no path
    /// mode is timed at the controller's default (exact stop at every non-tangent corner;
    /// on LinuxCNC, `G64` without P: blends without a limit), and the programs millpath
    /// writes state their own (the pocket's and the job's 0.01 mm, a profile's or contour's
    /// `--tolerance`); `--tolerance 0` asks for exact stop.
    pub path_tolerance: f64,
    /// The controller's interpolation cycle in s: acceleration steps at curvature jumps are
    /// spread over one cycle (see [`crate::motion`]).
    pub ipo_cycle: f64,
    /// Share of the axis acceleration available for centripetal acceleration on arcs (the rest
    /// is for tangential acceleration), in (0, 1).
    pub curvature_accel_share: f64,
    /// Share of the axis jerk available for the jerk that curvature implies on arcs, in (0, 1).
    pub curvature_jerk_share: f64,
    /// The controller model the planner follows.
    #[serde(default)]
    pub controller: Controller,
    /// Time in s the controller waits at each exact stop and at the program's end for the
    /// axes to settle in position (the 840D's exact-stop window). A property of the machine,
    /// not of the program's dialect: every exact stop the reader finds
    /// ([`crate::toolpath::Corner::ExactStop`]: LinuxCNC's G61.1, Fanuc's G61/G09,
    /// Sinumerik's G60/G9) and every corner under a zero tolerance costs it, on the
    /// `generic` and `sinumerik` models; the `linuxcnc` model has none (LinuxCNC's planner
    /// waits for no in-position window).
    #[serde(default)]
    pub exact_stop_time: f64,
    /// Time in s a LinuxCNC controller's task waits, at rest, at a spindle, coolant or tool
    /// command in the program (its I/O controller's cycle, `[EMCIO] CYCLE_TIME`); the
    /// `linuxcnc` model only.
    #[serde(default)]
    pub sync_wait: f64,
    /// Time in s a tool change (`M6`) takes, from the axes coming to rest to the next move
    /// (the changer's cycle, spindle stop and start included). The reader charges it as a
    /// dwell at every `M6` ([`crate::gcode::ReaderOptions::tool_change_time`]).
    #[serde(default)]
    pub tool_change_time: f64,
    /// The rotary axes A, B, C (limits in rad/s, rad/s², rad/s³; `None`: the machine has no
    /// such axis, and its words take no time). See module `rotary` for the profile's tables.
    #[serde(default)]
    pub rotary: [Option<AxisLimits>; 3],
}

/// The `hsm` preset's tool change time, s: a chip-to-chip time of a high-speed mill's
/// disc changer with the spindle's stop and run-up (makers quote 2.5–6 s).
pub const HSM_TOOL_CHANGE_TIME: f64 = 4.0;

/// The `router` preset's tool change time, s: a hobby router's tool is changed by hand
/// (`M6` pauses for the operator, who changes the collet and touches off the length).
pub const ROUTER_TOOL_CHANGE_TIME: f64 = 60.0;

/// The `hsm` preset's exact-stop settling time, s (fitted to Table 2, see
/// [`crate::motion::table2`]).
pub const HSM_EXACT_STOP_TIME: f64 = 0.03;

/// The `linuxcnc-time` preset's wait at a spindle, coolant or tool command, s: its
/// `[EMCIO] CYCLE_TIME` (0.1 s). Measured on `../shared/tools/linuxcnc-time`: 20 coolant
/// commands between moves of 3–17 mm at F3000 cost 0.097 s each on average (2 runs, 7.505
/// and 7.511 s); the wait depends on the phase of the I/O cycle (between 0 and 0.3 s seen
/// on single commands), so a program with few of them varies by up to that from run to run.
pub const LINUXCNC_TIME_SYNC_WAIT: f64 = 0.1;

/// The `linuxcnc-time` preset's rotary axes A, B and C: 90 deg/s and 900 deg/s² (the
/// `LCNC_ROT_VMAX` and `LCNC_ROT_AMAX` defaults of `../shared/tools/linuxcnc-time`).
pub const LINUXCNC_TIME_ROTARY: [f64; 2] = [90.0, 900.0];

/// The largest velocity (axis, rapid or feed) a machine may have: 1 km/s, in mm/s.
pub const MAX_VELOCITY: f64 = 1e6;
/// The largest axis acceleration: 1e9 mm/s² (100 000 g).
pub const MAX_ACCELERATION: f64 = 1e9;
/// The largest finite axis jerk, mm/s³ (jerk may also be unlimited).
pub const MAX_JERK: f64 = 1e13;

impl Machine {
    /// The names of the built-in presets.
    pub const PRESET_NAMES: [&'static str; 4] = ["hsm", "linuxcnc-sim", "router", "linuxcnc-time"];

    /// A built-in preset by name (see the module docs for the values and their sources).
    pub fn preset(name: &str) -> Result<Machine, InputError> {
        let axis = |v: f64, a: f64, j: f64| AxisLimits {
            max_velocity: v,
            max_acceleration: a,
            max_jerk: j,
        };
        match name {
            "hsm" => Ok(Machine {
                name: "hsm".into(),
                description: "high-speed 3-axis aerospace mill, Siemens 840D-class controller \
                              (Huron, the adaptive-spiral paper's Table 2)"
                    .into(),
                axes: [axis(500.0, 4500.0, 175_000.0); 3],
                max_feed: 500.0,
                rapid: [500.0; 3],
                path_tolerance: 0.01,
                ipo_cycle: 0.002,
                curvature_accel_share: 0.8,
                curvature_jerk_share: 0.75,
                controller: Controller::Sinumerik,
                exact_stop_time: HSM_EXACT_STOP_TIME,
                sync_wait: 0.0,
                tool_change_time: HSM_TOOL_CHANGE_TIME,
                rotary: [None; 3],
            }),
            "linuxcnc-sim" => {
                let v = 4.0 * MM_PER_INCH;
                let a = 100.0 * MM_PER_INCH;
                Ok(Machine {
                    name: "linuxcnc-sim".into(),
                    description: "LinuxCNC configs/sim/axis/axis.ini limits, trapezoidal".into(),
                    axes: [axis(v, a, f64::INFINITY); 3],
                    max_feed: 1.2 * MM_PER_INCH,
                    rapid: [1.2 * MM_PER_INCH; 3],
                    path_tolerance: 0.001 * MM_PER_INCH,
                    ipo_cycle: 0.001,
                    curvature_accel_share: 0.75,
                    curvature_jerk_share: 0.75,
                    controller: Controller::Generic,
                    exact_stop_time: 0.0,
                    sync_wait: 0.0,
                    tool_change_time: 0.0,
                    rotary: [None; 3],
                })
            }
            "linuxcnc-time" => Ok(Machine {
                name: "linuxcnc-time".into(),
                description: "LinuxCNC 2.9 trajectory planner, the machine of \
                              ../shared/tools/linuxcnc-time (500 mm/s, 2000 mm/s², 1 ms servo)"
                    .into(),
                axes: [axis(500.0, 2000.0, f64::INFINITY); 3],
                max_feed: 500.0 * 3f64.sqrt(),
                rapid: [500.0; 3],
                path_tolerance: 0.0,
                ipo_cycle: 0.001,
                curvature_accel_share: 0.75,
                curvature_jerk_share: 0.75,
                controller: Controller::LinuxCnc,
                exact_stop_time: 0.0,
                sync_wait: LINUXCNC_TIME_SYNC_WAIT,
                tool_change_time: 0.0,
                rotary: [Some(rotary_limits(
                    LINUXCNC_TIME_ROTARY[0],
                    LINUXCNC_TIME_ROTARY[1],
                    f64::INFINITY,
                )); 3],
            }),
            "router" => Ok(Machine {
                name: "router".into(),
                description: "low-acceleration hobby router".into(),
                axes: [
                    axis(250.0, 500.0, 10_000.0),
                    axis(250.0, 500.0, 10_000.0),
                    axis(100.0, 300.0, 5_000.0),
                ],
                max_feed: 200.0,
                rapid: [250.0, 250.0, 100.0],
                path_tolerance: 0.05,
                ipo_cycle: 0.001,
                curvature_accel_share: 0.75,
                curvature_jerk_share: 0.75,
                controller: Controller::Generic,
                exact_stop_time: 0.0,
                sync_wait: 0.0,
                tool_change_time: ROUTER_TOOL_CHANGE_TIME,
                rotary: [None; 3],
            }),
            _ => Err(InputError::new("machine preset", name)
                .expected(format!("one of {}", Self::PRESET_NAMES.join(", ")))),
        }
    }

    /// All built-in presets.
    pub fn presets() -> Vec<Machine> {
        Self::PRESET_NAMES
            .iter()
            .filter_map(|n| Machine::preset(n).ok())
            .collect()
    }

    /// True when every axis has a finite jerk limit.
    pub fn jerk_limited(&self) -> bool {
        self.axes.iter().all(|a| a.max_jerk.is_finite())
    }

    /// Checks every value; `origin` names where the machine came from.
    ///
    /// Limits are bounded above ([`MAX_VELOCITY`], [`MAX_ACCELERATION`], [`MAX_JERK`], an
    /// interpolation cycle of at most 1 s, a path tolerance within ±1e6 mm): far beyond any
    /// machine, and small enough that the planner's squares and cubes of them stay finite (a
    /// machine with every limit at 1e300 planned a move whose samples ended 43 mm from its
    /// end point; found by the `planner` fuzzer).
    pub fn validate(&self, origin: &str) -> Result<(), InputError> {
        let pos = |what: String, v: f64, max: f64, unit: &str| -> Result<(), InputError> {
            if v.is_finite() && v > 0.0 && v <= max {
                Ok(())
            } else {
                Err(InputError::new(what, v)
                    .at(origin)
                    .expected(format!("a finite number > 0 and at most {max:e} {unit}")))
            }
        };
        for (axis, name) in self.axes.iter().zip(["x", "y", "z"]) {
            pos(
                format!("axes.{name}.max_velocity"),
                axis.max_velocity,
                MAX_VELOCITY,
                "mm/s",
            )?;
            pos(
                format!("axes.{name}.max_acceleration"),
                axis.max_acceleration,
                MAX_ACCELERATION,
                "mm/s²",
            )?;
            if axis.max_jerk.is_nan()
                || axis.max_jerk <= 0.0
                || (axis.max_jerk.is_finite() && axis.max_jerk > MAX_JERK)
            {
                return Err(
                    InputError::new(format!("axes.{name}.max_jerk"), axis.max_jerk)
                        .at(origin)
                        .expected(format!(
                            "a finite number > 0 and at most {MAX_JERK:e} mm/s³, or \"unlimited\""
                        )),
                );
            }
        }
        for (r, name) in self.rapid.iter().zip(["x", "y", "z"]) {
            pos(format!("axes.{name}.rapid"), *r, MAX_VELOCITY, "mm/s")?;
        }
        pos("max_feed".into(), self.max_feed, MAX_VELOCITY, "mm/s")?;
        pos("ipo_cycle".into(), self.ipo_cycle, 1.0, "s")?;
        for (what, t) in [
            ("exact_stop_time", self.exact_stop_time),
            ("sync_wait", self.sync_wait),
        ] {
            if !(t.is_finite() && (0.0..=10.0).contains(&t)) {
                return Err(InputError::new(what, t)
                    .at(origin)
                    .expected("a time in [0, 10] s"));
            }
        }
        rotary::check_rotary(&self.rotary, origin)?;
        let t = self.tool_change_time;
        if !(t.is_finite() && (0.0..=3600.0).contains(&t)) {
            return Err(InputError::new("tool_change_time", t)
                .at(origin)
                .expected("a time in [0, 3600] s"));
        }
        let max_tol = crate::geom::MAX_COORDINATE_MM;
        if !(self.path_tolerance.is_finite()
            && self.path_tolerance >= 0.0
            && self.path_tolerance <= max_tol)
        {
            return Err(InputError::new("path_tolerance", self.path_tolerance)
                .at(origin)
                .expected(format!("a finite number >= 0 and at most {max_tol:e} mm")));
        }
        for (what, v) in [
            ("curvature_accel_share", self.curvature_accel_share),
            ("curvature_jerk_share", self.curvature_jerk_share),
        ] {
            if !(v > 0.0 && v < 1.0) {
                return Err(InputError::new(what, v)
                    .at(origin)
                    .expected("a number strictly between 0 and 1"));
            }
        }
        Ok(())
    }

    /// The machine as a TOML profile (millimetres; [`Machine::from_toml_str`] reads it back
    /// to the same machine).
    pub fn to_toml(&self) -> String {
        use toml::Value;
        let mut t = toml::Table::new();
        t.insert("name".into(), Value::String(self.name.clone()));
        t.insert(
            "description".into(),
            Value::String(self.description.clone()),
        );
        t.insert("units".into(), Value::String("mm".into()));
        t.insert(
            "controller".into(),
            Value::String(self.controller.name().into()),
        );
        for (k, v) in [
            ("max_feed", self.max_feed),
            ("path_tolerance", self.path_tolerance),
            ("ipo_cycle", self.ipo_cycle),
            ("curvature_accel_share", self.curvature_accel_share),
            ("curvature_jerk_share", self.curvature_jerk_share),
            ("exact_stop_time", self.exact_stop_time),
            ("sync_wait", self.sync_wait),
            ("tool_change_time", self.tool_change_time),
        ] {
            t.insert(k.into(), Value::Float(v));
        }
        let mut axes = toml::Table::new();
        for ((a, r), name) in self.axes.iter().zip(self.rapid).zip(["x", "y", "z"]) {
            let mut at = toml::Table::new();
            at.insert("max_velocity".into(), Value::Float(a.max_velocity));
            at.insert("max_acceleration".into(), Value::Float(a.max_acceleration));
            at.insert(
                "max_jerk".into(),
                if a.max_jerk.is_finite() {
                    Value::Float(a.max_jerk)
                } else {
                    Value::String("unlimited".into())
                },
            );
            at.insert("rapid".into(), Value::Float(r));
            axes.insert(name.into(), Value::Table(at));
        }
        rotary::write_rotary(&self.rotary, &mut axes);
        t.insert("axes".into(), Value::Table(axes));
        toml::to_string(&t).unwrap_or_default()
    }

    /// Reads a TOML machine profile (format in the module docs); `origin` (a file name) is
    /// quoted in errors.
    pub fn from_toml_str(text: &str, origin: &str) -> Result<Machine, InputError> {
        let table: toml::Table = text.parse().map_err(|e: toml::de::Error| {
            InputError::new("machine profile", "TOML")
                .at(origin)
                .expected(format!("valid TOML ({})", e.message()))
        })?;
        check_keys(&table, TOP_KEYS, "", origin)?;
        let unit = match table.get("units") {
            None => 1.0,
            Some(toml::Value::String(s)) if s == "mm" => 1.0,
            Some(toml::Value::String(s)) if s == "in" => MM_PER_INCH,
            Some(v) => {
                return Err(InputError::new("units", v)
                    .at(origin)
                    .expected("\"mm\" or \"in\""));
            }
        };
        let num = |t: &toml::Table, key: &str, full: &str| -> Result<Option<f64>, InputError> {
            match t.get(key) {
                None => Ok(None),
                Some(toml::Value::Float(f)) => Ok(Some(*f)),
                Some(toml::Value::Integer(i)) => Ok(Some(*i as f64)),
                Some(v) => Err(InputError::new(full, v).at(origin).expected("a number")),
            }
        };
        let required = |t: &toml::Table, key: &str, full: &str| -> Result<f64, InputError> {
            num(t, key, full)?.ok_or_else(|| {
                InputError::new(full, "missing")
                    .at(origin)
                    .expected("a finite number > 0")
            })
        };
        let name = match table.get("name") {
            Some(toml::Value::String(s)) => s.clone(),
            None => origin.to_string(),
            Some(v) => {
                return Err(InputError::new("name", v)
                    .at(origin)
                    .expected("a string (the machine's name)"));
            }
        };
        let axes_t = match table.get("axes") {
            Some(toml::Value::Table(t)) => t,
            _ => {
                return Err(InputError::new("axes", "missing")
                    .at(origin)
                    .expected("tables [axes.x], [axes.y], [axes.z]"));
            }
        };
        let mut axes = [AxisLimits {
            max_velocity: 0.0,
            max_acceleration: 0.0,
            max_jerk: 0.0,
        }; 3];
        let mut rapid = [0.0; 3];
        check_keys(axes_t, &["x", "y", "z", "a", "b", "c"], "axes.", origin)?;
        let rotary = rotary::read_rotary(axes_t, origin)?;
        for (i, an) in ["x", "y", "z"].iter().enumerate() {
            let t = match axes_t.get(*an) {
                Some(toml::Value::Table(t)) => t,
                _ => {
                    return Err(InputError::new(format!("axes.{an}"), "missing")
                        .at(origin)
                        .expected("a table with max_velocity, max_acceleration, max_jerk"));
                }
            };
            check_keys(t, AXIS_KEYS, &format!("axes.{an}."), origin)?;
            let key = |k: &str| format!("axes.{an}.{k}");
            let v = required(t, "max_velocity", &key("max_velocity"))?;
            let a = required(t, "max_acceleration", &key("max_acceleration"))?;
            let j = match t.get("max_jerk") {
                Some(toml::Value::String(s)) if s == "unlimited" => f64::INFINITY,
                Some(v @ toml::Value::String(_)) => {
                    return Err(InputError::new(key("max_jerk"), v)
                        .at(origin)
                        .expected("a finite number > 0 or \"unlimited\""));
                }
                _ => {
                    let j = required(t, "max_jerk", &key("max_jerk"))?;
                    if !j.is_finite() {
                        return Err(InputError::new(key("max_jerk"), j)
                            .at(origin)
                            .expected("a finite number > 0 or \"unlimited\""));
                    }
                    j
                }
            };
            let r = num(t, "rapid", &key("rapid"))?.unwrap_or(v);
            axes[i] = AxisLimits {
                max_velocity: v * unit,
                max_acceleration: a * unit,
                max_jerk: j * unit,
            };
            rapid[i] = r * unit;
        }
        let opt = |key: &str, default: f64| -> Result<f64, InputError> {
            Ok(num(&table, key, key)?.unwrap_or(default))
        };
        let description = match table.get("description") {
            None => format!("machine profile {origin}"),
            Some(toml::Value::String(s)) => s.clone(),
            Some(v) => {
                return Err(InputError::new("description", v)
                    .at(origin)
                    .expected("a string"));
            }
        };
        let m = Machine {
            name,
            description,
            axes,
            max_feed: required(&table, "max_feed", "max_feed")? * unit,
            rapid,
            path_tolerance: opt("path_tolerance", 0.0)? * unit,
            ipo_cycle: opt("ipo_cycle", 0.002)?,
            curvature_accel_share: opt("curvature_accel_share", 0.75)?,
            curvature_jerk_share: opt("curvature_jerk_share", 0.75)?,
            exact_stop_time: opt("exact_stop_time", 0.0)?,
            sync_wait: opt("sync_wait", 0.0)?,
            tool_change_time: opt("tool_change_time", 0.0)?,
            rotary,
            controller: match table.get("controller") {
                None => Controller::Generic,
                Some(v) => v.as_str().and_then(Controller::from_name).ok_or_else(|| {
                    InputError::new("controller", v)
                        .at(origin)
                        .expected(format!("one of {}", Controller::NAMES.join(", ")))
                })?,
            },
        };
        m.validate(origin)?;
        Ok(m)
    }
}

/// The keys a profile's top level may have.
const TOP_KEYS: &[&str] = &[
    "name",
    "description",
    "units",
    "max_feed",
    "path_tolerance",
    "ipo_cycle",
    "curvature_accel_share",
    "curvature_jerk_share",
    "controller",
    "exact_stop_time",
    "sync_wait",
    "tool_change_time",
    "axes",
];

/// The keys an `[axes.x|y|z]` table may have.
const AXIS_KEYS: &[&str] = &["max_velocity", "max_acceleration", "max_jerk", "rapid"];

/// Refuses a key of `table` that is not in `allowed` (a misspelt limit would otherwise fall
/// back to its default without a word), naming it with its table `prefix` and the file.
fn check_keys(
    table: &toml::Table,
    allowed: &[&str],
    prefix: &str,
    origin: &str,
) -> Result<(), InputError> {
    match table.keys().find(|k| !allowed.contains(&k.as_str())) {
        Some(k) => Err(
            InputError::new("machine profile key", format!("{prefix}{k}"))
                .at(origin)
                .expected(format!(
                    "one of {}",
                    allowed
                        .iter()
                        .map(|a| format!("{prefix}{a}"))
                        .collect::<Vec<_>>()
                        .join(", ")
                )),
        ),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The `planner` fuzzer (2026-11-22): a machine with every limit at 1e300 planned a move
    /// whose samples ended 43 mm from its end point (squares of the limits overflow). Limits
    /// beyond the documented maxima are refused, naming the key.
    #[test]
    fn limits_beyond_the_maxima_are_refused() {
        let base = Machine::preset("hsm").unwrap();
        let mut m = base.clone();
        m.axes[1].max_velocity = 1e300;
        let e = m.validate("m.toml").unwrap_err().to_string();
        assert!(
            e.contains("axes.y.max_velocity") && e.contains("1e6"),
            "{e}"
        );
        let mut m = base.clone();
        m.axes[2].max_jerk = 1e300;
        let e = m.validate("m.toml").unwrap_err().to_string();
        assert!(
            e.contains("axes.z.max_jerk") && e.contains("unlimited"),
            "{e}"
        );
        let mut m = base.clone();
        m.axes[2].max_jerk = f64::INFINITY;
        m.validate("m.toml").unwrap();
        let mut m = base;
        m.path_tolerance = 1e300;
        assert!(m.validate("m.toml").is_err());
    }

    /// Every preset written as TOML reads back to itself (the calibrated profile is written
    /// this way).
    #[test]
    fn presets_round_trip_through_toml() {
        for m in Machine::presets() {
            let text = m.to_toml();
            let back = Machine::from_toml_str(&text, "m.toml").unwrap();
            assert_eq!(back, m, "{text}");
        }
    }

    #[test]
    fn presets_are_valid_and_named() {
        for m in Machine::presets() {
            m.validate(&m.name).unwrap();
        }
        assert_eq!(Machine::presets().len(), 4);
        assert!(!Machine::preset("linuxcnc-sim").unwrap().jerk_limited());
        assert!(Machine::preset("hsm").unwrap().jerk_limited());
        let e = Machine::preset("nope").unwrap_err().to_string();
        assert!(e.contains("hsm") && e.contains("nope"), "{e}");
    }

    const PROFILE: &str = r#"
name = "t"
units = "in"
max_feed = 2
path_tolerance = 0.001
[axes.x]
max_velocity = 4
max_acceleration = 100
max_jerk = "unlimited"
[axes.y]
max_velocity = 4
max_acceleration = 100
max_jerk = 1000
[axes.z]
max_velocity = 2
max_acceleration = 50
max_jerk = 1000
rapid = 1
"#;

    #[test]
    fn toml_profile_in_inches() {
        let m = Machine::from_toml_str(PROFILE, "t.toml").unwrap();
        assert!((m.axes[0].max_velocity - 101.6).abs() < 1e-12);
        assert!(m.axes[0].max_jerk.is_infinite());
        assert!((m.axes[1].max_jerk - 25400.0).abs() < 1e-9);
        assert!((m.rapid[2] - 25.4).abs() < 1e-12);
        assert!((m.path_tolerance - 0.0254).abs() < 1e-12);
    }

    #[test]
    fn toml_errors_name_the_key() {
        let bad = PROFILE.replace("max_acceleration = 50", "max_acceleration = -5");
        let e = Machine::from_toml_str(&bad, "t.toml")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("axes.z.max_acceleration") && e.contains("t.toml"),
            "{e}"
        );
        let bad = PROFILE.replace("max_feed = 2", "max_feed = \"fast\"");
        let e = Machine::from_toml_str(&bad, "t.toml")
            .unwrap_err()
            .to_string();
        assert!(e.contains("max_feed"), "{e}");
        let bad = PROFILE.replace("units = \"in\"", "units = \"ft\"");
        let e = Machine::from_toml_str(&bad, "t.toml")
            .unwrap_err()
            .to_string();
        assert!(e.contains("units"), "{e}");
        let bad = PROFILE.replace("max_velocity = 2\n", "");
        let e = Machine::from_toml_str(&bad, "t.toml")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("axes.z.max_velocity") && e.contains("missing"),
            "{e}"
        );
        // Unknown keys and values are refused, naming the key and the file (a misspelt
        // limit fell back to its default without a word).
        for (bad, needle) in [
            (format!("bogus_key = 3\n{PROFILE}"), "bogus_key"),
            (
                PROFILE.replace("rapid = 1", "rapid = 1\nmax_jerks = 5"),
                "axes.z.max_jerks",
            ),
            (format!("{PROFILE}[axes.w]\nmax_velocity = 1\n"), "axes.w"),
            (
                PROFILE.replace("max_jerk = \"unlimited\"", "max_jerk = \"infinite\""),
                "axes.x.max_jerk",
            ),
            (PROFILE.replace("name = \"t\"", "name = 5"), "name"),
        ] {
            let e = Machine::from_toml_str(&bad, "t.toml")
                .unwrap_err()
                .to_string();
            assert!(e.contains(needle) && e.contains("t.toml"), "{e}");
        }
        let bad = PROFILE.replace("max_jerk = 1000\nrapid", "max_jerk = nan\nrapid");
        let e = Machine::from_toml_str(&bad, "t.toml")
            .unwrap_err()
            .to_string();
        assert!(e.contains("axes.z.max_jerk"), "{e}");
    }
}
