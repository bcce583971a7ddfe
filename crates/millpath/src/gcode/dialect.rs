//! Dialects, units and coolant: the vocabulary shared by the writer and the reader.
//!
//! What each dialect gets (and why) is tabled on [`Dialect`].

use crate::error::InputError;
use serde::{Deserialize, Serialize};
use std::fmt;
use std::str::FromStr;

/// A G-code dialect (serialised as its [`Dialect::name`]).
///
/// # What each dialect gets
/// | | LinuxCNC (default) | Fanuc | Sinumerik 840D | Grbl 1.1 |
/// |---|---|---|---|---|
/// | framing | – | `%`, `O0001 (NAME)`, `%` | – | – |
/// | comments | `( )` | `( )`, upper case | `;` | `;` |
/// | units | G21/G20 | G21/G20 | G710/G700 (feeds follow) | G21/G20 |
/// | numbers | `X10` | `X10.` (keeps the point: without decimal point programming `X10` means 10 increments) | `X10` | `X10` |
/// | tool | `T1 M6`, `G43` on the first move | `T1 M6`, `G43 H1` on the first move | `T1 M6` (D1 is active by default) | a comment: no M6 |
/// | dwell | `G4 P`s | `G04 X`s (X with a decimal point is seconds; P would be ms) | `G4 F`s (own block; F does not change the feed) | `G4 P`s |
/// | path tolerance | `G64 P`tol | `G05.1 Q1` (AI contour control; its tolerance is a machine parameter, written as a comment), `G05.1 Q0` at the end | `CYCLE832(tol,_FINISH,1)` | none (a comment) |
/// | path tolerance 0 | `G61.1` (never `G64 P0`: LinuxCNC reads it as no limit) | `G61` | `G60` | none (a comment) |
/// | exact stop / exact path | `G61.1` / `G61` | `G61` / `G61` (no exact-path mode) | `G60` / `G64` (continuous path without rounding) | – (grbl has only its planner) |
/// | blend / machine | `G64 P`t / `G64 P`path or `G64` | `G64` / `G64` | `CYCLE832(t,_FINISH,1)` / CYCLE832 with the path tolerance, or `G642` | – |
/// | multi-turn arcs | `P`turns+1 | split into full turns | `TURN=`n | split into full turns |
/// | canned drilling cycles (`toolpath::Cycle`, writer module `cycles`) | `G98`/`G99` `G81`, `G82 P`s, `G83 Q`, `G73 Q`; `G80` after a run | the same; `G82 P` in ms | `G0 X Y`, then `CYCLE81`, `CYCLE82` or `CYCLE83` (chip removal) per hole; chip breaking as its moves | the moves (no cycles) |
/// | arc radii (rounded start and end) | LinuxCNC's rule (`arc`) | LinuxCNC's rule | LinuxCNC's rule | and Grbl 1.1's: 0.005 mm, or 0.1 % and 0.5 mm |
/// | five-axis ([`five_axis`](super::five_axis)) | `G93`, `A`/`B` `C` words | the same, decimal points | the same | refused: no rotary axes |
/// | end | `M2` | `M30` | `M30` | `M2` |
///
/// **The program's path tolerance** ([`WriterOptions::path_tolerance`](super::WriterOptions::path_tolerance),
/// [`WriterOptions::with_path_tolerance`](super::WriterOptions::with_path_tolerance)) is stated once in the header, after the work
/// offset. Programs that millpath times state the tolerance they were timed with: `pocket`
/// and the demo's pocket programs the machine's (`--machine`, hsm's 0.01 mm by default),
/// `contour` the machine's or the contour's tolerance where that is tighter. Read back, a
/// LinuxCNC or Sinumerik program's moves carry it as `Blend(t)` (exact stop at 0), so
/// `millpath estimate` plans it with that tolerance whatever machine it is given; Fanuc's
/// `G64` and Grbl's silence read back as the estimating machine's own tolerance. Without it
/// LinuxCNC runs in its default `G64` and blends each corner by up to a quarter of the
/// shorter segment (`tc.c`, `tcFindBlendTolerance`); under `G64 P t` its naive-CAM merging
/// (`Q`, which defaults to `P`: `interp_convert.cc`, `convert_control_mode`) also joins
/// short collinear-within-t line segments of one feed.
///
/// Corner modes are modal: the writer writes one on its own line only when a move's
/// [`Corner`](crate::toolpath::Corner) differs from the last one written. What a corner mode
/// reads back as: LinuxCNC keeps all four exactly (`G64 P`tol reads as `Blend(tol)`, so a
/// `Machine` move written under a header `G64 P` reads back as the blend it means); Fanuc
/// reads `G61` as exact stop and `G64` as machine; Sinumerik `G60` exact stop, `G64` exact
/// path, `CYCLE832(t,..)` blend, `G642` machine; Grbl programs carry no corner mode (the
/// writer writes none), so they read back as machine.
///
/// Sources for the dwell words: LinuxCNC's G-code reference (`G4 P` seconds); Siemens'
/// ISO-dialect manual (840D, `G04 X_` seconds with decimal point, `P_` in ms without) and
/// Fanuc's identical convention; Sinumerik's Siemens mode `G4 F…` (seconds, "must be programmed
/// in a separate block"); Grbl 1.1 `G4 P` seconds.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Dialect {
    /// LinuxCNC (RS274/NGC): the reference dialect, checked with its own interpreter `rs274`.
    #[default]
    LinuxCnc,
    /// Fanuc 0i/30i-style ISO G-code.
    Fanuc,
    /// Siemens Sinumerik 840D (sl) in Siemens mode.
    Sinumerik,
    /// Grbl 1.1.
    Grbl,
}

impl Dialect {
    /// All dialects, in a stable order.
    pub const ALL: [Dialect; 4] = [
        Dialect::LinuxCnc,
        Dialect::Fanuc,
        Dialect::Sinumerik,
        Dialect::Grbl,
    ];

    /// The name used on the command line and in files.
    pub fn name(self) -> &'static str {
        match self {
            Dialect::LinuxCnc => "linuxcnc",
            Dialect::Fanuc => "fanuc",
            Dialect::Sinumerik => "sinumerik",
            Dialect::Grbl => "grbl",
        }
    }

    /// Default decimals of coordinates: 3 in mm and 4 in inches (1 µm / 0.1 thou: the IS-B
    /// least input increment of Fanuc, and what all four controls accept).
    pub fn default_decimals(self, units: Units) -> u32 {
        match units {
            Units::Mm => 3,
            Units::Inch => 4,
        }
    }

    /// The usual file extension of a program (without the dot): `ngc` (LinuxCNC), `nc`
    /// (Fanuc, Grbl), `mpf` (Sinumerik main program).
    pub fn file_extension(self) -> &'static str {
        match self {
            Dialect::LinuxCnc => "ngc",
            Dialect::Fanuc | Dialect::Grbl => "nc",
            Dialect::Sinumerik => "mpf",
        }
    }

    /// Whether comments use `;` to the end of the line (otherwise `( )`).
    pub fn semicolon_comments(self) -> bool {
        matches!(self, Dialect::Sinumerik | Dialect::Grbl)
    }

    /// Whether integral values keep their decimal point (`X10.`): Fanuc, see `super::format`.
    pub fn keeps_decimal_point(self) -> bool {
        matches!(self, Dialect::Fanuc)
    }
}

impl fmt::Display for Dialect {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Dialect {
    type Err = InputError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Dialect::ALL
            .into_iter()
            .find(|d| d.name().eq_ignore_ascii_case(s.trim()))
            .ok_or_else(|| {
                InputError::new("G-code dialect", s)
                    .expected("one of linuxcnc, fanuc, sinumerik, grbl")
            })
    }
}

/// Program units: G21 (mm) or G20 (inch); serialised as `"mm"` / `"in"`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash, Serialize, Deserialize)]
pub enum Units {
    /// G21: millimetres, feeds in mm/min.
    #[default]
    #[serde(rename = "mm")]
    Mm,
    /// G20: inches, feeds in in/min.
    #[serde(rename = "in", alias = "inch")]
    Inch,
}

impl Units {
    /// Millimetres per program unit.
    pub fn mm_per_unit(self) -> f64 {
        match self {
            Units::Mm => 1.0,
            Units::Inch => crate::geom::MM_PER_INCH,
        }
    }
}

impl fmt::Display for Units {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Units::Mm => "mm",
            Units::Inch => "in",
        })
    }
}

impl FromStr for Units {
    type Err = InputError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.trim().to_ascii_lowercase().as_str() {
            "mm" => Ok(Units::Mm),
            "in" | "inch" => Ok(Units::Inch),
            _ => Err(InputError::new("units", s).expected("mm or in")),
        }
    }
}

/// Coolant: M9 (off), M8 (flood), M7 (mist).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Coolant {
    /// M9.
    #[default]
    Off,
    /// M8.
    Flood,
    /// M7.
    Mist,
}

impl Coolant {
    /// The name used on the command line: `off`, `flood`, `mist`.
    pub fn name(self) -> &'static str {
        match self {
            Coolant::Off => "off",
            Coolant::Flood => "flood",
            Coolant::Mist => "mist",
        }
    }
}

impl fmt::Display for Coolant {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Coolant {
    type Err = InputError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        [Coolant::Off, Coolant::Flood, Coolant::Mist]
            .into_iter()
            .find(|c| c.name().eq_ignore_ascii_case(s.trim()))
            .ok_or_else(|| InputError::new("coolant", s).expected("off, flood or mist"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dialect_names_round_trip() {
        for d in Dialect::ALL {
            assert_eq!(d.to_string().parse::<Dialect>(), Ok(d));
        }
        assert_eq!("FANUC".parse::<Dialect>(), Ok(Dialect::Fanuc));
        for d in Dialect::ALL {
            let json = serde_json::to_string(&d).unwrap();
            assert_eq!(json, format!("\"{}\"", d.name()));
        }
        assert_eq!(serde_json::to_string(&Units::Inch).unwrap(), "\"in\"");
        let e = "haas".parse::<Dialect>().unwrap_err().to_string();
        assert!(e.contains("haas") && e.contains("linuxcnc"), "{e}");
        for c in [Coolant::Off, Coolant::Flood, Coolant::Mist] {
            assert_eq!(c.to_string().parse::<Coolant>(), Ok(c));
        }
        assert!("oil".parse::<Coolant>().is_err());
        assert_eq!(Dialect::detect("%\nO0001 (X)\nG0 X1\n"), Dialect::Fanuc);
        assert_eq!(Dialect::detect(":0001 (X)\nG0 X1\n"), Dialect::Fanuc);
        assert_eq!(Dialect::detect("; a\nG17 G710 G90\n"), Dialect::Sinumerik);
        assert_eq!(Dialect::detect("; a\nG17 G21 G90\n"), Dialect::Grbl);
        assert_eq!(
            Dialect::detect("; a\nG21 G90\nG64 P0.01\n"),
            Dialect::LinuxCnc
        );
        assert_eq!(
            Dialect::detect("(a)\nG17 G21 G90\nG64 P0.01\n"),
            Dialect::LinuxCnc
        );
    }
}
