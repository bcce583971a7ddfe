//! Arcs, helices and multi-turn arcs of the writer.
//!
//! The centre offsets are taken from the *rounded* start the reader will see, so the centre a
//! reader reconstructs is off by the rounding of the offsets alone. Before writing, the arc is
//! re-read as a reader would (rounded start, end and centre; LinuxCNC's radius rule; the
//! sweep rule of [`crate::toolpath::Move::sweep_from`]): an arc whose radius is below
//! [`MIN_ARC_RADIUS_MM`], or whose short sweep rounding would turn into a full circle, is
//! written as a line (its chord is within the arc's sagitta, smaller than one rounding unit);
//! so is a **near-straight arc**, whose sagitta ([`crate::toolpath::Move::sagitta_from`]) is
//! at most the output rounding `ρ = √2·½·10^−d` ([`crate::gcode::rounding_error_mm`], 0.0007
//! mm at 3 decimals in mm): the line then departs from the arc by no more than rounding
//! moves any written point, and a biarc fitted along a straight stretch (a centre 1.4 km
//! away, beyond what planners accept) never reaches the program;
//! a near-full circle whose end rounding moves past its start is written as a full circle and
//! a line to the end. An arc as the first motion of a program (the machine position unknown)
//! is preceded by a rapid to the toolpath's start. Dialects without a turn count get the full turns as separate circles,
//! each advancing the helix axis by `h·2π/S` (axial travel `h`, total sweep `S`).
//! Grbl programs are also held to Grbl 1.1's own radius rule ([`grbl_accepts`]), and get no
//! turn word at all (Grbl has no `P` on G2/G3).

use super::{Dialect, Emitter, MIN_ARC_RADIUS_MM, Motion, round};
use crate::error::{Error, InputError};
use crate::gcode::arc;
use crate::gcode::format::rounding_error_mm;
use crate::gcode::interp::plane_axes;
use crate::geom::Point3;
use crate::toolpath::{Move, MoveKind, Plane};
use std::f64::consts::{PI, TAU};

/// Grbl 1.1's arc-radius rule (`gcode.c`, centre format, radii in mm whatever the program's
/// units): with `r` the radius to the start and `Δ = |r_end − r|`, the block is refused when
/// `Δ > 0.005 mm` and (`Δ > 0.5 mm` or `Δ > 0.001·r`). Stricter than LinuxCNC's 0.0283 mm.
pub(super) fn grbl_accepts(r_start_mm: f64, r_end_mm: f64) -> bool {
    let delta = (r_end_mm - r_start_mm).abs();
    !(delta > 0.005 && (delta > 0.5 || delta > 0.001 * r_start_mm))
}

fn get(a: &[f64; 3], k: usize) -> f64 {
    a.get(k).copied().unwrap_or(0.0)
}

impl Emitter<'_> {
    pub(super) fn arc(&mut self, i: usize, m: &Move, from: Point3) -> Result<(), Error> {
        let MoveKind::Arc {
            center,
            plane,
            ccw,
            turns,
        } = m.kind
        else {
            return Ok(());
        };
        if self.pos.iter().any(Option::is_none) {
            // The machine's position is unknown and an arc's centre is relative to it: go to
            // the toolpath's start first.
            self.summary.start_rapid = true;
            self.linear(Motion::G0, &Move::rapid(from), 0.0)?;
        }
        let (r_mm, sweep) = m.sweep_from(from).unwrap_or((0.0, 0.0));
        let (ua, va, na) = plane_axes(plane);
        let s = self.emitted(from);
        let to = [m.to.x / self.unit, m.to.y / self.unit, m.to.z / self.unit];
        let e = to.map(|v| round(v, self.decimals));
        let c = [
            center.x / self.unit,
            center.y / self.unit,
            center.z / self.unit,
        ];
        let off = (
            round(get(&c, ua) - get(&s, ua), self.decimals),
            round(get(&c, va) - get(&s, va), self.decimals),
        );
        let (su, sv) = (get(&s, ua), get(&s, va));
        let cr = (su + off.0, sv + off.1);
        let (eu, ev) = (get(&e, ua), get(&e, va));
        let r1 = (su - cr.0).hypot(sv - cr.1) * self.unit;
        let r2 = (eu - cr.0).hypot(ev - cr.1) * self.unit;
        let single = sweep.abs() - TAU * f64::from(turns);
        let read_sweep = arc::unsigned_sweep((su, sv), (eu, ev), cr, ccw);
        let straight = m
            .sagitta_from(from)
            .is_some_and(|s| s <= rounding_error_mm(self.decimals, self.opts.units));
        if straight || r_mm < MIN_ARC_RADIUS_MM || (single < PI && read_sweep - single > PI) {
            // Too flat or too small to survive rounding: the chord is within the arc's
            // sagitta.
            self.summary.arcs_as_lines += 1;
            return self.linear(Motion::G1, m, m.feed);
        }
        if let Err(problem) = arc::check_radii(r1, r2, self.opts.units) {
            return Err(InputError::new("arc", problem)
                .at(format!("move {i}"))
                .expected(format!(
                    "an arc that survives rounding to {} decimals: raise the decimals",
                    self.decimals
                ))
                .into());
        }
        if self.dialect() == Dialect::Grbl && !grbl_accepts(r1, r2) {
            return Err(InputError::new(
                "arc",
                format!("radius to start {r1:.6} mm, to end {r2:.6} mm"),
            )
            .at(format!("move {i}"))
            .expected(format!(
                "an arc grbl accepts after rounding to {} decimals (radii within 0.005 mm, or \
                 within 0.1 % and 0.5 mm): raise the decimals",
                self.decimals
            ))
            .into());
        }
        let axial_mm = get(&[m.to.x, m.to.y, m.to.z], na) - get(&[from.x, from.y, from.z], na);
        let near_full_flipped = single > PI && single - read_sweep > PI;
        let native_turns = matches!(self.dialect(), Dialect::LinuxCnc | Dialect::Sinumerik);
        let split = if native_turns { 0 } else { turns };
        if split > 0 {
            self.summary.split_turns += 1;
        }
        // Full turns first (dialects without a turn count), then the last (partial) turn.
        let total = sweep.abs();
        let start_normal = get(&[from.x, from.y, from.z], na);
        for k in 1..=split {
            let normal_mm = start_normal + axial_mm * (TAU * f64::from(k)) / total;
            let normal = round(normal_mm / self.unit, self.decimals);
            self.arc_block(plane, ccw, (su, sv), normal, off, 0, m.feed)?;
        }
        let turn_word = if native_turns { turns } else { 0 };
        if near_full_flipped {
            // Rounding moved the end past the start: a full circle, then the last step.
            self.summary.arcs_as_lines += 1;
            self.arc_block(plane, ccw, (su, sv), get(&e, na), off, turn_word, m.feed)?;
            return self.linear(Motion::G1, m, m.feed);
        }
        self.arc_block(plane, ccw, (eu, ev), get(&e, na), off, turn_word, m.feed)
    }

    /// One G2/G3 block ending at in-plane `(eu, ev)` and `normal` (program units, rounded),
    /// with centre offsets `off` from the current emitted position.
    #[allow(clippy::too_many_arguments)]
    fn arc_block(
        &mut self,
        plane: Plane,
        ccw: bool,
        end: (f64, f64),
        normal: f64,
        off: (f64, f64),
        turns: u32,
        feed: f64,
    ) -> Result<(), Error> {
        let (ua, va, na) = plane_axes(plane);
        self.begin();
        if plane != self.plane {
            self.raw(match plane {
                Plane::Xy => "G17",
                Plane::Zx => "G18",
                Plane::Yz => "G19",
            });
            self.plane = plane;
            self.motion = None;
        }
        self.motion_word(if ccw { Motion::G3 } else { Motion::G2 });
        self.first_motion_words(self.tool_number());
        let mut ends = [0.0; 3];
        if let Some(x) = ends.get_mut(ua) {
            *x = end.0;
        }
        if let Some(x) = ends.get_mut(va) {
            *x = end.1;
        }
        if let Some(x) = ends.get_mut(na) {
            *x = normal;
        }
        for k in 0..3 {
            let force = k != na || self.pos.get(k).copied().flatten().is_none();
            self.axis(k, get(&ends, k) * self.unit, force);
        }
        let mut offs = [None; 3];
        if let Some(x) = offs.get_mut(ua) {
            *x = Some(off.0);
        }
        if let Some(x) = offs.get_mut(va) {
            *x = Some(off.1);
        }
        for (k, o) in offs.iter().enumerate() {
            if let Some(o) = o {
                self.word(
                    ["I", "J", "K"].get(k).copied().unwrap_or("I"),
                    *o,
                    self.decimals,
                );
            }
        }
        if turns > 0 {
            match self.dialect() {
                Dialect::LinuxCnc => self.raw(&format!("P{}", turns + 1)),
                Dialect::Sinumerik => self.raw(&format!("TURN={turns}")),
                Dialect::Fanuc | Dialect::Grbl => {}
            }
        }
        self.feed_word(feed);
        self.summary.blocks += 1;
        self.end()
    }
}
