//! G-code reading and writing throughput (the estimator reads 1-million-line programs).

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use millpath::gcode::{
    Dialect, Reader, ReaderOptions, WriterOptions, write_program, write_to_string,
};
use millpath::geom::Point3;
use millpath::toolpath::{Move, Tool, Toolpath};
use std::hint::black_box;

/// `n` short G1 moves along a wavy line (typical flattened free-form output) and every
/// 10th an arc.
fn toolpath(n: usize, arcs: bool) -> Toolpath {
    let mut tp = Toolpath::new(Tool::default(), Point3::new(0.0, 0.0, -1.0));
    for k in 1..=n {
        let x = k as f64 * 0.05;
        let to = Point3::new(x, (x * 0.7).sin() * 20.0, -1.0);
        if arcs && k % 10 == 0 {
            let from = tp.end();
            let mid = from.lerp(to, 0.5);
            let d = to - from;
            // Centre 10 chord-lengths to the left: a gentle arc.
            let c = Point3::new(mid.x - d.y * 10.0, mid.y + d.x * 10.0, -1.0);
            tp.push(Move::arc_xy(to, c, true, 50.0));
        } else {
            tp.push(Move::line(to, 50.0));
        }
    }
    tp
}

fn bench(c: &mut Criterion) {
    let n = 100_000;
    let mut g = c.benchmark_group("gcode");
    g.sample_size(10);
    g.throughput(Throughput::Elements(n as u64));
    for (name, arcs) in [("read_g1", false), ("read_g1_g3", true)] {
        let text = write_to_string(&toolpath(n, arcs), &WriterOptions::default())
            .expect("writes")
            .0;
        g.bench_function(name, |b| {
            b.iter(|| {
                let r = Reader::new(black_box(text.as_bytes()), ReaderOptions::default());
                r.map(|m| m.map(|m| m.mv.to.x))
                    .sum::<Result<f64, _>>()
                    .expect("reads")
            });
        });
    }
    // The same G1 program in the Fanuc dialect: its line source keeps the lines for jumps
    // and looks for macro statements in each.
    let fanuc = WriterOptions::default().with_dialect(Dialect::Fanuc);
    let text = write_to_string(&toolpath(n, false), &fanuc)
        .expect("writes")
        .0;
    g.bench_function("read_g1_fanuc", |b| {
        b.iter(|| {
            let opts = ReaderOptions::default().with_dialect(Dialect::Fanuc);
            let r = Reader::new(black_box(text.as_bytes()), opts);
            r.map(|m| m.map(|m| m.mv.to.x))
                .sum::<Result<f64, _>>()
                .expect("reads")
        });
    });
    let tp = toolpath(n, true);
    g.bench_function("write_g1_g3", |b| {
        b.iter(|| {
            write_program(
                black_box(&tp),
                &WriterOptions::default(),
                &mut std::io::sink(),
            )
        });
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
