//! Machines: per-axis limits, presets, TOML profiles, kinematics.
//!
//! A [`Machine`] is what the motion planner ([`crate::motion`]) needs to know about a
//! three-axis Cartesian machine: per-axis velocity, acceleration and jerk limits, the maximum
//! programmed feed, the rapid velocity per axis, the path tolerance used for corner blending
//! and the controller's interpolation cycle. Everything is stored in mm, s (feeds in mm/s).
//!
//! # Presets
//!
//! | preset | v_max x/y/z (mm/s) | a_max (mm/s²) | j_max (mm/s³) | max feed (mm/s) | rapid (mm/s) | tolerance (mm) | IPO (ms) |
//! |---|---|---|---|---|---|---|---|
//! | `hsm` | 500 / 500 / 500 | 5000 | 200 000 | 500 | 500 | 0.01 | 2 |
//! | `linuxcnc-sim` | 101.6 (4 in/s) | 2540 (100 in/s²) | unlimited | 30.48 (1.2 in/s) | 30.48 | 0.0254 (0.001 in) | 1 |
//! | `router` | 250 / 250 / 100 | 500 / 500 / 300 | 10 000 / 10 000 / 5 000 | 200 | 250 / 250 / 100 | 0.05 | 1 |
//!
//! Where the numbers come from:
//!
//! * **`hsm`** — a Huron-class high-speed vertical mill with a Siemens 840D, the machine of the
//!   adaptive-spiral paper's Table 2. Rapid 30 m/min (500 mm/s) and axis acceleration
//!   5 m/s² are the published class of such machines (Huron KX/MX high-speed series:
//!   30–40 m/min rapids, 3–6 m/s²); jerk 200 m/s³ is within the range the 840D's
//!   `MAX_AX_JERK` (MD32431) is set to on such machines (50–500 m/s³). Both are chosen to be
//!   consistent with Table 2: at 400 in/min (169 mm/s) on the r = 0.318 in (8.08 mm) circle
//!   the 840D took 0.52 s for 0.30 s of path at feed, i.e. it kept nearly full feed with a
//!   centripetal acceleration `v²/r ≈ 3.5 m/s²` and `v³/r² ≈ 74 m/s³`, so the axes allow at
//!   least that; the squares' corner losses then fix the pair (A, J) = (5 m/s², 200 m/s³)
//!   as the grid point that reproduces the table's trends with the smallest error (see
//!   [`crate::motion::table2`] for the fit and the remaining error). Path tolerance 0.01 mm
//!   (a typical G642/`CYCLE832` finishing tolerance; the paper does not give the 840D's
//!   continuous-path settings; on Table 2's 90° corners it leaves the corner speed so low
//!   that the squares behave almost as with exact stops; the grid search picks the same (A, J) with tolerance 0).
//!   Interpolation cycle 2 ms (the 840D's IPO cycle is typically
//!   2–4 ms, MD10071). On curved paths the 840D shares the axis acceleration between the
//!   tangential and the centripetal direction (`CURV_EFFECT_ON_PATH_ACCEL`, MD20602); the
//!   preset gives 3/4 of it (and of the jerk) to the curvature terms.
//! * **`linuxcnc-sim`** — LinuxCNC's sample simulator configuration
//!   `configs/sim/axis/axis.ini` (inch units): every axis `MAX_VELOCITY = 4` in/s,
//!   `MAX_ACCELERATION = 100.0` in/s², `[TRAJ] MAX_LINEAR_VELOCITY = 1.2` in/s (which caps
//!   every move, rapids included, so it is both the maximum feed and the rapid here),
//!   `SERVO_PERIOD = 1000000` ns. LinuxCNC's planner is trapezoidal: jerk unlimited. The path
//!   tolerance 0.001 in is the usual `G64 P0.001`.
//! * **`router`** — a low-acceleration hobby router (steel-belt or lead-screw gantry): 15 m/min
//!   rapids in XY, 6 m/min in Z, 0.5 m/s² in XY, 0.3 m/s² in Z, jerk 10 m/s³ (XY) and
//!   5 m/s³ (Z), the class of GRBL-based routers' `$120..$122` settings.
//!
//! # TOML profiles
//!
//! ```toml
//! name = "my-mill"
//! units = "mm"            # "mm" or "in": every length below is in these units
//! max_feed = 250.0        # units/s
//! path_tolerance = 0.01   # units; 0 = exact stop at every corner
//! ipo_cycle = 0.002       # s (optional, default 0.002)
//! curvature_accel_share = 0.75   # optional, default 0.75
//! curvature_jerk_share = 0.75    # optional, default 0.75
//!
//! [axes.x]
//! max_velocity = 500.0      # units/s
//! max_acceleration = 2000.0 # units/s²
//! max_jerk = 100000.0       # units/s³, or "unlimited"
//! rapid = 500.0             # units/s (optional, default max_velocity)
//! # [axes.y] and [axes.z] alike
//! ```
//! Every limit must be a finite number > 0 (jerk may be `"unlimited"`); errors name the key.
//! A key that is not one of these (a misspelt limit, which would otherwise fall back to its
//! default without a word) is refused, naming the key and the file.

pub mod kinematics;

use crate::error::InputError;
use serde::{Deserialize, Serialize};

/// Millimetres per inch.
pub const MM_PER_INCH: f64 = 25.4;

/// The limits of one axis.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct AxisLimits {
    /// Maximum axis velocity in mm/s.
    pub max_velocity: f64,
    /// Maximum axis acceleration in mm/s².
    pub max_acceleration: f64,
    /// Maximum axis jerk in mm/s³ (`f64::INFINITY` for unlimited: trapezoidal profiles).
    pub max_jerk: f64,
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
    /// and the blended path. 0 means exact stop at every non-tangent corner.
    pub path_tolerance: f64,
    /// The controller's interpolation cycle in s: acceleration steps at curvature jumps are
    /// spread over one cycle (see [`crate::motion`]).
    pub ipo_cycle: f64,
    /// Share of the axis acceleration available for centripetal acceleration on arcs (the rest
    /// is for tangential acceleration), in (0, 1).
    pub curvature_accel_share: f64,
    /// Share of the axis jerk available for the jerk that curvature implies on arcs, in (0, 1).
    pub curvature_jerk_share: f64,
}

/// The largest velocity (axis, rapid or feed) a machine may have: 1 km/s, in mm/s.
pub const MAX_VELOCITY: f64 = 1e6;
/// The largest axis acceleration: 1e9 mm/s² (100 000 g).
pub const MAX_ACCELERATION: f64 = 1e9;
/// The largest finite axis jerk, mm/s³ (jerk may also be unlimited).
pub const MAX_JERK: f64 = 1e13;

impl Machine {
    /// The names of the built-in presets.
    pub const PRESET_NAMES: [&'static str; 3] = ["hsm", "linuxcnc-sim", "router"];

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
                axes: [axis(500.0, 5000.0, 200_000.0); 3],
                max_feed: 500.0,
                rapid: [500.0; 3],
                path_tolerance: 0.01,
                ipo_cycle: 0.002,
                curvature_accel_share: 0.75,
                curvature_jerk_share: 0.75,
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
                })
            }
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
        check_keys(axes_t, &["x", "y", "z"], "axes.", origin)?;
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
        let m = Machine {
            name,
            description: format!("machine profile {origin}"),
            axes,
            max_feed: required(&table, "max_feed", "max_feed")? * unit,
            rapid,
            path_tolerance: opt("path_tolerance", 0.0)? * unit,
            ipo_cycle: opt("ipo_cycle", 0.002)?,
            curvature_accel_share: opt("curvature_accel_share", 0.75)?,
            curvature_jerk_share: opt("curvature_jerk_share", 0.75)?,
        };
        m.validate(origin)?;
        Ok(m)
    }
}

/// The keys a profile's top level may have.
const TOP_KEYS: &[&str] = &[
    "name",
    "units",
    "max_feed",
    "path_tolerance",
    "ipo_cycle",
    "curvature_accel_share",
    "curvature_jerk_share",
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

    /// The `planner` fuzzer (session 3): a machine with every limit at 1e300 planned a move
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

    #[test]
    fn presets_are_valid_and_named() {
        for m in Machine::presets() {
            m.validate(&m.name).unwrap();
        }
        assert_eq!(Machine::presets().len(), 3);
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
