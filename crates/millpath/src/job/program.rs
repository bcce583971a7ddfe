//! The G-code output settings every program-writing job shares (the CLI's `--dialect`,
//! `--units`, `--decimals`, `--tool-number`, `--spindle`, `--coolant`, `--line-numbers`),
//! each checked with the flag named, and the cycle time of a written program read back the
//! way `millpath estimate` reads it.

use crate::gcode::format::MAX_DECIMALS;
use crate::gcode::{
    Coolant, Dialect, Reader, ReaderOptions, Units, WriterOptions, rounding_error_mm,
};
use crate::machine::{Controller, Machine};
use crate::{Error, InputError};
use std::io::BufReader;

/// Largest tool number accepted: four digits (Fanuc's `T` word; LinuxCNC and Sinumerik take
/// more, Grbl only names it in a comment).
pub const MAX_TOOL_NUMBER: u32 = 9999;

/// How a program is written.
#[derive(Debug, Clone, PartialEq)]
pub struct ProgramSettings {
    /// G-code dialect.
    pub dialect: Dialect,
    /// Program units (inside, everything stays in mm; only the text converts).
    pub units: Units,
    /// Decimals of coordinates (`None`: the dialect's, raised to what the job's tolerance
    /// needs).
    pub decimals: Option<u32>,
    /// Tool number: `T n M6` and the tool length offset; 0 writes no tool change.
    pub tool_number: u32,
    /// Spindle speed, rev/min (0 leaves the spindle alone).
    pub spindle: f64,
    /// Coolant.
    pub coolant: Coolant,
    /// Write N line numbers.
    pub line_numbers: bool,
}

impl Default for ProgramSettings {
    fn default() -> Self {
        ProgramSettings {
            dialect: Dialect::LinuxCnc,
            units: Units::Mm,
            decimals: None,
            tool_number: 1,
            spindle: 10000.0,
            coolant: Coolant::Flood,
            line_numbers: false,
        }
    }
}

impl ProgramSettings {
    /// The writer's options for these settings, each checked with its flag named: the
    /// dialect, units, `decimals` (as the job settled them), tool, spindle, coolant,
    /// numbering and the program's name.
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
        let w = WriterOptions::default()
            .with_dialect(self.dialect)
            .with_units(self.units)
            .with_decimals(Some(decimals))
            .with_line_numbers(self.line_numbers)
            .with_spindle_rpm(self.spindle)
            .with_coolant(self.coolant)
            .with_program_name(Some(name))
            .with_tool_change(self.tool_number > 0)
            .with_tool_number(Some(self.tool_number));
        w.validate()?;
        Ok(w)
    }

    /// The decimals to write: `decimals` when given and fine enough that coordinates round
    /// by at most `max_rounding_mm` (else an input error naming `why` and the least that
    /// would do), else the dialect's default raised to that.
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

/// The cycle time of a written program on `machine`, read back as `millpath estimate` reads
/// it (streaming reader, look-ahead planner; LinuxCNC's sync points on a `linuxcnc` machine).
pub fn program_time(
    bytes: &[u8],
    dialect: Dialect,
    origin: &str,
    machine: &Machine,
) -> Result<f64, Error> {
    program_times(bytes, dialect, origin, machine).map(|(t, _)| t)
}

/// [`program_time`] and the same program's time at its programmed feeds (each block's
/// length over its feed, rapids at the machine's rapid speed along them, no acceleration):
/// the difference is the time the machine's limits cost it, slowing down for corners,
/// curves and stops.
pub fn program_times(
    bytes: &[u8],
    dialect: Dialect,
    origin: &str,
    machine: &Machine,
) -> Result<(f64, f64), Error> {
    use crate::motion::stream::{StreamOptions, plan_stream};
    let opts = ReaderOptions::default()
        .with_dialect(dialect)
        .with_origin(origin)
        .with_sync_points((machine.controller == Controller::LinuxCnc).then_some(machine.sync_wait))
        .with_tool_change_time(Some(machine.tool_change_time));
    let mut at = opts.start;
    let mut reader = Reader::new(BufReader::new(bytes), opts);
    let tracked = std::iter::from_fn(|| {
        reader.next().map(|item| {
            item.map(|rm| {
                let f = at;
                at = rm.mv.to;
                (f, rm.mv)
            })
        })
    });
    let sum = plan_stream(tracked, machine, &StreamOptions::default(), |_| Ok(()))?;
    Ok((sum.total_time, sum.time_at_programmed_feed))
}
