//! rs274's canonical calls → the motions they make, in machine millimetres.
//!
//! rs274 prints positions in program coordinates and program units with 4 decimals, and
//! announces the offsets it applies (`SET_G5X_OFFSET`, `SET_G92_OFFSET`,
//! `USE_TOOL_LENGTH_OFFSET`) and the units (`USE_LENGTH_UNITS`). Machine position = program
//! position + G5x origin + G92 offset + tool length offset, each converted to mm with the
//! units in force when it was printed. This is rs274's own interpretation, independent of
//! millpath's reader.

use millpath::gcode::ReadMove;
use millpath::geom::Point3;
use millpath::toolpath::{MoveKind, Plane};

/// One motion of the canonical output.
#[derive(Debug, Clone, PartialEq)]
pub enum CanonMove {
    /// `STRAIGHT_TRAVERSE`.
    Rapid(Point3),
    /// `STRAIGHT_FEED`: end, and the feed in force (mm/min, or the inverse-time F number).
    Feed(Point3, f64),
    /// `ARC_FEED`: end, centre (in-plane coordinates, machine mm), rotation, plane, feed.
    Arc {
        end: Point3,
        centre: (f64, f64),
        rotation: i32,
        plane: Plane,
        feed: f64,
    },
    /// `DWELL` seconds.
    Dwell(f64),
    /// `NURBS_FEED(n, ...)`: a G5.2 curve; rs274 prints none of its points. It stands for the
    /// run of our moves of one source line (the G5.3 block's).
    Nurbs,
}

/// A motion with what is needed to compare it: mm per program unit, inverse time or not, and
/// the rounding allowance (mm) of its printed numbers.
#[derive(Debug, Clone)]
pub struct Canon {
    pub mv: CanonMove,
    pub mm_per_unit: f64,
    pub inverse_time: bool,
    /// Rounding allowance of a position (mm): half a unit of the 4th decimal per printed
    /// number that went into it.
    pub position_tol: f64,
    /// Rounding allowance of the feed (mm/min, or of the inverse-time F number).
    pub feed_tol: f64,
    /// Canonical line number (for messages).
    pub line: usize,
}

/// The numbers of a call's argument list (separated by commas or spaces).
fn numbers(line: &str) -> Vec<f64> {
    let inside = line
        .split_once('(')
        .and_then(|(_, r)| r.rsplit_once(')'))
        .map_or("", |(a, _)| a);
    inside
        .split([',', ' '])
        .filter_map(|t| t.trim().parse().ok())
        .collect()
}

/// Half a unit in the 4th decimal: rs274 prints `%.4f`.
pub const PRINT_HALF_ULP: f64 = 0.5e-4;

/// Parses `canon`. Err names a call that moves in a way the comparison cannot follow (an XY
/// rotation, a probe move, a NURBS feed).
pub fn canon_moves(canon: &str) -> Result<Vec<Canon>, String> {
    let mut plane = Plane::Xy;
    let mut k = 1.0;
    let mut g5x = [0.0; 3];
    let mut g92 = [0.0; 3];
    let mut tool = [0.0; 3];
    let mut feed = 0.0;
    // rs274 prints G93 like G94 as SET_FEED_MODE(0, 0) (a G93 move then carries its feed
    // per minute in SET_FEED_RATE) and G95 as SET_FEED_MODE(s, 1).
    let inverse_time = false;
    let mut per_rev = false;
    let mut feed_k = 1.0;
    // SET_SPINDLE_SPEED (rev/min) and START_SPEED_FEED_SYNC's pitch (mm/rev) while synced.
    let mut spindle = 0.0;
    let mut sync: Option<f64> = None;
    // The end of the last motion (machine mm): a probe backs off toward it.
    let mut last = Point3::ORIGIN;
    // SET_XY_ROTATION (rad): machine = tool + G5x + rot(program + G92) in XY (emccanon.cc,
    // rotate_and_offset_pos).
    let mut xy_rotation: f64 = 0.0;
    let mut out = Vec::new();
    for (i, l) in canon.lines().enumerate() {
        let n = numbers(l);
        let get = |j: usize| n.get(j).copied().unwrap_or(f64::NAN);
        let offsets = |g5x: &[f64; 3], g92: &[f64; 3], tool: &[f64; 3]| {
            [0, 1, 2].map(|a| g5x[a] + g92[a] + tool[a])
        };
        let nonzero = |v: &[f64; 3]| usize::from(v.iter().any(|x| *x != 0.0));
        let terms = 1 + nonzero(&g5x) + nonzero(&g92) + nonzero(&tool);
        // A rotation mixes X and Y roundings: twice the allowance.
        let turned = if xy_rotation != 0.0 { 2.0 } else { 1.0 };
        let position_tol = PRINT_HALF_ULP * k * terms as f64 * turned + 1e-9;
        let off = offsets(&g5x, &g92, &tool);
        // The speed of a feed move (mm/min): the feed, or per revolution times the spindle
        // speed (G95), or the pitch times the spindle speed (G33, G33.1).
        let (speed, feed_tol) = match sync {
            Some(pitch) => (pitch * spindle, 0.5e-6 * k * spindle + 1e-9),
            None if per_rev => (feed * spindle, PRINT_HALF_ULP * feed_k * spindle + 1e-9),
            None => (feed, PRINT_HALF_ULP * feed_k + 1e-9),
        };
        let (sin, cos) = xy_rotation.sin_cos();
        let point = |x: f64, y: f64, z: f64| {
            if xy_rotation == 0.0 {
                return Point3::new(x * k + off[0], y * k + off[1], z * k + off[2]);
            }
            let (px, py) = (x * k + g92[0], y * k + g92[1]);
            Point3::new(
                px * cos - py * sin + g5x[0] + tool[0],
                px * sin + py * cos + g5x[1] + tool[1],
                z * k + off[2],
            )
        };
        let mv = if l.contains("USE_LENGTH_UNITS(CANON_UNITS_MM)") {
            k = 1.0;
            None
        } else if l.contains("USE_LENGTH_UNITS(CANON_UNITS_INCHES)") {
            k = 25.4;
            None
        } else if l.contains("USE_LENGTH_UNITS(") {
            return Err(format!("units: {l}"));
        } else if l.contains("SELECT_PLANE(CANON_PLANE_XZ)") {
            plane = Plane::Zx;
            None
        } else if l.contains("SELECT_PLANE(CANON_PLANE_YZ)") {
            plane = Plane::Yz;
            None
        } else if l.contains("SELECT_PLANE(CANON_PLANE_XY)") {
            plane = Plane::Xy;
            None
        } else if l.contains("SELECT_PLANE(") {
            return Err(format!("plane: {l}"));
        } else if l.contains("SET_G5X_OFFSET(") {
            g5x = [get(1) * k, get(2) * k, get(3) * k];
            None
        } else if l.contains("SET_G92_OFFSET(") {
            g92 = [get(0) * k, get(1) * k, get(2) * k];
            None
        } else if l.contains("USE_TOOL_LENGTH_OFFSET(") {
            tool = [get(0) * k, get(1) * k, get(2) * k];
            None
        } else if l.contains("SET_XY_ROTATION(") {
            xy_rotation = get(0).to_radians();
            None
        } else if l.contains("SET_FEED_MODE(") {
            per_rev = (get(1) - 1.0).abs() < 0.5;
            None
        } else if l.contains("SET_SPINDLE_SPEED(") {
            spindle = get(1);
            None
        } else if l.contains("START_SPEED_FEED_SYNC(") {
            sync = Some(get(0) * k);
            None
        } else if l.contains("STOP_SPEED_FEED_SYNC") {
            sync = None;
            None
        } else if l.contains("SET_FEED_RATE(") {
            // LinuxCNC's canon converts a feed rate to machine units when it is set
            // (emccanon.cc, SET_FEED_RATE: FROM_PROG_LEN), so a later G20/G21 keeps its
            // physical value: mm/min here (inverse time: the F number as it is).
            feed = if inverse_time { get(0) } else { get(0) * k };
            feed_k = if inverse_time { 1.0 } else { k };
            None
        } else if l.contains("STRAIGHT_TRAVERSE(") {
            Some(CanonMove::Rapid(point(get(0), get(1), get(2))))
        } else if l.contains("STRAIGHT_FEED(") {
            Some(CanonMove::Feed(point(get(0), get(1), get(2)), speed))
        } else if l.contains("ARC_FEED(") {
            // ARC_FEED(first_end, second_end, first_centre, second_centre, rotation,
            // axis_end, a, b, c, ...)
            let p = Point3::ORIGIN + plane.join(get(0), get(1), get(5));
            let end = point(p.x, p.y, p.z);
            let c = Point3::ORIGIN + plane.join(get(2), get(3), 0.0);
            let c = point(c.x, c.y, c.z);
            let (cu, cv, _) = plane.split(c - Point3::ORIGIN);
            Some(CanonMove::Arc {
                end,
                centre: (cu, cv),
                rotation: get(4) as i32,
                plane,
                feed: speed,
            })
        } else if l.contains("DWELL(") {
            Some(CanonMove::Dwell(get(0)))
        } else if l.contains("NURBS_FEED(") {
            Some(CanonMove::Nurbs)
        } else if l.contains("STRAIGHT_PROBE(") {
            // saicanon's STRAIGHT_PROBE: the probe reaches the target, and the position backs
            // off 0.254 mm (0.01 in) toward the start; the interpreter goes on from there.
            let target = point(get(0), get(1), get(2));
            let d = last - target;
            let moves = std::iter::once(target)
                .chain((d.length() > 0.0).then(|| target + d * (0.254 / d.length())));
            for p in moves {
                out.push(Canon {
                    mv: CanonMove::Feed(p, speed),
                    mm_per_unit: k,
                    inverse_time,
                    position_tol,
                    feed_tol,
                    line: i + 1,
                });
                last = p;
            }
            None
        } else if l.contains("RIGID_TAP(") {
            // In to the point and back out to the start at the synchronised speed.
            let start = last;
            for p in [point(get(0), get(1), get(2)), start] {
                out.push(Canon {
                    mv: CanonMove::Feed(p, speed),
                    mm_per_unit: k,
                    inverse_time,
                    position_tol,
                    feed_tol,
                    line: i + 1,
                });
            }
            last = start;
            None
        } else {
            None
        };
        if let Some(mv) = mv {
            match mv {
                CanonMove::Rapid(p) | CanonMove::Feed(p, _) => last = p,
                CanonMove::Arc { end, .. } => last = end,
                CanonMove::Dwell(_) | CanonMove::Nurbs => {}
            }
            if let Some(bad) = [get(0), get(1), get(2)].iter().find(|x| !x.is_finite())
                && !matches!(mv, CanonMove::Dwell(_) | CanonMove::Nurbs)
            {
                return Err(format!("unreadable numbers ({bad}) in {l}"));
            }
            out.push(Canon {
                mv,
                mm_per_unit: k,
                inverse_time,
                position_tol,
                feed_tol,
                line: i + 1,
            });
        }
    }
    Ok(out)
}

/// The first difference between our moves and rs274's, if any. A `NURBS_FEED` of rs274's
/// stands for our run of feed lines of one source line (the curve's polyline): those are
/// skipped, and the moves after it must agree again.
pub fn compare(ours: &[ReadMove], theirs: &[Canon], start: Point3) -> Option<String> {
    if theirs.iter().any(|t| t.mv == CanonMove::Nurbs) {
        let mut kept = Vec::new();
        let mut i = 0;
        for t in theirs {
            if t.mv == CanonMove::Nurbs {
                let Some(first) = ours.get(i) else {
                    return Some(format!(
                        "no moves here for rs274's NURBS_FEED (line {})",
                        t.line
                    ));
                };
                let run = ours
                    .get(i..)
                    .unwrap_or_default()
                    .iter()
                    .take_while(|m| m.line == first.line && m.mv.kind == MoveKind::Line)
                    .count();
                if run == 0 {
                    return Some(format!(
                        "no feed lines here for rs274's NURBS_FEED: {first:?}"
                    ));
                }
                i += run;
            } else {
                if let Some(m) = ours.get(i) {
                    kept.push((i, *m));
                }
                i += 1;
            }
        }
        if i != ours.len() {
            return Some(format!(
                "{} moves here, {i} matched with rs274's",
                ours.len()
            ));
        }
        let mine: Vec<ReadMove> = kept.iter().map(|(_, m)| *m).collect();
        let rest: Vec<Canon> = theirs
            .iter()
            .filter(|t| t.mv != CanonMove::Nurbs)
            .cloned()
            .collect();
        // The start of each kept move: the end of the move before it in our sequence.
        let mut from = start;
        for (k, ((idx, o), t)) in kept.iter().zip(&rest).enumerate() {
            if let Some(prev) = idx.checked_sub(1).and_then(|p| ours.get(p)) {
                from = prev.mv.to;
            }
            if let Some(d) = differs(o, t, from) {
                return Some(format!("move {k} (line {}): {d}", o.line));
            }
        }
        return (mine.len() != rest.len()).then(|| "move counts differ".to_string());
    }
    if ours.len() != theirs.len() {
        let n = ours.len().min(theirs.len());
        let first = ours
            .iter()
            .zip(theirs)
            .position(|(o, t)| differs(o, t, start).is_some())
            .unwrap_or(n);
        return Some(format!(
            "{} moves here, {} from rs274 (first difference at move {first}: ours {:?} rs274 {:?})",
            ours.len(),
            theirs.len(),
            ours.get(first).map(|m| (m.line, m.mv)),
            theirs.get(first)
        ));
    }
    let mut from = start;
    for (i, (o, t)) in ours.iter().zip(theirs).enumerate() {
        if let Some(d) = differs(o, t, from) {
            return Some(format!("move {i} (line {}): {d}", o.line));
        }
        from = o.mv.to;
    }
    None
}

fn differs(o: &ReadMove, t: &Canon, from: Point3) -> Option<String> {
    let m = &o.mv;
    let near = |a: Point3, b: Point3| {
        (a.x - b.x)
            .abs()
            .max((a.y - b.y).abs())
            .max((a.z - b.z).abs())
    };
    let tol = t.position_tol + 1e-6;
    let feed_number = |feed: f64| {
        if t.inverse_time {
            feed * 60.0 / m.length_from(from).max(1e-9)
        } else {
            feed * 60.0
        }
    };
    let feed_ok = |theirs: f64| (feed_number(m.feed) - theirs).abs() <= t.feed_tol + 1e-6;
    let bad = |what: &str| Some(format!("{what}: ours {m:?}, rs274 {t:?}"));
    match (&m.kind, &t.mv) {
        (MoveKind::Rapid, CanonMove::Rapid(p)) => {
            (near(m.to, *p) > tol).then(|| bad("end")).flatten()
        }
        (MoveKind::Line, CanonMove::Feed(p, f)) => {
            if near(m.to, *p) > tol {
                bad("end")
            } else if !feed_ok(*f) {
                bad(&format!("feed {} vs {f}", feed_number(m.feed)))
            } else {
                None
            }
        }
        (
            MoveKind::Arc {
                center,
                plane,
                ccw,
                turns,
            },
            CanonMove::Arc {
                end,
                centre,
                rotation,
                plane: p2,
                feed,
            },
        ) => {
            let (u, v, _) = plane.split(*center - Point3::ORIGIN);
            let rot = (*turns as i32 + 1) * if *ccw { 1 } else { -1 };
            if plane != p2 || rot != *rotation {
                bad("plane or rotation")
            } else if near(m.to, *end) > tol {
                bad("end")
            } else if (u - centre.0).abs().max((v - centre.1).abs()) > tol {
                bad("centre")
            } else if !feed_ok(*feed) {
                bad(&format!("feed {} vs {feed}", feed_number(m.feed)))
            } else {
                None
            }
        }
        (MoveKind::Dwell { seconds }, CanonMove::Dwell(s)) => ((seconds - s).abs()
            > t.feed_tol + 1e-6)
            .then(|| bad("dwell"))
            .flatten(),
        _ => bad("kind"),
    }
}
