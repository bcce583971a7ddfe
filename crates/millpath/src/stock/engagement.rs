//! The engagement's distribution over a simulation's recorded samples
//! ([`super::EngagementSample`], with `SimOptions::record_samples`): each sample stands for
//! the travel since the previous one, the entries aside (`super::tally`).

use super::EngagementSample;
use super::tally::{EngagementStats, EngagementTally, entry_moves};
use crate::toolpath::Toolpath;

/// The engagement's distribution over `samples` of `tp` (entries aside), with the share of
/// the cutting length above `bound_deg`.
pub fn engagement_stats(
    tp: &Toolpath,
    samples: &[EngagementSample],
    bound_deg: f64,
) -> EngagementStats {
    let entry = entry_moves(tp);
    let mut tally = EngagementTally::new(bound_deg);
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
            tally.entry(ds);
        } else {
            tally.cut(s.angle.to_degrees(), ds);
        }
    }
    tally.stats()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Point3;
    use crate::toolpath::{Move, Tool};

    /// A racetrack: the ramp round the loop and the flat lap on it are the entry; the first
    /// move off the loop is not, nor is a move back onto it after that, nor a chord across
    /// it whose ends lie on it.
    #[test]
    fn a_racetrack_and_its_flat_lap_are_the_entry_and_the_cut_after_is_not() {
        let tool = Tool::flat(6.0).unwrap();
        let p = Point3::new;
        let mut tp = Toolpath::new(tool, p(0.0, -4.0, 1.0));
        let lap = |tp: &mut Toolpath, z: [f64; 4]| {
            tp.push(Move::line(p(30.0, -4.0, z[0]), 10.0));
            tp.push(Move::arc_xy(
                p(30.0, 4.0, z[1]),
                p(30.0, 0.0, z[1]),
                true,
                10.0,
            ));
            tp.push(Move::line(p(0.0, 4.0, z[2]), 10.0));
            tp.push(Move::arc_xy(
                p(0.0, -4.0, z[3]),
                p(0.0, 0.0, z[3]),
                true,
                10.0,
            ));
        };
        lap(&mut tp, [-1.0, -2.0, -4.0, -5.0]);
        lap(&mut tp, [-5.0; 4]);
        tp.push(Move::line(p(5.0, -4.0, -5.0), 10.0));
        tp.push(Move::line(p(5.0, 4.0, -5.0), 10.0));
        tp.push(Move::line(p(5.0, -9.0, -5.0), 10.0));
        tp.push(Move::line(p(10.0, -4.0, -5.0), 10.0));
        let want = [
            true, true, true, true, true, true, true, true, true, false, false, false,
        ];
        assert_eq!(entry_moves(&tp), want);
    }

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
