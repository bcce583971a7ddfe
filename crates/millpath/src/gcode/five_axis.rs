//! Five-axis G-code for table-table machines (AC or BC trunnions).
//!
//! The planned trajectory is in joint space, so the program is written in **machine joint
//! coordinates** (no tool-centre-point control needed): every interval is split into
//! [`FiveAxisGcodeOptions::blocks_per_interval`] `G1` blocks at equal time steps, with
//! `X Y Z` in mm and the rotary words (`A C` or `B C`) in degrees.
//!
//! Feed words:
//! * inverse time (`G93`, the usual choice for simultaneous five-axis moves):
//!   `F = 1 / block duration in minutes`, so the control reproduces the planned timing
//!   exactly;
//! * units per minute (`G94`): `F` is the linear-joint distance of the block divided by its
//!   duration, in mm/min — what a LinuxCNC-style control without TCP applies to a combined
//!   linear + rotary move. A block with no linear motion gets the rotary speed in deg/min.

use crate::error::{Error, InputError};
use crate::machine::kinematics::Kinematics;
use crate::motion::five_axis::Segment;
use std::io::Write;

/// Options of [`write_five_axis`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FiveAxisGcodeOptions {
    /// `G93` inverse-time feeds (default) instead of `G94` mm/min.
    pub inverse_time: bool,
    /// `G1` blocks per planned interval. Default 4.
    pub blocks_per_interval: usize,
}

impl Default for FiveAxisGcodeOptions {
    fn default() -> Self {
        FiveAxisGcodeOptions {
            inverse_time: true,
            blocks_per_interval: 4,
        }
    }
}

fn io_err(e: &std::io::Error) -> Error {
    Error::internal(format!("writing G-code: {e}"))
}

/// Writes the program for `segments` on a table-table machine (`ac-trt` or `bc-trt`).
pub fn write_five_axis(
    w: &mut dyn Write,
    segments: &[Segment],
    kin: &dyn Kinematics,
    opts: &FiveAxisGcodeOptions,
) -> Result<(), Error> {
    if !matches!(kin.name(), "ac-trt" | "bc-trt") {
        return Err(InputError::new("machine", kin.name())
            .at("five-axis G-code")
            .expected("a table-table machine: ac-trt or bc-trt")
            .into());
    }
    let names = kin.axis_names();
    let n = opts.blocks_per_interval.max(1);
    let fmt = |q: &[f64; 5]| {
        format!(
            "X{:.4} Y{:.4} Z{:.4} {}{:.4} {}{:.4}",
            q[0],
            q[1],
            q[2],
            names[3],
            q[3].to_degrees(),
            names[4],
            q[4].to_degrees()
        )
    };
    let total: f64 = segments.iter().map(|s| s.duration).sum();
    let mut out = String::new();
    out.push_str(&format!(
        "(millpath five-axis, {} kinematics, {} intervals, planned time {:.4} s)\n",
        kin.name(),
        segments.len(),
        total
    ));
    out.push_str("G21 G90 G17 G40 G49 G80\n");
    let Some(first) = segments.first() else {
        return Err(InputError::new("trajectory", "no intervals")
            .expected("at least one interval")
            .into());
    };
    let start = first.eval(0.0)[0];
    out.push_str(&format!("G0 {}\n", fmt(&start)));
    out.push_str(if opts.inverse_time { "G93\n" } else { "G94\n" });
    let mut prev = start;
    for seg in segments {
        let dt = seg.duration / n as f64;
        for k in 1..=n {
            let q = seg.eval(dt * k as f64)[0];
            let f = if opts.inverse_time {
                60.0 / dt
            } else {
                let lin = ((q[0] - prev[0]).powi(2)
                    + (q[1] - prev[1]).powi(2)
                    + (q[2] - prev[2]).powi(2))
                .sqrt();
                if lin > 1e-9 {
                    lin / dt * 60.0
                } else {
                    let rot = (q[3] - prev[3])
                        .abs()
                        .max((q[4] - prev[4]).abs())
                        .to_degrees();
                    (rot / dt * 60.0).max(1e-3)
                }
            };
            out.push_str(&format!("G1 {} F{:.4}\n", fmt(&q), f));
            prev = q;
        }
    }
    if opts.inverse_time {
        out.push_str("G94\n");
    }
    out.push_str("M2\n");
    w.write_all(out.as_bytes()).map_err(|e| io_err(&e))
}
