//! What every operation of a job is planned in ([`OpContext`]) and gives back ([`OpResult`]),
//! and the job file's terms for an operation's errors.

use super::block::StockBlock;
use super::model::PartModel;
use super::spec::{JobOperation, JobSpec, JobTool};
use crate::Error;
use crate::error::InputError;
use crate::machine::Machine;
use crate::toolpath::{Tool, Toolpath};

/// What every operation's planning sees.
#[derive(Debug, Clone, Copy)]
pub struct OpContext<'a> {
    /// The job.
    pub spec: &'a JobSpec,
    /// The drawing's parts, pockets and holes.
    pub model: &'a PartModel,
    /// The stock.
    pub stock: StockBlock,
    /// The machine the cycle times are for.
    pub machine: &'a Machine,
    /// The rounding of the written coordinates, mm.
    pub rounding: f64,
}

impl OpContext<'_> {
    /// The clearance height: above the stock's top by the job's clearance.
    pub fn clearance_z(&self) -> f64 {
        self.stock.top + self.spec.clearance_height
    }
}

/// What an operation planned, and its verifier's figures.
#[derive(Debug, Clone)]
pub struct OpResult {
    /// The toolpath, from and back to the clearance height.
    pub toolpath: Toolpath,
    /// What it cut, for the setup sheet (`pockets 1, 2, 4`).
    pub cut: String,
    /// Its verifier's figures (name, value), for the report.
    pub checks: Vec<(String, String)>,
    /// The profile's tabs.
    pub tabs: Vec<crate::strategy::profile::PlacedTab>,
    /// The holes it made (drill, bore).
    pub holes: Vec<crate::geom::Hole>,
}

/// Where an operation is in the job file, for messages.
pub(crate) fn op_at(spec: &JobSpec, op: &JobOperation) -> String {
    format!(
        "{} line {}, operation {} ({})",
        spec.origin,
        op.line,
        op.name,
        op.kind.name()
    )
}

/// An input error of an operation's settings, its origin put in the job file's terms (a
/// flag `--step-down` becomes the key `step_down`).
pub(crate) fn in_op(e: Error, spec: &JobSpec, op: &JobOperation) -> Error {
    match e {
        Error::Input(mut i) => {
            let key = i
                .origin
                .as_deref()
                .map(|o| match o.strip_prefix("--") {
                    Some(flag) => format!(", key {}", flag.replace('-', "_")),
                    None => format!(", {o}"),
                })
                .unwrap_or_default();
            i.origin = Some(format!("{}{key}", op_at(spec, op)));
            Error::Input(i)
        }
        other => other,
    }
}

/// The flat end mill `tool` is, for the strategies.
pub(crate) fn end_mill(tool: &JobTool) -> Result<Tool, InputError> {
    let mut t = Tool::flat(tool.diameter)?;
    t.number = tool.number;
    t.flutes = tool.flutes;
    t.flute_length = tool.flute_length;
    Ok(t)
}
