//! Shared by the spline and probe tests: reading a program, and a reference NURBS evaluator
//! (Cox–de Boor, written apart from the reader's) to judge the curves it reads.
#![allow(dead_code)]

use millpath::gcode::{ReadMove, Reader, ReaderOptions};

/// The moves of `text` read with the default options.
pub fn try_read(text: &str) -> Result<Vec<ReadMove>, millpath::Error> {
    Reader::new(text.as_bytes(), ReaderOptions::default()).collect()
}

/// The moves of `text`, which must read.
pub fn read(text: &str) -> Vec<ReadMove> {
    try_read(text).unwrap()
}

/// The refusal of `text`, which must be refused.
pub fn refusal(text: &str) -> String {
    match try_read(text) {
        Ok(m) => panic!("read {} moves, expected a refusal", m.len()),
        Err(e) => e.to_string(),
    }
}

/// Cox–de Boor basis N(i, k, u) of order `k` on the knots `t`, half-open spans, the last
/// non-empty span closed.
pub fn basis(i: usize, k: usize, u: f64, t: &[f64]) -> f64 {
    if k == 1 {
        let end = t[t.len() - 1];
        let inside = t[i] <= u && u < t[i + 1];
        let last = u >= end && t[i] < end && t[i + 1] >= end;
        return f64::from(u8::from(inside || last));
    }
    let a = if t[i + k - 1] > t[i] {
        (u - t[i]) / (t[i + k - 1] - t[i]) * basis(i, k - 1, u, t)
    } else {
        0.0
    };
    let b = if t[i + k] > t[i + 1] {
        (t[i + k] - u) / (t[i + k] - t[i + 1]) * basis(i + 1, k - 1, u, t)
    } else {
        0.0
    };
    a + b
}

/// The rational curve of the weighted control points `(x, y, w)`, order `k`, knots `t`, at `u`.
pub fn curve_on_knots(cp: &[(f64, f64, f64)], k: usize, t: &[f64], u: f64) -> (f64, f64) {
    let (mut x, mut y, mut d) = (0.0, 0.0, 0.0);
    for (i, (px, py, w)) in cp.iter().enumerate() {
        let b = basis(i, k, u, t) * w;
        x += b * px;
        y += b * py;
        d += b;
    }
    (x / d, y / d)
}

/// Uniform clamped knots 0, …, 0, 1, 2, …, n − k + 2, … (G5.2's) for `n + 1` points of order
/// `k`.
pub fn clamped_knots(n: usize, k: usize) -> Vec<f64> {
    (0..=n + k)
        .map(|i| (i.saturating_sub(k - 1)).min(n + 1 - (k - 1)) as f64)
        .collect()
}

/// Distance from `p` to the segment `a b`.
pub fn distance_to_segment(p: (f64, f64), a: (f64, f64), b: (f64, f64)) -> f64 {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let l2 = dx * dx + dy * dy;
    let s = if l2 > 0.0 {
        (((p.0 - a.0) * dx + (p.1 - a.1) * dy) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p.0 - a.0 - s * dx).hypot(p.1 - a.1 - s * dy)
}

/// The farthest the densely sampled curve `dense` comes from the polyline `poly`, both in
/// order along the curve (the nearest segment is searched in a window that moves forward).
pub fn curve_off_polyline(dense: &[(f64, f64)], poly: &[(f64, f64)]) -> f64 {
    let mut seg = 0;
    let mut worst: f64 = 0.0;
    for p in dense {
        let (best, at) = (seg..(seg + 40).min(poly.len() - 1))
            .map(|j| (distance_to_segment(*p, poly[j], poly[j + 1]), j))
            .fold((f64::INFINITY, seg), |a, b| if b.0 < a.0 { b } else { a });
        seg = at;
        worst = worst.max(best);
    }
    worst
}

/// Asserts that every vertex of `poly` lies on the densely sampled curve `dense` (within
/// 1e-5 mm of its nearest chord, searched forward).
pub fn assert_vertices_on_curve(poly: &[(f64, f64)], dense: &[(f64, f64)]) {
    let mut j = 0;
    for v in poly {
        let (d, at) = (j..dense.len() - 1)
            .take(5000)
            .map(|i| (distance_to_segment(*v, dense[i], dense[i + 1]), i))
            .fold((f64::INFINITY, j), |a, b| if b.0 < a.0 { b } else { a });
        j = at;
        assert!(d < 1e-5, "vertex {v:?} is {d} mm off the curve");
    }
}
