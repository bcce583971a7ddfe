//! Criterion benchmarks: the height-field stock of a whole job on real drawings. Each
//! drawing's pockets are planned once (zigzag, 6 mm tool, 6 mm deep in two levels, as
//! `millpath pocket` would), then timed: a fresh field over the drawing's extents plus
//! 10 mm with the default cell, the whole program cut into it, and the bridge verdict read
//! round the drawing's first outline.
//! `ez_forms.dxf` is the largest real drawing (1016 × 831 mm, 40 outlines: a 0.23 mm cell
//! at the 16 M-cell budget); `pb_box_shell.dxf` the largest file (283 × 300 mm, 17
//! outlines: 0.073 mm).

use criterion::{Criterion, criterion_group, criterion_main};
use millpath::geom::Aabb;
use millpath::job::pocket::{PocketSettings, run};
use millpath::job::{ProgramSettings, load_outline};
use millpath::stock::{BridgeOptions, FieldOptions, HeightField, held_by};
use std::hint::black_box;
use std::path::PathBuf;

fn job(c: &mut Criterion) {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/real-inputs/files");
    let mut g = c.benchmark_group("height field, whole pocket job");
    g.sample_size(10);
    for name in ["ez_forms.dxf", "pb_box_shell.dxf"] {
        let path = dir.join(name).to_string_lossy().into_owned();
        let settings = PocketSettings {
            strategy: "zigzag".into(),
            tool_diameter: 6.0,
            depth: 6.0,
            step_down: 3.0,
            ..PocketSettings::default()
        };
        let Ok((loops, _)) = load_outline(&path, &settings.import) else {
            continue;
        };
        let Ok(planned) = run(
            &loops,
            name,
            &settings,
            &ProgramSettings::default(),
            None,
            &mut |_| {},
        ) else {
            continue;
        };
        let tp = planned.part.toolpath;
        let outlines = planned_outlines(&loops);
        let bounds = outlines
            .iter()
            .fold(Aabb::EMPTY, |b, o| b.union(o.bounds()))
            .inflate(10.0);
        let opts = FieldOptions::default().with_tool_diameter(6.0);
        g.bench_function(format!("{name}: new field + cut"), |b| {
            b.iter(|| {
                let mut field = HeightField::new(bounds, -20.0, 0.0, &opts).ok();
                field.as_mut().map(|f| f.cut(black_box(&tp)))
            });
        });
        let Ok(mut field) = HeightField::new(bounds, -20.0, 0.0, &opts) else {
            continue;
        };
        field.cut(&tp);
        if let Some(outline) = outlines.first() {
            g.bench_function(format!("{name}: bridge verdict round outline 1"), |b| {
                b.iter(|| {
                    held_by(
                        &field,
                        black_box(outline),
                        -6.0,
                        3.0,
                        &BridgeOptions::default(),
                    )
                });
            });
        }
    }
    g.finish();
}

/// Every outline of the drawing, boundaries and islands.
fn planned_outlines(loops: &millpath::io::outline_json::Loops) -> Vec<millpath::geom::Outline> {
    loops
        .pockets()
        .into_iter()
        .flat_map(|p| std::iter::once(p.outer).chain(p.islands))
        .collect()
}

criterion_group!(benches, job);
criterion_main!(benches);
