//! Scale in bounded memory, short versions (run by `cargo test`):
//!
//! * a 50,000-vertex outline through the pocket import path (outline JSON → validated
//!   `Outline`, with its self-intersection check → inward offset) and the contour import path
//!   (points CSV → closed Catmull-Rom curve → flattening within tolerance);
//! * a 100,000-line G-code program through the streaming reader and the streaming planner
//!   (`motion::plan_stream`, what `millpath estimate` runs), with each chunk checked
//!   by the limit verifier, and the planner's buffer bounded by its window whatever the
//!   program's length.
//!
//! The long runs (1,000,000 vertices, 10,000,000 lines, with peak memory) are the ignored
//! tests below and `millpath estimate` on a generated program; see README "Long runs" and
//! BENCHMARKS.md. Sizes come from `MILLPATH_SCALE_VERTICES` / `MILLPATH_SCALE_LINES`.

mod hostile_common;

use millpath::curve::{self, CurveKind, flatten_curve};
use millpath::gcode::{Reader, ReaderOptions};
use millpath::io::{outline_json, points};
use millpath::machine::Machine;
use millpath::motion::{StreamOptions, plan_stream};
use millpath::motion::{VerifyOptions, verify_plan};
use std::fmt::Write as _;
use std::io::Read;

/// A wavy star of `n` vertices (simple: the radius is a function of the angle), scaled so
/// that vertices are ~0.6 mm apart (radius ~480 mm at 5,000 vertices, ~96 m at 1,000,000).
fn star(n: usize) -> Vec<(f64, f64)> {
    star_of_radius(n, 0.1 * n as f64)
}

fn star_of_radius(n: usize, r0: f64) -> Vec<(f64, f64)> {
    (0..n)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / n as f64;
            let r = r0 * (1.0 + 0.04 * (7.0 * a).sin() + 0.01 * (61.0 * a).cos());
            (r * a.cos(), r * a.sin())
        })
        .collect()
}

fn outline_at_scale(n: usize) {
    let pts = star(n);
    // Pocket path: outline JSON → validated outline → inward offset.
    let mut json = String::from("{\"outline\": [");
    for (i, (x, y)) in pts.iter().enumerate() {
        let sep = if i == 0 { "" } else { "," };
        write!(json, "{sep}[{x:.6},{y:.6}]").unwrap();
    }
    json.push_str("]}");
    let loops = outline_json::parse(&json, "big.json").expect("a valid outline");
    drop(json);
    assert_eq!(loops.outer.len(), n);
    let area = loops.outer.signed_area();
    let offs = loops.outer.offset(2.0);
    assert_eq!(offs.len(), 1, "one inward offset loop");
    let inner = offs[0].signed_area();
    // The band lost is about perimeter · 2 mm (the outline is smooth at this scale).
    let band = loops.outer.length() * 2.0;
    assert!(
        inner < area && (area - inner - band).abs() < 0.01 * band,
        "area {area} → {inner}, band {band}"
    );
    drop(offs);
    drop(loops);
    // Contour path: points CSV → closed Catmull-Rom → flattening within 0.01 mm.
    let mut csv = String::new();
    for (x, y) in &pts {
        writeln!(csv, "{x:.6},{y:.6}").unwrap();
    }
    let groups = points::parse(&csv, "big.csv").expect("points");
    drop(csv);
    let c = curve::build(&groups, CurveKind::CatmullRom, "big.csv").expect("curve");
    drop(groups);
    let tol = 0.01;
    let f = flatten_curve(&c, tol).expect("flattening");
    // The curve interpolates the points, so each lies within the tolerance of the chords
    // (checked here by walking both in order, not by the flattener's own deviation).
    let chords = &f.points;
    let mut j = 0;
    let d = |p: (f64, f64), j: usize| seg_dist(p, chords[j], chords[(j + 1) % chords.len()]);
    for &p in &pts {
        while j + 1 < chords.len() && d(p, j + 1) <= d(p, j) {
            j += 1;
        }
        // + 1e-6: the CSV holds the points rounded to 6 decimals (≤ 7.1e-7 mm off).
        assert!(
            d(p, j) <= tol + 1e-6,
            "point {p:?} is {} from the chords",
            d(p, j)
        );
    }
}

fn seg_dist(p: (f64, f64), a: millpath::Point, b: millpath::Point) -> f64 {
    let (dx, dy) = (b.x - a.x, b.y - a.y);
    let l2 = dx * dx + dy * dy;
    let t = if l2 > 0.0 {
        (((p.0 - a.x) * dx + (p.1 - a.y) * dy) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    ((p.0 - a.x - t * dx).powi(2) + (p.1 - a.y - t * dy).powi(2)).sqrt()
}

/// A G-code program of `lines` lines produced on the fly (never held in memory): a zigzag of
/// short feed moves with an arc now and then.
struct Program {
    lines: usize,
    i: usize,
    buf: Vec<u8>,
    at: usize,
}

impl Program {
    fn new(lines: usize) -> Self {
        Program {
            lines,
            i: 0,
            buf: b"G21 G90 G17 G64 P0.01\nG0 X0 Y0 Z1\nG1 Z0 F1200\n".to_vec(),
            at: 0,
        }
    }
}

impl Read for Program {
    fn read(&mut self, out: &mut [u8]) -> std::io::Result<usize> {
        while self.at >= self.buf.len() {
            if self.i >= self.lines {
                return Ok(0);
            }
            self.buf.clear();
            self.at = 0;
            let k = self.i;
            let x = (k % 200) as f64 * 0.5;
            let y = (k / 200) as f64 * 0.5;
            let line = if k % 50 == 49 {
                format!("G2 X{x:.3} Y{y:.3} R5\n")
            } else {
                format!("G1 X{x:.3} Y{y:.3}\n")
            };
            self.buf.extend_from_slice(line.as_bytes());
            self.i += 1;
        }
        let n = (self.buf.len() - self.at).min(out.len());
        out[..n].copy_from_slice(&self.buf[self.at..self.at + n]);
        self.at += n;
        Ok(n)
    }
}

fn gcode_at_scale(lines: usize, verify: bool) {
    let machine = Machine::preset("hsm").unwrap();
    let mut reader = Reader::new(
        std::io::BufReader::new(Program::new(lines)),
        ReaderOptions::default(),
    );
    let mut at = reader.position();
    let stream = std::iter::from_fn(|| {
        let item = reader.next()?;
        Some(item.map(|rm| {
            let f = at;
            at = rm.mv.to;
            (f, rm.mv)
        }))
    });
    let opts = StreamOptions::default();
    let mut violations = 0;
    let sum = plan_stream(stream, &machine, &opts, |c| {
        if verify {
            violations +=
                verify_plan(&c.plan, &c.moves, &machine, &VerifyOptions::default())?.violations;
        }
        Ok(())
    })
    .expect("the program plans");
    assert!(
        sum.blocks >= lines,
        "{} blocks for {lines} lines",
        sum.blocks
    );
    assert!(sum.total_time > 0.0 && sum.total_time.is_finite());
    assert_eq!(violations, 0);
    // Bounded memory: the buffer never exceeds a few windows, however long the program.
    assert!(
        sum.max_buffered_blocks <= 4 * opts.window + 64,
        "{} blocks buffered (window {})",
        sum.max_buffered_blocks,
        opts.window
    );
    assert!(sum.chunks >= lines / (4 * opts.window));
}

#[test]
fn outline_of_50k_vertices_imports_validates_offsets_and_flattens() {
    outline_at_scale(50_000);
}

#[test]
fn program_of_100k_lines_streams_through_the_planner_and_verifier() {
    gcode_at_scale(100_000, true);
}

/// Found while writing the scale test: a smooth 50,000-vertex star of radius 500 mm (vertices
/// 0.063 mm apart, the radius a single-valued function of the angle, so simple by
/// construction) was refused as "self-intersecting": `cavalier_contours`' scan reports two
/// consecutive segments that turn by 1e-4 rad as overlapping (its parallel test is not scaled
/// by the segments' lengths). `Outline::new` now drops that report (see `first_crossing`).
#[test]
fn dense_smooth_outline_is_not_self_intersecting() {
    let pts: Vec<millpath::Point> = star_of_radius(50_000, 500.0)
        .into_iter()
        .map(|(x, y)| millpath::Point::new(x, y))
        .collect();
    millpath::geom::Outline::from_points(&pts, "dense").expect("a simple outline");
}

/// Long run: `MILLPATH_SCALE_VERTICES=1000000 cargo test --release -p millpath --test
/// hostile_scale -- --ignored outline_long`.
#[test]
#[ignore = "long run (README: Long runs)"]
fn outline_long() {
    outline_at_scale(hostile_common::env_or("MILLPATH_SCALE_VERTICES", 1_000_000));
}

/// Long run: `MILLPATH_SCALE_LINES=10000000 cargo test --release -p millpath --test
/// hostile_scale -- --ignored gcode_long` (planner only; `millpath estimate` adds the verifier).
#[test]
#[ignore = "long run (README: Long runs)"]
fn gcode_long() {
    gcode_at_scale(
        hostile_common::env_or("MILLPATH_SCALE_LINES", 10_000_000),
        false,
    );
}
