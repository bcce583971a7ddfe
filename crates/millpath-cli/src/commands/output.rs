//! The G-code output flags every program-writing command shares (`contour`, `pocket`,
//! `profile`, `five-axis`): one definition, flattened into each command's arguments
//! (`#[command(flatten)]`), so that `--dialect`, `--units`, `--decimals`, `--tool-number`,
//! `--spindle`, `--coolant` and `--line-numbers` are spelled, defaulted and checked alike.
//!
//! ```text
//! millpath pocket part.dxf --dialect fanuc --units in -o part.nc
//! millpath contour pts.csv --dialect sinumerik --tool-number 4 --coolant mist -o part.mpf
//! millpath five-axis --case paper --machine xyzac-trt --gcode traj.nc --dialect fanuc
//! ```

use millpath::gcode::{Coolant, Dialect, Units};
use millpath::job::ProgramSettings;

/// G-code output flags.
#[derive(Debug, Clone, clap::Args)]
#[command(next_help_heading = "G-code output")]
pub struct OutputArgs {
    /// G-code dialect: linuxcnc, fanuc, sinumerik, grbl.
    #[arg(long, default_value = "linuxcnc")]
    pub dialect: Dialect,
    /// Program units: mm or in (inside, everything stays in mm; only the text converts).
    #[arg(long, default_value = "mm")]
    pub units: Units,
    /// Decimals of coordinates (default: the dialect's, 3 in mm and 4 in inches, raised to
    /// what the command's tolerance needs).
    #[arg(long)]
    pub decimals: Option<u32>,
    /// Tool number: `T n M6` and the tool length offset (a comment on grbl); 0 writes no tool
    /// change.
    #[arg(long, default_value_t = 1)]
    pub tool_number: u32,
    /// Spindle speed, rev/min (0 leaves the spindle alone: no S, M3 or M5).
    #[arg(long, default_value_t = 10000.0)]
    pub spindle: f64,
    /// Coolant: flood (M8), mist (M7) or off.
    #[arg(long, default_value = "flood")]
    pub coolant: Coolant,
    /// Write N line numbers.
    #[arg(long)]
    pub line_numbers: bool,
}

impl OutputArgs {
    /// The engine's program settings these flags give.
    pub fn settings(&self) -> ProgramSettings {
        ProgramSettings {
            dialect: self.dialect,
            units: self.units,
            decimals: self.decimals,
            tool_number: self.tool_number,
            spindle: self.spindle,
            coolant: self.coolant,
            line_numbers: self.line_numbers,
        }
    }
}
