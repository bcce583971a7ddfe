//! Sinumerik 840D drilling cycles CYCLE81, CYCLE82 and CYCLE83, called at the current
//! position (one call per hole; `MCALL` is not read) in the XY plane, expanded into moves.
//!
//! Parameters are numbers (no variables or expressions), in the program's units, absolute
//! in the workpiece's coordinates; an empty one is absent:
//!
//! * `CYCLE81(RTP, RFP, SDIS, DP, DPR)`: retraction plane, reference plane, safety distance
//!   (≥ 0), final depth absolute (DP) or relative to RFP (DPR, without sign; used when DP is
//!   absent). With `R = RFP + SDIS`: a rapid to R where the tool is not already there, a
//!   feed to the bottom, a rapid to RTP.
//! * `CYCLE82(RTP, RFP, SDIS, DP, DPR, DTB)`: likewise with a dwell of DTB s at the bottom.
//! * `CYCLE83(RTP, RFP, SDIS, DP, DPR, FDEP, FDPR, DAM, DTB, DTS, FRF, VARI, _AXN, _MDEP,
//!   _VRT, _DTD, _DIS1)`: deep-hole drilling in strokes. The first depth is FDEP (absolute)
//!   or RFP − FDPR; each later stroke is the one before less the degression DAM but not less
//!   than DAM (DAM 0 or absent: every stroke as the first; a negative DAM, a factor, is
//!   refused); the stroke that would pass DP ends at DP. The first stroke runs at the feed
//!   times FRF (absent or 0: 1). After each stroke a dwell of DTB (when > 0), then with VARI
//!   1 (chip removal) a rapid out to R, a dwell of DTS (when > 0) and a rapid back down to
//!   the anticipation distance above the depth reached (`_DIS1`, or when absent or 0 the
//!   840D's own: 0.6 mm up to a hole 30 mm deep, the depth/50 beyond, at most 7 mm); with
//!   VARI 0 (chip breaking) a feed move back by `_VRT` (absent or 0: 1 mm). `_AXN`, `_MDEP`
//!   and `_DTD` other than absent or 0 are refused. At DP a dwell of DTB (when > 0) and a
//!   rapid to RTP.
//!
//! RTP must be at or above R and R above the bottom. The moves run in exact-path mode, as
//! LinuxCNC's canned cycles do (module `cycles`); the modal state (motion, feed) is left as
//! it was.

use super::{BlockError, ReadMove, State};
use crate::geom::Point3;
use crate::toolpath::{Corner, Move, Plane};

/// Two levels closer than this, mm, are one.
const LEVEL_EPS_MM: f64 = 1e-9;

/// The parameters of a call, numbers or absent.
fn parameters(name: &str, args: &str) -> Result<Vec<Option<f64>>, BlockError> {
    args.split(',')
        .map(|a| {
            let t = a.trim();
            if t.is_empty() {
                return Ok(None);
            }
            t.parse::<f64>()
                .ok()
                .filter(|v| v.is_finite() && v.abs() <= super::MAX_WORD_VALUE)
                .map(Some)
                .ok_or_else(|| {
                    BlockError::unsupported(
                        format!("{name}({args})"),
                        "numbers as the cycle's parameters (no variables or expressions)",
                    )
                })
        })
        .collect()
}

impl State {
    /// Expands the drilling cycle `name(args)` at the current position.
    pub(crate) fn sinumerik_drill(
        &mut self,
        name: &str,
        args: &str,
        line: usize,
        out: &mut Vec<ReadMove>,
    ) -> Result<(), BlockError> {
        let call = || format!("{name}({args})");
        let p = parameters(name, args)?;
        let max = match name {
            "CYCLE81" => 5,
            "CYCLE82" => 6,
            _ => 17,
        };
        if p.len() > max {
            return Err(BlockError::new(
                "Sinumerik cycle",
                call(),
                format!("at most {max} parameters"),
            ));
        }
        let get = |k: usize| p.get(k).copied().flatten();
        if self.modal.plane != Plane::Xy {
            return Err(BlockError::unsupported(
                call(),
                "drilling cycles in the XY plane (G17)",
            ));
        }
        let feed = match self.feed {
            Some(f) if f > 0.0 && self.modal.feed_mode == super::FeedMode::PerMinute => f,
            _ => {
                return Err(BlockError::new(
                    "Sinumerik cycle",
                    call(),
                    "a feed F > 0 per minute (G94) before the cycle",
                ));
            }
        };
        let unit = self.unit();
        let off_z = (self.origin + self.g92 + self.tool_offset).z;
        let z = |v: f64| v * unit + off_z;
        let need = |k: usize, what: &str| {
            get(k).ok_or_else(|| {
                BlockError::new(
                    "Sinumerik cycle",
                    call(),
                    format!("{what} (parameter {})", k + 1),
                )
            })
        };
        let rtp = need(0, "a retraction plane RTP")?;
        let rfp = need(1, "a reference plane RFP")?;
        let sdis = get(2).unwrap_or(0.0);
        if sdis < 0.0 {
            return Err(BlockError::new(
                "Sinumerik cycle safety distance",
                sdis,
                "SDIS >= 0 (without sign)",
            ));
        }
        let dp = match (get(3), get(4)) {
            (Some(dp), _) => dp,
            (None, Some(dpr)) => rfp - dpr.abs(),
            (None, None) => {
                return Err(BlockError::new(
                    "Sinumerik cycle",
                    call(),
                    "a final depth DP or DPR (parameters 4, 5)",
                ));
            }
        };
        let r = rfp + sdis;
        if !(rtp >= r && r > dp) {
            return Err(BlockError::new(
                "Sinumerik cycle planes",
                call(),
                "RTP at or above RFP + SDIS, and that above the final depth",
            ));
        }
        let (r_mm, dp_mm, rtp_mm) = (z(r), z(dp), z(rtp));
        let (x, y) = (self.pos.x, self.pos.y);
        let at = |zz: f64| Point3::new(x, y, zz);
        let modal = self.modal;
        let mut push = |mut mv: Move| {
            mv.corner = Corner::ExactPath;
            out.push(ReadMove { mv, line, modal });
        };
        if (self.pos.z - r_mm).abs() > LEVEL_EPS_MM {
            push(Move::rapid(at(r_mm)));
        }
        match name {
            "CYCLE81" => push(Move::line(at(dp_mm), feed)),
            "CYCLE82" => {
                let dtb = get(5).unwrap_or(0.0);
                if dtb < 0.0 {
                    return Err(BlockError::new("CYCLE82 dwell", dtb, "DTB >= 0 s"));
                }
                push(Move::line(at(dp_mm), feed));
                push(Move::dwell(at(dp_mm), dtb));
            }
            _ => {
                let first = match (get(5), get(6)) {
                    (Some(f), _) => f,
                    (None, Some(fr)) => rfp - fr.abs(),
                    (None, None) => {
                        return Err(BlockError::new(
                            "CYCLE83",
                            call(),
                            "a first depth FDEP or FDPR (parameters 6, 7)",
                        ));
                    }
                };
                let dam = get(7).unwrap_or(0.0);
                let dtb = get(8).unwrap_or(0.0);
                let dts = get(9).unwrap_or(0.0);
                let frf = match get(10) {
                    None => 1.0,
                    Some(f) if f > 0.0 && f <= 1.0 => f,
                    Some(f) if f.abs() <= 0.0 => 1.0,
                    Some(f) => return Err(BlockError::new("CYCLE83 FRF", f, "0 < FRF <= 1")),
                };
                // VARI: 0 chip breaking, 1 chip removal.
                let removal = match get(11) {
                    None => false,
                    Some(v) if v.abs() <= 0.0 => false,
                    Some(v) if (v - 1.0).abs() <= 0.0 => true,
                    Some(v) => return Err(BlockError::new("CYCLE83 VARI", v, "0 or 1")),
                };
                for (k, what) in [(12, "_AXN"), (13, "_MDEP"), (15, "_DTD")] {
                    if get(k).is_some_and(|v| v != 0.0) {
                        return Err(BlockError::unsupported(
                            call(),
                            &format!("CYCLE83 without {what} (parameter {})", k + 1),
                        ));
                    }
                }
                if dam < 0.0 || dtb < 0.0 || dts < 0.0 {
                    return Err(BlockError::new(
                        "CYCLE83",
                        call(),
                        "DAM >= 0 (a value, not a factor), DTB and DTS >= 0",
                    ));
                }
                if first >= r {
                    return Err(BlockError::new(
                        "CYCLE83 first depth",
                        first,
                        "below RFP + SDIS",
                    ));
                }
                let vrt = match get(14) {
                    Some(v) if v > 0.0 => v * unit,
                    _ => 1.0,
                };
                let dis1 = match get(16) {
                    Some(v) if v > 0.0 => v * unit,
                    _ => {
                        let depth = (rfp - dp) * unit;
                        if depth <= 30.0 {
                            0.6
                        } else {
                            (depth / 50.0).min(7.0)
                        }
                    }
                };
                let strokes = (r - dp) / dam.max(r - first);
                if strokes > crate::toolpath::MAX_PECKS {
                    return Err(BlockError::new(
                        "CYCLE83",
                        call(),
                        format!("at most {} strokes", crate::toolpath::MAX_PECKS),
                    ));
                }
                let mut stroke = (r - first) * unit;
                let mut depth = z(first);
                let mut f = feed * frf;
                while depth > dp_mm {
                    push(Move::line(at(depth), f));
                    f = feed;
                    if dtb > 0.0 {
                        push(Move::dwell(at(depth), dtb));
                    }
                    if removal {
                        push(Move::rapid(at(r_mm)));
                        if dts > 0.0 {
                            push(Move::dwell(at(r_mm), dts));
                        }
                        push(Move::rapid(at(depth + dis1)));
                    } else {
                        push(Move::line(at(depth + vrt), feed));
                    }
                    if dam > 0.0 {
                        stroke = (stroke - dam * unit).max(dam * unit);
                    }
                    depth -= stroke;
                }
                push(Move::line(at(dp_mm), f));
                if dtb > 0.0 {
                    push(Move::dwell(at(dp_mm), dtb));
                }
            }
        }
        push(Move::rapid(at(rtp_mm)));
        self.pos = at(rtp_mm);
        self.moved = true;
        Ok(())
    }
}
