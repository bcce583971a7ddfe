//! G28 and G30: rapid to the home positions stored in parameters `#5161..#5163` (G28) and
//! `#5181..#5183` (G30), machine coordinates (mm; 0 without a `.var` file), by way of an
//! optional waypoint (LinuxCNC 2.9, `interp_convert.cc` `convert_home`).
//!
//! * The block's axis words are the waypoint, in the active system (G90/G91 as usual). The
//!   tool rapids there first (a zero-length rapid without axis words, as LinuxCNC prints it).
//! * Then it rapids home on the axes named in the block, or on all three without axis words;
//!   the other axes stay where the waypoint left them.
//!
//! ```text
//!   G91 G28 Z0   →   rapid Z+0 (waypoint), rapid Z to #5163
//! ```
//!
//! Refused: a motion code in the same block, polar words, a rotated system.

use super::{Block, BlockError, ReadMove, State};
use crate::gcode::params::Store;
use crate::geom::Point3;
use crate::toolpath::Move;

impl State {
    /// G28 (`g` = 280) or G30 (300) for block `b`.
    pub(crate) fn home(
        &mut self,
        g: u16,
        b: &mut Block,
        store: &Store,
        line: usize,
        out: &mut Vec<ReadMove>,
    ) -> Result<(), BlockError> {
        let name = if g == 280 { "G28" } else { "G30" };
        if b.g
            .iter()
            .any(|&(c, _)| matches!(c, 0 | 10 | 20 | 30) || super::cycles::is_cycle(c))
            || b.polar.iter().any(Option::is_some)
            || self.rotation() != 0.0
        {
            return Err(BlockError::unsupported(
                format!("{name} with a motion code, polar words or in a rotated system"),
                "G28/G30 alone with X Y Z words, in a system without rotation",
            ));
        }
        let axes = [b.take(b'X'), b.take(b'Y'), b.take(b'Z')];
        if let Some((l, v)) = b.leftover() {
            return Err(BlockError::unsupported(
                format!("{}{v}", char::from(l)),
                "X, Y, Z (the waypoint) with G28/G30",
            ));
        }
        let unit = self.unit();
        let off = self.origin + self.g92 + self.tool_offset;
        let (off, cur) = ([off.x, off.y, off.z], [self.pos.x, self.pos.y, self.pos.z]);
        let mut way = cur;
        for (k, v) in axes.iter().enumerate() {
            if let (Some(v), Some(w), Some(c), Some(o)) =
                (v, way.get_mut(k), cur.get(k), off.get(k))
            {
                *w = if self.modal.absolute {
                    v * unit + o
                } else {
                    c + v * unit
                };
            }
        }
        let base = if g == 280 { 5161 } else { 5181 };
        let all = axes.iter().all(Option::is_none);
        let mut home = way;
        for (k, h) in home.iter_mut().enumerate() {
            if all || axes.get(k).is_some_and(Option::is_some) {
                *h = store.get(base + k);
            }
        }
        for p in [way, home] {
            let to = Point3::new(p[0], p[1], p[2]);
            out.push(ReadMove {
                mv: Move::rapid(to),
                line,
                modal: self.modal,
            });
            self.pos = to;
        }
        Ok(())
    }
}
