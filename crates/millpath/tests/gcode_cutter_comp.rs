//! Cutter radius compensation (G40, G41, G42, G41.1, G42.1), judged twice:
//!
//! * by LinuxCNC's `rs274 -g` (the canonical motions it prints, with the same tool table):
//!   millpath's compensated moves must equal them (rs274_common::canon), and what rs274
//!   refuses millpath refuses, naming the line;
//! * by a geometric verifier that shares nothing with the compensation code: every point of
//!   every compensated move (sampled densely) lies at the tool radius from the programmed
//!   path (the same program read with G41/G42 taken out), within 1e-6 mm.
//!
//! When `rs274` is missing these tests FAIL (install linuxcnc-uspace; CI does).

mod rs274_common;

use millpath::gcode::{ReadMove, Reader, ReaderOptions, ToolTable, Units};
use millpath::geom::Point3;
use millpath::toolpath::{MoveKind, Plane};
use rs274_common::canon::{canon_moves, compare};
use rs274_common::rs274_file;
use std::time::Duration;

/// The tool table both readers get. Standalone rs274 reads tool tables in inches, so ours is
/// read in inches too: T1 is a 6 mm end mill, T2 a 1/4" one, T3 a 20 mm one, T4 a lathe tool
/// (orientation 2, 0.8 mm nose radius).
const TOOLS: &str = "T1 P1 D0.236220472 ;6 mm\nT2 P2 D0.25 ;1/4 in\n\
                     T3 P3 D0.787401575 ;20 mm\nT4 P4 D0.062992126 Q2 ;lathe\n";

/// T1's radius in mm, as the table gives it (0.236220472 in, 6 mm to 8 digits).
const R: f64 = 0.236220472 * 25.4 / 2.0;

fn options(name: &str) -> ReaderOptions {
    ReaderOptions::default()
        .with_origin(name)
        .with_tool_table(Some(std::sync::Arc::new(
            ToolTable::parse(TOOLS, Units::Inch, "tool.tbl").unwrap(),
        )))
}

fn ours(text: &str) -> Result<Vec<ReadMove>, String> {
    Reader::new(text.as_bytes(), options("main.ngc"))
        .collect::<Result<Vec<_>, _>>()
        .map_err(|e| e.to_string())
}

/// rs274's verdict on `text`: Ok(canonical output) or Err(its message).
fn theirs(text: &str) -> Result<String, String> {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("main.ngc"), text).unwrap();
    std::fs::write(dir.path().join("tool.tbl"), TOOLS).unwrap();
    let run = rs274_file(
        &dir.path().join("main.ngc"),
        None,
        Some(&dir.path().join("tool.tbl")),
        Duration::from_secs(20),
    );
    if run.ok {
        Ok(run.canon)
    } else {
        Err(run.messages)
    }
}

/// Both read `text` and their motions agree.
fn same_as_rs274(text: &str) -> Vec<ReadMove> {
    let canon = theirs(text).unwrap_or_else(|m| panic!("rs274 refuses:\n{text}\n{m}"));
    let mine = ours(text).unwrap_or_else(|e| panic!("millpath refuses:\n{text}\n{e}"));
    let moves = canon_moves(&canon).unwrap();
    assert!(!moves.is_empty(), "no motion in\n{text}");
    if let Some(d) = compare(&mine, &moves, Point3::ORIGIN) {
        panic!("{d}\n{text}\n{canon}");
    }
    mine
}

/// Both refuse `text`; ours names line `line` and contains `words`.
fn refused_as_rs274(text: &str, line: usize, words: &str) {
    let rs = theirs(text);
    assert!(rs.is_err(), "rs274 reads\n{text}");
    let e = ours(text).expect_err(text);
    assert!(
        e.contains(&format!("main.ngc:{line}")) && e.to_lowercase().contains(words),
        "{e}\nrs274: {}",
        rs.unwrap_err()
    );
}

// ---- The verifier: distances to the programmed path. ----

/// A programmed move in the plane: a segment or an arc (centre, radius, start angle, signed
/// sweep).
enum Piece {
    Segment((f64, f64), (f64, f64)),
    Arc((f64, f64), f64, f64, f64),
}

fn uv(p: Point3, plane: Plane) -> (f64, f64) {
    let (u, v, _) = plane.split(p - Point3::ORIGIN);
    (u, v)
}

fn piece(from: Point3, m: &ReadMove) -> Option<Piece> {
    match m.mv.kind {
        MoveKind::Rapid | MoveKind::Line => {
            let plane = m.modal.plane;
            Some(Piece::Segment(uv(from, plane), uv(m.mv.to, plane)))
        }
        MoveKind::Arc {
            center,
            plane,
            ccw,
            turns,
        } => {
            let (c, s, e) = (uv(center, plane), uv(from, plane), uv(m.mv.to, plane));
            let a0 = (s.1 - c.1).atan2(s.0 - c.0);
            let a1 = (e.1 - c.1).atan2(e.0 - c.0);
            let tau = std::f64::consts::TAU;
            let mut sweep = if ccw {
                (a1 - a0).rem_euclid(tau)
            } else {
                -(a0 - a1).rem_euclid(tau)
            };
            if sweep.abs() < 1e-12 {
                sweep = if ccw { tau } else { -tau };
            }
            sweep += f64::from(turns) * tau * sweep.signum();
            let r = (s.0 - c.0).hypot(s.1 - c.1);
            Some(Piece::Arc(c, r, a0, sweep))
        }
        MoveKind::Dwell { .. } => None,
    }
}

fn distance(q: (f64, f64), p: &Piece) -> f64 {
    match *p {
        Piece::Segment(a, b) => {
            let (dx, dy) = (b.0 - a.0, b.1 - a.1);
            let l2 = dx * dx + dy * dy;
            let t = if l2 == 0.0 {
                0.0
            } else {
                (((q.0 - a.0) * dx + (q.1 - a.1) * dy) / l2).clamp(0.0, 1.0)
            };
            (q.0 - a.0 - t * dx).hypot(q.1 - a.1 - t * dy)
        }
        Piece::Arc(c, r, a0, sweep) => {
            let a = (q.1 - c.1).atan2(q.0 - c.0);
            let tau = std::f64::consts::TAU;
            let within = if sweep.abs() >= tau {
                true
            } else if sweep > 0.0 {
                (a - a0).rem_euclid(tau) <= sweep
            } else {
                (a0 - a).rem_euclid(tau) <= -sweep
            };
            let ends = [a0, a0 + sweep].map(|t| (c.0 + r * t.cos(), c.1 + r * t.sin()));
            let to_ends = ends
                .iter()
                .map(|e| (q.0 - e.0).hypot(q.1 - e.1))
                .fold(f64::INFINITY, f64::min);
            if within {
                ((q.0 - c.0).hypot(q.1 - c.1) - r).abs().min(to_ends)
            } else {
                to_ends
            }
        }
    }
}

/// Points along a move (its start excluded), `n` of them.
fn samples(from: Point3, m: &ReadMove, n: usize) -> Vec<(f64, f64)> {
    let plane = m.modal.plane;
    match piece(from, m) {
        Some(Piece::Segment(a, b)) => (1..=n)
            .map(|k| {
                let t = k as f64 / n as f64;
                (a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1))
            })
            .collect(),
        Some(Piece::Arc(c, r, a0, sweep)) => (1..=n)
            .map(|k| {
                let t = a0 + sweep * k as f64 / n as f64;
                (c.0 + r * t.cos(), c.1 + r * t.sin())
            })
            .collect(),
        None => vec![uv(m.mv.to, plane)],
    }
}

/// The largest departure from `radius` of the distance between the compensated moves of
/// `text` (lines after `entry` and before `exit`, and the entry move's end) and its
/// programmed path (the moves of lines `entry+1..exit` read without compensation), and
/// where it is.
fn worst_offset_error(text: &str, entry: usize, exit: usize, radius: f64) -> (f64, String) {
    let plain: String = text
        .lines()
        .map(|l| {
            l.replace("G41.1", "")
                .replace("G42.1", "")
                .replace("G41", "")
                .replace("G42", "")
        })
        .collect::<Vec<_>>()
        .join("\n");
    let programmed = ours(&plain).expect("the program without compensation reads");
    let mut from = Point3::ORIGIN;
    let mut pieces = Vec::new();
    for m in &programmed {
        if m.line > entry
            && m.line < exit
            && let Some(p) = piece(from, m)
        {
            pieces.push(p);
        }
        from = m.mv.to;
    }
    assert!(!pieces.is_empty(), "no programmed path in\n{text}");
    let compensated = ours(text).unwrap();
    let mut from = Point3::ORIGIN;
    let mut worst: f64 = 0.0;
    let mut at = String::new();
    let mut checked = 0;
    for m in &compensated {
        let points = if m.line > entry && m.line < exit {
            samples(from, m, 400)
        } else if m.line == entry {
            vec![uv(m.mv.to, m.modal.plane)]
        } else {
            Vec::new()
        };
        for q in points {
            let d = pieces
                .iter()
                .map(|p| distance(q, p))
                .fold(f64::INFINITY, f64::min);
            if (d - radius).abs() > worst {
                worst = (d - radius).abs();
                at = format!("line {} at {q:?}: distance {d}", m.line);
            }
            checked += 1;
        }
        from = m.mv.to;
    }
    assert!(checked > 400, "only {checked} points checked in\n{text}");
    (worst, at)
}

// ---- Programs. ----

const HEAD: &str = "G21 G17 G90 G64 F600\nT1 M6\n";

/// A 40 × 30 rectangle run clockwise or counter-clockwise from the middle of its left edge,
/// entered square to that edge from the side the tool is on.
fn rectangle(side: &str, ccw: bool) -> (String, bool) {
    let outside = ccw == (side == "G42");
    let x0 = if outside { -10 } else { 10 };
    let edges = if ccw {
        "G1 X0 Y0\nG1 X40 Y0\nG1 X40 Y30\nG1 X0 Y30\nG1 X0 Y15\n"
    } else {
        "G1 X0 Y30\nG1 X40 Y30\nG1 X40 Y0\nG1 X0 Y0\nG1 X0 Y15\n"
    };
    let p = format!(
        "{HEAD}G0 X{x0} Y15 Z1\nG1 Z-1\n{side} D1\nG1 X0 Y15\n{edges}G40\nG1 X{x0} Y15\nM2\n"
    );
    (p, outside)
}

#[test]
fn rectangles_inside_and_outside_as_rs274() {
    for side in ["G41", "G42"] {
        for ccw in [false, true] {
            let (p, outside) = rectangle(side, ccw);
            let m = same_as_rs274(&p);
            // Outside: an arc round each corner; inside: the corners are cut back.
            let arcs = m
                .iter()
                .filter(|m| matches!(m.mv.kind, MoveKind::Arc { .. }))
                .count();
            assert_eq!(arcs, if outside { 4 } else { 0 }, "{p}");
            let (worst, at) = worst_offset_error(&p, 6, 12, R);
            assert!(worst < 1e-6, "{side} outside={outside}: {at}\n{p}");
            // The verifier sees a path offset by another radius.
            assert!(worst_offset_error(&p, 6, 12, R + 0.01).0 > 0.009);
        }
    }
}

/// Lines and arcs run counter-clockwise, tangent and not, entered square to the bottom edge
/// from the side the tool is on (`{Y}`: 10 inside for G41, -10 outside for G42).
const PROFILE: &str = "G0 X15 Y{Y} Z1\nG1 Z-1\nG41 D1\nG1 X15 Y0\nG1 X30\nG3 X40 Y10 R10\n\
                       G1 Y20\nG2 X50 Y30 I10 J0\nG1 X60\nG1 Y50\nG3 X40 Y50 I-10 J0\n\
                       G2 X20 Y50 I-10 J0\nG1 X10 Y60\nG1 X0 Y40\nG1 X0 Y0\nG1 X15 Y0\nG40\n\
                       G0 X15 Y{Y}\nM2\n";

/// Corners that are not tangent between every pair of kinds: line–arc, arc–arc, arc–line,
/// line–line (concave with G41, convex with G42).
const CORNERS: &str = "G0 X10 Y{Y} Z1\nG1 Z-1\nG41 D1\nG1 X10 Y0\nG1 X20\n\
                       G3 X25 Y15 I-5 J10\nG2 X19 Y27 I5 J10\nG1 X0 Y27\nG1 X0 Y0\n\
                       G1 X10 Y0\nG40\nG0 X10 Y{Y}\nM2\n";

#[test]
fn lines_and_arcs_with_both_kinds_of_corner_as_rs274() {
    for (profile, exit) in [(PROFILE, 19), (CORNERS, 13)] {
        for (side, y) in [("G41", "10"), ("G42", "-10")] {
            let p = format!("{HEAD}{}", profile.replace("G41", side).replace("{Y}", y));
            let m = same_as_rs274(&p);
            assert!(m.iter().any(|m| matches!(m.mv.kind, MoveKind::Arc { .. })));
            let (worst, at) = worst_offset_error(&p, 6, exit, R);
            assert!(worst < 1e-6, "{side}: {at}\n{p}");
        }
    }
}

#[test]
fn entry_and_exit_moves_as_rs274() {
    for p in [
        // An arc entry, a G0 entry, an entry with Z, a G40 in the block of the exit move.
        format!("{HEAD}G0 X-10 Y0\nG41 D1\nG3 X0 Y10 R10\nG1 X20\nG40 G1 X30 Y20\nM2\n"),
        format!("{HEAD}G0 X-10 Y-5\nG42 D1\nG0 X0 Y0 Z-1\nG1 X20 Y0\nG1 Y20\nG40\nG0 X30\nM2\n"),
        format!(
            "{HEAD}G0 X-10 Y-5 Z5\nG41 D1\nG1 X0 Y0 Z-1\nG1 Z-2\nG1 X20\nG1 Y20 Z-1\nG40\n\
             G1 X25 Y25\nM2\n"
        ),
        // G91 moves are measured from the programmed point, not the tool.
        format!("{HEAD}G0 X-10 Y-5\nG41 D1\nG91 G1 X10 Y5\nX20\nY20\nX-20\nG90 G40\nG1 X-10\nM2\n"),
        // G41.1/G42.1 with a diameter, a negative one (the other side), the tool in the
        // spindle (no D), a D of another tool, inches.
        format!("{HEAD}G0 X-10\nG41.1 D8\nG1 X0 Y0\nG1 X20\nG1 Y20\nG40\nG1 X30\nM2\n"),
        format!("{HEAD}G0 X-10\nG42.1 D-8\nG1 X0 Y0\nG1 X20\nG1 Y20\nG40\nG1 X30\nM2\n"),
        format!("{HEAD}G0 X-10\nG42\nG1 X0 Y0\nG1 X20\nG2 Y20 R10\nG40\nG1 X30\nM2\n"),
        "G20\nG17 F20\nT1 M6\nG0 X-1 Y-1\nG41 D2\nG1 X0 Y0\nG1 Y1\nG2 X1 Y2 R1\nG1 X2\n\
         G40\nG0 X3\nM2\n"
            .to_string(),
        // A dwell and M0 while compensation is on; the queued move comes first.
        format!("{HEAD}G0 X-10\nG41 D1\nG1 X0 Y0\nG1 X20\nG4 P0.5\nG1 Y20\nM0\nG1 X0\nG40\nM2\n"),
        // M2 with compensation on: the last move keeps its offset end.
        format!("{HEAD}G0 X-10\nG42 D1\nG1 X0 Y0\nG1 X20\nG1 Y20\nM2\n"),
        // A full circle after a tangent entry arc, and a helix.
        format!(
            "{HEAD}G0 X0 Y-20\nG41 D1\nG3 X20 Y0 R20\nG3 I-20 J0\nG3 X0 Y20 Z-3 R20\nG40\nG1 X0 Y30\nM2\n"
        ),
        // G0 round a convex corner: a straight traverse instead of the arc.
        format!("{HEAD}G0 X-10 Y10\nG41 D1\nG0 X0 Y0\nG0 X20\nG0 X20 Y-20\nG40\nG0 X30\nM2\n"),
        // A two-turn circle (P2) after a line.
        format!(
            "{HEAD}G0 X-10 Y-10\nG42 D1\nG1 X0 Y0\nG1 X20\nG2 I0 J10 P2\nG1 X30\nG40\nG1 X40\nM2\n"
        ),
        // A collinear continuation and a straight line across a tangent arc.
        format!(
            "{HEAD}G0 X-10 Y-10\nG41 D1\nG1 X0 Y0\nG1 X10\nG1 X20\nG3 X30 Y10 R10\nG1 Y30\nG40\nG1 X40\nM2\n"
        ),
    ] {
        same_as_rs274(&p);
    }
}

#[test]
fn the_xz_plane_and_lathe_tools_as_rs274() {
    for p in [
        "G21 G18 G90 F200\nT1 M6\nG0 X-10 Z-10\nG41 D1\nG1 X0 Z0\nG1 Z30\nG2 X10 Z40 R10\n\
         G1 X20\nG40\nG1 X30 Z50\nM2\n",
        "G21 G18 G90 F200\nT4 M6\nG0 X10 Z5\nG42\nG1 X5 Z0\nG1 Z-20\nG2 X9 Z-24 R4\nG1 X15\n\
         G40\nG0 X20\nM2\n",
        "G21 G18 G90 F200\nT1 M6\nG0 X-10 Z-10\nG41.1 D2 L3\nG1 X0 Z0\nG1 Z30\nG40\nG1 X5\nM2\n",
    ] {
        same_as_rs274(p);
    }
}

#[test]
fn refusals_as_rs274() {
    for (p, line, words) in [
        // An inside arc smaller than the tool (r = 2 < 3 mm).
        (
            format!("{HEAD}G0 X-10\nG41 D1\nG1 X0 Y0\nG1 X20\nG3 X20 Y4 R2\nG40\nM2\n"),
            7,
            "tool radius not less than arc radius",
        ),
        // A notch 4 mm wide for a 6 mm tool.
        (
            format!(
                "{HEAD}G0 X-10 Y-10\nG41 D1\nG1 X0 Y0\nG1 X20\nG1 Y-10\nG1 X24\nG1 Y0\n\
                 G1 X40\nG40\nM2\n"
            ),
            9,
            "gouging",
        ),
        // An entry move no longer than the radius.
        (
            format!("{HEAD}G0 X-2\nG41 D1\nG1 X0 Y0\nG1 X20\nG40\nM2\n"),
            5,
            "entry move",
        ),
        (
            format!("{HEAD}G0 X-10\nG41 D1\nG1 X0 Y0\nG42 D1\nG1 X20\nG40\nM2\n"),
            6,
            "already on",
        ),
        (
            format!("{HEAD}G0 X-10\nG41 D1\nG1 X0 Y0\nG18\nG1 X20\nG40\nM2\n"),
            6,
            "planes",
        ),
        (
            format!("{HEAD}G0 X-10\nG41 D1\nG1 X0 Y0\nT2 M6\nG1 X20\nG40\nM2\n"),
            6,
            "tools",
        ),
        (
            format!("{HEAD}G0 X-10\nG41 D1\nG1 X0 Y0\nG1 X20\nG40\nG2 X30 Y10 R10\nM2\n"),
            8,
            "must be straight",
        ),
        (
            format!("{HEAD}G0 X-10\nG41 D1\nG1 X0 Y0\nG54\nG1 X20\nG40\nM2\n"),
            6,
            "coordinate systems",
        ),
        (format!("{HEAD}G19\nG41 D1\nG1 X0 Y10\nM2\n"), 4, "g19"),
        (
            format!("{HEAD}G0 X-10\nG41 D9\nG1 X0 Y0\nM2\n"),
            4,
            "tool 9",
        ),
    ] {
        refused_as_rs274(&p, line, words);
    }
}
