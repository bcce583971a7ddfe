//! Reading a pocket outline file by its extension: a JSON outline, a DXF or an SVG drawing,
//! with the drawing options (layer, join tolerance, the drawing's unit). What a drawing held
//! (units, extents, skipped entities) comes back as a note for the caller to show, so that a
//! wrong scale shows before anything is cut; the engine never prints it. The built-in samples
//! (`sample:aerospace`) are strategy-layer shapes: `job::load_outline` takes those and files.
//!
//! ```text
//! read_outline_file("part.dxf", &ImportSettings::default()) → (Loops, Some("part.dxf: …"))
//! ```

use super::outline_json::{self, Loops};
use super::{ReadOptions, dxf, svg};
use crate::{Error, InputError};
use std::path::Path;

/// How a DXF or SVG drawing is read (the CLI's `--layer`, `--join-tolerance`,
/// `--drawing-units`).
#[derive(Debug, Clone, PartialEq)]
pub struct ImportSettings {
    /// Only the outlines on this layer (DXF layer; SVG `<g>` with this inkscape:label or id).
    pub layer: Option<String>,
    /// Largest gap between piece ends joined into one outline, mm.
    pub join_tolerance: f64,
    /// The drawing's unit, overriding the file's: mm, cm, m, in, ft, pt or px.
    pub drawing_units: Option<String>,
}

impl Default for ImportSettings {
    fn default() -> Self {
        ImportSettings {
            layer: None,
            join_tolerance: super::drawing::DEFAULT_JOIN_TOLERANCE_MM,
            drawing_units: None,
        }
    }
}

/// Millimetres per unit of a unit name (`mm`, `cm`, `m`, `in`, `ft`, `pt`, `px`).
pub fn mm_per_unit(name: &str) -> Option<f64> {
    Some(match name {
        "mm" => 1.0,
        "cm" => 10.0,
        "m" => 1000.0,
        "in" => 25.4,
        "ft" => 304.8,
        "pt" => 25.4 / 72.0,
        "px" => 25.4 / 96.0,
        _ => return None,
    })
}

impl ImportSettings {
    /// The reader options these settings give.
    pub fn options(&self) -> Result<ReadOptions, InputError> {
        let mm_per_unit = match self.drawing_units.as_deref() {
            None => None,
            Some(u) => Some(mm_per_unit(u).ok_or_else(|| {
                InputError::new("drawing units", u)
                    .at("--drawing-units")
                    .expected("mm, cm, m, in, ft, pt or px")
            })?),
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

/// Reads a whole text file, turning an I/O failure into an input error naming the file.
pub fn read_text(path: &Path) -> Result<String, Error> {
    std::fs::read_to_string(path).map_err(|e| {
        Error::Input(
            InputError::new("input file", path.display())
                .expected(format!("a readable text file ({e})")),
        )
    })
}

/// Every closed outline of an outline file (by extension), as drawn (windings as in the
/// file; nothing merged or nested): a JSON outline's boundary and islands, a DXF's or SVG's
/// closed outlines (refused when it has none, with what it holds). Returns them and, for a
/// drawing, the note of what it held (`NAME: summary`).
pub fn read_outlines(
    name: &str,
    import: &ImportSettings,
) -> Result<(Vec<crate::geom::Outline>, Option<String>), Error> {
    let drawing = match read_drawing(name, import)? {
        Read::Loops(loops) => {
            let all = loops
                .pockets()
                .into_iter()
                .flat_map(|p| std::iter::once(p.outer).chain(p.islands))
                .collect();
            return Ok((all, None));
        }
        Read::Drawing(d) => d,
    };
    if drawing.outlines.is_empty() {
        return Err(drawing.nothing_closed(name).into());
    }
    let summary = drawing.summary();
    Ok((drawing.outlines, Some(format!("{name}: {summary}"))))
}

/// What reading a file by its extension gave.
enum Read {
    /// A JSON outline.
    Loops(Loops),
    /// A DXF or SVG drawing.
    Drawing(super::Drawing),
}

fn read_drawing(name: &str, import: &ImportSettings) -> Result<Read, Error> {
    File::read(name)?.parse(name, import)
}

/// An outline file's contents by its kind (its extension, any case): JSON and SVG as text,
/// DXF as bytes (it may be binary).
enum File {
    Json(String),
    Svg(String),
    Dxf(Vec<u8>),
}

/// The kinds of outline file.
#[derive(Clone, Copy)]
enum Kind {
    Json,
    Svg,
    Dxf,
}

/// What the extension of `name` says the file is.
fn kind(name: &str) -> Result<Kind, InputError> {
    let ext = Path::new(name)
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("json") => Ok(Kind::Json),
        Some("svg") => Ok(Kind::Svg),
        Some("dxf") => Ok(Kind::Dxf),
        _ => Err(InputError::new("outline file", name)
            .expected("a .json, .dxf or .svg file, or sample:aerospace or sample:part")),
    }
}

impl File {
    /// Reads the file at `name`.
    fn read(name: &str) -> Result<File, Error> {
        let path = Path::new(name);
        Ok(match kind(name)? {
            Kind::Json => File::Json(read_text(path)?),
            Kind::Svg => File::Svg(read_text(path)?),
            Kind::Dxf => File::Dxf(std::fs::read(path).map_err(|e| {
                Error::Input(
                    InputError::new("input file", name)
                        .expected(format!("a readable DXF file ({e})")),
                )
            })?),
        })
    }

    /// The file named `name` from its contents, refused as reading it would be (JSON and
    /// SVG must be UTF-8 text).
    fn from_bytes(name: &str, bytes: &[u8]) -> Result<File, Error> {
        let text = || {
            String::from_utf8(bytes.to_vec()).map_err(|_| {
                Error::Input(
                    InputError::new("input file", name)
                        .expected("a readable text file (stream did not contain valid UTF-8)"),
                )
            })
        };
        Ok(match kind(name)? {
            Kind::Json => File::Json(text()?),
            Kind::Svg => File::Svg(text()?),
            Kind::Dxf => File::Dxf(bytes.to_vec()),
        })
    }

    /// The outlines the file holds (`name` names it in messages).
    fn parse(&self, name: &str, import: &ImportSettings) -> Result<Read, Error> {
        Ok(Read::Drawing(match self {
            File::Json(text) => {
                if import.layer.is_some() {
                    return Err(InputError::new("--layer", name)
                        .expected("a .dxf or .svg drawing (the flag does not apply to this input)")
                        .into());
                }
                return Ok(Read::Loops(outline_json::parse(text, name)?));
            }
            File::Svg(text) => svg::read_loops(text, name, &import.options()?)?,
            File::Dxf(bytes) => dxf::read_loops(bytes, name, &import.options()?)?,
        }))
    }
}

/// The loops of a drawing and the note of what it held, from a read drawing.
fn loops_of(
    read: Read,
    name: &str,
    import: &ImportSettings,
) -> Result<(Loops, Option<String>), Error> {
    let drawing = match read {
        Read::Loops(loops) => return Ok((loops, None)),
        Read::Drawing(d) => d,
    };
    // The note only for a drawing that reads: a refusal's message already holds it, on
    // its one line.
    let summary = drawing.summary();
    let loops = drawing.into_loops(name, import.join_tolerance)?;
    Ok((loops, Some(format!("{name}: {summary}"))))
}

/// [`read_outline_file`] on a file's contents rather than its path, for a front end that has
/// the bytes and no file system (the web page): `name` gives the kind by its extension and
/// names the file in messages, which are those reading the file `name` gives.
///
/// ```text
/// read_outline_bytes("part.dxf", &bytes, &ImportSettings::default()) → (Loops, Some("part.dxf: …"))
/// ```
pub fn read_outline_bytes(
    name: &str,
    bytes: &[u8],
    import: &ImportSettings,
) -> Result<(Loops, Option<String>), Error> {
    loops_of(
        File::from_bytes(name, bytes)?.parse(name, import)?,
        name,
        import,
    )
}

/// Reads an outline file (by extension); returns the loops and, for a drawing, the note of
/// what it held (`NAME: summary`).
pub fn read_outline_file(
    name: &str,
    import: &ImportSettings,
) -> Result<(Loops, Option<String>), Error> {
    loops_of(read_drawing(name, import)?, name, import)
}
