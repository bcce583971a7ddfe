//! The contour pass traces the whole closed curve within the tolerance `T`: on the paper's
//! Table 1 outline at its own T = 0.00004 mm, every point of the exact curve (sampled densely,
//! the corner point (1, 15) included) lies within `T` of the finishing pass (`--side on`),
//! or within `r + T` of it where the tool can reach it (`inside`, `outside`), and no point of
//! the pass comes closer than `r` to the curve. The distances are measured against the
//! moves the tool makes (lines, and arcs sampled), not against the pass's own vertices.

use millpath::curve::{self, CompositeCurve, CurveKind};
use millpath::geom::Point;
use millpath::strategy::contour::{self, ContourOptions, Side};
use millpath::toolpath::MoveKind;

/// The paper's tolerance, mm.
const T: f64 = 0.00004;

/// Table 1 as given (no scaling), the units the paper states T in.
fn table1() -> CompositeCurve {
    curve::build(&curve::paper_groups(), CurveKind::FourPoint, "Table 1").expect("the outline")
}

/// Options at T with six decimals in the program (ρ = √2·½·10⁻⁶ mm), a 1 mm tool.
fn opts(side: Side, arcs: bool) -> ContourOptions {
    ContourOptions::default()
        .with_tool(millpath::Tool {
            diameter: 1.0,
            ..millpath::Tool::default()
        })
        .with_tolerance(T)
        .with_rounding(0.5e-6 * std::f64::consts::SQRT_2)
        .with_side(side)
        .with_depth(1.0)
        .with_step_down(1.0)
        .with_finish_allowance(0.0)
        .with_lead_radius(0.2)
        .with_arcs(arcs)
}

/// The finishing level's feed moves at depth as segments (`a`, `b`) and arcs (centre, radius,
/// start angle, sweep), excluding the plunge.
enum Piece {
    Line(Point, Point),
    Arc(Point, f64, f64, f64),
}

fn finishing_pieces(r: &contour::ContourResult) -> Vec<Piece> {
    let lv = r.toolpath.levels.last().expect("a finishing level");
    let segs: Vec<_> = r.toolpath.segments().collect();
    let mut out = Vec::new();
    for (from, m) in &segs[lv.start..lv.end] {
        if !m.is_feed() || (m.to.z - lv.z).abs() > 1e-9 || (from.z - lv.z).abs() > 1e-9 {
            continue;
        }
        match m.kind {
            MoveKind::Arc { center, .. } => {
                let (rad, sweep) = m.sweep_from(*from).expect("an arc");
                let a0 = (from.xy() - center.xy()).angle();
                out.push(Piece::Arc(center.xy(), rad, a0, sweep));
            }
            _ => out.push(Piece::Line(from.xy(), m.to.xy())),
        }
    }
    out
}

fn dist_to_pieces(p: Point, pieces: &[Piece]) -> f64 {
    pieces
        .iter()
        .map(|pc| match *pc {
            Piece::Line(a, b) => {
                let d = b - a;
                let l2 = d.dot(d);
                let t = if l2 > 0.0 {
                    ((p - a).dot(d) / l2).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                p.distance(a + d * t)
            }
            Piece::Arc(c, rad, a0, sweep) => {
                let ang = (p - c).angle();
                let rel = if sweep >= 0.0 {
                    (ang - a0).rem_euclid(std::f64::consts::TAU)
                } else {
                    (a0 - ang).rem_euclid(std::f64::consts::TAU)
                };
                if rel <= sweep.abs() {
                    (p.distance(c) - rad).abs()
                } else {
                    let e0 = c + millpath::Vec2::from_angle(a0) * rad;
                    let e1 = c + millpath::Vec2::from_angle(a0 + sweep) * rad;
                    p.distance(e0).min(p.distance(e1))
                }
            }
        })
        .fold(f64::INFINITY, f64::min)
}

/// Samples per piece of the curve: the outline is ~40 mm long, so ~1 µm apart.
const PER_PIECE: usize = 12_000;

/// Worst distance from a dense sample of the curve (each piece's ends included, so the corner)
/// to the pass, less `r`, over the points the tool can reach: those whose exact offset point
/// on the tool's side lies at least `r` from the whole curve.
fn worst_trace(c: &CompositeCurve, pieces: &[Piece], r: f64, side: Side) -> (f64, Point) {
    let mut worst = (0.0_f64, Point::new(0.0, 0.0));
    for k in 0..c.len() {
        for j in 0..=PER_PIECE {
            let s = k as f64 + j as f64 / PER_PIECE as f64;
            let s = s.min(c.len() as f64 - 1e-12);
            let p = c.eval(s);
            if side != Side::On {
                // The curve runs counter-clockwise: inside is on the left.
                let Some(t) = c.d1(s).normalize() else {
                    continue;
                };
                let n = if side == Side::Inside {
                    t.perp()
                } else {
                    -t.perp()
                };
                if curve::distance_to_curve(c, p + n * r) < r * (1.0 - 1e-9) {
                    continue; // a concave corner or curvature tighter than r: unreachable
                }
            }
            let d = dist_to_pieces(p, pieces) - r;
            if d > worst.0 {
                worst = (d, p);
            }
        }
    }
    worst
}

/// Closest approach of the pass to the curve, from samples of each move 1 µm apart or closer.
fn closest_approach(c: &CompositeCurve, pieces: &[Piece]) -> f64 {
    let mut best = f64::INFINITY;
    for pc in pieces {
        let (len, at): (f64, Box<dyn Fn(f64) -> Point>) = match *pc {
            Piece::Line(a, b) => (a.distance(b), Box::new(move |f| a.lerp(b, f))),
            Piece::Arc(cc, rad, a0, sw) => (
                rad * sw.abs(),
                Box::new(move |f| cc + millpath::Vec2::from_angle(a0 + sw * f) * rad),
            ),
        };
        let n = ((len / 2e-3).ceil() as usize).clamp(1, 4000);
        for j in 0..=n {
            best = best.min(curve::distance_to_curve(c, at(j as f64 / n as f64)));
        }
    }
    best
}

#[test]
fn on_the_outline_the_pass_traces_the_whole_curve_and_its_corner() {
    let c = table1();
    assert_eq!(c.corners(), &[0], "the outline's corner at (1, 15)");
    for arcs in [false, true] {
        let r = contour::contour(&c, &opts(Side::On, arcs)).expect("a contour");
        let pieces = finishing_pieces(&r);
        let corner = Point::new(1.0, 15.0);
        let at_corner = dist_to_pieces(corner, &pieces);
        assert!(
            at_corner <= T,
            "arcs {arcs}: the corner is {at_corner:.3e} mm from the pass"
        );
        let (worst, at) = worst_trace(&c, &pieces, 0.0, Side::On);
        assert!(worst <= T, "arcs {arcs}: {worst:.3e} mm at {at:?}, T = {T}");
        // The lobe cut off at the corner (the curve as drawn, out to (1, 15) and back).
        assert_eq!(c.lobes().len(), 1);
        for l in c.lobes() {
            for cubic in [l.to_tip, l.from_tip] {
                for j in 0..=2000 {
                    let p = cubic.eval(f64::from(j) / 2000.0);
                    let d = dist_to_pieces(p, &pieces);
                    assert!(
                        d <= T,
                        "arcs {arcs}: the lobe at {p:?} is {d:.3e} mm from the pass"
                    );
                }
            }
        }
        assert!(
            r.report.max_deviation_mm <= T,
            "arcs {arcs}: the report says {}",
            r.report.max_deviation_mm
        );
    }
}

#[test]
fn inside_and_outside_the_pass_follows_the_whole_offset_within_t() {
    let c = table1();
    for side in [Side::Inside, Side::Outside] {
        for arcs in [false, true] {
            let o = opts(side, arcs);
            let rad = o.tool.radius();
            let r = contour::contour(&c, &o).expect("a contour");
            let pieces = finishing_pieces(&r);
            let (worst, at) = worst_trace(&c, &pieces, rad, side);
            assert!(
                worst <= T,
                "{side:?} arcs {arcs}: {worst:.3e} mm beyond r at {at:?}, T = {T}"
            );
            let near = closest_approach(&c, &pieces);
            assert!(
                near >= rad - 1e-9,
                "{side:?} arcs {arcs}: the pass comes within {near:.6} mm of the curve (r = {rad})"
            );
        }
    }
}
