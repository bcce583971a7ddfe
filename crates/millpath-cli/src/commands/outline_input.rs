//! Reading a pocket outline for `pocket`, `verify` and `sweep`: JSON, DXF, SVG or a sample,
//! with the drawing flags (`--layer`, `--join-tolerance`, `--drawing-units`). What a DXF or
//! SVG held (units, extents, skipped entities) is printed as a `note:` on stderr, so a wrong
//! scale shows before anything is cut.

use millpath::io::outline_json::Loops;
use millpath::io::{ReadOptions, dxf, svg};
use millpath::strategy::pocket::samples;
use millpath::{Error, InputError};
use std::path::Path;

/// How a DXF or SVG drawing is read.
#[derive(Debug, Clone, clap::Args)]
pub struct ImportArgs {
    /// Only the outlines on this layer (DXF layer; SVG <g> with this inkscape:label or id).
    #[arg(long)]
    pub layer: Option<String>,
    /// Largest gap between piece ends joined into one outline, mm.
    #[arg(long, default_value_t = millpath::io::drawing::DEFAULT_JOIN_TOLERANCE_MM)]
    pub join_tolerance: f64,
    /// The drawing's unit, overriding the file ($INSUNITS/$MEASUREMENT, SVG width/height/
    /// viewBox): mm, cm, m, in, ft, pt or px.
    #[arg(long)]
    pub drawing_units: Option<String>,
}

impl Default for ImportArgs {
    fn default() -> Self {
        ImportArgs {
            layer: None,
            join_tolerance: millpath::io::drawing::DEFAULT_JOIN_TOLERANCE_MM,
            drawing_units: None,
        }
    }
}

impl ImportArgs {
    /// The reader options these flags give.
    pub fn options(&self) -> Result<ReadOptions, InputError> {
        let mm_per_unit = match self.drawing_units.as_deref() {
            None => None,
            Some(u) => Some(match u {
                "mm" => 1.0,
                "cm" => 10.0,
                "m" => 1000.0,
                "in" => 25.4,
                "ft" => 304.8,
                "pt" => 25.4 / 72.0,
                "px" => 25.4 / 96.0,
                _ => {
                    return Err(InputError::new("drawing units", u)
                        .at("--drawing-units")
                        .expected("mm, cm, m, in, ft, pt or px"));
                }
            }),
        };
        let opts = ReadOptions {
            join_tolerance: self.join_tolerance,
            layer: self.layer.clone(),
            mm_per_unit,
            ..ReadOptions::default()
        };
        opts.validate("--join-tolerance / --drawing-units")?;
        Ok(opts)
    }
}

/// Reads an outline file (by extension) or a built-in sample.
pub fn load_outline(name: &str, import: &ImportArgs) -> Result<Loops, Error> {
    if name == "sample:aerospace" {
        let s = samples::aerospace_pocket();
        return Ok(Loops::single(s.outer, s.islands));
    }
    let path = Path::new(name);
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let drawing_only = |flag: &str| -> Result<(), Error> {
        Err(InputError::new(flag, name)
            .expected("a .dxf or .svg drawing (the flag does not apply to this input)")
            .into())
    };
    let drawing = match ext.as_deref() {
        Some("json") => {
            if import.layer.is_some() {
                drawing_only("--layer")?;
            }
            return Ok(millpath::io::outline_json::parse(
                &super::read_text(path)?,
                name,
            )?);
        }
        Some("svg") => svg::read_loops(&super::read_text(path)?, name, &import.options()?)?,
        Some("dxf") => {
            let bytes = std::fs::read(path).map_err(|e| {
                Error::Input(
                    InputError::new("input file", name)
                        .expected(format!("a readable DXF file ({e})")),
                )
            })?;
            dxf::read_loops(&bytes, name, &import.options()?)?
        }
        _ => {
            return Err(InputError::new("outline file", name)
                .expected("a .json, .dxf or .svg file, or sample:aerospace")
                .into());
        }
    };
    // The note only for a drawing that reads: a refusal's message already holds it, on
    // its one line.
    let summary = drawing.summary();
    let loops = drawing.into_loops(name, import.join_tolerance)?;
    super::eprint(&format!("note: {name}: {summary}"));
    for n in &loops.notes {
        super::eprint(&format!("note: {name}: {n}"));
    }
    Ok(loops)
}
