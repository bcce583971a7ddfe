//! The feed profile, checked independently: the modulated toolpath is simulated again (its
//! moves split where the feed changes, so the samples fall differently) and at every sample
//! the programmed feed must be at most the law's feed for the engagement measured there
//! (within the documented tolerance), and a sample at or below the nominal engagement may
//! run below full feed only within the documented ramp distance of a sample above it (plus
//! the length of its move on a helix turn, which is not split). Moves are split only where
//! the feed changes, lines into lines and arcs into exact arcs.

use millpath::stock::{self, EngagementSample, SimOptions, StockSpec};
use millpath::strategy::pocket::{self, PocketOptions, StrategyKind, builtin};
use millpath::strategy::pocket::{FeedProfile, feed_factor as factor};
use millpath::toolpath::{MoveKind, Tool, Toolpath};

fn sim() -> SimOptions {
    SimOptions::default()
        .with_cell(0.05)
        .with_step(0.1)
        .with_window(0.5)
        .with_max_cells(40_000_000)
        .with_record_samples(true)
}

/// Path length along each chain of feed moves (reset at rapids and dwells) of every sample,
/// with the sample's programmed feed factor and engagement.
struct Along {
    chain: usize,
    s: f64,
    programmed: f64,
    angle: f64,
    /// The length of the sample's move when it is a helix turn (an arc that changes z;
    /// never split), else 0.
    entry: f64,
}

fn along(tp: &Toolpath, samples: &[EngagementSample], opts: &PocketOptions) -> Vec<Along> {
    let mut start = vec![(0usize, 0.0f64); tp.moves.len()];
    let mut entry = vec![0.0; tp.moves.len()];
    let (mut chain, mut s, mut open) = (0, 0.0, false);
    for (i, (from, m)) in tp.segments().enumerate() {
        if m.is_feed() {
            if !open {
                chain += 1;
                s = 0.0;
                open = true;
            }
            start[i] = (chain, s);
            s += m.length_from(from);
            if matches!(m.kind, MoveKind::Arc { .. }) && (m.to.z - from.z).abs() > 1e-9 {
                entry[i] = m.length_from(from);
            }
        } else {
            open = false;
        }
    }
    samples
        .iter()
        .map(|smp| {
            let m = &tp.moves[smp.move_index];
            // The programmed feed before modulation: the feed, or the plunge feed (at most a
            // third of it) of entries.
            let nominal = if m.feed > opts.plunge_feed * (1.0 + 1e-9) {
                opts.feed
            } else {
                opts.plunge_feed
            };
            let (chain, s0) = start[smp.move_index];
            Along {
                chain,
                s: s0 + smp.at,
                programmed: m.feed / nominal,
                angle: smp.angle,
                entry: entry[smp.move_index],
            }
        })
        .collect()
}

#[allow(clippy::print_stderr)]
fn check(kind: StrategyKind) {
    let shape = builtin::aerospace_pocket();
    let tool = Tool::flat(12.7).unwrap();
    let opts = PocketOptions::default()
        .with_depth(5.0)
        .with_step_down(5.0)
        .with_feed(600.0 * 25.4 / 60.0)
        .with_plunge_feed(600.0 * 25.4 / 180.0)
        // The finishing pass too (not after the spiral: its finishing lead-in feeds down
        // into the 5 µm the spiral's last lap leaves, which the verifier calls a plunge).
        .with_finish(kind != StrategyKind::Spiral);
    let r = pocket::generate(kind, &shape, &tool, &opts, &sim()).unwrap();
    assert!(r.notes.is_empty(), "{:?}", r.notes);
    assert!(r.verification.problems().is_empty());
    let nominal = pocket::nominal_engagement(opts.stepover_mm(&tool), tool.radius());
    let spec = StockSpec {
        outer: &shape.outer,
        islands: &shape.islands,
        wall_stock: 0.0,
    };
    let again = stock::simulate(&r.toolpath, spec, nominal.to_degrees(), &sim());
    let pts = along(&r.toolpath, &again.samples, &opts);
    assert!(pts.len() > 20_000, "{} samples", pts.len());
    let profile = FeedProfile::default();
    let tolerance = profile.tolerance(sim().step_for(&r.toolpath.tool));
    let ramp = profile.ramp_distance(opts.slowdown);

    // 1. Never above the law's feed (plus the tolerance) at the engagement measured there.
    let mut worst: f64 = f64::NEG_INFINITY;
    for p in &pts {
        let over = p.programmed - factor(p.angle, nominal, opts.slowdown);
        worst = worst.max(over);
    }
    assert!(
        worst <= tolerance + 1e-9,
        "{kind:?}: programmed feed {worst:.4} of F above the law's (tolerance {tolerance})"
    );

    // 2. Below full feed at or below the nominal engagement only near a higher engagement.
    let (mut reduced, mut reduced_nominal, mut total) = (0.0, 0.0, 0.0);
    let mut far: Vec<(usize, f64, f64)> = Vec::new();
    for (i, p) in pts.iter().enumerate() {
        let ds = if i > 0 && pts[i - 1].chain == p.chain {
            p.s - pts[i - 1].s
        } else {
            0.0
        };
        total += ds;
        if p.programmed >= 1.0 - 1e-9 {
            continue;
        }
        reduced += ds;
        if p.angle > nominal {
            continue;
        }
        reduced_nominal += ds;
        let near = pts
            .iter()
            .filter(|q| q.chain == p.chain && (q.s - p.s).abs() <= ramp + p.entry)
            .any(|q| q.angle > nominal);
        if !near {
            far.push((p.chain, p.s, p.programmed));
        }
    }
    assert!(
        far.is_empty(),
        "{kind:?}: {} samples below full feed farther than {ramp} mm from a higher engagement, \
         first {:?}",
        far.len(),
        far.first()
    );
    // The profile does slow down somewhere, and not everywhere.
    assert!(
        reduced > 0.0 && reduced < 0.8 * total,
        "{kind:?}: {reduced} of {total} mm"
    );
    eprintln!(
        "{kind:?}: {:.0} of {:.0} mm below full feed ({:.0} mm of it at or below the nominal \
         engagement), worst {worst:.4}",
        reduced, total, reduced_nominal
    );

    // 3. Split only where the feed changes: the unmodulated toolpath's moves map onto runs
    //    of modulated ones of the same kind, with a different feed from piece to piece, each
    //    piece at least half a piece long.
    let plain = pocket::toolpath(kind, &shape, &tool, &opts).unwrap();
    let mut j = 0;
    let mut from = plain.start;
    for m in &plain.moves {
        let first = j;
        while j < r.toolpath.moves.len() && r.toolpath.moves[j].to.distance(m.to) > 1e-9 {
            j += 1;
        }
        assert!(j < r.toolpath.moves.len(), "{kind:?}: move {m:?} lost");
        let run = &r.toolpath.moves[first..=j];
        if run.len() > 1 {
            let mut at = from;
            for (a, w) in run.iter().zip(run.iter().skip(1)) {
                assert!(
                    (a.feed - w.feed).abs() > 1e-9,
                    "{kind:?}: split without a change"
                );
                let len = a.length_from(at);
                assert!(
                    len >= 0.5 * profile.min_piece - 1e-6,
                    "{kind:?}: piece {len} mm"
                );
                at = a.to;
            }
            let mut at = from;
            for piece in run {
                let start = at;
                at = piece.to;
                match (m.kind, piece.kind) {
                    (MoveKind::Line, MoveKind::Line) => {}
                    (MoveKind::Arc { center: c, .. }, MoveKind::Arc { center: d, .. }) => {
                        assert!(c.xy().distance(d.xy()) < 1e-12);
                    }
                    // A piece of a near-straight arc flatter than the writer's rounding.
                    (MoveKind::Arc { .. }, MoveKind::Line) => {
                        let sub = millpath::toolpath::Move { to: piece.to, ..*m };
                        let s = sub.sagitta_from(start).unwrap();
                        assert!(s <= pocket::ARC_AS_LINE_SAGITTA, "{kind:?}: {s}");
                    }
                    (a, b) => panic!("{kind:?}: {a:?} split into {b:?}"),
                }
            }
        }
        from = m.to;
        j += 1;
    }
    assert_eq!(j, r.toolpath.moves.len());
}

#[test]
fn spiral_feed_follows_the_law_along_the_path() {
    check(StrategyKind::Spiral);
}

#[test]
fn offset_feed_follows_the_law_along_the_path() {
    check(StrategyKind::Offset);
}

#[test]
fn zigzag_feed_follows_the_law_along_the_path() {
    check(StrategyKind::Zigzag);
}

/// `x` moved by `k` units in its last place (towards larger magnitude for `k > 0`).
fn nudge(x: f64, k: i64) -> f64 {
    if x == 0.0 {
        return x;
    }
    f64::from_bits(x.to_bits().wrapping_add_signed(k))
}

/// The tool positions the simulation takes along a move do not follow the last bits of the
/// move's length (`stock::sample_count`, `STEP_TIE`): a zigzag's links between rows along a
/// straight wall are one stepover long, 1.2 mm for a 3 mm tool, twelve steps of 0.1 mm (on
/// `pb_key.dxf`, the web page's real drawing), and the same path with every coordinate a few
/// units in the last place off (what another platform's math library makes of the same
/// offsets) is sampled at the same number of positions on every move, at the same places
/// along it. The plain ceiling of `len/step` gave such a link 12 positions or 13 by its last
/// bit, and the feed profile a different feed word in the web page than in the CLI.
#[test]
fn samples_do_not_follow_the_last_bits_of_a_move() {
    let path = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../../shared/real-inputs/files/pb_key.dxf");
    let (loops, _) = millpath::job::load_outline(
        &path.display().to_string(),
        &millpath::io::ImportSettings::default(),
    )
    .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let tool = Tool::flat(3.0).unwrap();
    let opts = PocketOptions::default().with_depth(3.0).with_step_down(3.0);
    let step = sim().step_for(&tool);
    let mut links = 0;
    for (n, p) in loops.pockets().into_iter().enumerate() {
        let shape = pocket::PocketShape::new(p.outer, p.islands, "pb_key.dxf").expect("a pocket");
        let r = pocket::generate(StrategyKind::Zigzag, &shape, &tool, &opts, &sim()).unwrap();
        assert!(r.verification.problems().is_empty(), "pocket {n}");
        links += r
            .toolpath
            .segments()
            .filter(|(from, m)| m.is_feed() && (m.length_from(*from) / step - 12.0).abs() < 1e-9)
            .count();
        let spec = StockSpec {
            outer: &shape.outer,
            islands: &shape.islands,
            wall_stock: 0.0,
        };
        let per_move = |tp: &Toolpath| {
            let mut v: Vec<Vec<f64>> = vec![Vec::new(); tp.moves.len()];
            for smp in stock::simulate(tp, spec, 0.0, &sim()).samples {
                v[smp.move_index].push(smp.at);
            }
            v
        };
        let want = per_move(&r.toolpath);
        for k in 1..=4i64 {
            let mut tp = r.toolpath.clone();
            for (i, m) in tp.moves.iter_mut().enumerate() {
                let sign = [1, -1, 0][i % 3];
                m.to.x = nudge(m.to.x, sign * k);
                m.to.y = nudge(m.to.y, -sign * k);
            }
            for (i, (a, b)) in want.iter().zip(&per_move(&tp)).enumerate() {
                assert_eq!(a.len(), b.len(), "pocket {n}, {k} ulp: move {i}: positions");
                for (x, y) in a.iter().zip(b) {
                    assert!(
                        (x - y).abs() < 1e-9,
                        "pocket {n}, {k} ulp: move {i}: {x}, {y}"
                    );
                }
            }
        }
    }
    assert!(
        links >= 3,
        "{links} moves of twelve steps: the case has no ties"
    );
}
