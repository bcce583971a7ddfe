//! The module's functions, each a thin call of the engine's job of the same name.

use crate::convert::{Kwargs, err, input_err, outline_arg, path_text, to_py};
use crate::objects::{DrillResult, Estimate, Pocket, PocketResult, Toolpath};
use millpath::job::{self, DrillSettings, PocketSettings};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyTuple};

/// A selection: text (`"1,3"`, `"2-4"`) or a sequence of 1-based indices.
fn selection(v: Option<Bound<'_, PyAny>>) -> PyResult<Option<String>> {
    let Some(v) = v else { return Ok(None) };
    if v.is_none() {
        return Ok(None);
    }
    if v.is_instance_of::<PyList>() || v.is_instance_of::<PyTuple>() {
        let items: Vec<i64> = v.extract()?;
        return Ok(Some(
            items
                .iter()
                .map(i64::to_string)
                .collect::<Vec<_>>()
                .join(","),
        ));
    }
    if let Ok(i) = v.extract::<i64>() {
        return Ok(Some(i.to_string()));
    }
    Ok(Some(v.extract()?))
}

/// Rough a pocket: `millpath pocket OUTLINE --flags` as a function (see the stub for every
/// keyword).
#[pyfunction]
#[pyo3(signature = (outline, **kwargs))]
pub fn pocket(
    py: Python<'_>,
    outline: &Bound<'_, PyAny>,
    kwargs: Option<&Bound<'_, PyDict>>,
) -> PyResult<PocketResult> {
    let select = selection(kwargs.map(|k| k.get_item("select")).transpose()?.flatten())?;
    if let Some(k) = kwargs
        && k.contains("select")?
    {
        k.del_item("select")?;
    }
    let mut k = Kwargs::new(kwargs, "pocket")?;
    let mut s = PocketSettings {
        import: k.import()?,
        ..PocketSettings::default()
    };
    k.text("strategy", &mut s.strategy)?;
    k.f64("tool_diameter", &mut s.tool_diameter)?;
    k.opt_f64("flute_length", &mut s.flute_length)?;
    s.apply_strategy_defaults();
    let (mut stepover, mut step_down) = (None, None);
    k.opt_text("stepover", &mut stepover)?;
    k.f64("depth", &mut s.depth)?;
    k.opt_f64("step_down", &mut step_down)?;
    s.stepover = stepover.unwrap_or(s.stepover);
    s.step_down = step_down.unwrap_or(s.step_down);
    k.f64("wall_stock", &mut s.wall_stock)?;
    k.f64("floor_stock", &mut s.floor_stock)?;
    k.bool("conventional", &mut s.conventional)?;
    k.text("entry", &mut s.entry)?;
    k.opt_f64("helix_radius", &mut s.helix_radius)?;
    k.f64("ramp_angle", &mut s.ramp_angle)?;
    k.f64("safe_height", &mut s.safe_height)?;
    k.f64("clearance_height", &mut s.clearance_height)?;
    k.text("feed", &mut s.feed)?;
    k.f64("slowdown", &mut s.slowdown)?;
    k.f64("angle", &mut s.angle)?;
    k.opt_f64("transition", &mut s.transition)?;
    k.f64("min_radius", &mut s.min_radius)?;
    k.opt_text("morph", &mut s.morph)?;
    k.bool("arcs", &mut s.arcs)?;
    k.bool("both_ways", &mut s.both_ways)?;
    k.f64("lift", &mut s.lift)?;
    k.bool("finish", &mut s.finish)?;
    k.bool("no_feed_modulation", &mut s.no_feed_modulation)?;
    k.text("machine", &mut s.machine)?;
    k.opt_f64("cell", &mut s.cell)?;
    k.opt_f64("draft", &mut s.draft)?;
    k.opt_text("bottom_outline", &mut s.bottom_outline)?;
    k.opt_f64("tolerance", &mut s.tolerance)?;
    let (mut rest_from, mut rest_from_diameter) = (None, None);
    k.opt_text("rest_from", &mut rest_from)?;
    k.opt_f64("rest_from_diameter", &mut rest_from_diameter)?;
    let program = k.program()?;
    k.finish()?;
    s.check_before_loading(&program).map_err(err)?;
    let (loops, name, note) = outline_arg(py, outline, "outline", &s.import)?;
    let mut notes: Vec<String> = note.into_iter().collect();
    if let Some(from) = rest_from {
        let from = job::rest::RestFrom {
            program: from,
            diameter: rest_from_diameter,
        };
        let run = py
            .allow_threads(|| job::rest::run(&loops, &name, &s, &program, select.as_deref(), &from))
            .map_err(err)?;
        return rest_result(py, run, notes);
    }
    let run = py
        .allow_threads(|| {
            job::pocket::run(&loops, &name, &s, &program, select.as_deref(), &mut |n| {
                notes.push(n);
            })
        })
        .map_err(err)?;
    let gcode = String::from_utf8(run.gcode).map_err(|e| {
        crate::InternalError::new_err(format!("the pocket program is not UTF-8: {e}"))
    })?;
    Ok(PocketResult {
        gcode,
        cycle_time_s: run.report.cycle_time_s,
        strategy: run.name,
        report: to_py(py, &run.report)?,
        toolpath: Py::new(
            py,
            Toolpath {
                tp: run.part.toolpath,
            },
        )?,
        note: (!notes.is_empty()).then(|| notes.join("\n")),
    })
}

/// Drill and bore a drawing's circles: `millpath drill DRAWING --flags` as a function (see
/// the stub for every keyword).
#[pyfunction]
#[pyo3(signature = (drawing, **kwargs))]
pub fn drill(
    py: Python<'_>,
    drawing: &Bound<'_, PyAny>,
    kwargs: Option<&Bound<'_, PyDict>>,
) -> PyResult<DrillResult> {
    let name = path_text(drawing)?.ok_or_else(|| {
        crate::InputError::new_err(format!(
            "invalid drawing = {drawing} (from drill(drawing)): expected the path of a .dxf, \
             .svg or .json drawing"
        ))
    })?;
    let mut k = Kwargs::new(kwargs, "drill")?;
    let mut s = DrillSettings {
        import: k.import()?,
        ..DrillSettings::default()
    };
    k.f64("tool_diameter", &mut s.tool_diameter)?;
    k.f64("depth", &mut s.depth)?;
    k.bool("through", &mut s.through)?;
    k.f64("breakthrough", &mut s.breakthrough)?;
    k.opt_f64("min_diameter", &mut s.min_diameter)?;
    k.opt_f64("max_diameter", &mut s.max_diameter)?;
    k.opt_f64("peck", &mut s.peck)?;
    k.opt_f64("chip_break", &mut s.chip_break)?;
    k.opt_f64("dwell", &mut s.dwell)?;
    k.f64("retract", &mut s.retract)?;
    k.f64("clearance_height", &mut s.clearance_height)?;
    k.bool("stay_at_retract", &mut s.stay_at_retract)?;
    k.text("feed", &mut s.feed)?;
    k.text("bore_feed", &mut s.bore_feed)?;
    k.f64("pitch", &mut s.pitch)?;
    k.bool("conventional", &mut s.conventional)?;
    k.f64("stepover", &mut s.stepover)?;
    k.f64("finish_allowance", &mut s.finish_allowance)?;
    k.f64("tolerance", &mut s.tolerance)?;
    k.f64("diameter_tolerance", &mut s.diameter_tolerance)?;
    k.bool("drill_only", &mut s.drill_only)?;
    k.text("machine", &mut s.machine)?;
    let program = k.program()?;
    k.finish()?;
    s.check_before_loading(&program).map_err(err)?;
    let mut notes: Vec<String> = Vec::new();
    let run = py
        .allow_threads(|| job::drill::run(&name, &s, &program, &mut |n| notes.push(n)))
        .map_err(err)?;
    let gcode = String::from_utf8(run.gcode).map_err(|e| {
        crate::InternalError::new_err(format!("the drilling program is not UTF-8: {e}"))
    })?;
    let rows: Vec<Vec<f64>> = run
        .result
        .holes
        .iter()
        .filter(|p| p.op.is_cut())
        .map(|p| vec![p.hole.center.x, p.hole.center.y, p.hole.diameter])
        .collect();
    let holes = if rows.is_empty() {
        numpy::PyArray2::zeros(py, [0, 3], false)
    } else {
        numpy::PyArray2::from_vec2(py, &rows)
            .map_err(|e| crate::InternalError::new_err(format!("the holes array: {e}")))?
    };
    Ok(DrillResult {
        gcode,
        cycle_time_s: run.report.cycle_time_s,
        report: to_py(py, &run.report)?,
        toolpath: Py::new(
            py,
            Toolpath {
                tp: run.result.toolpath,
            },
        )?,
        holes: holes.unbind(),
        note: (!notes.is_empty()).then(|| notes.join("\n")),
    })
}

/// The pockets of an outline file (`.json`, `.dxf`, `.svg`) or a sample, nested into
/// boundaries and islands, as `millpath pocket FILE --list` numbers them.
#[pyfunction]
#[pyo3(signature = (path, **kwargs))]
pub fn read_outline(
    py: Python<'_>,
    path: &Bound<'_, PyAny>,
    kwargs: Option<&Bound<'_, PyDict>>,
) -> PyResult<Vec<Pocket>> {
    let mut k = Kwargs::new(kwargs, "read_outline")?;
    let import = k.import()?;
    k.finish()?;
    let (loops, _, _) = outline_arg(py, path, "path", &import)?;
    Ok(loops
        .pockets()
        .iter()
        .enumerate()
        .map(|(i, p)| Pocket::new(py, i + 1, p))
        .collect())
}

/// The cycle time of a G-code program on a machine, as `millpath estimate FILE --machine M`
/// gives it: `program` is a path (`str` naming an existing file, or `os.PathLike`) or the
/// program's text. `subroutine_path` (folders) and `tool_table` (a LinuxCNC tool table) are
/// the CLI's `--subroutine-path` and `--tool-table`; `verify` runs the limit verifier.
#[pyfunction]
#[pyo3(signature = (program, machine = "hsm", dialect = "auto", *, subroutine_path = None,
    tool_table = None, lenient = false, verify = true))]
#[allow(clippy::too_many_arguments)]
pub fn estimate(
    py: Python<'_>,
    program: &Bound<'_, PyAny>,
    machine: &str,
    dialect: &str,
    subroutine_path: Option<Vec<std::path::PathBuf>>,
    tool_table: Option<std::path::PathBuf>,
    lenient: bool,
    verify: bool,
) -> PyResult<Estimate> {
    enum Source {
        File(std::path::PathBuf),
        Text(String),
    }
    let source = match path_text(program)? {
        Some(p) if !p.contains('\n') && std::path::Path::new(&p).is_file() => {
            Source::File(p.into())
        }
        Some(p) if !program.is_instance_of::<pyo3::types::PyString>() => {
            return Err(input_err(
                millpath::InputError::new("input file", p).expected("a readable G-code file"),
            ));
        }
        Some(t) if crate::convert::looks_like_path(&t) => {
            // A path to a file that is not there: read it, for the reader's message.
            millpath::io::read_text(std::path::Path::new(&t)).map_err(err)?;
            Source::Text(t)
        }
        Some(t) => Source::Text(t),
        None => {
            return Err(pyo3::exceptions::PyTypeError::new_err(
                "estimate() takes the program as a path or its text (str)",
            ));
        }
    };
    let settings = job::estimate::EstimateSettings {
        dialect: dialect.to_owned(),
        lenient,
        verify,
        subroutine_path: subroutine_path.unwrap_or_default(),
        tool_table,
        whole: true,
        ..job::estimate::EstimateSettings::default()
    };
    let run = py
        .allow_threads(|| -> Result<_, millpath::Error> {
            let m = job::load_machine(machine)?;
            match &source {
                Source::File(p) => job::estimate::run(p, &m, &settings, &mut |_| {}),
                Source::Text(t) => job::estimate::run_text(t, "program (text)", &m, &settings),
            }
        })
        .map_err(err)?;
    let tp = run.toolpath.ok_or_else(|| {
        err(millpath::Error::internal(
            "a whole estimate without its toolpath",
        ))
    })?;
    Ok(Estimate {
        cycle_time_s: run.estimate.cycle_time_s,
        machine: run.estimate.machine,
        blocks: run.estimate.blocks,
        violations: run.estimate.violations,
        toolpath: Py::new(py, Toolpath { tp })?,
        dialect: run.dialect.dialect.name().to_owned(),
        dialect_reason: match run.dialect.reason {
            millpath::gcode::DialectReason::Named => "named".to_owned(),
            r => r.to_string(),
        },
    })
}

/// `millpath optimize`: a LinuxCNC program (a path or its text) with its straight feed
/// blocks rewritten in inverse time at what `machine`'s joints allow, kept only when the
/// machine's controller model runs it faster. Returns a dict: `text` (the program to run:
/// the input's when nothing was gained), `rewrite` (the inverse-time rewrite, kept or not),
/// `before_s` and `after_s` (the input's and the rewrite's estimated cycle times),
/// `rewritten_blocks`, `merged_blocks`, `kept_rewrite` and `outcome` (what was done and why).
/// Runs of straight blocks within `tolerance` mm and `tolerance_deg` of one chord are merged
/// first (`merge=False` keeps every block).
#[pyfunction]
#[pyo3(signature = (program, machine = "linuxcnc-time", tolerance = 0.001, tolerance_deg = 0.001, merge = true))]
pub fn optimize<'py>(
    py: Python<'py>,
    program: &Bound<'py, PyAny>,
    machine: &str,
    tolerance: f64,
    tolerance_deg: f64,
    merge: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let Some(p) = path_text(program)? else {
        return Err(pyo3::exceptions::PyTypeError::new_err(
            "optimize() takes the program as a path or its text (str)",
        ));
    };
    let (text, origin) = if !p.contains('\n') && std::path::Path::new(&p).is_file() {
        let path = std::path::Path::new(&p);
        (millpath::io::read_text(path).map_err(err)?, p.clone())
    } else if !program.is_instance_of::<pyo3::types::PyString>() {
        return Err(input_err(
            millpath::InputError::new("input file", p).expected("a readable G-code file"),
        ));
    } else {
        (p, "program (text)".to_owned())
    };
    let opt = py
        .allow_threads(|| -> Result<_, millpath::Error> {
            let m = job::load_machine(machine)?;
            let tol = merge.then(|| job::optimize::MergeTolerance {
                mm: tolerance,
                rad: tolerance_deg.to_radians(),
            });
            let opts = job::optimize::OptimizeOptions::default().with_merge(tol);
            job::optimize::optimize_text(&text, &origin, &m, &opts)
        })
        .map_err(err)?;
    let d = PyDict::new(py);
    d.set_item("kept_rewrite", opt.text == opt.rewrite)?;
    d.set_item("text", opt.text)?;
    d.set_item("rewrite", opt.rewrite)?;
    d.set_item("before_s", opt.before.cycle_time_s)?;
    d.set_item("after_s", opt.after.cycle_time_s)?;
    d.set_item("rewritten_blocks", opt.rewritten_blocks)?;
    d.set_item("merged_blocks", opt.merged_blocks)?;
    d.set_item("outcome", opt.outcome.to_string())?;
    Ok(d)
}

/// The built-in machine presets, as `millpath machines --json` lists them (a list of dicts).
#[pyfunction]
pub fn machines(py: Python<'_>) -> PyResult<PyObject> {
    to_py(py, &millpath::machine::Machine::presets())
}

/// A rest pass as a [`PocketResult`]: strategy `rest`, its figures as the report (what
/// `millpath pocket --rest-from` prints), the summary line as the note.
fn rest_result(
    py: Python<'_>,
    run: job::rest::RestRun,
    mut notes: Vec<String>,
) -> PyResult<PocketResult> {
    notes.push(run.summary());
    let gcode = String::from_utf8(run.gcode).map_err(|e| {
        crate::InternalError::new_err(format!("the rest program is not UTF-8: {e}"))
    })?;
    let cut_mm = run.toolpath.cut_length();
    let report = PyDict::new(py);
    report.set_item("previous_tool_diameter_mm", run.previous_tool.diameter)?;
    report.set_item("tool_diameter_mm", run.toolpath.tool.diameter)?;
    report.set_item("left_mm2", run.left_mm2)?;
    report.set_item("runs", run.runs)?;
    report.set_item("cut_length_mm", cut_mm)?;
    report.set_item("cycle_time_s", run.time_s)?;
    report.set_item("check", &run.check)?;
    Ok(PocketResult {
        gcode,
        cycle_time_s: run.time_s,
        strategy: "rest".to_owned(),
        report: report.into_any().unbind(),
        toolpath: Py::new(py, Toolpath { tp: run.toolpath })?,
        note: Some(notes.join("\n")),
    })
}
