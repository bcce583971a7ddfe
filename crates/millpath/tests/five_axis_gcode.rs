//! Five-axis G-code: the program's timing is the plan's (G93 on any control; G94 under the
//! RS274NGC rule, recomputed here from the printed words), and every block's chord stays within
//! the stated tolerance of the planned joint trajectory.

use millpath::gcode::five_axis::{FeedMode, FiveAxisGcodeOptions, write_five_axis};
use millpath::machine::kinematics::{Kinematics, TableTable, TrtKind};
use millpath::motion::five_axis::{self, FiveAxisOptions, KnotOptions, Limits, plan};

/// `(words [X Y Z r1 r2], F or G4 seconds)` of every motion block.
fn blocks(g: &str, names: [&str; 5]) -> Vec<([f64; 5], Option<f64>, Option<f64>)> {
    let mut out = Vec::new();
    for l in g.lines() {
        if l.starts_with("G4 ") {
            let p = l.trim_start_matches("G4 P").parse::<f64>().unwrap();
            out.push(([f64::NAN; 5], None, Some(p)));
            continue;
        }
        if !(l.starts_with("G1 ") || l.starts_with("G0 ")) {
            continue;
        }
        let mut q = [f64::NAN; 5];
        let mut f = None;
        for w in l.split_whitespace().skip(1) {
            let (letter, v) = w.split_at(1);
            let v: f64 = v.parse().unwrap();
            if letter == "F" {
                f = Some(v);
            } else if let Some(i) = names.iter().position(|n| *n == letter) {
                q[i] = v;
            }
        }
        out.push((q, f, None));
    }
    out
}

#[test]
fn g93_and_g94_programs_take_the_planned_time_and_follow_the_plan() {
    let kin = TableTable::typical(TrtKind::Ac);
    let poses: Vec<_> = five_axis::paper_path().into_iter().take(8).collect();
    let opts = FiveAxisOptions::default()
        .with_knots(KnotOptions::default().with_iterations(3))
        .with_baseline(None);
    let out = plan(&kin, &poses, &Limits::paper(), &opts, None).unwrap();
    let total = out.result.total_time_s;
    let names = kin.axis_names();
    for mode in [FeedMode::InverseTime, FeedMode::UnitsPerMinute] {
        let go = FiveAxisGcodeOptions::default().with_feed_mode(mode);
        let mut buf = Vec::new();
        write_five_axis(&mut buf, &out.segments, &kin, &go).unwrap();
        let g = String::from_utf8(buf).unwrap();
        assert!(g.contains(if mode == FeedMode::InverseTime {
            "G93"
        } else {
            "G94"
        }));
        let b = blocks(&g, names);
        let mut prev = b[0].0;
        let mut time = 0.0;
        let mut times = Vec::new();
        for (q, f, dwell) in &b[1..] {
            let dt = if let Some(p) = dwell {
                *p
            } else {
                let f = f.unwrap();
                match mode {
                    FeedMode::InverseTime => 60.0 / f,
                    FeedMode::UnitsPerMinute => {
                        let lin = ((q[0] - prev[0]).powi(2)
                            + (q[1] - prev[1]).powi(2)
                            + (q[2] - prev[2]).powi(2))
                        .sqrt();
                        let rot = ((q[3] - prev[3]).powi(2) + (q[4] - prev[4]).powi(2)).sqrt();
                        60.0 * if lin > 0.0 { lin } else { rot } / f
                    }
                }
            };
            if dwell.is_none() {
                prev = *q;
            }
            time += dt;
            times.push((time, *q));
        }
        assert!(
            (time - total).abs() <= 1e-8 * total,
            "{mode:?}: {time} vs {total}"
        );
        // Every block ends where the plan is at that time, and the chord's midpoint is within
        // the tolerance (plus the 5e-5 rounding of the words) of the plan at mid-block.
        let mut t0 = 0.0;
        let mut q0 = b[0].0;
        for (t1, q1) in &times {
            let tm = 0.5 * (t0 + t1);
            for (t, want) in [
                (*t1, *q1),
                (tm, std::array::from_fn(|i| 0.5 * (q0[i] + q1[i]))),
            ] {
                let mut acc = 0.0;
                let mut got = None;
                for s in &out.segments {
                    if t <= acc + s.duration + 1e-6 {
                        got = Some(s.eval((t - acc).clamp(0.0, s.duration))[0]);
                        break;
                    }
                    acc += s.duration;
                }
                let got = got.unwrap();
                for i in 0..5 {
                    let v = if i < 3 { got[i] } else { got[i].to_degrees() };
                    let tol = if i < 3 {
                        go.tolerance_mm
                    } else {
                        go.tolerance_deg
                    };
                    assert!(
                        (v - want[i]).abs() <= tol + 6e-5,
                        "{mode:?} axis {i} at {t}: {v} vs {}",
                        want[i]
                    );
                }
            }
            t0 = *t1;
            q0 = *q1;
        }
    }
}
