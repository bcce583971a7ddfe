//! Compute time of our five-axis minimum-time planner (inverse kinematics and the knot
//! optimiser, certified; the proof of minimality and the verifier are not planning) on the
//! paper's case (31 intervals, paper A/B machine), with and without poses added along the
//! end ramps, on the 200-pose tilting sweep through the pole (xyzac-trt), and of the paper's
//! GA baseline; and the whole library call (`five_axis::plan`: merging dense poses, planning,
//! the proof, the verifier) on the same sweep written with 100, 1,000 and 10,000 poses, and
//! turned 0.5° off the pole, as given and with a 1° tilt tolerance.

use criterion::{Criterion, criterion_group, criterion_main};
use millpath::job::five_axis::kinematics;
use millpath::machine::kinematics::{Kinematics, PaperAb, Pose, inverse_path};
use millpath::motion::five_axis::{
    self, BaselineOptions, FiveAxisOptions, KnotOptions, Limits, LimitsFile,
};
use std::hint::black_box;

/// Inverse kinematics, the poses added at the ends (`end_knots`), the knot optimiser.
fn plan(kin: &dyn Kinematics, poses: &[Pose], lim: &Limits, end_knots: usize) -> f64 {
    let ik = Default::default();
    let (joints, _) = inverse_path(kin, poses, &ik).expect("reachable");
    let (_, joints, _) = five_axis::refine_ends(poses, &joints, kin, lim, end_knots);
    let geo = five_axis::Geometry::new(&joints);
    let ko = KnotOptions::default().with_ramp_start(end_knots > 0);
    five_axis::optimize(&geo, kin, lim, &ko, &[])
        .expect("plan")
        .total()
}

fn bench(c: &mut Criterion) {
    let kin = PaperAb::paper();
    let lim = Limits::paper();
    let poses = five_axis::paper_path();
    let mut g = c.benchmark_group("five_axis_paper_case");
    g.sample_size(10);
    g.bench_function("ours_planner", |b| {
        b.iter(|| plan(&kin, black_box(&poses), &lim, 0));
    });
    g.bench_function("ours_planner_end_knots_auto", |b| {
        b.iter(|| {
            let (joints, _) =
                inverse_path(&kin, black_box(&poses), &Default::default()).expect("paper case");
            let k = five_axis::auto_end_knots(&joints, &kin, &lim);
            plan(&kin, &poses, &lim, k)
        });
    });
    g.bench_function("ours_planner_end_knots_4", |b| {
        b.iter(|| plan(&kin, black_box(&poses), &lim, 4));
    });
    let (joints, _) = inverse_path(&kin, &poses, &Default::default()).expect("paper case");
    let geo = five_axis::Geometry::new(&joints);
    let bo = BaselineOptions::default();
    let fixed = five_axis::fixed_states(&geo, &kin, &lim, &bo);
    g.bench_function("baseline_paper_ga", |b| {
        b.iter(|| {
            five_axis::run_baseline(
                black_box(&fixed),
                &kin,
                &lim,
                &bo,
                &KnotOptions::default().min_time,
            )
            .expect("baseline")
            .0
            .iter()
            .sum::<f64>()
        });
    });
    g.finish();

    let text = include_str!("../tests/data/five_axis/sweep.csv");
    let sweep = five_axis::parse_path_csv(text, "sweep.csv").expect("sweep");
    let trt = kinematics("xyzac-trt", &LimitsFile::default()).expect("machine");
    let mut g = c.benchmark_group("five_axis_sweep_200");
    g.sample_size(10);
    g.bench_function("ours_planner", |b| {
        b.iter(|| plan(trt.as_ref(), black_box(&sweep), &lim, 0));
    });
    g.finish();

    let mut g = c.benchmark_group("five_axis_sweep_poses");
    g.sample_size(10);
    let opts = FiveAxisOptions::default().with_baseline(None);
    for n in [100, 1000, 10_000] {
        let poses = five_axis::tilting_sweep(n);
        g.bench_function(format!("plan_{n}"), |b| {
            b.iter(|| {
                five_axis::plan(trt.as_ref(), black_box(&poses), &lim, &opts, None)
                    .expect("plan")
                    .result
                    .total_time_s
            });
        });
    }
    g.finish();

    // The tilting sweep turned 0.5° off the pole: as given (C turns round near the pole),
    // and with a 1° tilt tolerance (the axes straightened to pass the pole).
    let beside: Vec<Pose> = five_axis::tilting_sweep(200)
        .into_iter()
        .map(|p| {
            let miss = 0.5f64.to_radians();
            let c = std::f64::consts::FRAC_1_SQRT_2;
            let across = millpath::geom::Vec3::new(-c, c, 0.0) * miss.tan() * p.axis.z;
            Pose {
                tip: p.tip,
                axis: (p.axis + across).normalize().expect("axis"),
            }
        })
        .collect();
    let mut g = c.benchmark_group("five_axis_beside_pole_200");
    g.sample_size(10);
    for (name, tol) in [
        ("as_given", 0.0),
        ("tilt_tolerance_1deg", 1f64.to_radians()),
    ] {
        let o = opts.with_tilt_tolerance(tol);
        g.bench_function(name, |b| {
            b.iter(|| {
                five_axis::plan(trt.as_ref(), black_box(&beside), &lim, &o, None)
                    .expect("plan")
                    .result
                    .total_time_s
            });
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
