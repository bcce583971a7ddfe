//! Running a job: every operation planned with its tool on the drawing's part model, each
//! verified by its own verifier, the whole stock simulated operation after operation, one
//! program written with the tool changes, and its cycle time read back from that program.

use super::block::{StockBlock, stock_block};
use super::context::{OpContext, OpResult};
use super::model::PartModel;
use super::ops;
use super::spec::{JobOperation, JobSpec, JobTool, OperationKind};
use crate::Error;
use crate::error::InputError;
use crate::gcode::{ProgramSection, WriterOptions, write_sections};
use crate::geom::Hole;
use crate::io::outline_json::Loops;
use crate::machine::Machine;
use crate::toolpath::Toolpath;
use rayon::prelude::*;

/// One operation as planned.
#[derive(Debug, Clone)]
pub struct OperationRun {
    /// Its name.
    pub name: String,
    /// `face`, `pocket`, `profile`, `drill` or `bore`.
    pub kind: &'static str,
    /// Its tool.
    pub tool: JobTool,
    /// What it planned and verified.
    pub result: OpResult,
    /// Its share of the program's cycle time, s (from the read-back program).
    pub time_s: f64,
}

/// What a job made.
#[derive(Debug)]
pub struct JobRun {
    /// The program text.
    pub gcode: Vec<u8>,
    /// The operations, in order.
    pub operations: Vec<OperationRun>,
    /// The program's cycle time on the machine, s (read back from the text, tool changes
    /// included).
    pub cycle_time_s: f64,
    /// The machine.
    pub machine: Machine,
    /// The part model the drawing gave.
    pub model: PartModel,
    /// The stock.
    pub stock: StockBlock,
    /// The whole job's check on the stock simulation.
    pub check: super::check::JobCheck,
}

/// Runs `spec` on the drawing's outlines `loops`; `note` receives what the user should know
/// (a pocket left out, a hole no operation takes).
pub fn run(spec: &JobSpec, loops: &Loops, note: &mut dyn FnMut(String)) -> Result<JobRun, Error> {
    let machine = crate::job::load_machine(&spec.machine).map_err(|e| match e {
        Error::Input(i) => Error::Input(i.at(format!("{} key machine", spec.origin))),
        other => other,
    })?;
    let pockets = loops.pockets();
    let model = PartModel::new(&pockets, &|o| {
        Hole::from_outline(o, crate::geom::CIRCLE_TOLERANCE).map(|h| (h.center, h.diameter))
    });
    let stock = stock_block(spec, &model)?;
    let design = super::design::JobDesign::new(spec, &model)?;
    if stock.top > 0.0
        && !matches!(
            spec.operations.first().map(|o| &o.kind),
            Some(OperationKind::Face(_))
        )
    {
        return Err(InputError::new("[stock] top", stock.top)
            .at(spec.origin.clone())
            .expected(
                "0 (the stock's top is the part's), or a face operation first that cuts the \
                 material above the part's top away",
            )
            .into());
    }
    let (wopts, rounding) = writer_options(spec, &machine)?;
    let cx = OpContext {
        spec,
        model: &model,
        stock,
        machine: &machine,
        rounding,
    };
    // Each operation is planned on the part model alone, side by side; then each rest pass
    // (`rest_from`) after the operation it names, in the job's order. Their notes and the
    // first error come in the job's order, as if one after another.
    let tool_of = |op: &JobOperation| {
        spec.tool(op.tool).ok_or_else(|| {
            Error::from(
                InputError::new("tool", op.tool).at(format!("{} line {}", spec.origin, op.line)),
            )
        })
    };
    let mut planned: Vec<(Vec<String>, Option<Result<_, Error>>)> = spec
        .operations
        .par_iter()
        .map(|op| {
            let mut notes = Vec::new();
            if op.rest_from.is_some() {
                return (notes, None);
            }
            let r = tool_of(op).and_then(|tool| {
                ops::plan(&cx, op, tool, &mut |n| notes.push(n)).map(|r| (op, tool.clone(), r))
            });
            (notes, Some(r))
        })
        .collect();
    for (k, op) in spec.operations.iter().enumerate() {
        let Some(from) = op.rest_from.as_deref() else {
            continue;
        };
        // The last earlier operation of that name (checked when the file was read).
        let previous = spec.operations[..k]
            .iter()
            .rposition(|o| o.name == from)
            .and_then(|j| match &planned[j].1 {
                Some(Ok((_, _, r))) => Some(r.toolpath.clone()),
                _ => None,
            });
        // Without it (its own error comes first) the rest pass is not planned.
        planned[k].1 = previous.map(|previous| {
            tool_of(op).and_then(|tool| {
                ops::plan_rest(&cx, op, tool, &previous).map(|r| (op, tool.clone(), r))
            })
        });
    }
    let mut results = Vec::with_capacity(spec.operations.len());
    for (notes, r) in planned {
        notes.into_iter().for_each(&mut *note);
        if let Some(r) = r {
            results.push(r?);
        }
    }
    if results.len() != spec.operations.len() {
        return Err(Error::internal(
            "a rest pass was left unplanned though the operation it follows was planned",
        ));
    }
    let sections: Vec<(String, &Toolpath, &JobTool)> = results
        .iter()
        .enumerate()
        .map(|(k, (op, tool, r))| {
            (
                format!(
                    "operation {}: {} with T{} {}",
                    k + 1,
                    op.name,
                    tool.number,
                    tool.name
                ),
                &r.toolpath,
                tool,
            )
        })
        .collect();
    let descriptions: Vec<String> = results
        .iter()
        .map(|(_, t, _)| format!("{} D{} mm, {} flutes", t.kind.name(), t.diameter, t.flutes))
        .collect();
    let program: Vec<ProgramSection<'_>> = sections
        .iter()
        .zip(&descriptions)
        .map(|((title, tp, tool), d)| ProgramSection {
            toolpath: tp,
            tool_number: tool.number,
            tool_description: d,
            spindle_rpm: tool.spindle,
            coolant: spec.coolant,
            title,
        })
        .collect();
    let mut gcode = Vec::new();
    let written = write_sections(&program, &wopts, &mut gcode)
        .map_err(|e| e.engine_made("writing the job's program"))?;
    let names: Vec<String> = results.iter().map(|(op, _, _)| op.name.clone()).collect();
    let checked: Vec<super::check::Section<'_>> = results
        .iter()
        .zip(&names)
        .map(|((_, tool, r), name)| super::check::Section {
            name,
            toolpath: &r.toolpath,
            tool,
        })
        .collect();
    let placed: Vec<Vec<crate::strategy::profile::PlacedTab>> =
        results.iter().map(|(_, _, r)| r.tabs.clone()).collect();
    // The program's time (read back from its text) and the whole-job check (from the
    // toolpaths) side by side; a failure of the timing is reported first, as before.
    let (times, check) = rayon::join(
        || super::timing::section_times(&gcode, &wopts, &written.section_lines, &machine),
        || super::check::check_sections(&model, stock, &design, &checked, Some(&placed)),
    );
    let times = times.map_err(|e| e.engine_made("timing the job's written program"))?;
    let check = check?;
    let problems = check.problems();
    if !problems.is_empty() {
        return Err(Error::internal(format!(
            "the job's program fails the whole-job stock check: {}; nothing written",
            problems.join("; ")
        )));
    }
    let operations = results
        .into_iter()
        .zip(&times.per_section)
        .map(|((op, tool, r), t)| OperationRun {
            name: op.name.clone(),
            kind: op.kind.name(),
            tool,
            result: r,
            time_s: *t,
        })
        .collect();
    Ok(JobRun {
        gcode,
        operations,
        cycle_time_s: times.total,
        machine,
        model,
        stock,
        check,
    })
}

/// The writer's options for the job and the rounding of its coordinates (mm): the spec's
/// dialect, units and numbering, decimals fine enough for every operation's tolerance (a
/// profile's rounding at most a quarter of its tolerance), the program's path tolerance
/// (the job's `tolerance`, else the machine's where above 0, else 0.01 mm).
fn writer_options(spec: &JobSpec, machine: &Machine) -> Result<(WriterOptions, f64), Error> {
    let finest = spec
        .operations
        .iter()
        .filter_map(|o| match &o.kind {
            OperationKind::Profile(p) => Some(0.25 * p.tolerance),
            _ => None,
        })
        .fold(f64::INFINITY, f64::min);
    let program = crate::job::ProgramSettings {
        dialect: spec.dialect,
        units: spec.units,
        decimals: spec.decimals,
        tool_number: 1,
        spindle: 0.0,
        coolant: spec.coolant,
        line_numbers: spec.line_numbers,
    };
    let decimals = program
        .decimals_within(
            if finest.is_finite() { finest } else { 1.0 },
            "a quarter of a profile's tolerance",
        )
        .map_err(|e| match e {
            Error::Input(i) => Error::Input(i.at(format!("{} key decimals", spec.origin))),
            other => other,
        })?;
    let name = format!(
        "{} - {} operations",
        std::path::Path::new(&spec.origin)
            .file_name()
            .map_or(spec.origin.clone(), |f| f.to_string_lossy().into_owned()),
        spec.operations.len()
    );
    let mut w = program.writer_options(decimals, name)?;
    let tolerance = spec.tolerance.unwrap_or(if machine.path_tolerance > 0.0 {
        machine.path_tolerance
    } else {
        0.01
    });
    w.path_tolerance = Some(tolerance);
    Ok((w, crate::gcode::rounding_error_mm(decimals, spec.units)))
}
