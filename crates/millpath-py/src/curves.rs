//! `contour`, `verify` and `five_axis`: thin calls of `millpath::job::{contour, verify,
//! five_axis}` and of the five-axis planner.

use crate::convert::{Kwargs, err, input_err, outline_arg, path_text, to_py};
use crate::objects::Toolpath;
use millpath::job::contour::{ContourSettings, ContourSource};
use millpath::job::five_axis::FiveAxisSettings;
use millpath::job::verify::VerifySettings;
use millpath::motion::five_axis::LimitsFile;
use numpy::{PyArray1, PyArray2, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString};

/// A text argument that is a path to read or the text itself: `(text, name)`.
fn text_or_path(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Option<(String, String)>> {
    let Some(p) = path_text(obj)? else {
        return Ok(None);
    };
    if !obj.is_instance_of::<PyString>()
        || (!p.contains('\n') && std::path::Path::new(&p).is_file())
        || crate::convert::looks_like_path(&p)
    {
        let t = millpath::io::read_text(std::path::Path::new(&p)).map_err(err)?;
        return Ok(Some((t, p)));
    }
    Ok(Some((p, format!("{what} (text)"))))
}

/// Points as CSV text: an N × 2 array (x, y) or N × 3 (x, y, group), written exactly (the
/// shortest text that reads back to the same f64), so that the engine reads them as it reads
/// a CSV file.
fn points_csv(obj: &Bound<'_, PyAny>) -> PyResult<String> {
    let np = obj.py().import("numpy")?;
    let bad = || {
        input_err(
            millpath::InputError::new("points", "the array given")
                .expected("an N × 2 (x, y) or N × 3 (x, y, group) array of numbers, mm"),
        )
    };
    let arr = np
        .call_method1("asarray", (obj, "float64"))
        .map_err(|_| bad())?;
    let arr: numpy::PyReadonlyArray2<'_, f64> = arr.extract().map_err(|_| bad())?;
    let a = arr.as_array();
    if a.ncols() != 2 && a.ncols() != 3 {
        return Err(bad());
    }
    let mut csv = String::from(if a.ncols() == 3 {
        "x,y,group\n"
    } else {
        "x,y\n"
    });
    for r in a.rows() {
        if a.ncols() == 3 {
            csv.push_str(&format!("{},{},{}\n", r[0], r[1], r[2]));
        } else {
            csv.push_str(&format!("{},{}\n", r[0], r[1]));
        }
    }
    Ok(csv)
}

/// What `millpath.contour` made.
#[pyclass(module = "millpath", frozen, get_all)]
#[derive(Debug)]
pub struct ContourResult {
    /// The program text, byte for byte what `millpath contour … -o FILE` writes.
    pub gcode: String,
    /// Cycle time planned on the machine, s (as `--json` gives it).
    pub cycle_time_s: f64,
    /// The report, as `--report` writes it (a dict).
    pub report: PyObject,
    /// The toolpath.
    pub toolpath: Py<Toolpath>,
    /// Warnings of the contour strategy.
    pub warnings: Vec<String>,
}

#[pymethods]
impl ContourResult {
    fn __repr__(&self) -> String {
        format!(
            "ContourResult(cycle_time_s={:.3}, {} bytes of G-code)",
            self.cycle_time_s,
            self.gcode.len()
        )
    }
}

/// A free-form contour: `millpath contour POINTS --flags` (or `sample=True` for the paper's
/// die cavity); `points` is a CSV/JSON path, its text, or an N × 2 / N × 3 array.
#[pyfunction]
#[pyo3(signature = (points = None, **kwargs))]
pub fn contour(
    py: Python<'_>,
    points: Option<&Bound<'_, PyAny>>,
    kwargs: Option<&Bound<'_, PyDict>>,
) -> PyResult<ContourResult> {
    let mut k = Kwargs::new(kwargs, "contour")?;
    let mut sample = false;
    k.bool("sample", &mut sample)?;
    let mut s = ContourSettings::default();
    k.opt_f64("tool_diameter", &mut s.tool_diameter)?;
    k.opt_f64("tolerance", &mut s.tolerance)?;
    let mut side = "inside".to_owned();
    k.text("side", &mut side)?;
    s.side = millpath::job::contour::parse_side(&side).map_err(input_err)?;
    k.opt_f64("depth", &mut s.depth)?;
    k.opt_f64("step_down", &mut s.step_down)?;
    k.f64("finish_allowance", &mut s.finish_allowance)?;
    let mut curve = "four-point".to_owned();
    k.text("curve", &mut curve)?;
    s.curve = millpath::job::contour::parse_curve(&curve).map_err(input_err)?;
    k.bool("arcs", &mut s.arcs)?;
    k.f64("feed", &mut s.feed)?;
    k.f64("plunge_feed", &mut s.plunge_feed)?;
    k.f64("safe_height", &mut s.safe_height)?;
    k.f64("clearance_height", &mut s.clearance_height)?;
    k.f64("lead_radius", &mut s.lead_radius)?;
    k.text("machine", &mut s.machine)?;
    let program = k.program()?;
    k.finish()?;
    let points = points.filter(|p| !p.is_none());
    let given = match (points, sample) {
        (Some(p), false) => Some(match text_or_path(p, "points")? {
            Some(t) => t,
            None => (points_csv(p)?, "points (array)".to_owned()),
        }),
        (None, true) => None,
        (Some(_), true) => {
            return Err(input_err(
                millpath::InputError::new("points", "given with sample=True")
                    .expected("either points or sample=True"),
            ));
        }
        (None, false) => {
            return Err(input_err(
                millpath::InputError::new("points", "missing")
                    .expected("points (a CSV/JSON path, its text or an array) or sample=True"),
            ));
        }
    };
    let (run, t) = py
        .allow_threads(|| -> Result<_, millpath::Error> {
            let source = match &given {
                Some((text, name)) => ContourSource::Points { text, name },
                None => ContourSource::Sample,
            };
            let run = millpath::job::contour::run(source, &s, &program)?;
            let plan = millpath::motion::plan_toolpath(&run.toolpath, &run.machine)
                .map_err(|e| e.engine_made("timing the contour toolpath"))?;
            Ok((run, plan.total_time()))
        })
        .map_err(err)?;
    Ok(ContourResult {
        gcode: run.gcode,
        cycle_time_s: t,
        report: to_py(py, &run.report)?,
        toolpath: Py::new(py, Toolpath { tp: run.toolpath })?,
        warnings: run.warnings.iter().map(ToString::to_string).collect(),
    })
}

/// What `millpath.verify` found.
#[pyclass(module = "millpath", frozen, get_all)]
#[derive(Debug)]
pub struct VerifyResult {
    /// No problem beyond the program's rounding (the CLI exits 0).
    pub passed: bool,
    /// The problems found (the CLI exits 2 with them).
    pub problems: Vec<String>,
    /// The findings, as `millpath verify --json` prints them (a dict).
    pub report: PyObject,
    /// The program read back.
    pub toolpath: Py<Toolpath>,
}

#[pymethods]
impl VerifyResult {
    fn __repr__(&self) -> String {
        format!(
            "VerifyResult(passed={}, {} problems)",
            if self.passed { "True" } else { "False" },
            self.problems.len()
        )
    }
}

/// Check a G-code program against a pocket outline: `millpath verify PROGRAM --outline
/// OUTLINE [--tool-diameter D] [--machine M]`; `program` is a path or the program's text;
/// without `tool_diameter`, the tool the program's header names; with `machine`, the
/// report's `timing` (cycle time, time not cutting, removal rate). A failing program is a result with
/// `passed == False`, not an exception.
#[pyfunction]
#[pyo3(signature = (program, outline, **kwargs))]
pub fn verify(
    py: Python<'_>,
    program: &Bound<'_, PyAny>,
    outline: &Bound<'_, PyAny>,
    kwargs: Option<&Bound<'_, PyDict>>,
) -> PyResult<VerifyResult> {
    let mut k = Kwargs::new(kwargs, "verify")?;
    let import = k.import()?;
    let mut s = VerifySettings::default();
    let mut tool: Option<f64> = None;
    k.opt_f64("tool_diameter", &mut tool)?;
    k.f64("wall_stock", &mut s.wall_stock)?;
    k.text("stepover", &mut s.stepover)?;
    k.opt_f64("cell", &mut s.cell)?;
    k.opt_u32("decimals", &mut s.decimals)?;
    k.opt_text("select", &mut s.select)?;
    k.text("dialect", &mut s.dialect)?;
    k.opt_text("machine", &mut s.machine)?;
    k.finish()?;
    let (loops, _, _) = outline_arg(py, outline, "outline", &import)?;
    let Some((text, name)) = text_or_path(program, "program")? else {
        return Err(pyo3::exceptions::PyTypeError::new_err(
            "verify() takes the program as a path or its text (str)",
        ));
    };
    // As `millpath verify`: the tool given, else the one the program's header names.
    s.tool_diameter = millpath::job::verify::tool_diameter(tool, &text, &name).map_err(err)?;
    s.check().map_err(err)?;
    let run = py
        .allow_threads(|| millpath::job::verify::run(&loops, &text, &name, &s))
        .map_err(err)?;
    Ok(VerifyResult {
        passed: run.problems.is_empty(),
        problems: run.problems.iter().map(ToString::to_string).collect(),
        report: to_py(py, &run.json())?,
        toolpath: Py::new(py, Toolpath { tp: run.toolpath })?,
    })
}

/// A five-axis minimum-time trajectory: `millpath five-axis --case paper` (or `path=` a
/// path file) as a function. Returns a dict: `report` (the `--json` object), `axes` (the
/// machine's joint names), and numpy arrays sampled every `dt` s: `t`, `feed` (N), `q`, `v`,
/// `a`, `j` (N × 5, mm and rad).
#[pyfunction]
#[pyo3(signature = (case = None, **kwargs))]
pub fn five_axis<'py>(
    py: Python<'py>,
    case: Option<String>,
    kwargs: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    let mut k = Kwargs::new(kwargs, "five_axis")?;
    let mut path: Option<String> = None;
    k.opt_text("path", &mut path)?;
    let mut machine = "paper".to_owned();
    k.text("machine", &mut machine)?;
    let mut over = LimitsFile::default();
    k.opt_f64("feed", &mut over.feed)?;
    k.opt_f64("linear_velocity", &mut over.linear_velocity)?;
    k.opt_f64("linear_acceleration", &mut over.linear_acceleration)?;
    k.opt_f64("linear_jerk", &mut over.linear_jerk)?;
    k.opt_f64("rotary_velocity", &mut over.rotary_velocity)?;
    k.opt_f64("rotary_acceleration", &mut over.rotary_acceleration)?;
    k.opt_f64("rotary_jerk", &mut over.rotary_jerk)?;
    k.opt_f64("tool_length", &mut over.tool_length)?;
    k.opt_f64("z1", &mut over.z1)?;
    k.opt_f64("z2", &mut over.z2)?;
    let (mut no_baseline, mut no_deflection) = (false, false);
    k.bool("no_baseline", &mut no_baseline)?;
    k.bool("no_deflection", &mut no_deflection)?;
    let mut dt = 1e-3;
    k.f64("dt", &mut dt)?;
    let mut end_knots = None;
    k.opt_u32("end_knots", &mut end_knots)?;
    let mut min_interval = None;
    k.opt_f64("min_interval", &mut min_interval)?;
    let mut tilt_tolerance_deg = None;
    k.opt_f64("tilt_tolerance", &mut tilt_tolerance_deg)?;
    k.finish()?;
    let case = match (&case, &path) {
        (None, None) => Some("paper".to_owned()),
        _ => case,
    };
    let settings = FiveAxisSettings {
        case,
        path: path.map(std::path::PathBuf::from),
        machine,
        flags: over,
        no_deflection,
        no_baseline,
        end_knots: end_knots.map(|k| k as usize),
        min_interval,
        tilt_tolerance_deg,
        dt,
        ..FiveAxisSettings::default()
    };
    let (report, names, s) = py
        .allow_threads(|| -> Result<_, millpath::Error> {
            let run = millpath::job::five_axis::run(&settings)?;
            let s = run.samples(dt);
            let names = run.kinematics.axis_names();
            Ok((run.outcome.result, names, s))
        })
        .map_err(err)?;
    let d = PyDict::new(py);
    d.set_item("report", to_py(py, &report)?)?;
    d.set_item("axes", names.to_vec())?;
    d.set_item("t", PyArray1::from_slice(py, &s.t))?;
    d.set_item("feed", PyArray1::from_slice(py, &s.feed))?;
    for (key, rows) in [("q", &s.q), ("v", &s.v), ("a", &s.a), ("j", &s.j)] {
        let flat: Vec<f64> = rows.iter().flatten().copied().collect();
        let arr: Bound<'py, PyArray2<f64>> =
            PyArray1::from_vec(py, flat).reshape([rows.len(), 5])?;
        d.set_item(key, arr)?;
    }
    Ok(d)
}
