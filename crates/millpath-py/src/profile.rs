//! `millpath.profile`: a drawing's outlines cut out, as `millpath profile` does.

use crate::convert::{Kwargs, err, input_err, outline_arg, to_py};
use crate::objects::Toolpath;
use millpath::job::profile::{ProfileSettings, ProfileSource};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// What `millpath.profile` made.
#[pyclass(module = "millpath", frozen, get_all)]
#[derive(Debug)]
pub struct ProfileResult {
    /// The program text, byte for byte what `millpath profile … -o FILE` writes.
    pub gcode: String,
    /// Cycle time of the written program on the machine, s (the report's).
    pub cycle_time_s: f64,
    /// The report, as `--report` writes it (a dict).
    pub report: PyObject,
    /// The toolpath.
    pub toolpath: Py<Toolpath>,
    /// What the profile did differently from what was asked, and what the drawing held.
    pub notes: Vec<String>,
}

#[pymethods]
impl ProfileResult {
    fn __repr__(&self) -> String {
        format!(
            "ProfileResult(cycle_time_s={:.3}, {} bytes of G-code)",
            self.cycle_time_s,
            self.gcode.len()
        )
    }
}

/// Cut a drawing's outlines out: `millpath profile DRAWING --flags` (or `sample=True` for the
/// paper's die cavity) as a function; keywords are the CLI's flags.
#[pyfunction]
#[pyo3(signature = (drawing = None, **kwargs))]
pub fn profile(
    py: Python<'_>,
    drawing: Option<&Bound<'_, PyAny>>,
    kwargs: Option<&Bound<'_, PyDict>>,
) -> PyResult<ProfileResult> {
    let mut k = Kwargs::new(kwargs, "profile")?;
    let mut sample = false;
    k.bool("sample", &mut sample)?;
    let mut s = ProfileSettings {
        import: k.import()?,
        ..ProfileSettings::default()
    };
    k.text("side", &mut s.side)?;
    k.opt_f64("tool_diameter", &mut s.tool_diameter)?;
    k.opt_f64("depth", &mut s.depth)?;
    k.opt_f64("stock_thickness", &mut s.stock_thickness)?;
    k.opt_f64("step_down", &mut s.step_down)?;
    k.opt_f64("stock_to_leave", &mut s.stock_to_leave)?;
    k.bool("conventional", &mut s.conventional)?;
    k.f64("lead_radius", &mut s.lead_radius)?;
    k.text("entry", &mut s.entry)?;
    k.f64("helix_radius", &mut s.helix_radius)?;
    k.f64("ramp_angle", &mut s.ramp_angle)?;
    k.opt_f64("tolerance", &mut s.tolerance)?;
    k.text("feed", &mut s.feed)?;
    k.f64("plunge_feed", &mut s.plunge_feed)?;
    k.f64("safe_height", &mut s.safe_height)?;
    k.f64("clearance_height", &mut s.clearance_height)?;
    k.text("tabs", &mut s.tabs)?;
    k.f64("tab_width", &mut s.tab_width)?;
    k.f64("tab_height", &mut s.tab_height)?;
    k.text("tab_shape", &mut s.tab_shape)?;
    k.text("machine", &mut s.machine)?;
    let program = k.program()?;
    k.finish()?;
    // The flags are checked before the drawing is read, as the CLI does.
    s.options(sample).map_err(err)?;
    let drawing = drawing.filter(|d| !d.is_none());
    let mut notes = Vec::new();
    let run = match (drawing, sample) {
        (Some(d), false) => {
            let (loops, name, note) = outline_arg(py, d, "drawing", &s.import)?;
            notes.extend(note);
            notes.extend(loops.notes.iter().map(|n| format!("{name}: {n}")));
            py.allow_threads(|| {
                millpath::job::profile::run(
                    ProfileSource::Drawing {
                        loops: &loops,
                        name: &name,
                    },
                    &s,
                    &program,
                )
            })
        }
        (None, true) => {
            py.allow_threads(|| millpath::job::profile::run(ProfileSource::Sample, &s, &program))
        }
        (Some(_), true) => {
            return Err(input_err(
                millpath::InputError::new("drawing", "given with sample=True")
                    .expected("either a drawing or sample=True"),
            ));
        }
        (None, false) => {
            return Err(input_err(
                millpath::InputError::new("drawing", "missing").expected(
                    "a drawing (a .dxf, .svg or .json path, or outline arrays) or sample=True",
                ),
            ));
        }
    }
    .map_err(err)?;
    notes.extend(run.report.notes.iter().cloned());
    Ok(ProfileResult {
        cycle_time_s: run.report.cycle_time_s,
        report: to_py(py, &run.report)?,
        gcode: run.gcode,
        toolpath: Py::new(
            py,
            Toolpath {
                tp: run.result.toolpath,
            },
        )?,
        notes,
    })
}
