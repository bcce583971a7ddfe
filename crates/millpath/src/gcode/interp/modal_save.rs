//! M70 (save the modal state), M71 (forget it), M72 (restore it), M73 (save it, restored
//! when the subroutine returns; at the top level it is only saved): LinuxCNC 2.9,
//! `interp_convert.cc` `convert_m`, `save_settings`, `restore_settings`, `gen_settings`.
//!
//! A saved state belongs to its call level. Restoring sets again: units (first), F (as
//! LinuxCNC writes it back: `F%.1f`, one decimal, in the restored units), S (`S%.0f`), the
//! plane, G90/G91, G93/G94, the work coordinate system, G43/G49 (G43 with the tool in the
//! spindle), G98/G99, G90.1/G91.1, G7/G8, the path control mode, and the spindle on or off.
//! The position, the G92 offset and the motion mode are not restored. M72 without a saved
//! state at the level is refused, as LinuxCNC refuses it.

use super::{BlockError, FeedMode, Modal, State};
use crate::geom::Vec3;

/// What M70/M73 keep.
#[derive(Debug, Clone)]
pub(crate) struct Saved {
    level: usize,
    auto: bool,
    modal: Modal,
    f_word: f64,
    spindle_set: f64,
    system: usize,
    tool_length: bool,
    old_z: bool,
    arc_absolute: bool,
    diameter: bool,
}

impl State {
    /// M70–M73 at call level `level`, in the order given.
    pub(crate) fn modal_save(
        &mut self,
        m: u16,
        level: usize,
        store: &crate::gcode::params::Store,
    ) -> Result<(), BlockError> {
        match m {
            70 | 73 => {
                self.saved.retain(|s| s.level != level);
                self.saved.push(Saved {
                    level,
                    auto: m == 73 && level > 0,
                    modal: self.modal,
                    f_word: self.f_word,
                    spindle_set: self.spindle_set,
                    system: self.system,
                    tool_length: self.tool_offset != Vec3::ZERO,
                    old_z: self.cyc.old_z,
                    arc_absolute: self.arc_absolute,
                    diameter: self.diameter,
                });
            }
            71 => self.saved.retain(|s| s.level != level),
            _ => {
                let Some(k) = self.saved.iter().position(|s| s.level == level) else {
                    return Err(BlockError::new(
                        "modal state",
                        format!("M{m} without a saved state"),
                        "M70 or M73 at this call level before M72",
                    ));
                };
                let s = self
                    .saved
                    .get(k)
                    .cloned()
                    .ok_or_else(|| BlockError::new("modal state", "lost", "a saved state"))?;
                self.restore(&s, store);
            }
        }
        Ok(())
    }

    /// On return from call level `level`: its M73 state, if any.
    pub(crate) fn auto_restore(&mut self, level: usize, store: &crate::gcode::params::Store) {
        if let Some(k) = self.saved.iter().position(|s| s.level == level) {
            let s = self.saved.remove(k);
            if s.auto {
                self.restore(&s, store);
            }
        }
    }

    fn restore(&mut self, s: &Saved, store: &crate::gcode::params::Store) {
        self.modal.units = s.modal.units;
        if s.modal.feed_mode != self.modal.feed_mode {
            self.modal.feed_mode = s.modal.feed_mode;
            self.feed = None;
        }
        // F%.1f, read in the restored units.
        let f = (s.f_word * 10.0).round() / 10.0;
        self.f_word = f;
        match self.modal.feed_mode {
            FeedMode::PerMinute => self.feed = Some(f * self.unit() / 60.0),
            FeedMode::PerRevolution => self.feed = Some(f * self.unit()),
            FeedMode::InverseTime => {}
        }
        self.spindle_set = s.spindle_set.round();
        self.modal.plane = s.modal.plane;
        self.modal.absolute = s.modal.absolute;
        self.modal.corner = s.modal.corner;
        if s.system != self.system {
            self.system = s.system;
            self.load_origin(store);
        }
        if s.tool_length != (self.tool_offset != Vec3::ZERO) {
            self.tool_offset = if s.tool_length {
                self.tool_table
                    .as_ref()
                    .and_then(|t| t.get(self.modal.tool))
                    .map_or(Vec3::ZERO, |e| e.offset)
            } else {
                Vec3::ZERO
            };
        }
        self.cyc.old_z = s.old_z;
        self.arc_absolute = s.arc_absolute;
        self.diameter = s.diameter;
        // M3/M4 or M5 as saved.
        self.modal.spindle_rpm = if s.modal.spindle_rpm > 0.0 {
            self.spindle_speed(self.spindle_set)
        } else {
            0.0
        };
    }
}
