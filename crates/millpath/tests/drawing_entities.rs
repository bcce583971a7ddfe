//! The DXF and SVG readers on small drawings whose outlines are known exactly: each
//! entity kind, block and transform checked by the outline's area and extents, computed
//! here by hand (the comment on each case derives them), never by the reader's own code.

use millpath::io::{ReadOptions, dxf, svg};
use std::f64::consts::PI;

/// A DXF file from `(code, value)` pairs: a header with `header`, then the blocks and entities.
fn dxf_file(header: &[(i32, &str)], blocks: &[(i32, &str)], entities: &[(i32, &str)]) -> Vec<u8> {
    let mut s = String::new();
    let mut put = |pairs: &[(i32, &str)]| {
        for (c, v) in pairs {
            s.push_str(&format!("{c}\n{v}\n"));
        }
    };
    put(&[(0, "SECTION"), (2, "HEADER")]);
    put(header);
    put(&[(0, "ENDSEC"), (0, "SECTION"), (2, "BLOCKS")]);
    put(blocks);
    put(&[(0, "ENDSEC"), (0, "SECTION"), (2, "ENTITIES")]);
    put(entities);
    put(&[(0, "ENDSEC"), (0, "EOF")]);
    s.into_bytes()
}

fn area_and_extents(d: &millpath::io::Drawing) -> (f64, [f64; 4]) {
    assert_eq!(d.outlines.len(), 1, "{}", d.summary());
    let e = d.extents();
    (
        d.outlines[0].signed_area().abs(),
        [e.min.x, e.min.y, e.max.x, e.max.y],
    )
}

fn close(a: [f64; 4], b: [f64; 4], tol: f64) -> bool {
    a.iter().zip(b).all(|(x, y)| (x - y).abs() <= tol)
}

/// INNER (base (1, 0)) holds the square [0, 2]²; OUTER inserts INNER at (10, 0), scale 2,
/// rotation 90°; the drawing inserts OUTER at (100, 50), scale 0.5, in cm ($INSUNITS = 5).
/// By hand: [0,2]² − (1,0) = [−1,1]×[0,2]; ×2: [−2,2]×[0,4]; rotated 90° ((x, y) → (−y, x)):
/// [−4,0]×[−2,2]; + (10, 0): [6,10]×[−2,2]; ×0.5 + (100, 50): [103,105]×[49,51] cm, i.e.
/// [1030,1050]×[490,510] mm, area 400 mm².
#[test]
fn nested_inserts_scale_rotate_and_move_from_the_base_point() {
    let blocks = [
        (0, "BLOCK"),
        (2, "INNER"),
        (10, "1"),
        (20, "0"),
        (0, "LWPOLYLINE"),
        (8, "0"),
        (90, "4"),
        (70, "1"),
        (10, "0"),
        (20, "0"),
        (10, "2"),
        (20, "0"),
        (10, "2"),
        (20, "2"),
        (10, "0"),
        (20, "2"),
        (0, "ENDBLK"),
        (0, "BLOCK"),
        (2, "OUTER"),
        (10, "0"),
        (20, "0"),
        (0, "INSERT"),
        (8, "0"),
        (2, "INNER"),
        (10, "10"),
        (20, "0"),
        (41, "2"),
        (42, "2"),
        (50, "90"),
        (0, "ENDBLK"),
    ];
    let ents = [
        (0, "INSERT"),
        (8, "PART"),
        (2, "OUTER"),
        (10, "100"),
        (20, "50"),
        (41, "0.5"),
        (42, "0.5"),
    ];
    let d = dxf::read_loops(
        &dxf_file(&[(9, "$INSUNITS"), (70, "5")], &blocks, &ents),
        "insert.dxf",
        &ReadOptions::default(),
    )
    .unwrap();
    let (area, ext) = area_and_extents(&d);
    assert!((area - 400.0).abs() < 1e-6, "{area}");
    assert!(close(ext, [1030.0, 490.0, 1050.0, 510.0], 1e-9), "{ext:?}");
    assert!(
        d.units.contains("cm") && d.summary().contains("2 INSERT"),
        "{}",
        d.summary()
    );
    // The block's layer-0 square takes the INSERT's layer.
    let part = ReadOptions::default().with_layer(Some("part".into()));
    let bytes = dxf_file(&[], &blocks, &ents);
    assert_eq!(
        dxf::read_loops(&bytes, "i.dxf", &part)
            .unwrap()
            .outlines
            .len(),
        1
    );
}

/// A closed POLYLINE/VERTEX and a HATCH polyline path, both the square [0,10]² whose right
/// side is a half circle of bulge 1 bulging out to x = 15: area 100 + π·5²/2.
#[test]
fn polyline_vertices_and_hatch_paths_keep_their_bulges() {
    let want = 100.0 + PI * 12.5;
    let polyline = [
        (0, "POLYLINE"),
        (8, "0"),
        (66, "1"),
        (70, "1"),
        (0, "VERTEX"),
        (10, "0"),
        (20, "0"),
        (0, "VERTEX"),
        (10, "10"),
        (20, "0"),
        (42, "1"),
        (0, "VERTEX"),
        (10, "10"),
        (20, "10"),
        (0, "VERTEX"),
        (10, "0"),
        (20, "10"),
        (0, "SEQEND"),
    ];
    let hatch = [
        (0, "HATCH"),
        (8, "0"),
        (100, "AcDbHatch"),
        (10, "0"),
        (20, "0"),
        (2, "SOLID"),
        (70, "1"),
        (71, "0"),
        (91, "1"),
        (92, "2"),
        (72, "1"),
        (73, "1"),
        (93, "4"),
        (10, "0"),
        (20, "0"),
        (42, "0"),
        (10, "10"),
        (20, "0"),
        (42, "1"),
        (10, "10"),
        (20, "10"),
        (42, "0"),
        (10, "0"),
        (20, "10"),
        (42, "0"),
        (97, "0"),
        (75, "0"),
        (76, "1"),
        (98, "0"),
    ];
    for ents in [&polyline[..], &hatch[..]] {
        let d =
            dxf::read_loops(&dxf_file(&[], &[], ents), "p.dxf", &ReadOptions::default()).unwrap();
        let (area, ext) = area_and_extents(&d);
        assert!(
            (area - want).abs() < 1e-9,
            "{area} vs {want}: {}",
            d.summary()
        );
        assert!(close(ext, [0.0, 0.0, 15.0, 10.0], 1e-9), "{ext:?}");
    }
}

/// The upper half of the ellipse with semi-axes 10 and 5 (ELLIPSE, parameters 0…π) closed
/// by a LINE: area π·10·5/2, the flattening inside it by at most tolerance × arc length, its
/// extents the ellipse's within the tolerance.
#[test]
fn partial_ellipse_flattened_within_tolerance() {
    let ents = [
        (0, "ELLIPSE"),
        (8, "0"),
        (10, "0"),
        (20, "0"),
        (11, "10"),
        (21, "0"),
        (40, "0.5"),
        (41, "0"),
        (42, "3.141592653589793"),
        (0, "LINE"),
        (8, "0"),
        (10, "-10"),
        (20, "0"),
        (11, "10"),
        (21, "0"),
    ];
    let tol = 0.01;
    let opts = ReadOptions::default().with_tolerance(tol);
    let d = dxf::read_loops(&dxf_file(&[], &[], &ents), "e.dxf", &opts).unwrap();
    let (area, ext) = area_and_extents(&d);
    let exact = PI * 25.0;
    // Half the ellipse's perimeter is below π·10.
    assert!(
        area <= exact && exact - area <= tol * PI * 10.0,
        "{area} vs {exact}"
    );
    // Runs of the flattening's lines on one circle within the tolerance are read as arcs,
    // which may pass beyond the vertices by as much.
    assert!(close(ext, [-10.0, 0.0, 10.0, 5.0], tol), "{ext:?}");
}

/// Four LINEs of the square [0,10]² in mixed directions, a zero-length LINE (Inkscape
/// writes them) and a gap of 0.0254 mm: refused at the default 0.01 mm with the gap, both
/// ends and the tolerance that would close it; closed at 0.03 mm.
#[test]
fn gaps_are_named_and_the_join_tolerance_closes_them() {
    let ents = [
        (0, "LINE"),
        (10, "0"),
        (20, "0"),
        (11, "10"),
        (21, "0"),
        (0, "LINE"),
        (10, "10"),
        (20, "10"),
        (11, "10"),
        (21, "0"),
        (0, "LINE"),
        (10, "5"),
        (20, "5"),
        (11, "5"),
        (21, "5"),
        (0, "LINE"),
        (10, "10"),
        (20, "10"),
        (11, "0"),
        (21, "10"),
        (0, "LINE"),
        (10, "0"),
        (20, "10"),
        (11, "0"),
        (21, "0.0254"),
    ];
    let bytes = dxf_file(&[(9, "$MEASUREMENT"), (70, "1")], &[], &ents);
    let e = dxf::parse(&bytes, "gap.dxf", &ReadOptions::default())
        .unwrap_err()
        .to_string();
    for w in [
        "gap 0.0254 mm",
        "(0.0000, 0.0254)",
        "(0.0000, 0.0000)",
        "--join-tolerance 0.0257",
        "5 LINE",
    ] {
        assert!(e.contains(w), "{w:?} not in {e}");
    }
    let opts = ReadOptions::default().with_join_tolerance(0.03);
    let d = dxf::read_loops(&bytes, "gap.dxf", &opts).unwrap();
    let (area, _) = area_and_extents(&d);
    assert!((area - 100.0).abs() < 0.03 * 10.0, "{area}");
    assert_eq!(d.degenerate, 1);
}

/// SVG shapes under transforms and page units. The page is 100 mm wide over a viewBox of 50:
/// 2 mm per user unit, and 100 mm high, so y_mm = 100 − 2·y.
/// * rect 10×20 user units with rx = 2: 20×40 mm with corners of radius 4 mm: area
///   800 − (4 − π)·16;
/// * a circle at (5, 5), r = 3, `use`d at x = 5, y = 5 inside translate(10, 0): centre
///   (20, 10) user units → (40, 100 − 20) mm, radius 6 mm;
/// * a 10×10 polygon under skewX(45): area kept (det 1), x extent widened by 10·tan 45°.
#[test]
fn svg_shapes_use_and_transforms_at_page_scale() {
    let page = |body: &str| {
        format!(
            r#"<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink"
                 width="100mm" height="100mm" viewBox="0 0 50 50">{body}</svg>"#
        )
    };
    let read = |body: &str| svg::read_loops(&page(body), "s.svg", &ReadOptions::default()).unwrap();
    let d = read(r#"<rect x="1" y="2" width="10" height="20" rx="2"/>"#);
    let (area, ext) = area_and_extents(&d);
    assert!((area - (800.0 - (4.0 - PI) * 16.0)).abs() < 1e-9, "{area}");
    assert!(close(ext, [2.0, 100.0 - 44.0, 22.0, 96.0], 1e-9), "{ext:?}");
    let d = read(
        r#"<defs><circle id="c" cx="5" cy="5" r="3"/></defs>
           <g transform="translate(10, 0)"><use xlink:href="&#35;c" x="5" y="5"/></g>"#,
    );
    let (area, ext) = area_and_extents(&d);
    assert!((area - PI * 36.0).abs() < 1e-9, "{area}");
    assert!(close(ext, [34.0, 74.0, 46.0, 86.0], 1e-9), "{ext:?}");
    let d = read(r#"<polygon points="0,0 10,0 10,10 0,10" transform="skewX(45)"/>"#);
    let (area, ext) = area_and_extents(&d);
    assert!((area - 400.0).abs() < 1e-9, "{area}");
    assert!((ext[2] - ext[0] - 40.0).abs() < 1e-9, "{ext:?}");
    // An ellipse under a rotation stays within the flattening tolerance of its area.
    let d = read(r#"<ellipse cx="25" cy="25" rx="10" ry="5" transform="rotate(30 25 25)"/>"#);
    let (area, _) = area_and_extents(&d);
    let exact = PI * 20.0 * 10.0;
    assert!(
        area <= exact + 1e-9 && exact - area <= 0.001 * 2.0 * PI * 20.0,
        "{area}"
    );
}

/// Several open paths drawing one outline, in any direction, are joined; without a width
/// and viewBox the user unit is a CSS pixel (25.4/96 mm).
#[test]
fn open_svg_paths_join_into_one_outline() {
    let doc = r#"<svg xmlns="http://www.w3.org/2000/svg">
        <path d="M 0 0 L 96 0"/><path d="M 96 96 L 96 0"/><path d="M 96 96 L 0 96 L 0 0"/></svg>"#;
    let d = svg::read_loops(doc, "o.svg", &ReadOptions::default()).unwrap();
    let (area, ext) = area_and_extents(&d);
    assert!((area - 25.4 * 25.4).abs() < 1e-9, "{area}");
    assert!(close(ext, [0.0, -25.4, 25.4, 0.0], 1e-9), "{ext:?}");
    assert!(d.units.contains("px"), "{}", d.units);
}
