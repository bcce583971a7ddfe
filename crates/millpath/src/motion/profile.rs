//! One-dimensional time-optimal jerk-limited velocity profiles (S-curves).
//!
//! # The velocity change
//! Changing the velocity from `va` to `vb` (`x = |vb − va|`) with zero acceleration at both
//! ends, under `|a| ≤ A` and `|j| ≤ J`, fastest: jerk `±J` until the acceleration reaches `A`,
//! constant acceleration, then jerk `∓J` back to zero.
//! * If `x ≥ A²/J` the acceleration limit is reached: jerk phases `Tj = A/J`, constant
//!   phase `Ta = x/A − A/J`, duration `T(x) = x/A + A/J`.
//! * Otherwise the peak acceleration `a_p = √(xJ) < A`: two jerk phases of `Tj = √(x/J)`,
//!   `T(x) = 2√(x/J)`.
//! * With `J = ∞` (trapezoidal) `T(x) = x/A`.
//!
//! The profile is point-symmetric about its middle, so its mean velocity is `(va + vb)/2` and
//! the distance is `d(va, vb) = (va + vb)·T(x)/2`.
//!
//! # Reachable velocity (the inverse used by the look-ahead)
//! Given `va`, a distance `L` and the limits, the largest `vb ≥ va` with `d(va, vb) = L`:
//! * regime `x < A²/J`: with `s = √x`, `(2va + s²)·s/√J = L`, i.e. the depressed cubic
//!   `s³ + p·s − q = 0` with `p = 2va ≥ 0`, `q = L√J`. It has one real root; for `p > 0` the
//!   cancellation-free form is `s = 2√(p/3)·sinh(asinh((3q/2p)·√(3/p))/3)`, for `p = 0`
//!   `s = ∛q`.
//! * regime `x ≥ A²/J`: `(2va + x)(x/A + A/J) = 2L` ⇔ `x² + b·x + c = 0` with
//!   `b = 2va + A²/J`, `c = 2va·A²/J − 2LA < 0`; the positive root in the stable form
//!   `x = −2c/(b + √(b² − 4c))`.
//! * `J = ∞`: `x² + 2va·x − 2AL = 0`, `x = 4AL/(2va + √(4va² + 8AL))`.
//!
//! Each closed form is polished with one Newton step on `d(va, va + x) − L`.
//!
//! # Span profile (from `v0` to `v1` over a distance `L`, `v ≤ V`)
//! With zero acceleration at both ends, the time-optimal profile accelerates to a peak `vp`,
//! cruises, and decelerates: `D(vp) = d(v0, vp) + d(vp, v1)` is increasing in
//! `vp ≥ max(v0, v1)`. If `D(V) ≤ L` the peak is `V` and the cruise lasts `(L − D(V))/V`;
//! otherwise `vp` solves `D(vp) = L` — in closed form through the reachable velocity when
//! `v0 = v1` (`d(v0, vp) = L/2`, the rest-to-rest case), else by bracketed Newton iteration
//! (bisection fallback) to machine precision. The look-ahead guarantees
//! `d(v0, v1) ≤ L`; a profile whose end state or limits are off is rejected with an internal
//! error ([`SpanProfile::check`]).

use crate::error::Error;

/// Path limits of a profile: velocity, acceleration, jerk (jerk may be infinite).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Limits1 {
    /// Maximum velocity (> 0).
    pub v: f64,
    /// Maximum acceleration (> 0).
    pub a: f64,
    /// Maximum jerk (> 0, `f64::INFINITY` for trapezoidal profiles).
    pub j: f64,
}

/// Duration of a velocity change of magnitude `x ≥ 0` (zero acceleration at both ends).
pub fn change_time(x: f64, a: f64, j: f64) -> f64 {
    if x <= 0.0 {
        0.0
    } else if j.is_infinite() {
        x / a
    } else if x * j >= a * a {
        x / a + a / j
    } else {
        2.0 * (x / j).sqrt()
    }
}

/// Distance covered by the time-optimal velocity change between `va` and `vb`.
pub fn change_distance(va: f64, vb: f64, a: f64, j: f64) -> f64 {
    0.5 * (va + vb) * change_time((vb - va).abs(), a, j)
}

/// The largest `vb ≥ va` whose velocity change from `va` fits in `dist` (see module docs).
pub fn reachable_velocity(va: f64, dist: f64, a: f64, j: f64) -> f64 {
    if dist <= 0.0 {
        return va;
    }
    let x = if j.is_infinite() {
        4.0 * a * dist / (2.0 * va + (4.0 * va * va + 8.0 * a * dist).sqrt())
    } else {
        let p = 2.0 * va;
        let q = dist * j.sqrt();
        let s = if p <= 0.0 {
            q.cbrt()
        } else {
            let arg = 1.5 * q / p * (3.0 / p).sqrt();
            if arg > 1e100 {
                q.cbrt()
            } else {
                2.0 * (p / 3.0).sqrt() * (arg.asinh() / 3.0).sinh()
            }
        };
        let x1 = s * s;
        if x1 * j < a * a {
            x1
        } else {
            let b = 2.0 * va + a * a / j;
            let c = 2.0 * va * a * a / j - 2.0 * dist * a;
            -2.0 * c / (b + (b * b - 4.0 * c).sqrt())
        }
    };
    // One Newton step on f(x) = d(va, va + x) − dist, f'(x) = T/2 + (2va + x)/2 · T'(x).
    let mut x = x.max(0.0);
    let t = change_time(x, a, j);
    let dt = if j.is_infinite() || x * j >= a * a {
        1.0 / a
    } else if x > 0.0 {
        1.0 / (x * j).sqrt()
    } else {
        0.0
    };
    let f = 0.5 * (2.0 * va + x) * t - dist;
    let fp = 0.5 * t + 0.5 * (2.0 * va + x) * dt;
    if fp > 0.0 && fp.is_finite() {
        let xn = x - f / fp;
        if xn > 0.0 {
            x = xn;
        }
    }
    // The caller keeps `vb`, and a profile recomputes the change as `vb − va`, known only to
    // an ulp of `vb`: at 118 mm/s over 0.2 µm the change is 1.5e-7 mm/s, and the rounded `vb`
    // may need 2e-8 more distance than `dist` (a span the look-ahead then hands to
    // `SpanProfile::new` as infeasible). Step `vb` down by ulps until its change fits.
    let mut vb = va + x;
    for _ in 0..64 {
        if vb <= va || change_distance(va, vb, a, j) <= dist {
            break;
        }
        // The next f64 below `vb` (> va ≥ 0, so positive and finite); `f64::next_down` is
        // newer than the MSRV.
        vb = f64::from_bits(vb.to_bits() - 1);
    }
    vb.max(va)
}

/// One phase: duration, acceleration at its start, constant jerk.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Phase {
    /// Duration in s.
    pub duration: f64,
    /// Acceleration at the start of the phase (jumps are allowed only with infinite jerk).
    pub a0: f64,
    /// Jerk during the phase.
    pub jerk: f64,
}

/// The state of a 1-D profile: position, velocity, acceleration, jerk.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct State1 {
    /// Distance from the start of the profile.
    pub s: f64,
    /// Velocity.
    pub v: f64,
    /// Acceleration.
    pub a: f64,
    /// Jerk.
    pub j: f64,
}

/// A span profile: up to 3 phases up, a cruise, up to 3 phases down.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SpanProfile {
    /// Start velocity.
    pub v0: f64,
    /// Peak velocity.
    pub vp: f64,
    /// End velocity.
    pub v1: f64,
    /// Distance.
    pub length: f64,
    /// The phases (unused ones have zero duration).
    pub phases: [Phase; 7],
    /// Time at which the cruise (the velocity plateau) starts.
    pub t_peak: f64,
    /// Total duration.
    pub duration: f64,
}

fn change_phases(va: f64, vb: f64, a: f64, j: f64, out: &mut [Phase]) {
    let x = (vb - va).abs();
    let sg = if vb >= va { 1.0 } else { -1.0 };
    if x <= 0.0 {
        return;
    }
    if j.is_infinite() {
        out[0] = Phase {
            duration: x / a,
            a0: sg * a,
            jerk: 0.0,
        };
    } else if x * j >= a * a {
        let tj = a / j;
        out[0] = Phase {
            duration: tj,
            a0: 0.0,
            jerk: sg * j,
        };
        out[1] = Phase {
            duration: x / a - tj,
            a0: sg * a,
            jerk: 0.0,
        };
        out[2] = Phase {
            duration: tj,
            a0: sg * a,
            jerk: -sg * j,
        };
    } else {
        let tj = (x / j).sqrt();
        out[0] = Phase {
            duration: tj,
            a0: 0.0,
            jerk: sg * j,
        };
        out[2] = Phase {
            duration: tj,
            a0: sg * j * tj,
            jerk: -sg * j,
        };
    }
}

impl SpanProfile {
    /// The time-optimal profile from `v0` to `v1` over `length` with the limits `lim` (zero
    /// acceleration at both ends). Requires `v0, v1 ≤ lim.v` and `d(v0, v1) ≤ length`
    /// (within 1e-9 relative, which the look-ahead guarantees).
    pub fn new(v0: f64, v1: f64, length: f64, lim: Limits1) -> Result<SpanProfile, Error> {
        let (a, j) = (lim.a, lim.j);
        let vlo = v0.max(v1);
        let d = |vp: f64| change_distance(v0, vp, a, j) + change_distance(vp, v1, a, j);
        let dlo = d(vlo);
        if dlo > length * (1.0 + 1e-9) + 1e-12 || vlo > lim.v * (1.0 + 1e-12) {
            return Err(Error::internal(format!(
                "span profile infeasible: v0 {v0}, v1 {v1}, length {length}, needs {dlo}"
            )));
        }
        let vp = if d(lim.v) <= length {
            lim.v
        } else if dlo >= length {
            // No room to speed up: the velocity change alone fills the span. (Near `vlo`,
            // `d` grows like `√(vp − vlo)`, so a peak a rounding error above `vlo` would
            // overshoot the span by ~`vlo·√(ε/J)`.)
            vlo
        } else {
            let x = if (v0 - v1).abs() <= 0.0 {
                reachable_velocity(v0, 0.5 * length, a, j).min(lim.v)
            } else {
                peak_by_newton(&d, length, vlo, lim.v)
            };
            // The peak is stored as a velocity, so the change `vp − v0` it implies is only
            // known to an ulp of `vp`; when that change is tiny against `vp` (a short span at
            // speed: 0.5 µm at 139 mm/s changes the velocity by 2e-7 mm/s) `D(vp)` moves in
            // steps of ~1e-7 relative and the closest representable peak may overshoot the
            // span. Step down geometrically until `D ≤ L` (`vlo` always qualifies) and let a
            // cruise at the peak take up the rest, so the profile ends exactly at `L`.
            let mut y = x.clamp(vlo, lim.v);
            let mut step = 4.0 * f64::EPSILON * y;
            for _ in 0..60 {
                if d(y) <= length {
                    break;
                }
                y = (y - step).max(vlo);
                step *= 4.0;
            }
            if d(y) > length { vlo } else { y }
        };
        let mut phases = [Phase::default(); 7];
        change_phases(v0, vp, a, j, &mut phases[0..3]);
        let used = d(vp);
        phases[3] = Phase {
            duration: if vp > 0.0 {
                ((length - used) / vp).max(0.0)
            } else {
                0.0
            },
            a0: 0.0,
            jerk: 0.0,
        };
        change_phases(vp, v1, a, j, &mut phases[4..7]);
        let t_peak = phases[..3].iter().map(|p| p.duration).sum();
        let duration = phases.iter().map(|p| p.duration).sum();
        Ok(SpanProfile {
            v0,
            vp,
            v1,
            length,
            phases,
            t_peak,
            duration,
        })
    }

    /// The state at time `t` (clamped to the profile).
    pub fn state(&self, t: f64) -> State1 {
        let mut st = State1 {
            s: 0.0,
            v: self.v0,
            a: 0.0,
            j: 0.0,
        };
        let mut rest = t.clamp(0.0, self.duration);
        for (i, ph) in self.phases.iter().enumerate() {
            let last = i == 6;
            if rest <= ph.duration || last {
                let tau = rest.min(ph.duration);
                return advance(st, ph, tau);
            }
            st = advance(st, ph, ph.duration);
            rest -= ph.duration;
        }
        st
    }

    /// The state at the start of each phase, in order (what [`SpanProfile::state`] computes
    /// on its way to the phase it stops in), for [`SpanProfile::state_from`].
    pub(crate) fn phase_starts(&self) -> [State1; 7] {
        let mut starts = [State1::default(); 7];
        let mut st = State1 {
            s: 0.0,
            v: self.v0,
            a: 0.0,
            j: 0.0,
        };
        for (start, ph) in starts.iter_mut().zip(&self.phases) {
            *start = st;
            st = advance(st, ph, ph.duration);
        }
        starts
    }

    /// [`SpanProfile::state`] with the phases' start states `starts` (from
    /// [`SpanProfile::phase_starts`]) looked up instead of advanced through: the same
    /// operations on the same numbers, so the same state to the bit, for samplers that query
    /// one profile many times.
    pub(crate) fn state_from(&self, starts: &[State1; 7], t: f64) -> State1 {
        let mut rest = t.clamp(0.0, self.duration);
        for (i, (ph, st)) in self.phases.iter().zip(starts).enumerate() {
            if rest <= ph.duration || i == 6 {
                return advance(*st, ph, rest.min(ph.duration));
            }
            rest -= ph.duration;
        }
        starts[6]
    }

    /// The state `tau` s into phase `p` (clamped to the phase), from the phases' start states
    /// `starts`: at `tau = 0` the phase's own acceleration (after a jump of an unlimited
    /// jerk), not the one the phase before ends with.
    pub(crate) fn state_in(&self, starts: &[State1; 7], p: usize, tau: f64) -> State1 {
        let (Some(ph), Some(st)) = (self.phases.get(p), starts.get(p)) else {
            return State1::default();
        };
        advance(*st, ph, tau.clamp(0.0, ph.duration))
    }

    /// The time at which the profile has covered `s` (0 ≤ s ≤ length), by a safeguarded
    /// Newton iteration within the phase that contains it.
    pub fn time_at(&self, s: f64) -> f64 {
        if s <= 0.0 {
            return 0.0;
        }
        if s >= self.length {
            return self.duration;
        }
        let mut st = State1 {
            s: 0.0,
            v: self.v0,
            a: 0.0,
            j: 0.0,
        };
        let mut t0 = 0.0;
        for ph in &self.phases {
            let end = advance(st, ph, ph.duration);
            if end.s >= s && ph.duration > 0.0 {
                if ph.jerk == 0.0 && ph.a0 == 0.0 && st.v > 0.0 {
                    // Cruise: s is linear in t.
                    return t0 + ((s - st.s) / st.v).clamp(0.0, ph.duration);
                }
                let (mut lo, mut hi) = (0.0, ph.duration);
                let mut tau = if st.v > 0.0 {
                    ((s - st.s) / st.v).min(hi)
                } else {
                    0.5 * hi
                };
                for _ in 0..100 {
                    let e = advance(st, ph, tau);
                    let f = e.s - s;
                    if f.abs() <= 1e-14 * s.max(1e-300) {
                        break;
                    }
                    if f > 0.0 {
                        hi = tau;
                    } else {
                        lo = tau;
                    }
                    let next = if e.v > 0.0 { tau - f / e.v } else { -1.0 };
                    tau = if next >= lo && next <= hi {
                        next
                    } else {
                        0.5 * (lo + hi)
                    };
                    if hi - lo <= 1e-15 * (t0 + hi).max(1e-9) {
                        break;
                    }
                }
                return t0 + tau;
            }
            st = end;
            t0 += ph.duration;
        }
        self.duration
    }

    /// Checks the profile against the limits and its boundary conditions: every phase
    /// within `|v| ≤ V`, `|a| ≤ A`, `|j| ≤ J` (relative 1e-9), end velocity and distance.
    pub fn check(&self, lim: Limits1) -> Result<(), Error> {
        let tol = 1e-9;
        let mut st = State1 {
            s: 0.0,
            v: self.v0,
            a: 0.0,
            j: 0.0,
        };
        for ph in &self.phases {
            let bad_a = ph.a0.abs() > lim.a * (1.0 + tol);
            let bad_j = lim.j.is_finite() && ph.jerk.abs() > lim.j * (1.0 + tol);
            st = advance(st, ph, ph.duration);
            let bad_v = st.v > lim.v * (1.0 + tol) || st.v < -tol * lim.v;
            if bad_a || bad_j || bad_v || st.a.abs() > lim.a * (1.0 + tol) {
                return Err(Error::internal(format!(
                    "span profile violates its limits: {self:?} vs {lim:?}"
                )));
            }
        }
        let scale = self.length.max(1e-9);
        if (st.v - self.v1).abs() > tol * lim.v.max(1.0)
            || (st.s - self.length).abs() > 1e-8 * scale
        {
            return Err(Error::internal(format!(
                "span profile misses its end: reached s {} v {}, wanted {} {} ({self:?}, {lim:?})",
                st.s, st.v, self.length, self.v1
            )));
        }
        Ok(())
    }
}

/// The peak `vp ∈ [lo, hi]` with `D(vp) = length`, by bracketed Newton iteration (bisection
/// fallback) to machine precision; the caller corrects a rounding overshoot.
fn peak_by_newton(d: &dyn Fn(f64) -> f64, length: f64, lo: f64, hi: f64) -> f64 {
    let (mut lo, mut hi) = (lo, hi);
    let mut x = 0.5 * (lo + hi);
    for _ in 0..200 {
        let f = d(x) - length;
        if f.abs() <= 1e-15 * length {
            break;
        }
        if f > 0.0 {
            hi = x;
        } else {
            lo = x;
        }
        let h = 1e-7 * x.max(1e-12);
        let fp = (d(x + h) - d(x - h).max(0.0)) / (2.0 * h);
        let xn = x - f / fp;
        x = if fp > 0.0 && xn >= lo && xn <= hi {
            xn
        } else {
            0.5 * (lo + hi)
        };
        if hi - lo <= 4.0 * f64::EPSILON * hi {
            break;
        }
    }
    x
}

fn advance(st: State1, ph: &Phase, tau: f64) -> State1 {
    let (a0, j) = (ph.a0, ph.jerk);
    State1 {
        s: st.s + tau * (st.v + tau * (0.5 * a0 + tau * j / 6.0)),
        v: st.v + tau * (a0 + 0.5 * j * tau),
        a: a0 + j * tau,
        j,
    }
}

/// Minimum duration of a rest-to-rest move of `length` under `lim`.
pub fn rest_to_rest_time(length: f64, lim: Limits1) -> Result<f64, Error> {
    Ok(SpanProfile::new(0.0, 0.0, length, lim)?.duration)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reachable_inverts_distance() {
        for &(va, d, a, j) in &[
            (0.0, 1.0, 1000.0, 1e5),
            (10.0, 0.01, 1000.0, 1e5),
            (100.0, 50.0, 2000.0, 1e4),
            (5.0, 3.0, 100.0, f64::INFINITY),
            (0.0, 1e-6, 1e4, 1e6),
        ] {
            let vb = reachable_velocity(va, d, a, j);
            let back = change_distance(va, vb, a, j);
            assert!((back - d).abs() <= 1e-12 * d.max(1.0), "{va} {d}: {back}");
        }
    }

    #[test]
    fn profiles_end_where_they_should_and_respect_limits() {
        let lim = Limits1 {
            v: 100.0,
            a: 1000.0,
            j: 20000.0,
        };
        for &(v0, v1, l) in &[
            (0.0, 0.0, 1.0),
            (0.0, 0.0, 100.0),
            (50.0, 0.0, 30.0),
            (20.0, 90.0, 40.0),
        ] {
            let p = SpanProfile::new(v0, v1, l, lim).unwrap();
            p.check(lim).unwrap();
            let end = p.state(p.duration);
            assert!((end.s - l).abs() < 1e-9 && (end.v - v1).abs() < 1e-9);
            for k in 0..=20 {
                let s = l * f64::from(k) / 20.0;
                let t = p.time_at(s);
                assert!((p.state(t).s - s).abs() < 1e-9 * l.max(1.0), "{s}");
            }
        }
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(512))]
        /// Any feasible (v0, v1, L) gets a profile that ends exactly and respects its limits,
        /// and whose duration is no longer than a slower-peak alternative (cruise at vlo).
        #[test]
        fn span_profiles_are_feasible(
            v0 in 0.0f64..200.0, v1 in 0.0f64..200.0, extra in 0.0f64..100.0,
            a in 10.0f64..1e4, lj in 2.0f64..7.0, unlimited in proptest::bool::ANY,
        ) {
            let j = if unlimited { f64::INFINITY } else { 10f64.powf(lj) };
            let lim = Limits1 { v: 200.0, a, j };
            let l = change_distance(v0, v1, a, j) + extra + 1e-6;
            let p = SpanProfile::new(v0, v1, l, lim).unwrap();
            p.check(lim).unwrap();
            let vlo = v0.max(v1);
            if vlo > 0.0 {
                let slow = change_distance(v0, vlo, a, j) + change_distance(vlo, v1, a, j);
                let t_slow = change_time((vlo - v0).abs(), a, j)
                    + change_time((vlo - v1).abs(), a, j)
                    + (l - slow) / vlo;
                proptest::prop_assert!(p.duration <= t_slow * (1.0 + 1e-12) + 1e-12);
            }
            let r = reachable_velocity(v0, l, a, j);
            proptest::prop_assert!((change_distance(v0, r, a, j) - l).abs() <= 1e-9 * l.max(1.0));
        }
    }

    /// A 0.5 µm span between two equal speeds of 139 mm/s (the spiral of
    /// `pb_latch_test.svg`, tool 8.28 mm): the peak 2e-7 mm/s above the end speeds was
    /// rounded to an ulp of 139 mm/s, the profile covered 2.2e-8 more than the span, and
    /// `check` refused it ("span profile misses its end").
    #[test]
    fn tiny_span_at_speed_ends_exactly() {
        for &(v, l, a, j) in &[
            (
                139.2558260320198,
                0.000512289189829801,
                6273.140682464093,
                243955.47098471472,
            ),
            (
                139.22701079276607,
                0.00011985702212771335,
                4500.000000000893,
                175000.00000003472,
            ),
        ] {
            let lim = Limits1 {
                v: 253.99999999999997,
                a,
                j,
            };
            let p = SpanProfile::new(v, v, l, lim).unwrap();
            p.check(lim).unwrap();
            let end = p.state(p.duration);
            assert!((end.s - l).abs() <= 1e-12 * l, "{} vs {l}", end.s);
        }
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(512))]
        /// Short spans between equal (and nearly equal) speeds, down to 1e-7 mm: the velocity
        /// change is far below the speed's resolution, yet the profile ends at its length.
        #[test]
        fn short_spans_at_speed_end_exactly(
            v in 1.0f64..250.0, dv in 0.0f64..1e-9, ll in -7.0f64..-1.0,
            a in 100.0f64..1e4, lj in 4.0f64..7.0, equal in proptest::bool::ANY,
        ) {
            let lim = Limits1 { v: 254.0, a, j: 10f64.powf(lj) };
            let v1 = if equal { v } else { v + dv * v };
            let l = 10f64.powf(ll) + change_distance(v, v1, a, lim.j);
            let p = SpanProfile::new(v, v1, l, lim).unwrap();
            proptest::prop_assert!(p.check(lim).is_ok(), "{:?}", p.check(lim));
        }
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(1024))]
        /// The look-ahead's knots: `v1 = reachable_velocity(v0, L)` (and the same going
        /// down) always gives a feasible span that ends exactly, even when the change is far
        /// below the speed's resolution (`pb_latch_test.svg`, offset: 0.2 µm at 118 mm/s was
        /// "span profile infeasible").
        #[test]
        fn reachable_knots_give_feasible_spans(
            v in 1.0f64..250.0, ll in -7.0f64..-1.0,
            a in 100.0f64..1e4, lj in 4.0f64..7.0, down in proptest::bool::ANY,
        ) {
            let lim = Limits1 { v: 254.0, a, j: 10f64.powf(lj) };
            let l = 10f64.powf(ll);
            let w = reachable_velocity(v, l, a, lim.j).min(lim.v);
            let (v0, v1) = if down { (w, v) } else { (v, w) };
            let p = SpanProfile::new(v0, v1, l, lim);
            proptest::prop_assert!(p.is_ok(), "{:?}", p);
            let p = p.expect("feasible");
            proptest::prop_assert!(p.check(lim).is_ok(), "{:?}", p.check(lim));
        }
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(512))]
        /// The samplers' lookup of the phase starts gives `state` to the bit, at every time
        /// (inside, at and beyond the phase boundaries), on 512 feasible profiles.
        #[test]
        fn state_from_phase_starts_is_state(
            v0 in 0.0f64..200.0, v1 in 0.0f64..200.0, extra in 0.0f64..100.0,
            a in 10.0f64..1e4, lj in 2.0f64..7.0, unlimited in proptest::bool::ANY,
            ts in proptest::collection::vec(-0.1f64..1.1, 16),
        ) {
            let j = if unlimited { f64::INFINITY } else { 10f64.powf(lj) };
            let lim = Limits1 { v: 200.0, a, j };
            let l = change_distance(v0, v1, a, j) + extra + 1e-6;
            let p = SpanProfile::new(v0, v1, l, lim).unwrap();
            let starts = p.phase_starts();
            let mut bounds = vec![0.0, p.duration];
            let mut t = 0.0;
            for ph in &p.phases {
                t += ph.duration;
                bounds.push(t);
            }
            for t in ts.iter().map(|f| f * p.duration).chain(bounds) {
                let (x, y) = (p.state(t), p.state_from(&starts, t));
                proptest::prop_assert_eq!(
                    [x.s, x.v, x.a, x.j].map(f64::to_bits),
                    [y.s, y.v, y.a, y.j].map(f64::to_bits),
                    "t {}", t
                );
            }
        }
    }

    #[test]
    fn long_trapezoid_time_is_closed_form() {
        // J = ∞, cruise reached: T = L/V + V/A.
        let lim = Limits1 {
            v: 10.0,
            a: 100.0,
            j: f64::INFINITY,
        };
        let t = rest_to_rest_time(50.0, lim).unwrap();
        assert!((t - (5.0 + 0.1)).abs() < 1e-12);
    }
}
