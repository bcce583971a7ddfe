//! Parabolic blends as LinuxCNC runs them (`tpDoParabolicBlending`, `tpUpdateBlend`): the
//! segment heading into the blend decelerates towards rest at its end while the next one
//! starts from rest, the next's target speed rising as the first one slows; the two run
//! together until the first ends. Their speeds add up to about the blend speed `v_b` over
//! that overlap: the first segment's last `v_b²/(2·a₁)` and the next one's first
//! `v_b²/(2·a₂)` (`a` each segment's tangential acceleration, already halved for the blend)
//! are run together, in `v_b/a₁` s. The next segment gains at most `a₂·v₁/a₁` in the
//! overlap (`v₁` the first one's speed where the blend starts), which bounds `v_b` where it
//! accelerates more slowly than the first one slows (`queue`'s junction speed). The next
//! segment then heads for rest at its own end, so
//! that a chain of short segments never runs faster than `v_b`, however long the stretch
//! between two blends would let a continuous profile speed up.
//!
//! The planner is given that as pieces of the segment: a head (the overlap with the previous
//! segment) and a tail (with the next) whose speed is at most `v_b`, and the rest between
//! them at the segment's own limits. A line is cut into such pieces; a curve whose overlaps
//! cover it is capped at the larger of its two blend speeds as a whole, and otherwise runs as
//! one block (its overlaps timed at the junction's speed only).

use super::super::Prepared;
use crate::motion::path::BlockGeometry;

/// One segment as it leaves the queue, before it is cut.
pub(super) struct Leaving {
    /// The segment as one planner block (its junction cap with the previous one in
    /// `cap_in`).
    pub block: Prepared,
    /// Length of the overlap with the previous segment, and its speed.
    pub head: (f64, f64),
    /// Length of the overlap with the next segment, and its speed.
    pub tail: (f64, f64),
}

/// Appends the pieces of `leaving` to `out`.
pub(super) fn cut(leaving: &Leaving, out: &mut Vec<Prepared>) {
    let &Leaving {
        block,
        head: (h, vh),
        tail: (t, vt),
    } = leaving;
    let Some(geom) = block.geom else {
        out.push(block);
        return;
    };
    let length = geom.length();
    let (mut h, mut t) = (h.max(0.0), t.max(0.0));
    if h + t <= 1e-9 * length.max(1.0) {
        out.push(block);
        return;
    }
    let covered = h + t >= length;
    let BlockGeometry::Line { from, dir, .. } = geom else {
        let mut b = block;
        if covered {
            b.limits.v = b.limits.v.min(vh.max(vt));
        }
        out.push(b);
        return;
    };
    if covered {
        let k = length / (h + t);
        h *= k;
        t *= k;
    }
    let pieces = [
        (0.0, h, Some(vh)),
        (h, length - t, None),
        (length - t, length, Some(vt)),
    ];
    let mut first = true;
    let end = block.mv.to;
    for (s0, s1, cap) in pieces {
        if s1 - s0 <= 1e-12 {
            continue;
        }
        let mut b = block;
        b.geom = Some(BlockGeometry::Line {
            from: from + dir * s0,
            dir,
            length: s1 - s0,
        });
        b.from = from + dir * s0;
        b.mv.to = if s1 >= length { end } else { from + dir * s1 };
        if let Some(v) = cap {
            b.limits.v = b.limits.v.min(v.max(1e-9));
        }
        if !first {
            // Within the segment: no junction of its own.
            b.cap_in = f64::INFINITY;
            b.settle_before = 0.0;
        }
        first = false;
        out.push(b);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::{Point3, Vec3};
    use crate::motion::profile::Limits1;
    use crate::toolpath::Move;

    fn line_block(length: f64) -> Prepared {
        let from = Point3::new(1.0, 2.0, 3.0);
        let dir = Vec3::new(0.6, 0.8, 0.0);
        Prepared {
            from,
            mv: Move::line(from + dir * length, 10.0),
            geom: Some(BlockGeometry::Line { from, dir, length }),
            limits: Limits1 {
                v: 10.0,
                a: 100.0,
                j: f64::INFINITY,
            },
            cap_in: 4.0,
            origin: 7,
            exact_limits: true,
            settle_before: 0.0,
        }
    }

    /// Pieces of a line: contiguous, summing to its length, ending where it ends, the
    /// overlaps no faster than their speeds, the middle at the segment's own limit, the
    /// junction cap kept on the first piece only.
    #[test]
    fn a_line_is_cut_into_contiguous_pieces() {
        for (length, head, tail) in [(10.0, 1.0, 2.0), (10.0, 0.0, 3.0), (2.0, 1.5, 1.5)] {
            let block = line_block(length);
            let mut out = Vec::new();
            cut(
                &Leaving {
                    block,
                    head: (head, 4.0),
                    tail: (tail, 6.0),
                },
                &mut out,
            );
            let total: f64 = out.iter().filter_map(|p| p.geom).map(|g| g.length()).sum();
            assert!((total - length).abs() < 1e-12, "{out:?}");
            for w in out.windows(2) {
                assert!(w[0].mv.to.distance(w[1].from) < 1e-12);
                assert!(w[1].cap_in.is_infinite());
            }
            assert!((out[0].cap_in - 4.0).abs() < 1e-15);
            assert_eq!(out[0].from, block.from);
            assert!(out.last().unwrap().mv.to.distance(block.mv.to) < 1e-12);
            assert!(out.iter().all(|p| p.origin == 7 && p.limits.v <= 10.0));
            let covered = head + tail >= length;
            assert_eq!(out.len(), if covered || head <= 0.0 { 2 } else { 3 });
            assert!(out.last().unwrap().limits.v <= 6.0);
            if !covered && head > 0.0 {
                assert!((out[0].limits.v - 4.0).abs() < 1e-15);
                assert!((out[1].limits.v - 10.0).abs() < 1e-15);
            }
        }
    }

    /// No overlap: the block as it came.
    #[test]
    fn without_overlaps_the_block_is_kept() {
        let block = line_block(5.0);
        let mut out = Vec::new();
        cut(
            &Leaving {
                block,
                head: (0.0, 0.0),
                tail: (0.0, 0.0),
            },
            &mut out,
        );
        assert_eq!(out, vec![block]);
    }
}
