//! A checker of sharp back-and-forth turns in a toolpath, reading only its moves.

use std::f64::consts::TAU;
use std::fmt;

use millpath::geom::{Point, Vec2};
use millpath::toolpath::{MoveKind, Plane, Toolpath};

/// Longest stretch a hook spans, in tool diameters (1 mm for a 12.7 mm tool).
pub const HOOK_REACH: f64 = 0.08;
/// Least turning both ways along a hook, degrees.
pub const HOOK_LEAST: f64 = 60.0;
/// Least turning one way along a hook, degrees.
pub const HOOK_MOST: f64 = 90.0;

/// Moves shorter than this (mm) are below the written program's resolution (three
/// decimals): the checker passes over them as the controller will.
pub const RESOLUTION: f64 = 1e-3;

/// Moves at most this long (mm) make a jog, a hook wherever it lies.
pub const JOG: f64 = 0.01;

/// A hook found: where it starts and how far the path turns each way along it.
#[derive(Debug, Clone, Copy)]
pub struct Hook {
    /// Where the stretch starts.
    pub at: Point,
    /// Turning to the left, degrees.
    pub left: f64,
    /// Turning to the right, degrees.
    pub right: f64,
    /// The stretch's length, mm.
    pub span: f64,
}

impl fmt::Display for Hook {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "at ({:.3}, {:.3}): {:.0}° left and {:.0}° right within {:.3} mm",
            self.at.x, self.at.y, self.left, self.right, self.span
        )
    }
}

/// One planar feed move: its ends, its tangents there, its length and its signed sweep
/// (ccw positive; 0 for a line).
struct Piece {
    a: Point,
    t0: Vec2,
    t1: Vec2,
    len: f64,
    sweep: f64,
}

fn unit(v: Vec2) -> Vec2 {
    v * (1.0 / v.length())
}

/// The runs of planar feed moves at one height, each as its pieces in order.
fn runs(tp: &Toolpath) -> Vec<Vec<Piece>> {
    let mut out: Vec<Vec<Piece>> = vec![Vec::new()];
    let mut from = tp.start;
    for m in &tp.moves {
        let start = from;
        from = m.to;
        let (a, b) = (start.xy(), m.to.xy());
        let flat = (start.z - m.to.z).abs() < 1e-9;
        if flat && m.kind == MoveKind::Line && a.distance(b) < RESOLUTION {
            continue;
        }
        let piece = match m.kind {
            MoveKind::Line if flat => {
                let t = unit(b - a);
                Some(Piece {
                    a,
                    t0: t,
                    t1: t,
                    len: a.distance(b),
                    sweep: 0.0,
                })
            }
            MoveKind::Arc {
                center,
                plane: Plane::Xy,
                ccw,
                turns,
            } if flat => {
                let c = center.xy();
                let (ra, rb) = (a - c, b - c);
                let r = ra.length();
                let mut sweep = (rb.y.atan2(rb.x) - ra.y.atan2(ra.x)).rem_euclid(TAU);
                if !ccw {
                    sweep = (TAU - sweep).rem_euclid(TAU);
                }
                if sweep < 1e-12 {
                    sweep = TAU;
                }
                sweep += TAU * f64::from(turns);
                let sign = if ccw { 1.0 } else { -1.0 };
                let tan = |v: Vec2| unit(Vec2::new(-v.y, v.x) * sign);
                Some(Piece {
                    a,
                    t0: tan(ra),
                    t1: tan(rb),
                    len: r * sweep,
                    sweep: sign * sweep,
                })
            }
            _ => None,
        };
        match piece {
            Some(p) => out.last_mut().expect("a run").push(p),
            None => {
                if out.last().is_some_and(|r| !r.is_empty()) {
                    out.push(Vec::new());
                }
            }
        }
    }
    out.retain(|r| !r.is_empty());
    out
}

/// The signed angle from `u` to `v`, radians.
fn turn(u: Vec2, v: Vec2) -> f64 {
    u.cross(v).atan2(u.dot(v))
}

/// Every hook of `tp` (cut with a tool of diameter `d`), and how many joints were checked.
/// A stretch whose every turn lies where `forced` says the walls force it, between moves
/// longer than [`JOG`], is no hook.
pub fn find_hooks(tp: &Toolpath, d: f64, forced: impl Fn(Point) -> bool) -> (Vec<Hook>, usize) {
    let reach = HOOK_REACH * d;
    let mut hooks = Vec::new();
    let mut joints = 0;
    for run in runs(tp) {
        // (arc length, turn in degrees, where, whether between two moves longer than a jog):
        // joints at their points, arcs in pieces of at most a tenth of the reach.
        let mut ev: Vec<(f64, f64, Point, bool)> = Vec::new();
        let mut s = 0.0;
        for (i, p) in run.iter().enumerate() {
            if i > 0 {
                let long = run[i - 1].len.min(p.len) > JOG;
                ev.push((s, turn(run[i - 1].t1, p.t0).to_degrees(), p.a, long));
                joints += 1;
            }
            if p.sweep != 0.0 {
                let k = (p.len / (0.1 * reach)).ceil().max(1.0);
                for j in 0..k as usize {
                    let u = (j as f64 + 0.5) / k;
                    ev.push((s + u * p.len, p.sweep.to_degrees() / k, p.a, p.len > JOG));
                }
            }
            s += p.len;
        }
        let (mut left, mut right) = (0.0, 0.0);
        let mut j = 0;
        let mut i = 0;
        while i < ev.len() {
            while j < ev.len() && ev[j].0 - ev[i].0 <= reach {
                if ev[j].1 > 0.0 {
                    left += ev[j].1;
                } else {
                    right -= ev[j].1;
                }
                j += 1;
            }
            let (l, r): (f64, f64) = (left, right);
            let walls = || {
                ev[i..j]
                    .iter()
                    .all(|e| e.1.abs() < 1e-9 || (e.3 && forced(e.2)))
            };
            if l.min(r) >= HOOK_LEAST && l.max(r) >= HOOK_MOST && !walls() {
                hooks.push(Hook {
                    at: ev[i].2,
                    left: l,
                    right: r,
                    span: ev[j - 1].0 - ev[i].0,
                });
                // Past this one.
                i = j;
                (left, right) = (0.0, 0.0);
                continue;
            }
            if ev[i].1 > 0.0 {
                left -= ev[i].1;
            } else {
                right += ev[i].1;
            }
            i += 1;
        }
    }
    (hooks, joints)
}

/// The largest angle (degrees) between the tangents where two arcs meet, where, and how many
/// such joints there are. A joint where `forced` says the walls force a corner (the walls'
/// loop's convex corners, where the tool centre must reach the point that touches two walls
/// to clear their corner) is counted but not measured.
pub fn arc_joints(tp: &Toolpath, forced: impl Fn(Point) -> bool) -> (f64, Option<Point>, usize) {
    let mut worst = 0.0_f64;
    let mut at = None;
    let mut n = 0;
    for run in runs(tp) {
        for w in run.windows(2) {
            if w[0].sweep == 0.0 || w[1].sweep == 0.0 {
                continue;
            }
            n += 1;
            if forced(w[1].a) {
                continue;
            }
            let a = turn(w[0].t1, w[1].t0).to_degrees().abs();
            if a > worst {
                worst = a;
                at = Some(w[1].a);
            }
        }
    }
    (worst, at, n)
}
