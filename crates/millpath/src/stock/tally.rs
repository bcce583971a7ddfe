//! The engagement's distribution along a program's cutting path, the entries aside, and
//! which moves are the entries.
//!
//! The simulation records the engagement at every tool position of every feed move
//! ([`super::EngagementSample`], with `SimOptions::record_samples`); each sample stands for
//! the travel since the previous one. An [`EngagementTally`] weighs the samples that cut by
//! that travel: the mean, the quantiles (the smallest angle that the given share of the
//! cutting length stays at or under, read to [`TALLY_BIN_DEG`]) and the maximum, and the
//! share of the cutting length above a bound; the simulation keeps one as it goes
//! (`Simulation::engagement`), `super::engagement_stats` builds one from recorded samples.
//!
//! **Entries aside.** A feed move that goes down (a helix's or a ramp's descent, a feed
//! straight down) starts an entry; the entry lasts while the following level moves stay on
//! the descent's track (a helix's flat last turn, a ramp's pass back along its own path, a
//! racetrack's flat lap): both ends of the move, and a line's middle, within
//! [`TRACK_TOLERANCE`] of a descent move's line or of a descent arc's circle. It ends at the
//! first move off the track. What a program cuts while it gets down is the entry's business,
//! not the strategy's; every CAM program's entries are found the same way, ours or
//! another's.

use crate::geom::Point;
use crate::toolpath::{MoveKind, Toolpath};

/// The engagement along the cutting path (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize)]
pub struct EngagementStats {
    /// Cutting length counted (entries aside), mm.
    pub cutting_mm: f64,
    /// Cutting length inside entries, mm.
    pub entry_mm: f64,
    /// Mean engagement, degrees.
    pub mean_deg: f64,
    /// Median, degrees.
    pub p50_deg: f64,
    /// 95th percentile by length, degrees.
    pub p95_deg: f64,
    /// 99th percentile by length, degrees.
    pub p99_deg: f64,
    /// Largest, degrees.
    pub max_deg: f64,
    /// Share of the cutting length above the bound given to the tally (or `super::engagement_stats`).
    pub share_above_bound: f64,
}

/// How far a move after a descent may lie from the descent's track and still be its
/// entry, mm.
pub const TRACK_TOLERANCE: f64 = 1e-3;

/// One piece of a descent's track, in the plane.
#[derive(Debug, Clone, Copy)]
enum Track {
    Line(Point, Point),
    Circle(Point, f64),
}

impl Track {
    fn distance(&self, q: Point) -> f64 {
        match *self {
            Track::Line(a, b) => q.distance_to_segment(a, b),
            Track::Circle(c, r) => (q.distance(c) - r).abs(),
        }
    }
}

/// The flags of the moves that belong to an entry (module docs).
pub fn entry_moves(tp: &Toolpath) -> Vec<bool> {
    let mut out = vec![false; tp.moves.len()];
    let mut from = tp.start;
    let mut track: Vec<Track> = Vec::new();
    let mut descending = false;
    let on = |track: &[Track], q: Point| track.iter().any(|t| t.distance(q) <= TRACK_TOLERANCE);
    for (k, m) in tp.moves.iter().enumerate() {
        let down = m.kind != MoveKind::Rapid && m.to.z < from.z - 1e-9;
        if down {
            if !descending {
                track.clear();
            }
            descending = true;
            track.push(match m.kind {
                MoveKind::Arc { center, .. } => {
                    Track::Circle(center.xy(), center.xy().distance(m.to.xy()))
                }
                _ => Track::Line(from.xy(), m.to.xy()),
            });
            out[k] = true;
        } else {
            descending = false;
            let mid = from.xy().midpoint(m.to.xy());
            let stays = m.kind != MoveKind::Rapid
                && on(&track, from.xy())
                && on(&track, m.to.xy())
                && (matches!(m.kind, MoveKind::Arc { .. }) || on(&track, mid));
            if stays {
                out[k] = true;
            } else {
                track.clear();
            }
        }
        from = m.to;
    }
    out
}

/// Width of the tally's bins, degrees: the quantiles are read to it.
pub const TALLY_BIN_DEG: f64 = 0.05;

/// The engagement's distribution built up sample by sample: the cutting length per
/// [`TALLY_BIN_DEG`] of engagement, the entries' length aside, the exact mean, maximum and
/// length above a bound. Tallies of separate pockets merge into the program's.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct EngagementTally {
    bins: Vec<f64>,
    bound_deg: f64,
    entry_mm: f64,
    total_mm: f64,
    weighted: f64,
    above_mm: f64,
    max_deg: f64,
}

impl EngagementTally {
    /// An empty tally counting the length above `bound_deg`.
    pub fn new(bound_deg: f64) -> Self {
        EngagementTally {
            bound_deg,
            ..EngagementTally::default()
        }
    }

    /// Travel `ds` (mm) cutting inside an entry.
    pub fn entry(&mut self, ds: f64) {
        if ds > 0.0 {
            self.entry_mm += ds;
        }
    }

    /// Travel `ds` (mm) cutting at `deg` degrees (nothing when either is not positive).
    pub fn cut(&mut self, deg: f64, ds: f64) {
        if deg <= 0.0 || ds <= 0.0 {
            return;
        }
        let nbins = (180.0 / TALLY_BIN_DEG).round() as usize + 1;
        if self.bins.is_empty() {
            self.bins = vec![0.0; nbins];
        }
        let k = ((deg / TALLY_BIN_DEG) as usize).min(nbins - 1);
        self.bins[k] += ds;
        self.total_mm += ds;
        self.weighted += deg * ds;
        if deg > self.bound_deg {
            self.above_mm += ds;
        }
        self.max_deg = self.max_deg.max(deg);
    }

    /// Adds `other`'s lengths (its bound is taken as this tally's).
    pub fn merge(&mut self, other: &EngagementTally) {
        if self.bins.is_empty() {
            self.bins.clone_from(&other.bins);
        } else {
            for (a, b) in self.bins.iter_mut().zip(&other.bins) {
                *a += b;
            }
        }
        self.entry_mm += other.entry_mm;
        self.total_mm += other.total_mm;
        self.weighted += other.weighted;
        self.above_mm += other.above_mm;
        self.max_deg = self.max_deg.max(other.max_deg);
    }

    /// The distribution: the quantiles are the upper edge of the bin where the cumulative
    /// length reaches the share (at most the maximum).
    pub fn stats(&self) -> EngagementStats {
        let mut st = EngagementStats {
            entry_mm: self.entry_mm,
            ..EngagementStats::default()
        };
        let total = self.total_mm;
        if total <= 0.0 {
            return st;
        }
        st.cutting_mm = total;
        st.mean_deg = self.weighted / total;
        st.share_above_bound = self.above_mm / total;
        st.max_deg = self.max_deg;
        let quantile = |q: f64| {
            let mut acc = 0.0;
            for (k, b) in self.bins.iter().enumerate() {
                acc += b;
                if acc >= q * total {
                    return ((k + 1) as f64 * TALLY_BIN_DEG).min(self.max_deg);
                }
            }
            self.max_deg
        };
        st.p50_deg = quantile(0.5);
        st.p95_deg = quantile(0.95);
        st.p99_deg = quantile(0.99);
        st
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_tally_reads_the_sorted_quantiles_to_a_bin_and_merges_as_one() {
        // 2,000 samples of a fixed pseudo-random sequence, weighted by their travel.
        let mut x: u64 = 0x2545_f491_4f6c_dd1d;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 11) as f64 / (1u64 << 53) as f64
        };
        let cuts: Vec<(f64, f64)> = (0..2000).map(|_| (180.0 * next(), 0.01 + next())).collect();
        let (mut one, mut a, mut b) = (
            EngagementTally::new(86.3),
            EngagementTally::new(86.3),
            EngagementTally::new(86.3),
        );
        for (k, &(deg, ds)) in cuts.iter().enumerate() {
            one.cut(deg, ds);
            if k % 3 == 0 {
                a.cut(deg, ds);
            } else {
                b.cut(deg, ds);
            }
        }
        a.merge(&b);
        let (st, merged) = (one.stats(), a.stats());
        for (x, y) in [
            (st.p50_deg, merged.p50_deg),
            (st.p95_deg, merged.p95_deg),
            (st.max_deg, merged.max_deg),
            (st.cutting_mm, merged.cutting_mm),
        ] {
            assert!((x - y).abs() < 1e-9, "{x} against {y}");
        }
        let mut sorted = cuts.clone();
        sorted.sort_by(|p, q| p.0.total_cmp(&q.0));
        let total: f64 = sorted.iter().map(|c| c.1).sum();
        let exact = |q: f64| {
            let mut acc = 0.0;
            sorted
                .iter()
                .find(|c| {
                    acc += c.1;
                    acc >= q * total
                })
                .map_or(0.0, |c| c.0)
        };
        for (q, got) in [(0.5, st.p50_deg), (0.95, st.p95_deg), (0.99, st.p99_deg)] {
            let want = exact(q);
            assert!(
                got >= want - 1e-9 && got <= want + TALLY_BIN_DEG + 1e-9,
                "quantile {q}: {got} against {want}"
            );
        }
        let above: f64 = cuts.iter().filter(|c| c.0 > 86.3).map(|c| c.1).sum();
        assert!((st.share_above_bound - above / total).abs() < 1e-12);
    }
}
