//! The order to visit things in: pockets of a part, holes of a drilling job. Each item `i` is
//! entered at `s_i` and left at `e_i` (a hole: `s_i = e_i`, its centre); going from `i` to `j`
//! costs the rapid `d(e_i, s_j)` in the plane, and the tour starts at `home` (where the tool
//! is) and ends at its last item (nothing returns home). [`order_tour`] makes a short tour:
//!
//! 1. **Nearest neighbour:** from `home`, each time to the nearest entry not yet visited.
//! 2. **2-opt:** reverse a stretch `i..=j` of the tour when that shortens it (the items keep
//!    their own direction; with `s ≠ e` the stretch's inner links change cost too, which the
//!    prefix sums of forward and backward link costs give in `O(1)` per candidate).
//! 3. **Segment moves (Or-opt):** move a run of one to three consecutive items elsewhere in
//!    the tour when that shortens it.
//!
//! Steps 2 and 3 repeat until neither finds a move that saves more than 1e-9 mm (each pass
//! is `O(n²)`); they run up to [`TWO_OPT_MAX`] items, beyond which the nearest-neighbour tour
//! is kept. Up to [`MULTI_START_MAX`] items the whole is done once from each item as the
//! first (nearest neighbour from there), and the shortest tour kept.
//! 4. **Kicks:** the best tour is changed at pseudo-random (seeded, repeatable) places, by
//!    turns cut in three places with its two middle stretches swapped (a "double bridge",
//!    which 2-opt and segment moves cannot undo in one step) or with one item moved
//!    elsewhere, then improved again (steps 2 and 3) and kept when shorter; `400 000 / n²`
//!    kicks, from 1 to 200.
//!
//! The result is a local optimum, not always the shortest tour. The tests compare it with
//! the brute-force optimum over every permutation of random 8-item sets.

use crate::geom::Point;

/// Most items 2-opt and segment moves improve the order of.
pub const TWO_OPT_MAX: usize = 2000;

/// Up to this many items every item is tried as the first one (each tour improved, the
/// shortest kept).
pub const MULTI_START_MAX: usize = 32;

/// Kicks tried on the best tour: `KICK_BUDGET / n²`, from 1 to [`MAX_KICKS`].
const KICK_BUDGET: usize = 400_000;
const MAX_KICKS: usize = 200;

/// Smallest saving a move must make, mm.
const SAVING_EPS: f64 = 1e-9;

/// A short order to visit `ends` (each item's entry and exit in the plane) from `home` (see
/// the module docs): the item indices in visiting order.
pub fn order_tour(ends: &[(Point, Point)], home: Point) -> Vec<usize> {
    let n = ends.len();
    if n > TWO_OPT_MAX {
        return nearest_neighbour(ends, home, None);
    }
    let starts: Vec<Option<usize>> = if n <= MULTI_START_MAX {
        (0..n).map(Some).collect()
    } else {
        vec![None]
    };
    let mut best: Option<(f64, Vec<usize>)> = None;
    for first in starts {
        let mut tour = nearest_neighbour(ends, home, first);
        improve(ends, home, &mut tour);
        let len = tour_length(ends, home, &tour);
        if best.as_ref().is_none_or(|(b, _)| len < b - SAVING_EPS) {
            best = Some((len, tour));
        }
    }
    let Some((mut len, mut tour)) = best else {
        return Vec::new();
    };
    // Kicks at pseudo-random places, each improved and kept when shorter: a double bridge
    // (A B C D → A C B D), or one item moved elsewhere, by turns.
    if n >= 4 {
        let kicks = (KICK_BUDGET / (n * n)).clamp(1, MAX_KICKS);
        let mut state: u64 = 0x9E37_79B9_7F4A_7C15 ^ n as u64;
        let mut next = |m: usize| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state % m as u64) as usize
        };
        for k in 0..kicks {
            let mut t: Vec<usize>;
            if k % 2 == 0 {
                let mut cuts = [1 + next(n - 1), 1 + next(n - 1), 1 + next(n - 1)];
                cuts.sort_unstable();
                let [a, b, c] = cuts;
                if a == b || b == c {
                    continue;
                }
                t = tour[..a].to_vec();
                t.extend_from_slice(&tour[b..c]);
                t.extend_from_slice(&tour[a..b]);
                t.extend_from_slice(&tour[c..]);
            } else {
                t = tour.clone();
                let item = t.remove(next(n));
                t.insert(next(n), item);
            }
            improve(ends, home, &mut t);
            let l = tour_length(ends, home, &t);
            if l < len - SAVING_EPS {
                (len, tour) = (l, t);
            }
        }
    }
    tour
}

/// 2-opt and segment moves until neither helps.
fn improve(ends: &[(Point, Point)], home: Point, tour: &mut Vec<usize>) {
    let mut rounds = 0;
    while (two_opt(ends, home, tour) | or_opt(ends, home, tour)) && rounds < 1000 {
        rounds += 1;
    }
}

/// The nearest-neighbour tour from `home`, through `first` first when given.
fn nearest_neighbour(ends: &[(Point, Point)], home: Point, first: Option<usize>) -> Vec<usize> {
    let n = ends.len();
    let mut tour: Vec<usize> = Vec::with_capacity(n);
    let mut left: Vec<usize> = (0..n).collect();
    let mut at = home;
    if let Some(f) = first.filter(|&f| f < n) {
        left.retain(|&i| i != f);
        at = ends[f].1;
        tour.push(f);
    }
    while !left.is_empty() {
        let (k, _) = left
            .iter()
            .enumerate()
            .map(|(k, &i)| (k, at.distance(ends[i].0)))
            .fold((0, f64::INFINITY), |b, c| if c.1 < b.1 { c } else { b });
        let i = left.remove(k);
        at = ends[i].1;
        tour.push(i);
    }
    tour
}

/// Length of the rapids of a tour: from `home` to the first entry, then exit to entry.
pub fn tour_length(ends: &[(Point, Point)], home: Point, tour: &[usize]) -> f64 {
    let mut at = home;
    let mut sum = 0.0;
    for &i in tour {
        sum += at.distance(ends[i].0);
        at = ends[i].1;
    }
    sum
}

/// The cost of going from item `a` (`None`: home) to item `b` (`None`: the end, free).
fn link(ends: &[(Point, Point)], home: Point, a: Option<usize>, b: Option<usize>) -> f64 {
    let from = a.map_or(home, |i| ends[i].1);
    b.map_or(0.0, |j| from.distance(ends[j].0))
}

/// One pass of 2-opt; true when it shortened the tour.
fn two_opt(ends: &[(Point, Point)], home: Point, tour: &mut [usize]) -> bool {
    let n = tour.len();
    let mut improved = false;
    // fwd[k] = Σ links t[m] → t[m+1] for m < k; bwd likewise for t[m+1] → t[m].
    let sums = |tour: &[usize]| {
        let mut fwd = vec![0.0; n];
        let mut bwd = vec![0.0; n];
        for k in 1..n {
            fwd[k] = fwd[k - 1] + link(ends, home, Some(tour[k - 1]), Some(tour[k]));
            bwd[k] = bwd[k - 1] + link(ends, home, Some(tour[k]), Some(tour[k - 1]));
        }
        (fwd, bwd)
    };
    let (mut fwd, mut bwd) = sums(tour);
    for i in 0..n {
        for j in i + 1..n {
            let before = (i > 0).then(|| tour[i - 1]);
            let after = tour.get(j + 1).copied();
            let old = link(ends, home, before, Some(tour[i]))
                + (fwd[j] - fwd[i])
                + link(ends, home, Some(tour[j]), after);
            let new = link(ends, home, before, Some(tour[j]))
                + (bwd[j] - bwd[i])
                + link(ends, home, Some(tour[i]), after);
            if new < old - SAVING_EPS {
                tour[i..=j].reverse();
                (fwd, bwd) = sums(tour);
                improved = true;
            }
        }
    }
    improved
}

/// One pass of segment moves (runs of 1 to 3 items, put back as they were or reversed);
/// true when it shortened the tour.
fn or_opt(ends: &[(Point, Point)], home: Point, tour: &mut Vec<usize>) -> bool {
    let n = tour.len();
    let mut improved = false;
    for len in 1..=3.min(n.saturating_sub(1)) {
        let mut i = 0;
        while i + len <= tour.len() {
            let run: Vec<usize> = tour[i..i + len].to_vec();
            let inner = |r: &[usize]| -> f64 {
                r.windows(2)
                    .map(|w| link(ends, home, Some(w[0]), Some(w[1])))
                    .sum()
            };
            let before = (i > 0).then(|| tour[i - 1]);
            let after = tour.get(i + len).copied();
            let removed = link(ends, home, before, Some(run[0]))
                + link(ends, home, Some(run[len - 1]), after)
                + inner(&run)
                - link(ends, home, before, after);
            let reversed: Vec<usize> = run.iter().rev().copied().collect();
            let inner_fwd = inner(&run);
            let inner_rev = inner(&reversed);
            // The rest of the tour, and the best gap (and way round) to put the run in.
            let rest: Vec<usize> = tour[..i].iter().chain(&tour[i + len..]).copied().collect();
            let mut best: Option<(usize, bool, f64)> = None;
            for g in 0..=rest.len() {
                let a = g.checked_sub(1).map(|k| rest[k]);
                let b = rest.get(g).copied();
                let gap = link(ends, home, a, b);
                for (rev, r, inn) in [(false, &run, inner_fwd), (true, &reversed, inner_rev)] {
                    if g == i && !rev {
                        continue;
                    }
                    let added = link(ends, home, a, Some(r[0]))
                        + inn
                        + link(ends, home, Some(r[len - 1]), b)
                        - gap;
                    if added < removed - SAVING_EPS && best.is_none_or(|(_, _, c)| added < c) {
                        best = Some((g, rev, added));
                    }
                }
            }
            if let Some((g, rev, _)) = best {
                let mut next = rest;
                next.splice(g..g, if rev { reversed } else { run });
                *tour = next;
                improved = true;
            }
            i += 1;
        }
    }
    improved
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_opt_untangles_a_crossed_tour() {
        // Pockets on a line, each starting and ending at its own point: the best tour visits
        // them in order from the origin.
        let xs = [0.0, 40.0, 10.0, 30.0, 20.0];
        let ends: Vec<(Point, Point)> = xs
            .iter()
            .map(|&x| (Point::new(x, 5.0), Point::new(x, 5.0)))
            .collect();
        let t = order_tour(&ends, Point::ORIGIN);
        let visited: Vec<f64> = t.iter().map(|&i| xs[i]).collect();
        assert_eq!(visited, vec![0.0, 10.0, 20.0, 30.0, 40.0]);
        let worst = tour_length(&ends, Point::ORIGIN, &[0, 1, 2, 3, 4]);
        assert!(tour_length(&ends, Point::ORIGIN, &t) < worst);
    }

    #[test]
    fn the_moves_cost_what_the_whole_tour_says() {
        // Items whose entry and exit differ: every accepted move must shorten the tour as
        // recosted from scratch, and the result is a permutation.
        let ends: Vec<(Point, Point)> = (0..9)
            .map(|k| {
                let a = f64::from(k) * 2.3;
                (
                    Point::new(30.0 * a.cos(), 20.0 * (1.7 * a).sin()),
                    Point::new(25.0 * (0.6 * a).sin(), 15.0 * a.cos()),
                )
            })
            .collect();
        let home = Point::new(-5.0, 3.0);
        let mut tour: Vec<usize> = (0..ends.len()).collect();
        let mut len = tour_length(&ends, home, &tour);
        for _ in 0..20 {
            let a = two_opt(&ends, home, &mut tour);
            let after = tour_length(&ends, home, &tour);
            assert!(after <= len + 1e-9 && (a || (after - len).abs() < 1e-12));
            len = after;
            let b = or_opt(&ends, home, &mut tour);
            let after = tour_length(&ends, home, &tour);
            assert!(after <= len + 1e-9 && (b || (after - len).abs() < 1e-12));
            len = after;
        }
        let mut sorted = tour.clone();
        sorted.sort_unstable();
        assert_eq!(sorted, (0..ends.len()).collect::<Vec<_>>());
    }
}
