//! The writer's options: dialect, units, decimals, numbering, spindle, coolant, header, path
//! tolerance and tool change, with their defaults and checks.
//!
//! Lengths are in mm (converted to inches on output with G20), the spindle speed in rev/min.

use crate::error::InputError;
use crate::gcode::dialect::{Coolant, Dialect, Units};
use crate::gcode::format::MAX_DECIMALS;

/// How to write a program. Built from [`Default`] with the `with_*` methods (the struct is
/// `#[non_exhaustive]`: new settings do not break callers).
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct WriterOptions {
    /// The dialect.
    pub dialect: Dialect,
    /// G21 (mm) or G20 (inch): coordinates and feeds are converted on output.
    pub units: Units,
    /// Decimals of coordinates, offsets and feeds; `None`: the dialect's default
    /// ([`Dialect::default_decimals`]). Use [`crate::gcode::required_decimals`] to derive it from a
    /// tolerance.
    pub decimals: Option<u32>,
    /// Write `N` numbers.
    pub line_numbers: bool,
    /// Step between `N` numbers.
    pub line_number_step: u32,
    /// Work offset: 54..=59 (G54..G59).
    pub work_offset: u8,
    /// Spindle speed in rev/min; 0 leaves the spindle alone (no S, no M3/M4/M5).
    pub spindle_rpm: f64,
    /// Spindle clockwise (M3) or counter-clockwise (M4).
    pub spindle_cw: bool,
    /// Coolant.
    pub coolant: Coolant,
    /// Path tolerance in mm for the controller's blending, stated in the header: `G64 P`
    /// (LinuxCNC), `CYCLE832(tol,_FINISH,1)` (Sinumerik), `G05.1 Q1` (Fanuc AI contour
    /// control; its tolerance is a machine parameter, so the value goes into a comment),
    /// nothing (Grbl: a comment). A tolerance that rounds to 0 at the written decimals
    /// (`Some(0.0)` included) is exact stop at every corner (`G61.1`, `G60`, `G61`): LinuxCNC
    /// reads `G64 P0` as *no* limit. `None` states nothing (the controller's default).
    /// [`WriterOptions::with_path_tolerance`] sets it with the decimals it needs; assign the
    /// field to state a tolerance at the decimals already chosen.
    pub path_tolerance: Option<f64>,
    /// Program name: a header comment (and the Fanuc `O` line's comment).
    pub program_name: Option<String>,
    /// Fanuc program number (`O0001`).
    pub program_number: u32,
    /// Write header comments.
    pub comments: bool,
    /// Extra header comment lines (tolerances, sources...).
    pub header_notes: Vec<String>,
    /// Write the tool change (`T.. M6`, a comment for Grbl) and tool length compensation.
    pub tool_change: bool,
    /// The tool number written (`T`, Fanuc's `H`), in place of the toolpath's own
    /// ([`crate::toolpath::Tool::number`]); `None` keeps the toolpath's.
    pub tool_number: Option<u32>,
}

impl Default for WriterOptions {
    fn default() -> Self {
        WriterOptions {
            dialect: Dialect::LinuxCnc,
            units: Units::Mm,
            decimals: None,
            line_numbers: false,
            line_number_step: 10,
            work_offset: 54,
            spindle_rpm: 10_000.0,
            spindle_cw: true,
            coolant: Coolant::Flood,
            path_tolerance: None,
            program_name: None,
            program_number: 1,
            comments: true,
            header_notes: Vec::new(),
            tool_change: true,
            tool_number: None,
        }
    }
}

impl WriterOptions {
    /// The decimals actually used.
    pub fn effective_decimals(&self) -> u32 {
        self.decimals
            .unwrap_or_else(|| self.dialect.default_decimals(self.units))
    }

    /// These options with enough decimals for a path tolerance of `tolerance_mm`: the larger
    /// of the current decimals and [`crate::gcode::required_decimals`] (rounding within 10 %
    /// of the tolerance, see `gcode::format`).
    #[must_use]
    pub fn with_tolerance(mut self, tolerance_mm: f64) -> Self {
        let need = crate::gcode::required_decimals(tolerance_mm, self.units);
        self.decimals = Some(self.effective_decimals().max(need));
        self
    }

    /// These options stating `tolerance_mm` as the program's path tolerance
    /// ([`WriterOptions::path_tolerance`]), with enough decimals to hold it
    /// ([`WriterOptions::with_tolerance`]; none are added for 0, exact stop). Programs that
    /// are timed on a machine state that machine's path tolerance, so that the estimate of
    /// the program read back uses the tolerance the program was timed with.
    #[must_use]
    pub fn with_path_tolerance(mut self, tolerance_mm: f64) -> Self {
        self.path_tolerance = Some(tolerance_mm);
        if tolerance_mm > 0.0 {
            self.with_tolerance(tolerance_mm)
        } else {
            self
        }
    }

    /// Checks the options (work offset, decimals, spindle speed, path tolerance), as
    /// [`write_program`](crate::gcode::write_program) does first: callers whose options come
    /// from the user check them here, so that what `write_program` refuses afterwards is a
    /// property of the toolpath.
    pub fn validate(&self) -> Result<(), InputError> {
        if !(54..=59).contains(&self.work_offset) {
            return Err(InputError::new("work offset", self.work_offset)
                .at("writer options")
                .expected("54 to 59 (G54..G59)"));
        }
        if self.effective_decimals() > MAX_DECIMALS {
            return Err(InputError::new("decimals", self.effective_decimals())
                .at("writer options")
                .expected(format!("0 to {MAX_DECIMALS}")));
        }
        if !(self.spindle_rpm.is_finite() && self.spindle_rpm >= 0.0) {
            return Err(InputError::new("spindle speed", self.spindle_rpm)
                .at("writer options")
                .expected("a finite number >= 0 rev/min"));
        }
        if let Some(t) = self.path_tolerance
            && !(t.is_finite() && t >= 0.0)
        {
            return Err(InputError::new("path tolerance", t)
                .at("writer options")
                .expected("a finite number >= 0 mm (0: exact stop)"));
        }
        Ok(())
    }
}

option_builders! {
    WriterOptions;
    /// Sets [`WriterOptions::dialect`].
    with_dialect => dialect: Dialect;
    /// Sets [`WriterOptions::units`].
    with_units => units: Units;
    /// Sets [`WriterOptions::decimals`].
    with_decimals => decimals: Option<u32>;
    /// Sets [`WriterOptions::line_numbers`].
    with_line_numbers => line_numbers: bool;
    /// Sets [`WriterOptions::line_number_step`].
    with_line_number_step => line_number_step: u32;
    /// Sets [`WriterOptions::work_offset`], 54..=59.
    with_work_offset => work_offset: u8;
    /// Sets [`WriterOptions::spindle_rpm`], rev/min.
    with_spindle_rpm => spindle_rpm: f64;
    /// Sets [`WriterOptions::spindle_cw`].
    with_spindle_cw => spindle_cw: bool;
    /// Sets [`WriterOptions::coolant`].
    with_coolant => coolant: Coolant;
    /// Sets [`WriterOptions::program_name`].
    with_program_name => program_name: Option<String>;
    /// Sets [`WriterOptions::program_number`].
    with_program_number => program_number: u32;
    /// Sets [`WriterOptions::comments`].
    with_comments => comments: bool;
    /// Sets [`WriterOptions::header_notes`].
    with_header_notes => header_notes: Vec<String>;
    /// Sets [`WriterOptions::tool_change`].
    with_tool_change => tool_change: bool;
    /// Sets [`WriterOptions::tool_number`].
    with_tool_number => tool_number: Option<u32>;
}
