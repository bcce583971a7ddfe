//! Codes that change the machine's state but not the path (LinuxCNC 2.9,
//! `interp_convert.cc`): lathe diameter mode, spindle speed mode, override switches,
//! digital outputs and M61.
//!
//! * `G7` / `G8` (`convert_lathe_diameter_mode`, `read_x`): in diameter mode every X word
//!   means a diameter, so the tool goes to half of it (absolute and incremental alike). The
//!   mode of the block's end applies to the block's own X word (`G7 X10` goes to X5).
//! * `G96 D S` / `G97`: constant surface speed (S in surface units per minute, D the
//!   speed limit) or rev/min. The path does not change; under G96 the modal spindle speed
//!   is D (the speed the spindle reaches near the axis) or 0 without D: the reader knows no
//!   diameter to turn surface speed into rev/min.
//! * `M48`/`M49` (overrides on/off), `M50 P` (feed override), `M51 P` (spindle override),
//!   `M52 P` (adaptive feed), `M53 P` (feed stop): switches of the machine; without a
//!   machine they do nothing to the path (the programmed feed is the feed at 100 %).
//! * `M62`–`M65 P n`: digital outputs (with the next move, or at once): no path change.
//! * `M66 P|E n L m Q t`: wait for input n (LinuxCNC's task waits for the motion to stop
//!   first). The input is taken as ready at once, as LinuxCNC's standalone interpreter takes
//!   it (`saicanon.cc` `WAIT` returns at once, #5399 = 0): no wait is timed.
//! * `M61 Q n`: tool n is in the spindle without a tool change (it must be in the tool
//!   table when there is one).
//!
//! ```text
//! G7 G0 X20   → X 10 (a radius)          G8 X20 → X 20
//! ```

use super::{Block, BlockError, State};

impl State {
    /// Applies G7/G8 and halves the block's X word in diameter mode (before anything reads
    /// it).
    pub(crate) fn diameter_mode(&mut self, b: &mut Block) {
        if b.has_g(70) {
            self.diameter = true;
        } else if b.has_g(80) {
            self.diameter = false;
        }
        if self.diameter
            && let Some(x) = b.words.get_mut(usize::from(b'X' - b'A'))
            && let Some(x) = x.as_mut()
        {
            *x /= 2.0;
        }
    }

    /// G96/G97, M48–M53 and M61 (after S and T were read).
    pub(crate) fn machine_codes(&mut self, b: &mut Block) -> Result<(), BlockError> {
        if b.has_g(960) {
            let d = b.take(b'D');
            if let Some(d) = d
                && (d.is_nan() || d < 0.0)
            {
                return Err(BlockError::new("G96 D", d, "a speed limit >= 0 rev/min"));
            }
            self.css = Some(d.unwrap_or(0.0));
        } else if b.has_g(970) {
            self.css = None;
        }
        for m in b.m.clone() {
            match m {
                50..=53 | 62..=65 => {
                    if let Some(p) = b.take(b'P')
                        && (p.is_nan() || p < 0.0)
                    {
                        return Err(BlockError::new(
                            "override switch",
                            format!("M{m} P{p}"),
                            "P >= 0",
                        ));
                    }
                }
                66 => {
                    let (p, l, q) = (b.take(b'P'), b.take(b'L'), b.take(b'Q'));
                    if p.is_none_or(|p| p.is_nan() || p < 0.0)
                        || l.is_some_and(|l| !(0.0..=4.0).contains(&l) || l.fract() != 0.0)
                        || q.is_some_and(|q| q.is_nan() || q < 0.0)
                    {
                        return Err(BlockError::new(
                            "M66",
                            format!("P{p:?} L{l:?} Q{q:?}"),
                            "M66 P n (a digital input >= 0) with L 0..4 and Q >= 0 s",
                        ));
                    }
                }
                61 => {
                    let q = b.take(b'Q').ok_or_else(|| {
                        BlockError::new("M61", "without Q", "M61 Q n (the tool number)")
                    })?;
                    if q.is_nan() || q < -0.5 {
                        return Err(BlockError::new("M61 Q", q, "a tool number >= 0"));
                    }
                    // LinuxCNC rounds Q (round_to_int).
                    let n = q.round() as u32;
                    if let Some(t) = &self.tool_table
                        && n != 0
                        && t.get(n).is_none()
                    {
                        return Err(BlockError::new(
                            "M61 tool",
                            n,
                            format!("a tool of the tool table ({} tools)", t.len()),
                        ));
                    }
                    self.modal.tool = n;
                }
                _ => {}
            }
        }
        Ok(())
    }

    /// The spindle speed the modal state reports for a set speed `s` (see the module docs).
    pub(crate) fn spindle_speed(&self, s: f64) -> f64 {
        match self.css {
            Some(limit) => limit,
            None => s,
        }
    }
}
