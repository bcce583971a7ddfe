//! Reading a pocket outline for `pocket`, `verify` and `sweep`: JSON, DXF, SVG or a sample,
//! with the drawing flags (`--layer`, `--join-tolerance`, `--drawing-units`). What a DXF or
//! SVG held (units, extents, skipped entities) is printed as a `note:` on stderr, so a wrong
//! scale shows before anything is cut.

use millpath::Error;
use millpath::io::ImportSettings;
use millpath::io::outline_json::Loops;

/// How a DXF or SVG drawing is read.
#[derive(Debug, Clone, clap::Args)]
pub struct ImportArgs {
    /// Only the outlines on this layer (DXF layer; SVG <g> with this inkscape:label or id).
    #[arg(long)]
    pub layer: Option<String>,
    /// Largest gap between piece ends joined into one outline, mm.
    #[arg(long, default_value_t = millpath::io::DEFAULT_JOIN_TOLERANCE_MM)]
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
            join_tolerance: millpath::io::DEFAULT_JOIN_TOLERANCE_MM,
            drawing_units: None,
        }
    }
}

impl ImportArgs {
    /// The engine's import settings these flags give.
    pub fn settings(&self) -> ImportSettings {
        ImportSettings {
            layer: self.layer.clone(),
            join_tolerance: self.join_tolerance,
            drawing_units: self.drawing_units.clone(),
        }
    }
}

/// Reads an outline file (by extension) or a built-in sample ([`millpath::job::load_outline`]),
/// printing what a drawing held as a `note:`.
pub fn load_outline(name: &str, import: &ImportArgs) -> Result<Loops, Error> {
    let (loops, note) = millpath::job::load_outline(name, &import.settings())?;
    if let Some(n) = note {
        super::eprint(&format!("note: {n}"));
    }
    for n in &loops.notes {
        super::eprint(&format!("note: {name}: {n}"));
    }
    Ok(loops)
}
