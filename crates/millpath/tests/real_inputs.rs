//! Every real drawing in `../shared/real-inputs/files/` (41 DXF and SVG files from a dozen CAD
//! programs, sources in `SOURCES.md` there) through the DXF and SVG readers: the closed
//! outlines each holds and their extents in mm, checked against numbers read by hand from each
//! file's header (`$EXTMIN`/`$EXTMAX`, `width`/`height`/`viewBox`) or its raw coordinates
//! (the comment on each row says which), and the files with nothing closed refused with a
//! message that says what they hold. No file may panic.

use millpath::io::{Drawing, ReadOptions, dxf, svg};
use std::path::PathBuf;

fn dir() -> PathBuf {
    let d = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/real-inputs/files");
    assert!(
        d.is_dir(),
        "{} is missing: the real-input drawings live in ../shared beside the clone",
        d.display()
    );
    d
}

fn read(name: &str, opts: &ReadOptions) -> Result<Drawing, millpath::InputError> {
    let bytes = std::fs::read(dir().join(name)).expect("readable file");
    if name.to_ascii_lowercase().ends_with(".svg") {
        svg::read_loops(&String::from_utf8_lossy(&bytes), name, opts)
    } else {
        dxf::read_loops(&bytes, name, opts)
    }
}

/// What a file must give.
enum Want {
    /// `n` closed outlines whose extents are `[xmin, ymin, xmax, ymax]` mm within 1e-3 mm.
    Closed(usize, [f64; 4]),
    /// Nothing closed: refused, the message naming these.
    Refused(&'static [&'static str]),
}
use Want::*;

const IN: f64 = 25.4;

#[rustfmt::skip]
fn table() -> Vec<(&'static str, Want)> {
    vec![
        // $INSUNITS = 6 (m); $EXTMIN x 119.508…, y 127.175… (the arcs' extremes; the TEXT
        // reaches higher); ×1000.
        ("ez_1_polylines.dxf", Closed(8, [119508.0906, 127175.4519, 343477.6304, 255738.9492])),
        // No units; raw LINE/ARC ends 0…3.5 × 0…1.5 (the 3.625 × 1.625 of $EXTMAX is an open
        // chain).
        ("ez_AC1003_LINE_Example.dxf", Closed(1, [0.0, 0.0, 3.5, 1.5])),
        // One INSERT of a TEXT block and two LINEs.
        ("ez_ASCII_R12.dxf", Refused(&["1 INSERT", "2 LINE", "1 TEXT", "open chain"])),
        // Every POLYLINE has a tilted extrusion (210 = 0.0207, 0.3240, 0.9458): not a plan view.
        ("ez_POLI-ALL210_12.DXF", Refused(&["30 POLYLINE (not in the XY plane)", "3DFACE"])),
        // Binary R2000 holding one TEXT.
        ("ez_bin_dxf_r2000.dxf", Refused(&["1 TEXT", "in m ($INSUNITS = 6)"])),
        // A closed 3D POLYLINE projected on XY; raw vertices x 0.1022…1.2508.
        ("ez_cc_dxflib.dxf", Closed(1, [0.1022, -1.5795, 1.2508, -0.3619])),
        // HATCH edges (lines, clockwise arcs), $INSUNITS = 6: raw x −292.6468…−236.6468,
        // y 536.6832…606.6832, ×1000.
        ("ez_clockwise_arcs_hatch.dxf", Closed(2, [-292646.755, 536683.187, -236646.753, 606683.187])),
        // $EXTMIN (−246, −1015), $EXTMAX (770, −183.6618), $INSUNITS = 4.
        ("ez_forms.dxf", Closed(40, [-246.0, -1015.0, 770.0, -183.6618])),
        // Nested INSERTs, $INSUNITS = 6: the LWPOLYLINEs' raw x −1.8647…15.7034 (m).
        ("ez_insert_bricscad_level_1.dxf", Closed(6, [-1864.662, 7044.443, 15703.370, 18456.153])),
        // $EXTMIN (−0.1750, −0.0108), $EXTMAX (1.4250, 2.5892).
        ("ez_small_r13.dxf", Closed(4, [-0.1750, -0.0108, 1.4250, 2.5892])),
        // Headerless LINE gears: raw ±17.8254 and ±28.0113.
        ("kg_teeth-12.dxf", Closed(2, [-17.8254, -17.8254, 17.8254, 17.8254])),
        ("kg_teeth-20.dxf", Closed(2, [-28.0113, -28.0113, 28.0113, 28.0113])),
        // dxflib (header variables after ENDSEC, $INSUNITS = 0): the screw head's LINEs
        // x −0.7…0, y ±1.
        ("lc_screw.dxf", Closed(1, [-0.7, -1.0, 0.0, 1.0])),
        // The T part's outline LINEs at x = ±100, y = −70 and 50 (the ±120 LINEs are centre
        // lines).
        ("lc_t-part.dxf", Closed(3, [-100.0, -70.0, 100.0, 50.0])),
        // 87 ARCs drawing Tux, no loop closes within 0.01 mm (one misses by 0.1 mm).
        ("lc_tux.dxf", Refused(&["87 ARC", "gap 0.1000 mm", "--join-tolerance 0.1010"])),
        // $MEASUREMENT = 0 (inches), no $INSUNITS: raw ±8.8583 × ±3.9370 in.
        ("ma_Part.dxf", Closed(10, [-8.858_268 * IN, -3.937_008 * IN, 8.858_268 * IN, 3.937_008 * IN])),
        // $MEASUREMENT = 1: raw x −130…100, y 0.47…45.47; the 450 × 35 mm slot.
        ("ma_hautparleur.dxf", Closed(9, [-130.0, 0.47, 100.0, 45.47])),
        ("ma_support.dxf", Closed(1, [-57.4189, -43.2995, 392.5811, -8.2995])),
        // Headerless (the gear template generator writes inches, SOURCES.md): read as mm,
        // raw 0.0011…3.5008 × 0.0064…3.4955; `--drawing-units in` is the user's to give.
        ("pb_4_spoke_gear.dxf", Closed(6, [0.0011, 0.0064, 3.5008, 3.4955])),
        // Inkscape R14 exports, $MEASUREMENT = 1: raw LINE/SPLINE coordinates.
        ("pb_box_shell.dxf", Closed(17, [10.1, 10.1, 292.68, 310.0885])),
        ("pb_gear_cutout.dxf", Closed(2, [51.4477, 31.7627, 151.7523, 132.0670])),
        ("pb_key.dxf", Closed(6, [5.4287, 1.2283, 76.0107, 55.4150])),
        ("pb_latch_test.dxf", Closed(3, [-83.4099, -31.4148, 286.6099, 94.9148])),
        ("pb_left_drawer.dxf", Closed(5, [6.0127, 6.0127, 164.8339, 94.9127])),
        // Says $MEASUREMENT = 1 but is in inches (its SVG is 22.83564 in wide, see
        // `svg_and_dxf_exports_agree`): raw 0.0059…22.8298 × 0.0059…5.0059.
        ("pb_screw_plate.dxf", Closed(15, [0.0059, 0.0059, 22.8298, 5.0059])),
        // SOLIDWORKS, $INSUNITS = 4: $EXTMIN/$EXTMAX.
        ("wro_Braking_Arm.DXF", Closed(3, [-5.9806, -3.0, 3.0, 30.9104])),
        ("wro_Plate_2.DXF", Closed(16, [-48.0, -80.0, 48.0, 12.0])),
        ("wro_Plate_3.DXF", Closed(29, [-48.0, -96.0, 48.0, 12.0])),
        // width 6.9804072in, viewBox width 628.23662: 0.282222 mm per user unit (Inkscape
        // 0.91's 90 dpi); two gears side by side within the 177.3 × 88.9 mm page. Each gear's
        // lettering follows a circle (a textPath's guide, skipped): 6 outlines a gear.
        ("pb_4_spoke_gear.svg", Closed(12, [0.0136, 0.0128, 177.2888, 88.8873])),
        // width 380.17383mm = viewBox: 1 mm per user unit; the same 370.0198 × 126.3296 mm
        // as its DXF export.
        ("pb_latch_test.svg", Closed(3, [5.0642, 5.0899, 375.0839, 131.4192])),
        // width 202.61926mm over viewBox 717.94225 (0.282222): exactly its DXF export.
        ("pb_left_drawer.svg", Closed(5, [6.0127, 6.0127, 164.8339, 94.9127])),
        // width 22.83564in = 580.025 mm = viewBox: 1 mm per user unit; its DXF × 25.4.
        ("pb_screw_plate.svg", Closed(15, [0.1494, 0.1494, 579.8759, 127.1494])),
        // The arrow's path by hand: x 0.7070…26.2930, y 1017.1455…1051.9042 user units,
        // translate(0.9025, −1015.7925), × 0.32005584in/28.805027 = 0.282222 mm, y flipped
        // about the 0.41022143in = 10.4196 mm page: (0.4542, 0.2281)…(7.6752, 10.0378).
        ("pb_white_arrow.svg", Closed(1, [0.4542, 0.2281, 7.6752, 10.0378])),
        ("s2g_circular_interpolation.svg", Closed(1, [4.4838, 1.7452, 7.4830, 3.7456])),
        ("s2g_shapes.svg", Closed(6, [8.0093, 78.2732, 143.9221, 189.9186])),
        // viewBox only: pixels; two self-intersecting loops skipped.
        ("s2g_smooth_curves.svg", Closed(31, [10.6389, 1.2195, 63.7475, 71.4846])),
        // 1920pt × 1080pt = viewBox: 0.352778 mm per user unit; the rect is the page.
        ("s2g_snowflake.svg", Closed(1, [0.0, 0.0, 677.3333, 381.0])),
        // 10mm = viewBox 10: the square M 1,1 H 9 V 9 H 1 Z.
        ("s2g_square_transformed_nested.svg", Closed(2, [1.0, 1.0, 9.0, 9.0])),
        // viewBox −10 −10 10 10: the square −9…−1 lands on 1…9.
        ("s2g_square_viewport.svg", Closed(2, [1.0, 1.0, 9.0, 9.0])),
        // A symbol holding one open path "M 0,0 H 2", used at (1, 1).
        ("s2g_use_symbol.svg", Refused(&["1 use", "open at (1.0000, 9.0000) and (3.0000, 9.0000)"])),
        // width 117.73 (px) over viewBox 117.73047: 0.264576 mm per user unit.
        ("s2g_vanderbilt_logo.svg", Closed(3, [0.2773, 0.2778, 30.8966, 30.2048])),
    ]
}

#[test]
fn every_real_drawing_reads_at_its_scale_or_is_refused_clearly() {
    let table = table();
    let mut files: Vec<String> = std::fs::read_dir(dir())
        .expect("folder")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .filter(|n| !n.ends_with(".md"))
        .collect();
    files.sort();
    let listed: Vec<&str> = table.iter().map(|t| t.0).collect();
    for f in &files {
        assert!(listed.contains(&f.as_str()), "{f} is not in the table");
    }
    assert_eq!(files.len(), table.len(), "files {files:?}");
    let opts = ReadOptions::default();
    for (name, want) in table {
        let got = std::panic::catch_unwind(|| read(name, &opts));
        let d = match got {
            Ok(Ok(d)) => d,
            Ok(Err(e)) => panic!("{name}: {e}"),
            Err(_) => panic!("{name}: panicked"),
        };
        match want {
            Closed(n, [x0, y0, x1, y1]) => {
                assert_eq!(d.outlines.len(), n, "{name}: {}", d.summary());
                let e = d.extents();
                let got = [e.min.x, e.min.y, e.max.x, e.max.y];
                for (g, w) in got.iter().zip([x0, y0, x1, y1]) {
                    assert!(
                        (g - w).abs() <= 1e-3,
                        "{name}: extents {got:?}, want {:?}",
                        [x0, y0, x1, y1]
                    );
                }
            }
            Refused(words) => {
                assert!(d.outlines.is_empty(), "{name}: {}", d.summary());
                let e = d
                    .into_loops(name, opts.join_tolerance)
                    .expect_err("refused")
                    .to_string();
                assert!(e.contains(name), "{e}");
                for w in words {
                    assert!(e.contains(w), "{name}: {w:?} not in {e}");
                }
            }
        }
    }
}

/// Inkscape exported the same drawings as SVG and DXF: the readers agree, the SVG through
/// its width/height/viewBox and layer transforms, the DXF through its coordinates.
#[test]
fn svg_and_dxf_exports_agree() {
    let o = ReadOptions::default();
    let size = |d: &Drawing| (d.extents().width(), d.extents().height());
    // The same place and size.
    let s = read("pb_left_drawer.svg", &o).unwrap().extents();
    let x = read("pb_left_drawer.dxf", &o).unwrap().extents();
    assert!(
        s.min.distance(x.min) < 1e-3 && s.max.distance(x.max) < 1e-3,
        "{s:?} {x:?}"
    );
    // The same size (the DXF export moved the drawing): the scale(0.26458333) layer.
    let (sw, sh) = size(&read("pb_latch_test.svg", &o).unwrap());
    let (xw, xh) = size(&read("pb_latch_test.dxf", &o).unwrap());
    assert!(
        (sw - xw).abs() < 1e-3 && (sh - xh).abs() < 1e-3,
        "{sw} {sh} / {xw} {xh}"
    );
    // The DXF in inches although it says metric: --drawing-units in makes them agree.
    let inch = ReadOptions::default().with_mm_per_unit(Some(IN));
    let d = read("pb_screw_plate.dxf", &inch).unwrap();
    assert!(d.units.contains("given"), "{}", d.units);
    let (xw, xh) = size(&d);
    let (sw, sh) = size(&read("pb_screw_plate.svg", &o).unwrap());
    assert!(
        (sw - xw).abs() < 2e-3 && (sh - xh).abs() < 2e-3,
        "{sw} {sh} / {xw} {xh}"
    );
}

/// The nested transforms of `s2g_square_transformed_nested.svg` (translate(5,5) ·
/// rotate(−90) · translate(−5,−5)) move the circle from (7.5, 7.5) to (7.5, 2.5) in SVG
/// coordinates, (7.5, 7.5) in mm once y is flipped about the 10 mm page: the pocket's island
/// is there, not where the untransformed path data puts it.
#[test]
fn nested_transforms_place_the_island() {
    let l = svg::parse_with(
        &std::fs::read_to_string(dir().join("s2g_square_transformed_nested.svg")).unwrap(),
        "nested",
        &ReadOptions::default(),
    )
    .unwrap();
    assert_eq!(l.islands.len(), 1);
    let c = l.islands[0].bounds().center();
    assert!(c.distance(millpath::Point::new(7.5, 7.5)) < 1e-9, "{c:?}");
    assert!((l.islands[0].signed_area().abs() - std::f64::consts::PI * 0.25).abs() < 1e-9);
}

/// `--layer`: a DXF layer (names compared ignoring case) or an SVG group's label or id; an
/// unknown name is refused with the layers the file has.
#[test]
fn layers_select_outlines() {
    let on = |l: &str| ReadOptions::default().with_layer(Some(l.to_owned()));
    let all = read("lc_t-part.dxf", &ReadOptions::default()).unwrap();
    let aux = read("lc_t-part.dxf", &on("AUXILIARY")).unwrap();
    let zero = read("lc_t-part.dxf", &on("0")).unwrap();
    assert!(
        aux.summary().contains("on another layer"),
        "{}",
        aux.summary()
    );
    // The outlines are on layer 0, the construction lines on `auxiliary`.
    assert_eq!(
        (aux.outlines.len(), zero.outlines.len()),
        (0, all.outlines.len())
    );
    assert!(zero.open.len() < all.open.len());
    let e = read("lc_t-part.dxf", &on("nope")).unwrap_err().to_string();
    assert!(
        e.contains("nope") && e.contains("auxiliary") && e.contains("_stretch_hu_50"),
        "{e}"
    );
    let by_label = read("s2g_square_transformed_nested.svg", &on("Layer 1")).unwrap();
    let by_id = read("s2g_square_transformed_nested.svg", &on("layer1")).unwrap();
    assert_eq!((by_label.outlines.len(), by_id.outlines.len()), (2, 2));
    let e = read("s2g_square_transformed_nested.svg", &on("Layer 2"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("Layer 1") && e.contains("layer1"), "{e}");
    // R12's \U+ escapes decoded: the Greek layer name reads as written.
    let r12 = read("ez_ASCII_R12.dxf", &ReadOptions::default()).unwrap();
    assert!(
        r12.layers.iter().any(|l| l.starts_with("ΛΑΓΕΡ")),
        "{:?}",
        r12.layers
    );
}

/// The circle a gear's lettering follows (an SVG `textPath`'s guide) is no outline: with it,
/// each gear of `pb_4_spoke_gear.svg` had a 85 mm circle crossing its teeth 52 times, and the
/// drawing was refused as crossing outlines; its DXF export has no such circle.
#[test]
fn text_path_guides_are_skipped_with_a_note() {
    let d = read("pb_4_spoke_gear.svg", &ReadOptions::default()).expect("reads");
    let s = d.summary();
    assert!(
        s.contains("skipped 2 circle (the path a text follows (textPath))"),
        "{s}"
    );
    let loops = d.into_loops("pb_4_spoke_gear.svg", 0.01).expect("nests");
    assert_eq!(loops.pockets().len(), 2);
    assert!(loops.notes.is_empty(), "{:?}", loops.notes);
}
