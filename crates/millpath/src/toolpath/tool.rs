//! Cutting tools.

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
