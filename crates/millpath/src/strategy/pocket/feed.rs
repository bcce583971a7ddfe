//! Feed modulation from the measured engagement: the law (the paper's §2.4) and the feed
//! profile that applies it along the path, the same for every strategy (spiral, offset,
//! zigzag, the finishing pass).
//!
//! # The law
//! With `φ_n` the nominal engagement (the stepover's, `arccos(1 − s/r)`) and `φ_max = 180°`
//! (slotting), engagement `φ` calls for the feed `F·f(φ)`, [`factor`]:
//!
//! ```text
//!   f(φ) = 1                                     for φ ≤ φ_n
//!   f(φ) = 1 − (1 − k)·(φ − φ_n)/(φ_max − φ_n)   for φ_n < φ ≤ φ_max
//! ```
//!
//! `k` the slowdown (0.75 gives 75% of the feed when slotting). The paper interpolates in the
//! radial depth of cut ("cutting thickness") between the specified and the maximum; we
//! interpolate in the engagement angle, which is what loads the tool (chip thickness and
//! the number of teeth in the cut both follow the angle).
//!
//! # The profile along the path
//! A feed set per move from the move's largest engagement runs a whole side of an offset loop
//! at the reduced feed of the corner at its end. Instead, [`modulate`]:
//!
//! 1. **Samples.** The stock simulation ([`crate::stock`], a verifier-side measurement, with
//!    [`crate::stock::SimOptions::record_samples`]) gives the engagement `φ_i` at tool
//!    positions every `step` (0.1 mm) along every feed move (a move of a whole number of
//!    steps, to [`crate::stock::STEP_TIE`], gets that number of positions whatever the last
//!    bits of its length: [`crate::stock::sample_count`]; the web page's build and the
//!    CLI's, whose math libraries differ in the last place, sample alike and write the same
//!    feed words). A *chain* is a run of feed moves
//!    between rapids; `s` is the path length along it. Sample `i` at `s_i` stands for the
//!    travel from `s_{i−1}` to `s_i` (its *cell*); a move the simulation did not sample is
//!    one cell at `f = 1`.
//! 2. **Target.** `f_i = f(φ_i)`, the law's factor.
//! 3. **Envelope.** `g_i = min_j (f_j + ρ·|s_i − s_j|)` with the rate `ρ` = [`RATE`]: the
//!    largest profile below every target that changes by at most `ρ·F` per mm. It drops
//!    *before* a high-engagement point is reached, linearly, and recovers after it; a dip
//!    to `k` spans at most `(1 − k)/ρ` on each side (8.3 mm for k = 0.75).
//! 4. **Ladder.** `q_i = 1 − n·Δ`, the highest step of [`STEP`] `Δ` at most `g_i + σ` with
//!    the slack `σ` = [`SLACK`]: feed words change by whole steps of 5 % of F, and the
//!    raster's noise about the nominal engagement (a factor above `1 − σ`, i.e. within about
//!    2° of `φ_n` at k = 0.75, the margin the simulation's `share_above_nominal` uses) keeps
//!    the full feed.
//! 5. **Pieces.** Equal neighbours join; a stretch shorter than [`MIN_PIECE`] is lowered to a
//!    lower neighbour, or (a dip) widened to [`MIN_PIECE`] at its own level
//!    ([`profile::pieces`]): no value ever rises, so the programmed feed stays at or below
//!    `F·(g + σ)` everywhere.
//! 6. **Moves.** Each feed move takes the pieces over its span: a move shorter than
//!    [`MIN_PIECE`] runs at the lowest of them, a longer one is split where the level
//!    changes ([`crate::toolpath::Move::piece`]: lines into lines, arcs into arcs about the
//!    same centre; a piece of an arc flatter than the writer's rounding,
//!    [`super::segments::ARC_AS_LINE_SAGITTA`], into a line), an end fragment shorter than
//!    half of [`MIN_PIECE`] being lowered into its neighbour or widened (at its own, lower
//!    level) to half of [`MIN_PIECE`]. A move
//!    whose level is constant stays one move; interior joints are tangent, so only the
//!    last piece keeps the move's corner mode. Helix turns (arcs that change z, the helical
//!    entries) are never split: each runs at its lowest level (a turn's pieces, rounded in
//!    the program, would meet at small kinks where an exact-stop controller stops: the
//!    aerospace pocket's offset on a machine of `path_tolerance = 0` read back at 20.19 s
//!    with its helix split, 19.62 s without, against 19.45 s planned).
//!
//! `F` is each move's programmed feed (the feed, or the plunge feed of entries).
//!
//! **Scale.** The samples come `λ·0.1 mm` apart for a tool of diameter `D` over 12.7 mm
//! (`λ = D / 12.7 mm`, [`crate::stock::SimOptions`]), as the simulation's cells grow with
//! the tool. The rate `ρ` and the shortest piece stay in millimetres at every scale: they
//! are the machine's (its deceleration at the feed, the planner's cost of a knot), not the
//! part's. A pocket and its enlargement cut with the tool enlarged alike therefore get the
//! same path with the same samples, but the larger one's feed changes are sharper relative
//! to the part, and its path is split into more pieces.
//!
//! **Why 5 % and 5 mm.** Every feed change is a knot of the jerk-limited planner
//! ([`crate::motion::plan`]: zero acceleration at knots), about 10 ms each at 600 in/min on
//! `hsm`; LinuxCNC's trapezoidal planner does not notice them. On the aerospace pocket (one
//! 5 mm level, 600 in/min, `hsm`), offset took 19.75 s with steps of 2 % at 2 %/mm and 1 mm
//! pieces (431 moves), 17.50 s with these constants (173 moves), 16.63 s unmodulated;
//! LinuxCNC 19.460 s and 19.456 s. The spiral, whose path is already cut in 0.5 mm chords, does not split.
//!
//! # What it guarantees (checked independently in `tests/pocket_feed.rs`)
//! * At every sample, the programmed feed is at most `F·(f(φ) + σ)` for the engagement `φ`
//!   measured there (re-simulated on the modulated path, where the samples fall a little
//!   differently, within [`FeedProfile::tolerance`]: `σ + ρ·step`).
//! * The feed is below `F` only within [`FeedProfile::ramp_distance`], `(1 − k)/ρ +
//!   2·`[`MIN_PIECE`] (18.3 mm for k = 0.75), of a sample whose engagement is above the
//!   nominal one (the ramp, then a lowered short piece and a short move on either side),
//!   and on a helix turn within that distance plus the turn's length (a turn in the air
//!   above the slab runs at the feed of the turn below it).

pub(crate) mod profile;

use crate::stock::EngagementSample;
use crate::toolpath::{Corner, Level, Move, MoveKind, Toolpath};
use profile::Span;
use std::f64::consts::PI;

/// The law's feed factor for engagement `phi` (rad), nominal `nominal` (rad), slowdown `k`.
pub fn factor(phi: f64, nominal: f64, k: f64) -> f64 {
    if phi <= nominal || nominal >= PI {
        1.0
    } else {
        1.0 - (1.0 - k) * ((phi - nominal) / (PI - nominal)).min(1.0)
    }
}

/// `ρ`: the largest change of the feed factor per mm of path, 3 % of F per mm: what a
/// machine of 2000 mm/s² (LinuxCNC's judge) can follow at 600 in/min (`a/F² = 2000/254² =
/// 0.031` per mm), so that no modulated feed asks for more than the machine's deceleration.
pub const RATE: f64 = 0.03;
/// `Δ`: the ladder step of the feed factor, 5 % of F.
pub const STEP: f64 = 0.05;
/// `σ`: how far the ladder may round a factor up, 0.5 % of F.
pub const SLACK: f64 = 0.005;
/// The shortest stretch of path at one feed, 5 mm (shorter moves of the path itself
/// excepted).
pub const MIN_PIECE: f64 = 5.0;

/// The constants of the feed profile (see the module docs); [`Default`] has `RATE`,
/// `STEP`, `SLACK` and `MIN_PIECE`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FeedProfile {
    /// `ρ`, factor per mm.
    pub rate: f64,
    /// `Δ`, factor.
    pub step: f64,
    /// `σ`, factor.
    pub slack: f64,
    /// mm.
    pub min_piece: f64,
}

impl Default for FeedProfile {
    fn default() -> Self {
        FeedProfile {
            rate: RATE,
            step: STEP,
            slack: SLACK,
            min_piece: MIN_PIECE,
        }
    }
}

impl FeedProfile {
    /// How far from a sample above the nominal engagement the feed may still be reduced, mm:
    /// `(1 − k)/ρ + 2·min_piece` for slowdown `k` (on a helix turn, which is not split, the
    /// turn's length more).
    pub fn ramp_distance(&self, slowdown: f64) -> f64 {
        (1.0 - slowdown).max(0.0) / self.rate + 2.0 * self.min_piece
    }

    /// How far above the law's factor at a sample the programmed factor may be, for samples
    /// `sample_step` mm apart: the slack `σ` plus `ρ·sample_step` (a sample of a re-simulated
    /// path falls up to one step from the samples the profile was made from).
    pub fn tolerance(&self, sample_step: f64) -> f64 {
        self.slack + self.rate * sample_step
    }
}

/// The toolpath with every feed move's feed following the profile of the module docs, from
/// the simulation's `samples` of `tp` ([`crate::stock::Simulation::samples`], in path
/// order), nominal engagement `nominal` (rad), slowdown `k`.
pub fn modulate(
    tp: &Toolpath,
    samples: &[EngagementSample],
    nominal: f64,
    k: f64,
) -> (Toolpath, Vec<usize>) {
    modulate_with(tp, samples, nominal, k, &FeedProfile::default())
}

/// [`modulate`] with the profile's constants given. Move `i` of `tp` becomes the moves
/// `index[i]..index[i + 1]` of the result (`index`, the second value, has one entry more
/// than `tp` has moves).
pub fn modulate_with(
    tp: &Toolpath,
    samples: &[EngagementSample],
    nominal: f64,
    k: f64,
    profile: &FeedProfile,
) -> (Toolpath, Vec<usize>) {
    let moves: Vec<(crate::geom::Point3, &Move)> = tp.segments().collect();
    // Samples of each move: a range of `samples` (they come in move order).
    let mut ranges = vec![(0usize, 0usize); moves.len()];
    let mut i = 0;
    while i < samples.len() {
        let mi = samples[i].move_index;
        let start = i;
        while i < samples.len() && samples[i].move_index == mi {
            i += 1;
        }
        if let Some(r) = ranges.get_mut(mi) {
            *r = (start, i);
        }
    }
    // Per move, the pieces (from, to, level) along it.
    let mut parts: Vec<Vec<(f64, f64, f64)>> = vec![Vec::new(); moves.len()];
    let mut c = 0;
    while c < moves.len() {
        if !moves[c].1.is_feed() {
            c += 1;
            continue;
        }
        let first = c;
        while c < moves.len() && moves[c].1.is_feed() {
            c += 1;
        }
        chain_parts(
            &moves[first..c],
            first,
            samples,
            &ranges,
            nominal,
            k,
            profile,
        )
        .into_iter()
        .enumerate()
        .for_each(|(j, p)| parts[first + j] = p);
    }
    let mut out = Toolpath::new(tp.tool, tp.start);
    let mut index = Vec::with_capacity(moves.len() + 1);
    for ((from, m), p) in moves.iter().zip(&parts) {
        index.push(out.moves.len());
        if p.is_empty() {
            out.push(**m);
            continue;
        }
        let last = p.len() - 1;
        for (j, &(t0, t1, level)) in p.iter().enumerate() {
            let mut piece = if p.len() == 1 {
                **m
            } else {
                // A piece of an arc is flatter than the arc: a line below the pocket's
                // criterion ([`super::segments::ARC_AS_LINE_SAGITTA`]), as the writer would.
                let start = m.point_at(*from, t0);
                m.piece(*from, t0, t1)
                    .line_if_flat(start, super::segments::ARC_AS_LINE_SAGITTA)
            };
            piece.feed = m.feed * level;
            if j < last {
                piece.corner = Corner::Machine;
                piece.tag = None;
            }
            out.push(piece);
        }
    }
    index.push(out.moves.len());
    let at = |i: usize| index.get(i).copied().unwrap_or(out.moves.len());
    out.levels = tp
        .levels
        .iter()
        .map(|l| Level {
            start: at(l.start),
            end: at(l.end),
            ..l.clone()
        })
        .collect();
    (out, index)
}

/// The pieces of each move of one chain (`chain[j]` is move `first + j`).
fn chain_parts(
    chain: &[(crate::geom::Point3, &Move)],
    first: usize,
    samples: &[EngagementSample],
    ranges: &[(usize, usize)],
    nominal: f64,
    k: f64,
    profile: &FeedProfile,
) -> Vec<Vec<(f64, f64, f64)>> {
    // Cells along the chain: end position and target factor.
    let lengths: Vec<f64> = chain.iter().map(|(f, m)| m.length_from(*f)).collect();
    let mut at = Vec::new();
    let mut target = Vec::new();
    let mut s0 = 0.0;
    for (j, len) in lengths.iter().enumerate() {
        let (a, b) = ranges.get(first + j).copied().unwrap_or((0, 0));
        let own = samples.get(a..b).unwrap_or(&[]);
        if own.is_empty() {
            at.push(s0 + len);
            target.push(1.0);
        }
        for smp in own {
            at.push(s0 + smp.at.min(*len));
            target.push(factor(smp.angle, nominal, k));
        }
        s0 += len;
    }
    let g = profile::envelope(&at, &target, profile.rate);
    let mut prev = 0.0;
    let cells: Vec<Span> = at
        .iter()
        .zip(&g)
        .map(|(&s, &g)| {
            let c = Span {
                len: (s - prev).max(0.0),
                value: profile::ladder(g, profile.step, profile.slack),
            };
            prev = s;
            c
        })
        .collect();
    let pieces = profile::pieces(&cells, profile.min_piece);
    // Walk moves and pieces together: `pi` is the first piece not ending before the move.
    let mut out = Vec::with_capacity(chain.len());
    let (mut pi, mut p_start) = (0usize, 0.0);
    let mut m_start = 0.0;
    for ((from, m), len) in chain.iter().zip(lengths) {
        let m_end = m_start + len;
        while pi + 1 < pieces.len() && p_start + pieces[pi].len <= m_start + 1e-12 {
            p_start += pieces[pi].len;
            pi += 1;
        }
        let mut own: Vec<(f64, f64, f64)> = Vec::new();
        let (mut j, mut js) = (pi, p_start);
        while let Some(piece) = pieces.get(j) {
            let je = js + piece.len;
            let (a, b) = (js.max(m_start) - m_start, je.min(m_end) - m_start);
            if b > a + 1e-12 || own.is_empty() {
                own.push((a.max(0.0), b.max(a).min(len), piece.value));
            }
            if je >= m_end - 1e-12 {
                break;
            }
            js = je;
            j += 1;
        }
        // The parts tile the move exactly.
        if let Some(f) = own.first_mut() {
            f.0 = 0.0;
        }
        if let Some(l) = own.last_mut() {
            l.1 = len;
        }
        // Helix turns (arcs that change z) are not split.
        let helix = matches!(m.kind, MoveKind::Arc { .. }) && (m.to.z - from.z).abs() > 1e-9;
        let min_piece = if helix {
            f64::INFINITY
        } else {
            profile.min_piece
        };
        out.push(move_parts(own, len, min_piece));
        m_start = m_end;
    }
    out
}

/// The parts of one move of length `len` from the pieces over it (see the module docs,
/// step 6): one part at the lowest level for a move shorter than `min_piece`, else end
/// fragments shorter than `min_piece / 2` lowered into or widened against their neighbour.
fn move_parts(mut p: Vec<(f64, f64, f64)>, len: f64, min_piece: f64) -> Vec<(f64, f64, f64)> {
    let lowest = p.iter().map(|x| x.2).fold(1.0, f64::min);
    if p.len() <= 1 || len < min_piece {
        return vec![(0.0, len, lowest)];
    }
    let frag = 0.5 * min_piece;
    let part_len = |x: &(f64, f64, f64)| x.1 - x.0;
    let short = |x: &(f64, f64, f64)| part_len(x) < frag - 1e-9;
    // Leading fragment.
    while p.len() > 1 && short(&p[0]) {
        let (a, b) = (p[0], p[1]);
        if a.2 >= b.2 {
            p[1].0 = a.0;
            p.remove(0);
        } else if part_len(&b) - (frag - part_len(&a)) < frag {
            p[0].1 = b.1;
            p.remove(1);
        } else {
            p[0].1 = a.0 + frag;
            p[1].0 = a.0 + frag;
        }
    }
    // Trailing fragment.
    while p.len() > 1 && short(&p[p.len() - 1]) {
        let n = p.len();
        let (a, b) = (p[n - 2], p[n - 1]);
        if b.2 >= a.2 {
            p[n - 2].1 = b.1;
            p.remove(n - 1);
        } else if part_len(&a) - (frag - part_len(&b)) < frag {
            p[n - 1].0 = a.0;
            p.remove(n - 2);
        } else {
            p[n - 2].1 = b.1 - frag;
            p[n - 1].0 = b.1 - frag;
        }
    }
    p
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn full_feed_up_to_nominal_then_linear_to_slowdown() {
        let n = 1.0;
        assert!((factor(0.5, n, 0.75) - 1.0).abs() < 1e-12);
        assert!((factor(n, n, 0.75) - 1.0).abs() < 1e-12);
        assert!((factor(PI, n, 0.75) - 0.75).abs() < 1e-12);
        assert!((factor(0.5 * (n + PI), n, 0.75) - 0.875).abs() < 1e-12);
    }

    #[test]
    fn end_fragments_are_lowered_or_widened() {
        // A short high head joins the lower piece after it; a short low tail widens.
        let p = move_parts(
            vec![
                (0.0, 0.2, 1.0),
                (0.2, 8.0, 0.9),
                (8.0, 9.9, 0.96),
                (9.9, 10.0, 0.8),
            ],
            10.0,
            1.0,
        );
        assert_eq!(p.len(), 3, "{p:?}");
        assert!((p[0].0 - 0.0).abs() < 1e-12 && (p[0].2 - 0.9).abs() < 1e-12);
        assert!((p[2].1 - 10.0).abs() < 1e-12 && (p[2].0 - 9.5).abs() < 1e-12);
        assert!((p[2].2 - 0.8).abs() < 1e-12 && (p[1].1 - 9.5).abs() < 1e-12);
        // A move shorter than a piece takes its lowest level.
        let q = move_parts(vec![(0.0, 0.3, 1.0), (0.3, 0.5, 0.94)], 0.5, 1.0);
        assert_eq!(q, vec![(0.0, 0.5, 0.94)]);
    }
}
