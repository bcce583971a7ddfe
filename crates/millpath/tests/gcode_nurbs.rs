//! LinuxCNC's NURBS blocks (G5.2 … G5.3) read as the true curve. rs274 prints a whole curve
//! as one `NURBS_FEED` without points, so the curve is judged here independently:
//!
//! * a rational quadratic with the middle weight cos(45°) is an exact quarter circle: every
//!   vertex must lie on the circle (1e-9 mm) and every chord within the reader's tolerance
//!   (its sagitta, computed from the circle);
//! * a cubic with unequal weights: the curve, evaluated here by the Cox–de Boor recursion of
//!   the basis functions (not the reader's de Boor algorithm), must stay within the tolerance
//!   of the polyline everywhere, and the polyline's vertices on the curve.

mod nurbs_common;

use millpath::geom::Point3;
use millpath::toolpath::MoveKind;
use nurbs_common::{
    assert_vertices_on_curve, clamped_knots, curve_off_polyline, curve_on_knots, read, try_read,
};

const TOL: f64 = 0.001;

#[test]
fn a_weighted_quadratic_is_a_quarter_circle() {
    let r = 50.0;
    let w = std::f64::consts::FRAC_1_SQRT_2;
    let text = format!(
        "G21 G17 G90\nG0 X{r} Y0 Z-1\nF600\nG5.2 P1\nX{r} Y{r} P{w}\nX0 Y{r} P1\nG5.3\nG0 Z5\nM2\n"
    );
    let moves = read(&text);
    let lines: Vec<_> = moves
        .iter()
        .filter(|m| m.mv.kind == MoveKind::Line)
        .collect();
    assert!(lines.len() > 20, "{} lines", lines.len());
    assert!(
        lines
            .iter()
            .all(|m| m.line == 7 && (m.mv.feed - 10.0).abs() < 1e-12)
    );
    let mut from = Point3::new(r, 0.0, -1.0);
    for m in &lines {
        let p = m.mv.to;
        assert!((p.x.hypot(p.y) - r).abs() < 1e-9, "{p:?} off the circle");
        assert!((p.z + 1.0).abs() < 1e-12);
        let chord = p.distance(from);
        let sagitta = r - (r * r - chord * chord / 4.0).sqrt();
        assert!(
            sagitta <= TOL + 1e-12,
            "sagitta {sagitta} of a chord {chord}"
        );
        from = p;
    }
    assert!(
        from.distance(Point3::new(0.0, r, -1.0)) < 1e-12,
        "end {from:?}"
    );
}

fn curve(cp: &[(f64, f64, f64)], k: usize, u: f64) -> (f64, f64) {
    curve_on_knots(cp, k, &clamped_knots(cp.len() - 1, k), u)
}

#[test]
fn a_weighted_cubic_stays_within_the_tolerance_of_the_true_curve() {
    let cp = [
        (0.0, 0.0, 1.0),
        (10.0, 40.0, 2.0),
        (40.0, 45.0, 0.5),
        (60.0, -10.0, 1.0),
        (90.0, 20.0, 3.0),
        (100.0, 0.0, 1.0),
    ];
    let mut text = String::from("G21 G17 G90\nG0 X0 Y0 Z0\nF300\nG5.2 P1 L4\n");
    for (x, y, w) in cp.iter().skip(1) {
        text.push_str(&format!("X{x} Y{y} P{w}\n"));
    }
    text.push_str("G5.3\nG1 X0 Y0\nM2\n");
    let moves = read(&text);
    let mut poly = vec![(0.0, 0.0)];
    poly.extend(
        moves
            .iter()
            .filter(|m| m.line == 10)
            .map(|m| (m.mv.to.x, m.mv.to.y)),
    );
    assert!(poly.len() > 50, "{} vertices", poly.len());
    assert_eq!(*poly.last().unwrap(), (100.0, 0.0));
    // The true curve, densely sampled, along the polyline (a window that moves forward).
    let umax = (cp.len() + 1 - 4) as f64;
    let samples = 200_000;
    let dense: Vec<_> = (0..=samples)
        .map(|s| curve(&cp, 4, umax * s as f64 / samples as f64))
        .collect();
    let worst = curve_off_polyline(&dense, &poly);
    assert!(
        worst <= TOL + 1e-9,
        "the curve is {worst} mm from the polyline"
    );
    // And the vertices lie on the curve (found by the nearest dense sample).
    assert_vertices_on_curve(&poly, &dense);
}

#[test]
fn a_quadratic_g5_1_is_a_parabola() {
    // From (0, 0) over the control point (5, 10) to (10, 0): x = 10t, y = 20t(1 − t), so
    // y = 2x − x²/5 on every vertex; a parabola is farthest from a chord at the middle x of
    // the chord (where its slope equals the chord's), which gives each chord's exact error.
    let moves = read("G21 G17 G90\nG0 X0 Y0\nF100\nG5.1 X10 Y0 I5 J10\nM2\n");
    let mut from = (0.0, 0.0);
    assert!(moves.len() > 20, "{} moves", moves.len() - 1);
    for m in moves.iter().filter(|m| m.line == 4) {
        let (x, y) = (m.mv.to.x, m.mv.to.y);
        assert!(
            (y - (2.0 * x - x * x / 5.0)).abs() < 1e-9,
            "({x}, {y}) off the parabola"
        );
        let xm = 0.5 * (from.0 + x);
        let gap = (2.0 * xm - xm * xm / 5.0) - 0.5 * (from.1 + y);
        let slope = (y - from.1) / (x - from.0);
        let error = gap.abs() / (1.0 + slope * slope).sqrt();
        assert!(
            error <= TOL + 1e-12,
            "chord to ({x}, {y}) is {error} mm from the curve"
        );
        from = (x, y);
    }
    assert_eq!(from, (10.0, 0.0));
}

#[test]
fn splines_end_where_rs274_ends_them() {
    // rs274 prints each spline as one NURBS_FEED; the incremental moves after each show
    // where it ended. The reader's ends must be rs274's.
    let text = "G21 G17 G90\nG0 X0 Y0\nF100\nG5.1 X10 Y0 I5 J10\nG91 G1 X1\nG90\n\
                G5 X20 Y5 I2 J2 P-2 Q3\nG91 G1 Y1\nG90\nG5 X30 Y0 I1 J1 P1 Q1\nG5 X40 Y5 P2 Q2\n\
                G91 G1 X1 Y1\nG90 G5.2 P1\nX45 Y10 P1\nX50 Y0 P2\nX55 Y5 P1\nG5.3\nG91 G1 X1\nM2\n";
    let moves = read(text);
    let ends: Vec<_> = moves
        .iter()
        .filter(|m| m.mv.kind == MoveKind::Line && [5, 8, 12, 18].contains(&m.line))
        .map(|m| (m.mv.to.x, m.mv.to.y))
        .collect();
    assert_eq!(ends, [(11.0, 0.0), (20.0, 6.0), (41.0, 6.0), (56.0, 5.0)]);
}

#[test]
fn what_linuxcnc_refuses_or_the_reader_leaves_out_is_refused() {
    for (text, word) in [
        ("G21 G17 G90 F100\nG5.3\nM2\n", "G5.3"),
        (
            "G21 G17 G90 F100\nG5 X1 Y1 I1 J0 P0 Q1\nX2 Y0 P1 Q1\nM2\n",
            "every spline block",
        ),
        ("G21 G17 G90 F100\nG5 X1 Y1 P0 Q1\nM2\n", "I and J"),
        ("G21 G17 G90 F100\nG5.1 X1 Y1 I1\nM2\n", "I and J"),
        (
            "G21 G17 G90 F100\nG5.2 P1 L4\nX1 Y1 P1\nX2 Y0 P1\nG5.3\nM2\n",
            "order",
        ),
        (
            "G21 G17 G90 F100\nG5.2 P1\nX1 Y1\nX2 Y0 P1\nG5.3\nM2\n",
            "weight",
        ),
        (
            "G21 G17 G90 F100\nG5.2 P1\nX1 P1\nG5.3\nM2\n",
            "X without Y",
        ),
        (
            "G21 G18 G90 F100\nG5.2 P1\nX1 Z1 Y1 P1\nG5.3\nM2\n",
            "G5.2 with Y",
        ),
        ("G21 G17 G90\nG5.2 P1\nX1 Y1 P1\nG5.3\nM2\n", "feed"),
    ] {
        let e = try_read(text).unwrap_err();
        assert!(e.to_string().contains(word), "{text}: {e}");
    }
}
