//! A whole-part stock check of any program that cuts a drawing out or drills its holes,
//! whoever wrote it (the FreeCAD peer programs of `tools/freecad_profile/`, or ours): the
//! engine's verifiers on the moves read back, nothing from the strategies.
//!
//! ```text
//! cargo run --release --example peer_check -- outlines DRAWING
//! cargo run --release --example peer_check -- profile DRAWING PROGRAM --tool-diameter D --thickness T
//! cargo run --release --example peer_check -- holes DRAWING PROGRAM --diameter d --bottom Z
//! ```
//!
//! * `outlines` prints the drawing as millpath reads it (JSON, mm): the parts (outermost
//!   outlines), their windows (inner outlines that are not circles) and their holes (circles
//!   within 0.01 mm), vertices as `[x, y, bulge]`. `tools/freecad_profile/` builds its FreeCAD
//!   solid from it, so both programs cut the same geometry.
//! * `profile` cuts a block (the parts' extents plus `3 D + 10` mm, from `-T` to `0`) by the
//!   program with a flat end mill of diameter `D` (`stock::HeightField`) and reports: rapids
//!   through material and plunges; each part's bridge verdict (`stock::held_by`, cut outside;
//!   windows cut inside: their slugs); the exact least distance from the tool centre to the
//!   drawn walls below the top (`stock::min_clearance`, against `D/2`); the part's material
//!   cut below the top (`stock::check_field`, windows and holes as regions cut through).
//! * `holes` checks the program against the drawing's circles of diameter `d` (within
//!   `--tolerance`, 0.01 mm by default) with `stock::verify_holes`: nothing cut outside a hole,
//!   no rapid through material, each hole's envelope at `Z` on the drawn centre and diameter.
//! * Both first print the program's feed path and rapid lengths as read back (canned cycles
//!   expanded into their moves, arcs and helices by their length).
//!
//! Exit code 0 when every check passes, 1 when one fails, 2 for bad arguments or input.
#![allow(clippy::print_stdout, clippy::print_stderr)]

use millpath::geom::{Hole, Outline, Point3};
use millpath::io::ImportSettings;
use millpath::job::part::PartModel;
use millpath::stock::{
    BridgeOptions, CheckOptions, CutSide, Deviation, FieldOptions, Floor, HeightField, PartTop,
    StockSpec, check_field, held_by, min_clearance, verify_holes,
};
use millpath::toolpath::Tool;
use millpath::{Move, Toolpath, Vec2};
use serde_json::{Value, json};
use std::process::ExitCode;

type Res<T> = Result<T, String>;

/// The drawing read as parts, windows and holes.
fn model(drawing: &str) -> Res<PartModel> {
    let (loops, _) = millpath::io::read_outline_file(drawing, &ImportSettings::default())
        .map_err(|e| e.to_string())?;
    let circle = |o: &Outline| Hole::from_outline(o, 0.01).map(|h| (h.center, h.diameter));
    Ok(PartModel::new(&loops.pockets(), &circle))
}

fn vertices(o: &Outline) -> Value {
    Value::Array(
        o.vertices()
            .map(|(p, b)| json!([p.x, p.y, b]))
            .collect::<Vec<_>>(),
    )
}

fn outlines(drawing: &str) -> Res<bool> {
    let m = model(drawing)?;
    let b = m.bounds().ok_or("the drawing has no closed outline")?;
    let out = json!({
        "drawing": drawing,
        "units": "mm",
        "bounds": [b.min.x, b.min.y, b.max.x, b.max.y],
        "parts": m.parts.iter().map(vertices).collect::<Vec<_>>(),
        "windows": m.pockets.iter().map(|p| json!({"part": p.part, "outline": vertices(&p.outer)})).collect::<Vec<_>>(),
        "holes": m.holes.iter().map(|h| json!({"part": h.part, "x": h.center.x, "y": h.center.y, "d": h.diameter})).collect::<Vec<_>>(),
    });
    println!("{out:#}");
    Ok(true)
}

/// The program read back (LinuxCNC's RS274/NGC) with the given tool.
fn program(path: &str, tool: Tool) -> Res<Toolpath> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{path}: {e}"))?;
    let opts = millpath::gcode::ReaderOptions::default().with_origin(path);
    let (mut tp, _) = millpath::gcode::read_str(&text, opts).map_err(|e| e.to_string())?;
    tp.tool = tool;
    println!(
        "program: feed path {:.1} mm, rapids {:.1} mm, {} moves",
        tp.cut_length(),
        tp.rapid_length(),
        tp.moves.len()
    );
    Ok(tp)
}

/// `--name value` among `args`, as a number.
fn number(args: &[String], name: &str) -> Res<Option<f64>> {
    match args.iter().position(|a| a == name) {
        None => Ok(None),
        Some(i) => {
            let v = args.get(i + 1).ok_or(format!("{name} needs a value"))?;
            let x: f64 = v
                .parse()
                .map_err(|_| format!("{name} = {v}: expected a number"))?;
            if x.is_finite() {
                Ok(Some(x))
            } else {
                Err(format!("{name} = {v}: expected a finite number"))
            }
        }
    }
}

fn required(args: &[String], name: &str) -> Res<f64> {
    number(args, name)?.ok_or(format!("{name} is required"))
}

fn profile(drawing: &str, path: &str, args: &[String]) -> Res<bool> {
    let d = required(args, "--tool-diameter")?;
    let t = required(args, "--thickness")?;
    let m = model(drawing)?;
    let tool = Tool::flat(d).map_err(|e| e.to_string())?;
    let r = tool.radius();
    let tp = program(path, tool)?;
    let b = m.bounds().ok_or("the drawing has no closed outline")?;
    let mut field = HeightField::new(
        b.inflate(3.0 * d + 10.0),
        -t,
        0.0,
        &FieldOptions::default().with_tool_diameter(d),
    )
    .map_err(|e| e.to_string())?;
    let cut = field.cut(&tp);
    println!(
        "stock {:.1} x {:.1} mm, cell {:.4} mm; {cut}",
        field.bounds().width(),
        field.bounds().height(),
        field.cell()
    );
    let mut ok = cut.problems().is_empty();
    let hole_outlines: Vec<Outline> = m
        .holes
        .iter()
        .map(|h| {
            let r = Vec2::new(0.5 * h.diameter, 0.0);
            Outline::new(&[(h.center - r, 1.0), (h.center + r, 1.0)], "a drawn hole")
        })
        .collect::<Result<_, _>>()
        .map_err(|e| e.to_string())?;
    for (k, part) in m.parts.iter().enumerate() {
        let verdict = held_by(
            &field,
            part,
            -t,
            r,
            &BridgeOptions::default().with_side(CutSide::Outside),
        )
        .map_err(|e| e.to_string())?;
        println!("part {}: {verdict}", k + 1);
        ok &= verdict.holding().count() > 0
            && verdict
                .bridges
                .iter()
                .all(|b| b.holds() || b.area_mm2 < 1.0);
        let windows: Vec<&Outline> = m
            .pockets
            .iter()
            .filter(|p| p.part == k)
            .map(|p| &p.outer)
            .collect();
        for (j, w) in windows.iter().enumerate() {
            let v = held_by(
                &field,
                w,
                -t,
                r,
                &BridgeOptions::default().with_side(CutSide::Inside),
            )
            .map_err(|e| e.to_string())?;
            println!("part {} window {}: {v}", k + 1, j + 1);
        }
        let islands: Vec<Outline> = windows
            .iter()
            .map(|w| (*w).clone())
            .chain(
                m.holes
                    .iter()
                    .zip(&hole_outlines)
                    .filter(|(h, _)| h.part == k)
                    .map(|(_, o)| o.clone()),
            )
            .collect();
        let c = min_clearance(
            &tp,
            StockSpec {
                outer: part,
                islands: &islands,
                wall_stock: 0.0,
            },
        );
        let gouge = c.distance < r - millpath::stock::GOUGE_RESOLUTION;
        println!(
            "part {}: least distance from the tool centre to a drawn wall below the top {:.4} mm (radius {r:.4}){}",
            k + 1,
            c.distance,
            if gouge {
                format!(
                    ": GOUGE at ({:.3}, {:.3}, {:.3}), move {}",
                    c.at.x, c.at.y, c.at.z, c.move_index
                )
            } else {
                String::new()
            }
        );
        ok &= !gouge;
        let floors: Vec<Floor<'_>> = islands
            .iter()
            .map(|o| Floor {
                outer: o,
                islands: &[],
                z: -t,
                tool_radius: r,
            })
            .collect();
        let fc = check_field(
            &field,
            Some(PartTop {
                outline: part,
                windows: &[],
                top_z: 0.0,
            }),
            &floors,
            &CheckOptions::default(),
        );
        let into: Vec<&Deviation> = fc
            .deviations
            .iter()
            .filter(|d| matches!(d, Deviation::CutIntoPart { .. }))
            .collect();
        if into.is_empty() {
            println!("part {}: nothing cut into the part", k + 1);
        }
        for d in &into {
            println!("part {}: {d}", k + 1);
        }
        ok &= into.is_empty();
    }
    Ok(ok)
}

fn holes(drawing: &str, path: &str, args: &[String]) -> Res<bool> {
    let d = required(args, "--diameter")?;
    let bottom = required(args, "--bottom")?;
    let tol = number(args, "--tolerance")?.unwrap_or(0.01);
    let m = model(drawing)?;
    let drawn: Vec<Hole> = m
        .holes
        .iter()
        .filter(|h| (h.diameter - d).abs() <= tol)
        .map(|h| Hole::new(h.center, h.diameter))
        .collect();
    let tool = Tool::flat(d).map_err(|e| e.to_string())?;
    let tp = program(path, tool)?;
    let mut at = tp.start;
    let moves: Vec<(Point3, Move)> = tp
        .moves
        .iter()
        .map(|mv| {
            let from = at;
            at = mv.to;
            (from, *mv)
        })
        .collect();
    let v = verify_holes(&drawn, &moves, &tool, 0.0, bottom, tol);
    let cut = v.holes.iter().filter(|h| h.is_some()).count();
    let worst = |f: &dyn Fn(&millpath::stock::HoleCheck) -> f64| {
        v.holes.iter().flatten().map(f).fold(0.0, f64::max)
    };
    println!(
        "{} holes of {d} mm drawn, {cut} cut to Z {bottom}; worst diameter error {:.4} mm, centre error {:.4} mm, roundness {:.4} mm",
        drawn.len(),
        worst(&|h| (h.diameter_mm - d).abs()),
        worst(&|h| h.center_error_mm),
        worst(&|h| h.roundness_mm)
    );
    for p in &v.problems {
        println!("problem: {p}");
    }
    Ok(v.ok() && cut == drawn.len() && !drawn.is_empty())
}

fn run(args: &[String]) -> Res<bool> {
    match args {
        [cmd, drawing] if cmd == "outlines" => outlines(drawing),
        [cmd, drawing, path, rest @ ..] if cmd == "profile" => profile(drawing, path, rest),
        [cmd, drawing, path, rest @ ..] if cmd == "holes" => holes(drawing, path, rest),
        _ => Err("usage: peer_check outlines DRAWING | profile DRAWING PROGRAM --tool-diameter D --thickness T | holes DRAWING PROGRAM --diameter d --bottom Z [--tolerance t]".into()),
    }
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match run(&args) {
        Ok(true) => ExitCode::SUCCESS,
        Ok(false) => ExitCode::from(1),
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
    }
}
