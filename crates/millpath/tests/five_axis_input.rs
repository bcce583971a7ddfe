//! Bad input gets an `InputError` (exit code 2), never a panic: zero tool axis, pose out of
//! the rotary range, non-finite numbers, limits ≤ 0, malformed path files. Also the path-file
//! units and the G-code writer.

use millpath::Error;
use millpath::gcode::five_axis::{FiveAxisGcodeOptions, write_five_axis};
use millpath::geom::{Point3, Vec3};
use millpath::machine::kinematics::{PaperAb, Pose, TableTable, TrtKind};
use millpath::motion::five_axis::{self, FiveAxisOptions, Limits, plan};

fn quick() -> FiveAxisOptions {
    FiveAxisOptions::default().with_baseline(None)
}

fn input_err(r: Result<impl std::fmt::Debug, Error>) -> String {
    match r {
        Err(e @ Error::Input(_)) => {
            assert_eq!(e.exit_code(), 2);
            e.to_string()
        }
        other => panic!("expected an input error, got {other:?}"),
    }
}

#[test]
fn zero_axis_and_non_finite_numbers_are_rejected() {
    let csv = "# unit: mm\nx,y,z,i,j,k\n0,0,0,0,0,1\n1,0,0,0,0,0\n";
    let e = five_axis::parse_path_csv(csv, "p.csv")
        .unwrap_err()
        .to_string();
    assert!(e.contains("tool axis") && e.contains("p.csv:4"), "{e}");
    let csv = "# unit: mm\nx,y,z,i,j,k\n0,0,0,0,0,1\nNaN,0,0,0,0,1\n";
    let e = five_axis::parse_path_csv(csv, "p.csv")
        .unwrap_err()
        .to_string();
    assert!(e.contains("NaN") && e.contains("p.csv:4"), "{e}");
    let csv = "x,y,z,i,j,k\n0,0,0,0,0,1\n";
    assert!(
        five_axis::parse_path_csv(csv, "p.csv")
            .unwrap_err()
            .to_string()
            .contains("unit")
    );
    // Poses built by hand with a zero axis or a NaN tip.
    let kin = PaperAb::paper();
    let bad = vec![
        Pose {
            tip: Point3::ORIGIN,
            axis: Vec3::new(0.0, 0.0, 1.0),
        },
        Pose {
            tip: Point3::new(1.0, 0.0, 0.0),
            axis: Vec3::new(0.0, 0.0, 0.0),
        },
    ];
    let e = input_err(plan(&kin, &bad, &Limits::paper(), &quick(), None));
    assert!(e.contains("tool axis") && e.contains("path point 1"), "{e}");
    let bad = vec![
        Pose {
            tip: Point3::ORIGIN,
            axis: Vec3::new(0.0, 0.0, 1.0),
        },
        Pose {
            tip: Point3::new(f64::NAN, 0.0, 0.0),
            axis: Vec3::new(0.0, 0.0, 1.0),
        },
    ];
    input_err(plan(&kin, &bad, &Limits::paper(), &quick(), None));
}

#[test]
fn metres_are_converted_to_millimetres() {
    let csv = "# unit: m\nx,y,z,i,j,k\n0.01,0,0,0,0,2\n0.02,0,0,0,0,1\n";
    let p = five_axis::parse_path_csv(csv, "p.csv").unwrap();
    assert!((p[1].tip.x - 20.0).abs() < 1e-12);
    assert!((p[0].axis.z - 1.0).abs() < 1e-12);
}

#[test]
fn pose_out_of_rotary_range_is_rejected() {
    let kin = PaperAb::paper();
    let poses = vec![
        Pose::new(Point3::ORIGIN, Vec3::new(0.0, 0.0, 1.0)).unwrap(),
        Pose::new(Point3::new(5.0, 0.0, 0.0), Vec3::new(1.0, 0.0, 0.0)).unwrap(),
    ];
    let e = input_err(plan(&kin, &poses, &Limits::paper(), &quick(), None));
    assert!(e.contains("path point 1") && e.contains("rad"), "{e}");
}

#[test]
fn limits_must_be_positive() {
    let kin = PaperAb::paper();
    let poses = five_axis::paper_path();
    for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let mut lim = Limits::paper();
        lim.feed = bad;
        input_err(plan(&kin, &poses, &lim, &quick(), None));
        let mut lim = Limits::paper();
        lim.jerk[4] = bad;
        let e = input_err(plan(&kin, &poses, &lim, &quick(), None));
        assert!(e.contains("jerk limit of joint 4"), "{e}");
    }
}

#[test]
fn table_table_gcode_has_rotary_words_and_inverse_time() {
    let kin = TableTable::typical(TrtKind::Ac);
    let poses: Vec<Pose> = five_axis::paper_path().into_iter().take(6).collect();
    let out = plan(&kin, &poses, &Limits::paper(), &quick(), None).unwrap();
    assert!(out.result.violations.is_empty());
    let mut g = Vec::new();
    write_five_axis(
        &mut g,
        &out.segments,
        &kin,
        &FiveAxisGcodeOptions::default(),
    )
    .unwrap();
    let g = String::from_utf8(g).unwrap();
    assert!(
        g.contains("G93") && g.contains(" A") && g.contains(" C"),
        "{g}"
    );
    // Inverse-time feeds reproduce the planned time: Σ 1/F (min) = total.
    let t: f64 = g
        .lines()
        .filter(|l| l.starts_with("G1 "))
        .filter_map(|l| l.rsplit_once('F').and_then(|(_, f)| f.parse::<f64>().ok()))
        .map(|f| 60.0 / f)
        .sum();
    assert!(
        (t - out.result.total_time_s).abs() < 1e-3,
        "{t} vs {}",
        out.result.total_time_s
    );
    // Not a table-table machine: rejected.
    let paper = PaperAb::paper();
    let out = plan(&paper, &poses, &Limits::paper(), &quick(), None).unwrap();
    let mut g = Vec::new();
    input_err(write_five_axis(
        &mut g,
        &out.segments,
        &paper,
        &FiveAxisGcodeOptions::default(),
    ));
}
