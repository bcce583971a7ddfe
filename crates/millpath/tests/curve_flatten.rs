//! Flattening of the paper's outline scaled to the die block: tolerance sweep, verified by
//! dense sampling through kurbo (≥ 1000 samples per chord), compared with kurbo's flatten,
//! the asymptotic optimum and the greedy lower bound.

// The figures are printed for the benchmark notes (`cargo test -- --nocapture`).
#![allow(clippy::print_stderr)]

use millpath::curve;

#[test]
fn tolerance_sweep_on_the_paper_outline() {
    let c = curve::paper_outline().unwrap();
    for tol in [1e-1, 1e-2, 1e-3, 1e-4, 4e-5] {
        let f = curve::flatten(&c, tol).unwrap();
        let dense = curve::chordal_deviation(&c, &f.params, &f.points, 1000);
        let kurbo = curve::kurbo_count(&c, tol);
        let asym = curve::asymptotic_count(&c, tol);
        let lower = f.lower_bound(c.corners().len());
        let n = f.segments();
        eprintln!(
            "T={tol:e}: segments {n}, lower bound {lower}, kurbo {kurbo}, asymptotic {asym:.1}, exact max dev {:.3e}, dense {:.3e}",
            f.max_deviation, dense
        );
        assert!(dense <= tol, "T={tol}: dense deviation {dense}");
        assert!(f.max_deviation <= tol);
        assert!(n <= kurbo, "T={tol}: {n} > kurbo {kurbo}");
        assert!(
            n as f64 <= 1.02 * lower as f64,
            "T={tol}: {n} vs lower bound {lower}"
        );
        assert!(c.corners().is_empty() || (f.params[0] - f.params[0].round()).abs() < 1e-12);
    }
}

#[test]
fn every_curve_kind_flattens_within_tolerance() {
    let groups = curve::paper_groups();
    for kind in [curve::CurveKind::CatmullRom, curve::CurveKind::Spline] {
        let c = curve::build(&groups, kind, "paper").unwrap();
        for tol in [1e-2, 1e-4] {
            let f = curve::flatten(&c, tol).unwrap();
            let dense = curve::chordal_deviation(&c, &f.params, &f.points, 1000);
            assert!(dense <= tol, "{kind:?} T={tol}: {dense}");
            assert!(
                f.segments() <= curve::kurbo_count(&c, tol),
                "{kind:?} T={tol}"
            );
        }
    }
}
