//! A toolpath timed on a machine and its plan checked by the independent limit verifier
//! ([`crate::motion::verify`], sampling per-axis velocity, acceleration and jerk at 1 kHz):
//! what the demo states for every program it writes. The `linuxcnc` controller model is not
//! verified here: its plans follow LinuxCNC's rules and are judged against LinuxCNC itself.

use crate::Error;
use crate::machine::Machine;
use crate::motion::verify::{VerifyOptions, VerifyReport, verify_plan};
use crate::motion::{Plan, plan_toolpath};
use crate::toolpath::Toolpath;

/// Plans `tp` on `machine` and, unless the controller model reshaped the path (the
/// `linuxcnc` model), checks the plan with the limit verifier at its default rate.
pub fn time_and_verify(
    tp: &Toolpath,
    machine: &Machine,
) -> Result<(Plan, Option<VerifyReport>), Error> {
    let plan = plan_toolpath(tp, machine).map_err(|e| e.engine_made("timing a toolpath"))?;
    if plan.reshaped {
        return Ok((plan, None));
    }
    let moves: Vec<_> = tp.segments().map(|(from, m)| (from, *m)).collect();
    let v = verify_plan(&plan, &moves, machine, &VerifyOptions::default())?;
    Ok((plan, Some(v)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::machine::Controller;
    use crate::{Move, Point3, Tool};

    fn square() -> Toolpath {
        let mut tp = Toolpath::new(Tool::default(), Point3::new(0.0, 0.0, 5.0));
        tp.push(Move::rapid(Point3::new(0.0, 0.0, 1.0)));
        for (x, y) in [
            (0.0, 0.0),
            (30.0, 0.0),
            (30.0, 30.0),
            (0.0, 30.0),
            (0.0, 0.0),
        ] {
            tp.push(Move::line(Point3::new(x, y, -1.0), 20.0));
        }
        tp
    }

    #[test]
    fn the_plan_is_verified_unless_reshaped() {
        let m = Machine::preset("hsm").unwrap();
        let (plan, v) = time_and_verify(&square(), &m).unwrap();
        let v = v.unwrap();
        assert_eq!(v.violations, 0);
        // Sampled at 1 kHz over the whole plan.
        assert!((v.samples + v.bounded) as f64 >= 1000.0 * plan.total_time());
        // 2 mm plunge plus 120 mm at 20 mm/s: at least 6.1 s.
        assert!(plan.total_time() > 6.1);
        let lc = Machine {
            controller: Controller::LinuxCnc,
            ..m
        };
        let (plan, v) = time_and_verify(&square(), &lc).unwrap();
        assert!(plan.reshaped && v.is_none());
    }
}
