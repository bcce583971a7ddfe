//! Canned cycles G73, G81, G82, G83, G85, G89 with G98/G99, expanded into the moves LinuxCNC
//! 2.9 makes (`interp_cycles.cc`: `convert_cycle`, `convert_cycle_xy`, `CYCLE_MACRO`).
//!
//! In the active plane (u, v; the normal axis n is "Z" of the XY plane), in program
//! coordinates:
//!
//! * The initial level is the n position when the first cycle of a run of cycles began
//!   (kept until a motion that is not a cycle). G98 retracts to it (when above R), G99 (the
//!   default) to R.
//! * G90: R and Z (the n word) are absolute; G91: R is an increment from the initial level,
//!   Z one from R, and X/Y (or `@`/`^`) increments applied on each of the L repeats.
//! * R, Z, P, Q are modal within a run of the same cycle; a new cycle needs R and Z. R below Z,
//!   L = 0 and Q ≤ 0 are refused, as are inverse-time feed and a zero feed.
//! * A start below R first rapids up to R. Each repeat goes across at the retract level
//!   (the first one, when it starts above R, at its own level) and rapids down to R.
//! * Bodies: G81 feed to Z, rapid out; G82 adds a dwell P at Z; G73 pecks of Q with a rapid
//!   back by the clearance (0.254 mm, LinuxCNC 2.9's built-in 0.01 in); G83 pecks of Q with a
//!   rapid out to R and back down to the clearance above the last depth; G85 feeds in and
//!   out to R, then rapids to the retract level; G89 dwells P at Z and feeds out to it.
//! * The cycle's moves run in exact-path mode (LinuxCNC switches to `G61` around them).
//!
//! G74, G84 (tapping), G86, G87, G88 (spindle stops, manual retract) and G76 are refused.
//!
//! **Fanuc** programs get the same expansion (G73, G81, G82, G83 with G98/G99; the initial
//! level and the R and Z words mean the same on a Fanuc mill), with two differences of
//! notation: G82's P is in milliseconds, and the peck clearance of G73/G83 is a machine
//! parameter (5114, 5115) the reader takes as LinuxCNC's 0.254 mm. Sinumerik's CYCLE81,
//! CYCLE82 and CYCLE83 are read by `sinumerik_cycles`.
//!
//! ```text
//!      initial ──┐            ┌── G98
//!   R ─ ─ ─ ─ ─ ─│─ ─ ─ ─ ─ ─ │─ G99
//!                │ feed       │ rapid
//!   Z ───────────┴────────────┘
//! ```

use super::{Block, BlockError, FeedMode, ReadMove, State, plane_axes};
use crate::gcode::Dialect;
use crate::geom::Point3;
use crate::toolpath::{Corner, Move};

/// Two Z levels closer than this, mm, are the same level (rounding of offset sums).
const LEVEL_EPS_MM: f64 = 1e-9;

/// LinuxCNC 2.9's G73/G83 peck clearance, mm.
const PECK_CLEARANCE_MM: f64 = 0.254;

/// The modal numbers of the canned cycles (mm; P in s).
#[derive(Debug, Clone, Default)]
pub(crate) struct CycleState {
    r: f64,
    cc: f64,
    p: f64,
    q: f64,
    /// The initial level of the present run of cycles (program mm).
    initial: Option<f64>,
    /// G98: retract to the initial level.
    pub(crate) old_z: bool,
}

impl CycleState {
    /// A motion that is not a cycle ends the run.
    pub(crate) fn end_run(&mut self) {
        self.initial = None;
    }
}

/// G codes (×10) of the cycles the reader expands.
pub(crate) fn is_cycle(code: u16) -> bool {
    matches!(code, 730 | 810 | 820 | 830 | 850 | 890)
}

struct Emit<'a> {
    out: &'a mut Vec<ReadMove>,
    state: &'a State,
    line: usize,
    off: [f64; 3],
    axes: (usize, usize, usize),
    feed: f64,
}

impl Emit<'_> {
    fn point(&self, u: f64, v: f64, n: f64) -> Point3 {
        let mut p = [0.0; 3];
        let (ua, va, na) = self.axes;
        for (k, x) in [(ua, u), (va, v), (na, n)] {
            if let (Some(slot), Some(o)) = (p.get_mut(k), self.off.get(k)) {
                *slot = x + o;
            }
        }
        Point3::new(p[0], p[1], p[2])
    }

    fn push(&mut self, mut mv: Move) {
        mv.corner = Corner::ExactPath;
        self.out.push(ReadMove {
            mv,
            line: self.line,
            modal: self.state.modal,
        });
    }

    fn rapid(&mut self, u: f64, v: f64, n: f64) {
        let p = self.point(u, v, n);
        self.push(Move::rapid(p));
    }

    fn feed(&mut self, u: f64, v: f64, n: f64) {
        let p = self.point(u, v, n);
        let f = self.feed;
        self.push(Move::line(p, f));
    }

    fn dwell(&mut self, u: f64, v: f64, n: f64, s: f64) {
        let p = self.point(u, v, n);
        self.push(Move::dwell(p, s));
    }
}

impl State {
    /// Expands canned cycle `m` (×10) for block `b`; `axes` are its X Y Z words (program
    /// units), `polar` its `@ ^` words, `same` whether the previous motion mode was `m`;
    /// `dialect` says what P means in G82 (s; Fanuc: ms).
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn cycle(
        &mut self,
        m: u16,
        same: bool,
        b: &mut Block,
        axes: [Option<f64>; 3],
        polar: [Option<f64>; 2],
        line: usize,
        dialect: Dialect,
        out: &mut Vec<ReadMove>,
    ) -> Result<(), BlockError> {
        let name = format!("G{}", m / 10);
        let p_scale = if dialect == Dialect::Fanuc { 1e-3 } else { 1.0 };
        if self.modal.feed_mode != FeedMode::PerMinute {
            return Err(BlockError::new(
                "canned cycle",
                format!("{name} in G93 or G95"),
                "G94 feed (LinuxCNC refuses inverse time in canned cycles; the reader \
                 expands cycles in G94 only)",
            ));
        }
        let feed = match self.feed {
            Some(f) if f > 0.0 => f,
            _ => {
                return Err(BlockError::new(
                    "canned cycle",
                    format!("{name} without a feed"),
                    "an F > 0 before the cycle",
                ));
            }
        };
        let unit = self.unit();
        let (ua, va, na) = plane_axes(self.modal.plane);
        let offset = self.origin + self.g92 + self.tool_offset;
        let off = [offset.x, offset.y, offset.z];
        let pos = [self.pos.x, self.pos.y, self.pos.z];
        let prog =
            |k: usize| pos.get(k).copied().unwrap_or(0.0) - off.get(k).copied().unwrap_or(0.0);
        let word = |k: usize| axes.get(k).copied().flatten().map(|v| v * unit);
        let letter = |k: usize| char::from(b"XYZ".get(k).copied().unwrap_or(b'Z'));
        let r_word = match b.take(b'R') {
            Some(r) => r * unit,
            None if same => self.cyc.r,
            None => {
                return Err(BlockError::new(
                    "canned cycle",
                    format!("{name} without R"),
                    "an R word (the retract plane) when a cycle starts",
                ));
            }
        };
        let repeats = match b.take(b'L') {
            None => 1,
            Some(l) if l >= 1.0 && l.fract() == 0.0 && l <= 1e6 => l as u32,
            Some(l) => {
                return Err(BlockError::new(
                    "canned cycle repeats",
                    format!("L{l}"),
                    "L = an integer >= 1",
                ));
            }
        };
        let cc_word = match word(na) {
            Some(z) => z,
            None if same => self.cyc.cc,
            None => {
                return Err(BlockError::new(
                    "canned cycle",
                    format!("{name} without {}", letter(na)),
                    format!("a {} word when a cycle starts", letter(na)),
                ));
            }
        };
        let mut dwell = 0.0;
        if matches!(m, 820 | 890) {
            dwell = match b.take(b'P') {
                Some(p) if p >= 0.0 => p * p_scale,
                Some(p) => return Err(BlockError::new("dwell", format!("P{p}"), "P >= 0 s")),
                None if same => self.cyc.p,
                None => {
                    return Err(BlockError::new(
                        "canned cycle",
                        format!("{name} without P"),
                        "a P word (dwell, s)",
                    ));
                }
            };
        }
        let mut delta = 0.0;
        if matches!(m, 730 | 830) {
            delta = match b.take(b'Q') {
                Some(q) if q > 0.0 => q * unit,
                Some(q) => {
                    return Err(BlockError::new("peck", format!("Q{q}"), "Q > 0"));
                }
                None if same => self.cyc.q,
                None => {
                    return Err(BlockError::new(
                        "canned cycle",
                        format!("{name} without Q"),
                        "a Q word (the peck depth)",
                    ));
                }
            };
        }
        if let Some((letter, v)) = b.leftover() {
            return Err(BlockError::unsupported(
                format!("{}{v}", char::from(letter)),
                "X, Y, Z, R, L, and P (G82, G89) or Q (G73, G83) in a canned cycle",
            ));
        }
        let mut current_cc = prog(na);
        let mut old_cc = *self.cyc.initial.get_or_insert(current_cc);
        let (mut aa, mut bb) = (prog(ua), prog(va));
        let (mut inc_a, mut inc_b, mut inc_r, mut inc_t) = (0.0, 0.0, 0.0, 0.0);
        let polar_used = polar.iter().any(Option::is_some);
        if polar_used && self.modal.plane != crate::toolpath::Plane::Xy {
            return Err(BlockError::new(
                "polar coordinates",
                format!("{name} outside G17"),
                "@ and ^ in canned cycles of the XY plane",
            ));
        }
        let (r, cc) = if self.modal.absolute {
            if polar_used {
                let radius = polar[0].map_or(bb.hypot(aa), |p| p * unit);
                let theta = polar[1].map_or(bb.atan2(aa), f64::to_radians);
                (aa, bb) = (radius * theta.cos(), radius * theta.sin());
            } else {
                aa = word(ua).unwrap_or(aa);
                bb = word(va).unwrap_or(bb);
            }
            (r_word, cc_word)
        } else {
            inc_a = word(ua).unwrap_or(0.0);
            inc_b = word(va).unwrap_or(0.0);
            inc_r = polar[0].map_or(0.0, |p| p * unit);
            inc_t = polar[1].map_or(0.0, f64::to_radians);
            (r_word + old_cc, r_word + old_cc + cc_word)
        };
        if r < cc {
            return Err(BlockError::new(
                "canned cycle",
                format!("R {:.4} below {} {:.4}", r / unit, letter(na), cc / unit),
                "R at or above the bottom of the cycle",
            ));
        }
        let mut e = Emit {
            out,
            state: self,
            line,
            off,
            axes: (ua, va, na),
            feed,
        };
        if old_cc < r {
            e.rapid(prog(ua), prog(va), r);
            old_cc = r;
            current_cc = r;
        }
        let clear = if e.state.cyc.old_z { old_cc } else { r };
        for repeat in 0..repeats {
            aa += inc_a;
            bb += inc_b;
            for (inc, radial) in [(inc_r, true), (inc_t, false)] {
                if inc == 0.0 {
                    continue;
                }
                if aa == 0.0 && bb == 0.0 {
                    return Err(BlockError::new(
                        "polar coordinates",
                        "at the program origin",
                        "a position off the origin for incremental @ or ^",
                    ));
                }
                let (rad, th) = (bb.hypot(aa), bb.atan2(aa));
                let (rad, th) = if radial {
                    (rad + inc, th)
                } else {
                    (rad, th + inc)
                };
                (aa, bb) = (rad * th.cos(), rad * th.sin());
            }
            // Levels equal to within LEVEL_EPS_MM are one level: R and the Z the last cycle
            // left the tool at come from different sums of the same offsets, and a rapid of
            // no length down to R is not a move (LinuxCNC makes none).
            if repeat == 0 && current_cc > r + LEVEL_EPS_MM {
                e.rapid(aa, bb, current_cc);
                e.rapid(aa, bb, r);
            } else {
                e.rapid(aa, bb, clear);
                if clear > r + LEVEL_EPS_MM {
                    e.rapid(aa, bb, r);
                }
            }
            match m {
                810 => {
                    e.feed(aa, bb, cc);
                    e.rapid(aa, bb, clear);
                }
                820 => {
                    e.feed(aa, bb, cc);
                    e.dwell(aa, bb, cc, dwell);
                    e.rapid(aa, bb, clear);
                }
                730 | 830 => {
                    let mut depth = r - delta;
                    while depth > cc {
                        e.feed(aa, bb, depth);
                        if m == 830 {
                            e.rapid(aa, bb, r);
                        }
                        e.rapid(aa, bb, depth + PECK_CLEARANCE_MM);
                        depth -= delta;
                    }
                    e.feed(aa, bb, cc);
                    e.rapid(aa, bb, clear);
                }
                850 => {
                    e.feed(aa, bb, cc);
                    e.feed(aa, bb, r);
                    e.rapid(aa, bb, clear);
                }
                _ => {
                    e.feed(aa, bb, cc);
                    e.dwell(aa, bb, cc, dwell);
                    e.feed(aa, bb, clear);
                }
            }
        }
        let end = e.point(aa, bb, clear);
        self.pos = end;
        self.cyc.r = r_word;
        self.cyc.cc = cc_word;
        if matches!(m, 820 | 890) {
            self.cyc.p = dwell;
        }
        if matches!(m, 730 | 830) {
            self.cyc.q = delta;
        }
        Ok(())
    }
}
