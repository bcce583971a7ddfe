//! Cutting tools, and the scale a tool sets for the tolerances of the work done with it.
//!
//! **Tolerances scale with the tool.** A part and the same part ten times as large, cut with
//! a tool ten times as large, are the same problem. The engine's default resolutions and
//! tolerances of pocketing and of its verification (the stock simulation's cell and sample
//! spacing, offset and arc-fitting tolerances, shortest pieces, the verifier's uncut-area
//! threshold) are written in millimetres for tools up to [`REFERENCE_DIAMETER`] (12.7 mm)
//! and multiplied by [`Tool::tolerance_scale`], `max(1, D / 12.7 mm)`, for larger tools, so
//! that from 12.7 mm up a drawing and its `k`-fold enlargement (tool, depths and heights
//! `k`-fold) plan the same path scaled, with the same work. Below 12.7 mm the millimetre
//! values stay: they are workshop resolutions (the stock simulation's 0.05 mm cell, micron
//! tolerances) that are already fine for the tool; making them finer still with the tool
//! would only make small tools slower. An area tolerance scales with the square.

use crate::error::{InputError, require_positive};
use serde::{Deserialize, Serialize};

/// A flat end mill.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Tool {
    /// Cutting diameter in mm.
    pub diameter: f64,
    /// Number of flutes.
    pub flutes: u32,
    /// Length of the flutes in mm (the deepest a single pass may cut).
    pub flute_length: f64,
    /// Tool number in the tool changer (`T` word).
    pub number: u32,
}

/// The tool diameter up to which the default resolutions and tolerances are the
/// millimetres written (module docs), mm: the half-inch end mill they were chosen with (the
/// adaptive-spiral paper's, and `millpath pocket`'s default).
pub const REFERENCE_DIAMETER: f64 = 12.7;

/// [`Tool::tolerance_scale`] of a tool of `diameter` mm: `max(1, diameter / 12.7 mm)` (1 for
/// a diameter that is not a positive finite length).
pub fn tolerance_scale(diameter: f64) -> f64 {
    if diameter.is_finite() && diameter > REFERENCE_DIAMETER {
        diameter / REFERENCE_DIAMETER
    } else {
        1.0
    }
}

impl Default for Tool {
    fn default() -> Self {
        Tool {
            diameter: 10.0,
            flutes: 3,
            flute_length: 30.0,
            number: 1,
        }
    }
}

impl Tool {
    /// A flat end mill of `diameter` mm with default flutes (3) and flute length (3 × diameter).
    pub fn flat(diameter: f64) -> Result<Self, InputError> {
        require_positive("tool diameter", diameter, "tool")?;
        Ok(Tool {
            diameter,
            flute_length: 3.0 * diameter,
            ..Tool::default()
        })
    }

    /// Radius in mm.
    pub fn radius(&self) -> f64 {
        self.diameter * 0.5
    }

    /// The factor the default lengths of the work done with this tool are multiplied by (the
    /// module docs): `max(1, D / `[`REFERENCE_DIAMETER`]`)`, 1 for a tool that is not a
    /// positive finite length.
    pub fn tolerance_scale(&self) -> f64 {
        tolerance_scale(self.diameter)
    }

    /// Checks every field; `origin` names where the tool was described.
    pub fn validate(&self, origin: &str) -> Result<(), InputError> {
        require_positive("tool diameter", self.diameter, origin)?;
        require_positive("tool flute length", self.flute_length, origin)?;
        if self.flutes == 0 {
            return Err(InputError::new("tool flutes", 0)
                .at(origin)
                .expected("at least 1 flute"));
        }
        Ok(())
    }
}
