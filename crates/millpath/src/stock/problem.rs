//! What the verifier can find wrong with a program, as values: a report or a test matches on
//! the kind and reads the figures; `Display` gives the sentence the CLI prints.

use crate::geom::Point3;
use serde::Serialize;
use std::fmt;

/// One problem found by [`super::Verification::problems_within`] or
/// [`super::PartVerification::problems_within`].
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Problem {
    /// The tool centre comes closer to a wall than the clearance the cut needs.
    Gouge {
        /// Smallest distance between the tool centre and a wall, mm.
        clearance_mm: f64,
        /// Tool radius plus wall stock, mm.
        required_mm: f64,
    },
    /// Material the tool could reach is left, beyond [`super::UNCUT_AREA_TOLERANCE`].
    Uncut {
        /// Area left, mm².
        area_mm2: f64,
        /// Where most of it lies.
        at: Option<Point3>,
    },
    /// Rapid moves that sweep through material.
    RapidsThroughMaterial(usize),
    /// Feed moves steeper than 45° that end in material.
    Plunges(usize),
    /// Chunks of a part program that cut below the stock top outside every pocket.
    CutsOutside(usize),
    /// The problems of one pocket of a part (1-based, in the order given).
    InPocket {
        /// The pocket, 1-based.
        pocket: usize,
        /// What was found in it.
        problems: Vec<Problem>,
    },
}

impl Problem {
    /// True for a gouge, in this pocket or any.
    pub fn is_gouge(&self) -> bool {
        match self {
            Problem::Gouge { .. } => true,
            Problem::InPocket { problems, .. } => problems.iter().any(Problem::is_gouge),
            _ => false,
        }
    }
}

/// The problems in words, `"; "` between them.
pub fn problems_text(problems: &[Problem]) -> String {
    let words: Vec<String> = problems.iter().map(ToString::to_string).collect();
    words.join("; ")
}

/// The uncut area and where most of it lies, in words.
pub(crate) fn uncut_text(area_mm2: f64, at: Option<Point3>) -> String {
    match at {
        Some(p) => format!(
            "{area_mm2:.3} mm², most of it around ({:.3}, {:.3}) at z = {:.3}",
            p.x, p.y, p.z
        ),
        None => format!("{area_mm2:.3} mm²"),
    }
}

impl fmt::Display for Problem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Problem::Gouge {
                clearance_mm,
                required_mm,
            } => write!(
                f,
                "gouge: the tool centre comes within {clearance_mm:.6} mm of a wall (needs {required_mm:.6})"
            ),
            Problem::Uncut { area_mm2, at } => {
                write!(f, "uncut material: {}", uncut_text(*area_mm2, *at))
            }
            Problem::RapidsThroughMaterial(n) => write!(f, "{n} rapid moves through material"),
            Problem::Plunges(n) => write!(f, "{n} plunges into material"),
            Problem::CutsOutside(n) => {
                write!(f, "{n} cuts below the stock top outside every pocket")
            }
            Problem::InPocket { pocket, problems } => {
                write!(f, "pocket {pocket}: ")?;
                for (i, p) in problems.iter().enumerate() {
                    if i > 0 {
                        f.write_str(", ")?;
                    }
                    write!(f, "{p}")?;
                }
                Ok(())
            }
        }
    }
}
