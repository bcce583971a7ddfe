//! Pocket outlines from DXF drawings (ASCII or binary, AutoCAD R12 to R2018 and the files
//! LibreCAD, Inkscape, Onshape, SOLIDWORKS, BricsCAD and scripts write).
//!
//! [`read_loops`] returns every closed outline of the drawing in mm, with what it read and
//! skipped ([`Drawing`]); [`parse`] hands them to the outer-outline/island classification.
//!
//! * **Units.** Coordinates are scaled to mm by `$INSUNITS` (1 in, 2 ft, 4 mm, 5 cm, 6 m, …,
//!   the DXF reference's 0–20); when it is 0 (unitless) or absent, by `$MEASUREMENT`
//!   (0 imperial: inches, 1 metric: mm); when both are absent (headerless files), mm is
//!   assumed and the summary says so. [`ReadOptions::mm_per_unit`] overrides the file.
//!   Header variables are read wherever they appear, so dxflib's files (header variables
//!   after the header's `ENDSEC`) read as their writer meant.
//! * **Entities** (`entities`): LINE, ARC, CIRCLE, LWPOLYLINE, POLYLINE/VERTEX, ELLIPSE,
//!   SPLINE, HATCH boundaries, INSERT (nested blocks); the rest counted and skipped.
//! * **Joins** (`crate::io::join`): open pieces chained end to end within
//!   [`ReadOptions::join_tolerance`] (mm, after scaling).
//! * **Layers:** [`ReadOptions::layer`] keeps one layer (names compared ignoring ASCII case,
//!   as AutoCAD does); an unknown layer is refused with the list of the file's layers.
//!
//! Why not the `dxf` crate (0.6): it has no HATCH entity, stops at dxflib's header layout,
//! and reading the group codes directly is a few hundred lines we control (every malformed
//! value is an input error, never a panic; the fuzz target `outline_importers` covers it).

mod codes;
pub(crate) mod entities;
mod hatch;
pub(crate) mod spline;

use super::drawing::{Drawing, ReadOptions};
use super::join::join;
use super::outline_json::Loops;
use crate::error::InputError;
use crate::geom::Point;
use codes::Group;
use codes::Record;
use entities::{Block, Ctx, Reader};
use std::collections::HashMap;

/// The DXF importer's options (the importers share one options type).
pub type DxfOptions = ReadOptions;

/// Millimetres per unit of `$INSUNITS` code `code` (DXF reference), `None` for 0 (unitless)
/// and unknown codes.
pub fn insunits_mm(code: i64) -> Option<(f64, &'static str)> {
    Some(match code {
        1 => (25.4, "in"),
        2 => (304.8, "ft"),
        3 => (1_609_344.0, "mi"),
        4 => (1.0, "mm"),
        5 => (10.0, "cm"),
        6 => (1000.0, "m"),
        7 => (1e6, "km"),
        8 => (25.4e-6, "µin"),
        9 => (0.0254, "mil"),
        10 => (914.4, "yd"),
        11 => (1e-7, "Å"),
        12 => (1e-6, "nm"),
        13 => (1e-3, "µm"),
        14 => (100.0, "dm"),
        15 => (1e4, "dam"),
        16 => (1e5, "hm"),
        17 => (1e12, "Gm"),
        18 => (1.495_978_707e14, "AU"),
        19 => (9.460_730_472_580_8e18, "ly"),
        20 => (3.085_677_581_49e19, "pc"),
        _ => return None,
    })
}

/// The drawing's scale to mm and how it was found.
fn units(header: &HashMap<String, Group>, opts: &ReadOptions) -> (f64, String) {
    if let Some(s) = opts.mm_per_unit {
        return (s, format!("{s} mm per unit (given)"));
    }
    let ins = header.get("$INSUNITS").map(Group::int);
    if let Some(code) = ins
        && let Some((s, name)) = insunits_mm(code)
    {
        return (s, format!("{name} ($INSUNITS = {code})"));
    }
    match header.get("$MEASUREMENT").map(Group::int) {
        Some(0) => (25.4, "in ($MEASUREMENT = 0, imperial)".to_owned()),
        Some(m) => (1.0, format!("mm ($MEASUREMENT = {m}, metric)")),
        None => (
            1.0,
            match ins {
                Some(code) => format!("mm ($INSUNITS = {code}, no $MEASUREMENT: assumed)"),
                None => "mm (no $INSUNITS or $MEASUREMENT: assumed)".to_owned(),
            },
        ),
    }
}

/// Reads the closed outlines of a DXF drawing, in mm; `origin` names the file.
pub fn read_loops(bytes: &[u8], origin: &str, opts: &ReadOptions) -> Result<Drawing, InputError> {
    opts.validate(origin)?;
    let groups = codes::read(bytes, origin)?;
    let mut header: HashMap<String, Group> = HashMap::new();
    let mut blocks: HashMap<String, Block> = HashMap::new();
    let mut ents: Vec<Record> = Vec::new();
    let mut section = String::new();
    let mut block: Option<(String, Block)> = None;
    let mut i = 0;
    while i < groups.len() {
        if groups[i].code != 0 {
            i += 1;
            continue;
        }
        let kind = groups[i].value.to_ascii_uppercase();
        let start = i + 1;
        i = start;
        while i < groups.len() && groups[i].code != 0 {
            i += 1;
        }
        let body = &groups[start..i];
        match kind.as_str() {
            "SECTION" | "ENDSEC" | "EOF" => {
                if kind == "SECTION" {
                    section = body
                        .iter()
                        .find(|g| g.code == 2)
                        .map_or(String::new(), |g| g.value.to_ascii_uppercase());
                } else {
                    section.clear();
                }
                // Header variables: `9 $NAME` then the value's group.
                for (k, g) in body.iter().enumerate() {
                    if g.code == 9
                        && let Some(v) = body.get(k + 1)
                    {
                        header.entry(g.value.clone()).or_insert_with(|| v.clone());
                    }
                }
            }
            _ => {
                let rec = Record {
                    kind: kind.clone(),
                    groups: body.to_vec(),
                };
                match section.as_str() {
                    "ENTITIES" => ents.push(rec),
                    "BLOCKS" => match kind.as_str() {
                        "BLOCK" => {
                            let name = rec.groups.iter().find(|g| g.code == 2);
                            let num = |c: i32| {
                                rec.groups
                                    .iter()
                                    .find(|g| g.code == c)
                                    .map_or(0.0, Group::real)
                            };
                            block = Some((
                                name.map_or(String::new(), |g| g.value.to_ascii_uppercase()),
                                Block {
                                    base: Point::new(num(10), num(20)),
                                    records: Vec::new(),
                                },
                            ));
                        }
                        "ENDBLK" => {
                            if let Some((name, b)) = block.take() {
                                blocks.insert(name, b);
                            }
                        }
                        _ => {
                            if let Some((_, b)) = &mut block {
                                b.records.push(rec);
                            }
                        }
                    },
                    _ => {}
                }
            }
        }
    }
    let (scale, unit_text) = units(&header, opts);
    let mut drawing = Drawing {
        units: unit_text,
        mm_per_unit: scale,
        layer: opts.layer.clone(),
        ..Drawing::default()
    };
    let mut reader = Reader::new(&blocks, opts, origin, &mut drawing);
    let root = Ctx {
        t: super::affine::Affine::scale(scale, scale),
        layer: None,
        depth: 0,
    };
    reader.entities(&ents, &root)?;
    let pieces = std::mem::take(&mut reader.pieces);
    if let Some(want) = &opts.layer
        && !drawing.layers.iter().any(|l| l.eq_ignore_ascii_case(want))
    {
        return Err(InputError::new("layer", want).at(origin).expected(format!(
            "one of the drawing's layers: {}",
            drawing
                .layers
                .iter()
                .cloned()
                .collect::<Vec<_>>()
                .join(", ")
        )));
    }
    let joined = join(pieces, opts.join_tolerance);
    drawing.open = joined.open;
    drawing.degenerate = joined.degenerate;
    drawing.add_closed(&joined.closed, origin, opts.tolerance);
    Ok(drawing)
}

/// Reads a DXF drawing's outer outline and islands from `bytes`; `origin` names the file.
pub fn parse(bytes: &[u8], origin: &str, opts: &DxfOptions) -> Result<Loops, InputError> {
    read_loops(bytes, origin, opts)?.into_loops(origin, opts.join_tolerance)
}
