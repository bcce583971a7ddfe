//! `calibrate` recovers a LinuxCNC machine's limits from measured cycle times.
//!
//! The programs are the LinuxCNC test programs (`tests/data/linuxcnc/`) and four more
//! (`tests/data/calibrate/`: 0.05 mm chords bound by the servo cycle, slots in `G64 P0`, a
//! square in `G64 P1`, rapids between short cuts). Their times were recorded on 2026-11-25
//! with `../shared/tools/linuxcnc-time FILE 500 2000` and `FILE 500 1000` (LinuxCNC 2.9's own
//! planner on a trivkins machine with 500 mm/s and 2000 resp. 1000 mm/s² per axis, 1 ms servo
//! period, jerk unlimited) into `tests/data/calibrate/{fit,predict}_a{2000,1000}.csv`.
//!
//! From a wrong start (3000 mm/s², 2 ms, tolerance 0.05 mm) and the 5 programs of
//! `fit_*.csv`, the fit must recover the acceleration and the servo period within 5 %, find
//! that `G64` without P blends without a tolerance limit (tolerance 0) and leave the jerk
//! unlimited; the fitted profile must then time the 10 programs of `predict_*.csv` within 5 %.

use millpath::calibrate::{CalibrateOptions, ParamFit, calibrate, load};
use millpath::machine::Machine;
use millpath::motion::{PlanOptions, plan_moves};
use std::path::Path;

fn recovers(acceleration: f64) {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/calibrate");
    let mut start = Machine::preset("linuxcnc-time").unwrap();
    for a in &mut start.axes {
        a.max_acceleration = 3000.0;
    }
    start.ipo_cycle = 0.002;
    start.path_tolerance = 0.05;
    let fit_set = load(&dir.join(format!("fit_a{acceleration}.csv")), &start).unwrap();
    assert_eq!(fit_set.len(), 5);
    let cal = calibrate(&start, &fit_set, &CalibrateOptions::default()).unwrap();
    let near = |p: ParamFit, want: f64| match p {
        ParamFit::Fitted { value } => (value - want).abs() <= 0.05 * want,
        _ => false,
    };
    let report = format!(
        "a {:?}, j {:?}, tolerance {:?}, T {:?}, residuals {:#?}",
        cal.acceleration, cal.jerk, cal.tolerance, cal.ipo_cycle, cal.residuals
    );
    assert!(near(cal.acceleration, acceleration), "{report}");
    assert!(near(cal.ipo_cycle, 0.001), "{report}");
    assert_eq!(cal.tolerance, ParamFit::Fitted { value: 0.0 }, "{report}");
    assert_eq!(cal.jerk, ParamFit::NotApplicable, "{report}");
    assert!(
        cal.machine.axes.iter().all(|a| a.max_jerk.is_infinite()),
        "{report}"
    );
    for r in &cal.residuals {
        assert!(r.error().abs() <= 0.05, "{report}");
    }
    // The fitted profile, written and read back as the CLI does, predicts the others.
    let machine = Machine::from_toml_str(&cal.machine.to_toml(), "fitted.toml").unwrap();
    let others = load(&dir.join(format!("predict_a{acceleration}.csv")), &machine).unwrap();
    assert_eq!(others.len(), 10);
    for p in &others {
        let t = plan_moves(
            p.moves.iter().map(|x| Ok(*x)),
            &machine,
            &PlanOptions::default(),
        )
        .unwrap()
        .total_time();
        let err = (t - p.seconds) / p.seconds;
        assert!(
            err.abs() <= 0.05,
            "{}: LinuxCNC {} s, fitted profile {t} s ({report})",
            p.name,
            p.seconds
        );
    }
}

#[test]
fn recovers_linuxcnc_at_2000_mm_s2() {
    recovers(2000.0);
}

#[test]
fn recovers_linuxcnc_at_1000_mm_s2() {
    recovers(1000.0);
}
