//! The Python result objects: a toolpath with numpy views of its moves and of its planned
//! trajectory, a pocket job's result, an estimate, a drawing's pocket.

use crate::convert::{err, outline_array};
use millpath::toolpath::MoveKind;
use numpy::{PyArray1, PyArray2, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// A toolpath: the moves the engine planned, in mm and mm/s.
#[pyclass(module = "millpath", frozen)]
#[derive(Debug)]
pub struct Toolpath {
    pub(crate) tp: millpath::Toolpath,
}

#[pymethods]
impl Toolpath {
    /// The path's points as an (N + 1) × 3 array, mm: the start, then the end of each move.
    #[getter]
    fn points<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let mut flat = Vec::with_capacity(3 * (self.tp.moves.len() + 1));
        let s = self.tp.start;
        flat.extend([s.x, s.y, s.z]);
        for m in &self.tp.moves {
            flat.extend([m.to.x, m.to.y, m.to.z]);
        }
        let n = flat.len() / 3;
        PyArray1::from_vec(py, flat).reshape([n, 3])
    }

    /// The programmed feed of each move, mm/s (N; NaN for a rapid).
    #[getter]
    fn feeds<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_iter(
            py,
            self.tp.moves.iter().map(|m| {
                if matches!(m.kind, MoveKind::Rapid) {
                    f64::NAN
                } else {
                    m.feed
                }
            }),
        )
    }

    /// Whether each move is a rapid (N booleans).
    #[getter]
    fn rapid<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<bool>> {
        PyArray1::from_iter(
            py,
            self.tp
                .moves
                .iter()
                .map(|m| matches!(m.kind, MoveKind::Rapid)),
        )
    }

    /// Cutting length, mm.
    #[getter]
    fn cut_length_mm(&self) -> f64 {
        self.tp.cut_length()
    }

    /// Rapid length, mm.
    #[getter]
    fn rapid_length_mm(&self) -> f64 {
        self.tp.rapid_length()
    }

    /// Number of depth levels.
    #[getter]
    fn levels(&self) -> usize {
        self.tp.levels.len()
    }

    /// The trajectory planned on `machine` (a preset name or a TOML profile), sampled every
    /// `dt` s: a dict of numpy arrays `t`, `s` (path length, mm), `feed` (mm/s), `position`,
    /// `velocity`, `acceleration`, `jerk` (N × 3). Planned with the GIL released.
    #[pyo3(signature = (machine = "hsm", dt = 0.01))]
    fn trajectory<'py>(
        &self,
        py: Python<'py>,
        machine: &str,
        dt: f64,
    ) -> PyResult<Bound<'py, PyDict>> {
        if !(dt.is_finite() && dt > 0.0) {
            return Err(crate::convert::input_err(
                millpath::InputError::new("dt", dt)
                    .at("trajectory(dt=…)")
                    .expected("a time step > 0 s"),
            ));
        }
        let tp = &self.tp;
        let samples = py
            .allow_threads(|| -> Result<_, millpath::Error> {
                let m = millpath::job::load_machine(machine)?;
                let plan = millpath::motion::plan_toolpath(tp, &m)?;
                plan.sample(dt)
            })
            .map_err(err)?;
        let d = PyDict::new(py);
        let col = |f: &dyn Fn(&millpath::motion::Sample) -> f64| {
            PyArray1::from_iter(py, samples.iter().map(f))
        };
        d.set_item("t", col(&|s| s.t))?;
        d.set_item("s", col(&|s| s.s))?;
        d.set_item("feed", col(&|s| s.feed))?;
        let n = samples.len();
        let mat = |f: &dyn Fn(&millpath::motion::Sample) -> [f64; 3]| {
            PyArray1::from_iter(py, samples.iter().flat_map(f)).reshape([n, 3])
        };
        d.set_item(
            "position",
            mat(&|s| [s.position.x, s.position.y, s.position.z])?,
        )?;
        d.set_item("velocity", mat(&|s| s.vel)?)?;
        d.set_item("acceleration", mat(&|s| s.acc)?)?;
        d.set_item("jerk", mat(&|s| s.jerk)?)?;
        Ok(d)
    }

    fn __len__(&self) -> usize {
        self.tp.moves.len()
    }

    fn __repr__(&self) -> String {
        format!(
            "Toolpath({} moves, {} levels, cut {:.1} mm)",
            self.tp.moves.len(),
            self.tp.levels.len(),
            self.tp.cut_length()
        )
    }
}

/// What `millpath.pocket` made.
#[pyclass(module = "millpath", frozen, get_all)]
#[derive(Debug)]
pub struct PocketResult {
    /// The program text, byte for byte what `millpath pocket … -o FILE` writes.
    pub gcode: String,
    /// Cycle time of the written program on the machine, s.
    pub cycle_time_s: f64,
    /// The strategy that cut it (`spiral`, `offset`, `zigzag`, or `mixed`).
    pub strategy: String,
    /// The report, as `--report` writes it (a dict).
    pub report: PyObject,
    /// The toolpath.
    pub toolpath: Py<Toolpath>,
    /// What the drawing held, when the outline was a DXF or SVG file.
    pub note: Option<String>,
}

#[pymethods]
impl PocketResult {
    fn __repr__(&self) -> String {
        format!(
            "PocketResult(strategy={:?}, cycle_time_s={:.3}, {} bytes of G-code)",
            self.strategy,
            self.cycle_time_s,
            self.gcode.len()
        )
    }
}

/// What `millpath.drill` made.
#[pyclass(module = "millpath", frozen, get_all)]
#[derive(Debug)]
pub struct DrillResult {
    /// The program text, byte for byte what `millpath drill … -o FILE` writes.
    pub gcode: String,
    /// Cycle time of the written program on the machine, s.
    pub cycle_time_s: f64,
    /// The report, as `--report` writes it (a dict).
    pub report: PyObject,
    /// The toolpath.
    pub toolpath: Py<Toolpath>,
    /// The holes cut, in cutting order: N × 3 (x, y, diameter), mm.
    pub holes: Py<PyArray2<f64>>,
    /// What the drawing held, when it was a DXF or SVG file.
    pub note: Option<String>,
}

#[pymethods]
impl DrillResult {
    fn __repr__(&self, py: Python<'_>) -> String {
        format!(
            "DrillResult({} holes, cycle_time_s={:.3}, {} bytes of G-code)",
            numpy::PyUntypedArrayMethods::shape(self.holes.bind(py))[0],
            self.cycle_time_s,
            self.gcode.len()
        )
    }
}

/// What `millpath.estimate` found.
#[pyclass(module = "millpath", frozen, get_all)]
#[derive(Debug)]
pub struct Estimate {
    /// Cycle time on the machine, s.
    pub cycle_time_s: f64,
    /// The machine's name.
    pub machine: String,
    /// Blocks planned (moves after joining).
    pub blocks: usize,
    /// Samples over a limit found by the verifier; `None` when it did not run (`verify=False`,
    /// or the `linuxcnc` controller model, judged against LinuxCNC instead).
    pub violations: Option<usize>,
    /// The program read back.
    pub toolpath: Py<Toolpath>,
    /// The dialect the program was read in (`linuxcnc`, `fanuc`, `sinumerik`, `grbl`).
    pub dialect: String,
    /// Why: `named` when given as `dialect=`, else what it was found from (the CLI's
    /// `note: dialect …` line).
    pub dialect_reason: String,
}

#[pymethods]
impl Estimate {
    fn __repr__(&self) -> String {
        format!(
            "Estimate(cycle_time_s={:.3}, machine={:?})",
            self.cycle_time_s, self.machine
        )
    }
}

/// One pocket of a drawing: its boundary and islands as N × 3 arrays (x, y, bulge), mm.
#[pyclass(module = "millpath", frozen, get_all)]
#[derive(Debug)]
pub struct Pocket {
    /// Index in the drawing (1-based, as `select` and the CLI's `--list` number them).
    pub index: usize,
    /// The boundary, counter-clockwise: x, y, bulge of the span leaving each vertex.
    pub outer: PyObject,
    /// The islands, clockwise.
    pub islands: Vec<PyObject>,
    /// Area of material, mm².
    pub area_mm2: f64,
}

impl Pocket {
    /// The pocket `index` of a drawing.
    pub fn new(py: Python<'_>, index: usize, p: &millpath::geom::Pocket) -> Self {
        Pocket {
            index,
            outer: outline_array(py, &p.outer).into_any().unbind(),
            islands: p
                .islands
                .iter()
                .map(|i| outline_array(py, i).into_any().unbind())
                .collect(),
            area_mm2: p.area(),
        }
    }
}

#[pymethods]
impl Pocket {
    fn __repr__(&self) -> String {
        format!(
            "Pocket(index={}, area_mm2={:.3}, {} islands)",
            self.index,
            self.area_mm2,
            self.islands.len()
        )
    }
}
