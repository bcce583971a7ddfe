//! LinuxCNC's straight probe `G38.2`–`G38.5`, read as LinuxCNC's own interpreter reads it
//! without a machine (`rs274`, `saicanon.cc`): the probe reaches its target.
//!
//! # What is modelled
//! A probe move is a feed move to the target at the current feed (G94, or G93 with its F).
//! Where the probe trips cannot be known before the program runs; `rs274` assumes the
//! target, and so does the reader: the time is that of the whole approach, an upper bound.
//! After the move `rs274`'s canon backs the position off by 0.254 mm (0.01 in) toward the
//! start (`STRAIGHT_PROBE`), and the interpreter continues from there; the reader makes that a
//! second feed move. The probe results are set as LinuxCNC sets them (`set_probe_data`):
//! #5061–#5063 the target in program coordinates and units, #5064–#5069 zero, #5070 (tripped)
//! 0 as `rs274` reports it, so that probing loops such as `while [#5070 NE 0]` end.
//!
//! # Refused
//! G38.2/G38.4 that do not move (LinuxCNC: "start point too close to probe point") and
//! probing in G95 (LinuxCNC: "Cannot probe with feed per rev mode").

use super::{BlockError, FeedMode, ReadMove, State};
use crate::gcode::params::Store;
use crate::toolpath::Move;

/// `rs274`'s back-off after a probe (mm): 0.254 mm in G21, 0.01 in in G20, the same length.
pub(crate) const PROBE_BACKOFF_MM: f64 = 0.254;

impl State {
    /// The probe move `mv` of G38.x (`motion` = 382..=385).
    pub(crate) fn probe(
        &mut self,
        motion: u16,
        mv: Move,
        line: usize,
        out: &mut Vec<ReadMove>,
    ) -> Result<(), BlockError> {
        let name = format!("G38.{}", motion - 380);
        if self.modal.feed_mode == FeedMode::PerRevolution {
            return Err(BlockError::new(
                "probe",
                format!("{name} in G95"),
                "probing in G94 or G93 (LinuxCNC cannot probe with feed per revolution)",
            ));
        }
        let from = self.pos;
        let d = mv.to - from;
        let len = d.length();
        if len == 0.0 && matches!(motion, 382 | 384) {
            return Err(BlockError::new(
                "probe",
                format!("{name} to where the tool is"),
                "a probe target away from the start (LinuxCNC: start point too close)",
            ));
        }
        out.push(ReadMove {
            mv,
            line,
            modal: self.modal,
        });
        self.pos = mv.to;
        self.probed = Some(self.program_mm());
        if len > 0.0 {
            let back = mv.to - d * (PROBE_BACKOFF_MM / len);
            out.push(ReadMove {
                mv: Move { to: back, ..mv },
                line,
                modal: self.modal,
            });
            self.pos = back;
        }
        Ok(())
    }

    /// #5061–#5070 after a probe at `p` (program mm).
    pub(crate) fn set_probe_parameters(&self, p: [f64; 3], store: &mut Store) {
        let u = self.unit();
        for (k, v) in p.iter().enumerate() {
            store.set(5061 + k, v / u);
        }
        for n in 5064..=5070 {
            store.set(n, 0.0);
        }
    }
}
