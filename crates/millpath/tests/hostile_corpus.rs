//! The bounded fuzz pass of CI: replays the committed, minimised fuzz corpus
//! (`fuzz/corpus-min/TARGET/*`) through the fuzz targets' own bodies (`fuzz/harness/mod.rs`,
//! included here), on stable Rust and without libFuzzer. Every file that ever made a target
//! crash is kept in the corpus, so a regression fails `cargo test`.
//!
//! The corpora were produced by coverage-guided runs (`cargo fuzz run -O TARGET`, see
//! `fuzz/README.md`) and reduced with `cargo fuzz cmin`; each holds a few hundred small files
//! that together reach the coverage the long runs reached.

#[path = "../../../fuzz/harness/mod.rs"]
mod harness;
mod hostile_common;

use cavalier_contours::polyline::PlineSource;
use hostile_common::{Harness, corpus};
use millpath::strategy::pocket;
use std::path::PathBuf;

fn replay(target: &'static str, min_files: usize, f: fn(&[u8])) {
    let files = corpus(target);
    let mut h = Harness::new(target);
    for (name, data) in &files {
        h.run(&(name, String::from_utf8_lossy(data)), || f(data));
    }
    h.finish(min_files);
}

/// Strict: what reads is written back and read again to the same moves.
#[test]
fn corpus_gcode_reader() {
    harness::STRICT_VERIFY.store(true, std::sync::atomic::Ordering::Relaxed);
    replay("gcode_reader", 100, harness::gcode_reader);
    let n = harness::ROUND_TRIPS.load(std::sync::atomic::Ordering::Relaxed);
    assert!(
        n >= MIN_ROUND_TRIPS,
        "only {n} corpus programs written and read back"
    );
}

/// Fewest corpus programs the `gcode_reader` replay must write and read back (7 of its files
/// read as programs with moves and are written on 2026-11-25; the rest are refused or empty).
const MIN_ROUND_TRIPS: usize = 5;

#[test]
fn corpus_outline_importers() {
    replay("outline_importers", 100, harness::outline_importers);
}

#[test]
fn corpus_points() {
    replay("points", 50, harness::points);
}

/// Strict: no accepted pocket may gouge (the geometric clearance check of the verification)
/// or leave material the tool could have reached (the stock simulation's coverage;
/// `generate` refuses such a path as an internal error, which fails here too). This is the
/// test-command form of [`uncut_over_the_corpus`]: every corpus pocket, walls as drawn.
#[test]
fn corpus_pocket() {
    harness::STRICT_VERIFY.store(true, std::sync::atomic::Ordering::Relaxed);
    replay("pocket", 50, harness::pocket);
}

/// Strict: every contour's finishing pass lies within the tolerance band of the exact curve
/// (dense distances to the curve, not the pass's own measure); no known exceptions since
/// 2026-11-26 ([`contours_stay_in_the_band_on_fuzz_outlines`]).
#[test]
fn corpus_contour() {
    harness::STRICT_VERIFY.store(true, std::sync::atomic::Ordering::Relaxed);
    replay("contour", 50, harness::contour);
}

/// Strict: every plan of the corpus must also pass the independent verifier (0 limit
/// violations), not only finish without a panic.
#[test]
fn corpus_planner() {
    harness::STRICT_VERIFY.store(true, std::sync::atomic::Ordering::Relaxed);
    replay("planner", 50, harness::planner);
}

/// Plans the `planner` fuzzer found violating their machine's limits (velocity, acceleration
/// and jerk over the limit, position inconsistency, corner deviation), replayed with the
/// verifier check on (`FUZZ_STRICT_VERIFY`). See fuzz/README.md, "Findings".
#[test]
fn planner_limit_violations_found_by_the_fuzzer() {
    harness::STRICT_VERIFY.store(true, std::sync::atomic::Ordering::Relaxed);
    let dir =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../fuzz/regressions/planner-limits");
    let mut h = Harness::new("planner limits");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("regressions dir")
        .map(|e| e.expect("entry").path())
        .collect();
    files.sort();
    for f in &files {
        let data = std::fs::read(f).expect("file");
        h.run(&f.display(), || harness::planner(&data));
    }
    h.finish(1);
}

/// The hand-written seeds of the `outline_importers` corpus (`seed-*.dxf`, `.svg`, `.json`,
/// `.toml`: every entity kind, path command and key the importers read, each under the fuzz
/// runs' 4,096-byte limit) are valid documents: without valid starting points libFuzzer never
/// reached the DXF importer's entity code or the machine checks (2026-11-22, fuzz/README.md).
#[test]
fn importer_seeds_are_accepted() {
    use millpath::{io, machine::Machine};
    let seeds: Vec<_> = corpus("outline_importers")
        .into_iter()
        .filter(|(n, _)| n.starts_with("seed-"))
        .collect();
    assert!(seeds.len() >= 11, "{} seeds", seeds.len());
    for (name, data) in &seeds {
        assert!(data.len() <= 4096, "{name}: {} bytes", data.len());
        let text = std::str::from_utf8(data).expect("seeds are text");
        let ok = match name.rsplit('.').next() {
            Some("dxf") => io::dxf::parse(data, name, &Default::default()).map(|_| ()),
            Some("svg") => io::svg::parse(text, name, 0.01).map(|_| ()),
            Some("json") => io::outline_json::parse(text, name).map(|_| ()),
            Some("toml") => Machine::from_toml_str(text, name).map(|_| ()),
            _ => panic!("{name}: unknown seed kind"),
        };
        if let Err(e) = ok {
            panic!("seed {name} refused: {e}");
        }
    }
}

/// Found by the corpus replay after main's pocket walls landed: a zigzag pocket with a depth
/// of 1e300 mm and a step-down of 333 mm (tool diameter 1e300 mm) makes
/// `strategy::pocket::levels::level_depths` (called from `walls::level_shapes`) allocate
/// ~3e297 levels: "capacity overflow". Fixed: `PocketOptions::validate` bounds the depth
/// (1e6 mm) and the level count (10 000), as `ContourOptions::validate` does. The second
/// file (`crash-2c2cc0ef…`, the strict run of 2026-11-25) made cavalier_contours' shape
/// offset panic ("expect non-empty polyline") with the finer epsilons `PocketShape::offset`
/// tries: such a candidate now counts as none. Three more (pk39, 2026-11-26,
/// `crash-{b4767a26,c53e840c,d7d51d15}…`) made cavalier_contours' boolean panic in a
/// `--morph fronts` front (`index out of bounds` while stitching its slices): the fronts'
/// planning catches it, and the fronts fail as for any failed front.
#[test]
fn pocket_crashes_found_by_the_fuzzer() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../fuzz/regressions/pocket-crash");
    let mut h = Harness::new("pocket crash");
    for e in std::fs::read_dir(&dir).expect("regressions dir") {
        let f = e.expect("entry").path();
        let data = std::fs::read(&f).expect("file");
        h.run(&f.display(), || harness::pocket(&data));
    }
    h.finish(1);
}

/// Pockets on which the spiral gouged (found on 2026-11-22 when the `pocket` target began to
/// run `pocket::generate` with its verification: 10 of 663 corpus inputs gouged, 0.002 µm to
/// 2.9 mm). Four of them gouged 0.015–2.9 mm into the wall clearance with either morph: a
/// lap blending into the boundary offset cut across its concave arcs; `spiral::keep_inside`
/// now moves such samples onto the last loop. Two more, found by the next runs (`ef412b15…`,
/// `efe94e0e…`), gouged 0.011–0.018 mm where `--arcs` biarcs overshot the samples at a kink or
/// a sharp corner: `generate` retries such a path as chords. The seventh (`698ed17d…`, found by
/// the run pk20 and refused by `generate` until 5a67d3f) gouged 0.023 mm with
/// chords: projecting the samples of a lap that cut across a dent onto the arc round it spread
/// them 0.69 mm apart, and those chords cut across the arc; `spiral::inside` now splits every
/// chord that leaves the last loop. The eighth (`b43b53a3…`, pk23, 62,000 executions
/// into a strict run) ran a 22 mm chord straight through a thin spike of the wall, 10.7 mm
/// deep: the lap's samples inside the spike were moved onto its two sides, and midpoint splits
/// of a chord from one side to the other only creep towards the tip; such a chord is now
/// walked along the last loop, round the tip. What is left is the arc fit's micrometres.
#[test]
fn spiral_laps_stay_out_of_the_walls_on_fuzz_outlines() {
    for (name, r) in gouge_cases() {
        match r {
            Ok(v) => assert!(
                v.min_clearance_mm >= v.required_clearance_mm - 0.002,
                "{name}: gouges {:.4} mm: {v:?}",
                v.required_clearance_mm - v.min_clearance_mm
            ),
            // `b810bd9b…` (a 1.7° corner) is refused since the fronts check the first
            // front's ridge slot: it is no slot, and the harmonic morph does not converge.
            // A clear refusal, never a gouge or an internal error.
            Err(millpath::Error::Input(e)) if name.contains("b810bd9b") => {
                assert!(e.to_string().contains("--strategy offset"), "{name}: {e}");
            }
            Err(e) => panic!("{name}: {e}"),
        }
    }
}

/// `--arcs` spirals keep their arcs and stay out of the walls' clearance: each biarc is
/// checked against the spiral's guard loop like a chord, and one that crosses it is written as
/// the chords it spans. Before, biarcs were not checked: `ef412b15…` cut 0.017 mm into the
/// clearance (so `generate` planned it again as chords, all of it, and said so in a note), and
/// on `5f57c1cb…` and `fb1e90b2…` of the corpus they came 7.7 and 6.8 µm inside it (under
/// `GOUGE_TOLERANCE`, so written as they were). The fallback machinery itself is tested in
/// `strategy::pocket::fallback`.
#[test]
fn arcs_stay_out_of_the_walls_without_a_fallback() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../fuzz");
    for f in [
        "regressions/pocket-gouge/ef412b15773f575d85fdb0b286fc292aa5dca6e2",
        "corpus-min/pocket/5f57c1cbe3a2279ad2af9ff76d7c887119eefad3",
        "corpus-min/pocket/fb1e90b28d693df640c8a89fb42add74817e663e",
    ] {
        let data = std::fs::read(root.join(f)).expect("file");
        let (kind, shape, tool, mut opts, sim) =
            harness::pocket_case_vertical(&data).expect("a pocket");
        assert_eq!(kind, pocket::StrategyKind::Spiral, "{f}");
        opts.spiral.arcs = true;
        let r = pocket::generate(kind, &shape, &tool, &opts, &sim).expect("a toolpath");
        assert!(r.notes.is_empty(), "{f}: {:?}", r.notes);
        let arcs = r
            .toolpath
            .moves
            .iter()
            .filter(|m| matches!(m.kind, millpath::toolpath::MoveKind::Arc { .. }))
            .count();
        assert!(arcs > 10, "{f}: {arcs} arcs");
        let v = r.verification;
        assert!(
            v.min_clearance_mm >= v.required_clearance_mm - 1e-4,
            "{f}: {:.6} mm inside the clearance",
            v.required_clearance_mm - v.min_clearance_mm
        );
    }
}

/// Found by the `pocket` run pk19 on 2026-11-22 (fuzz/README.md): on a 4 × 6.5 mm pocket with
/// a 1.08 mm tool, the finishing pass's lead-in, a straight feed move from the nearest point
/// of the roughed region to the finishing loop, cut 0.09 mm into a wall spike between them,
/// whatever the morph or arcs (`generate` refused it). The lead-in now starts from the
/// nearest point whose move stays inside the tool-centre region.
#[test]
fn finishing_lead_in_stays_out_of_the_walls() {
    let f = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(
        "../../fuzz/regressions/pocket-finish-entry/finish-entry-4d52e850db73be008726bf53f0d538c8a6211e67",
    );
    let data = std::fs::read(&f).expect("file");
    let (kind, shape, tool, opts, sim) = harness::pocket_case_vertical(&data).expect("a pocket");
    let v = pocket::generate(kind, &shape, &tool, &opts, &sim)
        .expect("a toolpath")
        .verification;
    assert!(
        v.min_clearance_mm >= v.required_clearance_mm - 1e-6,
        "gouges {:.4} mm",
        v.required_clearance_mm - v.min_clearance_mm
    );
}

/// Found by the `pocket` run pk21 on 2026-11-22, 1,300 executions into it: the zigzag linked
/// two pieces of a pinched tool-centre region with a straight move that ran along one piece's
/// edge, across the 1.2 mm neck between them and along the other's edge, 0.017 mm into the
/// wall stock (`generate` refused it). `offset::crosses` tested only crossings away from the
/// ends and the link's midpoint, which lay on the first edge; it now tests every piece
/// between the loops' crossings and overlaps. The small piece is then a cut of its own, too
/// short to ramp into and with no cleared point it can be reached from: refused as bad input
/// (exit 2), as any such sliver is.
#[test]
fn zigzag_links_stay_inside_a_pinched_region() {
    let f = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../fuzz/regressions/pocket-link/668b7c4357e1e0b5fb27fe08deacc4eb4e48339f");
    let data = std::fs::read(&f).expect("file");
    let (kind, shape, tool, opts, sim) = harness::pocket_case_vertical(&data).expect("a pocket");
    assert_eq!(kind, pocket::StrategyKind::Zigzag);
    match pocket::generate(kind, &shape, &tool, &opts, &sim) {
        Ok(r) => {
            let v = r.verification;
            assert!(
                v.min_clearance_mm >= v.required_clearance_mm - 1e-6,
                "gouges {:.4} mm",
                v.required_clearance_mm - v.min_clearance_mm
            );
        }
        Err(millpath::Error::Input(e)) => {
            assert!(e.to_string().contains("ramp into"), "{e}");
        }
        Err(e) => panic!("{e}"),
    }
}

/// Found by the strict `pocket` run of 2026-11-25 (fuzz/README.md), 400 s into it: a 0.33 mm
/// tool with 0.48 mm of wall stock and a finishing pass. The finishing pass was one loop at
/// `r`: its disc reaches `r` out from it and the roughing's last loop's `r` in from
/// `r + stock`, so a ridge `stock − 2r` wide stood between them, 4.05 mm² (`generate`
/// refused it). The finishing pass now steps through the stock in loops a step apart.
#[test]
fn finishing_clears_stock_wider_than_the_tool() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../fuzz/regressions/pocket-uncut");
    let mut n = 0;
    for e in std::fs::read_dir(&dir).expect("regressions dir") {
        let f = e.expect("entry").path();
        let data = std::fs::read(&f).expect("file");
        let (kind, shape, tool, opts, sim) = harness::pocket_case(&data).expect("a pocket");
        assert!(
            opts.finish && opts.wall_stock > tool.diameter,
            "{}",
            f.display()
        );
        let v = pocket::generate(kind, &shape, &tool, &opts, &sim)
            .unwrap_or_else(|e| panic!("{}: {e}", f.display()))
            .verification;
        assert!(
            v.uncut_area_mm2 <= millpath::stock::UNCUT_AREA_TOLERANCE,
            "{}: {}",
            f.display(),
            v.uncut_text()
        );
        assert!(v.min_clearance_mm >= v.required_clearance_mm - 1e-6);
        n += 1;
    }
    assert!(n >= 1);
}

fn gouge_cases() -> Vec<(String, millpath::Result<millpath::stock::Verification>)> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../fuzz/regressions/pocket-gouge");
    let mut names: Vec<_> = std::fs::read_dir(&dir)
        .expect("regressions dir")
        .map(|e| e.expect("entry").path())
        .collect();
    names.sort();
    assert_eq!(names.len(), 8, "{names:?}");
    names
        .iter()
        .map(|f| {
            let data = std::fs::read(f).expect("file");
            let (kind, shape, tool, opts, sim) =
                harness::pocket_case_vertical(&data).expect("a pocket");
            let r = pocket::generate(kind, &shape, &tool, &opts, &sim).map(|r| r.verification);
            (f.display().to_string(), r)
        })
        .collect()
}

/// Measures how close `--arcs` spirals come to the walls over the whole pocket corpus: every
/// input that decodes to a spiral, planned with `--arcs` (`cargo test -p millpath --test
/// hostile_corpus -- --ignored arcs_clearance_over_the_corpus --nocapture`, about 2 minutes;
/// on stderr).
/// Prints how many needed a fallback and the deepest excursions into the clearance, mm.
#[test]
#[ignore = "tool: prints the --arcs spirals' clearance over the pocket corpus"]
#[allow(clippy::print_stderr)]
fn arcs_clearance_over_the_corpus() {
    let mut rows = Vec::new();
    let mut fallbacks = 0;
    for (name, data) in corpus("pocket") {
        let Some((kind, shape, tool, mut opts, sim)) = harness::pocket_case_vertical(&data) else {
            continue;
        };
        if kind != pocket::StrategyKind::Spiral {
            continue;
        }
        opts.spiral.arcs = true;
        if let Ok(r) = pocket::generate(kind, &shape, &tool, &opts, &sim) {
            fallbacks += usize::from(!r.notes.is_empty());
            let v = r.verification;
            rows.push((v.required_clearance_mm - v.min_clearance_mm, name));
        }
    }
    rows.sort_by(|a, b| b.0.total_cmp(&a.0));
    eprintln!(
        "{} spirals with --arcs, {fallbacks} with a fallback; deepest inside the clearance:",
        rows.len()
    );
    for (depth, name) in rows.iter().take(8) {
        eprintln!("{depth:.6} mm  {name}");
    }
}

/// Measures coverage over the whole pocket corpus: every input that decodes to a pocket
/// (walls as drawn), planned by `generate`, and how many leave uncut material beyond the
/// verifier's tolerance, by strategy (`generate` refuses those, naming the area and where:
/// they are counted from that refusal). `cargo test --release -p millpath --test
/// hostile_corpus -- --ignored uncut_over_the_corpus --nocapture`; on stderr, with the worst
/// inputs. The test command checks the same inputs in [`corpus_pocket`] (strict: a refusal
/// for uncut material is an internal error there).
#[test]
#[ignore = "tool: prints the uncut material over the pocket corpus"]
#[allow(clippy::print_stderr)]
fn uncut_over_the_corpus() {
    let mut rows = Vec::new();
    let mut planned = [0usize; 4];
    for (name, data) in corpus("pocket") {
        let Some((kind, shape, tool, opts, sim)) = harness::pocket_case(&data) else {
            continue;
        };
        let k = strategy_index(kind);
        match pocket::generate(kind, &shape, &tool, &opts, &sim) {
            Ok(r) => {
                planned[k] += 1;
                let v = r.verification;
                if v.uncut_area_mm2 > millpath::stock::UNCUT_AREA_TOLERANCE {
                    rows.push((v.uncut_area_mm2, kind, name, v.uncut_text()));
                }
            }
            Err(millpath::Error::Internal(e)) if e.to_string().contains("leaves material") => {
                planned[k] += 1;
                let text = e.to_string();
                let area = text
                    .split("reach: ")
                    .nth(1)
                    .and_then(|t| t.split(' ').next())
                    .and_then(|a| a.parse::<f64>().ok())
                    .unwrap_or(f64::NAN);
                let morph = format!("{:?} walls {:?}", opts.spiral.morph, !shape.is_prismatic());
                rows.push((area, kind, name, format!("{morph}: {text}")));
            }
            Err(_) => {}
        }
    }
    rows.sort_by(|a, b| b.0.total_cmp(&a.0));
    for kind in [
        pocket::StrategyKind::Zigzag,
        pocket::StrategyKind::Offset,
        pocket::StrategyKind::Spiral,
    ] {
        let n = rows.iter().filter(|r| r.1 == kind).count();
        eprintln!(
            "{kind:?}: {} planned, {n} with uncut material",
            planned[strategy_index(kind)]
        );
    }
    let shown = hostile_common::env_or("UNCUT_SHOW", 12usize);
    for (area, kind, name, what) in rows.iter().take(shown) {
        eprintln!("{area:.3} mm²  {kind:?}  {name}  {what}");
    }
}

/// Where `kind` counts in [`uncut_over_the_corpus`]'s table.
fn strategy_index(kind: pocket::StrategyKind) -> usize {
    match kind {
        pocket::StrategyKind::Zigzag => 0,
        pocket::StrategyKind::Offset => 1,
        pocket::StrategyKind::Spiral => 2,
        pocket::StrategyKind::Adaptive => 3,
    }
}

/// Replays one file: `FUZZ_TARGET=pocket FUZZ_FILE=path FUZZ_TRACE=1 cargo test -p millpath
/// --test hostile_corpus -- --ignored replay_one --nocapture` (prints the decoded input).
#[test]
#[ignore = "tool: replays FUZZ_FILE through FUZZ_TARGET"]
fn replay_one() {
    let target = std::env::var("FUZZ_TARGET").expect("FUZZ_TARGET");
    let data = std::fs::read(std::env::var("FUZZ_FILE").expect("FUZZ_FILE")).expect("file");
    let f: fn(&[u8]) = match target.as_str() {
        "gcode_reader" => harness::gcode_reader,
        "outline_importers" => harness::outline_importers,
        "points" => harness::points,
        "pocket" => harness::pocket,
        "adaptive" => harness::adaptive,
        "contour" => harness::contour,
        _ => harness::planner,
    };
    let t = std::time::Instant::now();
    f(&data);
    let _ = t.elapsed();
}

/// Prints what a pocket input plans to, level by level (`FUZZ_FILE=path cargo test --release
/// -p millpath --test hostile_corpus -- --ignored inspect_pocket --nocapture`).
#[test]
#[ignore = "tool: prints the levels of FUZZ_FILE's pocket"]
#[allow(clippy::print_stderr)]
fn inspect_pocket() {
    let data = std::fs::read(std::env::var("FUZZ_FILE").expect("FUZZ_FILE")).expect("file");
    let (kind, shape, tool, opts, mut sim) = harness::pocket_case(&data).expect("a pocket");
    if std::env::var_os("FINE_SIM").is_some() {
        sim = millpath::stock::SimOptions::default();
    }
    eprintln!("{sim:?}");
    eprintln!(
        "{kind:?} morph {:?} tool {} stepover {:.3} depth {} step-down {} stock {} finish {} islands {} prismatic {}",
        opts.spiral.morph,
        tool.diameter,
        opts.stepover_mm(&tool),
        opts.depth,
        opts.step_down,
        opts.wall_stock,
        opts.finish,
        shape.islands.len(),
        shape.is_prismatic()
    );
    if std::env::var_os("OFFSET_SCAN").is_some() {
        let outer: Vec<(millpath::Point, f64)> = shape.outer.vertices().collect();
        let mut pl = cavalier_contours::polyline::Polyline::new_closed();
        for (p, b) in &outer {
            cavalier_contours::polyline::PlineSourceMut::add(&mut pl, p.x, p.y, *b);
        }
        let mut d = 0.5;
        while d < 40.0 {
            let reg = shape.offset_loops(d);
            let outers: Vec<_> = reg.iter().filter(|l| l.signed_area() > 0.0).collect();
            let a: f64 = outers.iter().map(|l| l.signed_area()).sum();
            let sh = cavalier_contours::shape_algorithms::Shape::from_plines(std::iter::once(
                pl.clone(),
            ));
            let off = sh.parallel_offset(d, &Default::default());
            let a2: f64 = off.ccw_plines.iter().map(|p| p.polyline.area()).sum();
            eprintln!(
                "offset {d:.2}: {} outers, area {a:.1}; shape {} area {a2:.1}",
                outers.len(),
                off.ccw_plines.len()
            );
            d += 0.5;
        }
        eprintln!(
            "outline area {:.1} vertices {outer:?}",
            shape.outer.signed_area()
        );
    }
    let tp = pocket::toolpath(kind, &shape, &tool, &opts).expect("a toolpath");
    if let Ok(out) = std::env::var("SVG_OUT") {
        let mut outlines = vec![shape.outer.clone()];
        outlines.extend(shape.islands.iter().cloned());
        let mut first = tp.clone();
        let li = hostile_common::env_or("LEVEL", 0usize);
        if let Some(lv) = tp.levels.get(li) {
            first.moves = tp.moves[lv.start..lv.end].to_vec();
            first.start = if lv.start > 0 {
                tp.moves[lv.start - 1].to
            } else {
                tp.start
            };
            first.levels.clear();
        }
        let svg = millpath::report::toolpath_svg(&first, &outlines, &Default::default());
        std::fs::write(out, svg).expect("svg");
    }
    if let Ok(range) = std::env::var("MOVES") {
        let (a, b) = range.split_once("..").expect("a..b");
        let (a, b): (usize, usize) = (a.parse().expect("a"), b.parse().expect("b"));
        for (i, m) in tp.moves.iter().enumerate().take(b).skip(a) {
            eprintln!("{i}: {:?}", m);
        }
        eprintln!("outer {:?}", shape.outer.vertices().collect::<Vec<_>>());
    }
    for lv in &tp.levels {
        let sub = millpath::Toolpath {
            moves: tp.moves[lv.start..lv.end].to_vec(),
            ..tp.clone()
        };
        eprintln!(
            "level z {:.3} {:?}: moves {}..{} cut {:.1} mm",
            lv.z,
            lv.kind,
            lv.start,
            lv.end,
            sub.cut_length()
        );
    }
    match pocket::generate(kind, &shape, &tool, &opts, &sim) {
        Ok(r) => eprintln!("{:?}", r.verification),
        Err(e) => eprintln!("{e}"),
    }
}

/// The strict pocket run of 2026-11-25 timed out (54 s in a test build) on a `--morph fronts`
/// spiral whose fronts failed, after a checked shape offset for each of the four smoothing
/// offsets of every front, and fell back to the harmonic morph. The smoothing takes the
/// single-loop offset when its area is plausible: the fronts succeed, in milliseconds.
#[test]
fn the_slow_fronts_input_is_cut_with_the_fronts() {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(
        "../../fuzz/regressions/pocket-slow/timeout-3c9f2d235e3936d3f9d3f978735ab9c0e3ae6c3f",
    );
    let data = std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let (kind, shape, tool, opts, sim) = harness::pocket_case(&data).expect("a pocket");
    assert_eq!(opts.spiral.morph, pocket::SpiralMorph::Fronts);
    let (_, stats) = pocket::spiral_with_stats(&shape, &tool, &opts).expect("a spiral");
    assert_eq!(stats.construction, pocket::Construction::Fronts);
    let r = pocket::generate(kind, &shape, &tool, &opts, &sim).unwrap_or_else(|e| panic!("{e}"));
    let problems = r.verification.problems();
    assert!(problems.is_empty(), "{problems:?}");
}

/// Decodes a pocket regression input of `fuzz/regressions/`, plans it with `generate` and
/// returns the verifier's problems (none expected) with the spiral's construction when it is
/// a spiral.
fn regression_pocket(rel: &str) -> (Vec<String>, Option<pocket::Construction>) {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../fuzz/regressions")
        .join(rel);
    let data = std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let (kind, shape, tool, opts, sim) = harness::pocket_case(&data).expect("a pocket");
    let construction = (kind == pocket::StrategyKind::Spiral).then(|| {
        pocket::spiral_with_stats(&shape, &tool, &opts)
            .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
            .1
            .construction
    });
    let r = pocket::generate(kind, &shape, &tool, &opts, &sim)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let problems = r
        .verification
        .problems()
        .iter()
        .map(|p| p.to_string())
        .collect();
    (problems, construction)
}

/// The strict pocket run of 2026-11-26 (fuzz/README.md, pk38): a zigzag whose passes are
/// exactly one tool diameter apart, verified on a raster of 0.19 mm cells with the tool
/// sampled 0.375 mm apart. The simulation stamped a disc at each sample, and the scallops
/// between the discs of two tangent passes left 0.21 mm² "uncut" that no tool leaves, so
/// `generate` refused a correct program. It now sweeps the capsule between samples.
#[test]
fn passes_one_diameter_apart_leave_nothing() {
    let (problems, _) =
        regression_pocket("pocket-tangent/crash-181787d61090147b776c0ade61895ac2d628c9b0");
    assert!(problems.is_empty(), "{problems:?}");
}

/// Two `--morph fronts` inputs of the pk38 run: one ran out of memory (24 GB) in
/// cavalier_contours' shape offset of a 301-vertex sliver of 5·10⁻⁹ mm² by 0.4 mm, the other
/// took 20 s because a checked outward offset returned a sliver of 7·10⁻⁷ mm² for a loop
/// of 510 mm² (the loop went out to a point 2·10⁻⁵ mm away and came back: a spike of no
/// width) and the next smoothing offset started from it. An inward offset by `d` of a loop
/// smaller than `π·d²` is now empty without offsetting; the smoothing offsets drop repeated
/// vertices and spikes first (cavalier_contours' `remove_redundant`), and refuse a checked
/// offset that grew inward or shrank outward. Both are cut and verified, the second with the
/// fronts (without the spike's removal its fronts fail, and the harmonic morph does not
/// converge on its 1° corner).
#[test]
fn fronts_neither_offset_slivers_nor_take_implausible_offsets() {
    let (problems, construction) =
        regression_pocket("pocket-slow/timeout-4396f9382c1547d45778fa9e1d4a9578fef7bed4");
    assert!(problems.is_empty(), "{problems:?}");
    assert!(construction.is_some(), "a spiral");
    let (problems, construction) =
        regression_pocket("pocket-slow/slow-unit-e5c93547ef69f7975a35d1c995690f3917231ea1");
    assert!(problems.is_empty(), "{problems:?}");
    assert_eq!(construction, Some(pocket::Construction::Fronts));
}

/// The strict pocket run of 2026-11-26 (fuzz/README.md, pk40) ran out of memory on a
/// `--morph fronts` spiral: a front, a union of offsets, carried hairs a tenth of a
/// micrometre wide running back and forth along a line, which the spike removal did not see
/// (a removed spike left its neighbours on one point, hiding the next). cavalier_contours'
/// single-loop offset returned open pieces for it, and the checked shape offset the smoothing
/// fell back to took 7.9 GB on a 24-vertex loop. The smoothing now removes repeated vertices
/// with the spikes, hairs up to 1e-4 mm wide, and has no shape-offset fallback: the fronts
/// fail in milliseconds (a later front's single-loop offset is still implausible), and the
/// pocket is cut with the harmonic morph and verified.
#[test]
fn hairy_fronts_are_smoothed_without_the_shape_offset() {
    let (problems, construction) =
        regression_pocket("pocket-slow/oom-ca63de143e55be7646178f185c9e4a0e9a15bd24");
    assert!(problems.is_empty(), "{problems:?}");
    assert_eq!(construction, Some(pocket::Construction::Harmonic));
}
