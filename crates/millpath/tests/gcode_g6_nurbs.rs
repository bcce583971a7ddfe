//! LinuxCNC master's G6.2 NURBS (explicit knots K, weights R, order P), and G5.2 in the
//! G18/G19 planes, read as the true curve. LinuxCNC 2.9's rs274 refuses both, so the curve
//! is judged here independently of the reader:
//!
//! * a rational quadratic with knots 0 0 0 1 1 1 and the middle weight cos(45°) is an exact
//!   quarter circle: every vertex on the circle (1e-9 mm), every chord's sagitta within the
//!   reader's tolerance, the ends those of the control polygon;
//! * a weighted cubic on a non-uniform knot vector: the curve, evaluated here by the
//!   Cox–de Boor recursion of the basis functions (not the reader's de Boor algorithm), stays
//!   within the tolerance of the polyline everywhere, and the vertices lie on it.

mod nurbs_common;

use millpath::geom::Point3;
use millpath::toolpath::MoveKind;
use nurbs_common::{
    assert_vertices_on_curve, curve_off_polyline, curve_on_knots as curve, read, refusal, try_read,
};

const TOL: f64 = 0.001;

/// A G6.2 program: the tool at the first control point (in the plane `g`, with the axis
/// letters `a b`), then one entry per control point and `order` knot-only entries.
fn g6_program(
    g: &str,
    ab: (char, char),
    cp: &[(f64, f64, f64)],
    knots: &[f64],
    order: usize,
) -> String {
    assert_eq!(knots.len(), cp.len() + order);
    let (a, b) = ab;
    let mut text = format!("G21 {g} G90\nG0 {a}{} {b}{}\nF600\n", cp[0].0, cp[0].1);
    for (i, ((x, y, w), k)) in cp.iter().zip(knots).enumerate() {
        let head = if i == 0 {
            format!("G6.2 P{order} Q1 ")
        } else {
            String::new()
        };
        text.push_str(&format!("{head}{a}{x} {b}{y} R{w} K{k}\n"));
    }
    for k in &knots[cp.len()..] {
        text.push_str(&format!("G6.2 K{k}\n"));
    }
    text.push_str("G0 Z5\nM2\n");
    text
}

#[test]
fn a_g6_2_quarter_circle_lies_on_the_circle() {
    let r = 50.0;
    let w = std::f64::consts::FRAC_1_SQRT_2;
    let cp = [(r, 0.0, 1.0), (r, r, w), (0.0, r, 1.0)];
    let text = g6_program("G17", ('X', 'Y'), &cp, &[0.0, 0.0, 0.0, 1.0, 1.0, 1.0], 3);
    let moves = read(&text);
    // The curve's moves are on the line of the entry that completes it (line 9).
    let curve: Vec<_> = moves.iter().filter(|m| m.line == 9).collect();
    assert!(curve.len() > 20, "{} vertices", curve.len());
    assert!(
        curve
            .iter()
            .all(|m| m.mv.kind == MoveKind::Line && (m.mv.feed - 10.0).abs() < 1e-12)
    );
    let mut from = Point3::new(r, 0.0, 0.0);
    for m in &curve {
        let p = m.mv.to;
        assert!((p.x.hypot(p.y) - r).abs() < 1e-9, "{p:?} off the circle");
        assert!(p.z.abs() < 1e-12);
        let chord = p.distance(from);
        let sagitta = r - (r * r - chord * chord / 4.0).sqrt();
        assert!(
            sagitta <= TOL + 1e-12,
            "sagitta {sagitta} of a chord {chord}"
        );
        from = p;
    }
    assert!(
        from.distance(Point3::new(0.0, r, 0.0)) < 1e-12,
        "end {from:?}"
    );
    // After the curve no motion mode is in effect (as LinuxCNC's motion_mode = -1).
    let after = try_read(&text.replace("G0 Z5\n", "Z5\n"));
    assert!(
        after.is_err(),
        "axis words after the curve must need a motion code"
    );
}

#[test]
fn a_g6_2_in_g19_is_the_same_curve_in_y_z() {
    let r = 20.0;
    let w = std::f64::consts::FRAC_1_SQRT_2;
    let cp = [(r, 0.0, 1.0), (r, r, w), (0.0, r, 1.0)];
    let knots = [0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
    let xy = read(&g6_program("G17", ('X', 'Y'), &cp, &knots, 3));
    let yz = read(&g6_program("G19", ('Y', 'Z'), &cp, &knots, 3));
    let zx = read(&g6_program("G18", ('Z', 'X'), &cp, &knots, 3));
    assert_eq!(xy.len(), yz.len());
    assert_eq!(xy.len(), zx.len());
    for ((a, b), c) in xy
        .iter()
        .zip(&yz)
        .zip(&zx)
        .filter(|((a, _), _)| a.line == 9)
    {
        let (p, q, s) = (a.mv.to, b.mv.to, c.mv.to);
        assert!((p.x - q.y).abs() < 1e-12 && (p.y - q.z).abs() < 1e-12 && q.x == 0.0);
        assert!((p.x - s.z).abs() < 1e-12 && (p.y - s.x).abs() < 1e-12 && s.y == 0.0);
    }
}

#[test]
fn a_weighted_cubic_on_uneven_knots_stays_on_the_true_curve() {
    let cp = [
        (0.0, 0.0, 1.0),
        (10.0, 40.0, 2.0),
        (40.0, 45.0, 0.5),
        (60.0, -10.0, 1.0),
        (90.0, 20.0, 3.0),
        (100.0, 0.0, 1.0),
    ];
    let t = [0.0, 0.0, 0.0, 0.0, 0.3, 1.7, 2.5, 2.5, 2.5, 2.5];
    let text = g6_program("G17", ('X', 'Y'), &cp, &t, 4);
    let moves = read(&text);
    let last = moves.iter().map(|m| m.line).max().unwrap();
    let complete = 4 + cp.len() + 3;
    // The rapid to the start, the curve, the rapid up.
    assert_eq!(
        moves.iter().filter(|m| m.line == complete).count() + 2,
        moves.len()
    );
    assert!(last > complete);
    let mut poly = vec![(0.0, 0.0)];
    poly.extend(
        moves
            .iter()
            .filter(|m| m.line == complete)
            .map(|m| (m.mv.to.x, m.mv.to.y)),
    );
    assert!(poly.len() > 50, "{} vertices", poly.len());
    assert_eq!(*poly.last().unwrap(), (100.0, 0.0));
    let (u0, u1) = (t[3], t[cp.len()]);
    let samples = 200_000;
    let dense: Vec<_> = (0..=samples)
        .map(|s| curve(&cp, 4, &t, u0 + (u1 - u0) * s as f64 / samples as f64))
        .collect();
    assert_eq!(dense[0], (0.0, 0.0));
    assert!((dense[samples].0 - 100.0).abs() < 1e-12 && dense[samples].1.abs() < 1e-12);
    // The true curve along the polyline (a window that moves forward).
    let worst = curve_off_polyline(&dense, &poly);
    assert!(
        worst <= TOL + 1e-9,
        "the curve is {worst} mm from the polyline"
    );
    // The vertices on the curve.
    assert_vertices_on_curve(&poly, &dense);
}

#[test]
fn a_g6_2_away_from_the_tool_starts_with_a_line_to_its_first_point() {
    let cp = [(10.0, 0.0, 1.0), (10.0, 10.0, 1.0), (0.0, 10.0, 1.0)];
    let text = g6_program("G17", ('X', 'Y'), &cp, &[0.0, 0.0, 0.0, 1.0, 1.0, 1.0], 3)
        .replace("G0 X10 Y0", "G0 X-5 Y-5");
    let moves = read(&text);
    let first = moves.iter().find(|m| m.line == 9).unwrap();
    assert_eq!(first.mv.kind, MoveKind::Line);
    assert_eq!(first.mv.to, Point3::new(10.0, 0.0, 0.0));
}

#[test]
fn g6_2_refusals_name_the_word_and_the_line() {
    let cp = [(10.0, 0.0, 1.0), (10.0, 10.0, 1.0), (0.0, 10.0, 1.0)];
    let good = g6_program("G17", ('X', 'Y'), &cp, &[0.0, 0.0, 0.0, 1.0, 1.0, 1.0], 3);
    assert!(try_read(&good).is_ok());
    let cases = [
        // Not clamped at the start.
        (
            g6_program("G17", ('X', 'Y'), &cp, &[0.0, 0.5, 0.7, 1.0, 1.0, 1.0], 3),
            ":9",
            "clamped start",
        ),
        (
            good.replace("X10 Y10 R1 K0", "X10 Y10 R1"),
            ":5",
            "K on every",
        ),
        (
            good.replace("X10 Y10 R1", "X10 Y10 R0"),
            ":5",
            "weight R > 0",
        ),
        (
            good.replace("Y10 R1 K0", "Y10 R1 K2"),
            ":7",
            "do not decrease",
        ),
        (good.replace("G6.2 P3 Q1", "G6.2 Q1"), ":4", "order P"),
        (good.replace("G6.2 P3 Q1", "G6.2 P3"), ":4", "method Q"),
        (
            good.replace("G6.2 K1\nG6.2 K1\n", "G1 X0\n"),
            ":7",
            "not complete",
        ),
        (
            good.replace("X0 Y10 R1", "X0 Y10 Z1 R1"),
            ":6",
            "G6.2 with Z",
        ),
        (
            good.replace(
                "G6.2 K1\nG6.2 K1\nG6.2 K1\n",
                "I5\nG6.2 K1\nG6.2 K1\nG6.2 K1\n",
            ),
            ":7",
            "I5 in a G6.2 block",
        ),
    ];
    for (text, line, expected) in cases {
        let m = refusal(&text);
        assert!(
            m.contains(line) && m.contains(expected),
            "{m}\n(for {text})"
        );
    }
}

#[test]
fn g5_2_in_g18_and_g19_is_the_g17_curve_in_their_axes() {
    let body = |a: char, b: char| {
        format!(
            "G21 G90 {}\nG0 {a}0 {b}0\nF100\nG5.2 P1 L3\n{a}0 {b}1 P1\n{a}2 {b}2 P1\n\
             {a}2 {b}0 P1\n{a}0 {b}0 P2\nG5.3\nM2\n",
            match (a, b) {
                ('X', 'Y') => "G17",
                ('Y', 'Z') => "G19",
                _ => "G18",
            }
        )
    };
    let xy = read(&body('X', 'Y'));
    let yz = read(&body('Y', 'Z'));
    let zx = read(&body('Z', 'X'));
    assert!(xy.len() > 20);
    assert_eq!(xy.len(), yz.len());
    assert_eq!(xy.len(), zx.len());
    for ((a, b), c) in xy.iter().zip(&yz).zip(&zx) {
        let (p, q, s) = (a.mv.to, b.mv.to, c.mv.to);
        assert!((p.x - q.y).abs() < 1e-12 && (p.y - q.z).abs() < 1e-12 && q.x == 0.0);
        assert!((p.x - s.z).abs() < 1e-12 && (p.y - s.x).abs() < 1e-12 && s.y == 0.0);
    }
    // The normal axis in a G5.2 block is refused with its letter.
    let m = refusal(&body('Y', 'Z').replace("Y2 Z2 P1", "Y2 Z2 X1 P1"));
    assert!(m.contains("G5.2 with X") && m.contains(":6"), "{m}");
}
