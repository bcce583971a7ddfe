//! The real drawings with circles (`../shared/real-inputs/files/`, sources in its
//! SOURCES.md): their circles found (CIRCLE entities, SVG circles, arcs, spline circles
//! flattened to polygons), and jobs that drill every circle up to 12 mm with a tool of its
//! diameter and bore every larger one with a 6 mm tool: each hole cut exactly once, each
//! program checked by the holes verifier on the program read back (the job refuses
//! otherwise) to within 0.01 mm of the drawn centre and diameter, read by LinuxCNC's
//! `rs274`, its report's cycle time that of the written program.

mod rs274_common;

use millpath::job::ProgramSettings;
use millpath::job::drill::{self, DrillSettings};
use millpath::strategy::drill::Hole;
use std::path::PathBuf;

fn real(name: &str) -> String {
    let d = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/real-inputs/files");
    assert!(
        d.is_dir(),
        "{} is missing: the real-input drawings live in ../shared beside the clone",
        d.display()
    );
    d.join(name).display().to_string()
}

/// The drawings with circles, and the circles each holds: (diameter mm, how many).
fn table() -> Vec<(&'static str, Vec<(f64, usize)>)> {
    vec![
        // CIRCLE entities, mm; the 150 mm one is a round form, holding nothing.
        ("ez_forms.dxf", vec![(26.0, 4), (150.0, 1)]),
        // CIRCLE entities in inches ($MEASUREMENT = 0): r 0.5906 in.
        ("ma_Part.dxf", vec![(30.0, 9)]),
        ("ma_hautparleur.dxf", vec![(3.0, 8)]),
        // Paths of Bézier arcs (Inkscape), 3/16 in.
        ("pb_4_spoke_gear.svg", vec![(4.7625, 2)]),
        // SPLINE circles flattened to polygons (the file's unit is the inch, read as mm).
        ("pb_screw_plate.dxf", vec![(0.215, 8)]),
        ("s2g_shapes.svg", vec![(15.0227, 1)]),
        ("wro_Braking_Arm.DXF", vec![(2.3, 2)]),
        ("wro_Plate_2.DXF", vec![(2.7, 3), (3.0, 10)]),
        ("wro_Plate_3.DXF", vec![(3.0, 8), (4.0, 18)]),
    ]
}

#[test]
fn every_circle_up_to_12_mm_is_drilled_and_every_larger_one_bored() {
    let program = ProgramSettings::default();
    for (file, want) in table() {
        let name = real(file);
        let base = DrillSettings {
            depth: 4.0,
            ..DrillSettings::default()
        };
        let found = drill::find(&name, &base, &mut |_| {}).unwrap();
        let mut groups: Vec<(f64, usize)> = Vec::new();
        for h in &found {
            match groups
                .iter_mut()
                .find(|(d, _)| (d - h.diameter).abs() < 0.005)
            {
                Some(g) => g.1 += 1,
                None => groups.push((h.diameter, 1)),
            }
        }
        groups.sort_by(|a, b| a.0.total_cmp(&b.0));
        assert_eq!(groups.len(), want.len(), "{file}: {groups:?}");
        for ((d, n), (wd, wn)) in groups.iter().zip(&want) {
            assert!(
                (d - wd).abs() < 2e-3 && n == wn,
                "{file}: {groups:?} vs {want:?}"
            );
        }
        // One job per diameter up to 12 mm (a drill of that diameter), one for the rest.
        let mut cut: Vec<Hole> = Vec::new();
        let mut jobs: Vec<DrillSettings> = groups
            .iter()
            .filter(|(d, _)| *d <= 12.0)
            .map(|&(d, _)| DrillSettings {
                tool_diameter: d,
                min_diameter: Some(d - 0.005),
                max_diameter: Some(d + 0.005),
                ..base.clone()
            })
            .collect();
        if groups.iter().any(|(d, _)| *d > 12.0) {
            jobs.push(DrillSettings {
                tool_diameter: 6.0,
                min_diameter: Some(12.0),
                ..base.clone()
            });
        }
        for s in &jobs {
            let run = drill::run(&name, s, &program, &mut |_| {})
                .unwrap_or_else(|e| panic!("{file} with ⌀{}: {e}", s.tool_diameter));
            let rep = &run.report;
            let large = s.max_diameter.is_none();
            let n = rep.holes_selected;
            if large {
                assert_eq!((rep.bored, rep.drilled), (n, 0), "{file}");
            } else {
                assert_eq!((rep.drilled, rep.bored), (n, 0), "{file}");
            }
            assert_eq!(rep.skipped, 0);
            assert!(run.verification.ok());
            assert!(rep.max_center_error_mm <= 0.01 && rep.max_diameter_error_mm <= 0.01);
            assert_eq!(rep.holes.len(), n);
            for h in &rep.holes {
                let e = h.center_error_mm.expect("checked");
                let c = h.cut_diameter_mm.expect("checked");
                assert!(
                    e <= 0.01 && (c - h.diameter_mm).abs() <= 0.01,
                    "{file}: {h:?}"
                );
            }
            cut.extend(run.result.holes.iter().map(|p| p.hole));
            // The time reported is the written program's, read back as estimate reads it.
            let t = millpath::job::program_time(&run.gcode, program.dialect, file, &run.machine)
                .unwrap();
            assert!(
                (t - rep.cycle_time_s).abs() <= 1e-9 * t,
                "{file}: {t} vs {rep:?}"
            );
            let text = String::from_utf8(run.gcode).unwrap();
            rs274_common::rs274(&text).unwrap_or_else(|e| panic!("{file}: rs274: {e}"));
        }
        // Every circle cut exactly once.
        assert_eq!(cut.len(), found.len(), "{file}");
        for h in &found {
            let times = cut
                .iter()
                .filter(|c| {
                    c.center.distance(h.center) < 1e-9 && (c.diameter - h.diameter).abs() < 1e-12
                })
                .count();
            assert_eq!(times, 1, "{file}: {h:?}");
        }
    }
}

#[test]
fn a_drawing_without_circles_and_an_empty_selection_are_refused_by_flag() {
    let s = DrillSettings::default();
    let e = drill::find(&real("lc_t-part.dxf"), &s, &mut |_| {}).unwrap_err();
    assert_eq!(e.exit_code(), 2);
    assert!(e.to_string().contains("circle"), "{e}");
    let s = DrillSettings {
        min_diameter: Some(50.0),
        ..DrillSettings::default()
    };
    let e = drill::run(
        &real("wro_Plate_2.DXF"),
        &s,
        &ProgramSettings::default(),
        &mut |_| {},
    )
    .unwrap_err();
    assert!(e.to_string().contains("--min-diameter"), "{e}");
    assert!(e.to_string().contains("2.700, 3.000"), "{e}");
    // The layer flag is the readers': a layer the drawing lacks leaves nothing closed.
    let s = DrillSettings {
        import: millpath::io::ImportSettings {
            layer: Some("no such layer".into()),
            ..Default::default()
        },
        ..DrillSettings::default()
    };
    let e = drill::find(&real("wro_Plate_2.DXF"), &s, &mut |_| {}).unwrap_err();
    assert_eq!(e.exit_code(), 2, "{e}");
}
