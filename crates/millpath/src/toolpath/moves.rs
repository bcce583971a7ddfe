//! One move of a toolpath.

use crate::geom::{Point3, Vec3};
use serde::{Deserialize, Serialize};
use std::f64::consts::TAU;

/// The plane an arc turns in (G17, G18, G19).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Plane {
    /// G17: arcs in XY, helix axis Z.
    #[default]
    Xy,
    /// G18: arcs in ZX, helix axis Y.
    Zx,
    /// G19: arcs in YZ, helix axis X.
    Yz,
}

impl Plane {
    /// Splits `v` into the two in-plane components (in the right-handed order of the plane:
    /// (x, y) for XY, (z, x) for ZX, (y, z) for YZ) and the axial component.
    pub fn split(self, v: Vec3) -> (f64, f64, f64) {
        match self {
            Plane::Xy => (v.x, v.y, v.z),
            Plane::Zx => (v.z, v.x, v.y),
            Plane::Yz => (v.y, v.z, v.x),
        }
    }

    /// The inverse of [`Plane::split`].
    pub fn join(self, u: f64, v: f64, w: f64) -> Vec3 {
        match self {
            Plane::Xy => Vec3::new(u, v, w),
            Plane::Zx => Vec3::new(v, w, u),
            Plane::Yz => Vec3::new(w, u, v),
        }
    }
}

/// How the controller may treat the corner at the end of a move.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Corner {
    /// Whatever the machine's profile says (its path tolerance).
    #[default]
    Machine,
    /// Exact stop at the end of the move: the axes come to rest in position before the next
    /// move. One notion whichever dialect wrote it: LinuxCNC's `G61.1`, Fanuc's `G61` and
    /// `G09`, Sinumerik's `G60` and `G9` (Grbl has none). What a stop costs beyond coming to
    /// rest (the settling in the controller's exact-stop window) is the machine's, not the
    /// program's: [`crate::machine::Machine::exact_stop_time`].
    ExactStop,
    /// Exact path, no stop required: the corner speed is limited by the axes (LinuxCNC's
    /// `G61`, Sinumerik's `G64` without rounding). The axes may slow down to nearly nothing
    /// at a sharp corner but wait for no exact-stop window.
    ExactPath,
    /// Blend within this tolerance in mm (G64 P).
    Blend(f64),
    /// LinuxCNC's `G64 P p Q q` with a Q other than P: blend within `tolerance` (mm), and
    /// merge runs of G1 moves whose points stay within `merge` (mm) of one straight line into
    /// that line (LinuxCNC's "naive CAM detector"; `G64 P p` alone merges within p). Other
    /// controllers take it as [`Corner::Blend`] of `tolerance`.
    BlendMerge {
        /// Blend tolerance in mm (P).
        tolerance: f64,
        /// Merge tolerance in mm (Q).
        merge: f64,
    },
}

impl Corner {
    /// The blend tolerance of a blend mode (`Blend` and `BlendMerge`), `None` otherwise.
    pub fn blend_tolerance(self) -> Option<f64> {
        match self {
            Corner::Blend(t) | Corner::BlendMerge { tolerance: t, .. } => Some(t),
            _ => None,
        }
    }
}

/// Where a move came from on a source curve: curve index and parameter at the move's end.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct CurveTag {
    /// Index of the curve (or curve piece) in the strategy's input.
    pub curve: u32,
    /// Curve parameter at the end point of the move.
    pub u: f64,
}

/// The kind of a move.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", tag = "type")]
pub enum MoveKind {
    /// G0: as fast as the machine goes, not cutting.
    Rapid,
    /// G1: a straight line at the feed.
    Line,
    /// G2/G3: a circular arc about `center` in `plane`; with a change along the plane's normal
    /// axis it is a helix. An arc whose end equals its start is a full circle; `turns` adds
    /// further full turns (see [`Move::sweep_from`]).
    Arc {
        /// Centre of the arc; its coordinate along the plane's normal is ignored.
        center: Point3,
        /// The plane the arc turns in.
        plane: Plane,
        /// Counter-clockwise (G3) seen from the plane's positive normal.
        ccw: bool,
        /// Full turns added to the sweep (0 for an ordinary arc or a single full circle).
        turns: u32,
    },
    /// G4: stay still for `seconds`.
    Dwell {
        /// Dwell time in s.
        seconds: f64,
    },
}

/// Where the rotary axes A, B and C of a machine with trivkins kinematics stand (each axis
/// its own joint, as LinuxCNC's `trivkins` has them: the program's A/B/C words are the joints'
/// angles, the tool tip is not transformed), in radians.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct Rotary {
    /// A (about X), rad.
    pub a: f64,
    /// B (about Y), rad.
    pub b: f64,
    /// C (about Z), rad.
    pub c: f64,
}

impl Rotary {
    /// A, B and C in rad.
    pub const fn new(a: f64, b: f64, c: f64) -> Rotary {
        Rotary { a, b, c }
    }

    /// `[a, b, c]`.
    pub const fn to_array(self) -> [f64; 3] {
        [self.a, self.b, self.c]
    }

    /// The length of the rotary chord from `from` to `self`, rad: `√(ΔA² + ΔB² + ΔC²)`.
    pub fn distance(self, from: Rotary) -> f64 {
        let d = [self.a - from.a, self.b - from.b, self.c - from.c];
        (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt()
    }
}

/// One move: where it goes, how, and at what feed.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Move {
    /// The kind of move.
    pub kind: MoveKind,
    /// End point in mm.
    pub to: Point3,
    /// Programmed feed in mm/s along the X Y Z path (ignored for rapids and dwells); on a
    /// move of the rotary axes alone, in rad/s along their chord ([`Move::rotary`]).
    pub feed: f64,
    /// How the corner at the end of this move may be blended.
    #[serde(default)]
    pub corner: Corner,
    /// The source curve parameter this move's end point came from, if any.
    #[serde(default)]
    pub tag: Option<CurveTag>,
    /// Where the rotary axes stand at the end of the move; `None`: where they stood (a
    /// three-axis program never sets it).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rotary: Option<Rotary>,
}

impl Move {
    /// A rapid move to `to`.
    pub fn rapid(to: Point3) -> Self {
        Move {
            kind: MoveKind::Rapid,
            to,
            feed: 0.0,
            corner: Corner::Machine,
            tag: None,
            rotary: None,
        }
    }

    /// A straight feed move to `to` at `feed` mm/s.
    pub fn line(to: Point3, feed: f64) -> Self {
        Move {
            kind: MoveKind::Line,
            to,
            feed,
            corner: Corner::Machine,
            tag: None,
            rotary: None,
        }
    }

    /// An arc (or helix, if `to.z` differs from the start) in the XY plane.
    pub fn arc_xy(to: Point3, center: Point3, ccw: bool, feed: f64) -> Self {
        Move {
            kind: MoveKind::Arc {
                center,
                plane: Plane::Xy,
                ccw,
                turns: 0,
            },
            to,
            feed,
            corner: Corner::Machine,
            tag: None,
            rotary: None,
        }
    }

    /// A dwell of `seconds` at `at` (the current position).
    pub fn dwell(at: Point3, seconds: f64) -> Self {
        Move {
            kind: MoveKind::Dwell { seconds },
            to: at,
            feed: 0.0,
            corner: Corner::ExactStop,
            tag: None,
            rotary: None,
        }
    }

    /// This move tagged with a source-curve parameter.
    #[must_use]
    pub fn with_tag(mut self, curve: u32, u: f64) -> Self {
        self.tag = Some(CurveTag { curve, u });
        self
    }

    /// This move with a corner mode.
    #[must_use]
    pub fn with_corner(mut self, corner: Corner) -> Self {
        self.corner = corner;
        self
    }

    /// True when `other` is the same kind of move: both rapids, both lines, both dwells of
    /// the same time (within `eps` s), or both arcs about the same centre (within `eps` mm)
    /// in the same plane, direction and turns (the centre's coordinate along the plane's
    /// normal aside).
    pub fn kind_matches(&self, other: &Move, eps: f64) -> bool {
        match (self.kind, other.kind) {
            (MoveKind::Rapid, MoveKind::Rapid) | (MoveKind::Line, MoveKind::Line) => true,
            (MoveKind::Dwell { seconds: a }, MoveKind::Dwell { seconds: b }) => {
                (a - b).abs() <= eps
            }
            (
                MoveKind::Arc {
                    center: c0,
                    plane: p0,
                    ccw: w0,
                    turns: t0,
                },
                MoveKind::Arc {
                    center: c1,
                    plane: p1,
                    ccw: w1,
                    turns: t1,
                },
            ) => {
                let (u, v, _) = p0.split(c1 - c0);
                p0 == p1 && w0 == w1 && t0 == t1 && u.hypot(v) <= eps
            }
            _ => false,
        }
    }

    /// True for lines and arcs (moves that cut at the feed).
    pub fn is_feed(&self) -> bool {
        matches!(self.kind, MoveKind::Line | MoveKind::Arc { .. })
    }

    /// For an arc starting at `from`: (radius at the start, signed sweep in radians, positive
    /// counter-clockwise). `None` for other moves.
    pub fn sweep_from(&self, from: Point3) -> Option<(f64, f64)> {
        let MoveKind::Arc {
            center,
            plane,
            ccw,
            turns,
        } = self.kind
        else {
            return None;
        };
        let (su, sv, _) = plane.split(from - center);
        let (eu, ev, _) = plane.split(self.to - center);
        let r = su.hypot(sv);
        let a0 = sv.atan2(su);
        let a1 = ev.atan2(eu);
        let mut sweep = if ccw { a1 - a0 } else { a0 - a1 };
        sweep = sweep.rem_euclid(TAU);
        if sweep <= 1e-12 {
            sweep = TAU;
        }
        sweep += TAU * f64::from(turns);
        Some((r, if ccw { sweep } else { -sweep }))
    }

    /// For an arc starting at `from`: its sagitta in mm, the largest distance between the arc
    /// (projected on its plane) and its chord, `r·(1 − cos(θ/2))` for the unsigned sweep
    /// `θ ≤ 2π` (at most `2r`; `2r` for a multi-turn arc), `r` the start radius. A line
    /// from `from` to the end stays within the sagitta of the arc in the plane (for a helix,
    /// the axial travel is shared alike). `None` for other moves.
    pub fn sagitta_from(&self, from: Point3) -> Option<f64> {
        let (r, sweep) = self.sweep_from(from)?;
        let theta = sweep.abs();
        Some(if theta > TAU {
            2.0 * r
        } else {
            r * (1.0 - (0.5 * theta).cos())
        })
    }

    /// This move, or a line to the same end (same feed, corner and tag) when it is an arc
    /// whose sagitta from `from` ([`Move::sagitta_from`]) is at most `max_sagitta` mm: the
    /// line stays within `max_sagitta` of the arc.
    #[must_use]
    pub fn line_if_flat(self, from: Point3, max_sagitta: f64) -> Move {
        match self.sagitta_from(from) {
            Some(s) if s <= max_sagitta => Move {
                kind: MoveKind::Line,
                ..self
            },
            _ => self,
        }
    }

    /// The point at path length `t` (clamped to `[0, length]`) along this move from `from`:
    /// on a line by linear interpolation; on an arc (helix, multi-turn arc) at the fraction
    /// `f = t/length` of its sweep, with the radius and the axial coordinate interpolated
    /// linearly in `f` (the parametrisation of [`Move::length_from`]). A dwell stays at `to`.
    pub fn point_at(&self, from: Point3, t: f64) -> Point3 {
        let len = self.length_from(from);
        let f = if len > 0.0 {
            (t / len).clamp(0.0, 1.0)
        } else {
            1.0
        };
        match (self.kind, self.sweep_from(from)) {
            (MoveKind::Arc { center, plane, .. }, Some((r0, sweep))) => {
                let (su, sv, sw) = plane.split(from - center);
                let (eu, ev, ew) = plane.split(self.to - center);
                let r = r0 + (eu.hypot(ev) - r0) * f;
                let a = sv.atan2(su) + sweep * f;
                center + plane.join(r * a.cos(), r * a.sin(), sw + (ew - sw) * f)
            }
            (MoveKind::Dwell { .. }, _) => self.to,
            _ => from.lerp(self.to, f),
        }
    }

    /// The piece of this move (from `from`) between path lengths `t0 < t1`: a line for a
    /// line (or rapid), an arc about the same centre for an arc (its full turns counted in
    /// `turns`), same feed, corner and tag; it starts at [`Move::point_at`]`(from, t0)`.
    /// Exact arcs stay exact arcs.
    pub fn piece(&self, from: Point3, t0: f64, t1: f64) -> Move {
        let to = self.point_at(from, t1);
        let kind = match (self.kind, self.sweep_from(from)) {
            (
                MoveKind::Arc {
                    center, plane, ccw, ..
                },
                Some((_, sweep)),
            ) => {
                let len = self.length_from(from);
                let part = if len > 0.0 {
                    sweep.abs() * ((t1 - t0) / len).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                // `sweep_from` reads an end on the start as one full turn.
                let full = (part / TAU).floor();
                let turns = if part - full * TAU <= 1e-12 {
                    full - 1.0
                } else {
                    full
                };
                MoveKind::Arc {
                    center,
                    plane,
                    ccw,
                    turns: turns.max(0.0) as u32,
                }
            }
            (k, _) => k,
        };
        Move { kind, to, ..*self }
    }

    /// Path length of this move starting from `from`, in mm (helices included).
    ///
    /// An arc whose end is not exactly on its start circle (G-code rounds coordinates; the
    /// reader accepts LinuxCNC's tolerance) is the spiral whose radius changes linearly with
    /// the angle; its length is taken as `r̄·|sweep|` (hypot the axial travel) with `r̄` the
    /// mean of the start and end radii: exact for a circle, and the nominal length by which
    /// the planner and the verifier both parametrise the spiral.
    pub fn length_from(&self, from: Point3) -> f64 {
        match self.kind {
            MoveKind::Rapid | MoveKind::Line => from.distance(self.to),
            MoveKind::Dwell { .. } => 0.0,
            MoveKind::Arc { plane, center, .. } => {
                let (r0, sweep) = self.sweep_from(from).unwrap_or((0.0, 0.0));
                let (eu, ev, _) = plane.split(self.to - center);
                let r1 = eu.hypot(ev);
                let (_, _, axial) = plane.split(self.to - from);
                (0.5 * (r0 + r1) * sweep).hypot(axial)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn arc_sweep_and_length() {
        let from = Point3::new(10.0, 0.0, 0.0);
        let c = Point3::ORIGIN;
        let quarter_ccw = Move::arc_xy(Point3::new(0.0, 10.0, 0.0), c, true, 1.0);
        let (r, s) = quarter_ccw.sweep_from(from).unwrap();
        assert!((r - 10.0).abs() < 1e-12 && (s - PI / 2.0).abs() < 1e-12);
        let three_quarter_cw = Move::arc_xy(Point3::new(0.0, 10.0, 0.0), c, false, 1.0);
        let (_, s) = three_quarter_cw.sweep_from(from).unwrap();
        assert!((s + 1.5 * PI).abs() < 1e-12);
        let full = Move::arc_xy(from, c, true, 1.0);
        assert!((full.length_from(from) - 20.0 * PI).abs() < 1e-9);
        let helix = Move::arc_xy(Point3::new(10.0, 0.0, -3.0), c, true, 1.0);
        assert!((helix.length_from(from) - (20.0 * PI).hypot(3.0)).abs() < 1e-9);
    }

    #[test]
    fn sagitta_of_arcs() {
        let from = Point3::new(10.0, 0.0, 0.0);
        let c = Point3::ORIGIN;
        let quarter = Move::arc_xy(Point3::new(0.0, 10.0, 0.0), c, true, 1.0);
        let s = quarter.sagitta_from(from).unwrap();
        assert!((s - 10.0 * (1.0 - (PI / 4.0).cos())).abs() < 1e-12);
        // The chord's midpoint is the sagitta away from the arc's midpoint.
        let mid = Point3::new(10.0 * (PI / 4.0).cos(), 10.0 * (PI / 4.0).sin(), 0.0);
        assert!((from.lerp(quarter.to, 0.5).distance(mid) - s).abs() < 1e-12);
        let full = Move::arc_xy(from, c, true, 1.0);
        assert!((full.sagitta_from(from).unwrap() - 20.0).abs() < 1e-12);
        let three_quarter = Move::arc_xy(Point3::new(0.0, 10.0, 0.0), c, false, 1.0);
        assert!(three_quarter.sagitta_from(from).unwrap() > 10.0);
        assert!(Move::line(from, 1.0).sagitta_from(Point3::ORIGIN).is_none());
    }

    #[test]
    fn pieces_of_lines_arcs_and_helices_join_up_and_keep_the_length() {
        let from = Point3::new(10.0, 0.0, 0.0);
        let c = Point3::ORIGIN;
        let moves = [
            Move::line(Point3::new(4.0, 7.0, -2.0), 3.0),
            Move::arc_xy(Point3::new(0.0, 10.0, 0.0), c, true, 3.0),
            Move::arc_xy(Point3::new(0.0, 10.0, -6.0), c, false, 3.0),
            Move {
                kind: MoveKind::Arc {
                    center: c,
                    plane: Plane::Xy,
                    ccw: true,
                    turns: 2,
                },
                ..Move::arc_xy(Point3::new(0.0, -10.0, -9.0), c, true, 3.0)
            },
            Move {
                kind: MoveKind::Arc {
                    center: Point3::new(10.0, 0.0, 5.0),
                    plane: Plane::Zx,
                    ccw: true,
                    turns: 0,
                },
                ..Move::line(Point3::new(10.0, 3.0, 10.0), 3.0)
            },
        ];
        for m in moves {
            let len = m.length_from(from);
            let cuts = [0.0, 0.13 * len, 0.5 * len, 0.51 * len, len];
            let mut at = from;
            let mut total = 0.0;
            for w in cuts.windows(2) {
                let p = m.piece(from, w[0], w[1]);
                assert!(at.distance(m.point_at(from, w[0])) < 1e-9, "{m:?}");
                let l = p.length_from(at);
                assert!((l - (w[1] - w[0])).abs() < 1e-9, "{m:?}: {l} {w:?}");
                // Every point of the piece is the move's point at the same length.
                for f in [0.25, 0.5, 0.75] {
                    let q = p.point_at(at, f * l);
                    let want = m.point_at(from, w[0] + f * l);
                    assert!(q.distance(want) < 1e-9, "{m:?} {w:?} {f}");
                }
                total += l;
                at = p.to;
            }
            assert!(
                at.distance(m.to) < 1e-9 && (total - len).abs() < 1e-9,
                "{m:?}"
            );
        }
    }

    #[test]
    fn plane_split_join_round_trip() {
        let v = Vec3::new(1.0, 2.0, 3.0);
        for p in [Plane::Xy, Plane::Zx, Plane::Yz] {
            let (a, b, c) = p.split(v);
            assert_eq!(p.join(a, b, c), v);
        }
    }
}
