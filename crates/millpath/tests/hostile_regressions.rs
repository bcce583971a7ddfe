//! Inputs the hostile passes (`hostile_*.rs`) found panicking, kept as regression tests: each
//! must now be refused with an input error that names the offending value.

use millpath::Error;
use millpath::io::{dxf, svg};

/// A DXF polyline with a vertex at -1e308 and a bulge of -1e308: `cavalier_contours` asserted
/// ("point does not lie on the line defined by p0 to p1") while scanning for self-intersections.
/// Fixed in `Outline::from_polyline`: coordinates beyond ±1e6 mm and bulges beyond 1000 are
/// refused.
#[test]
fn dxf_vertex_at_1e308_is_refused() {
    let text = "0\nSECTION\n2\nENTITIES\n0\nLWPOLYLINE\n90\n4\n70\n1\n10\n-68.02\n20\n-53.09\n\
                10\n-1e308\n20\n-1e308\n42\n-1e308\n10\n87.14\n20\n45.12\n0\nENDSEC\n0\nEOF\n";
    let e = dxf::parse(text.as_bytes(), "r.dxf", &dxf::DxfOptions::default()).unwrap_err();
    let msg = e.to_string();
    assert!(msg.contains("1e308") || msg.contains("100000000"), "{msg}");
    assert!(msg.contains("vertex 1"), "{msg}");
}

/// A polyline whose coordinates are ordinary but one vertex is 1e29 mm away.
#[test]
fn dxf_huge_coordinate_is_refused() {
    let text = "0\nSECTION\n2\nENTITIES\n0\nLWPOLYLINE\n90\n4\n70\n1\n\
                10\n99999999999999999999999999999\n20\n82.31\n10\n-97.62\n20\n-37.12\n\
                10\n98.28\n20\n0\n42\n-72.21\n0\nENDSEC\n0\nEOF\n";
    let e = dxf::parse(text.as_bytes(), "r.dxf", &dxf::DxfOptions::default()).unwrap_err();
    assert!(e.to_string().contains("within ±1000000 mm"), "{e}");
}

/// An SVG cubic with a control point at -1e308: kurbo's flattening computed an infinite
/// subdivision count and `Vec::with_capacity` panicked with "capacity overflow". Fixed in
/// `svg::path_loops`: curve points are checked before flattening.
#[test]
fn svg_curve_at_1e308_is_refused() {
    let doc = r#"<svg><path d="M -29.08 -10 L -17.13 -69.92 S 0 -20.54 13.56 -1e308 Z"/></svg>"#;
    let e = svg::parse(doc, "r.svg", 0.01).unwrap_err();
    assert!(e.to_string().contains("SVG curve point"), "{e}");
}

/// A flattening tolerance that is not a positive number ≥ 1e-6 mm is refused up front (a zero
/// or tiny tolerance would flatten a curve into an unbounded number of points).
#[test]
fn svg_bad_tolerance_is_refused() {
    let doc = r#"<svg><circle cx="0" cy="0" r="5"/></svg>"#;
    for tol in [f64::NAN, 0.0, -1.0, 1e-12, f64::INFINITY] {
        let e = svg::parse(doc, "r.svg", tol).unwrap_err();
        assert!(e.to_string().contains("tolerance"), "{tol}: {e}");
    }
    assert!(svg::parse(doc, "r.svg", 0.01).is_ok());
}

/// The outline bounds also hold for outlines built in code.
#[test]
fn outline_bounds_are_input_errors() {
    use millpath::Point;
    use millpath::geom::Outline;
    let far = [
        Point::new(0.0, 0.0),
        Point::new(2e6, 0.0),
        Point::new(0.0, 10.0),
    ];
    let e: Error = Outline::from_points(&far, "code").unwrap_err().into();
    assert_eq!(e.exit_code(), 2);
    let bulgy = [(Point::new(0.0, 0.0), 1e300), (Point::new(10.0, 0.0), 1.0)];
    assert!(Outline::new(&bulgy, "code").is_err());
}
