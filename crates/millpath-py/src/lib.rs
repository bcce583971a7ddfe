//! `millpath` for Python: a thin layer over the engine's jobs (`millpath::job`), the same
//! pipelines the `millpath` CLI runs, with keyword arguments named as the CLI's flags
//! (`tool_diameter` for `--tool-diameter`). Results are Python objects holding numpy arrays;
//! an input error raises `millpath.InputError` (a `ValueError`) with the message the CLI
//! prints, an internal fault `millpath.InternalError`; planning runs with the GIL released.
//!
//! ```text
//! r = millpath.pocket("part.dxf", strategy="spiral", tool_diameter=6, depth=3, step_down=3)
//! r.gcode           # the bytes `millpath pocket part.dxf … -o` writes, as a str
//! r.toolpath.points # N × 3 numpy array
//! d = millpath.drill("plate.dxf", tool_diameter=3, depth=5, peck=2)
//! d.holes           # N × 3 numpy array: x, y, diameter of each hole cut
//! j = millpath.job("part.toml")  # a whole part: face, pockets, holes, profile with tabs
//! j.report["operations"]         # each operation's tool, cut, time and checks
//! ```

mod convert;
mod curves;
mod job;
mod jobs;
mod objects;
mod profile;

use pyo3::prelude::*;

pyo3::create_exception!(
    millpath,
    InputError,
    pyo3::exceptions::PyValueError,
    "Bad input: the message names the value, where it came from and what is expected (the \
     CLI's exit code 2)."
);
pyo3::create_exception!(
    millpath,
    InternalError,
    pyo3::exceptions::PyRuntimeError,
    "An internal fault of the engine: a bug to report (the CLI's exit code 1)."
);

/// The module `millpath._millpath`, re-exported by `millpath`.
#[pymodule]
fn _millpath(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("InputError", py.get_type::<InputError>())?;
    m.add("InternalError", py.get_type::<InternalError>())?;
    m.add_function(wrap_pyfunction!(jobs::pocket, m)?)?;
    m.add_function(wrap_pyfunction!(jobs::drill, m)?)?;
    m.add_function(wrap_pyfunction!(jobs::read_outline, m)?)?;
    m.add_function(wrap_pyfunction!(jobs::estimate, m)?)?;
    m.add_function(wrap_pyfunction!(jobs::optimize, m)?)?;
    m.add_function(wrap_pyfunction!(jobs::machines, m)?)?;
    m.add_function(wrap_pyfunction!(curves::contour, m)?)?;
    m.add_function(wrap_pyfunction!(profile::profile, m)?)?;
    m.add_function(wrap_pyfunction!(job::job, m)?)?;
    m.add_function(wrap_pyfunction!(job::job_init, m)?)?;
    m.add_function(wrap_pyfunction!(curves::verify, m)?)?;
    m.add_function(wrap_pyfunction!(curves::five_axis, m)?)?;
    m.add_class::<curves::ContourResult>()?;
    m.add_class::<profile::ProfileResult>()?;
    m.add_class::<job::JobResult>()?;
    m.add_class::<curves::VerifyResult>()?;
    m.add_class::<objects::Toolpath>()?;
    m.add_class::<objects::PocketResult>()?;
    m.add_class::<objects::DrillResult>()?;
    m.add_class::<objects::Estimate>()?;
    m.add_class::<objects::Pocket>()?;
    Ok(())
}
