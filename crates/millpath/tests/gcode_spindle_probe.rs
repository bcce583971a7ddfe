//! LinuxCNC's spindle-synchronised moves (G33, G33.1, G95), straight probes (G38.2–G38.5),
//! rotary axis words and M66, read by the reader. Expected speeds are worked out here from
//! the definitions (pitch × rev/min ÷ 60, F × rev/min ÷ 60), not taken from the reader;
//! tests/linuxcnc_programs.rs compares the same programs' end points and feeds with rs274.

mod nurbs_common;

use millpath::gcode::{ReadMove, Reader, ReaderOptions};
use millpath::geom::Point3;
use millpath::toolpath::{MoveKind, Rotary};
use nurbs_common::{read, refusal};

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() < 1e-9
}

#[test]
fn g33_moves_at_pitch_times_spindle_speed() {
    let m = read("G21 G18 G90\nS600 M3\nG0 X10 Z5\nG33 Z-20 K1.5\nG0 X12\nM2\n");
    let t = &m[1];
    assert_eq!((t.line, t.mv.kind), (4, MoveKind::Line));
    assert_eq!(t.mv.to, Point3::new(10.0, 0.0, -20.0));
    // 1.5 mm/rev at 600 rev/min: 15 mm/s, 25 mm in 5/3 s.
    assert!(close(t.mv.feed, 15.0), "{}", t.mv.feed);
    // In inches: 0.05 in/rev at 400 rev/min.
    let m = read("G20 G90\nS400 M3\nG0 X0.5 Z0.7\nG33 Z0.1 K0.05\nM2\n");
    assert!(close(m[1].mv.feed, 0.05 * 25.4 * 400.0 / 60.0));
    // A later S changes the speed of the next G33 (the commanded speed).
    let m = read("G21\nS600 M3\nG33 Z-5 K1\nS1200\nG33 Z-10 K1\nM2\n");
    assert!(close(m[0].mv.feed, 10.0) && close(m[1].mv.feed, 20.0));
}

#[test]
fn g33_1_taps_in_and_back_out_to_its_start() {
    let m = read("G21 G90\nS300 M3\nG0 X1 Y2 Z2\nG33.1 Z-10 K1.0\nG91 G0 X1\nM2\n");
    let (a, b) = (&m[1], &m[2]);
    assert_eq!(a.mv.to, Point3::new(1.0, 2.0, -10.0));
    assert_eq!(b.mv.to, Point3::new(1.0, 2.0, 2.0));
    assert!(close(a.mv.feed, 5.0) && close(b.mv.feed, 5.0));
    // The position stays at the start: the incremental move goes from there.
    assert_eq!(m[3].mv.to, Point3::new(2.0, 2.0, 2.0));
    // LinuxCNC master's I: the way out I times faster.
    let m = read("G21 G90\nS300 M3\nG33.1 Z-10 K1.0 I2\nM2\n");
    assert!(close(m[0].mv.feed, 5.0) && close(m[1].mv.feed, 10.0));
}

#[test]
fn g95_feeds_per_revolution() {
    let m = read("G21 G90\nS1000 M3\nG95 F0.1\nG1 X10\nS500\nX20\nG94 F600 X30\nM2\n");
    assert!(close(m[0].mv.feed, 0.1 * 1000.0 / 60.0));
    assert!(close(m[1].mv.feed, 0.1 * 500.0 / 60.0));
    assert!(close(m[2].mv.feed, 10.0));
}

#[test]
fn synchronised_refusals_name_the_word_and_the_line() {
    for (text, expected) in [
        ("G21\nG33 Z-5 K1\nM2\n", ":2"),
        ("G21\nS100 M3\nG33 Z-5\nM2\n", "pitch K"),
        ("G21\nS100 M3\nG96 D2000 S100\nG33 Z-5 K1\nM2\n", "G97"),
        ("G21\nM3\nG95 F0.1\nG1 X1\nM2\n", "S > 0"),
        ("G21\nS100 M3\nG95 F0.1\nG81 X0 Y0 Z-1 R1\nM2\n", "G94"),
    ] {
        let m = refusal(text);
        assert!(m.contains(expected), "{m}\n(for {text})");
    }
}

#[test]
fn a_probe_goes_to_its_target_and_backs_off_as_rs274_does() {
    let m = read(
        "G21 G90\nG0 X1 Y2 Z10\nF120\nG38.2 Z-5\nG0 X#5061 Y#5062 Z[#5063 + 20]\n\
         #5070=1\no1 while [#5070 NE 0]\nG38.3 Z-6\no1 endwhile\nM2\n",
    );
    assert_eq!(m[1].mv.to, Point3::new(1.0, 2.0, -5.0));
    assert!(close(m[1].mv.feed, 2.0));
    // Backed off 0.254 mm toward the start.
    assert_eq!(m[2].mv.kind, MoveKind::Line);
    assert!(m[2].mv.to.distance(Point3::new(1.0, 2.0, -5.0 + 0.254)) < 1e-12);
    // #5061–#5063: the target.
    assert_eq!(m[3].mv.to, Point3::new(1.0, 2.0, 15.0));
    // #5070 = 0 after a probe (rs274's "not tripped"): the loop runs once.
    assert_eq!(m.iter().filter(|x| x.line == 8).count(), 2);
    // G38.2 must move; G38.3 need not.
    let e = refusal("G21\nF100\nG38.2 X0\nM2\n");
    assert!(e.contains("G38.2") && e.contains(":3"), "{e}");
    assert_eq!(read("G21\nF100\nG38.3 X0\nM2\n").len(), 1);
}

#[test]
fn rotary_words_are_read_and_the_path_is_x_y_z() {
    let m = read("G21 G90\nG92 A0\nG0 X0 Y0 A0\nG1 X10 A90 F600\nG0 A45\nG1 Y5 B10 C20\nM2\n");
    let ends: Vec<Point3> = m.iter().map(|x| x.mv.to).collect();
    assert_eq!(
        ends,
        [
            Point3::new(0.0, 0.0, 0.0),
            Point3::new(10.0, 0.0, 0.0),
            Point3::new(10.0, 0.0, 0.0),
            Point3::new(10.0, 5.0, 0.0),
        ]
    );
    assert!(close(m[1].mv.feed, 10.0));
    // Each move that turns a rotary axis carries where the axes end, in radians; the others
    // leave them where they stood.
    let deg =
        |a: f64, b: f64, c: f64| Some(Rotary::new(a.to_radians(), b.to_radians(), c.to_radians()));
    let rot: Vec<Option<Rotary>> = m.iter().map(|x| x.mv.rotary).collect();
    assert_eq!(
        rot,
        [
            deg(0.0, 0.0, 0.0),
            deg(90.0, 0.0, 0.0),
            deg(45.0, 0.0, 0.0),
            deg(45.0, 10.0, 20.0)
        ]
    );
    // G91 turns them by the words; a rotary-only feed is F deg/min in rad/s whatever the
    // units (G20), and in G93 the rotary chord times F/60.
    let m = read("G20 G91\nG1 C30 F600\nG1 X1\nG93 G1 A30 C40 F2\nM2\n");
    assert_eq!(m[0].mv.rotary, deg(0.0, 0.0, 30.0));
    assert!(close(m[0].mv.feed, 10f64.to_radians()));
    assert_eq!(m[1].mv.rotary, None);
    assert!(close(m[1].mv.feed, 25.4 * 10.0));
    assert_eq!(m[2].mv.rotary, deg(30.0, 0.0, 70.0));
    assert!(close(m[2].mv.feed, 50f64.to_radians() * 2.0 / 60.0));
    // Other dialects have no rotary words in the reader.
    let fanuc = ReaderOptions::default().with_dialect(millpath::gcode::Dialect::Fanuc);
    let r: Result<Vec<ReadMove>, _> = Reader::new("G21\nG0 A10\nM30\n".as_bytes(), fanuc).collect();
    assert!(r.is_err());
}

#[test]
fn m66_waits_for_nothing_and_reports_input_zero() {
    let m = read("G21\nM66 P0 L1 Q5\nG0 X[#5399 + 3]\nM2\n");
    assert_eq!(m.len(), 1);
    assert_eq!(m[0].mv.to, Point3::new(3.0, 0.0, 0.0));
    let e = refusal("G21\nM66 L1\nM2\n");
    assert!(e.contains("M66") && e.contains(":2"), "{e}");
}
