//! Quintic polynomials in time, built from boundary states (the paper's equations 7a–7b), and
//! their exact extrema.
//!
//! # Boundary-value solution
//! On `u = t/T ∈ [0, 1]` write `p(u) = Σ C_n uⁿ`. With position, velocity and acceleration
//! given at both ends (time derivatives `v, a`, so `p'(0) = v0 T`, `p''(0) = a0 T²`):
//! `C0 = q0`, `C1 = v0 T`, `C2 = a0 T²/2`, and with
//! `D1 = q1 − C0 − C1 − C2`, `D2 = v1 T − C1 − 2 C2`, `D3 = a1 T² − 2 C2`
//! the end conditions `C3 + C4 + C5 = D1`, `3C3 + 4C4 + 5C5 = D2`, `6C3 + 12C4 + 20C5 = D3`
//! give
//!
//! ```text
//! C3 = 10 D1 − 4 D2 + D3/2,   C4 = −15 D1 + 7 D2 − D3,   C5 = 6 D1 − 3 D2 + D3/2.
//! ```
//! **Misprint in the paper:** equation (7b) has `+D3, −2D3, +D3` with the same `D3`; that only
//! holds if `D3` were `(r''(k+1) − 2C2)/2`. (It also writes `r(k)'''` for `r(k)''` among the
//! givens.) In time, `c_n = C_n / Tⁿ`.
//!
//! Two more misprints in the paper's equations (7d)–(7e), which map the parameter `u` to time
//! (we do not need them: our quintics are in time directly, `u = t/T`):
//! * (7d) divides by `√(x_w² + y_w² + z_w²)`; the chain rule `u̇ = v/|r'(u)|` needs the
//!   derivatives `√(x_w'² + y_w'² + z_w'²)`, and `ü = v̇/|r'| − v² (r'·r'')/|r'|⁴` likewise;
//! * (7e) gives the jerk as `w''' u̇³ + 3 w'' u̇ ü`; differentiating
//!   `a = w'' u̇² + w' ü` gives `w''' u̇³ + 3 w'' u̇ ü + w' u⃛` — the last term is missing.
//!
//! # Exact extrema
//! Velocity is a quartic, acceleration a cubic, jerk a quadratic. The largest `|v|` on `[0, T]`
//! is at an end or at a root of the acceleration (a cubic), the largest `|a|` at an end or at a
//! root of the jerk (a quadratic, closed form), the largest `|j|` at an end or at the root of
//! the snap (linear). Cubic roots are isolated exactly: the roots of its derivative (closed
//! form) split `[0, T]` into monotone pieces, and a piece whose ends differ in sign holds
//! exactly one root, found by Newton's method safeguarded by bisection (to adjacent
//! floating-point numbers or a step below two ulps).

/// `q(t) = Σ c[n] tⁿ` on `[0, duration]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Quintic {
    /// Coefficients in time (units/sⁿ).
    pub c: [f64; 6],
    /// Duration, s.
    pub duration: f64,
}

/// Position, velocity and acceleration at one end.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct End {
    /// Position.
    pub q: f64,
    /// Velocity (per s).
    pub v: f64,
    /// Acceleration (per s²).
    pub a: f64,
}

impl Quintic {
    /// The quintic joining `e0` at `t = 0` to `e1` at `t = duration`.
    pub fn from_ends(e0: End, e1: End, duration: f64) -> Quintic {
        let t = duration;
        let c0 = e0.q;
        let c1 = e0.v * t;
        let c2 = 0.5 * e0.a * t * t;
        let d1 = e1.q - c0 - c1 - c2;
        let d2 = e1.v * t - c1 - 2.0 * c2;
        let d3 = e1.a * t * t - 2.0 * c2;
        let c3 = 10.0 * d1 - 4.0 * d2 + 0.5 * d3;
        let c4 = -15.0 * d1 + 7.0 * d2 - d3;
        let c5 = 6.0 * d1 - 3.0 * d2 + 0.5 * d3;
        let (t2, t3) = (t * t, t * t * t);
        Quintic {
            c: [c0, c1 / t, c2 / t2, c3 / t3, c4 / (t3 * t), c5 / (t3 * t2)],
            duration,
        }
    }

    /// Position, velocity, acceleration, jerk at `t`.
    pub fn eval(&self, t: f64) -> [f64; 4] {
        let c = &self.c;
        [
            c[0] + t * (c[1] + t * (c[2] + t * (c[3] + t * (c[4] + t * c[5])))),
            c[1] + t * (2.0 * c[2] + t * (3.0 * c[3] + t * (4.0 * c[4] + t * 5.0 * c[5]))),
            2.0 * c[2] + t * (6.0 * c[3] + t * (12.0 * c[4] + t * 20.0 * c[5])),
            6.0 * c[3] + t * (24.0 * c[4] + t * 60.0 * c[5]),
        ]
    }

    /// Exact maxima of `|v|, |a|, |j|` over `[0, duration]` (see the module docs).
    pub fn max_abs_derivs(&self) -> [f64; 3] {
        let c = &self.c;
        let t_end = self.duration;
        let acc = [2.0 * c[2], 6.0 * c[3], 12.0 * c[4], 20.0 * c[5]];
        let jerk = [6.0 * c[3], 24.0 * c[4], 60.0 * c[5]];
        let snap = [24.0 * c[4], 120.0 * c[5]];
        let mut out = [0.0f64; 3];
        for (k, roots) in [
            real_roots_in(&acc, 0.0, t_end),
            real_roots_in(&jerk, 0.0, t_end),
            real_roots_in(&snap, 0.0, t_end),
        ]
        .into_iter()
        .enumerate()
        {
            let mut m = 0.0f64;
            for t in roots.into_iter().chain([0.0, t_end]) {
                m = m.max(self.eval(t)[k + 1].abs());
            }
            out[k] = m;
        }
        out
    }
}

/// Evaluates `Σ p[n] xⁿ`.
pub fn poly_eval(p: &[f64], x: f64) -> f64 {
    p.iter().rev().fold(0.0, |acc, &c| acc * x + c)
}

/// `Σ p[n] xⁿ` and its derivative.
fn poly_eval_d(p: &[f64], x: f64) -> (f64, f64) {
    let mut v = 0.0;
    let mut d = 0.0;
    for &c in p.iter().rev() {
        d = d * x + v;
        v = v * x + c;
    }
    (v, d)
}

/// Real roots in `[lo, hi]` of a polynomial of degree ≤ 3 (`p[n]` the coefficient of `xⁿ`).
pub fn real_roots_in(p: &[f64], lo: f64, hi: f64) -> Vec<f64> {
    let mut deg = p.len();
    while deg > 0 && p[deg - 1] == 0.0 {
        deg -= 1;
    }
    let p = &p[..deg];
    let inside = |x: f64| x.is_finite() && x >= lo && x <= hi;
    match deg {
        0 | 1 => vec![],
        2 => {
            let x = -p[0] / p[1];
            if inside(x) { vec![x] } else { vec![] }
        }
        3 => {
            let (c, b, a) = (p[0], p[1], p[2]);
            let disc = b * b - 4.0 * a * c;
            if disc < 0.0 {
                return vec![];
            }
            // Stable form: no cancellation between −b and √disc.
            let q = -0.5 * (b + b.signum() * disc.sqrt());
            let mut r = vec![];
            if q != 0.0 {
                r.push(q / a);
                r.push(c / q);
            } else {
                r.push(0.0);
            }
            r.retain(|&x| inside(x));
            r
        }
        _ => {
            let dp: Vec<f64> = p
                .iter()
                .enumerate()
                .skip(1)
                .map(|(n, &c)| c * n as f64)
                .collect();
            let mut cuts = vec![lo];
            let mut crit = real_roots_in(&dp, lo, hi);
            crit.sort_by(f64::total_cmp);
            cuts.extend(crit);
            cuts.push(hi);
            let mut roots = Vec::new();
            for w in cuts.windows(2) {
                let (mut a, mut b) = (w[0], w[1]);
                let (mut fa, fb) = (poly_eval(p, a), poly_eval(p, b));
                if fa == 0.0 {
                    roots.push(a);
                    continue;
                }
                if fb == 0.0 {
                    roots.push(b);
                    continue;
                }
                if fa.signum() == fb.signum() {
                    continue;
                }
                // Safeguarded Newton: [a, b] always holds the sign change; a Newton step
                // that leaves it is replaced by bisection. Stops at an exact zero, at adjacent
                // floating-point numbers, or when a Newton step no longer moves the iterate
                // by more than two ulps (quadratic convergence at a simple root).
                let mut x = 0.5 * (a + b);
                for _ in 0..200 {
                    let (fx, dfx) = poly_eval_d(p, x);
                    if fx == 0.0 {
                        break;
                    }
                    if fx.signum() == fa.signum() {
                        a = x;
                        fa = fx;
                    } else {
                        b = x;
                    }
                    let mid = 0.5 * (a + b);
                    if mid <= a || mid >= b {
                        x = mid;
                        break;
                    }
                    let newton = x - fx / dfx;
                    if newton > a && newton < b {
                        let done = (newton - x).abs() <= 2.0 * f64::EPSILON * x.abs();
                        x = newton;
                        if done {
                            break;
                        }
                    } else {
                        x = mid;
                    }
                }
                roots.push(x);
            }
            roots
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn boundary_conditions_hold() {
        let e0 = End {
            q: 1.0,
            v: -2.0,
            a: 3.0,
        };
        let e1 = End {
            q: 4.0,
            v: 0.5,
            a: -1.0,
        };
        let p = Quintic::from_ends(e0, e1, 0.7);
        let s = p.eval(0.0);
        let e = p.eval(0.7);
        for (got, want) in [
            (s[0], 1.0),
            (s[1], -2.0),
            (s[2], 3.0),
            (e[0], 4.0),
            (e[1], 0.5),
            (e[2], -1.0),
        ] {
            assert!((got - want).abs() < 1e-9, "{got} vs {want}");
        }
    }

    #[test]
    fn extrema_match_dense_sampling() {
        let p = Quintic::from_ends(
            End {
                q: 0.0,
                v: 1.0,
                a: -4.0,
            },
            End {
                q: 2.0,
                v: -1.0,
                a: 6.0,
            },
            1.3,
        );
        let m = p.max_abs_derivs();
        let mut s = [0.0f64; 3];
        for i in 0..=100_000 {
            let e = p.eval(1.3 * f64::from(i) / 100_000.0);
            for k in 0..3 {
                s[k] = s[k].max(e[k + 1].abs());
            }
        }
        for k in 0..3 {
            assert!(
                m[k] >= s[k] - 1e-12 && m[k] <= s[k] * (1.0 + 1e-8),
                "{k}: {} {}",
                m[k],
                s[k]
            );
        }
    }

    #[test]
    fn cubic_roots_are_found() {
        // (x−0.2)(x−0.5)(x−0.9)
        let p = [-0.09, 0.73, -1.6, 1.0];
        let mut r = real_roots_in(&p, 0.0, 1.0);
        r.sort_by(f64::total_cmp);
        assert_eq!(r.len(), 3);
        for (x, w) in r.iter().zip([0.2, 0.5, 0.9]) {
            assert!((x - w).abs() < 1e-12);
        }
    }
}
