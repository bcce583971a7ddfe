//! Criterion benchmarks: a whole job made from a real drawing alone, as `millpath job --init
//! DRAWING` then `millpath job part.toml` make it: every operation planned (face, pockets,
//! holes, profile with tabs), the program written and timed, and the whole job verified on
//! the height-field stock. The job file is made once; each iteration reads the drawing and
//! runs the job.
//! `ez_forms.dxf` is the largest real drawing (1016 × 831 mm, 40 outlines), `pb_gear_cutout.dxf`
//! the largest file (splines and arcs); the sample part is the reference beside them. A
//! starting job whose profile is refused (no tab fits on some part) is run with the narrower
//! tabs its row names, added after the profile's `tabs` key.

use criterion::{Criterion, criterion_group, criterion_main};
use millpath::gcode::Dialect;
use millpath::io::ImportSettings;
use millpath::job::part::{init_file, parse, run_spec};
use std::hint::black_box;
use std::path::PathBuf;

fn job(c: &mut Criterion) {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/real-inputs/files");
    let work = std::env::temp_dir();
    let mut g = c.benchmark_group("whole job from the drawing alone");
    g.sample_size(10);
    for (name, edit) in [
        ("sample:part", None),
        ("ez_forms.dxf", Some("tab_width = 6.0")),
        ("pb_gear_cutout.dxf", None),
    ] {
        let drawing = if name.starts_with("sample:") {
            PathBuf::from(name)
        } else {
            dir.join(name)
        };
        let out = work.join("millpath-bench-job.toml");
        let Ok(text) = init_file(
            &drawing,
            &out,
            &ImportSettings::default(),
            Dialect::LinuxCnc,
            "hsm",
            &mut |_| {},
        ) else {
            continue;
        };
        let Ok(spec) = parse(&text, name, Some(&work)) else {
            continue;
        };
        let (spec, label) = if run_spec(spec.clone(), &mut |_| {}).is_ok() {
            (spec, name.to_owned())
        } else {
            let Some(edit) = edit else { continue };
            let edited: String = text
                .lines()
                .flat_map(|l| {
                    let extra = l.starts_with("tabs = ").then_some(edit);
                    std::iter::once(l).chain(extra)
                })
                .map(|l| format!("{l}\n"))
                .collect();
            let Ok(spec) = parse(&edited, name, Some(&work)) else {
                continue;
            };
            if run_spec(spec.clone(), &mut |_| {}).is_err() {
                continue;
            }
            (spec, format!("{name} ({edit})"))
        };
        g.bench_function(format!("{label}: plan, write, time and verify"), |b| {
            b.iter(|| run_spec(black_box(spec.clone()), &mut |_| {}).map(|r| r.report));
        });
    }
    g.finish();
}

criterion_group!(benches, job);
criterion_main!(benches);
