//! Between Python and the engine: errors, outlines given as a name or as arrays, keyword
//! arguments onto the engine's settings, JSON onto Python objects.

use crate::{InputError, InternalError};
use millpath::geom::{Outline, Point};
use millpath::io::outline_json::{self, Loops};
use numpy::{PyArray2, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString};

/// The engine's error as a Python exception: input errors as `InputError` with the CLI's
/// message, internal faults as `InternalError`.
pub fn err(e: millpath::Error) -> PyErr {
    match e {
        millpath::Error::Input(i) => InputError::new_err(millpath::Error::Input(i).to_string()),
        millpath::Error::Internal(i) => {
            InternalError::new_err(millpath::Error::Internal(i).to_string())
        }
    }
}

/// An input error as a Python exception.
pub fn input_err(e: millpath::InputError) -> PyErr {
    err(e.into())
}

/// A file path (`str` or `os.PathLike`) as text, or `None` for anything else.
pub fn path_text(obj: &Bound<'_, PyAny>) -> PyResult<Option<String>> {
    if obj.is_instance_of::<PyString>() {
        return Ok(Some(obj.extract()?));
    }
    if obj.hasattr("__fspath__")? {
        let p = obj.call_method0("__fspath__")?;
        return Ok(Some(p.extract()?));
    }
    Ok(None)
}

/// Whether a one-line text names a file rather than being a program or points itself: it
/// ends in a file extension the readers take or holds a path separator.
pub fn looks_like_path(text: &str) -> bool {
    const EXTENSIONS: &[&str] = &[
        ".ngc", ".nc", ".tap", ".mpf", ".gcode", ".csv", ".json", ".txt",
    ];
    !text.contains('\n')
        && (text.contains('/')
            || EXTENSIONS
                .iter()
                .any(|e| text.to_ascii_lowercase().ends_with(e)))
}

/// One outline from an N × 2 (x, y) or N × 3 (x, y, bulge) array, mm.
fn outline_from_array(a: &Bound<'_, PyAny>, origin: &str) -> PyResult<Outline> {
    let np = a.py().import("numpy")?;
    let arr = np
        .call_method1("ascontiguousarray", (a, "float64"))
        .map_err(|_| {
            input_err(
                millpath::InputError::new("outline", origin)
                    .expected("an array of points: N × 2 (x, y) or N × 3 (x, y, bulge), in mm"),
            )
        })?;
    let arr: PyReadonlyArray2<'_, f64> = arr.extract().map_err(|_| {
        input_err(
            millpath::InputError::new("outline", origin)
                .expected("a 2-D array of points: N × 2 (x, y) or N × 3 (x, y, bulge), in mm"),
        )
    })?;
    let shape = arr.shape();
    if shape[1] != 2 && shape[1] != 3 {
        return Err(input_err(
            millpath::InputError::new("outline columns", shape[1])
                .at(origin)
                .expected("2 (x, y) or 3 (x, y, bulge)"),
        ));
    }
    let view = arr.as_array();
    let vertices: Vec<(Point, f64)> = view
        .rows()
        .into_iter()
        .map(|r| {
            (
                Point::new(r[0], r[1]),
                if shape[1] == 3 { r[2] } else { 0.0 },
            )
        })
        .collect();
    Outline::new(&vertices, origin).map_err(input_err)
}

/// An outline argument: a name (a `.json`, `.dxf`, `.svg` path or `sample:aerospace`),
/// one array of points (a pocket without islands), or a list of arrays (outlines nested into
/// pockets and islands). Returns the loops, the name used in messages and the drawing's
/// note.
pub fn outline_arg(
    py: Python<'_>,
    obj: &Bound<'_, PyAny>,
    what: &str,
    import: &millpath::io::ImportSettings,
) -> PyResult<(Loops, String, Option<String>)> {
    if let Some(name) = path_text(obj)? {
        let import = import.clone();
        let n = name.clone();
        let (loops, note) = py
            .allow_threads(move || millpath::job::load_outline(&n, &import))
            .map_err(err)?;
        return Ok((loops, name, note));
    }
    let np = py.import("numpy")?;
    let ndim: usize = np
        .call_method1("ndim", (obj,))
        .and_then(|d| d.extract())
        .unwrap_or(0);
    let origin = format!("{what} (points)");
    let outlines = if ndim == 2 {
        vec![outline_from_array(obj, &origin)?]
    } else {
        let mut v = Vec::new();
        for (i, item) in obj.try_iter()?.enumerate() {
            v.push(outline_from_array(
                &item?,
                &format!("{what} (outline {})", i + 1),
            )?);
        }
        v
    };
    let loops = outline_json::classify(outlines, &origin).map_err(input_err)?;
    Ok((loops, origin, None))
}

/// An outline's vertices as an N × 3 array: x, y and the bulge of the span leaving each
/// (0 for a line; tan of a quarter of an arc's sweep).
pub fn outline_array<'py>(py: Python<'py>, o: &Outline) -> Bound<'py, PyArray2<f64>> {
    let rows: Vec<Vec<f64>> = o.vertices().map(|(p, b)| vec![p.x, p.y, b]).collect();
    PyArray2::from_vec2(py, &rows).unwrap_or_else(|_| PyArray2::zeros(py, [0, 3], false))
}

/// A serialisable value as Python objects (through `json.loads`).
pub fn to_py(py: Python<'_>, value: &impl serde::Serialize) -> PyResult<PyObject> {
    let text = serde_json::to_string(value)
        .map_err(|e| InternalError::new_err(format!("JSON of a result: {e}")))?;
    Ok(py.import("json")?.call_method1("loads", (text,))?.unbind())
}

/// Keyword arguments taken one by one: each known name consumed, anything left refused.
pub struct Kwargs<'py> {
    map: Vec<(String, Bound<'py, PyAny>)>,
    func: &'static str,
}

impl<'py> Kwargs<'py> {
    /// The keyword arguments of `func`.
    pub fn new(kwargs: Option<&Bound<'py, PyDict>>, func: &'static str) -> PyResult<Self> {
        let mut map = Vec::new();
        if let Some(d) = kwargs {
            for (k, v) in d.iter() {
                map.push((k.extract()?, v));
            }
        }
        Ok(Kwargs { map, func })
    }

    fn take(&mut self, name: &str) -> Option<Bound<'py, PyAny>> {
        let i = self.map.iter().position(|(k, _)| k == name)?;
        Some(self.map.swap_remove(i).1)
    }

    fn bad(&self, name: &str, v: &Bound<'py, PyAny>, expected: &str) -> PyErr {
        let flag = format!("--{}", name.replace('_', "-"));
        input_err(
            millpath::InputError::new(name.replace('_', " "), v.to_string())
                .at(format!("{}({name}=…) ({flag})", self.func))
                .expected(expected),
        )
    }

    /// A number.
    pub fn f64(&mut self, name: &str, into: &mut f64) -> PyResult<()> {
        if let Some(v) = self.take(name) {
            *into = v.extract().map_err(|_| self.bad(name, &v, "a number"))?;
        }
        Ok(())
    }

    /// A number or `None`.
    pub fn opt_f64(&mut self, name: &str, into: &mut Option<f64>) -> PyResult<()> {
        if let Some(v) = self.take(name) {
            *into = v
                .extract()
                .map_err(|_| self.bad(name, &v, "a number or None"))?;
        }
        Ok(())
    }

    /// A whole number >= 0.
    pub fn u32(&mut self, name: &str, into: &mut u32) -> PyResult<()> {
        if let Some(v) = self.take(name) {
            *into = v
                .extract()
                .map_err(|_| self.bad(name, &v, "a whole number >= 0"))?;
        }
        Ok(())
    }

    /// A whole number >= 0 or `None`.
    pub fn opt_u32(&mut self, name: &str, into: &mut Option<u32>) -> PyResult<()> {
        if let Some(v) = self.take(name) {
            *into = v
                .extract()
                .map_err(|_| self.bad(name, &v, "a whole number >= 0 or None"))?;
        }
        Ok(())
    }

    /// A flag.
    pub fn bool(&mut self, name: &str, into: &mut bool) -> PyResult<()> {
        if let Some(v) = self.take(name) {
            *into = v
                .extract()
                .map_err(|_| self.bad(name, &v, "True or False"))?;
        }
        Ok(())
    }

    /// Text; a number is taken as its text (`stepover=0.4`, `feed=1500`), a path as its path.
    pub fn text(&mut self, name: &str, into: &mut String) -> PyResult<()> {
        if let Some(v) = self.take(name) {
            *into = self.text_of(name, &v)?;
        }
        Ok(())
    }

    /// Text or `None`.
    pub fn opt_text(&mut self, name: &str, into: &mut Option<String>) -> PyResult<()> {
        if let Some(v) = self.take(name) {
            *into = if v.is_none() {
                None
            } else {
                Some(self.text_of(name, &v)?)
            };
        }
        Ok(())
    }

    fn text_of(&self, name: &str, v: &Bound<'py, PyAny>) -> PyResult<String> {
        if let Some(p) = path_text(v)? {
            return Ok(p);
        }
        if let Ok(i) = v.extract::<i64>() {
            return Ok(i.to_string());
        }
        if let Ok(x) = v.extract::<f64>() {
            return Ok(x.to_string());
        }
        Err(self.bad(name, v, "text or a number"))
    }

    /// A value parsed from text (`dialect="fanuc"`), refused with the parser's message.
    pub fn parsed<T>(&mut self, name: &str, into: &mut T) -> PyResult<()>
    where
        T: std::str::FromStr<Err = millpath::InputError>,
    {
        if let Some(v) = self.take(name) {
            let s = self.text_of(name, &v)?;
            *into = s.parse().map_err(input_err)?;
        }
        Ok(())
    }

    /// The program settings (`dialect`, `units`, `decimals`, `tool_number`, `spindle`,
    /// `coolant`, `line_numbers`).
    pub fn program(&mut self) -> PyResult<millpath::job::ProgramSettings> {
        let mut p = millpath::job::ProgramSettings::default();
        self.parsed("dialect", &mut p.dialect)?;
        self.parsed("units", &mut p.units)?;
        self.opt_u32("decimals", &mut p.decimals)?;
        self.u32("tool_number", &mut p.tool_number)?;
        self.f64("spindle", &mut p.spindle)?;
        self.parsed("coolant", &mut p.coolant)?;
        self.bool("line_numbers", &mut p.line_numbers)?;
        Ok(p)
    }

    /// The drawing settings (`layer`, `join_tolerance`, `drawing_units`).
    pub fn import(&mut self) -> PyResult<millpath::io::ImportSettings> {
        let mut i = millpath::io::ImportSettings::default();
        self.opt_text("layer", &mut i.layer)?;
        self.f64("join_tolerance", &mut i.join_tolerance)?;
        self.opt_text("drawing_units", &mut i.drawing_units)?;
        Ok(i)
    }

    /// Refuses the names left (a `TypeError`, as Python does for an unknown keyword).
    pub fn finish(self) -> PyResult<()> {
        match self.map.first() {
            None => Ok(()),
            Some((k, _)) => Err(pyo3::exceptions::PyTypeError::new_err(format!(
                "{}() got an unexpected keyword argument '{k}'",
                self.func
            ))),
        }
    }
}
