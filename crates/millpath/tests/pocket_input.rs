//! Bad input gets a clear input error, never a panic or an internal error.

use millpath::Error;
use millpath::io::{dxf, outline_json, svg};
use millpath::stock::SimOptions;
use millpath::strategy::pocket::{
    self, PocketOptions, PocketShape, Stepover, StrategyKind, builtin,
};
use millpath::toolpath::Tool;

fn input_error<T: std::fmt::Debug>(r: Result<T, Error>) -> String {
    match r {
        Err(Error::Input(e)) => e.to_string(),
        other => panic!("expected an input error, got {other:?}"),
    }
}

#[test]
fn open_outlines_are_refused() {
    let e = svg::parse(r#"<path d="M 0 0 L 10 0 L 10 10"/>"#, "open.svg", 0.01).unwrap_err();
    assert!(e.to_string().contains("open"), "{e}");
    let e = dxf::parse(
        &dxf_lines(&[(0.0, 0.0, 10.0, 0.0), (10.0, 0.0, 10.0, 10.0)]),
        "open.dxf",
        &Default::default(),
    )
    .unwrap_err();
    assert!(e.to_string().contains("open at"), "{e}");
}

#[test]
fn chained_dxf_lines_close() {
    let l = dxf::parse(
        &dxf_lines(&[
            (0.0, 0.0, 10.0, 0.0),
            (10.0, 10.0, 10.0, 0.0),
            (10.0, 10.0, 0.0, 10.0),
            (0.0, 10.0, 0.0, 0.0),
        ]),
        "square.dxf",
        &Default::default(),
    )
    .unwrap();
    assert!((l.outer.signed_area() - 100.0).abs() < 1e-9);
}

fn dxf_lines(lines: &[(f64, f64, f64, f64)]) -> Vec<u8> {
    let mut d = ::dxf::Drawing::new();
    for &(x1, y1, x2, y2) in lines {
        let l = ::dxf::entities::Line::new(
            ::dxf::Point::new(x1, y1, 0.0),
            ::dxf::Point::new(x2, y2, 0.0),
        );
        d.add_entity(::dxf::entities::Entity::new(
            ::dxf::entities::EntityType::Line(l),
        ));
    }
    let mut buf = Vec::new();
    d.save(&mut buf).unwrap();
    buf
}

#[test]
fn self_intersecting_and_touching_islands_are_refused() {
    let bow = r#"{"outline": [[0,0],[10,10],[10,0],[0,10]]}"#;
    let e = outline_json::parse(bow, "bow.json")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("self-intersecting") && e.contains("bow.json"),
        "{e}"
    );
    let touching =
        r#"{"outline": [[0,0],[20,0],[20,20],[0,20]], "islands": [[[0,5],[5,5],[5,10],[0,10]]]}"#;
    let e = outline_json::parse(touching, "t.json")
        .unwrap_err()
        .to_string();
    assert!(e.contains("island 0"), "{e}");
    let outer = builtin::rounded_rectangle(0.0, 0.0, 20.0, 20.0, 2.0);
    let isl = builtin::rounded_rectangle(0.0, 5.0, 5.0, 5.0, 1.0);
    assert!(PocketShape::new(outer, vec![isl], "t").is_err());
}

#[test]
fn tool_too_large_and_bad_stepovers_are_refused() {
    let shape = PocketShape::simple(builtin::rounded_rectangle(0.0, 0.0, 20.0, 20.0, 2.0));
    let sim = SimOptions::default();
    for kind in [
        StrategyKind::Zigzag,
        StrategyKind::Offset,
        StrategyKind::Spiral,
    ] {
        let big = Tool::flat(25.0).unwrap();
        let e = input_error(pocket::generate(
            kind,
            &shape,
            &big,
            &PocketOptions::default(),
            &sim,
        ));
        assert!(e.contains("tool diameter"), "{kind:?}: {e}");
        let tool = Tool::flat(6.0).unwrap();
        for s in [
            Stepover::Fraction(0.0),
            Stepover::Fraction(-0.2),
            Stepover::Fraction(1.2),
            Stepover::Distance(7.0),
        ] {
            let o = PocketOptions::default().with_stepover(s);
            let e = input_error(pocket::generate(kind, &shape, &tool, &o, &sim));
            assert!(e.contains("stepover"), "{kind:?} {s:?}: {e}");
        }
        let o = PocketOptions::default().with_depth(f64::NAN);
        assert!(input_error(pocket::generate(kind, &shape, &tool, &o, &sim)).contains("depth"));
    }
}

/// A pocket metres wide cut with a millimetre tool (a drawing in metres read as millimetres,
/// or the wrong tool) is refused before planning, for every strategy, with the path it would
/// need; the same pocket a thousand times smaller plans.
#[test]
fn absurd_path_lengths_are_refused_before_planning() {
    let tool = Tool::flat(1.0).unwrap();
    let opts = PocketOptions::default().with_depth(1.0).with_step_down(1.0);
    let sim = SimOptions::default();
    let big = PocketShape::simple(builtin::rounded_rectangle(0.0, 0.0, 6000.0, 4000.0, 10.0));
    for kind in [
        StrategyKind::Spiral,
        StrategyKind::Offset,
        StrategyKind::Zigzag,
    ] {
        let e = input_error(pocket::generate(kind, &big, &tool, &opts, &sim));
        assert!(e.contains("check the drawing's units"), "{e}");
        assert!(e.contains("needs about 60 km"), "{e}");
    }
    let small = PocketShape::simple(builtin::rounded_rectangle(0.0, 0.0, 6.0, 4.0, 1.0));
    assert!(pocket::generate(StrategyKind::Zigzag, &small, &tool, &opts, &sim).is_ok());
}

/// A pocket whose path would run past `pocket::MAX_PATH_MM` (a 10 m square, as a drawing in
/// metres read as millimetres gives, with a 12.7 mm tool: about 20 km of path) is refused by
/// every public way to a toolpath, the library's lower ones included, before anything is
/// planned.
#[test]
fn a_pocket_too_large_to_plan_is_refused_by_every_entry_point() {
    let side = 10_000.0;
    let p = [(0.0, 0.0), (side, 0.0), (side, side), (0.0, side)]
        .map(|(x, y)| millpath::geom::Point::new(x, y));
    let shape = PocketShape::simple(millpath::geom::Outline::from_points(&p, "huge").unwrap());
    let tool = Tool::flat(12.7).unwrap();
    let opts = PocketOptions::default().with_depth(5.0).with_step_down(5.0);
    for kind in [
        StrategyKind::Spiral,
        StrategyKind::Adaptive,
        StrategyKind::Zigzag,
    ] {
        let errors = [
            input_error(pocket::toolpath(kind, &shape, &tool, &opts)),
            input_error(pocket::plan_level(kind, &shape, &tool, &opts)),
            input_error(pocket::plan_levels(kind, &shape, &tool, &opts)),
            input_error(pocket::generate(
                kind,
                &shape,
                &tool,
                &opts,
                &SimOptions::default(),
            )),
        ];
        for e in errors {
            assert!(
                e.contains("at most 5 km") && e.contains("drawing's units"),
                "{e}"
            );
        }
    }
}
