//! The engagement's distribution along a program's cutting path, the entries aside.
//!
//! The simulation records the engagement at every tool position of every feed move
//! ([`super::EngagementSample`], with `SimOptions::record_samples`); each sample stands for
//! the travel since the previous one. [`engagement_stats`] weighs the samples that cut by
//! that travel: the mean, the quantiles (the smallest angle that the given share of the
//! cutting length stays at or under) and the maximum, and the share of the cutting length
//! above a bound.
//!
//! **Entries aside.** A feed move that goes down (a helix's or a ramp's descent, a feed
//! straight down) starts an entry; the entry lasts while the following moves end within the
//! circle that holds the descent's points (a helix's flat last turn, a ramp's passes back
//! along its own path), and ends at the first move that leaves it. What a program cuts while
//! it gets down is the entry's business, not the strategy's; every CAM program's entries
//! are found the same way, ours or another's.

use super::EngagementSample;
use crate::geom::Point;
use crate::toolpath::{MoveKind, Toolpath};

/// The engagement along the cutting path (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
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
    /// Share of the cutting length above the bound given to [`engagement_stats`].
    pub share_above_bound: f64,
}

/// The flags of the moves that belong to an entry (module docs).
pub fn entry_moves(tp: &Toolpath) -> Vec<bool> {
    let mut out = vec![false; tp.moves.len()];
    let mut from = tp.start;
    let mut circle: Option<(Point, f64)> = None;
    let mut descent: Vec<Point> = Vec::new();
    for (k, m) in tp.moves.iter().enumerate() {
        let down = m.kind != MoveKind::Rapid && m.to.z < from.z - 1e-9;
        if down {
            if descent.is_empty() {
                descent.push(from.xy());
            }
            descent.push(m.to.xy());
            if let MoveKind::Arc { center, .. } = m.kind {
                // A helix: its whole circle.
                descent.push(center.xy());
                let rr = center.xy().distance(m.to.xy());
                descent.push(center.xy() + crate::geom::Vec2::new(rr, 0.0));
                descent.push(center.xy() - crate::geom::Vec2::new(rr, 0.0));
            }
            out[k] = true;
            let n = descent.len() as f64;
            let c = descent.iter().fold(Point::ORIGIN, |a, p| {
                Point::new(a.x + p.x / n, a.y + p.y / n)
            });
            let rad = descent.iter().map(|p| p.distance(c)).fold(0.0, f64::max);
            circle = Some((c, rad + 1e-6));
        } else {
            descent.clear();
            match circle {
                Some((c, rad)) if m.kind != MoveKind::Rapid && m.to.xy().distance(c) <= rad => {
                    out[k] = true;
                }
                _ => circle = None,
            }
        }
        from = m.to;
    }
    out
}

/// The engagement's distribution over `samples` of `tp` (entries aside), with the share of
/// the cutting length above `bound_deg`.
pub fn engagement_stats(
    tp: &Toolpath,
    samples: &[EngagementSample],
    bound_deg: f64,
) -> EngagementStats {
    let entry = entry_moves(tp);
    let mut cut: Vec<(f64, f64)> = Vec::with_capacity(samples.len());
    let mut st = EngagementStats::default();
    let mut prev: Option<(usize, f64)> = None;
    for s in samples {
        let ds = match prev {
            Some((m, at)) if m == s.move_index => s.at - at,
            _ => s.at,
        };
        prev = Some((s.move_index, s.at));
        if s.angle <= 0.0 || ds <= 0.0 {
            continue;
        }
        if entry.get(s.move_index).copied().unwrap_or(false) {
            st.entry_mm += ds;
            continue;
        }
        cut.push((s.angle.to_degrees(), ds));
    }
    let total: f64 = cut.iter().map(|c| c.1).sum();
    if total <= 0.0 {
        return st;
    }
    st.cutting_mm = total;
    st.mean_deg = cut.iter().map(|c| c.0 * c.1).sum::<f64>() / total;
    st.share_above_bound = cut
        .iter()
        .filter(|c| c.0 > bound_deg)
        .map(|c| c.1)
        .sum::<f64>()
        / total;
    cut.sort_by(|a, b| a.0.total_cmp(&b.0));
    let quantile = |q: f64| {
        let mut acc = 0.0;
        for c in &cut {
            acc += c.1;
            if acc >= q * total {
                return c.0;
            }
        }
        cut.last().map_or(0.0, |c| c.0)
    };
    st.p50_deg = quantile(0.5);
    st.p95_deg = quantile(0.95);
    st.p99_deg = quantile(0.99);
    st.max_deg = cut.last().map_or(0.0, |c| c.0);
    st
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Point3;
    use crate::toolpath::{Move, Tool};

    #[test]
    fn a_helix_and_its_flat_turn_are_the_entry_and_the_cut_after_is_not() {
        let tool = Tool::flat(6.0).unwrap();
        let mut tp = Toolpath::new(tool, Point3::new(2.0, 0.0, 1.0));
        let c = |z| Point3::new(0.0, 0.0, z);
        tp.push(Move::arc_xy(
            Point3::new(-2.0, 0.0, -1.0),
            c(-1.0),
            true,
            10.0,
        ));
        tp.push(Move::arc_xy(
            Point3::new(2.0, 0.0, -3.0),
            c(-3.0),
            true,
            10.0,
        ));
        tp.push(Move::arc_xy(
            Point3::new(2.0, 0.0, -3.0),
            c(-3.0),
            true,
            10.0,
        ));
        tp.push(Move::line(Point3::new(20.0, 0.0, -3.0), 10.0));
        assert_eq!(entry_moves(&tp), vec![true, true, true, false]);
        let s = |m, at, deg: f64| EngagementSample {
            move_index: m,
            at,
            angle: deg.to_radians(),
        };
        let samples = [
            s(2, 5.0, 180.0),
            s(3, 6.0, 90.0),
            s(3, 12.0, 60.0),
            s(3, 18.0, 0.0),
        ];
        let st = engagement_stats(&tp, &samples, 80.0);
        assert!((st.cutting_mm - 12.0).abs() < 1e-9);
        assert!((st.entry_mm - 5.0).abs() < 1e-9);
        assert!((st.max_deg - 90.0).abs() < 1e-9);
        assert!((st.mean_deg - 75.0).abs() < 1e-9);
        assert!((st.share_above_bound - 0.5).abs() < 1e-9);
        assert!((st.p95_deg - 90.0).abs() < 1e-9);
    }
}
