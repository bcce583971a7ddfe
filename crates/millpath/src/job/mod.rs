//! Jobs: a whole command's pipeline from its settings to the program text and the report,
//! for every front end alike (the `millpath` CLI, the Python package). A job checks its
//! settings with the names of the CLI's flags (`--tool-diameter`), reads its inputs, plans,
//! writes the program and reads it back for the cycle time; it never prints or writes files.
//!
//! This is the top layer: it may use every other module, and none uses it.

pub mod contour;
pub mod drill;
pub mod estimate;
pub mod five_axis;
pub mod optimize;
pub mod part;
pub mod pocket;
pub(crate) mod pocket_report;
pub mod profile;
pub(crate) mod profile_check;
pub(crate) mod profile_runs;
pub(crate) mod program;
pub mod rest;
pub mod sweep;
pub(crate) mod timing;
pub mod verify;

use crate::Error;
use crate::io::ImportSettings;
use crate::io::outline_json::Loops;
use crate::machine::Machine;
use crate::strategy::pocket::builtin;
use std::path::Path;

pub use drill::{DrillReport, DrillRun, DrillSettings};
pub use pocket::{PocketRun, PocketSettings};
pub use pocket_report::{
    AirTimes, AutoEntry, PocketEntry, REPORT_TIME_MODEL, Report as PocketReport, air_times,
    auto_entries, auto_line, pocket_line,
};
pub use profile::{ProfileRun, ProfileSettings};
pub use program::{ProgramSettings, program_time, program_times};
pub use timing::time_and_verify;

/// The built-in outline names `load_outline` takes.
pub const SAMPLE_OUTLINES: &[&str] = &["sample:aerospace", "sample:part"];

/// Reads an outline by name: a built-in sample (`sample:aerospace`, the paper's pocket;
/// `sample:part`, the sample part's drawing [`sample_part_job_drawing`] read through the DXF
/// reader with `import`'s layer) or a JSON, DXF or SVG file ([`crate::io::read_outline_file`]);
/// returns the loops and, for a drawing, the note of what it held.
pub fn load_outline(name: &str, import: &ImportSettings) -> Result<(Loops, Option<String>), Error> {
    match name {
        "sample:aerospace" => {
            let s = builtin::aerospace_pocket();
            Ok((Loops::single(s.outer, s.islands), None))
        }
        "sample:part" => {
            let dxf = sample_part_job_drawing();
            let opts = crate::io::dxf::DxfOptions::default().with_layer(import.layer.clone());
            Ok((crate::io::dxf::parse(dxf.as_bytes(), name, &opts)?, None))
        }
        _ => crate::io::read_outline_file(name, import),
    }
}

/// The built-in sample part (after the adaptive-spiral paper's Figure 17) as a drawing: its
/// pockets written as a DXF (LWPOLYLINEs with bulges) and read back through the DXF reader,
/// the path any drawing takes. Returns the DXF text and the pockets read back, named
/// `pocket 1`, `pocket 2`, ... (`origin` names the drawing in messages).
pub fn sample_part_drawing(
    origin: &str,
) -> Result<(String, Vec<(String, crate::strategy::pocket::PocketShape)>), Error> {
    let drawn = builtin::structural_part();
    let dxf = crate::io::dxf_out::write_outlines(drawn.iter().map(|(_, s)| &s.outer), "POCKETS");
    let loops = crate::io::dxf::parse(
        dxf.as_bytes(),
        origin,
        &crate::io::dxf::DxfOptions::default(),
    )?;
    let mut part = Vec::new();
    for (i, p) in loops.pockets().into_iter().enumerate() {
        let shape = crate::strategy::pocket::PocketShape::new(
            p.outer,
            p.islands,
            &format!("{origin}, pocket {}", i + 1),
        )?;
        part.push((format!("pocket {}", i + 1), shape));
    }
    Ok((dxf, part))
}

/// The built-in sample part as a whole drawing, for `millpath job` and the demo: the sample
/// part's six pockets ([`builtin::structural_part`]) inside a plate outline (290 × 280 mm,
/// corner radius 15 mm) with four 6 mm holes at its corners and two larger holes (16 and
/// 20 mm) between the pockets, written as a DXF (LWPOLYLINEs with bulges, the holes as two
/// half arcs), the way a drawing reaches a job.
pub fn sample_part_job_drawing() -> String {
    let mut outlines: Vec<crate::geom::Outline> =
        vec![builtin::rounded_rectangle(-15.0, -15.0, 290.0, 280.0, 15.0)];
    outlines.extend(builtin::structural_part().into_iter().map(|(_, s)| s.outer));
    let holes = [
        (-6.0, -6.0, 6.0),
        (266.0, -6.0, 6.0),
        (266.0, 256.0, 6.0),
        (-6.0, 256.0, 6.0),
        (250.0, 215.0, 16.0),
        (85.0, 215.0, 20.0),
    ];
    for (x, y, d) in holes {
        let r = 0.5 * d;
        if let Ok(o) = crate::geom::Outline::new(
            &[
                (crate::geom::Point::new(x + r, y), 1.0),
                (crate::geom::Point::new(x - r, y), 1.0),
            ],
            "the sample part's holes",
        ) {
            outlines.push(o);
        }
    }
    crate::io::dxf_out::write_outlines(outlines.iter(), "PART")
}

/// The machine named by `spec`: a preset name (see `Machine::presets`) or the path of a
/// TOML machine profile (anything ending in `.toml`, or an existing file). Every job that
/// gives a cycle time takes its machine through this one function.
pub fn load_machine(spec: &str) -> Result<Machine, Error> {
    if spec.ends_with(".toml") || Path::new(spec).is_file() {
        let text = crate::io::read_text(Path::new(spec))?;
        Ok(Machine::from_toml_str(&text, spec)?)
    } else {
        Ok(Machine::preset(spec).map_err(|e| e.at("--machine"))?)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The sample part read back from its DXF has the drawn pockets' areas.
    #[test]
    fn sample_part_survives_the_dxf_round_trip() {
        let (dxf, part) = sample_part_drawing("part.dxf").unwrap();
        assert!(dxf.contains("LWPOLYLINE"));
        let drawn = builtin::structural_part();
        assert_eq!(part.len(), drawn.len());
        let area = |o: &crate::geom::Outline| o.signed_area().abs();
        let mut read: Vec<f64> = part.iter().map(|(_, s)| area(&s.outer)).collect();
        let mut want: Vec<f64> = drawn.iter().map(|(_, s)| area(&s.outer)).collect();
        read.sort_by(f64::total_cmp);
        want.sort_by(f64::total_cmp);
        for (r, w) in read.iter().zip(&want) {
            assert!((r - w).abs() < 1e-6 * w, "{r} vs {w}");
        }
        assert_eq!(part[0].0, "pocket 1");
    }
}
