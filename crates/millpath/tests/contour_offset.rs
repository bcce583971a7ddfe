//! Contour offsets: distance never below tool radius + allowance (dense check against the
//! true curve through kurbo), one-sided tolerance band, loop trimming with warnings, tool too
//! large, invariance under reversal and start rotation.

// The figures are printed for the benchmark notes (`cargo test -- --nocapture`).
#![allow(clippy::print_stderr)]

use millpath::curve::{self, CompositeCurve, CurveKind, LabeledPoint};
use millpath::geom::Point;
use millpath::strategy::contour::{self, ContourOptions, ContourWarning, Side, offset_pass};

fn opts(tol: f64, side: Side) -> ContourOptions {
    ContourOptions::default()
        .with_tolerance(tol)
        .with_side(side)
}

fn loop_points(p: &contour::Pass) -> Vec<Vec<Point>> {
    p.loops
        .iter()
        .map(|l| l.iter().map(|v| v.p).collect())
        .collect()
}

fn area(pts: &[Point]) -> f64 {
    let n = pts.len();
    (0..n)
        .map(|i| pts[i].to_vec2().cross(pts[(i + 1) % n].to_vec2()))
        .sum::<f64>()
        * 0.5
}

#[test]
fn paper_outline_offsets_keep_their_distance() {
    let c = curve::paper_outline().unwrap();
    for side in [Side::Inside, Side::Outside] {
        for tol in [1e-2, 1e-3] {
            let o = opts(tol, side);
            let d = o.tool.radius() + o.finish_allowance;
            let sd = if side == Side::Inside { d } else { -d };
            let pass = offset_pass(&c, sd, &o).unwrap();
            let min = loop_points(&pass)
                .iter()
                .map(|l| curve::polyline_min_distance(&c, l, 8))
                .fold(f64::INFINITY, f64::min);
            eprintln!(
                "{side:?} T={tol}: {} segments, min distance {min:.9} (d = {d}), measured dev {:.3e}, warnings {}",
                pass.segments(),
                pass.max_deviation,
                pass.warnings.len()
            );
            assert!(min >= d - 1e-6, "{side:?} T={tol}: {min} < {d}");
            assert!(
                pass.max_deviation <= tol,
                "{side:?} T={tol}: {}",
                pass.max_deviation
            );
        }
    }
}

#[test]
fn the_spike_of_the_paper_outline_is_reported_unreachable() {
    let c = curve::paper_outline().unwrap();
    let o = opts(1e-2, Side::Inside);
    let pass = offset_pass(&c, 5.2, &o).unwrap();
    assert!(!pass.warnings.is_empty());
    assert!(
        pass.warnings.iter().any(|w| matches!(
            w,
            ContourWarning::Unreachable { offset_mm, .. }
                if (offset_mm - 5.2).abs() < 1e-12
        )),
        "{:?}",
        pass.warnings
    );
}

#[test]
fn a_tool_too_large_is_an_input_error() {
    let pts: Vec<Vec<LabeledPoint>> = vec![
        [(0.0, 0.0), (6.0, 0.0), (6.0, 6.0), (0.0, 6.0)]
            .iter()
            .enumerate()
            .map(|(i, (x, y))| LabeledPoint {
                p: Point::new(*x, *y),
                origin: format!("p{i}"),
            })
            .collect(),
    ];
    let c = curve::build(&pts, CurveKind::Spline, "square").unwrap();
    let o = opts(1e-2, Side::Inside);
    let e = offset_pass(&c, 5.2, &o).unwrap_err();
    assert_eq!(e.exit_code(), 2, "{e}");
    assert!(e.to_string().contains("tool diameter"), "{e}");
}

fn groups(pts: &[(f64, f64)]) -> Vec<Vec<LabeledPoint>> {
    vec![
        pts.iter()
            .enumerate()
            .map(|(i, (x, y))| LabeledPoint {
                p: Point::new(*x, *y),
                origin: format!("p{i}"),
            })
            .collect(),
    ]
}

#[test]
fn reversed_and_rotated_input_give_the_same_result() {
    let base = [
        (0.0, 0.0),
        (120.0, -10.0),
        (160.0, 60.0),
        (110.0, 140.0),
        (40.0, 90.0),
        (-20.0, 110.0),
    ];
    let mut rev = base.to_vec();
    rev.reverse();
    let mut rot = base.to_vec();
    rot.rotate_left(2);
    for kind in [CurveKind::CatmullRom, CurveKind::Spline] {
        let summary = |pts: &[(f64, f64)]| {
            let c: CompositeCurve = curve::build(&groups(pts), kind, "t").unwrap();
            let o = opts(1e-3, Side::Inside);
            let f = curve::flatten(&c, 1e-3).unwrap();
            let pass = offset_pass(&c, 5.2, &o).unwrap();
            let a: f64 = loop_points(&pass).iter().map(|l| area(l)).sum();
            (f.segments(), f.max_deviation, a, c.signed_area())
        };
        let (n0, d0, a0, c0) = summary(&base);
        for other in [&rev, &rot] {
            let (n, d, a, ca) = summary(other);
            assert!(n.abs_diff(n0) <= 1, "{kind:?}: {n} vs {n0}");
            assert!(d <= 1e-3 && d0 <= 1e-3);
            assert!(
                (ca - c0).abs() < 1e-6 * c0.abs(),
                "{kind:?}: curve area {ca} vs {c0}"
            );
            assert!(
                (a - a0).abs() < 1e-3 * a0.abs(),
                "{kind:?}: offset area {a} vs {a0}"
            );
        }
    }
}

#[test]
fn full_contour_layers_and_report() {
    let c = curve::paper_outline().unwrap();
    let o = ContourOptions::default().with_tolerance(1e-2);
    let r = contour::contour(&c, &o).unwrap();
    // 20 mm at 2.5 mm: 8 roughing layers, then the finishing pass.
    assert_eq!(r.report.layers.len(), 9);
    assert!(r.report.max_deviation_mm <= 1e-2);
    let js = serde_json::to_value(&r.report).unwrap();
    for k in ["segments", "max_deviation_mm", "layers", "blocks"] {
        assert!(js.get(k).is_some(), "{k}");
    }
    assert!(r.toolpath.moves.iter().filter(|m| m.tag.is_some()).count() >= 9 * r.report.segments);
}

#[test]
fn on_the_outline_lines_and_arcs_stay_within_tolerance() {
    let c = curve::paper_outline().unwrap();
    for arcs in [false, true] {
        let o = ContourOptions::default()
            .with_tolerance(1e-3)
            .with_side(Side::On)
            .with_arcs(arcs);
        let r = contour::contour(&c, &o).unwrap();
        assert!(
            r.report.max_deviation_mm <= 1e-3,
            "arcs {arcs}: {}",
            r.report.max_deviation_mm
        );
        assert!(r.report.segments > 0);
        // Every cutting move at depth is tagged with the curve parameter it came from.
        let finish = r.toolpath.levels.last().unwrap();
        let tagged = r.toolpath.moves[finish.start..finish.end]
            .iter()
            .filter(|m| m.tag.is_some())
            .count();
        assert!(
            tagged >= r.report.segments,
            "arcs {arcs}: {tagged} tagged of {}",
            r.report.segments
        );
    }
}

#[test]
fn every_feed_move_including_lead_arcs_keeps_the_tool_off_the_outline() {
    use millpath::toolpath::{LevelKind, MoveKind};
    let c = curve::paper_outline().unwrap();
    for side in [Side::Inside, Side::Outside] {
        for arcs in [false, true] {
            let o = ContourOptions::default()
                .with_tolerance(1e-2)
                .with_side(side)
                .with_arcs(arcs);
            let r = contour::contour(&c, &o).unwrap();
            let segs: Vec<_> = r.toolpath.segments().collect();
            for lv in &r.toolpath.levels {
                let need = o.tool.radius()
                    + if lv.kind == LevelKind::Roughing {
                        o.finish_allowance
                    } else {
                        0.0
                    };
                let mut min = f64::INFINITY;
                for (from, m) in &segs[lv.start..lv.end] {
                    if !m.is_feed() {
                        continue;
                    }
                    let samples: Vec<Point> = match m.kind {
                        MoveKind::Arc { center, .. } => {
                            let (rad, sweep) = m.sweep_from(*from).unwrap();
                            let a0 = (from.xy() - center.xy()).angle();
                            (0..=16)
                                .map(|j| {
                                    center.xy()
                                        + millpath::Vec2::from_angle(
                                            a0 + sweep * f64::from(j) / 16.0,
                                        ) * rad
                                })
                                .collect()
                        }
                        _ => (0..=4)
                            .map(|j| from.xy().lerp(m.to.xy(), f64::from(j) / 4.0))
                            .collect(),
                    };
                    for p in samples {
                        min = min.min(curve::distance_to_curve(&c, p));
                    }
                }
                assert!(
                    min >= need - 1e-6,
                    "{side:?} arcs {arcs} z {}: {min} < {need}",
                    lv.z
                );
            }
        }
    }
}
