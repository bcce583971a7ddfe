//! Shared fixtures of the G-code integration tests.
#![allow(dead_code)]

use millpath::geom::Point3;
use millpath::toolpath::{Corner, Move, MoveKind, Plane, Tool, Toolpath};
use proptest::prelude::*;
use std::f64::consts::PI;

/// A varied toolpath: rapids, lines, arcs both ways in several quadrants, full circles,
/// helices (one with extra turns), arcs in G18/G19, dwells and corner modes.
pub fn varied_toolpath() -> Toolpath {
    let mut tp = Toolpath::new(Tool::default(), Point3::new(0.0, 0.0, 50.0));
    let f = 20.0;
    let p = Point3::new;
    tp.push(Move::rapid(p(10.0, 0.0, 50.0)));
    tp.push(Move::rapid(p(10.0, 0.0, 2.0)));
    tp.push(Move::line(p(10.0, 0.0, -1.0), 5.0));
    // Quarter CCW, then three quarters CW, in several quadrants.
    tp.push(Move::arc_xy(p(0.0, 10.0, -1.0), p(0.0, 0.0, 0.0), true, f));
    tp.push(Move::arc_xy(p(-10.0, 0.0, -1.0), p(0.0, 0.0, 0.0), true, f));
    tp.push(
        Move::arc_xy(p(0.0, -10.0, -1.0), p(0.0, 0.0, 0.0), false, f)
            .with_corner(Corner::ExactStop),
    );
    tp.push(Move::line(p(12.345_678, -10.0, -1.0), f).with_corner(Corner::Blend(0.02)));
    // Full circle CW.
    tp.push(Move::arc_xy(
        p(12.345_678, -10.0, -1.0),
        p(2.345_678, -10.0, 0.0),
        false,
        f,
    ));
    // Helix down, one extra turn.
    let mut helix = Move::arc_xy(
        p(12.345_678, -10.0, -4.0),
        p(7.345_678, -10.0, 0.0),
        true,
        f,
    );
    if let MoveKind::Arc { turns, .. } = &mut helix.kind {
        *turns = 1;
    }
    tp.push(helix);
    // Partial helix.
    tp.push(
        Move::arc_xy(p(7.345_678, -5.0, -5.0), p(7.345_678, -10.0, 0.0), true, f)
            .with_corner(Corner::ExactPath),
    );
    tp.push(Move::dwell(p(7.345_678, -5.0, -5.0), 0.75));
    // Arcs in G18 and G19 (G3 counter-clockwise seen from +Y / +X).
    tp.push(Move {
        kind: MoveKind::Arc {
            center: p(7.345_678, -5.0, -2.0),
            plane: Plane::Zx,
            ccw: true,
            turns: 0,
        },
        to: p(7.345_678, -5.0, 1.0),
        feed: f,
        corner: Corner::Machine,
        tag: None,
        rotary: None,
    });
    tp.push(Move {
        kind: MoveKind::Arc {
            center: p(7.345_678, -2.5, 1.0),
            plane: Plane::Yz,
            ccw: false,
            turns: 0,
        },
        to: p(7.345_678, 0.0, 1.0),
        feed: 12.5,
        corner: Corner::Machine,
        tag: None,
        rotary: None,
    });
    tp.push(Move::line(p(-3.0, 4.0, 1.0), 33.333_333_333));
    tp.push(Move::rapid(p(-3.0, 4.0, 50.0)));
    tp
}

use millpath::gcode::Dialect;

/// The corner a dialect reads back for `c` written without a path tolerance.
pub fn corner_read_back(d: Dialect, c: Corner) -> Corner {
    match (d, c) {
        (Dialect::LinuxCnc | Dialect::Sinumerik, c) => c,
        (Dialect::Fanuc, Corner::ExactStop | Corner::ExactPath) => Corner::ExactStop,
        (Dialect::Fanuc, _) | (Dialect::Grbl, _) => Corner::Machine,
    }
}

/// `tp` with multi-turn arcs split into full turns plus the last arc, as dialects without a
/// turn count write them. Derived here independently of the writer: a helix of total sweep S
/// and axial travel h advances h·2π/S per full turn.
pub fn expand_turns(tp: &Toolpath) -> Toolpath {
    let mut out = Toolpath::new(tp.tool, tp.start);
    for (from, m) in tp.segments() {
        match m.kind {
            MoveKind::Arc {
                center,
                plane,
                ccw,
                turns,
            } if turns > 0 => {
                let (_, sweep) = m.sweep_from(from).unwrap();
                let (_, _, h) = plane.split(m.to - from);
                let (fu, fv, fw) = plane.split(from - Point3::ORIGIN);
                for k in 1..=turns {
                    let w = fw + h * std::f64::consts::TAU * f64::from(k) / sweep.abs();
                    let to = Point3::ORIGIN + plane.join(fu, fv, w);
                    out.push(Move {
                        kind: MoveKind::Arc {
                            center,
                            plane,
                            ccw,
                            turns: 0,
                        },
                        to,
                        ..*m
                    });
                }
                out.push(Move {
                    kind: MoveKind::Arc {
                        center,
                        plane,
                        ccw,
                        turns: 0,
                    },
                    ..*m
                });
            }
            _ => out.push(*m),
        }
    }
    out
}

/// Largest difference between two moves' numbers (end, centre, feed, dwell), or infinity when
/// their kinds, planes, directions or turns differ. Centres compare in-plane only.
pub fn move_difference(a: &Move, b: &Move) -> f64 {
    let d3 = |p: Point3, q: Point3| {
        (p.x - q.x)
            .abs()
            .max((p.y - q.y).abs())
            .max((p.z - q.z).abs())
    };
    let ends = d3(a.to, b.to);
    match (a.kind, b.kind) {
        (MoveKind::Rapid, MoveKind::Rapid) => ends,
        (MoveKind::Line, MoveKind::Line) => ends.max((a.feed - b.feed).abs()),
        (MoveKind::Dwell { seconds: s }, MoveKind::Dwell { seconds: t }) => (s - t).abs(),
        (
            MoveKind::Arc {
                center: c1,
                plane: p1,
                ccw: w1,
                turns: t1,
            },
            MoveKind::Arc {
                center: c2,
                plane: p2,
                ccw: w2,
                turns: t2,
            },
        ) if p1 == p2 && w1 == w2 && t1 == t2 => {
            let (u1, v1, _) = p1.split(c1 - Point3::ORIGIN);
            let (u2, v2, _) = p2.split(c2 - Point3::ORIGIN);
            ends.max((u1 - u2).abs())
                .max((v1 - v2).abs())
                .max((a.feed - b.feed).abs())
        }
        _ => f64::INFINITY,
    }
}

/// `tp` as the writer writes it when its first motion is an arc: a rapid to the start first.
pub fn with_start_rapid(tp: &Toolpath) -> Toolpath {
    let first_motion = tp
        .moves
        .iter()
        .find(|m| !matches!(m.kind, MoveKind::Dwell { .. }));
    let mut out = tp.clone();
    if let Some(Move {
        kind: MoveKind::Arc { .. },
        ..
    }) = first_motion
    {
        let at = tp
            .moves
            .iter()
            .position(|m| !matches!(m.kind, MoveKind::Dwell { .. }))
            .unwrap_or(0);
        out.moves.insert(at, Move::rapid(tp.start));
    }
    out
}

/// One random step: kind, four numbers in [-1, 1], a direction and a plane.
pub type Step = (u8, f64, f64, f64, f64, bool, u8);

pub fn random_step() -> impl Strategy<Value = Step> {
    (
        0u8..5,
        -1.0..1.0f64,
        -1.0..1.0f64,
        -1.0..1.0f64,
        -1.0..1.0f64,
        any::<bool>(),
        0u8..3,
    )
}

/// Builds a toolpath of rapids, lines, arcs and helices in all planes (sweeps 0.05..6.15
/// rad), full circles with 0..2 extra turns, and dwells.
pub fn build_random(steps: &[Step]) -> Toolpath {
    let mut tp = Toolpath::new(Tool::default(), Point3::new(0.0, 0.0, 20.0));
    let mut p = tp.start;
    for &(kind, a, b, c, d, ccw, pl) in steps {
        let plane = [Plane::Xy, Plane::Zx, Plane::Yz][usize::from(pl)];
        let m = match kind {
            0 => Move::rapid(Point3::new(a * 500.0, b * 500.0, c * 100.0)),
            1 => Move::line(
                Point3::new(a * 500.0, b * 500.0, c * 100.0),
                d.abs() * 100.0 + 0.1,
            ),
            2 | 3 => {
                let r = 0.5 + a.abs() * 200.0;
                let t0 = b * PI;
                let (pu, pv, pw) = plane.split(p - Point3::ORIGIN);
                let (cu, cv) = (pu - r * t0.cos(), pv - r * t0.sin());
                let (to, turns) = if kind == 2 {
                    let sweep = 0.05 + c.abs() * 6.1;
                    let t1 = if ccw { t0 + sweep } else { t0 - sweep };
                    (
                        Point3::ORIGIN
                            + plane.join(cu + r * t1.cos(), cv + r * t1.sin(), pw + d * 10.0),
                        0,
                    )
                } else {
                    (
                        Point3::ORIGIN + plane.join(pu, pv, pw + d * 5.0),
                        (c.abs() * 2.99) as u32,
                    )
                };
                let center = Point3::ORIGIN + plane.join(cu, cv, pw);
                Move {
                    kind: MoveKind::Arc {
                        center,
                        plane,
                        ccw,
                        turns,
                    },
                    to,
                    feed: d.abs() * 50.0 + 0.5,
                    corner: Corner::Machine,
                    tag: None,
                    rotary: None,
                }
            }
            _ => Move::dwell(p, a.abs() * 5.0),
        };
        p = m.to;
        tp.push(m);
    }
    tp
}
