//! `millpath estimate` on a 1,000,000-line program (reader → planner → limit verifier), with
//! the verifier (on a second thread, and on the planner's), without it, and on the
//! `linuxcnc` model, beside LinuxCNC's own interpreter `rs274 -g` reading the same file in
//! the same run (skipped with a note when `rs274` is not installed). Each run twice: in wall
//! time (group `estimate`) and in CPU time of the process and its children (group
//! `estimate_cpu`, what the runs cost whatever else shares the machine).
//!
//! The program is a finishing raster over a free-form surface as CAM output writes it: rows
//! 0.15 mm apart following a gentle flowline, each row flattened into G1 segments of 0.05–0.5 mm
//! (chordal tolerance 0.5 µm on the surface's curvature along the row: 0.14 mm on average,
//! about 2900 s at F3000), three decimals, `G64
//! P0.01`, F3000 cutting and F1000 plunges. It is written to
//! `$CARGO_TARGET_TMPDIR/estimate_surface_1m.ngc` (deterministic: the same bytes every run),
//! where the command-line runs of BENCHMARKS.md read it too.

// The program's path and the note on a missing rs274 go to stderr, beside criterion's report.
#![allow(clippy::print_stderr)]

use criterion::measurement::{Measurement, ValueFormatter};
use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use millpath::job::estimate::{EstimateSettings, run};
use millpath::machine::Machine;
use std::fmt::Write as _;
use std::hint::black_box;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

/// G1 lines of the program (the header, row links and footer add about 0.1 % more).
const LINES: usize = 1_000_000;

/// The surface, mm.
fn surface(x: f64, y: f64) -> f64 {
    -3.0 + 2.0 * (x / 13.0).sin() * (y / 17.0).cos()
        + 0.8 * ((x + 2.0 * y) / 5.3).sin()
        + 0.3 * (x / 0.9).sin() * (y / 3.1).cos()
}

/// The row's flowline: `y` at `x` on row `k`.
fn flowline(k: usize, x: f64) -> f64 {
    k as f64 * 0.15 + 1.5 * (x / 31.0 + k as f64 * 0.01).sin()
}

/// The program text: `lines` G1 cutting segments in rows over 0 ≤ x ≤ 200 mm.
pub fn surface_program(lines: usize) -> String {
    let mut out = String::with_capacity(lines * 30);
    out.push_str("(surface finishing raster, 6 mm ball)\nG21 G90 G17 G64 P0.01\n");
    out.push_str("G0 Z5.000\nG0 X0.000 Y0.000\nS12000 M3\n");
    let (x_end, tol, h) = (200.0_f64, 0.0005_f64, 0.01_f64);
    let mut written = 0;
    let mut k = 0;
    while written < lines {
        let forward = k % 2 == 0;
        let mut x: f64 = if forward { 0.0 } else { x_end };
        let y = flowline(k, x);
        if k == 0 {
            let _ = writeln!(out, "G1 Z{:.3} F1000", surface(x, y));
        } else {
            // Step over to the next row at the plunge feed.
            let _ = writeln!(out, "G1 X{x:.3} Y{y:.3} Z{:.3} F1000", surface(x, y));
        }
        let _ = writeln!(out, "F3000");
        while written < lines {
            // Curvature of the surface along the row (second difference in x), and the
            // chord whose sagitta is `tol` on it.
            let z2 = |x: f64| surface(x, flowline(k, x));
            let curv = ((z2(x + h) - 2.0 * z2(x) + z2(x - h)) / (h * h)).abs();
            let step = (8.0 * tol / curv.max(1e-9)).sqrt().clamp(0.05, 0.5);
            x = if forward {
                (x + step).min(x_end)
            } else {
                (x - step).max(0.0)
            };
            let y = flowline(k, x);
            let _ = writeln!(out, "X{x:.3} Y{y:.3} Z{:.3}", surface(x, y));
            written += 1;
            if x <= 0.0 || x >= x_end {
                break;
            }
        }
        k += 1;
    }
    out.push_str("G0 Z5.000\nM5\nM2\n");
    out
}

/// Writes the program where BENCHMARKS.md's command-line runs read it.
fn program_file() -> PathBuf {
    let path = Path::new(env!("CARGO_TARGET_TMPDIR")).join("estimate_surface_1m.ngc");
    std::fs::write(&path, surface_program(LINES)).expect("writes the program");
    eprintln!("program: {}", path.display());
    path
}

/// Whether `rs274` runs here.
fn has_rs274() -> bool {
    Command::new("rs274")
        .arg("-g")
        .arg("/dev/null")
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .is_ok()
}

/// CPU time of this process and of the children it waited for (rs274): user and system,
/// from `/proc/self/stat`, in clock ticks of 10 ms (Linux's `USER_HZ`). An iteration here
/// takes a second or more, so the tick is at most 1 % of it. On a machine shared with other
/// builds, wall time measures the scheduler as much as the code; CPU time does not (it is
/// the sum over the estimate's threads: the cost, not the latency).
#[derive(Debug)]
struct CpuTime;

fn cpu_ns() -> u64 {
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    // The fields after the command name (which may hold spaces) in parentheses: utime,
    // stime, cutime, cstime are the 12th to 15th of them.
    let rest = stat.rsplit_once(')').map_or("", |(_, r)| r);
    let ticks: u64 = rest
        .split_whitespace()
        .skip(11)
        .take(4)
        .filter_map(|f| f.parse::<u64>().ok())
        .sum();
    ticks * 10_000_000
}

impl Measurement for CpuTime {
    type Intermediate = u64;
    type Value = u64;
    fn start(&self) -> u64 {
        cpu_ns()
    }
    fn end(&self, start: u64) -> u64 {
        cpu_ns().saturating_sub(start)
    }
    fn add(&self, a: &u64, b: &u64) -> u64 {
        a + b
    }
    fn zero(&self) -> u64 {
        0
    }
    fn to_f64(&self, v: &u64) -> f64 {
        *v as f64
    }
    fn formatter(&self) -> &dyn ValueFormatter {
        &CpuFormatter
    }
}

#[derive(Debug)]
struct CpuFormatter;

impl ValueFormatter for CpuFormatter {
    fn scale_values(&self, _typical: f64, values: &mut [f64]) -> &'static str {
        for v in values {
            *v /= 1e9;
        }
        "s CPU"
    }
    fn scale_throughputs(&self, _typical: f64, t: &Throughput, values: &mut [f64]) -> &'static str {
        let n = match t {
            Throughput::Elements(n)
            | Throughput::Bytes(n)
            | Throughput::BytesDecimal(n)
            | Throughput::Bits(n) => *n as f64,
            _ => 1.0,
        };
        for v in values {
            *v = n / (*v / 1e9).max(1e-9) / 1e6;
        }
        "M elem/s CPU"
    }
    fn scale_for_machines(&self, _values: &mut [f64]) -> &'static str {
        "ns"
    }
}

/// The runs, under the measurement `M` (wall time or CPU time).
fn runs<M: Measurement>(c: &mut Criterion<M>, group: &str, path: &Path) {
    let mut g = c.benchmark_group(group);
    g.throughput(Throughput::Elements(LINES as u64));
    g.sample_size(10);
    let hsm = Machine::preset("hsm").expect("preset");
    let lc = Machine::preset("linuxcnc-time").expect("preset");
    for (name, machine, verify, parallel) in [
        ("surface_1m_hsm_verify", &hsm, true, true),
        ("surface_1m_hsm_verify_one_thread", &hsm, true, false),
        ("surface_1m_hsm_no_verify", &hsm, false, false),
        ("surface_1m_linuxcnc_time", &lc, true, false),
    ] {
        let settings = EstimateSettings {
            verify,
            parallel,
            ..EstimateSettings::default()
        };
        g.bench_function(name, |b| {
            b.iter(|| {
                let r = run(black_box(path), machine, &settings, &mut |_| {}).expect("estimate");
                black_box(r.estimate.cycle_time_s)
            });
        });
    }
    // The reference: LinuxCNC's interpreter reading the same file (its canonical calls to
    // /dev/null), with a HOME of its own (rs274 keeps its tool table in $HOME).
    if has_rs274() {
        let home = std::env::temp_dir().join("millpath-bench-rs274-home");
        std::fs::create_dir_all(&home).expect("a HOME for rs274");
        g.bench_function("surface_1m_rs274", |b| {
            b.iter(|| {
                let st = Command::new("rs274")
                    .env("HOME", &home)
                    .arg("-g")
                    .arg(path)
                    .stdout(Stdio::null())
                    .stderr(Stdio::null())
                    .status()
                    .expect("rs274 runs");
                assert!(st.success(), "rs274 failed: {st}");
            });
        });
    } else {
        eprintln!(
            "note: rs274 not found (Debian package linuxcnc-uspace): the reference is skipped"
        );
    }
    g.finish();
}

fn wall(c: &mut Criterion) {
    runs(c, "estimate", &program_file());
}

fn cpu(c: &mut Criterion<CpuTime>) {
    runs(c, "estimate_cpu", &program_file());
}

criterion_group!(wall_time, wall);
criterion_group! {
    name = cpu_time;
    config = Criterion::default().with_measurement(CpuTime);
    targets = cpu
}
criterion_main!(wall_time, cpu_time);
