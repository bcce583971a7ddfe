//! The job behind `millpath job part.toml`: a drawing made into a whole part by several
//! operations (face, pocket, profile, drill, bore), each with its own tool, in one program.
//!
//! ```text
//! job file (spec) ─▶ drawing ─▶ part model (parts, pockets, holes)
//!     ─▶ each operation planned with its tool and verified alone (ops)
//!     ─▶ one program with the tool changes ─▶ its cycle time read back (timing)
//!     ─▶ the whole stock cut operation after operation and compared with the drawn part
//!        (check, design) ─▶ the report and the setup sheet (report)
//! ```
//!
//! A program is returned only when every operation passed its own verifier and the whole
//! job passed the stock check: the drawn part left, held by exactly its tabs.

mod block;
mod check;
mod context;
mod design;
mod init;
mod keys;
mod model;
mod op_face;
mod op_holes;
mod op_pocket;
mod op_profile;
mod ops;
mod pocket_keys;
mod report;
mod run;
mod spec;
mod timing;
mod verify;

pub use block::{StockBlock, stock_block};
pub use check::{HoldCheck, JobCheck};
pub use context::OpResult;
pub use init::{DRILL_MAX, DRILL_OVER, END_MILLS, end_mill_at_most};
pub use model::{ModelHole, ModelPocket, PartModel};
pub use report::{JobReport, OperationRow, ToolRow, report, setup_sheet};
pub use run::{JobRun, OperationRun, run};
pub use spec::{
    BoreSettings, Depth, DrillSettings, FaceSettings, JobOperation, JobSpec, JobTool,
    OperationKind, ProfileSettings, StockSettings, ToolKind, parse,
};
pub use verify::{JobVerifyRun, verify_program};

use crate::Error;
use crate::gcode::Dialect;
use crate::io::ImportSettings;
use crate::toolpath::{Level, Toolpath};
use std::path::Path;

/// A job run from its file, with its report.
#[derive(Debug)]
pub struct FileRun {
    /// The job file as read.
    pub spec: JobSpec,
    /// What the job made.
    pub run: JobRun,
    /// Its report.
    pub report: JobReport,
}

/// Reads the job file `path` (its drawing relative to its folder), with the dialect and the
/// machine given over the file's, and runs it.
pub fn run_file(
    path: &Path,
    dialect: Option<Dialect>,
    machine: Option<&str>,
    note: &mut dyn FnMut(String),
) -> Result<FileRun, Error> {
    let mut spec = read_file(path)?;
    if let Some(d) = dialect {
        spec.dialect = d;
    }
    if let Some(m) = machine {
        spec.machine = m.to_owned();
    }
    run_spec(spec, note)
}

/// Reads the job file `path` (its drawing relative to its folder).
pub fn read_file(path: &Path) -> Result<JobSpec, Error> {
    let text = crate::io::read_text(path)?;
    Ok(parse(&text, &path.display().to_string(), path.parent())?)
}

/// Runs a job already read.
pub fn run_spec(spec: JobSpec, note: &mut dyn FnMut(String)) -> Result<FileRun, Error> {
    let (loops, drawing_note) = load_drawing(&spec.drawing, &spec.import).map_err(|e| match e {
        Error::Input(i) if i.origin.is_none() => {
            Error::Input(i.at(format!("{} key drawing", spec.origin)))
        }
        other => other,
    })?;
    if let Some(n) = drawing_note {
        note(n);
    }
    let run = run(&spec, &loops, note)?;
    let report = report(&spec, &run);
    Ok(FileRun { spec, run, report })
}

/// The starting job file for `drawing` (the sizing rules of `job --init`), naming the drawing relative to
/// where the job file `out` goes.
pub fn init_file(
    drawing: &Path,
    out: &Path,
    import: &ImportSettings,
    dialect: Dialect,
    machine: &str,
    note: &mut dyn FnMut(String),
) -> Result<String, Error> {
    crate::job::load_machine(machine)?;
    let name = drawing.display().to_string();
    let (loops, drawing_note) = load_drawing(&name, import)?;
    if let Some(n) = drawing_note {
        note(n);
    }
    let pockets = loops.pockets();
    let model = PartModel::new(&pockets, &|o| {
        crate::geom::Hole::from_outline(o, crate::geom::CIRCLE_TOLERANCE)
            .map(|h| (h.center, h.diameter))
    });
    let named = if name == SAMPLE_PART {
        name.clone()
    } else {
        relative(drawing, out.parent().unwrap_or(Path::new("")))
    };
    let mut text = init::job_file(&named, &model, &dialect.to_string(), machine);
    let joined = (import.join_tolerance - ImportSettings::default().join_tolerance).abs() > 1e-12;
    if import.layer.is_some() || import.drawing_units.is_some() || joined {
        let mut extra = String::new();
        if let Some(l) = &import.layer {
            extra.push_str(&format!("layer = \"{}\"\n", l.replace('"', "\\\"")));
        }
        if let Some(u) = &import.drawing_units {
            extra.push_str(&format!("drawing_units = \"{u}\"\n"));
        }
        if joined {
            extra.push_str(&format!("join_tolerance = {:?}\n", import.join_tolerance));
        }
        if let Some(k) = text.find("machine = ") {
            text.insert_str(k, &extra);
        }
    }
    Ok(text)
}

/// A hole's circle as an outline (two half arcs), for pictures.
pub fn hole_outline(
    center: crate::geom::Point,
    diameter: f64,
) -> Result<crate::geom::Outline, Error> {
    design::circle(&crate::geom::Hole::new(center, diameter))
}

/// The built-in sample part's drawing name (`crate::job::sample_part_job_drawing`).
pub const SAMPLE_PART: &str = "sample:part";

/// Reads a job's drawing: a DXF or SVG file, or a built-in sample ([`SAMPLE_PART`],
/// [`crate::job::load_outline`]).
pub fn load_drawing(
    name: &str,
    import: &ImportSettings,
) -> Result<(crate::io::outline_json::Loops, Option<String>), Error> {
    crate::job::load_outline(name, import)
}

/// `to` as a path from the folder `from` (both made absolute against the current folder):
/// `../drawings/part.dxf`; `to` as given when there is no common root.
fn relative(to: &Path, from: &Path) -> String {
    let abs = |p: &Path| -> Vec<std::ffi::OsString> {
        std::path::absolute(p)
            .unwrap_or_else(|_| p.to_path_buf())
            .components()
            .map(|c| c.as_os_str().to_owned())
            .collect()
    };
    let (t, f) = (abs(to), abs(from));
    let common = t.iter().zip(&f).take_while(|(a, b)| a == b).count();
    if common == 0 {
        return to.display().to_string();
    }
    let mut p = std::path::PathBuf::new();
    for _ in common..f.len() {
        p.push("..");
    }
    for c in &t[common..] {
        p.push(c);
    }
    p.display().to_string()
}

impl JobRun {
    /// Every operation's toolpath joined into one (the tool of the first), for pictures and
    /// playback.
    pub fn toolpath(&self) -> Toolpath {
        let mut ops = self.operations.iter();
        let Some(first) = ops.next() else {
            return Toolpath::new(
                crate::toolpath::Tool::default(),
                crate::geom::Point3::ORIGIN,
            );
        };
        let mut tp = first.result.toolpath.clone();
        for o in ops {
            let base = tp.moves.len();
            tp.moves.extend(o.result.toolpath.moves.iter().copied());
            tp.levels
                .extend(o.result.toolpath.levels.iter().map(|l| Level {
                    start: l.start + base,
                    end: l.end + base,
                    ..*l
                }));
        }
        tp
    }

    /// The joined toolpath planned on the job's machine (tool changes not timed: see
    /// [`JobRun::cycle_time_s`] for the program's time).
    pub fn plan(&self) -> Result<crate::motion::Plan, Error> {
        crate::motion::plan_toolpath(&self.toolpath(), &self.machine)
            .map_err(|e| e.engine_made("timing the job's toolpath"))
    }
}
