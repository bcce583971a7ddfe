//! The offset moves and their corners: LinuxCNC's `convert_straight_comp1/2`,
//! `convert_arc_comp1/2` and `move_endpoint_and_flush`, in the plane's (u, v) coordinates
//! (X Y in G17, Z X in G18) and machine millimetres. Angles and their tolerances are
//! LinuxCNC's; see the parent module.

use super::{Comp, Queued, ReadMove, Side, refuse};
use crate::gcode::arc::center_arc_radius_tolerance_mm;
use crate::gcode::dialect::Units;
use crate::gcode::interp::BlockError;
use crate::geom::Point3;
use crate::toolpath::MoveKind;
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// LinuxCNC's `TOLERANCE_CONCAVE_CORNER` (rad).
const SMALL: f64 = 0.05;
/// LinuxCNC's `TOLERANCE_EQUAL`.
const EQUAL: f64 = 1e-6;

const GOUGE: &str = "a corner the tool fits in (a tool smaller than the corner, or no \
                     compensation there)";

/// A queued arc's centre, end and turn.
type FrontArc = ((f64, f64), (f64, f64), i32);

fn hypot(a: (f64, f64), b: (f64, f64)) -> f64 {
    (a.0 - b.0).hypot(a.1 - b.1)
}

fn dir(from: (f64, f64), to: (f64, f64)) -> f64 {
    (to.1 - from.1).atan2(to.0 - from.0)
}

fn polar(c: (f64, f64), r: f64, a: f64) -> (f64, f64) {
    (c.0 + r * a.cos(), c.1 + r * a.sin())
}

/// LinuxCNC's `find_turn`: the signed sweep (rad) of an arc of `turn` turns (> 0 CCW).
fn find_turn(s: (f64, f64), c: (f64, f64), turn: i32, e: (f64, f64)) -> f64 {
    if turn == 0 {
        return 0.0;
    }
    let mut alpha = dir(c, s);
    let mut beta = dir(c, e);
    if turn > 0 {
        if beta <= alpha {
            beta += TAU;
        }
        beta - alpha + f64::from(turn - 1) * TAU
    } else {
        if alpha <= beta {
            alpha += TAU;
        }
        beta - alpha + f64::from(turn + 1) * TAU
    }
}

/// The signed turn count of an arc move (LinuxCNC's `turn`: ±(turns + 1), + for CCW).
fn turn_of(kind: &MoveKind) -> Option<(Point3, i32)> {
    match *kind {
        MoveKind::Arc {
            center, ccw, turns, ..
        } => {
            let n = i32::try_from(turns).unwrap_or(i32::MAX - 1) + 1;
            Some((center, if ccw { n } else { -n }))
        }
        _ => None,
    }
}

/// The tool is on the inside of an arc turning `turn` (LinuxCNC's `TOOL_INSIDE_ARC`).
fn inside(side: Side, turn: i32) -> bool {
    (side == Side::Left && turn > 0) || (side == Side::Right && turn < 0)
}

fn too_small() -> BlockError {
    refuse(
        "tool radius not less than arc radius with comp",
        "an arc larger than the tool on the side the tool is (inside arcs > tool radius)",
    )
}

impl Comp {
    fn side(&self) -> Side {
        self.side.unwrap_or(Side::Left)
    }

    /// The first queued move, if it is an arc: its centre, end and turn.
    fn front_arc(&self) -> Option<FrontArc> {
        let q = self.queue.first()?;
        let (c, turn) = turn_of(&q.rm.mv.kind)?;
        Some((self.uv(c), self.uv(q.rm.mv.to), turn))
    }

    /// The entry line (`convert_straight_comp1`).
    pub(super) fn straight_entry(&mut self, rm: ReadMove, from: Point3) -> Result<(), BlockError> {
        let c = self.uv(from);
        let p = self.uv(rm.mv.to);
        let r = self.radius;
        if hypot(p, c) <= r {
            return Err(refuse(
                "length of cutter compensation entry move is not greater than the tool radius",
                format!("an entry move longer than the tool radius ({r} mm)").as_str(),
            ));
        }
        let alpha = dir(c, p)
            + match self.side() {
                Side::Left => FRAC_PI_2,
                Side::Right => -FRAC_PI_2,
            };
        let end = polar(p, r, alpha);
        self.set_endpoint(c);
        let mut m = rm;
        m.mv.to = self.with_uv(rm.mv.to, end);
        self.enqueue(m, (alpha.cos(), alpha.sin()), 0.0);
        self.first = false;
        self.current = m.mv.to;
        Ok(())
    }

    /// A line after the entry (`convert_straight_comp2`).
    pub(super) fn straight(
        &mut self,
        rm: ReadMove,
        from: Point3,
        units: Units,
        out: &mut Vec<ReadMove>,
    ) -> Result<(), BlockError> {
        let c = self.uv(self.current);
        let op = self.uv(from);
        let p = self.uv(rm.mv.to);
        let rapid = rm.mv.kind == MoveKind::Rapid;
        if p == op {
            // No motion in the plane: straight along the normal where the tool is.
            let mut m = rm;
            m.mv.to = self.with_uv(rm.mv.to, c);
            self.enqueue(m, (0.0, 0.0), 0.0);
            self.current = m.mv.to;
            return Ok(());
        }
        let side = self.side();
        let r = self.radius;
        let mut theta = dir(op, c);
        let mut alpha = dir(op, p);
        let (beta, gamma) = match side {
            Side::Left => {
                if theta < alpha {
                    theta += TAU;
                }
                (theta - alpha - FRAC_PI_2, FRAC_PI_2)
            }
            Side::Right => {
                if alpha < theta {
                    alpha += TAU;
                }
                (alpha - theta - FRAC_PI_2, -FRAC_PI_2)
            }
        };
        let end = polar(p, r, alpha + gamma);
        let mid = polar(op, r, alpha + gamma);
        let front = self.front_arc();
        let concave = !(-SMALL..=PI + SMALL).contains(&beta)
            || (beta > PI - SMALL
                && front.is_some_and(|(_, _, turn)| {
                    (side == Side::Right && turn > 0) || (side == Side::Left && turn < 0)
                }));
        if !concave && beta > SMALL {
            // Convex: round the corner about the programmed point.
            self.move_endpoint_and_flush(c, units, out)?;
            let mut m = rm;
            let cz = self.with_uv(self.current, mid);
            m.mv.to = cz;
            if rapid {
                self.enqueue(m, (0.0, 0.0), 0.0);
            } else {
                let ccw = side == Side::Right;
                m.mv.kind = MoveKind::Arc {
                    center: self.with_uv(self.current, op),
                    plane: self.plane,
                    ccw,
                    turns: 0,
                };
                self.enqueue(m, (0.0, 0.0), 0.0);
            }
            self.dequeue(out);
            self.set_endpoint(mid);
        } else if concave {
            let cut = match front {
                None => {
                    // line → line: back along the previous offset line.
                    let halfcorner = (beta + PI) / 2.0;
                    if halfcorner == 0.0 {
                        return Err(refuse(
                            "zero degree inside corner is invalid for cutter compensation",
                            GOUGE,
                        ));
                    }
                    let retreat = r / halfcorner.tan();
                    polar(c, retreat, theta + gamma)
                }
                Some((pc, pe, pturn)) => {
                    // arc → line: where the offset line meets the previous offset arc.
                    let oldrad = hypot(pc, pe);
                    let base = dir(op, p);
                    let th = if pturn > 0 {
                        base + FRAC_PI_2
                    } else {
                        base - FRAC_PI_2
                    };
                    let phi = dir(op, pc);
                    let ins = inside(side, pturn);
                    let uncomp = if ins { oldrad + r } else { oldrad - r };
                    let d = uncomp * (th - phi).cos();
                    let l = (if ins { d - r } else { d + r }) / oldrad;
                    if !(-1.0..=1.0).contains(&l) {
                        return Err(refuse(
                            "arc to straight motion makes a corner the compensated tool can't \
                             fit in without gouging",
                            GOUGE,
                        ));
                    }
                    let a = if ins == (pturn > 0) {
                        -l.acos() + th + PI
                    } else {
                        l.acos() + th + PI
                    };
                    polar(pc, oldrad, a)
                }
            };
            self.move_endpoint_and_flush(cut, units, out)?;
        } else {
            self.dequeue(out);
            self.set_endpoint(c);
        }
        let mut m = rm;
        m.mv.to = self.with_uv(rm.mv.to, end);
        self.enqueue(m, (p.0 - op.0, p.1 - op.1), 0.0);
        self.current = m.mv.to;
        Ok(())
    }

    /// The entry arc (`convert_arc_comp1`).
    pub(super) fn arc_entry(
        &mut self,
        rm: ReadMove,
        from: Point3,
        units: Units,
    ) -> Result<(), BlockError> {
        let Some((center3, turn)) = turn_of(&rm.mv.kind) else {
            return Ok(());
        };
        let side = self.side();
        let r = self.radius;
        let c = self.uv(from);
        let e = self.uv(rm.mv.to);
        let center = self.uv(center3);
        if hypot(e, c) <= r {
            return Err(refuse(
                "radius of cutter compensation entry arc is not greater than the tool radius",
                format!("an entry arc whose chord is longer than the tool radius ({r} mm)")
                    .as_str(),
            ));
        }
        if inside(side, turn) && hypot(center, c) <= r {
            return Err(too_small());
        }
        let gamma = if inside(side, turn) {
            dir(e, center)
        } else {
            dir(center, e)
        };
        let end = polar(e, r, gamma);
        let b_len = hypot(c, end) / 2.0;
        let ab = dir(end, center);
        let a = dir(end, c) - ab;
        if a.cos().abs() < EQUAL {
            return Err(too_small());
        }
        let new_center = polar(end, b_len / a.cos(), ab);
        let spiral = center_arc_radius_tolerance_mm(units);
        if (hypot(new_center, end) - hypot(new_center, c)).abs() > spiral {
            return Err(refuse(
                "cutter compensation made an entry arc whose radii differ",
                "an entry arc LinuxCNC can compensate",
            ));
        }
        self.first = false;
        if !matches!(self.orientation, 0 | 9) {
            // LinuxCNC moves the lathe tool's origin first.
            let mut m = rm;
            m.mv.kind = MoveKind::Line;
            m.mv.to = from;
            self.enqueue(m, (0.0, 0.0), 0.0);
            self.set_endpoint(c);
        }
        let mut m = rm;
        m.mv.to = self.with_uv(rm.mv.to, end);
        if let MoveKind::Arc { center: mc, .. } = &mut m.mv.kind {
            *mc = self.with_uv(from, new_center);
        }
        self.enqueue(m, (0.0, 0.0), find_turn(c, new_center, turn, end));
        self.current = m.mv.to;
        Ok(())
    }

    /// An arc after the entry (`convert_arc_comp2`).
    pub(super) fn arc(
        &mut self,
        rm: ReadMove,
        from: Point3,
        units: Units,
        out: &mut Vec<ReadMove>,
    ) -> Result<(), BlockError> {
        let Some((center3, turn)) = turn_of(&rm.mv.kind) else {
            return Ok(());
        };
        let side = self.side();
        let r = self.radius;
        let op = self.uv(from);
        let c = self.uv(self.current);
        let e = self.uv(rm.mv.to);
        let center = self.uv(center3);
        let ccw = turn > 0;
        let arc_radius = hypot(center, e);
        let theta = dir(op, c)
            + match side {
                Side::Left => -FRAC_PI_2,
                Side::Right => FRAC_PI_2,
            };
        let mut delta = dir(op, center);
        let alpha = if ccw {
            delta - FRAC_PI_2
        } else {
            delta + FRAC_PI_2
        };
        let mut beta = match side {
            Side::Left => theta - alpha,
            Side::Right => alpha - theta,
        };
        if beta > 1.5 * PI {
            beta -= TAU;
        } else if beta < -FRAC_PI_2 {
            beta += TAU;
        }
        let ins = inside(side, turn);
        let gamma = if ins {
            if arc_radius <= r {
                return Err(too_small());
            }
            dir(e, center)
        } else {
            delta += PI;
            dir(center, e)
        };
        let new_end = polar(e, r, gamma);
        let mut main = rm;
        main.mv.to = self.with_uv(rm.mv.to, new_end);
        if let MoveKind::Arc { center: mc, .. } = &mut main.mv.kind {
            *mc = self.with_uv(self.current, center);
        }
        let sweep = find_turn(op, center, turn, e);
        if !(-SMALL..=PI + SMALL).contains(&beta) || ((beta - PI).abs() < SMALL && !ins) {
            // Concave: cut the previous move back to where the offset arc starts.
            let cut = match self.front_arc() {
                None => {
                    let cy = arc_radius * (beta - FRAC_PI_2).sin();
                    let (dist, toward) = if ins {
                        (arc_radius - r, cy + r)
                    } else {
                        (arc_radius + r, cy - r)
                    };
                    let l = toward / dist;
                    if !(-1.0..=1.0).contains(&l) {
                        return Err(refuse(
                            "arc move in concave corner cannot be reached by the tool without \
                             gouging",
                            GOUGE,
                        ));
                    }
                    let a = match (ins, turn > 0) {
                        (true, true) => theta + l.asin(),
                        (true, false) => theta - l.asin(),
                        (false, true) => theta + PI - l.asin(),
                        (false, false) => theta + PI + l.asin(),
                    };
                    polar(center, dist, a)
                }
                Some((pc, pe, pturn)) => {
                    let oldrad = hypot(pc, pe);
                    let newrad = if ins { arc_radius - r } else { arc_radius + r };
                    let arc_cc = hypot(pc, center);
                    if oldrad == 0.0 || arc_cc == 0.0 {
                        return Err(refuse(
                            "arc to arc motion is invalid because the arcs have the same center",
                            GOUGE,
                        ));
                    }
                    let a = (oldrad * oldrad + arc_cc * arc_cc - newrad * newrad)
                        / (2.0 * oldrad * arc_cc);
                    if !(-1.0..=1.0).contains(&a) {
                        return Err(refuse(
                            "arc to arc motion makes a corner the compensated tool can't fit \
                             in without gouging",
                            GOUGE,
                        ));
                    }
                    let pullback = a.acos();
                    let cc_dir = dir(pc, center);
                    let d = if inside(side, pturn) == (turn > 0) {
                        cc_dir + pullback
                    } else {
                        cc_dir - pullback
                    };
                    polar(pc, oldrad, d)
                }
            };
            self.move_endpoint_and_flush(cut, units, out)?;
            self.enqueue(main, (0.0, 0.0), sweep);
        } else if beta > SMALL {
            // Convex: an arc about the programmed corner first.
            let mid = polar(op, r, delta);
            self.dequeue(out);
            let mut corner = rm;
            corner.mv.to = self.with_uv(self.current, mid);
            corner.mv.kind = MoveKind::Arc {
                center: self.with_uv(self.current, op),
                plane: self.plane,
                ccw: side == Side::Right,
                turns: 0,
            };
            self.enqueue(corner, (0.0, 0.0), 0.0);
            self.dequeue(out);
            self.set_endpoint(mid);
            self.enqueue(main, (0.0, 0.0), sweep);
        } else {
            self.dequeue(out);
            self.set_endpoint(c);
            self.enqueue(main, (0.0, 0.0), sweep);
        }
        self.current = main.mv.to;
        Ok(())
    }

    /// Moves the end of every queued move to `to` and puts them out
    /// (`move_endpoint_and_flush`), refusing a cut-back that gouges.
    pub(super) fn move_endpoint_and_flush(
        &mut self,
        to: (f64, f64),
        units: Units,
        out: &mut Vec<ReadMove>,
    ) -> Result<(), BlockError> {
        if self.queue.is_empty() {
            return Ok(());
        }
        let unit = units.mm_per_unit();
        // LinuxCNC compares sweeps (rad) with .0254 in mm and .001 in inches.
        let sweep_slack = if units == Units::Mm { 0.0254 } else { 0.001 };
        let mut queue = std::mem::take(&mut self.queue);
        for q in &mut queue {
            let Queued {
                rm,
                dir: d,
                original_turns,
            } = q;
            match turn_of(&rm.mv.kind) {
                Some((c3, turn)) => {
                    let c = self.uv(c3);
                    let r1 = hypot(self.uv(rm.mv.to), c);
                    let r2 = hypot(to, c);
                    let l2 = find_turn(self.endpoint, c, turn, to);
                    if (r1 - r2).abs() > 0.01 * unit {
                        return Err(refuse(
                            &format!(
                                "cutter compensation made an arc with mismatched radii \
                                 {r1:.4} and {r2:.4} mm"
                            ),
                            GOUGE,
                        ));
                    }
                    if *original_turns != 0.0
                        && self.endpoint_valid
                        && l2.abs() > original_turns.abs() + sweep_slack
                    {
                        return Err(refuse(
                            "arc move in concave corner cannot be reached by the tool without \
                             gouging",
                            GOUGE,
                        ));
                    }
                }
                None if matches!(rm.mv.kind, MoveKind::Dwell { .. }) => continue,
                None => {
                    let dot = d.0 * (to.0 - self.endpoint.0) + d.1 * (to.1 - self.endpoint.1);
                    if self.endpoint_valid && dot < 0.0 {
                        let what = if rm.mv.kind == MoveKind::Rapid {
                            "straight traverse"
                        } else {
                            "straight feed"
                        };
                        return Err(refuse(
                            &format!(
                                "{what} in concave corner cannot be reached by the tool \
                                 without gouging"
                            ),
                            GOUGE,
                        ));
                    }
                }
            }
            rm.mv.to = self.with_uv(rm.mv.to, to);
        }
        self.queue = queue;
        self.dequeue(out);
        self.set_endpoint(to);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn find_turn_follows_linuxcnc() {
        let c = (0.0, 0.0);
        // A quarter turn CCW, and the same ends CW (three quarters).
        assert!((find_turn((1.0, 0.0), c, 1, (0.0, 1.0)) - FRAC_PI_2).abs() < 1e-12);
        assert!((find_turn((1.0, 0.0), c, -1, (0.0, 1.0)) + 1.5 * PI).abs() < 1e-12);
        // A full circle, and a second turn.
        assert!((find_turn((1.0, 0.0), c, 1, (1.0, 0.0)) - TAU).abs() < 1e-12);
        assert!((find_turn((1.0, 0.0), c, 2, (0.0, 1.0)) - (TAU + FRAC_PI_2)).abs() < 1e-12);
        assert!(find_turn((1.0, 0.0), c, 0, (0.0, 1.0)).abs() < 1e-300);
    }

    #[test]
    fn the_tool_is_inside_a_left_ccw_arc() {
        assert!(inside(Side::Left, 1));
        assert!(inside(Side::Right, -1));
        assert!(!inside(Side::Left, -2));
        assert!(!inside(Side::Right, 1));
    }
}
