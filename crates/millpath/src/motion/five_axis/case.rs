//! Inputs: the paper's simulation case and CSV path files.
//!
//! # The paper's case, and our reading of it
//! The paper states "a quarter circle with center at (0.0707 m, 0.0707 m, 0) and radius 0.1 m",
//! 31 intervals, and a deflection example whose projection is (0.058, 0.058, 0.0571) m. That
//! projection lies 0.0599 m from the stated centre — not on the circle — but 0.09994 m from the
//! **origin**, with `x = y`. The one reading that puts the example on the curve is:
//!
//! * the circle is centred at the origin, radius 100 mm, in the vertical plane `x = y`;
//!   (0.0707, 0.0707, 0) m — 0.1 m from the origin at 45° — is an *end point* of the quarter,
//!   not its centre;
//! * the quarter runs from the top `(0, 0, 100)` mm down to `(70.71, 70.71, 0)` mm:
//!   `p(φ) = 100 (cos φ/√2, cos φ/√2, sin φ)`, `φ` from 90° to 0° in 31 equal steps.
//!   The paper's projection is then at `φ = 34.9°`, 18.98 intervals from the start: the knot
//!   that ends the 19th interval and starts the 20th ("the 20th interval" of the paper);
//! * the tool orientation, unstated, is the bisector of the vertical and the circle's outward
//!   normal, `k = normalize(p/|p| + e_z)`: vertical at the top, tilted 45° at the bottom, so
//!   both rotary axes move (A to −30°, B to −35.3° on the paper's machine).
//!
//! The deflection (0.059, 0.0568, 0.0589) m is 1.78 mm off the circle; its exact closest point
//! on our reading is (57.40, 57.40, 58.39) mm, 69 % into the 19th interval (the paper's
//! potential-field answer (58, 58, 57.1) mm is 1.55 mm from it and 0.06 mm off the circle:
//! on the curve, but not the closest point).

use super::min_time::Limits;
use crate::error::{InputError, require_positive};
use crate::geom::{Point3, Vec3};
use crate::machine::kinematics::Pose;
use serde::Deserialize;
use std::f64::consts::FRAC_PI_2;

/// Number of intervals in the paper's case.
pub const PAPER_INTERVALS: usize = 31;

/// The tilting sweep through the pole with `n` poses (at least 2): the tool tip from
/// x = −50 to 50 mm along X, the tool tilting evenly from −30° to 30° in the vertical plane at
/// 45° to X, so that it passes the vertical (a table-table machine's C is undefined there);
/// every number rounded to six decimals, as `tests/data/five_axis/sweep.csv` (its 200-pose
/// version) writes them.
pub fn tilting_sweep(n: usize) -> Vec<Pose> {
    let n = n.max(2);
    let r6 = |x: f64| (x * 1e6).round() / 1e6;
    let c = std::f64::consts::FRAC_1_SQRT_2;
    (0..n)
        .map(|k| {
            let u = k as f64 / (n - 1) as f64;
            let t = (-30.0 + 60.0 * u).to_radians();
            Pose {
                tip: Point3::new(r6(-50.0 + 100.0 * u), 0.0, 0.0),
                axis: Vec3::new(r6(t.sin() * c), r6(t.sin() * c), r6(t.cos())),
            }
        })
        .collect()
}

/// The paper's 32 reference poses (mm), see the module docs.
pub fn paper_path() -> Vec<Pose> {
    (0..=PAPER_INTERVALS)
        .map(|k| {
            let phi = FRAC_PI_2 * (1.0 - k as f64 / PAPER_INTERVALS as f64);
            let r = 100.0;
            let c = phi.cos() / std::f64::consts::SQRT_2;
            let tip = Point3::new(r * c, r * c, r * phi.sin());
            let n = Vec3::new(c, c, phi.sin());
            let axis = (n + Vec3::new(0.0, 0.0, 1.0))
                .normalize()
                .unwrap_or(Vec3::new(0.0, 0.0, 1.0));
            Pose { tip, axis }
        })
        .collect()
}

/// The paper's deflected tool position, mm.
pub fn paper_deflection() -> Point3 {
    Point3::new(59.0, 56.8, 58.9)
}

/// The paper's reported projection, mm.
pub fn paper_projection() -> Point3 {
    Point3::new(58.0, 58.0, 57.1)
}

/// Length unit of a path file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LengthUnit {
    /// Millimetres.
    Mm,
    /// Metres.
    M,
}

/// Parses a path file: a unit line `# unit: mm` or `# unit: m`, a header `x,y,z,i,j,k`, then
/// one pose per line (tip in the stated unit, tool axis any non-zero length). Returns poses in
/// mm. `origin` names the file in errors.
pub fn parse_path_csv(text: &str, origin: &str) -> Result<Vec<Pose>, InputError> {
    Ok(parse_path_csv_lines(text, origin)?
        .into_iter()
        .map(|(_, p)| p)
        .collect())
}

/// As [`parse_path_csv`], each pose with its 1-based line number (to name the line in later
/// errors, e.g. a pose the machine cannot reach).
pub fn parse_path_csv_lines(text: &str, origin: &str) -> Result<Vec<(usize, Pose)>, InputError> {
    let mut unit = None;
    let mut header = false;
    let mut poses = Vec::new();
    for (n, raw) in text.lines().enumerate() {
        let at = format!("{origin}:{}", n + 1);
        let line = raw.trim();
        if line.is_empty() {
            continue;
        }
        if let Some(rest) = line.strip_prefix('#') {
            let rest = rest.trim().to_ascii_lowercase();
            if let Some(u) = rest
                .strip_prefix("unit:")
                .or_else(|| rest.strip_prefix("units:"))
            {
                unit = Some(match u.trim() {
                    "mm" => LengthUnit::Mm,
                    "m" => LengthUnit::M,
                    other => {
                        return Err(InputError::new("length unit", other)
                            .at(at)
                            .expected("mm or m"));
                    }
                });
            }
            continue;
        }
        let Some(unit) = unit else {
            return Err(InputError::new("path file", line)
                .at(at)
                .expected("a first line `# unit: mm` or `# unit: m`"));
        };
        if !header {
            let cols: Vec<String> = line
                .split(',')
                .map(|c| c.trim().to_ascii_lowercase())
                .collect();
            if cols != ["x", "y", "z", "i", "j", "k"] {
                return Err(InputError::new("CSV header", line)
                    .at(at)
                    .expected("x,y,z,i,j,k"));
            }
            header = true;
            continue;
        }
        let vals: Vec<&str> = line.split(',').map(str::trim).collect();
        if vals.len() != 6 {
            return Err(InputError::new("path row", line)
                .at(at)
                .expected("6 comma-separated numbers x,y,z,i,j,k"));
        }
        let mut v = [0.0; 6];
        for (slot, s) in v.iter_mut().zip(&vals) {
            *slot = s
                .parse::<f64>()
                .ok()
                .filter(|x| x.is_finite())
                .ok_or_else(|| {
                    InputError::new("number", s)
                        .at(at.clone())
                        .expected("a finite number")
                })?;
        }
        let scale = if unit == LengthUnit::M { 1000.0 } else { 1.0 };
        let pose = Pose::new(
            Point3::new(v[0] * scale, v[1] * scale, v[2] * scale),
            Vec3::new(v[3], v[4], v[5]),
        )
        .map_err(|e| e.at(at))?;
        poses.push((n + 1, pose));
    }
    if poses.len() < 2 {
        return Err(InputError::new("path", format!("{} poses", poses.len()))
            .at(origin)
            .expected("at least two poses"));
    }
    Ok(poses)
}

/// A limits file (TOML, mm, s, rad; every key optional, missing keys keep the defaults):
///
/// ```toml
/// feed = 30.0                   # tool-tip speed, mm/s
/// linear_velocity = 500.0       # mm/s      (X, Y, Z)
/// linear_acceleration = 20000.0 # mm/s²
/// linear_jerk = 200000.0        # mm/s³
/// rotary_velocity = 0.5         # rad/s     (both rotary axes)
/// rotary_acceleration = 20.0    # rad/s²
/// rotary_jerk = 200.0           # rad/s³
/// tool_length = 50.0            # mm
/// z1 = 300.0                    # mm, the paper's machine only
/// z2 = 30.0                     # mm, the paper's machine only
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LimitsFile {
    /// Feed, mm/s.
    pub feed: Option<f64>,
    /// Linear velocity, mm/s.
    pub linear_velocity: Option<f64>,
    /// Linear acceleration, mm/s².
    pub linear_acceleration: Option<f64>,
    /// Linear jerk, mm/s³.
    pub linear_jerk: Option<f64>,
    /// Rotary velocity, rad/s.
    pub rotary_velocity: Option<f64>,
    /// Rotary acceleration, rad/s².
    pub rotary_acceleration: Option<f64>,
    /// Rotary jerk, rad/s³.
    pub rotary_jerk: Option<f64>,
    /// Tool length, mm.
    pub tool_length: Option<f64>,
    /// The paper machine's z1, mm.
    pub z1: Option<f64>,
    /// The paper machine's z2, mm.
    pub z2: Option<f64>,
}

impl LimitsFile {
    /// Parses a limits file; `origin` names it in errors. Every given value must be finite
    /// and > 0 (`z2` may be any finite number).
    pub fn parse(text: &str, origin: &str) -> Result<LimitsFile, InputError> {
        let f: LimitsFile = toml::from_str(text).map_err(|e| {
            InputError::new("limits file", origin).expected(format!(
                "TOML with the keys feed, linear_velocity, linear_acceleration, linear_jerk, \
                 rotary_velocity, rotary_acceleration, rotary_jerk, tool_length, z1, z2 ({})",
                e.message()
            ))
        })?;
        f.validate(origin)?;
        Ok(f)
    }

    /// Every given value finite and > 0 (z2 finite), or an error naming the key.
    pub fn validate(&self, origin: &str) -> Result<(), InputError> {
        for (k, v) in [
            ("feed", self.feed),
            ("linear_velocity", self.linear_velocity),
            ("linear_acceleration", self.linear_acceleration),
            ("linear_jerk", self.linear_jerk),
            ("rotary_velocity", self.rotary_velocity),
            ("rotary_acceleration", self.rotary_acceleration),
            ("rotary_jerk", self.rotary_jerk),
            ("tool_length", self.tool_length),
            ("z1", self.z1),
        ] {
            if let Some(v) = v {
                require_positive(k, v, origin)?;
            }
        }
        if let Some(z2) = self.z2.filter(|z| !z.is_finite()) {
            return Err(InputError::new("z2", z2)
                .at(origin)
                .expected("a finite length in mm"));
        }
        Ok(())
    }

    /// Values of `other` where given, else ours.
    #[must_use]
    pub fn overridden_by(self, other: &LimitsFile) -> LimitsFile {
        LimitsFile {
            feed: other.feed.or(self.feed),
            linear_velocity: other.linear_velocity.or(self.linear_velocity),
            linear_acceleration: other.linear_acceleration.or(self.linear_acceleration),
            linear_jerk: other.linear_jerk.or(self.linear_jerk),
            rotary_velocity: other.rotary_velocity.or(self.rotary_velocity),
            rotary_acceleration: other.rotary_acceleration.or(self.rotary_acceleration),
            rotary_jerk: other.rotary_jerk.or(self.rotary_jerk),
            tool_length: other.tool_length.or(self.tool_length),
            z1: other.z1.or(self.z1),
            z2: other.z2.or(self.z2),
        }
    }

    /// `base` with the given limits applied.
    pub fn apply(&self, base: &Limits) -> Limits {
        let mut l = *base;
        if let Some(f) = self.feed {
            l.feed = f;
        }
        for (i, (v, a, j)) in [
            (
                self.linear_velocity,
                self.linear_acceleration,
                self.linear_jerk,
            ),
            (
                self.linear_velocity,
                self.linear_acceleration,
                self.linear_jerk,
            ),
            (
                self.linear_velocity,
                self.linear_acceleration,
                self.linear_jerk,
            ),
            (
                self.rotary_velocity,
                self.rotary_acceleration,
                self.rotary_jerk,
            ),
            (
                self.rotary_velocity,
                self.rotary_acceleration,
                self.rotary_jerk,
            ),
        ]
        .into_iter()
        .enumerate()
        {
            if let Some(v) = v {
                l.vel[i] = v;
            }
            if let Some(a) = a {
                l.acc[i] = a;
            }
            if let Some(j) = j {
                l.jerk[i] = j;
            }
        }
        l
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn limits_file_overrides_and_rejects() {
        let f = LimitsFile::parse("feed = 20\nrotary_jerk = 100\nz1 = 250", "l.toml").unwrap();
        let l = f.apply(&Limits::paper());
        assert!((l.feed - 20.0).abs() < 1e-12);
        let want = [200_000.0, 200_000.0, 200_000.0, 100.0, 100.0];
        assert!(l.jerk.iter().zip(want).all(|(a, b)| (a - b).abs() < 1e-9));
        let e = LimitsFile::parse("linear_jerk = -3", "l.toml")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("linear_jerk") && e.contains("-3") && e.contains("l.toml"),
            "{e}"
        );
        let e = LimitsFile::parse("speed = 3", "l.toml")
            .unwrap_err()
            .to_string();
        assert!(e.contains("speed") && e.contains("l.toml"), "{e}");
        let e = LimitsFile::parse("feed = nan", "l.toml")
            .unwrap_err()
            .to_string();
        assert!(e.contains("feed"), "{e}");
    }

    #[test]
    fn path_lines_are_numbered() {
        let p = parse_path_csv_lines(
            "# unit: mm\nx,y,z,i,j,k\n\n1,2,3,0,0,1\n4,5,6,0,0,2\n",
            "p.csv",
        )
        .unwrap();
        assert_eq!(p.iter().map(|x| x.0).collect::<Vec<_>>(), [4, 5]);
        let e = parse_path_csv("# unit: mm\nx,y,z,i,j,k\n1,2,3,0,0,0\n", "p.csv")
            .unwrap_err()
            .to_string();
        assert!(e.contains("p.csv:3"), "{e}");
    }
}
