//! No hook in a spiral: the path never steps back with two sharp turns of opposite sign a
//! short way apart (the controller stops for each), and with `--arcs` arcs meet arcs with
//! their tangents within 1°.
//!
//! The checker reads only the toolpath's moves (their end points, arc centres and senses)
//! and shares no code with the generator. A **hook** is a stretch of one level's planar feed
//! path no longer than [`HOOK_REACH`] tool diameters along which the path turns left by at
//! least [`HOOK_LEAST`] and right by at least [`HOOK_LEAST`], one of them by at least
//! [`HOOK_MOST`] (turns at the joints between moves, and along arcs). A slot's end reverses
//! the path one way only and a lane change bends both ways gently: neither is a hook. A
//! straight step between loops (a tool's stepover long) is longer than the reach. Turns on
//! the walls' loop (one tool radius from the walls, within [`WALL_BAND`]) are the walls' own:
//! a notch of the drawing is followed as drawn; so are arcs meeting there at a corner of the
//! walls' loop (a crescent's horn: the tool centre must reach the point that touches both
//! walls). Everywhere inside, arcs meet arcs within 1° on every pocket of the suite: the
//! interior loops' cusps (where two reflex corners' arcs meet on the medial axis) are
//! filleted and the lane changes leave and join the loops with their tangents.

mod hooks;

use hooks::{arc_joints, find_hooks};
use millpath::job::load_outline;
use millpath::job::pocket::DEFAULT_HELIX_RADIUS_PER_DIAMETER;
use millpath::stock::SimOptions;
use millpath::strategy::pocket::{self, Entry, PocketOptions, PocketShape, StrategyKind, builtin};
use millpath::toolpath::Tool;

/// How near one tool radius from the walls a turn is the walls' own, mm (the walls' loop is
/// cut 5 µm inside its exact offset).
const WALL_BAND: f64 = 0.01;

/// Whether a turn at `p` lies on the walls' loop of `shape` cut with a tool of radius `r`.
fn on_walls(shape: &PocketShape, r: f64) -> impl Fn(millpath::geom::Point) -> bool + '_ {
    move |p| (shape.distance_to(p) - r).abs() <= WALL_BAND
}

/// The suite's pockets, the structural part's and the sample part's, with their tools.
fn suite() -> Vec<(String, PocketShape, f64)> {
    let mut out: Vec<(String, PocketShape, f64)> = builtin::shape_suite()
        .into_iter()
        .map(|s| (s.name.to_owned(), s.shape, s.tool_diameter))
        .collect();
    for (name, shape) in builtin::structural_part() {
        out.push((format!("structural {name}"), shape, 10.0));
    }
    let (loops, _) = load_outline("sample:part", &Default::default()).expect("the sample part");
    for (i, p) in loops.pockets().into_iter().enumerate() {
        if let Ok(shape) = PocketShape::new(p.outer, p.islands, "sample:part") {
            out.push((format!("sample:part pocket {}", i + 1), shape, 6.0));
        }
    }
    out
}

#[test]
fn no_spiral_of_the_suite_has_a_hook() {
    let mut failures = Vec::new();
    let mut checked = 0;
    for (name, shape, d) in suite() {
        let tool = Tool::flat(d).unwrap();
        let opts = PocketOptions::default().with_depth(5.0).with_step_down(5.0);
        let tp = pocket::toolpath(StrategyKind::Spiral, &shape, &tool, &opts)
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        let (hooks, joints) = find_hooks(&tp, d, on_walls(&shape, 0.5 * d));
        assert!(joints > 20, "{name}: only {joints} joints checked");
        checked += 1;
        if let Some(h) = hooks.first() {
            failures.push(format!("{name}: {} hooks, first {h}", hooks.len()));
        }
    }
    assert!(checked >= 10, "{checked} pockets");
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn spiral_arcs_meet_within_a_degree() {
    let sim = SimOptions::default();
    let mut failures = Vec::new();
    let mut joints = 0;
    for (name, shape, d) in suite() {
        let tool = Tool::flat(d).unwrap();
        let opts = PocketOptions::default()
            .with_depth(5.0)
            .with_step_down(5.0)
            .with_arcs(true);
        // Verified: the fillets and the tangent lane ends gouge nothing and leave nothing.
        let r = pocket::generate(StrategyKind::Spiral, &shape, &tool, &opts, &sim)
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        let problems = r.verification.problems();
        if !problems.is_empty() {
            failures.push(format!("{name} --arcs: {problems:?}"));
        }
        let tp = r.toolpath;
        let (worst, at, n) = arc_joints(&tp, on_walls(&shape, 0.5 * d));
        assert!(n > 0, "{name}: no arc meets an arc");
        joints += n;
        if worst > 1.0 {
            failures.push(format!("{name}: arcs meet at {worst:.2}° at {at:?}"));
        }
        let (hooks, _) = find_hooks(&tp, d, on_walls(&shape, 0.5 * d));
        if let Some(h) = hooks.first() {
            failures.push(format!("{name} --arcs: {} hooks, first {h}", hooks.len()));
        }
    }
    assert!(joints > 500, "{joints} arc-to-arc joints");
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The real drawings (`../shared/real-inputs/files/`): every pocket of each, cut with a tool a
/// tenth of the largest pocket's smaller side (0.5–10 mm; uncapped at building scale, as
/// `millpath-cli`'s `cli_real_files` sizes it), one level, with the command line's default
/// helix ([`DEFAULT_HELIX_RADIUS_PER_DIAMETER`] of the tool: the library's fixed 2.5 mm is no
/// helix at all for `ez_1_polylines.dxf`'s 6 m tool, whose pocket 4 then had a leaf loop
/// entered by a straight lead-in at 129°).
#[test]
fn no_spiral_of_the_real_drawings_has_a_hook() {
    let dir = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../../shared/real-inputs/files");
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .expect("the real inputs")
        .filter_map(|e| e.ok()?.file_name().into_string().ok())
        .filter(|n| n.ends_with(".dxf") || n.ends_with(".svg"))
        .collect();
    names.sort();
    let (mut pockets, mut failures) = (0, Vec::new());
    for name in &names {
        let path = dir.join(name).display().to_string();
        let Ok((loops, _)) = load_outline(&path, &Default::default()) else {
            continue;
        };
        let all = loops.pockets();
        let side = all
            .iter()
            .map(|p| {
                let b = p.outer.bounds();
                (b.max.x - b.min.x).min(b.max.y - b.min.y)
            })
            .fold(0.0, f64::max);
        let d = if side > 2000.0 {
            side / 10.0
        } else {
            (side / 10.0).clamp(0.5, 10.0)
        };
        let tool = Tool::flat(d).unwrap();
        let opts = PocketOptions::default()
            .with_depth(d.min(3.0))
            .with_step_down(d.min(3.0))
            .with_entry(Entry::Helix {
                radius: DEFAULT_HELIX_RADIUS_PER_DIAMETER * d,
                ramp_angle: 3f64.to_radians(),
            });
        for (i, p) in all.into_iter().enumerate() {
            let Ok(shape) = PocketShape::new(p.outer, p.islands, name) else {
                continue;
            };
            // A pocket the tool does not fit is refused: nothing to check.
            let Ok(tp) = pocket::toolpath(StrategyKind::Spiral, &shape, &tool, &opts) else {
                continue;
            };
            pockets += 1;
            let (hooks, _) = find_hooks(&tp, d, on_walls(&shape, 0.5 * d));
            if let Some(h) = hooks.first() {
                failures.push(format!(
                    "{name} pocket {}: {} hooks, first {h}",
                    i + 1,
                    hooks.len()
                ));
            }
        }
    }
    assert!(pockets >= 80, "{pockets} pockets checked");
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
