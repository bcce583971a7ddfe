//! Consecutive straight feed blocks merged into one where the path stays within a tolerance.
//!
//! # Why
//! LinuxCNC 2.9 blends a corner next to rotary motion parabolically (no blend arc, no
//! tangency: `tcRotaryMotionCheck`): each block is planned to end at rest under half the
//! acceleration its joints allow along it, overlapping the next, so a block of length `L`
//! runs at most about `√(a L / 2)`. On `sweep_g64.ngc` (C turning 1.91 °/mm, C's
//! acceleration 900 °/s²) that is 19.2 mm/s on 1.57 mm blocks programmed at 25 mm/s, as both
//! LinuxCNC and our model show. Fewer, longer blocks run faster; feed words cannot change it.
//!
//! # The rule
//! A run of consecutive lines is a candidate where every line makes one straight feed move
//! (`G1`) that moves X, Y or Z, carries no word but axis words, `F`, `G1` and `N`, and runs
//! in absolute distance mode with the same feed mode, units and plane, at feeds (mm/s; in
//! `G93` each block's length over its time) within 1 % of the run's first block's; in a blending
//! corner mode (`G64`, with or without `P`: not `G61` or `G61.1`, whose
//! path is the program's exactly). From the run's start `P₀`, the merged block's end `Pₑ`
//! moves on while every end point `Pⱼ` in between lies within half the tolerance of the
//! chord: at the parameter `u` of its projection on the chord's XYZ, `|xyzⱼ − xyz(u)| ≤ tol/2`
//! and, for each rotary axis, `|rⱼ − r(u)| ≤ tol_r/2`. The tolerance is the caller's (by
//! default 0.001 mm and 0.001°, the five-axis writer's), or the block's `G64 P` where that is
//! smaller. Half, so that the check after the rewrite, which measures the same points by
//! another route (the least normalised distance over the whole chord), has room.
//!
//! # The merged block
//! Its line is the run's last line (absolute coordinates: its words and the modal values are
//! the end point), with the slowest feed of the run, then timed and written in inverse time as
//! every block (`t = max(L/F, maxᵢ |dᵢ|/vᵢ)`): the tool tip never faster than any of the
//! merged blocks' feeds.

use crate::Point3;
use crate::gcode::ReadMove;
use crate::toolpath::{Corner, MoveKind, Rotary};

/// The largest relative difference of a block's feed (mm/s) from the run's first block's: in
/// `G93` each block's feed is its own, and a merged block runs at the run's slowest.
const SAME_FEED: f64 = 0.01;

/// How far merged blocks' end points may be from the merged chord.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MergeTolerance {
    /// X, Y, Z: mm.
    pub mm: f64,
    /// Each rotary axis: rad.
    pub rad: f64,
}

impl Default for MergeTolerance {
    /// 0.001 mm and 0.001° (the five-axis writer's tolerance).
    fn default() -> Self {
        MergeTolerance {
            mm: 0.001,
            rad: 0.001f64.to_radians(),
        }
    }
}

/// One output block: the input moves `first..=last` (indices into the moves).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Group {
    pub first: usize,
    pub last: usize,
}

/// The words of a line's code (comments removed), upper case: `(letter, number as written)`;
/// `None` if a letter has no number.
fn words(code: &str) -> Option<Vec<(u8, String)>> {
    let compact: String = code
        .chars()
        .filter(|c| !c.is_whitespace())
        .collect::<String>()
        .to_ascii_uppercase();
    let b = compact.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < b.len() {
        let mut j = i + 1;
        while j < b.len() && (b[j].is_ascii_digit() || b[j] == b'.' || b[j] == b'-' || b[j] == b'+')
        {
            j += 1;
        }
        if j == i + 1 {
            return None;
        }
        out.push((b[i], compact[i + 1..j].to_owned()));
        i = j;
    }
    Some(out)
}

/// The line's code words are all axis words, `F`, `G1`/`G01` and `N`.
fn plain_line(code: &str) -> bool {
    words(code).is_some_and(|w| {
        w.iter().all(|(letter, v)| match letter {
            b'X' | b'Y' | b'Z' | b'A' | b'B' | b'C' | b'F' | b'N' => v.parse::<f64>().is_ok(),
            b'G' => v.parse::<f64>().is_ok_and(|g| (g - 1.0).abs() < 1e-9),
            _ => false,
        })
    })
}

/// The axis words of a line's code, as written.
fn axis_words(code: &str) -> Vec<(u8, String)> {
    words(code)
        .unwrap_or_default()
        .into_iter()
        .filter(|(l, _)| matches!(l, b'X' | b'Y' | b'Z' | b'A' | b'B' | b'C'))
        .collect()
}

/// The merged block's words: `G1` and, for every axis a line of the run sets, its last value
/// there as written (so that it reads back as the run's end point, the lines left out setting
/// some of the axes).
pub(crate) fn merged_words(
    lines: &[&str],
    moves: &[ReadMove],
    grp: Group,
    strip: impl Fn(&str) -> String,
) -> String {
    let mut words = String::from("G1");
    for axis in [b'X', b'Y', b'Z', b'A', b'B', b'C'] {
        let found = (grp.first..=grp.last).rev().find_map(|k| {
            let line = lines.get(moves[k].line.checked_sub(1)?)?;
            axis_words(&strip(line))
                .into_iter()
                .rev()
                .find(|(l, _)| *l == axis)
                .map(|(_, v)| v)
        });
        if let Some(v) = found {
            words.push(' ');
            words.push(char::from(axis));
            words.push_str(&v);
        }
    }
    words
}

/// Point `(xyz, rotary)` at parameter `u` of the chord.
fn lerp(a: (Point3, Rotary), b: (Point3, Rotary), u: f64) -> (Point3, Rotary) {
    (
        a.0.lerp(b.0, u),
        Rotary::new(
            a.1.a + u * (b.1.a - a.1.a),
            a.1.b + u * (b.1.b - a.1.b),
            a.1.c + u * (b.1.c - a.1.c),
        ),
    )
}

/// `p` within half of `tol` of the chord `a → b` at its XYZ projection.
fn near_chord(
    a: (Point3, Rotary),
    b: (Point3, Rotary),
    p: (Point3, Rotary),
    tol: MergeTolerance,
) -> bool {
    let ab = b.0 - a.0;
    let l2 = ab.dot(ab);
    if l2 <= 1e-18 {
        return false;
    }
    let u = ((p.0 - a.0).dot(ab) / l2).clamp(0.0, 1.0);
    let q = lerp(a, b, u);
    q.0.distance(p.0) <= 0.5 * tol.mm
        && [
            (q.1.a - p.1.a).abs(),
            (q.1.b - p.1.b).abs(),
            (q.1.c - p.1.c).abs(),
        ]
        .iter()
        .all(|d| *d <= 0.5 * tol.rad)
}

/// The groups of `moves` (every move in exactly one, in order): runs merged as the module docs
/// say. `lines` are the program's lines, `start` where each move starts.
pub(crate) fn groups(
    moves: &[ReadMove],
    lines: &[&str],
    start: &[(Point3, Rotary)],
    tol: MergeTolerance,
    strip: impl Fn(&str) -> String,
) -> Vec<Group> {
    let end = |k: usize| (moves[k].mv.to, moves[k].mv.rotary.unwrap_or(start[k].1));
    let candidate = |k: usize| {
        let rm = &moves[k];
        matches!(rm.mv.kind, MoveKind::Line)
            && rm.modal.absolute
            && !matches!(rm.mv.corner, Corner::ExactStop | Corner::ExactPath)
            && rm.mv.to.distance(start[k].0) > 1e-9
            && rm.line >= 1
            && lines
                .get(rm.line - 1)
                .is_some_and(|l| plain_line(&strip(l)))
    };
    // May move `k` join the run whose previous move is `k - 1`?
    let joins = |k: usize| {
        let (a, b) = (&moves[k - 1], &moves[k]);
        candidate(k - 1)
            && candidate(k)
            && b.line == a.line + 1
            && a.modal.feed_mode == b.modal.feed_mode
            && a.modal.units == b.modal.units
            && a.modal.plane == b.modal.plane
            && a.mv.corner == b.mv.corner
    };
    let tol_at = |k: usize| match moves[k].mv.corner {
        Corner::Blend(p) if p > 0.0 => MergeTolerance {
            mm: tol.mm.min(p),
            ..tol
        },
        _ => tol,
    };
    let mut out = Vec::new();
    let mut k = 0;
    while k < moves.len() {
        let first = k;
        let mut last = k;
        let t = tol_at(k);
        let f0 = moves[first].mv.feed;
        while last + 1 < moves.len()
            && joins(last + 1)
            && (moves[last + 1].mv.feed - f0).abs() <= SAME_FEED * f0.abs()
        {
            let e = last + 1;
            let a = start[first];
            let b = end(e);
            if !(first..e).all(|j| near_chord(a, b, end(j), t)) {
                break;
            }
            last = e;
        }
        out.push(Group { first, last });
        k = last + 1;
    }
    out
}

/// The least over the chord `a → b` of the larger of `|xyz − p|/tol.mm` and
/// `maxᵢ |rᵢ − pᵢ|/tol.rad` (a convex function of the chord's parameter, minimised by
/// ternary search): at most 1 when `p` lies within the tolerance of the chord.
pub(crate) fn chord_distance(
    a: (Point3, Rotary),
    b: (Point3, Rotary),
    p: (Point3, Rotary),
    tol: MergeTolerance,
) -> f64 {
    let f = |u: f64| {
        let q = lerp(a, b, u);
        let r = [
            (q.1.a - p.1.a).abs(),
            (q.1.b - p.1.b).abs(),
            (q.1.c - p.1.c).abs(),
        ];
        (q.0.distance(p.0) / tol.mm).max(r.iter().fold(0.0, |m: f64, x| m.max(*x)) / tol.rad)
    };
    let (mut lo, mut hi) = (0.0, 1.0);
    for _ in 0..200 {
        let m1 = lo + (hi - lo) / 3.0;
        let m2 = hi - (hi - lo) / 3.0;
        if f(m1) <= f(m2) {
            hi = m2;
        } else {
            lo = m1;
        }
    }
    f(0.5 * (lo + hi))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(x: f64, y: f64, c_deg: f64) -> (Point3, Rotary) {
        (
            Point3::new(x, y, 0.0),
            Rotary::new(0.0, 0.0, c_deg.to_radians()),
        )
    }

    #[test]
    fn chord_distance_is_the_normalised_distance_to_the_chord() {
        let tol = MergeTolerance::default();
        let (a, b) = (p(0.0, 0.0, 0.0), p(10.0, 0.0, 10.0));
        // On the chord (C in step with X): 0.
        assert!(chord_distance(a, b, p(4.0, 0.0, 4.0), tol) < 1e-6);
        // 0.001 mm off in Y: 1; 0.002 mm: 2.
        assert!((chord_distance(a, b, p(4.0, 0.001, 4.0), tol) - 1.0).abs() < 1e-6);
        assert!((chord_distance(a, b, p(4.0, 0.002, 4.0), tol) - 2.0).abs() < 1e-6);
        // C off by 0.002° where X is: the nearest point of the chord trades the two.
        let d = chord_distance(a, b, p(4.0, 0.0, 4.002), tol);
        assert!(d > 0.1 && d < 2.0, "{d}");
        // The merge's own rule is stricter: half the tolerance at the XYZ projection.
        assert!(near_chord(a, b, p(4.0, 0.0004, 4.0), tol));
        assert!(!near_chord(a, b, p(4.0, 0.0006, 4.0), tol));
        assert!(!near_chord(a, b, p(4.0, 0.0, 4.0006), tol));
    }

    #[test]
    fn only_plain_lines_merge() {
        assert!(plain_line("G1 X1.5 Y-2 A3 F1500"));
        assert!(plain_line("N10 X1 C2"));
        assert!(plain_line("g01 x1"));
        assert!(!plain_line("G1 X1 M8"));
        assert!(!plain_line("G2 X1 Y1 I1 J0"));
        assert!(!plain_line("G1 X#1"));
        assert!(!plain_line("G1 X1 S1000"));
        assert_eq!(
            axis_words("G1 X1.50 Y-2 F100 C3"),
            vec![
                (b'X', "1.50".to_owned()),
                (b'Y', "-2".to_owned()),
                (b'C', "3".to_owned())
            ]
        );
    }
}
