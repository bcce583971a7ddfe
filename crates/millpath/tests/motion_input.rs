//! The planner's handling of bad input, streams, corner modes and machines from TOML.

use millpath::gcode::{ReaderOptions, read_str};
use millpath::machine::Machine;
use millpath::motion::{PlanOptions, plan_moves, plan_toolpath};
use millpath::toolpath::{Corner, Move, Tool, Toolpath};
use millpath::{Error, InputError, Point3};

fn two_lines(corner: Corner) -> Toolpath {
    let mut tp = Toolpath::new(Tool::default(), Point3::ORIGIN);
    tp.push(Move::line(Point3::new(20.0, 0.0, 0.0), 100.0).with_corner(corner));
    tp.push(Move::line(Point3::new(20.0, 20.0, 0.0), 100.0));
    tp
}

#[test]
fn bad_feeds_are_input_errors_naming_the_move() {
    let m = Machine::preset("hsm").unwrap();
    for feed in [0.0, -5.0, f64::NAN] {
        let mut tp = Toolpath::new(Tool::default(), Point3::ORIGIN);
        tp.push(Move::line(Point3::new(1.0, 0.0, 0.0), 10.0));
        tp.push(Move::line(Point3::new(2.0, 0.0, 0.0), feed));
        let e = plan_toolpath(&tp, &m).unwrap_err();
        assert_eq!(e.exit_code(), 2);
        assert!(e.to_string().contains("move 2"), "{e}");
    }
}

#[test]
fn stream_errors_pass_through() {
    let m = Machine::preset("router").unwrap();
    let items: Vec<Result<(Point3, Move), Error>> = vec![
        Ok((Point3::ORIGIN, Move::line(Point3::new(1.0, 0.0, 0.0), 10.0))),
        Err(InputError::new("G-code word", "Q5").at("x.ngc:2").into()),
    ];
    let e = plan_moves(items, &m, &PlanOptions::default()).unwrap_err();
    assert!(e.to_string().contains("x.ngc:2"), "{e}");
}

#[test]
fn corner_modes_order_the_times() {
    // A 90° corner: exact stop ≥ exact path ≥ a blend within 0.1 mm ≥ a blend within 1 mm.
    let m = Machine::preset("hsm").unwrap();
    let t = |c| plan_toolpath(&two_lines(c), &m).unwrap().total_time();
    let (stop, path, b01, b1) = (
        t(Corner::ExactStop),
        t(Corner::ExactPath),
        t(Corner::Blend(0.1)),
        t(Corner::Blend(1.0)),
    );
    assert!(
        stop > path && path >= b01 && b01 > b1,
        "{stop} {path} {b01} {b1}"
    );
}

#[test]
fn gcode_program_plans_like_the_equivalent_toolpath() {
    let m = Machine::preset("linuxcnc-sim").unwrap();
    let (tp, _) = read_str(
        "G21 G90 G17\nG1 X20 F1200\nG2 X40 Y0 I10 J0\nG1 Y-20\nM30\n",
        ReaderOptions::default(),
    )
    .unwrap();
    let mut own = Toolpath::new(Tool::default(), Point3::ORIGIN);
    own.push(Move::line(Point3::new(20.0, 0.0, 0.0), 20.0));
    own.push(Move::arc_xy(
        Point3::new(40.0, 0.0, 0.0),
        Point3::new(30.0, 0.0, 0.0),
        false,
        20.0,
    ));
    own.push(Move::line(Point3::new(40.0, -20.0, 0.0), 20.0));
    let a = plan_toolpath(&tp, &m).unwrap().total_time();
    let b = plan_toolpath(&own, &m).unwrap().total_time();
    assert!((a - b).abs() < 1e-9, "{a} {b}");
}

#[test]
fn toml_machine_plans() {
    let text = r#"
name = "slow"
units = "mm"
max_feed = 50
[axes.x]
max_velocity = 50
max_acceleration = 100
max_jerk = 1000
[axes.y]
max_velocity = 50
max_acceleration = 100
max_jerk = 1000
[axes.z]
max_velocity = 20
max_acceleration = 50
max_jerk = "unlimited"
"#;
    let m = Machine::from_toml_str(text, "slow.toml").unwrap();
    let t = plan_toolpath(&two_lines(Corner::Machine), &m)
        .unwrap()
        .total_time();
    // Path tolerance 0 → two rest-to-rest moves of 20 mm (a 100, j 1000, v ≤ 50). The feed is
    // not reached: the peak solves vp·(vp/a + a/j) = L, i.e. vp² + 10·vp − 2000 = 0, vp = 40,
    // and each move takes 2·(vp/a + a/j) = 1.0 s.
    assert!((t - 2.0).abs() < 1e-9, "{t}");
}
