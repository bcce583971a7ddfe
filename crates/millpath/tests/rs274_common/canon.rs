//! rs274's canonical calls → the motions they make, in machine millimetres.
//!
//! rs274 prints positions in program coordinates and program units with 4 decimals, and
//! announces the offsets it applies (`SET_G5X_OFFSET`, `SET_G92_OFFSET`,
//! `USE_TOOL_LENGTH_OFFSET`) and the units (`USE_LENGTH_UNITS`). Machine position = program
//! position + G5x origin + G92 offset + tool length offset, each converted to mm with the
//! units in force when it was printed. This is rs274's own interpretation, independent of
//! millpath's reader.

use millpath::geom::Point3;
use millpath::toolpath::Plane;

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
    let mut inverse_time = false;
    let mut feed_k = 1.0;
    let mut out = Vec::new();
    for (i, l) in canon.lines().enumerate() {
        let n = numbers(l);
        let get = |j: usize| n.get(j).copied().unwrap_or(f64::NAN);
        let offsets = |g5x: &[f64; 3], g92: &[f64; 3], tool: &[f64; 3]| {
            [0, 1, 2].map(|a| g5x[a] + g92[a] + tool[a])
        };
        let nonzero = |v: &[f64; 3]| usize::from(v.iter().any(|x| *x != 0.0));
        let terms = 1 + nonzero(&g5x) + nonzero(&g92) + nonzero(&tool);
        let position_tol = PRINT_HALF_ULP * k * terms as f64 + 1e-9;
        let off = offsets(&g5x, &g92, &tool);
        let point =
            |x: f64, y: f64, z: f64| Point3::new(x * k + off[0], y * k + off[1], z * k + off[2]);
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
            if get(0) != 0.0 {
                return Err(format!("XY rotation: {l}"));
            }
            None
        } else if l.contains("SET_FEED_MODE(") {
            inverse_time = (get(1) - 1.0).abs() < 0.5;
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
            Some(CanonMove::Feed(point(get(0), get(1), get(2)), feed))
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
                feed,
            })
        } else if l.contains("DWELL(") {
            Some(CanonMove::Dwell(get(0)))
        } else if l.contains("STRAIGHT_PROBE(")
            || l.contains("NURBS_FEED(")
            || l.contains("RIGID_TAP(")
        {
            return Err(format!("a motion the comparison does not follow: {l}"));
        } else {
            None
        };
        if let Some(mv) = mv {
            if let Some(bad) = [get(0), get(1), get(2)].iter().find(|x| !x.is_finite())
                && !matches!(mv, CanonMove::Dwell(_))
            {
                return Err(format!("unreadable numbers ({bad}) in {l}"));
            }
            out.push(Canon {
                mv,
                mm_per_unit: k,
                inverse_time,
                position_tol,
                feed_tol: PRINT_HALF_ULP * feed_k + 1e-9,
                line: i + 1,
            });
        }
    }
    Ok(out)
}
