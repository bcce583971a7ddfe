//! `millpath.job` and `millpath.job_init`: a whole part from a job file, and a starting job
//! file for a drawing, as `millpath job` and `millpath job --init` make them.

use crate::convert::{Kwargs, err, to_py};
use crate::objects::Toolpath;
use millpath::gcode::Dialect;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::PathBuf;

/// What `millpath.job` made.
#[pyclass(module = "millpath", frozen, get_all)]
#[derive(Debug)]
pub struct JobResult {
    /// The program text, byte for byte what `millpath job FILE -o OUT` writes.
    pub gcode: String,
    /// Cycle time of the written program on the machine, tool changes included, s.
    pub cycle_time_s: f64,
    /// The report, as `--report` writes it (a dict): tools, operations with their times and
    /// checks, the whole-stock check.
    pub report: PyObject,
    /// Every operation's toolpath joined (for pictures and playback).
    pub toolpath: Py<Toolpath>,
    /// What the user should know (a pocket left out, what the drawing held).
    pub notes: Vec<String>,
}

#[pymethods]
impl JobResult {
    fn __repr__(&self) -> String {
        format!(
            "JobResult(cycle_time_s={:.3}, {} bytes of G-code)",
            self.cycle_time_s,
            self.gcode.len()
        )
    }
}

fn dialect_of(k: &mut Kwargs<'_>) -> PyResult<Option<Dialect>> {
    let mut d: Option<String> = None;
    k.opt_text("dialect", &mut d)?;
    d.map(|d| {
        d.parse::<Dialect>()
            .map_err(|e| crate::convert::input_err(e.at("dialect")))
    })
    .transpose()
}

/// Run a job file: `millpath job FILE` as a function; keywords `dialect` and `machine`
/// override the file's.
#[pyfunction]
#[pyo3(signature = (path, **kwargs))]
pub fn job(
    py: Python<'_>,
    path: &Bound<'_, PyAny>,
    kwargs: Option<&Bound<'_, PyDict>>,
) -> PyResult<JobResult> {
    let path: PathBuf = path.extract()?;
    let mut k = Kwargs::new(kwargs, "job")?;
    let dialect = dialect_of(&mut k)?;
    let mut machine: Option<String> = None;
    k.opt_text("machine", &mut machine)?;
    k.finish()?;
    let mut notes = Vec::new();
    let run = py
        .allow_threads(|| {
            millpath::job::part::run_file(&path, dialect, machine.as_deref(), &mut |n| {
                notes.push(n);
            })
        })
        .map_err(err)?;
    let gcode = String::from_utf8(run.run.gcode.clone()).map_err(|e| {
        crate::InternalError::new_err(format!("the job's program is not UTF-8: {e}"))
    })?;
    Ok(JobResult {
        gcode,
        cycle_time_s: run.report.cycle_time_s,
        report: to_py(py, &run.report)?,
        toolpath: Py::new(
            py,
            Toolpath {
                tp: run.run.toolpath(),
            },
        )?,
        notes,
    })
}

/// A starting job file for a drawing: the text `millpath job --init DRAWING -o OUTPUT`
/// writes (`output` only decides how the file names the drawing: relative to its folder;
/// nothing is written). Keywords: `dialect`, `machine`, `layer`, `drawing_units`,
/// `join_tolerance`.
#[pyfunction]
#[pyo3(signature = (drawing, output = None, **kwargs))]
pub fn job_init(
    py: Python<'_>,
    drawing: &Bound<'_, PyAny>,
    output: Option<&Bound<'_, PyAny>>,
    kwargs: Option<&Bound<'_, PyDict>>,
) -> PyResult<String> {
    let drawing: PathBuf = drawing.extract()?;
    let output: Option<PathBuf> = output.map(|o| o.extract()).transpose()?;
    let mut k = Kwargs::new(kwargs, "job_init")?;
    let import = k.import()?;
    let dialect = dialect_of(&mut k)?.unwrap_or(Dialect::LinuxCnc);
    let mut machine = "hsm".to_owned();
    k.text("machine", &mut machine)?;
    k.finish()?;
    let out = output.unwrap_or_else(|| PathBuf::from("job.toml"));
    py.allow_threads(|| {
        millpath::job::part::init_file(&drawing, &out, &import, dialect, &machine, &mut |_| {})
    })
    .map_err(err)
}
