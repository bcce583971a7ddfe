//! The motion part of a block: G0/G1/G2/G3 and G80, targets, feeds and arc centres.

use super::cycles::is_cycle;
use super::{Block, BlockError, FeedMode, ReadMove, ReaderOptions, State, arc_error, plane_axes};
use crate::gcode::Dialect;
use crate::gcode::arc;
use crate::geom::Point3;
use crate::toolpath::{Corner, Move, MoveKind, Rotary};

fn at(a: &[f64; 3], k: usize) -> f64 {
    a.get(k).copied().unwrap_or(0.0)
}

impl State {
    /// Executes the motion of `b` (after the modal groups); `block_f` is the block's F in G93.
    pub(crate) fn motion(
        &mut self,
        b: &mut Block,
        block_f: Option<f64>,
        line: usize,
        opts: &ReaderOptions,
        out: &mut Vec<ReadMove>,
    ) -> Result<(), BlockError> {
        let mut code = None;
        for &(g, _) in &b.g {
            let linuxcnc = opts.dialect == Dialect::LinuxCnc;
            if matches!(g, 0 | 10 | 20 | 30 | 800 | 52 | 53)
                || (linuxcnc && matches!(g, 50 | 51 | 62 | 330 | 331 | 382..=385))
                || is_cycle(g)
            {
                // G80 with another motion code: the other one wins (LinuxCNC's read_g).
                if g == 800 && code.is_some() {
                    continue;
                }
                if code.is_some_and(|c| c != 800) {
                    return Err(BlockError::new(
                        "G-code block",
                        "two motion codes",
                        "at most one of G0, G1, G2, G3, G80 per block",
                    ));
                }
                code = Some(g);
            }
        }
        let previous = self.motion;
        if self.g6_open() && code.is_some_and(|c| c != 62) {
            return Err(BlockError::new(
                "G6.2 curve",
                "not complete before another motion code",
                "G6.2 entries up to the last P equal knots K (the curve's end)",
            ));
        }
        if let Some(c) = code {
            self.motion = (c != 800).then_some(c);
        }
        let g53 = b.has_g(530);
        if self.motion == Some(53) {
            self.motion = None;
            return self.nurbs_end(previous, line, out);
        }
        if let Some(m @ (50 | 51)) = self.motion
            && opts.dialect == Dialect::LinuxCnc
        {
            let axes = [b.take(b'X'), b.take(b'Y'), b.take(b'Z')];
            if code.is_none() && axes.iter().all(Option::is_none) {
                return Ok(());
            }
            if code.is_none() {
                return Err(BlockError::new(
                    "spline block",
                    "without G5/G5.1",
                    "G5 or G5.1 in every spline block (LinuxCNC refuses their words alone)",
                ));
            }
            return self.spline(m, previous, b, axes, line, out);
        }
        if self.motion == Some(62) {
            let axes = [b.take(b'X'), b.take(b'Y'), b.take(b'Z')];
            if g53 || b.polar.iter().any(Option::is_some) {
                return Err(BlockError::unsupported(
                    "G53 or polar words in a G6.2 block",
                    "axis words of the plane, R, K, P and Q in a G6.2 block",
                ));
            }
            return self.g6_block(b, axes, line, out);
        }
        if self.motion == Some(52) {
            let axes = [b.take(b'X'), b.take(b'Y'), b.take(b'Z')];
            if code.is_none() && axes.iter().all(Option::is_none) {
                return Ok(());
            }
            if g53 || b.polar.iter().any(Option::is_some) {
                return Err(BlockError::unsupported(
                    "G53 or polar words in a NURBS block",
                    "X, Y, P and L in a NURBS block",
                ));
            }
            return self.nurbs_block(previous == Some(52), b, axes);
        }
        if let Some(m) = self.motion
            && is_cycle(m)
        {
            let axes = [b.take(b'X'), b.take(b'Y'), b.take(b'Z')];
            let polar = std::mem::take(&mut b.polar);
            let words = axes.iter().any(Option::is_some) || polar.iter().any(Option::is_some);
            if code != Some(m) && !words {
                return Ok(());
            }
            if g53 {
                return Err(BlockError::new(
                    "canned cycle",
                    "with G53",
                    "a canned cycle without G53",
                ));
            }
            if self.rotation() != 0.0 {
                return Err(BlockError::unsupported(
                    "a canned cycle in a rotated system",
                    "canned cycles in systems without rotation (G10 L2 R0)",
                ));
            }
            return self.cycle(
                m,
                previous == Some(m),
                b,
                axes,
                polar,
                line,
                opts.dialect,
                out,
            );
        }
        if code.is_some() {
            self.cyc.end_run();
        }
        let mut axes = [b.take(b'X'), b.take(b'Y'), b.take(b'Z')];
        let polar = std::mem::take(&mut b.polar);
        if polar.iter().any(Option::is_some) {
            if g53 {
                return Err(BlockError::new(
                    "polar coordinates",
                    "with G53",
                    "@ and ^ without G53 (LinuxCNC's find_ends)",
                ));
            }
            let (x, y) = self.polar_end(polar, &mut axes)?;
            // The end as absolute program coordinates: taken below as G90 words.
            axes[0] = Some(x);
            axes[1] = Some(y);
        }
        let polar_absolute = polar.iter().any(Option::is_some);
        // Rotary axes (LinuxCNC): the move happens, its X Y Z part is the path.
        let rotary = [b.take(b'A'), b.take(b'B'), b.take(b'C')];
        let has_axes = axes.iter().chain(&rotary).any(Option::is_some);
        let sync = match self.motion {
            Some(m @ (330 | 331)) if has_axes || code == Some(m) => Some(self.sync_words(m, b)?),
            _ => None,
        };
        let ijk = [b.take(b'I'), b.take(b'J'), b.take(b'K')];
        let r = b.take(b'R');
        let is_arc = matches!(self.motion, Some(20 | 30));
        let arc_words = ijk.iter().any(Option::is_some) || r.is_some();
        let p = if is_arc { b.take(b'P') } else { None };
        let turn = b.turn.take();
        while let Some((l, v)) = b.leftover() {
            let word = format!("{}{v}", char::from(l));
            let expected = "a word this block uses (this one has no effect here)";
            if !opts.lenient {
                return Err(BlockError {
                    unsupported: true,
                    ..BlockError::new("G-code word", word, expected)
                });
            }
            self.notes.push(format!("skipped {word} ({expected})"));
            b.take(l);
        }
        // LinuxCNC moves on a G0 or G1 without axis words too: to where the tool is
        // (`convert_straight`; rs274 prints the zero-length STRAIGHT_TRAVERSE/FEED).
        let in_place =
            opts.dialect == Dialect::LinuxCnc && matches!(code, Some(0 | 10)) && !arc_words;
        let moves = has_axes || in_place || (is_arc && code.is_some() && arc_words);
        if !moves {
            if arc_words && is_arc {
                return Err(BlockError::new(
                    "G-code word",
                    if r.is_some() { "R" } else { "I/J/K" },
                    "arc words with axis words, or with G2/G3 in the block for a full circle",
                ));
            }
            if arc_words && !is_arc {
                return Err(BlockError::new(
                    "G-code word",
                    if r.is_some() { "R" } else { "I/J/K" },
                    "arc words only with G2/G3",
                ));
            }
            return Ok(());
        }
        let Some(motion) = self.motion else {
            return Err(BlockError::new(
                "G-code block",
                "axis words without a motion mode",
                "G0, G1, G2 or G3 in effect (not after G80 or before the first motion code)",
            ));
        };
        if !is_arc && arc_words {
            return Err(BlockError::new(
                "G-code word",
                if r.is_some() { "R" } else { "I/J/K" },
                "arc words only with G2/G3",
            ));
        }
        if g53 && !self.modal.absolute {
            return Err(BlockError::new("G53", "in G91", "G53 with G90"));
        }
        let unit = self.unit();
        let offset = self.origin + self.g92 + self.tool_offset;
        let off = [offset.x, offset.y, offset.z];
        let cur = [self.pos.x, self.pos.y, self.pos.z];
        let mut target = cur;
        for (k, v) in axes.iter().enumerate() {
            if let (Some(v), Some(t)) = (v, target.get_mut(k)) {
                let absolute = self.modal.absolute || (polar_absolute && k < 2);
                *t = if !absolute {
                    at(&cur, k) + v * unit
                } else if g53 {
                    v * unit
                } else {
                    v * unit + at(&off, k)
                };
            }
        }
        let rotated = self.rotation() != 0.0 && !g53;
        let mut ijk = ijk;
        if rotated && self.g92 != crate::geom::Vec3::ZERO {
            return Err(BlockError::unsupported(
                "a G92 offset in a rotated system",
                "rotated systems without a G92 offset (LinuxCNC re-bases its position without \
                 it when a system is rotated)",
            ));
        }
        if rotated {
            // In the rotated frame: the end, and the centre offsets (module `rotation`).
            let pp = self.program_mm();
            let mut p = pp;
            for (k, v) in axes.iter().enumerate() {
                if let (Some(v), Some(t), Some(c)) = (v, p.get_mut(k), pp.get(k)) {
                    let absolute = self.modal.absolute || (polar_absolute && k < 2);
                    *t = if absolute { v * unit } else { c + v * unit };
                }
            }
            let m = self.program_to_machine(p);
            target = [m.x, m.y, m.z];
            if is_arc && arc_words {
                if self.modal.plane != crate::toolpath::Plane::Xy {
                    return Err(BlockError::unsupported(
                        "an arc outside G17 in a rotated system",
                        "arcs in the XY plane (G17) while the system is rotated",
                    ));
                }
                let (i, j) = (ijk[0].unwrap_or(0.0), ijk[1].unwrap_or(0.0));
                let (ri, rj) = if self.arc_absolute {
                    // centre = rot(IJ + G92) + origin + tool; arc_kind adds origin + G92 + tool.
                    let (gx, gy) = (self.g92.x / unit, self.g92.y / unit);
                    let (x, y) = super::rotation::rotate(i + gx, j + gy, self.rotation());
                    (x - gx, y - gy)
                } else {
                    super::rotation::rotate(i, j, self.rotation())
                };
                if ijk[0].is_some() || ijk[1].is_some() {
                    ijk[0] = Some(ri);
                    ijk[1] = Some(rj);
                }
            }
        }
        let to = Point3::new(target[0], target[1], target[2]);
        // The rotary axes (degrees in the program; offsets do not move them).
        let turned = rotary.iter().any(Option::is_some);
        let r0 = self.rotary.to_array();
        let r1: [f64; 3] = std::array::from_fn(|k| match rotary.get(k).copied().flatten() {
            Some(v) if self.modal.absolute || g53 => v.to_radians(),
            Some(v) => at(&r0, k) + v.to_radians(),
            None => at(&r0, k),
        });
        let rot_to = Rotary::new(r1[0], r1[1], r1[2]);
        let rot_len = rot_to.distance(self.rotary);
        let corner = if b.has_g(90) {
            Corner::ExactStop
        } else {
            self.modal.corner
        };
        let kind = match motion {
            0 => MoveKind::Rapid,
            10 | 330 | 331 | 382..=385 => MoveKind::Line,
            _ => self.arc_kind(motion == 30, &cur, &target, ijk, r, p, turn, &off)?,
        };
        let mut mv = Move {
            kind,
            to,
            feed: 0.0,
            corner,
            tag: None,
            rotary: turned.then_some(rot_to),
        };
        if mv.is_feed() {
            mv.feed = match sync {
                Some(s) => self.sync_feed(s)?,
                None => self.feed_for(&mv, block_f, rot_len)?,
            };
        }
        let centre_ok = match mv.kind {
            MoveKind::Arc { center, .. } => center.is_finite(),
            _ => true,
        };
        if !(to.is_finite() && centre_ok && mv.feed.is_finite()) {
            return Err(BlockError::new(
                "G-code block",
                "coordinates or feed out of range",
                "finite positions, centres and feeds",
            ));
        }
        if (382..=385).contains(&motion) {
            return self.probe(motion, mv, line, out);
        }
        self.pos = to;
        self.rotary = rot_to;
        out.push(ReadMove {
            mv,
            line,
            modal: self.modal,
        });
        if motion == 331 {
            self.tap_retract(Point3::new(cur[0], cur[1], cur[2]), sync, line, out);
        }
        Ok(())
    }

    /// The end of a polar move in program coordinates (X, Y; program units), LinuxCNC's
    /// `find_ends`: in G90 `@ ^` is the point at radius @ and angle ^ about the program origin,
    /// `@` alone keeps the angle and `^` alone the radius of the present position; in G91 `@`
    /// adds to the radius and `^` to the angle, both about the origin.
    fn polar_end(
        &self,
        polar: [Option<f64>; 2],
        axes: &mut [Option<f64>; 3],
    ) -> Result<(f64, f64), BlockError> {
        if axes[0].is_some() || axes[1].is_some() {
            return Err(BlockError::new(
                "polar coordinates",
                "with X or Y",
                "@ and ^ without X and Y words",
            ));
        }
        let [px, py, _] = self.program_position();
        let at_origin = px == 0.0 && py == 0.0;
        let (r0, t0) = (px.hypot(py), py.atan2(px));
        let indeterminate = || {
            BlockError::new(
                "polar coordinates",
                "at the program origin",
                "an angle ^ (the angle at the origin is indeterminate)",
            )
        };
        let (r, t) = match (polar[0], polar[1], self.modal.absolute) {
            (Some(r), Some(t), true) => (r, t.to_radians()),
            (Some(r), None, true) => {
                if at_origin {
                    return Err(indeterminate());
                }
                (r, t0)
            }
            (None, Some(t), true) => (r0, t.to_radians()),
            (r, t, false) => {
                if at_origin {
                    return Err(indeterminate());
                }
                (r0 + r.unwrap_or(0.0), t0 + t.unwrap_or(0.0).to_radians())
            }
            (None, None, true) => (r0, t0),
        };
        Ok((r * t.cos(), r * t.sin()))
    }

    /// G4's time in seconds: `P` s (Fanuc: ms), Fanuc's `X` s, Sinumerik's `F` s.
    pub(crate) fn dwell_seconds(&self, b: &mut Block, dialect: Dialect) -> Result<f64, BlockError> {
        let p = b.take(b'P');
        let x = if dialect == Dialect::Fanuc {
            b.take(b'X')
        } else {
            None
        };
        let f = if dialect == Dialect::Sinumerik {
            b.take(b'F')
        } else {
            None
        };
        let seconds = match (p, x, f) {
            (Some(p), None, None) if dialect == Dialect::Fanuc => p / 1000.0,
            (Some(s), None, None) | (None, Some(s), None) | (None, None, Some(s)) => s,
            _ => {
                return Err(BlockError::new(
                    "dwell",
                    "G4",
                    match dialect {
                        Dialect::Fanuc => "one of G04 X (s) or G04 P (ms)",
                        Dialect::Sinumerik => "G4 F (s)",
                        _ => "G4 P (s)",
                    },
                ));
            }
        };
        if seconds < 0.0 {
            return Err(BlockError::new("dwell", seconds, "a time >= 0 s"));
        }
        Ok(seconds)
    }

    /// The feed of `mv`, which also turns the rotary axes by `rot_len` rad: mm/s along its
    /// X Y Z path, or on a move of the rotary axes alone rad/s along their chord.
    fn feed_for(&self, mv: &Move, block_f: Option<f64>, rot_len: f64) -> Result<f64, BlockError> {
        let xyz = mv.length_from(self.pos);
        let rotary_only = xyz <= 0.0 && rot_len > 0.0;
        match self.modal.feed_mode {
            // `SET_FEED_RATE`: the angular feed is F in degrees/min whatever the length units.
            FeedMode::PerMinute if rotary_only => match self.feed {
                Some(f) if f > 0.0 => Ok((self.f_word / 60.0).to_radians()),
                _ => self.feed_for(mv, block_f, 0.0),
            },
            FeedMode::InverseTime if rotary_only => match block_f {
                Some(f) if f > 0.0 => Ok(rot_len * f / 60.0),
                _ => self.feed_for(mv, block_f, 0.0),
            },
            FeedMode::PerMinute => match self.feed {
                Some(f) if f > 0.0 => Ok(f),
                Some(f) => Err(BlockError::new(
                    "feed",
                    format!("F{}", f * 60.0 / self.unit()),
                    "a feed > 0 on a feed move (G1/G2/G3)",
                )),
                None => Err(BlockError::new(
                    "feed",
                    "missing",
                    "an F word before the first feed move (G1/G2/G3), and after G93/G94",
                )),
            },
            FeedMode::PerRevolution => self.per_revolution_feed(),
            FeedMode::InverseTime => match block_f {
                Some(f) if f > 0.0 => Ok(xyz.max(1e-9) * f / 60.0),
                Some(f) => Err(BlockError::new(
                    "inverse-time feed",
                    format!("F{f}"),
                    "F > 0",
                )),
                None => Err(BlockError::new(
                    "inverse-time feed",
                    "missing",
                    "an F word on every feed move in G93",
                )),
            },
        }
    }

    #[allow(clippy::too_many_arguments)]
    fn arc_kind(
        &self,
        ccw: bool,
        cur: &[f64; 3],
        target: &[f64; 3],
        ijk: [Option<f64>; 3],
        r: Option<f64>,
        p: Option<f64>,
        turn: Option<f64>,
        off: &[f64; 3],
    ) -> Result<MoveKind, BlockError> {
        let plane = self.modal.plane;
        let (ua, va, na) = plane_axes(plane);
        let unit = self.unit();
        let s = (at(cur, ua), at(cur, va));
        let e = (at(target, ua), at(target, va));
        let letter = |k: usize| char::from(b"IJK".get(k).copied().unwrap_or(b'I'));
        let center = if let Some(r) = r {
            if ijk.iter().any(Option::is_some) {
                return Err(BlockError::new("arc", "R with I/J/K", "either R or I/J/K"));
            }
            arc::center_from_radius(s, e, r * unit, ccw).map_err(arc_error)?
        } else {
            if ijk.get(na).copied().flatten().is_some() {
                return Err(BlockError::new(
                    "arc",
                    format!("{} word", letter(na)),
                    "only the centre offsets of the active plane's axes",
                ));
            }
            let (iu, iv) = (
                ijk.get(ua).copied().flatten(),
                ijk.get(va).copied().flatten(),
            );
            if iu.is_none() && iv.is_none() {
                return Err(BlockError::new(
                    "arc",
                    "no centre",
                    format!("{} or {} (or R)", letter(ua), letter(va)),
                ));
            }
            let (iu, iv) = (iu.unwrap_or(0.0) * unit, iv.unwrap_or(0.0) * unit);
            let c = if self.arc_absolute {
                (iu + at(off, ua), iv + at(off, va))
            } else {
                (s.0 + iu, s.1 + iv)
            };
            let r1 = (s.0 - c.0).hypot(s.1 - c.1);
            let r2 = (e.0 - c.0).hypot(e.1 - c.1);
            arc::check_radii(r1, r2, self.modal.units).map_err(arc_error)?;
            c
        };
        let turns = match (p, turn) {
            (Some(p), None) if p >= 1.0 && p.fract() == 0.0 && p <= 1e6 => p as u32 - 1,
            (None, Some(t)) if t >= 0.0 && t.fract() == 0.0 && t <= 1e6 => t as u32,
            (None, None) => 0,
            _ => {
                return Err(BlockError::new(
                    "arc turns",
                    format!("{:?}", p.or(turn)),
                    "P = an integer >= 1 (LinuxCNC) or TURN = an integer >= 0 (Sinumerik)",
                ));
            }
        };
        let mut cc = [0.0; 3];
        if let Some(x) = cc.get_mut(ua) {
            *x = center.0;
        }
        if let Some(x) = cc.get_mut(va) {
            *x = center.1;
        }
        if let Some(x) = cc.get_mut(na) {
            *x = at(cur, na);
        }
        Ok(MoveKind::Arc {
            center: Point3::new(cc[0], cc[1], cc[2]),
            plane,
            ccw,
            turns,
        })
    }
}
