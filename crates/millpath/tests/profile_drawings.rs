//! `millpath profile` on real drawings (`../shared/real-inputs/files/`): every written program
//! read back and checked against the drawn outlines with `cavalier_contours`' exact closest
//! point (not the profile's own check, nor its offset): the finishing loops within
//! `[d, d + T]` of their outline after rounding, no feed move below the top nearer a wall than
//! the tool radius, arcs written where the drawing has arcs, tabs away from corners with the
//! tool lifted over them; LinuxCNC's `rs274` reads every program.

mod rs274_common;

use millpath::gcode::{self, ReaderOptions};
use millpath::io::ImportSettings;
use millpath::job::ProgramSettings;
use millpath::job::profile::{self, ProfileRun, ProfileSettings, ProfileSource};
use millpath::stock::{BridgeOptions, FieldOptions, HeightField, Hold, held_by};
use millpath::strategy::profile::ProfileSide;
use millpath::toolpath::{MoveKind, Tool, Toolpath};
use rs274_common::rs274;
use std::path::PathBuf;

fn drawing(name: &str) -> String {
    let d = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/real-inputs/files");
    assert!(d.is_dir(), "{} is missing", d.display());
    d.join(name).to_string_lossy().into_owned()
}

fn run(name: &str, settings: &ProfileSettings) -> Result<ProfileRun, millpath::Error> {
    let path = drawing(name);
    let (loops, _) = millpath::job::load_outline(&path, &ImportSettings::default())?;
    profile::run(
        ProfileSource::Drawing {
            loops: &loops,
            name: &path,
        },
        settings,
        &ProgramSettings::default(),
    )
}

/// Points every `step` mm along move `k` of `tp` (both ends included).
fn samples(tp: &Toolpath, k: usize, step: f64) -> Vec<millpath::Point3> {
    let from = if k == 0 { tp.start } else { tp.moves[k - 1].to };
    let m = &tp.moves[k];
    let len = m.length_from(from);
    let n = ((len / step).ceil() as usize).max(1);
    (0..=n)
        .map(|j| m.point_at(from, len * j as f64 / n as f64))
        .collect()
}

/// The checks of the module docs on a run; returns the read-back toolpath.
fn check_written(job: &ProfileRun) -> Toolpath {
    rs274(&job.gcode).unwrap_or_else(|e| panic!("rs274: {e}"));
    let (back, _) = gcode::read_str(&job.gcode, ReaderOptions::default()).unwrap();
    assert_eq!(back.moves.len(), job.result.toolpath.moves.len());
    let opts = &job.options;
    let r = job.result.toolpath.tool.radius();
    let t = opts.tolerance;
    assert!(!job.result.cuts.is_empty());
    // The finishing loops in the band, after rounding.
    for cut in &job.result.cuts {
        let o = &job.targets[cut.target].outline;
        let (lo_want, hi_want) = match cut.side {
            ProfileSide::On => (0.0, t),
            _ => (r, r + t),
        };
        let (mut lo, mut hi) = (f64::INFINITY, 0.0_f64);
        for range in &cut.finish_moves {
            for k in range.clone() {
                if !back.moves[k].is_feed() {
                    continue;
                }
                for q in samples(&back, k, 0.02) {
                    let d = o.distance_to(q.xy());
                    lo = lo.min(d);
                    hi = hi.max(d);
                }
            }
        }
        assert!(
            lo >= lo_want - 1e-9 && hi <= hi_want + 1e-9,
            "outline {}: finishing path {lo}..{hi} mm from it, band {lo_want}..{hi_want}",
            cut.target + 1
        );
    }
    // No gouge: every feed move below the top keeps the tool radius from every wall.
    let walls: Vec<_> = job
        .targets
        .iter()
        .filter(|x| x.side != ProfileSide::On)
        .collect();
    for k in 0..back.moves.len() {
        let from = if k == 0 {
            back.start
        } else {
            back.moves[k - 1].to
        };
        if !back.moves[k].is_feed() || from.z.min(back.moves[k].to.z) >= opts.top_z {
            continue;
        }
        for q in samples(&back, k, 0.1) {
            if q.z >= opts.top_z {
                continue;
            }
            for w in &walls {
                let d = w.outline.distance_to(q.xy());
                assert!(d >= r - 1e-9, "move {k}: {d} mm from a wall at {q:?}");
            }
        }
    }
    // Arcs where the drawing has arcs.
    let drawn_arcs = job
        .targets
        .iter()
        .any(|x| x.outline.vertices().any(|(_, b)| b != 0.0));
    let written_arcs = back
        .moves
        .iter()
        .filter(|m| matches!(m.kind, MoveKind::Arc { .. }))
        .count();
    if drawn_arcs {
        assert!(written_arcs > 0, "the drawing has arcs, the program none");
    }
    // The stock simulation's verdict (tabs asked for): each piece held by exactly its tabs,
    // free where none fit.
    for row in &job.report.outlines {
        let Some(v) = &row.tabs else { continue };
        if v.hold.is_empty() {
            continue;
        }
        let n = job
            .result
            .tabs
            .iter()
            .filter(|t| t.target + 1 == row.index)
            .count();
        let want = match n {
            0 => "falls free".to_owned(),
            1 => "held by 1 bridge".to_owned(),
            n => format!("held by {n} bridges"),
        };
        assert_eq!(v.hold, want, "outline {}", row.index);
        assert_eq!(v.bridges - v.loose, n);
        // A holding bridge is never narrower than the tab asked for; a square tab is that
        // wide at the slot's middle, a ramped one widens by its ramps (`TAB_RAMP_RUN` mm
        // along the path per mm of height) to the floor. The neck is measured along the
        // drawn outline: inside an arc of radius R the slot's middle (R − r) is shorter by
        // (R − r) / R, so the bridge measures up to R / (R − r) times its width there.
        let (w, h) = (job.options.tabs.width, job.options.tabs.height);
        let target = &job.targets[row.index - 1];
        let stretch = if target.side == ProfileSide::Inside {
            let pts: Vec<(millpath::geom::Point, f64)> = target.outline.vertices().collect();
            (0..pts.len())
                .filter(|&i| pts[i].1 != 0.0)
                .map(|i| {
                    let (a, b) = (pts[i].0, pts[(i + 1) % pts.len()].0);
                    let bulge = pts[i].1.abs();
                    let radius = a.distance(b) * (1.0 + bulge * bulge) / (4.0 * bulge);
                    radius / (radius - r)
                })
                .fold(1.0, f64::max)
        } else {
            1.0
        };
        let widest = stretch
            * match job.options.tabs.shape {
                millpath::strategy::profile::TabShape::Square => w,
                millpath::strategy::profile::TabShape::Ramped => {
                    w + 2.0 * millpath::strategy::profile::TAB_RAMP_RUN * h + 1.0
                }
            };
        for neck in v.necks_mm.iter().filter(|n| **n > 0.0) {
            assert!(
                *neck >= w - 4.0 * v.cell_mm && *neck <= widest + 4.0 * v.cell_mm,
                "neck {neck} for a tab {w} wide, {h} high (cell {})",
                v.cell_mm
            );
        }
    }
    // Tabs: away from corners, the tool lifted over each.
    for tab in &job.result.tabs {
        let o = &job.targets[tab.target].outline;
        let h = 0.5 * tab.width;
        for (v, _) in o.vertices() {
            assert!(
                v.distance(tab.at) >= h + 0.5 * r,
                "tab at {:?} is {} mm from the corner {v:?}",
                tab.at,
                v.distance(tab.at)
            );
        }
        let mut over = false;
        for k in 0..back.moves.len() {
            if !back.moves[k].is_feed() {
                continue;
            }
            for q in samples(&back, k, 0.05) {
                let dist = q.xy().distance(tab.at);
                if q.z < tab.top_z - 1e-6 {
                    assert!(
                        dist >= 0.9 * (h + r),
                        "move {k} at z {} is {dist} mm from the tab at {:?}",
                        q.z,
                        tab.at
                    );
                } else if (q.z - tab.top_z).abs() <= 1e-6 && dist <= r + t + 0.01 {
                    over = true;
                }
            }
        }
        assert!(over, "the tool never passes over the tab at {:?}", tab.at);
    }
    back
}

#[test]
fn t_part_with_auto_tabs_helix_entry_and_a_finishing_pass() {
    let s = ProfileSettings {
        tabs: "auto".into(),
        stock_to_leave: Some(0.3),
        entry: "helix".into(),
        ..ProfileSettings::default()
    };
    let job = run("lc_t-part.dxf", &s).unwrap();
    assert_eq!(job.result.cuts.len(), 3);
    // Perimeters 200, 200 and 180 mm: two tabs each.
    assert_eq!(job.result.tabs.len(), 6);
    assert!(job.report.notes.is_empty(), "{:?}", job.report.notes);
    let back = check_written(&job);
    // Helices: arcs that descend.
    let helical = back
        .moves
        .iter()
        .zip(std::iter::once(back.start).chain(back.moves.iter().map(|m| m.to)))
        .filter(|(m, from)| matches!(m.kind, MoveKind::Arc { .. }) && m.to.z < from.z - 1e-9)
        .count();
    assert!(helical > 0);
}

#[test]
fn ma_part_conventional_with_ramped_tabs() {
    let s = ProfileSettings {
        tabs: "3".into(),
        tab_shape: "ramped".into(),
        conventional: true,
        ..ProfileSettings::default()
    };
    let job = run("ma_Part.dxf", &s).unwrap();
    assert!(!job.result.tabs.is_empty());
    check_written(&job);
}

/// A plate whose edges pass holes smaller than the tool (left for a drill, never cut): they
/// keep no tab off the plate's outline. `wro_Plate_2.DXF` has 3 mm holes 1 mm from its sides
/// and its top; before, they kept every tab off the plate and it fell free. Its windows, 12 mm
/// and 8 mm inside its edges, still keep the tabs off all but one stretch (the neighbour rule
/// of `generate`). The program read back, cut into a height field, holds the plate by as many
/// bridges as tabs were placed, at least one.
#[test]
fn holes_left_for_a_drill_keep_no_tab_off_the_plate() {
    let s = ProfileSettings {
        tabs: "4".into(),
        ..ProfileSettings::default()
    };
    let job = run("wro_Plate_2.DXF", &s).unwrap();
    let (mut back, _) = gcode::read_str(&job.gcode, ReaderOptions::default()).unwrap();
    let outer = job
        .targets
        .iter()
        .position(|t| t.side == ProfileSide::Outside)
        .unwrap();
    let placed = job.result.tabs.iter().filter(|t| t.target == outer).count();
    assert!(placed >= 1, "{:?}", job.report.notes);
    back.tool = Tool::flat(6.0).unwrap();
    let o = &job.targets[outer].outline;
    let mut field = HeightField::new(
        o.bounds().inflate(30.0),
        -6.0,
        0.0,
        &FieldOptions::default().with_tool_diameter(6.0),
    )
    .unwrap();
    field.cut(&back);
    let v = held_by(&field, o, -6.0, 3.0, &BridgeOptions::default()).unwrap();
    assert_eq!(v.hold(), Hold::Held { bridges: placed }, "{v}");
}

#[test]
fn gear_cutout_keeps_its_arcs_and_latch_splines_their_lines() {
    for name in ["pb_gear_cutout.dxf", "pb_latch_test.dxf"] {
        let job = run(name, &ProfileSettings::default()).unwrap();
        check_written(&job);
    }
}

#[test]
fn on_the_line_and_forced_inside() {
    for side in ["on", "inside"] {
        let s = ProfileSettings {
            side: side.into(),
            tool_diameter: Some(3.0),
            ..ProfileSettings::default()
        };
        let job = run("ma_support.dxf", &s).unwrap();
        check_written(&job);
    }
}

#[test]
fn outlines_closer_than_the_tool_are_refused_naming_the_flag() {
    let e = run("pb_box_shell.dxf", &ProfileSettings::default()).unwrap_err();
    assert_eq!(e.exit_code(), 2, "{e}");
    assert!(e.to_string().contains("--tool-diameter"), "{e}");
    for (field, bad) in [("tabs", "x"), ("entry", "plunge"), ("side", "left")] {
        let mut s = ProfileSettings::default();
        match field {
            "tabs" => s.tabs = bad.into(),
            "entry" => s.entry = bad.into(),
            _ => s.side = bad.into(),
        }
        let e = run("lc_t-part.dxf", &s).unwrap_err();
        assert_eq!(e.exit_code(), 2, "{e}");
        assert!(e.to_string().contains(&format!("--{field}")), "{e}");
    }
}

/// The tool's path within the tolerance of the exact offset (dense check of the library
/// against an independent one): the report's band equals the read-back's to the rounding.
#[test]
fn report_band_agrees_with_the_read_back() {
    let job = run("lc_t-part.dxf", &ProfileSettings::default()).unwrap();
    for row in &job.report.outlines {
        assert!(row.band_min_mm >= row.offset_mm);
        assert!(row.band_max_mm <= row.offset_mm + job.report.tolerance_mm);
    }
}
