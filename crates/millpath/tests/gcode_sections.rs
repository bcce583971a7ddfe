//! Programs of several tools (`gcode::write_sections`): read back by our reader in every
//! dialect to the sections' moves with the sections' tools, read by LinuxCNC's `rs274`, and
//! timed with the machine's tool change time once per change of tool.

mod rs274_common;

use millpath::gcode::{
    Coolant, Dialect, ProgramSection, ReadMove, Reader, ReaderOptions, WriterOptions,
    write_sections,
};
use millpath::geom::Point3;
use millpath::job::program_time;
use millpath::machine::Machine;
use millpath::toolpath::{Move, MoveKind, Tool, Toolpath};

/// A square at depth `z` of side `s` from (x0, y0), entered and left at Z 5.
fn square(tool: u32, x0: f64, s: f64, z: f64) -> Toolpath {
    let t = Tool {
        number: tool,
        ..Tool::flat(6.0).unwrap()
    };
    let mut tp = Toolpath::new(t, Point3::new(0.0, 0.0, 5.0));
    tp.push(Move::rapid(Point3::new(x0, 0.0, 5.0)));
    tp.push(Move::line(Point3::new(x0, 0.0, z), 5.0));
    for (x, y) in [(s, 0.0), (s, s), (0.0, s), (0.0, 0.0)] {
        tp.push(Move::line(Point3::new(x0 + x, y, z), 20.0));
    }
    tp.push(Move::rapid(Point3::new(x0, 0.0, 5.0)));
    tp
}

fn program(dialect: Dialect, paths: &[Toolpath]) -> String {
    let sections: Vec<ProgramSection<'_>> = paths
        .iter()
        .enumerate()
        .map(|(k, tp)| ProgramSection {
            toolpath: tp,
            tool_number: tp.tool.number,
            tool_description: "flat end mill D6 mm, 3 flutes",
            spindle_rpm: 8000.0 + 1000.0 * k as f64,
            coolant: Coolant::Flood,
            title: if k == 0 { "face" } else { "profile" },
        })
        .collect();
    let opts = WriterOptions::default()
        .with_dialect(dialect)
        .with_path_tolerance(0.01);
    let mut out = Vec::new();
    write_sections(&sections, &opts, &mut out).unwrap();
    String::from_utf8(out).unwrap()
}

/// Read back, the feed and rapid moves are the sections' moves in order, each with its
/// section's tool; the spindle runs at the section's speed.
#[test]
fn sections_read_back_with_their_tools_in_every_dialect() {
    let paths = [square(1, 0.0, 20.0, -1.0), square(4, 40.0, 10.0, -2.0)];
    for dialect in [
        Dialect::LinuxCnc,
        Dialect::Fanuc,
        Dialect::Sinumerik,
        Dialect::Grbl,
    ] {
        let text = program(dialect, &paths);
        let read: Vec<ReadMove> = Reader::new(
            text.as_bytes(),
            ReaderOptions::default().with_dialect(dialect),
        )
        .collect::<Result<_, _>>()
        .unwrap_or_else(|e| panic!("{dialect}: {e}\n{text}"));
        let moved: Vec<_> = read
            .iter()
            .filter(|m| !matches!(m.mv.kind, MoveKind::Dwell { .. }))
            .collect();
        let want: Vec<(u32, &Move)> = paths
            .iter()
            .flat_map(|tp| tp.moves.iter().map(move |m| (tp.tool.number, m)))
            .collect();
        assert_eq!(moved.len(), want.len(), "{dialect}:\n{text}");
        for (got, (tool, m)) in moved.iter().zip(&want) {
            assert!(
                got.mv.to.distance(m.to) < 1e-3,
                "{dialect}: {got:?} vs {m:?}"
            );
            assert_eq!(got.mv.kind == MoveKind::Rapid, m.kind == MoveKind::Rapid);
            if dialect != Dialect::Grbl {
                assert_eq!(got.modal.tool, *tool, "{dialect}: {got:?}");
            }
        }
        let last = moved.last().unwrap();
        assert!((last.modal.spindle_rpm - 9000.0).abs() < 1e-9, "{dialect}");
        // Coolant and spindle stopped between the sections and at the end.
        assert_eq!(text.matches("M5").count(), 2, "{dialect}:\n{text}");
        if dialect == Dialect::Grbl {
            assert_eq!(text.lines().filter(|l| l.trim() == "M0").count(), 1);
        } else {
            assert_eq!(text.matches("M6").count(), 2, "{dialect}:\n{text}");
        }
    }
}

/// LinuxCNC's own interpreter reads the two-tool program, with both tool changes.
#[test]
fn rs274_reads_a_two_tool_program() {
    let paths = [square(1, 0.0, 20.0, -1.0), square(2, 40.0, 10.0, -2.0)];
    let text = program(Dialect::LinuxCnc, &paths);
    let canon = rs274_common::rs274(&text).unwrap_or_else(|e| panic!("{e}\n{text}"));
    assert_eq!(canon.matches("CHANGE_TOOL").count(), 2, "{canon}");
    assert!(canon.contains("USE_TOOL_LENGTH_OFFSET"), "{canon}");
}

/// The cycle time charges the machine's tool change time once per change of tool (with the
/// stop before it): not for the first tool (loaded at set-up), nor for a section that keeps
/// the tool.
#[test]
fn tool_changes_cost_the_machine_s_tool_change_time() {
    let a = square(1, 0.0, 20.0, -1.0);
    let b = square(2, 40.0, 10.0, -2.0);
    let b_same = square(1, 40.0, 10.0, -2.0);
    let mut m = Machine::preset("hsm").unwrap();
    let time = |paths: &[Toolpath], m: &Machine| {
        program_time(
            program(Dialect::LinuxCnc, paths).as_bytes(),
            Dialect::LinuxCnc,
            "two tools",
            m,
        )
        .unwrap()
    };
    m.tool_change_time = 0.0;
    let (t0_two, t0_same) = (
        time(&[a.clone(), b.clone()], &m),
        time(&[a.clone(), b_same.clone()], &m),
    );
    m.tool_change_time = 7.5;
    let (t_two, t_same) = (time(&[a.clone(), b], &m), time(&[a, b_same], &m));
    // The change itself, and the axes coming to rest for it (a few ms here).
    let extra = t_two - t0_two;
    assert!((7.5..7.55).contains(&extra), "{t_two} vs {t0_two}");
    assert!((t_same - t0_same).abs() < 1e-6, "{t_same} vs {t0_same}");
}

/// A section that keeps the tool, spindle speed and coolant of the one before goes on
/// without a stop or a tool change; the moves still read back in order.
#[test]
fn a_section_keeping_its_tool_changes_nothing() {
    let paths = [square(3, 0.0, 20.0, -1.0), square(3, 40.0, 10.0, -2.0)];
    let sections: Vec<ProgramSection<'_>> = paths
        .iter()
        .map(|tp| ProgramSection {
            toolpath: tp,
            tool_number: 3,
            tool_description: "flat end mill D6 mm, 3 flutes",
            spindle_rpm: 8000.0,
            coolant: Coolant::Flood,
            title: "pass",
        })
        .collect();
    let mut out = Vec::new();
    let summary = write_sections(&sections, &WriterOptions::default(), &mut out).unwrap();
    let text = String::from_utf8(out).unwrap();
    assert_eq!(text.matches("M6").count(), 1, "{text}");
    assert_eq!(text.matches("M5").count(), 1, "{text}");
    assert_eq!(summary.section_lines.len(), 2);
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines[summary.section_lines[1] - 1], "(pass)", "{text}");
    let read: Vec<ReadMove> = Reader::new(text.as_bytes(), ReaderOptions::default())
        .collect::<Result<_, _>>()
        .unwrap();
    let n: usize = paths.iter().map(|tp| tp.moves.len()).sum();
    assert_eq!(read.len(), n);
}
