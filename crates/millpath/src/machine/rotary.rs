//! The rotary axes A, B and C of a machine profile: their limits, read from `[axes.a]`,
//! `[axes.b]`, `[axes.c]`, checked once here, and kept in radians.
//!
//! ```toml
//! [axes.c]
//! max_velocity = 90.0       # deg/s
//! max_acceleration = 900.0  # deg/s²
//! max_jerk = "unlimited"    # deg/s³, or "unlimited" (optional, default "unlimited")
//! ```
//! Rotary limits are in degrees whatever the profile's `units` (LinuxCNC's angular units).
//! Each axis is its own joint (trivkins): the program's A/B/C words are its angles and the
//! tool tip is not transformed, so that a move's speed and acceleration along the path are
//! bounded by each axis's limit over its share of the move (see `crate::motion`'s
//! `linuxcnc` model). A machine without an axis's table has no such axis: its words are read
//! and take no time.

use super::AxisLimits;
use crate::error::InputError;

/// The rotary axes' names, in the order of [`super::Machine::rotary`].
pub const ROTARY_NAMES: [&str; 3] = ["a", "b", "c"];

/// The largest rotary velocity: 1e5 deg/s.
pub const MAX_ROTARY_VELOCITY_DEG: f64 = 1e5;
/// The largest rotary acceleration: 1e8 deg/s².
pub const MAX_ROTARY_ACCELERATION_DEG: f64 = 1e8;
/// The largest finite rotary jerk: 1e12 deg/s³.
pub const MAX_ROTARY_JERK_DEG: f64 = 1e12;

/// The keys of an `[axes.a|b|c]` table.
pub(super) const ROTARY_KEYS: &[&str] = &["max_velocity", "max_acceleration", "max_jerk"];

/// Limits in deg/s, deg/s², deg/s³ → rad/s, rad/s², rad/s³.
pub fn rotary_limits(v_deg: f64, a_deg: f64, j_deg: f64) -> AxisLimits {
    AxisLimits {
        max_velocity: v_deg.to_radians(),
        max_acceleration: a_deg.to_radians(),
        max_jerk: j_deg.to_radians(),
    }
}

/// Reads the rotary tables of `axes` (the profile's `[axes]` table); `origin` names the file.
pub(super) fn read_rotary(
    axes: &toml::Table,
    origin: &str,
) -> Result<[Option<AxisLimits>; 3], InputError> {
    let mut out = [None; 3];
    for (slot, an) in out.iter_mut().zip(ROTARY_NAMES) {
        let Some(v) = axes.get(an) else {
            continue;
        };
        let key = |k: &str| format!("axes.{an}.{k}");
        let toml::Value::Table(t) = v else {
            return Err(InputError::new(format!("axes.{an}"), v)
                .at(origin)
                .expected("a table with max_velocity (deg/s), max_acceleration (deg/s²)"));
        };
        super::check_keys(t, ROTARY_KEYS, &format!("axes.{an}."), origin)?;
        let num = |k: &str| -> Result<f64, InputError> {
            match t.get(k) {
                Some(toml::Value::Float(f)) => Ok(*f),
                Some(toml::Value::Integer(i)) => Ok(*i as f64),
                None => Err(InputError::new(key(k), "missing")
                    .at(origin)
                    .expected("a finite number > 0 (degrees)")),
                Some(v) => Err(InputError::new(key(k), v)
                    .at(origin)
                    .expected("a number (degrees)")),
            }
        };
        let j = match t.get("max_jerk") {
            None => f64::INFINITY,
            Some(toml::Value::String(s)) if s == "unlimited" => f64::INFINITY,
            Some(v @ toml::Value::String(_)) => {
                return Err(InputError::new(key("max_jerk"), v)
                    .at(origin)
                    .expected("a finite number > 0 (deg/s³) or \"unlimited\""));
            }
            Some(_) => {
                let j = num("max_jerk")?;
                if !j.is_finite() {
                    return Err(InputError::new(key("max_jerk"), j)
                        .at(origin)
                        .expected("a finite number > 0 (deg/s³) or \"unlimited\""));
                }
                j
            }
        };
        *slot = Some(rotary_limits(
            num("max_velocity")?,
            num("max_acceleration")?,
            j,
        ));
    }
    Ok(out)
}

/// Checks the rotary limits (in rad), naming the key in degrees.
pub(super) fn check_rotary(
    rotary: &[Option<AxisLimits>; 3],
    origin: &str,
) -> Result<(), InputError> {
    for (r, an) in rotary.iter().zip(ROTARY_NAMES) {
        let Some(r) = r else { continue };
        for (what, v, max, unit, jerk) in [
            (
                "max_velocity",
                r.max_velocity,
                MAX_ROTARY_VELOCITY_DEG,
                "deg/s",
                false,
            ),
            (
                "max_acceleration",
                r.max_acceleration,
                MAX_ROTARY_ACCELERATION_DEG,
                "deg/s²",
                false,
            ),
            ("max_jerk", r.max_jerk, MAX_ROTARY_JERK_DEG, "deg/s³", true),
        ] {
            let deg = v.to_degrees();
            let ok = deg > 0.0 && (deg <= max || (jerk && deg == f64::INFINITY));
            if !ok {
                return Err(InputError::new(format!("axes.{an}.{what}"), deg)
                    .at(origin)
                    .expected(format!(
                        "a finite number > 0 and at most {max:e} {unit}{}",
                        if jerk { ", or \"unlimited\"" } else { "" }
                    )));
            }
        }
    }
    Ok(())
}

/// The rotary tables of a profile, in degrees, for [`super::Machine::to_toml`].
pub(super) fn write_rotary(rotary: &[Option<AxisLimits>; 3], axes: &mut toml::Table) {
    use toml::Value;
    for (r, an) in rotary.iter().zip(ROTARY_NAMES) {
        let Some(r) = r else { continue };
        let mut t = toml::Table::new();
        t.insert(
            "max_velocity".into(),
            Value::Float(r.max_velocity.to_degrees()),
        );
        t.insert(
            "max_acceleration".into(),
            Value::Float(r.max_acceleration.to_degrees()),
        );
        t.insert(
            "max_jerk".into(),
            if r.max_jerk.is_finite() {
                Value::Float(r.max_jerk.to_degrees())
            } else {
                Value::String("unlimited".into())
            },
        );
        axes.insert(an.into(), Value::Table(t));
    }
}

#[cfg(test)]
mod tests {
    use super::super::Machine;

    const PROFILE: &str = r#"
max_feed = 500
controller = "linuxcnc"
[axes.x]
max_velocity = 500
max_acceleration = 2000
max_jerk = "unlimited"
[axes.y]
max_velocity = 500
max_acceleration = 2000
max_jerk = "unlimited"
[axes.z]
max_velocity = 500
max_acceleration = 2000
max_jerk = "unlimited"
[axes.c]
max_velocity = 90
max_acceleration = 900
"#;

    #[test]
    fn rotary_tables_are_read_in_degrees_and_kept_in_radians() {
        let m = Machine::from_toml_str(PROFILE, "m.toml").unwrap();
        assert!(m.rotary[0].is_none() && m.rotary[1].is_none());
        let c = m.rotary[2].unwrap();
        assert!((c.max_velocity - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
        assert!((c.max_acceleration - 5.0 * std::f64::consts::PI).abs() < 1e-12);
        assert!(c.max_jerk.is_infinite());
        let back = Machine::from_toml_str(&m.to_toml(), "m.toml").unwrap();
        assert_eq!(back, m);
    }

    #[test]
    fn rotary_errors_name_the_key_and_the_file() {
        for (bad, needle) in [
            (
                PROFILE.replace("max_acceleration = 900", "max_acceleration = -900"),
                "axes.c.max_acceleration",
            ),
            (
                PROFILE.replace("max_velocity = 90", "max_velocity = 1e9"),
                "axes.c.max_velocity",
            ),
            (
                PROFILE.replace("max_velocity = 90\n", ""),
                "axes.c.max_velocity",
            ),
            (
                PROFILE.replace(
                    "max_acceleration = 900",
                    "max_acceleration = 900\nrapid = 5",
                ),
                "axes.c.rapid",
            ),
            (
                PROFILE.replace(
                    "max_acceleration = 900",
                    "max_acceleration = 900\nmax_jerk = \"no\"",
                ),
                "axes.c.max_jerk",
            ),
            (format!("{PROFILE}[axes.d]\nmax_velocity = 1\n"), "axes.d"),
        ] {
            let e = Machine::from_toml_str(&bad, "m.toml")
                .unwrap_err()
                .to_string();
            assert!(e.contains(needle) && e.contains("m.toml"), "{e}");
        }
    }
}
