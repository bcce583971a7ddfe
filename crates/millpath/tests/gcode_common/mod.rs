//! Shared fixtures of the G-code integration tests.
#![allow(dead_code)]

use millpath::geom::Point3;
use millpath::toolpath::{Corner, Move, MoveKind, Plane, Tool, Toolpath};

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
    });
    tp.push(Move::line(p(-3.0, 4.0, 1.0), 33.333_333_333));
    tp.push(Move::rapid(p(-3.0, 4.0, 50.0)));
    tp
}
