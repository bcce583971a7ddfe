//! A pass's positions before they are written: smoothed ([`smoothed`]), then, on tight
//! curves of a thin cut, with the chords' midpoints added ([`refined`]; see the parent
//! module).

use super::SMOOTH_ROUNDS;
use crate::geom::Point;

/// The positions with their wobble smoothed out: Taubin's λ|μ smoothing (a Laplacian step
/// `λ = 0.5` towards the neighbours' mean, then `μ = −0.53` away from it, which removes the
/// short wavelengths without shrinking the curve), each position kept within `within` of
/// where it was; the ends stay. The stepper's turns come from cell counts, so consecutive
/// positions zigzag by a few hundredths of a millimetre; through them, an interpolating
/// curve changes its turn at every position, and the arcs fitted to it are as short as the
/// steps.
pub(super) fn smoothed(pts: &[Point], within: f64) -> Vec<Point> {
    let n = pts.len();
    if n < 3 || within <= 0.0 {
        return pts.to_vec();
    }
    let mut p = pts.to_vec();
    let mut next = p.clone();
    for _ in 0..SMOOTH_ROUNDS {
        for f in [0.5, -0.53] {
            for i in 1..n - 1 {
                let m = p[i - 1].midpoint(p[i + 1]);
                let q = p[i] + (m - p[i]) * f;
                let d = q - pts[i];
                let len = d.length();
                next[i] = if len > within {
                    pts[i] + d * (within / len)
                } else {
                    q
                };
            }
            std::mem::swap(&mut p, &mut next);
        }
    }
    p
}

/// The positions `pts` with, between two of them, the midpoint of the four-point
/// interpolating subdivision (`(−a + 9b + 9c − d)/16`; the three-point rule at the ends) where
/// it lies more than `tau` off the chord and `ok` allows it.
pub(super) fn refined(pts: &[Point], tau: f64, ok: impl Fn(Point) -> bool) -> Vec<Point> {
    let n = pts.len();
    if n < 3 {
        return pts.to_vec();
    }
    let mut out = Vec::with_capacity(2 * n);
    for i in 0..n - 1 {
        out.push(pts[i]);
        let (b, c) = (pts[i], pts[i + 1]);
        let mid = b.lerp(c, 0.5);
        let m = match (i.checked_sub(1).map(|k| pts[k]), pts.get(i + 2)) {
            (Some(a), Some(&d)) => mid + ((b - a) + (c - d)) * (1.0 / 16.0),
            (Some(a), None) => mid + ((b - a) * 0.5 - (c - b) * 0.5) * 0.25,
            (None, Some(&d)) => mid + ((c - d) * 0.5 - (b - c) * 0.5) * 0.25,
            (None, None) => mid,
        };
        if m.distance(mid) > tau && ok(m) {
            out.push(m);
        }
    }
    out.push(pts[n - 1]);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The largest distance from the chords between `pts` to the circle of radius `r` about
    /// the origin, sampled along each chord.
    fn sagitta(pts: &[Point], r: f64) -> f64 {
        pts.windows(2)
            .flat_map(|w| (0..=20).map(move |k| w[0].lerp(w[1], f64::from(k) / 20.0)))
            .map(|p| (r - p.distance(Point::ORIGIN)).abs())
            .fold(0.0, f64::max)
    }

    /// Positions `δ = 0.79` mm apart on circles of radius 2–8 mm (the curves a thin cut
    /// bends along in a channel): where a chord's sagitta `δ²/8R` exceeds `tau`, its midpoint
    /// is added, on the circle within a twentieth of the sagitta, and the chords then stray
    /// from the circle by about a quarter of what they did (under 0.3); where it does not,
    /// nothing is added.
    /// A straight run never gets a midpoint, nor a curve where `ok` refuses every point.
    #[test]
    fn midpoints_quarter_the_chords_sagitta_on_tight_curves() {
        let delta = 0.79;
        for r in [2.0, 3.0, 5.0, 8.0] {
            let step = delta / r;
            let pts: Vec<Point> = (0..12)
                .map(|k| {
                    let a = 0.3 + step * f64::from(k);
                    Point::new(r * a.cos(), r * a.sin())
                })
                .collect();
            let sag = r - (r * r - 0.25 * delta * delta).sqrt();
            let tau = 0.0127;
            let fine = refined(&pts, tau, |_| true);
            if sag > 1.01 * tau {
                assert_eq!(fine.len(), 2 * pts.len() - 1, "r {r}");
                for m in fine.iter().skip(1).step_by(2) {
                    let off = (m.distance(Point::ORIGIN) - r).abs();
                    assert!(off < 0.05 * sag, "r {r}: midpoint {off} mm off the circle");
                }
                let (before, after) = (sagitta(&pts, r), sagitta(&fine, r));
                assert!(
                    after < 0.3 * before && after > 0.2 * before,
                    "r {r}: {before} → {after}"
                );
            } else if sag < 0.99 * tau {
                assert_eq!(fine, pts, "r {r}");
            }
            assert_eq!(refined(&pts, tau, |_| false), pts);
        }
        let line: Vec<Point> = (0..10)
            .map(|k| Point::new(0.79 * f64::from(k), 1.0))
            .collect();
        assert_eq!(refined(&line, 1e-9, |_| true), line);
    }
}
