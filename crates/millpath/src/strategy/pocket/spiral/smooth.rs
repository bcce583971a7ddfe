//! Curvature-continuous output: the spiral's interior path with its curvature steps spread
//! into ramps, written as chords.
//!
//! The rounded loops are lines and arcs: where a line meets an arc of radius `R` the
//! curvature jumps by `1/R`, and a jerk-limited controller must slow there (the normal
//! acceleration `v²κ` cannot step). The path is sampled every `δ` mm (equally spaced over the
//! stretch) and each sample replaced by the mean of the samples within `±W/2` of it (a moving average in arc length): a
//! curvature step becomes a linear ramp over `W`, the path curvature-continuous. On an arc of
//! radius `R` the mean moves the path towards the centre by about `W²/(24·R)`; the window is
//! therefore `W = min(W_max, √(24·ε·R))` with `R` the smallest radius of the exact segments
//! within `W_max/2`, so that no point moves by more than `ε`
//! ([`SmoothOptions::max_shift`]), and shrinks symmetrically at the ends of a stretch, which
//! stay where they are; from one sample to the next it changes by one sample at most (a
//! window shrinking at once moves the mean across the path by the difference of the shifts,
//! a step back).
//!
//! Stretches are split at kinks (a deflection above [`SmoothOptions::kink`]: a straight step,
//! an unrounded corner, whose material must still be reached) and nothing from the last
//! change onto a wall's loop on is touched (the wall's loop is cut exactly). The result is
//! written as chords within [`SmoothOptions::chord_tolerance`] of the smoothed samples.

use super::super::segments::Seg;
use crate::geom::{Point, Vec2};

/// How the interior path is smoothed.
#[derive(Debug, Clone, Copy)]
pub struct SmoothOptions {
    /// Largest averaging window, mm.
    pub max_window: f64,
    /// Largest displacement of the path by the smoothing, mm.
    pub max_shift: f64,
    /// Sample spacing, mm.
    pub spacing: f64,
    /// Largest distance between a chord and the samples it replaces, mm.
    pub chord_tolerance: f64,
    /// Deflection (rad) from which a junction is a kink that stays.
    pub kink: f64,
}

/// `path` with `path[..until]` smoothed (see the module docs) and as chords; the rest as it is.
pub fn smooth(path: &[Seg], until: usize, opts: &SmoothOptions) -> Vec<Seg> {
    let until = until.min(path.len());
    let mut out = Vec::with_capacity(path.len());
    let mut start = 0;
    for i in 0..until {
        let kink = i + 1 == until || {
            let t0 = path[i].tangent_at(path[i].length());
            let t1 = path[i + 1].tangent_at(0.0);
            (t1 - t0).length() > opts.kink
        };
        if kink {
            out.extend(smooth_stretch(&path[start..=i], opts));
            start = i + 1;
        }
    }
    out.extend(path[until..].iter().copied());
    out
}

/// One stretch without kinks, smoothed and as chords.
fn smooth_stretch(segs: &[Seg], opts: &SmoothOptions) -> Vec<Seg> {
    let total: f64 = segs.iter().map(Seg::length).sum();
    if segs.is_empty() || total < 4.0 * opts.spacing {
        return segs.to_vec();
    }
    // Samples equally spaced in arc length over the whole stretch (a mean over unevenly
    // spaced samples would pull the path along itself, towards where they crowd), each with
    // the radius of the segment it lies on (infinite on lines).
    let count = ((total / opts.spacing).ceil() as usize).max(4);
    let ds = total / count as f64;
    let mut pts: Vec<Point> = Vec::with_capacity(count + 1);
    let mut radius: Vec<f64> = Vec::with_capacity(count + 1);
    let (mut j, mut start) = (0, 0.0);
    for k in 0..count {
        let s = ds * k as f64;
        while j + 1 < segs.len() && s > start + segs[j].length() {
            start += segs[j].length();
            j += 1;
        }
        let g = &segs[j];
        pts.push(g.point_at((s - start).clamp(0.0, g.length())));
        radius.push(g.arc.map_or(f64::INFINITY, |a| a.radius));
    }
    if let Some(last) = segs.last() {
        pts.push(last.b);
        radius.push(last.arc.map_or(f64::INFINITY, |a| a.radius));
    }
    let n = pts.len();
    let half_max = ((0.5 * opts.max_window / opts.spacing).floor() as usize).max(1);
    // Smallest radius near each sample, and the window's half-width in samples.
    let half: Vec<usize> = (0..n)
        .map(|i| {
            let lo = i.saturating_sub(half_max);
            let hi = (i + half_max).min(n - 1);
            let r = radius[lo..=hi]
                .iter()
                .copied()
                .fold(f64::INFINITY, f64::min);
            let w = (24.0 * opts.max_shift * r).sqrt().min(opts.max_window);
            let h = ((0.5 * w / opts.spacing).floor() as usize)
                .min(i)
                .min(n - 1 - i);
            h.min(half_max)
        })
        .collect();
    // Windows that change by at most one sample from one sample to the next: a window that
    // shrinks at once moves the mean across the path by the difference of the two shifts.
    let mut half = half;
    for i in 1..n {
        half[i] = half[i].min(half[i - 1] + 1);
    }
    for i in (0..n - 1).rev() {
        half[i] = half[i].min(half[i + 1] + 1);
    }
    // Prefix sums for the means.
    let mut cx = vec![0.0; n + 1];
    let mut cy = vec![0.0; n + 1];
    for (i, p) in pts.iter().enumerate() {
        cx[i + 1] = cx[i] + p.x;
        cy[i + 1] = cy[i] + p.y;
    }
    let smoothed: Vec<Point> = (0..n)
        .map(|i| {
            let h = half[i];
            let (a, b) = (i - h, i + h + 1);
            let m = (b - a) as f64;
            Point::new((cx[b] - cx[a]) / m, (cy[b] - cy[a]) / m)
        })
        .collect();
    chords(&smoothed, opts.chord_tolerance)
}

/// Chords through `pts` (first and last kept), each as long as every sample it passes by is
/// within `tol` of it (the end found by doubling, then bisection).
fn chords(pts: &[Point], tol: f64) -> Vec<Seg> {
    let fits = |a: usize, b: usize| (a + 1..b).all(|k| deviation(pts[a], pts[b], pts[k]) <= tol);
    let last = pts.len().saturating_sub(1);
    let mut out = Vec::new();
    let mut a = 0;
    while a < last {
        let mut step = 1;
        let mut good = a + 1;
        while good < last {
            let b = (a + 2 * step).min(last);
            if !fits(a, b) {
                break;
            }
            good = b;
            step *= 2;
        }
        let (mut lo, mut hi) = (good, (a + 2 * step).min(last));
        while hi > lo + 1 {
            let mid = (lo + hi) / 2;
            if fits(a, mid) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        if pts[a].distance(pts[lo]) > 1e-12 {
            out.push(Seg::line(pts[a], pts[lo]));
        }
        a = lo;
    }
    out
}

/// Distance from `p` to the segment `a`–`b`.
fn deviation(a: Point, b: Point, p: Point) -> f64 {
    let d: Vec2 = b - a;
    let l2 = d.dot(d);
    let t = if l2 > 0.0 {
        ((p - a).dot(d) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    a.lerp(b, t).distance(p)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn opts() -> SmoothOptions {
        SmoothOptions {
            max_window: 6.0,
            max_shift: 0.1,
            spacing: 0.1,
            chord_tolerance: 0.002,
            kink: 0.1,
        }
    }

    /// A line, a quarter arc of radius 10, a line: the curvature steps 0 → 0.1 → 0.
    fn corner() -> Vec<Seg> {
        let q = (std::f64::consts::PI / 8.0).tan();
        vec![
            Seg::line(Point::new(-30.0, 0.0), Point::new(0.0, 0.0)),
            Seg::from_bulge(Point::new(0.0, 0.0), Point::new(10.0, 10.0), q),
            Seg::line(Point::new(10.0, 10.0), Point::new(10.0, 40.0)),
        ]
    }

    /// Discrete curvature (Menger) along a polyline's vertices.
    fn curvatures(segs: &[Seg]) -> Vec<f64> {
        segs.windows(2)
            .map(|w| {
                let (a, b, c) = (w[0].a, w[0].b, w[1].b);
                let cross = (b - a).cross(c - b);
                2.0 * cross.abs() / (a.distance(b) * b.distance(c) * a.distance(c)).max(1e-300)
            })
            .collect()
    }

    #[test]
    fn a_curvature_step_becomes_a_ramp_within_the_shift() {
        let path = corner();
        let out = smooth(&path, path.len(), &opts());
        // Ends kept, path continuous, every point within the shift of the exact corner.
        assert!(out[0].a.distance(Point::new(-30.0, 0.0)) < 1e-12);
        assert!(
            out.last()
                .expect("moves")
                .b
                .distance(Point::new(10.0, 40.0))
                < 1e-12
        );
        assert!(out.windows(2).all(|w| w[0].b.distance(w[1].a) < 1e-12));
        let ring = super::super::ring::Ring::from_segs(path.clone());
        for g in &out {
            for p in [g.a, g.b, g.a.lerp(g.b, 0.5)] {
                assert!(ring.project(p).1 <= 0.1 + 0.002 + 1e-9, "{p:?}");
            }
        }
        // Curvature between consecutive chords changes by little: no step of 1/R.
        let k = curvatures(&out);
        let steps = k
            .windows(2)
            .map(|w| (w[1] - w[0]).abs())
            .fold(0.0, f64::max);
        assert!(steps < 0.035, "largest curvature step {steps}");
        // The exact path's step.
        assert!(k.iter().copied().fold(0.0, f64::max) < 0.1 + 0.01);
    }

    #[test]
    fn kinks_and_the_kept_tail_stay_exact() {
        // A right-angle corner: not smoothed.
        let path = vec![
            Seg::line(Point::new(0.0, 0.0), Point::new(20.0, 0.0)),
            Seg::line(Point::new(20.0, 0.0), Point::new(20.0, 20.0)),
        ];
        let out = smooth(&path, 2, &opts());
        assert!(
            out.iter()
                .any(|g| g.b.distance(Point::new(20.0, 0.0)) < 1e-12)
        );
        // Nothing after `until` changes.
        let c = corner();
        let out = smooth(&c, 1, &opts());
        assert_eq!(&out[out.len() - 2..], &c[1..]);
    }
}
