//! Kinematics: inverse ∘ forward round trips, analytic Jacobian vs finite differences, pole
//! behaviour and out-of-range poses, for every machine.

use millpath::geom::{Point3, Vec3};
use millpath::machine::kinematics::{
    HeadHead, IkOptions, IkWarning, Joints, Kinematics, PaperAb, Pose, RotaryRange, TableTable,
    TrtKind, inverse_path,
};
use proptest::prelude::*;

fn machines() -> Vec<Box<dyn Kinematics>> {
    vec![
        Box::new(PaperAb::paper()),
        Box::new(TableTable::typical(TrtKind::Ac)),
        Box::new(TableTable::typical(TrtKind::Bc)),
        Box::new(HeadHead::typical()),
    ]
}

/// Random joints inside the ranges, at least 0.05 rad away from the pole.
fn joints_for(k: &dyn Kinematics, u: [f64; 5]) -> Joints {
    let [ra, rb] = k.rotary_ranges();
    let mut q = [
        -200.0 + 400.0 * u[0],
        -200.0 + 400.0 * u[1],
        -100.0 + 200.0 * u[2],
        ra.min + (ra.max - ra.min) * u[3],
        rb.min + (rb.max - rb.min) * u[4],
    ];
    if k.name() == "paper-ab" {
        // The pole |A| = 90° is outside the range; keep B away from ±90° (unreachable).
        q[4] = -1.3 + 2.6 * u[4];
    } else if q[3].abs() < 0.05 {
        q[3] = if q[3] < 0.0 { -0.05 } else { 0.05 };
    }
    q
}

fn pose_dist(a: &Pose, b: &Pose) -> f64 {
    a.tip.distance(b.tip).max((a.axis - b.axis).length())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 96, ..ProptestConfig::default() })]

    #[test]
    fn inverse_then_forward_returns_the_pose(u in prop::array::uniform5(0.0f64..1.0)) {
        for k in machines() {
            let q = joints_for(k.as_ref(), u);
            let pose = k.forward(&q);
            let sols = k.inverse(&pose).expect("pose from forward is reachable");
            prop_assert!(!sols.is_empty());
            let mut found = false;
            for s in &sols {
                let back = k.forward(s);
                prop_assert!(pose_dist(&back, &pose) < 1e-9, "{}: {:?} -> {:?}", k.name(), s, back);
                let d = s.iter().zip(&q).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
                found |= d < 1e-8;
            }
            prop_assert!(found, "{}: original joints {:?} not among {:?}", k.name(), q, sols);
        }
    }

    #[test]
    fn analytic_jacobian_matches_finite_differences(u in prop::array::uniform5(0.0f64..1.0)) {
        for k in machines() {
            let q = joints_for(k.as_ref(), u);
            let jac = k.jacobian(&q);
            for c in 0..5 {
                let h = if c < 3 { 1e-4 } else { 1e-6 };
                let mut qp = q;
                let mut qm = q;
                qp[c] += h;
                qm[c] -= h;
                let (fp, fm) = (k.forward(&qp), k.forward(&qm));
                let fd = [
                    (fp.tip.x - fm.tip.x) / (2.0 * h),
                    (fp.tip.y - fm.tip.y) / (2.0 * h),
                    (fp.tip.z - fm.tip.z) / (2.0 * h),
                    (fp.axis.x - fm.axis.x) / (2.0 * h),
                    (fp.axis.y - fm.axis.y) / (2.0 * h),
                    (fp.axis.z - fm.axis.z) / (2.0 * h),
                ];
                for r in 0..6 {
                    let err = (jac[r][c] - fd[r]).abs();
                    prop_assert!(err < 1e-5 * (1.0 + fd[r].abs()),
                        "{} J[{r}][{c}] = {} vs fd {}", k.name(), jac[r][c], fd[r]);
                }
            }
        }
    }
}

/// A path whose tool axis passes exactly through the pole of an AC table (vertical), tilting
/// in a fixed plane: the solver keeps C at the pole, warns there, and reports any flip.
#[test]
fn pole_crossing_keeps_c_warns_and_reports_flip() {
    let k = TableTable::typical(TrtKind::Ac);
    let mut poses = Vec::new();
    for i in -10..=10 {
        let t = f64::from(i) * 0.01;
        let axis = Vec3::new(0.3 * t.sin(), t.sin(), t.cos());
        poses.push(Pose::new(Point3::new(1.0, 2.0, 3.0), axis).unwrap());
    }
    let (joints, warnings) = inverse_path(&k, &poses, &IkOptions::default()).unwrap();
    // At the pole (index 10) the free C keeps its previous value.
    assert!((joints[10][4] - joints[9][4]).abs() < 1e-12);
    assert!(
        warnings
            .iter()
            .any(|(i, w)| *i == 10 && matches!(w, IkWarning::AtPole { .. }))
    );
    assert!(
        warnings
            .iter()
            .any(|(_, w)| matches!(w, IkWarning::NearPole { .. }))
    );
    // Least rotary travel takes A through zero with C constant: no jump at all.
    for w in joints.windows(2) {
        assert!((w[1][4] - w[0][4]).abs() < 1e-9, "C jumped: {w:?}");
    }
    assert!(
        !warnings
            .iter()
            .any(|(_, w)| matches!(w, IkWarning::Flip { .. }))
    );
    for (q, p) in joints.iter().zip(&poses) {
        let back = k.forward(q);
        assert!(back.tip.distance(p.tip) < 1e-9 && (back.axis - p.axis).length() < 1e-9);
    }
}

/// When the tilt range allows only one sign, passing the pole forces C through 180°: the flip
/// is reported, never silent.
#[test]
fn forced_flip_is_reported() {
    let mut k = TableTable::typical(TrtKind::Bc);
    k.tilt_range = RotaryRange::new(0.0, 2.0);
    let mut poses = Vec::new();
    for i in -5..=5 {
        let t = f64::from(i) * 0.02;
        poses.push(Pose::new(Point3::ORIGIN, Vec3::new(t.sin(), 0.0, t.cos())).unwrap());
    }
    let (joints, warnings) = inverse_path(&k, &poses, &IkOptions::default()).unwrap();
    let jumps = joints
        .windows(2)
        .filter(|w| (w[1][4] - w[0][4]).abs() > 3.0)
        .count();
    let flips = warnings
        .iter()
        .filter(|(_, w)| matches!(w, IkWarning::Flip { axis, delta } if axis == "C" && delta.abs() > 3.0))
        .count();
    assert_eq!(jumps, 1, "{joints:?}");
    assert_eq!(flips, jumps, "{warnings:?}");
}

#[test]
fn out_of_range_pose_is_input_error() {
    let k = PaperAb::paper();
    // Tool axis horizontal along X needs B = ±90°: outside the range.
    let pose = Pose::new(Point3::new(10.0, 0.0, 0.0), Vec3::new(1.0, 0.0, 0.0)).unwrap();
    let e = k.inverse(&pose).unwrap_err();
    assert!(e.to_string().contains("paper-ab"), "{e}");
    let mut ac = TableTable::typical(TrtKind::Ac);
    ac.tilt_range = RotaryRange::new(-0.5, 0.5);
    let pose = Pose::new(Point3::ORIGIN, Vec3::new(0.0, 1.0, 0.2)).unwrap();
    assert!(ac.inverse(&pose).is_err());
}
