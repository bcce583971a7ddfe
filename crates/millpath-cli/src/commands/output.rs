//! The G-code output flags every program-writing command shares (`contour`, `pocket`,
//! `five-axis`): one definition, flattened into each command's arguments
//! (`#[command(flatten)]`), so that `--dialect`, `--units`, `--decimals`, `--tool-number`,
//! `--spindle`, `--coolant` and `--line-numbers` are spelled, defaulted and checked alike.
//!
//! ```text
//! millpath pocket part.dxf --dialect fanuc --units in -o part.nc
//! millpath contour pts.csv --dialect sinumerik --tool-number 4 --coolant mist -o part.mpf
//! millpath five-axis --case paper --machine xyzac-trt --gcode traj.nc --dialect fanuc
//! ```

use millpath::gcode::format::MAX_DECIMALS;
use millpath::gcode::{Coolant, Dialect, Units, WriterOptions, rounding_error_mm};
use millpath::{Error, InputError};

/// Largest tool number accepted: four digits (Fanuc's `T` word; LinuxCNC and Sinumerik take
/// more, Grbl only names it in a comment).
pub const MAX_TOOL_NUMBER: u32 = 9999;

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
    /// The writer's options for these flags, each checked with its flag named: the dialect,
    /// units, `decimals` (as the command settled them), tool, spindle, coolant, numbering and
    /// the program's name.
    pub fn writer_options(&self, decimals: u32, name: String) -> Result<WriterOptions, Error> {
        if decimals > MAX_DECIMALS {
            return Err(InputError::new("decimals", decimals)
                .at("--decimals")
                .expected(format!("0 to {MAX_DECIMALS}"))
                .into());
        }
        if self.tool_number > MAX_TOOL_NUMBER {
            return Err(InputError::new("tool number", self.tool_number)
                .at("--tool-number")
                .expected(format!("0 to {MAX_TOOL_NUMBER} (0: no tool change)"))
                .into());
        }
        if !(self.spindle.is_finite() && self.spindle >= 0.0) {
            return Err(InputError::new("spindle speed", self.spindle)
                .at("--spindle")
                .expected("a finite number >= 0 rev/min (0: spindle left alone)")
                .into());
        }
        let w = WriterOptions {
            dialect: self.dialect,
            units: self.units,
            decimals: Some(decimals),
            line_numbers: self.line_numbers,
            spindle_rpm: self.spindle,
            coolant: self.coolant,
            program_name: Some(name),
            tool_change: self.tool_number > 0,
            tool_number: Some(self.tool_number),
            ..WriterOptions::default()
        };
        w.validate()?;
        Ok(w)
    }

    /// The decimals to write: `--decimals` when given and fine enough that coordinates round
    /// by at most `max_rounding_mm` (else exit 2, naming `why` and the least that would do),
    /// else the dialect's default raised to that.
    pub fn decimals_within(&self, max_rounding_mm: f64, why: &str) -> Result<u32, Error> {
        let least = (0..=MAX_DECIMALS)
            .find(|&d| rounding_error_mm(d, self.units) <= max_rounding_mm * (1.0 + 1e-9))
            .unwrap_or(MAX_DECIMALS);
        match self.decimals {
            Some(d) if d < least => Err(InputError::new("decimals", d)
                .at("--decimals")
                .expected(format!(
                    "at least {least} decimals in {}: {d} round a point by up to {:.3e} mm, \
                     more than {why} ({max_rounding_mm:.3e} mm)",
                    match self.units {
                        Units::Mm => "millimetres",
                        Units::Inch => "inches",
                    },
                    rounding_error_mm(d, self.units)
                ))
                .into()),
            Some(d) => Ok(d),
            None => Ok(self.dialect.default_decimals(self.units).max(least)),
        }
    }
}
