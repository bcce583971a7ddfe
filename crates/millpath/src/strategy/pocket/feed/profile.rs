//! The feed profile in one dimension: along a path cut into *cells* (the stretch of travel
//! each engagement sample stands for), a lower envelope rate-limited in arc length, a ladder
//! of feed levels, and pieces no shorter than a minimum. See [`super`] for the math and the
//! constants; these functions know nothing of moves or engagement.

/// A stretch of path `len` mm long with one feed factor `value`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Span {
    /// Length, mm.
    pub len: f64,
    /// Feed factor (a fraction of the programmed feed).
    pub value: f64,
}

/// The lower envelope of `targets` rate-limited by `rate` (factor per mm) at the positions
/// `at` (mm, non-decreasing): `g_i = min_j (f_j + rate·|s_i − s_j|)`, the largest profile
/// below every target that changes by at most `rate` per mm. One pass forward and one
/// backward: the forward pass carries `min_{j ≤ i}`, the backward pass `min_{j ≥ i}`.
pub fn envelope(at: &[f64], targets: &[f64], rate: f64) -> Vec<f64> {
    let mut g: Vec<f64> = targets.to_vec();
    for i in 1..g.len() {
        let carried = g[i - 1] + rate * (at[i] - at[i - 1]);
        g[i] = g[i].min(carried);
    }
    for i in (0..g.len().saturating_sub(1)).rev() {
        let carried = g[i + 1] + rate * (at[i + 1] - at[i]);
        g[i] = g[i].min(carried);
    }
    g
}

/// The highest ladder level `1 − n·step` (`n ≥ 0` whole) at most `g + slack`.
pub fn ladder(g: f64, step: f64, slack: f64) -> f64 {
    let n = ((1.0 - g - slack) / step - 1e-9).ceil().max(0.0);
    1.0 - n * step
}

/// Cells of equal value joined, then every span shorter than `min_len` removed without
/// raising any value: a short span with a neighbour at or below its value joins the highest
/// such neighbour (it is lowered to it); a short span lower than every neighbour (a valley,
/// or a dip at an end) grows to `min_len` by taking travel from its neighbours, half from
/// each (they are lowered over that travel), taking a neighbour whole when it is shorter
/// than what is asked of it. Every value of the result is at most the value of each cell
/// it covers, and every span is at least `min_len` long unless the whole is shorter.
pub fn pieces(cells: &[Span], min_len: f64) -> Vec<Span> {
    let mut joined: Vec<Span> = Vec::new();
    for c in cells {
        push_joined(&mut joined, *c);
    }
    // The spans as a gap buffer around the cursor `i`: every step reads and removes spans
    // at `i − 1`, `i` and `i + 1` only, each in constant time (a `Vec::remove` there cost
    // the length of the path: a 2 m square pocket's level has millions of cells).
    let mut v = Gap::new(joined);
    let short = |s: &Span| s.len < min_len - 1e-9;
    // Left to right, stepping back one span after each change: each step removes a span or
    // brings a valley to `min_len` (which it then keeps, only growing); the bound is a guard.
    let mut budget = 4 * v.len() + 16;
    let mut i = 0;
    while v.len() > 1 && i < v.len() && budget > 0 {
        v.seek(i);
        if !short(v.get(i)) {
            i += 1;
            continue;
        }
        budget -= 1;
        let left = i.checked_sub(1);
        let right = (i + 1 < v.len()).then_some(i + 1);
        let vi = *v.get(i);
        let lower = [left, right]
            .into_iter()
            .flatten()
            .filter(|&j| v.get(j).value <= vi.value)
            .max_by(|&a, &b| {
                let (sa, sb) = (v.get(a), v.get(b));
                sa.value
                    .total_cmp(&sb.value)
                    .then(sa.len.total_cmp(&sb.len))
            });
        if let Some(j) = lower {
            v.get_mut(j).len += vi.len;
            v.remove(i);
            let j = if j > i { j - 1 } else { j };
            i = coalesce(&mut v, j).saturating_sub(1);
            continue;
        }
        let need = min_len - vi.len;
        let (take_left, take_right) = match (left, right) {
            (Some(_), Some(_)) => (0.5 * need, 0.5 * need),
            (Some(_), None) => (need, 0.0),
            _ => (0.0, need),
        };
        // Right first, so that `i` stays valid.
        if let Some(r) = right
            && take_right > 0.0
        {
            let rl = v.get(r).len;
            if rl <= take_right + 1e-9 {
                v.get_mut(i).len += rl;
                v.remove(r);
            } else {
                v.get_mut(r).len -= take_right;
                v.get_mut(i).len += take_right;
            }
        }
        if let Some(l) = left
            && take_left > 0.0
        {
            let ll = v.get(l).len;
            if ll <= take_left + 1e-9 {
                v.get_mut(i).len += ll;
                v.remove(l);
                i -= 1;
            } else {
                v.get_mut(l).len -= take_left;
                v.get_mut(i).len += take_left;
            }
        }
        i = coalesce(&mut v, i).saturating_sub(1);
    }
    v.into_vec()
}

/// Spans split at a cursor: `left` before it, `right` from it on; reading or removing
/// next to the cursor costs a constant.
struct Gap {
    left: Vec<Span>,
    right: std::collections::VecDeque<Span>,
}

impl Gap {
    fn new(v: Vec<Span>) -> Gap {
        Gap {
            left: Vec::with_capacity(v.len()),
            right: v.into(),
        }
    }

    fn len(&self) -> usize {
        self.left.len() + self.right.len()
    }

    /// Moves the cursor to index `k`.
    fn seek(&mut self, k: usize) {
        while self.left.len() > k {
            if let Some(s) = self.left.pop() {
                self.right.push_front(s);
            }
        }
        while self.left.len() < k {
            match self.right.pop_front() {
                Some(s) => self.left.push(s),
                None => break,
            }
        }
    }

    fn get(&self, k: usize) -> &Span {
        let n = self.left.len();
        if k < n {
            &self.left[k]
        } else {
            &self.right[k - n]
        }
    }

    fn get_mut(&mut self, k: usize) -> &mut Span {
        let n = self.left.len();
        if k < n {
            &mut self.left[k]
        } else {
            &mut self.right[k - n]
        }
    }

    fn remove(&mut self, k: usize) {
        let n = self.left.len();
        if k < n {
            self.left.remove(k);
        } else {
            self.right.remove(k - n);
        }
    }

    fn into_vec(self) -> Vec<Span> {
        let mut v = self.left;
        v.extend(self.right);
        v
    }
}

/// Appends `c`, joining it to the last span when their values are equal.
fn push_joined(v: &mut Vec<Span>, c: Span) {
    match v.last_mut() {
        Some(last) if (last.value - c.value).abs() <= 1e-12 => last.len += c.len,
        _ => v.push(c),
    }
}

/// Joins span `i` with its neighbours where their values are equal; returns the index of
/// the joined span.
fn coalesce(v: &mut Gap, i: usize) -> usize {
    let same = |a: &Span, b: &Span| (a.value - b.value).abs() <= 1e-12;
    if i + 1 < v.len() && same(v.get(i), v.get(i + 1)) {
        let add = v.get(i + 1).len;
        v.get_mut(i).len += add;
        v.remove(i + 1);
    }
    if i > 0 && i < v.len() && same(v.get(i - 1), v.get(i)) {
        let add = v.get(i).len;
        v.get_mut(i - 1).len += add;
        v.remove(i);
        return i - 1;
    }
    i
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The same spans as the plain `Vec` version (each removal shifting the rest), on
    /// random profiles of many short spans.
    #[test]
    fn pieces_match_the_plain_vec_version() {
        let mut seed = 11u64;
        let mut rnd = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut cases = 0;
        for n in [1usize, 2, 3, 10, 100, 2000] {
            for _ in 0..20 {
                let cells: Vec<Span> = (0..n)
                    .map(|_| Span {
                        len: 0.05 + 3.0 * rnd(),
                        value: 1.0 - 0.05 * (rnd() * 6.0).floor(),
                    })
                    .collect();
                for min_len in [0.5, 2.0, 8.0] {
                    assert_eq!(pieces(&cells, min_len), pieces_by_vec(&cells, min_len));
                    cases += 1;
                }
            }
        }
        assert_eq!(cases, 360);
    }

    fn pieces_by_vec(cells: &[Span], min_len: f64) -> Vec<Span> {
        let mut v: Vec<Span> = Vec::new();
        for c in cells {
            push_joined(&mut v, *c);
        }
        let short = |s: &Span| s.len < min_len - 1e-9;
        // Left to right, stepping back one span after each change: each step removes a span or
        // brings a valley to `min_len` (which it then keeps, only growing); the bound is a guard.
        let mut budget = 4 * v.len() + 16;
        let mut i = 0;
        while v.len() > 1 && i < v.len() && budget > 0 {
            if !short(&v[i]) {
                i += 1;
                continue;
            }
            budget -= 1;
            let left = i.checked_sub(1);
            let right = (i + 1 < v.len()).then_some(i + 1);
            let lower = [left, right]
                .into_iter()
                .flatten()
                .filter(|&j| v[j].value <= v[i].value)
                .max_by(|&a, &b| {
                    v[a].value
                        .total_cmp(&v[b].value)
                        .then(v[a].len.total_cmp(&v[b].len))
                });
            if let Some(j) = lower {
                v[j].len += v[i].len;
                v.remove(i);
                let j = if j > i { j - 1 } else { j };
                i = coalesce_vec(&mut v, j).saturating_sub(1);
                continue;
            }
            let need = min_len - v[i].len;
            let (take_left, take_right) = match (left, right) {
                (Some(_), Some(_)) => (0.5 * need, 0.5 * need),
                (Some(_), None) => (need, 0.0),
                _ => (0.0, need),
            };
            // Right first, so that `i` stays valid.
            if let Some(r) = right
                && take_right > 0.0
            {
                if v[r].len <= take_right + 1e-9 {
                    v[i].len += v[r].len;
                    v.remove(r);
                } else {
                    v[r].len -= take_right;
                    v[i].len += take_right;
                }
            }
            if let Some(l) = left
                && take_left > 0.0
            {
                if v[l].len <= take_left + 1e-9 {
                    v[i].len += v[l].len;
                    v.remove(l);
                    i -= 1;
                } else {
                    v[l].len -= take_left;
                    v[i].len += take_left;
                }
            }
            i = coalesce_vec(&mut v, i).saturating_sub(1);
        }
        v
    }

    fn coalesce_vec(v: &mut Vec<Span>, i: usize) -> usize {
        let same = |a: &Span, b: &Span| (a.value - b.value).abs() <= 1e-12;
        if i + 1 < v.len() && same(&v[i], &v[i + 1]) {
            v[i].len += v[i + 1].len;
            v.remove(i + 1);
        }
        if i > 0 && i < v.len() && same(&v[i - 1], &v[i]) {
            v[i - 1].len += v[i].len;
            v.remove(i);
            return i - 1;
        }
        i
    }

    /// The envelope equals the brute-force minimum, stays below the targets and changes by
    /// at most the rate per mm.
    #[test]
    fn envelope_is_the_rate_limited_lower_envelope() {
        let at: Vec<f64> = (0..200)
            .map(|k| 0.1 * f64::from(k) + 0.001 * f64::from(k % 7))
            .collect();
        let targets: Vec<f64> = (0..200)
            .map(|k| match k {
                50..=55 => 0.75,
                120 => 0.9,
                150..=190 => 0.8 + 0.01 * f64::from(k % 3),
                _ => 1.0,
            })
            .collect();
        let rate = 0.02;
        let g = envelope(&at, &targets, rate);
        for i in 0..at.len() {
            let brute = (0..at.len())
                .map(|j| targets[j] + rate * (at[i] - at[j]).abs())
                .fold(f64::INFINITY, f64::min);
            assert!((g[i] - brute).abs() < 1e-12, "{i}");
            assert!(g[i] <= targets[i]);
            if i > 0 {
                assert!((g[i] - g[i - 1]).abs() <= rate * (at[i] - at[i - 1]) + 1e-12);
            }
        }
        // It drops before the dip: 12.5 mm ahead of the 0.75 at s = 5 mm the feed is
        // already below 1 from the start of the path.
        assert!(g[0] < 1.0);
    }

    #[test]
    fn ladder_rounds_down_to_steps_within_the_slack() {
        let eq = |a: f64, b: f64| (a - b).abs() < 1e-12;
        assert!(eq(ladder(1.0, 0.02, 0.005), 1.0));
        assert!(eq(ladder(0.996, 0.02, 0.005), 1.0));
        assert!(eq(ladder(0.994, 0.02, 0.005), 0.98));
        assert!(eq(ladder(0.98, 0.02, 0.005), 0.98));
        assert!(eq(ladder(0.9751, 0.02, 0.005), 0.98));
        assert!(eq(ladder(0.97, 0.02, 0.005), 0.96));
        for k in 0..1000 {
            let g = 0.7 + 0.0003 * f64::from(k);
            let l = ladder(g, 0.02, 0.005);
            assert!(
                l <= g + 0.005 + 1e-12 && l > g + 0.005 - 0.02 - 1e-12,
                "{g} {l}"
            );
        }
    }

    /// Pieces never rise above a cell they cover, are at least the minimum long, and cover
    /// the same length.
    #[test]
    fn pieces_are_long_enough_and_never_above_the_cells() {
        let mut cells = Vec::new();
        // Noise around a ladder line, a staircase down and up, a short dip, a short peak.
        for k in 0..40 {
            cells.push(Span {
                len: 0.1,
                value: if k % 3 == 0 { 0.96 } else { 0.98 },
            });
        }
        for step in [0.96, 0.94, 0.92, 0.9, 0.92, 0.94, 0.96, 1.0] {
            for _ in 0..7 {
                cells.push(Span {
                    len: 0.1,
                    value: step,
                });
            }
        }
        cells.push(Span {
            len: 0.2,
            value: 0.8,
        });
        for _ in 0..30 {
            cells.push(Span {
                len: 0.1,
                value: 1.0,
            });
        }
        cells.push(Span {
            len: 0.3,
            value: 1.0,
        });
        cells.push(Span {
            len: 5.0,
            value: 0.9,
        });
        let total: f64 = cells.iter().map(|c| c.len).sum();
        let p = pieces(&cells, 1.0);
        assert!((p.iter().map(|s| s.len).sum::<f64>() - total).abs() < 1e-9);
        assert!(p.iter().all(|s| s.len >= 1.0 - 1e-9), "{p:?}");
        assert!(
            p.windows(2)
                .all(|w| (w[0].value - w[1].value).abs() > 1e-12)
        );
        // Every cell's midpoint lies in a piece no higher than the cell.
        let mut start = 0.0;
        for c in &cells {
            let mid = start + 0.5 * c.len;
            start += c.len;
            let mut end = 0.0;
            let piece = p
                .iter()
                .find(|q| {
                    end += q.len;
                    mid < end
                })
                .unwrap();
            assert!(piece.value <= c.value + 1e-12, "at {mid}: {p:?}");
        }
        // One cell, or a whole shorter than the minimum: a single span at the lowest value.
        let one = pieces(&cells[..3], 1.0);
        assert_eq!(one.len(), 1);
        assert!((one[0].value - 0.96).abs() < 1e-12);
    }
}
