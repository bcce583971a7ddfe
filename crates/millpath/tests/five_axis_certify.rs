//! The certificates are sound: the structural derivative bounds of every machine hold (finite
//! differences), the feed upper bound is above a dense sampling, and every duration the
//! minimality proof excludes is infeasible by the independent verifier.

use millpath::machine::kinematics::{HeadHead, Joints, Kinematics, PaperAb, TableTable, TrtKind};
use millpath::motion::five_axis::verify;
use millpath::motion::five_axis::{CertifyOptions, FeedVerdict, feed_bound};
use millpath::motion::five_axis::{KnotState, Limits, Segment};
use millpath::motion::five_axis::{MinTimeOptions, lower_bound, min_time};
use proptest::prelude::*;

fn machine(i: usize) -> Box<dyn Kinematics> {
    match i {
        0 => Box::new(PaperAb::paper()),
        1 => Box::new(TableTable::typical(TrtKind::Ac)),
        2 => Box::new(TableTable::typical(TrtKind::Bc)),
        _ => Box::new(HeadHead::typical()),
    }
}

fn col(k: &dyn Kinematics, q: &Joints, a: usize) -> [f64; 3] {
    let j = k.jacobian(q);
    [j[0][a], j[1][a], j[2][a]]
}

fn norm(v: [f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

fn shifted(q: &Joints, b: usize, h: f64) -> Joints {
    let mut r = *q;
    r[b] += h;
    r
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    /// Derivatives with one linear index ≤ 1, with two linear indices 0, rotary-only (orders
    /// 1–3) ≤ R = lever_bound over a box around the point.
    #[test]
    fn structural_derivative_bounds_hold(m in 0usize..4, u in prop::array::uniform5(0.0f64..1.0)) {
        let k = machine(m);
        let q: Joints = [
            -150.0 + 300.0 * u[0],
            -150.0 + 300.0 * u[1],
            -80.0 + 160.0 * u[2],
            -1.2 + 2.4 * u[3],
            -1.2 + 2.4 * u[4],
        ];
        let lo = q.map(|x| x - 0.01);
        let hi = q.map(|x| x + 0.01);
        let r = k.lever_bound(&lo, &hi);
        let h = 1e-4;
        for a in 0..5 {
            let n1 = norm(col(k.as_ref(), &q, a));
            prop_assert!(n1 <= if a < 3 { 1.0 + 1e-12 } else { r * (1.0 + 1e-12) }, "{} col {a}: {n1} (R {r})", k.name());
            for b in 0..5 {
                let cp = col(k.as_ref(), &shifted(&q, b, h), a);
                let cm = col(k.as_ref(), &shifted(&q, b, -h), a);
                let d2 = norm(std::array::from_fn(|i| (cp[i] - cm[i]) / (2.0 * h)));
                let linear = usize::from(a < 3) + usize::from(b < 3);
                let bound = match linear { 2 => 0.0, 1 => 1.0, _ => r };
                prop_assert!(d2 <= bound * (1.0 + 1e-5) + 1e-6, "{} d2 {a}{b}: {d2} > {bound}", k.name());
                if a >= 3 && b >= 3 {
                    for c in 3..5 {
                        let c0 = col(k.as_ref(), &q, a);
                        let cpp = col(k.as_ref(), &shifted(&shifted(&q, b, h), c, h), a);
                        let cpm = col(k.as_ref(), &shifted(&shifted(&q, b, h), c, -h), a);
                        let cmp = col(k.as_ref(), &shifted(&shifted(&q, b, -h), c, h), a);
                        let cmm = col(k.as_ref(), &shifted(&shifted(&q, b, -h), c, -h), a);
                        let d3 = norm(std::array::from_fn(|i| (cpp[i] - cpm[i] - cmp[i] + cmm[i]) / (4.0 * h * h) + 0.0 * c0[i]));
                        prop_assert!(d3 <= r * (1.0 + 1e-4) + 1e-4, "{} d3 {a}{b}{c}: {d3} > {r}", k.name());
                    }
                }
            }
        }
    }
}

fn state(u: &[f64], scale: f64) -> KnotState {
    KnotState {
        q: [
            u[0] * 20.0,
            u[1] * 20.0,
            u[2] * 10.0,
            0.2 + u[3] * 0.3,
            0.3 + u[4] * 0.3,
        ],
        v: [
            u[5] * 20.0 * scale,
            u[6] * 20.0 * scale,
            u[7] * 10.0 * scale,
            u[8] * 0.2 * scale,
            u[9] * 0.2 * scale,
        ],
        a: [
            u[10] * 200.0 * scale,
            u[11] * 200.0 * scale,
            0.0,
            u[12] * 2.0 * scale,
            u[13] * 2.0 * scale,
        ],
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 16, ..ProptestConfig::default() })]

    /// The feed bound brackets a dense sampling; the minimum time passes the verifier; and
    /// durations the proof excludes fail it.
    #[test]
    fn feed_bound_and_minimality_proof_are_sound(
        m in 0usize..4,
        a in prop::collection::vec(-1.0f64..1.0, 14),
        b in prop::collection::vec(-1.0f64..1.0, 14),
        scale in 0.0f64..1.0,
        pick in 0.0f64..0.9,
    ) {
        let k = machine(m);
        let lim = Limits::paper();
        let s0 = state(&a, scale);
        let mut s1 = state(&b, scale);
        s1.q[0] += 15.0;
        let seg = Segment::new(&s0, &s1, 0.8);
        let mut dense = 0.0f64;
        for i in 0..=4000 {
            dense = dense.max(seg.feed(k.as_ref(), 0.8 * f64::from(i) / 4000.0));
        }
        let fb = feed_bound(&seg, k.as_ref(), dense * 1.000_001, &CertifyOptions::default(), false);
        prop_assert_eq!(fb.verdict, FeedVerdict::Certified);
        prop_assert!(fb.upper >= dense && fb.lower <= fb.upper);

        let opts = MinTimeOptions::default();
        let Some((t, c)) = min_time(&s0, &s1, k.as_ref(), &lim, &opts) else {
            return Ok(());
        };
        let rep = verify(&[Segment::new(&s0, &s1, t)], k.as_ref(), &lim, 2000);
        prop_assert!(rep.violations.is_empty(), "{}: {:?}", k.name(), rep.violations);
        let t_lb = lower_bound(&s0, &s1, k.as_ref(), &lim);
        prop_assert!(c.proven_below <= t && c.proven_below >= t_lb * (1.0 - 1e-12));
        if c.proven_below > t_lb {
            let tx = t_lb + pick * (c.proven_below - t_lb);
            let rep = verify(&[Segment::new(&s0, &s1, tx)], k.as_ref(), &lim, 4000);
            prop_assert!(!rep.violations.is_empty(), "{}: {tx} in [{t_lb}, {}) passed the verifier", k.name(), c.proven_below);
        }
    }
}
