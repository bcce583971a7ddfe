//! "No panic on any input" for the text and file readers: the G-code reader, the point-list
//! parser, the outline importers (JSON, DXF, SVG) and machine profiles from TOML.
//!
//! Each pass is seeded (ChaCha8) and bounded so the whole of it stays well under a few seconds
//! at the test profile; every call must return `Ok` or `Err`, and a panic fails the test with
//! the input that caused it (see `hostile_common`). What the G-code reader accepts is
//! also written back (LinuxCNC, 10 decimals) and read again: the same moves, or the test
//! fails with the program.

mod gcode_common;
mod hostile_common;

use hostile_common::{Harness, hostile_number_text, random_bytes, rng};
use millpath::gcode::{Dialect, Reader, ReaderOptions, WriterOptions, read_str, write_to_string};
use millpath::io::{dxf, outline_json, points, svg};
use millpath::machine::Machine;
use rand::RngExt;
use rand_chacha::ChaCha8Rng;

fn pick<'a>(rng: &mut ChaCha8Rng, from: &[&'a str]) -> &'a str {
    from[rng.random_range(0..from.len())]
}

/// A line of G-code word soup: real words with hostile numbers, empty words, comments,
/// deep arcs (large `P` turn counts), unit and mode switches.
fn gcode_line(rng: &mut ChaCha8Rng) -> String {
    let mut line = String::new();
    if rng.random_bool(0.05) {
        line.push('/');
    }
    if rng.random_bool(0.1) {
        line.push_str(&format!("N{} ", rng.random_range(0..100000)));
    }
    for _ in 0..rng.random_range(0..7) {
        match rng.random_range(0..12) {
            0 => line.push_str(pick(
                rng,
                &[
                    "G0", "G1", "G2", "G3", "G4", "G17", "G18", "G19", "G20", "G21", "G40", "G41",
                    "G43", "G53", "G54", "G59", "G61", "G61.1", "G64", "G90", "G91", "G93", "G94",
                    "G90.1", "G91.1", "M2", "M3", "M5", "M6", "M30", "G28", "G70", "G71", "G5",
                    "G99999",
                ],
            )),
            1 => line.push_str("(comment"),
            2 => line.push(';'),
            3 => line.push_str(&format!("P{}", rng.random_range(-3..1_000_000_000i64))),
            _ => {
                let l = pick(
                    rng,
                    &[
                        "X", "Y", "Z", "I", "J", "K", "R", "F", "P", "Q", "S", "T", "A", "B", "C",
                        "H", "D", "L", "E", "O", "#", "",
                    ],
                );
                line.push_str(l);
                line.push_str(&hostile_number_text(rng));
            }
        }
        line.push(' ');
    }
    line
}

fn gcode_opts(rng: &mut ChaCha8Rng) -> ReaderOptions {
    ReaderOptions::default()
        .with_dialect(match rng.random_range(0..3) {
            0 => Dialect::LinuxCnc,
            1 => Dialect::Fanuc,
            _ => Dialect::Sinumerik,
        })
        .with_lenient(rng.random_bool(0.5))
        .with_block_delete(rng.random_bool(0.3))
}

#[test]
fn gcode_reader_survives_word_soup_and_random_bytes() {
    let mut h = Harness::new("gcode reader");
    let mut r = rng(0x6c0de);
    let mut round_tripped = 0;
    for case in 0..1500 {
        let text: String = if case % 3 == 0 {
            String::from_utf8_lossy(&random_bytes(&mut r, 200)).into_owned()
        } else if case % 3 == 1 && r.random_bool(0.5) {
            plausible_program(&mut r)
        } else {
            let start = if r.random_bool(0.5) {
                "G21 G90 G17\n"
            } else {
                ""
            };
            let body: Vec<String> = (0..r.random_range(1..12))
                .map(|_| gcode_line(&mut r))
                .collect();
            format!("{start}{}", body.join("\n"))
        };
        let opts = gcode_opts(&mut r);
        if h.run(&text, || round_trips(&text, &opts)) == Some(true) {
            round_tripped += 1;
        }
        // The streaming reader over the raw bytes (invalid UTF-8 included), read to the end.
        let bytes = if case % 3 == 0 {
            random_bytes(&mut r, 200)
        } else {
            text.clone().into_bytes()
        };
        h.run(&bytes, || {
            let mut rd = Reader::new(std::io::Cursor::new(bytes.clone()), opts.clone());
            for item in rd.by_ref().take(10_000) {
                let _ = item;
            }
            let _ = (rd.position(), rd.warnings().len(), rd.lines_read());
        });
    }
    assert!(
        round_tripped >= 150,
        "only {round_tripped} programs read, written and read back"
    );
    h.finish(3000);
}

/// A program that reads: rapids, lines, arcs (the end on the start's circle, centre by
/// `I J`, in any plane) and dwells with ordinary numbers, in mm or inches, absolute or
/// incremental: what the round trip is checked on (word soup rarely reads).
fn plausible_program(r: &mut ChaCha8Rng) -> String {
    let mut out = vec![format!(
        "{} {} G17 F{:.3}",
        pick(r, &["G21", "G20"]),
        pick(r, &["G90", "G91"]),
        r.random_range(10.0..3000.0)
    )];
    let incremental = out[0].contains("G91");
    let (mut x, mut y) = (0.0f64, 0.0f64);
    for _ in 0..r.random_range(1..20) {
        match r.random_range(0..6) {
            0 => {
                let (nx, ny) = (r.random_range(-50.0..50.0), r.random_range(-50.0..50.0));
                out.push(coords(
                    "G0",
                    nx,
                    ny,
                    r.random_range(-5.0..5.0),
                    x,
                    y,
                    incremental,
                ));
                (x, y) = (nx, ny);
            }
            1 | 2 => {
                let (nx, ny) = (r.random_range(-50.0..50.0), r.random_range(-50.0..50.0));
                out.push(coords(
                    "G1",
                    nx,
                    ny,
                    r.random_range(-5.0..5.0),
                    x,
                    y,
                    incremental,
                ));
                (x, y) = (nx, ny);
            }
            3 | 4 => {
                // A centre 1..20 away, the end turned about it: exactly on the circle.
                let (i, j) = (r.random_range(-20.0..20.0), r.random_range(-20.0..20.0));
                if f64::hypot(i, j) < 1.0 {
                    continue;
                }
                let a = r.random_range(-3.0..3.0f64);
                let (cx, cy) = (x + i, y + j);
                let (nx, ny) = (
                    cx - i * a.cos() + j * a.sin(),
                    cy - i * a.sin() - j * a.cos(),
                );
                let g = pick(r, &["G2", "G3"]);
                let head = coords(g, nx, ny, 0.0, x, y, incremental);
                out.push(format!("{head} I{i:.6} J{j:.6}"));
                (x, y) = (nx, ny);
            }
            _ => out.push(format!("G4 P{:.3}", r.random_range(0.0..2.0))),
        }
    }
    out.push("M2".to_owned());
    out.join("\n")
}

/// `G X Y Z` to `(x, y)` from `(fx, fy)`, absolute or incremental (z absolute: it is drawn
/// fresh each move, so incremental z is the drawn value as a step).
fn coords(g: &str, x: f64, y: f64, z: f64, fx: f64, fy: f64, incremental: bool) -> String {
    let (x, y) = if incremental {
        (x - fx, y - fy)
    } else {
        (x, y)
    };
    format!("{g} X{x:.6} Y{y:.6} Z{z:.6}")
}

/// Reads `text`; when it reads (with a move), writes the moves back (LinuxCNC, 10 decimals)
/// and reads that again: it must give the same moves (within 1e-9 of each number's
/// magnitude), else this panics with both programs. `true` when it round-tripped.
fn round_trips(text: &str, opts: &ReaderOptions) -> bool {
    let Ok((tp, _)) = read_str(text, opts.clone()) else {
        return false;
    };
    if tp.moves.is_empty() {
        return false;
    }
    let wopts = WriterOptions::default()
        .with_dialect(Dialect::LinuxCnc)
        .with_decimals(Some(10));
    // The writer may refuse what the reader took (an arc below its smallest radius, a
    // coordinate it cannot write): an input error, never a panic.
    let written = match write_to_string(&tp, &wopts) {
        Ok((w, _)) => w,
        Err(millpath::Error::Input(_)) => return false,
        Err(e) => panic!("the writer failed: {e}\n{text}"),
    };
    let ropts = ReaderOptions::default()
        .with_dialect(Dialect::LinuxCnc)
        .with_start(tp.start);
    let (back, _) = read_str(&written, ropts)
        .unwrap_or_else(|e| panic!("the written program does not read: {e}\n{written}"));
    let want = gcode_common::with_start_rapid(&tp);
    assert_eq!(
        want.moves.len(),
        back.moves.len(),
        "move count\n{text}\n--- written:\n{written}"
    );
    for (i, (a, b)) in want.moves.iter().zip(&back.moves).enumerate() {
        let scale = 1.0 + a.to.x.abs().max(a.to.y.abs()).max(a.to.z.abs()) + a.feed.abs();
        let diff = gcode_common::move_difference(a, b);
        assert!(
            diff <= 1e-9 * scale,
            "move {i}: {a:?} read back as {b:?}\n{text}\n--- written:\n{written}"
        );
    }
    true
}

#[test]
fn point_parser_survives_hostile_csv_and_json() {
    let mut h = Harness::new("point parser");
    let mut r = rng(0x901475);
    for case in 0..1500 {
        let text = match case % 4 {
            0 => String::from_utf8_lossy(&random_bytes(&mut r, 200)).into_owned(),
            1 | 2 => {
                let sep = pick(&mut r, &[",", ";", "\t", " ", ",,", ""]);
                let mut s = String::new();
                if r.random_bool(0.3) {
                    s.push_str("x,y,group\n");
                }
                for _ in 0..r.random_range(0..20) {
                    match r.random_range(0..10) {
                        0 => s.push('\n'),
                        1 => s.push_str("# c\n"),
                        _ => {
                            let n = r.random_range(0..5);
                            let f: Vec<String> =
                                (0..n).map(|_| hostile_number_text(&mut r)).collect();
                            s.push_str(&f.join(sep));
                            s.push('\n');
                        }
                    }
                }
                s
            }
            _ => {
                let pt = |r: &mut ChaCha8Rng| {
                    let n = r.random_range(0..4);
                    let f: Vec<String> = (0..n).map(|_| json_number(r)).collect();
                    format!("[{}]", f.join(","))
                };
                let list = |r: &mut ChaCha8Rng| {
                    let n = r.random_range(0..10);
                    let v: Vec<String> = (0..n).map(|_| pt(r)).collect();
                    format!("[{}]", v.join(","))
                };
                if r.random_bool(0.5) {
                    format!("{{\"points\": {}}}", list(&mut r))
                } else {
                    let n = r.random_range(0..4);
                    let g: Vec<String> = (0..n).map(|_| list(&mut r)).collect();
                    format!("{{\"groups\": [{}]}}", g.join(","))
                }
            }
        };
        h.run(&text, || {
            if let Ok(groups) = points::parse(&text, "fuzz.csv") {
                let _ = points::regroup_for_four_point(groups);
            }
            let _ = points::parse_csv(&text, "fuzz.csv");
            let _ = points::parse_json(&text, "fuzz.json");
        });
    }
    h.finish(1500);
}

/// A JSON number token, sometimes one JSON cannot hold as f64 or not a number at all.
fn json_number(r: &mut ChaCha8Rng) -> String {
    match r.random_range(0..10) {
        0 => "1e400".into(),
        1 => "-1e400".into(),
        2 => "null".into(),
        3 => "\"7\"".into(),
        4 => "123456789012345678901234567890".into(),
        5 => "[]".into(),
        _ => format!("{:.3}", r.random_range(-200.0..200.0)),
    }
}

fn outline_json_text(r: &mut ChaCha8Rng) -> String {
    let vertex = |r: &mut ChaCha8Rng| {
        let n = r.random_range(1..5);
        let f: Vec<String> = (0..n).map(|_| json_number(r)).collect();
        format!("[{}]", f.join(","))
    };
    let ring = |r: &mut ChaCha8Rng| {
        let n = r.random_range(0..8);
        let v: Vec<String> = (0..n).map(|_| vertex(r)).collect();
        format!("[{}]", v.join(","))
    };
    let units = pick(r, &["\"mm\"", "\"in\"", "\"ft\"", "3"]);
    let outline = ring(r);
    let n = r.random_range(0..3);
    let islands: Vec<String> = (0..n).map(|_| ring(r)).collect();
    format!(
        "{{\"units\": {units}, \"outline\": {outline}, \"islands\": [{}]}}",
        islands.join(",")
    )
}

#[test]
fn outline_json_survives_hostile_rings() {
    let mut h = Harness::new("outline json");
    let mut r = rng(0x0a71e);
    for case in 0..1200 {
        let text = if case % 5 == 0 {
            String::from_utf8_lossy(&random_bytes(&mut r, 200)).into_owned()
        } else {
            outline_json_text(&mut r)
        };
        h.run(&text, || {
            let _ = outline_json::parse(&text, "fuzz.json");
        });
    }
    h.finish(1200);
}

/// An SVG document of paths, rects, circles, polygons with hostile numbers and commands.
fn svg_text(r: &mut ChaCha8Rng) -> String {
    let mut body = String::new();
    for _ in 0..r.random_range(0..4) {
        match r.random_range(0..5) {
            0 => {
                let mut d = String::new();
                for _ in 0..r.random_range(0..10) {
                    let c = pick(r, &["M", "m", "L", "l", "H", "V", "C", "c", "S", "Q", "T", "A", "a", "Z", "z", ""]);
                    d.push_str(c);
                    let n = match c {
                        "A" | "a" => 7,
                        "C" | "c" => 6,
                        "S" | "Q" => 4,
                        "H" | "V" => 1,
                        "Z" | "z" => 0,
                        _ => 2,
                    };
                    for _ in 0..n {
                        d.push(' ');
                        d.push_str(&svg_number(r));
                    }
                    d.push(' ');
                }
                body.push_str(&format!("<path d=\"{d}\"/>"));
            }
            1 => body.push_str(&format!(
                "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" rx=\"{}\"/>",
                svg_number(r),
                svg_number(r),
                svg_number(r),
                svg_number(r),
                svg_number(r)
            )),
            2 => body.push_str(&format!(
                "<circle cx=\"{}\" cy=\"{}\" r=\"{}\"/>",
                svg_number(r),
                svg_number(r),
                svg_number(r)
            )),
            3 => {
                let n = r.random_range(0..8);
                let p: Vec<String> = (0..n).map(|_| svg_number(r)).collect();
                body.push_str(&format!("<polygon points=\"{}\"/>", p.join(" ")));
            }
            _ => body.push_str(&format!(
                "<g transform=\"matrix({} {} {} {} {} {})\"><ellipse cx=\"1\" cy=\"2\" rx=\"{}\" ry=\"{}\"/></g>",
                svg_number(r),
                svg_number(r),
                svg_number(r),
                svg_number(r),
                svg_number(r),
                svg_number(r),
                svg_number(r),
                svg_number(r)
            )),
        }
    }
    format!("<svg xmlns=\"http://www.w3.org/2000/svg\">{body}</svg>")
}

fn svg_number(r: &mut ChaCha8Rng) -> String {
    match r.random_range(0..12) {
        0 => "1e400".into(),
        1 => "-1e308".into(),
        2 => "1e-320".into(),
        3 => "0".into(),
        4 => hostile_number_text(r),
        _ => format!("{:.2}", r.random_range(-100.0..100.0)),
    }
}

#[test]
fn svg_importer_survives_hostile_documents() {
    let mut h = Harness::new("svg importer");
    let mut r = rng(0x5f6);
    for case in 0..800 {
        let text = if case % 5 == 0 {
            String::from_utf8_lossy(&random_bytes(&mut r, 200)).into_owned()
        } else {
            svg_text(&mut r)
        };
        let tol = match r.random_range(0..6) {
            0 => f64::NAN,
            1 => 0.0,
            2 => -1.0,
            3 => 1e-12,
            _ => 0.01,
        };
        h.run(&(&text, tol), || {
            let _ = svg::parse(&text, "fuzz.svg", tol);
        });
    }
    h.finish(800);
}

/// An ASCII DXF with LINE, ARC, CIRCLE and LWPOLYLINE entities carrying hostile numbers.
fn dxf_text(r: &mut ChaCha8Rng) -> String {
    let mut s = String::from("0\nSECTION\n2\nENTITIES\n");
    let pair = |s: &mut String, code: u32, v: &str| s.push_str(&format!("{code}\n{v}\n"));
    for _ in 0..r.random_range(0..6) {
        match r.random_range(0..4) {
            0 => {
                pair(&mut s, 0, "LINE");
                for c in [10, 20, 30, 11, 21, 31] {
                    pair(&mut s, c, &svg_number(r));
                }
            }
            1 => {
                pair(&mut s, 0, "ARC");
                for c in [10, 20, 30, 40, 50, 51] {
                    pair(&mut s, c, &svg_number(r));
                }
            }
            2 => {
                pair(&mut s, 0, "CIRCLE");
                for c in [10, 20, 30, 40] {
                    pair(&mut s, c, &svg_number(r));
                }
            }
            _ => {
                pair(&mut s, 0, "LWPOLYLINE");
                let n = r.random_range(0..6);
                pair(&mut s, 90, &format!("{}", n + r.random_range(0..2)));
                pair(&mut s, 70, pick(r, &["0", "1", "128", "-1", "x"]));
                for _ in 0..n {
                    pair(&mut s, 10, &svg_number(r));
                    pair(&mut s, 20, &svg_number(r));
                    if r.random_bool(0.4) {
                        pair(&mut s, 42, &svg_number(r));
                    }
                }
            }
        }
    }
    s.push_str("0\nENDSEC\n0\nEOF\n");
    s
}

#[test]
fn dxf_importer_survives_hostile_drawings() {
    let mut h = Harness::new("dxf importer");
    let mut r = rng(0xd4f);
    for case in 0..800 {
        let bytes = if case % 5 == 0 {
            random_bytes(&mut r, 200)
        } else {
            dxf_text(&mut r).into_bytes()
        };
        h.run(&String::from_utf8_lossy(&bytes), || {
            let _ = dxf::parse(&bytes, "fuzz.dxf", &dxf::DxfOptions::default());
        });
    }
    h.finish(800);
}

#[test]
fn machine_profiles_survive_hostile_toml() {
    let mut h = Harness::new("machine toml");
    let mut r = rng(0x7011);
    let tv = |r: &mut ChaCha8Rng| -> String {
        match r.random_range(0..12) {
            0 => "nan".into(),
            1 => "inf".into(),
            2 => "-inf".into(),
            3 => "\"unlimited\"".into(),
            4 => "0".into(),
            5 => "-1".into(),
            6 => "9223372036854775807".into(),
            7 => "1e308".into(),
            8 => "5e-324".into(),
            9 => "\"x\"".into(),
            _ => format!("{:.3}", r.random_range(0.001..5000.0)),
        }
    };
    for case in 0..1000 {
        let text = if case % 5 == 0 {
            String::from_utf8_lossy(&random_bytes(&mut r, 200)).into_owned()
        } else {
            let mut s = format!(
                "name = \"m\"\nunits = {}\n",
                pick(&mut r, &["\"mm\"", "\"in\"", "\"ft\"", "1"])
            );
            for k in [
                "max_feed",
                "path_tolerance",
                "ipo_cycle",
                "curvature_accel_share",
                "curvature_jerk_share",
            ] {
                if r.random_bool(0.85) {
                    s.push_str(&format!("{k} = {}\n", tv(&mut r)));
                }
            }
            for a in ["x", "y", "z"] {
                if r.random_bool(0.95) {
                    s.push_str(&format!("[axes.{a}]\n"));
                    for k in ["max_velocity", "max_acceleration", "max_jerk", "rapid"] {
                        if r.random_bool(0.9) {
                            s.push_str(&format!("{k} = {}\n", tv(&mut r)));
                        }
                    }
                }
            }
            s
        };
        h.run(&text, || {
            let _ = Machine::from_toml_str(&text, "fuzz.toml");
        });
    }
    h.finish(1000);
}
