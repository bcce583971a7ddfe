//! Coordinate systems and the parameters that read the machine's state (LinuxCNC 2.9,
//! `interp_convert.cc`: `convert_setup`, `convert_axis_offsets`, `convert_coordinate_system`).
//!
//! machine position = program position + G5x origin + G92 offset + tool length offset, all in
//! mm inside. The nine work coordinate systems G54, G55 … G59, G59.1, G59.2, G59.3 live in
//! parameters `#5221 + 20·(p−1)` (X, Y, Z of system p = 1..9, mm), G92's offset in
//! `#5211..#5213` (`#5210` = 1 while it is applied), the active system in `#5220` (1..9).
//!
//! * `G10 L2 P p X Y Z`: sets system p's origin (p 0 = the active one) to the values given.
//! * `G10 L20 P p X Y Z`: sets it so that the tool's present position reads X Y Z in it:
//!   origin = machine − G92 − tool − value.
//! * `G92 X Y Z`: an offset so that the present position reads X Y Z:
//!   G92 = machine − origin − tool − value. `G92.1` clears it and its parameters, `G92.2`
//!   clears it and keeps the parameters, `G92.3` applies the parameters again.
//! * `G10 L2 P p R deg` rotates system p's XY frame about its origin (module `rotation`).
//!
//! Parameters read from the state: `#5220`, `#5400` (tool), `#5410` (its diameter),
//! `#5420..#5422` (position in the active system, program units), and the named
//! `#<_x>`, `#<_y>`, `#<_z>` (the same), `#<_a>`..`#<_w>` (0), `#<_metric>`, `#<_imperial>`,
//! `#<_absolute>`, `#<_incremental>`, `#<_inverse_time>`, `#<_units_per_minute>`,
//! `#<_units_per_rev>` (0), `#<_feed>`, `#<_rpm>`, `#<_current_tool>`, `#<_motion_mode>`,
//! `#<_plane>`, `#<_coord_system>`, `#<_call_level>`, `#<_remap_level>` (0), `#<_task>`
//! (0: not run by a machine), `#<_vmajor>` (2), `#<_vminor>` (9),
//! `#<_lathe_diameter_mode>` (1 in G7), `#<_lathe_radius_mode>`, `#<_value>`,
//! `#<_value_returned>` (0 until a subroutine returns).

use super::{Block, BlockError, FeedMode, State};
use crate::gcode::dialect::Units;
use crate::gcode::expr;
use crate::gcode::params::{MAX_PARAM, Store};
use crate::geom::Vec3;
use crate::toolpath::Plane;

/// First parameter of system p: `5201 + 20·p` (p = 1..9).
fn system_base(p: usize) -> usize {
    5201 + 20 * p
}

/// The parameters and the state, for expressions.
pub(crate) struct Scope<'a> {
    pub(crate) store: &'a Store,
    pub(crate) state: &'a State,
    pub(crate) call_level: usize,
}

impl State {
    /// The active system's origin from the parameters.
    pub(crate) fn load_origin(&mut self, store: &Store) {
        let b = system_base(self.system + 1);
        self.origin = Vec3::new(store.get(b), store.get(b + 1), store.get(b + 2));
        self.rotation = store.get(b + 9).to_radians();
    }

    /// The present position in the active system, program units.
    pub(crate) fn program_position(&self) -> [f64; 3] {
        let p = self.program_mm();
        let u = self.modal.units.mm_per_unit();
        [p[0] / u, p[1] / u, p[2] / u]
    }

    fn axes(b: &mut Block) -> [Option<f64>; 3] {
        [b.take(b'X'), b.take(b'Y'), b.take(b'Z')]
    }

    /// G10 L2 / L20.
    pub(crate) fn g10(&mut self, b: &mut Block, store: &mut Store) -> Result<(), BlockError> {
        let l = b.take(b'L');
        let p = b.take(b'P');
        let r = b.take(b'R');
        let axes = Self::axes(b);
        let l20 = match l.map(f64::round) {
            Some(v) if l.is_some_and(|l| (l - v).abs() < 1e-9) && (v - 2.0).abs() < 0.5 => false,
            Some(v) if l.is_some_and(|l| (l - v).abs() < 1e-9) && (v - 20.0).abs() < 0.5 => true,
            _ => {
                return Err(BlockError::unsupported(
                    format!("G10 L{}", l.unwrap_or(f64::NAN)),
                    "G10 L2 or G10 L20 (work offsets)",
                ));
            }
        };
        let p = match p {
            Some(p) if p.fract() == 0.0 && (0.0..=9.0).contains(&p) => p as usize,
            _ => {
                return Err(BlockError::new(
                    "G10 P",
                    format!("{p:?}"),
                    "P0 (the active system) to P9 (G59.3)",
                ));
            }
        };
        let sys = if p == 0 { self.system + 1 } else { p };
        let base = system_base(sys);
        if let Some(r) = r {
            if l20 {
                return Err(BlockError::new(
                    "G10 L20",
                    format!("R{r}"),
                    "R only with G10 L2",
                ));
            }
            store.set(base + 9, r);
        }
        if l20 && store.get(base + 9) != 0.0 {
            return Err(BlockError::unsupported(
                "G10 L20 in a rotated system",
                "G10 L20 in systems without rotation (G10 L2 R0)",
            ));
        }
        let u = self.unit();
        let pos = [self.pos.x, self.pos.y, self.pos.z];
        let g92 = [self.g92.x, self.g92.y, self.g92.z];
        let tool = [self.tool_offset.x, self.tool_offset.y, self.tool_offset.z];
        for (k, v) in axes.iter().enumerate() {
            if let Some(v) = v {
                let at = |a: &[f64; 3]| a.get(k).copied().unwrap_or(0.0);
                let origin = if l20 {
                    at(&pos) - at(&g92) - at(&tool) - v * u
                } else {
                    v * u
                };
                store.set(base + k, origin);
            }
        }
        if sys == self.system + 1 {
            self.load_origin(store);
        }
        Ok(())
    }

    /// G92, G92.1, G92.2, G92.3 (`g` ×10).
    pub(crate) fn g92(
        &mut self,
        g: u16,
        b: &mut Block,
        store: &mut Store,
    ) -> Result<(), BlockError> {
        match g {
            920 if self.rotation != 0.0 => {
                return Err(BlockError::unsupported(
                    "G92 in a rotated system",
                    "G92 in systems without rotation (G10 L2 R0)",
                ));
            }
            920 => {
                let axes = Self::axes(b);
                // Rotary offsets (LinuxCNC): the rotary axes are not part of the path.
                let rotary = [b.take(b'A'), b.take(b'B'), b.take(b'C')];
                if axes.iter().chain(&rotary).all(Option::is_none) {
                    return Err(BlockError::new(
                        "G92",
                        "no axis word",
                        "G92 with X, Y or Z (or A, B, C)",
                    ));
                }
                let u = self.unit();
                let mut g92 = [self.g92.x, self.g92.y, self.g92.z];
                let m = [self.pos.x, self.pos.y, self.pos.z];
                let o = [self.origin.x, self.origin.y, self.origin.z];
                let t = [self.tool_offset.x, self.tool_offset.y, self.tool_offset.z];
                for (k, v) in axes.iter().enumerate() {
                    if let (Some(v), Some(slot)) = (v, g92.get_mut(k)) {
                        let at = |a: &[f64; 3]| a.get(k).copied().unwrap_or(0.0);
                        *slot = at(&m) - at(&o) - at(&t) - v * u;
                    }
                }
                self.g92 = Vec3::new(g92[0], g92[1], g92[2]);
                for (k, v) in g92.iter().enumerate() {
                    store.set(5211 + k, *v);
                }
                store.set(5210, 1.0);
            }
            921 | 922 => {
                self.g92 = Vec3::ZERO;
                store.set(5210, 0.0);
                if g == 921 {
                    for k in 0..3 {
                        store.set(5211 + k, 0.0);
                    }
                }
            }
            _ => {
                self.g92 = Vec3::new(store.get(5211), store.get(5212), store.get(5213));
                store.set(5210, 1.0);
            }
        }
        Ok(())
    }

    /// A numbered parameter the state owns, in program units where it is a length.
    fn numbered_system(&self, n: usize) -> Option<f64> {
        let pp = self.program_position();
        match n {
            5220 => Some((self.system + 1) as f64),
            5400 => Some(f64::from(self.modal.tool)),
            5410 => Some(
                self.tool_table
                    .as_ref()
                    .and_then(|t| t.get(self.modal.tool))
                    .map_or(0.0, |e| e.diameter / self.unit()),
            ),
            5420..=5422 => pp.get(n - 5420).copied(),
            5423..=5428 => Some(0.0),
            _ => None,
        }
    }

    fn named_system(&self, name: &str, call_level: usize) -> Option<f64> {
        let t = |c: bool| f64::from(u8::from(c));
        let pp = self.program_position();
        let units = self.modal.units;
        Some(match name {
            "_x" => pp[0],
            "_y" => pp[1],
            "_z" => pp[2],
            "_a" | "_b" | "_c" | "_u" | "_v" | "_w" => 0.0,
            "_metric" => t(units == Units::Mm),
            "_imperial" => t(units == Units::Inch),
            "_absolute" => t(self.modal.absolute),
            "_incremental" => t(!self.modal.absolute),
            "_inverse_time" => t(self.modal.feed_mode == FeedMode::InverseTime),
            "_units_per_minute" => t(self.modal.feed_mode == FeedMode::PerMinute),
            "_units_per_rev" => t(self.modal.feed_mode == FeedMode::PerRevolution),
            "_feed" => self.feed_number(),
            "_rpm" => self.spindle_set,
            "_current_tool" | "_selected_tool" => f64::from(self.modal.tool),
            "_motion_mode" => self.motion.map_or(800.0, f64::from),
            "_plane" => match self.modal.plane {
                Plane::Xy => 170.0,
                Plane::Zx => 180.0,
                Plane::Yz => 190.0,
            },
            "_coord_system" => [
                540.0, 550.0, 560.0, 570.0, 580.0, 590.0, 591.0, 592.0, 593.0,
            ]
            .get(self.system)
            .copied()
            .unwrap_or(540.0),
            "_call_level" => call_level as f64,
            "_remap_level" | "_task" => 0.0,
            "_vmajor" => 2.0,
            "_vminor" => 9.0,
            "_lathe_diameter_mode" => t(self.diameter),
            "_lathe_radius_mode" => t(!self.diameter),
            _ => return None,
        })
    }
}

impl expr::Params for Scope<'_> {
    fn numbered(&self, n: f64) -> Result<f64, String> {
        let n = n as usize;
        if !(1..=usize::from(MAX_PARAM)).contains(&n) {
            return Err(format!("parameter #{n} (1 to {MAX_PARAM})"));
        }
        Ok(self
            .state
            .numbered_system(n)
            .unwrap_or_else(|| self.store.get(n)))
    }

    fn named(&self, name: &str) -> Result<f64, String> {
        if let Some(v) = self.store.named(name) {
            return Ok(v);
        }
        if let Some(v) = self.state.named_system(name, self.call_level) {
            return Ok(v);
        }
        if name == "_value" || name == "_value_returned" {
            return Ok(0.0);
        }
        Err(format!(
            "named parameter #<{name}> not defined{}",
            if name.starts_with("_hal[") || name.starts_with("_ini[") {
                " (HAL pins and INI values exist only on a running machine)"
            } else {
                ""
            }
        ))
    }

    fn exists(&self, name: &str) -> bool {
        self.store.named(name).is_some() || self.state.named_system(name, self.call_level).is_some()
    }
}
