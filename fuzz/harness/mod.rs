//! The bodies of the fuzz targets, shared by the cargo-fuzz binaries (`fuzz/fuzz_targets/*`)
//! and by the corpus replay test (`crates/millpath/tests/hostile_corpus.rs`), which includes
//! this file with `#[path]`: CI replays the committed corpus (`fuzz/corpus-min/TARGET/*`)
//! through exactly the code libFuzzer runs, on stable Rust and without libFuzzer.
//!
//! Each function takes arbitrary bytes and must return without panicking; where the call
//! succeeds, it also checks cheap invariants of the result (finite coordinates, finite
//! times, the planner's limits as measured by the independent verifier) and panics when one
//! fails, so libFuzzer reports broken results as well as crashes.
//!
//! Structured inputs are decoded by [`Bytes`]: each number is two bytes mapped into a sane
//! range, or (when a selector byte says so) a hostile value (NaN, ±∞, 0, negative, 1e300,
//! 1e-300). Ranges are chosen so that the work per input stays bounded (at most ~20 passes
//! per pocket level, a few levels, short programs).

#![allow(dead_code)]

use millpath::curve::{self, CurveKind, LabeledPoint};
use millpath::gcode::{Dialect, Reader, ReaderOptions, read_str};
use millpath::geom::Outline;
use millpath::io::{dxf, outline_json, points, svg};
use millpath::machine::{AxisLimits, Machine};
use millpath::motion::{PlanOptions, plan_moves};
use millpath::motion::{VerifyOptions, verify_plan};
use millpath::stock::SimOptions;
use millpath::strategy::contour::{self, ContourOptions, Side};
use millpath::strategy::pocket::{
    self, Direction, Entry, PocketOptions, PocketShape, Stepover, StrategyKind, Walls,
};
use millpath::toolpath::{Corner, MoveKind, Plane};
use millpath::{Move, Point, Point3, Tool, Toolpath};

/// A cursor over fuzz bytes that never fails: past the end it yields zeros.
pub struct Bytes<'a> {
    data: &'a [u8],
    at: usize,
}

impl<'a> Bytes<'a> {
    /// Decodes from `data`.
    pub fn new(data: &'a [u8]) -> Self {
        Bytes { data, at: 0 }
    }

    /// The next byte (0 past the end).
    pub fn byte(&mut self) -> u8 {
        let b = self.data.get(self.at).copied().unwrap_or(0);
        self.at += 1;
        b
    }

    /// The bytes not decoded yet.
    pub fn rest(&self) -> &'a [u8] {
        self.data.get(self.at..).unwrap_or(&[])
    }

    /// True when every byte has been decoded.
    pub fn done(&self) -> bool {
        self.at >= self.data.len()
    }

    /// A boolean.
    pub fn flag(&mut self) -> bool {
        self.byte() & 1 == 1
    }

    /// An index below `n` (`n` ≥ 1).
    pub fn pick(&mut self, n: usize) -> usize {
        usize::from(self.byte()) % n.max(1)
    }

    /// A number in `[lo, hi]` from two bytes.
    pub fn unit(&mut self, lo: f64, hi: f64) -> f64 {
        let v = u16::from_le_bytes([self.byte(), self.byte()]);
        lo + (hi - lo) * f64::from(v) / f64::from(u16::MAX)
    }

    /// A number in `[lo, hi]`, or a hostile value when the selector byte is 250 or more.
    pub fn num(&mut self, lo: f64, hi: f64) -> f64 {
        let sel = self.byte();
        if sel >= 250 {
            hostile(sel - 250)
        } else {
            self.unit(lo, hi)
        }
    }
}

/// The hostile values: NaN, +∞, −∞, 0, −1, 1e300 (index mod 6; 1e-300 for the rest).
pub fn hostile(i: u8) -> f64 {
    match i % 7 {
        0 => f64::NAN,
        1 => f64::INFINITY,
        2 => f64::NEG_INFINITY,
        3 => 0.0,
        4 => -1.0,
        5 => 1e300,
        _ => 1e-300,
    }
}

/// A polygon of 3..=14 vertices within `size` of `(cx, cy)`: a star (sorted angles) or, when
/// `chaos`, points in byte order (self-intersecting, repeated, collinear...).
pub fn polygon(b: &mut Bytes<'_>, size: f64) -> Vec<Point> {
    let n = 3 + b.pick(12);
    let chaos = b.byte() < 64;
    let (cx, cy) = (b.unit(-50.0, 50.0), b.unit(-50.0, 50.0));
    let mut pts: Vec<(f64, f64)> = (0..n)
        .map(|_| {
            if chaos {
                (b.num(-size, size), b.num(-size, size))
            } else {
                (b.unit(0.0, std::f64::consts::TAU), b.unit(0.3, 1.0) * size)
            }
        })
        .collect();
    if chaos {
        return pts
            .into_iter()
            .map(|(x, y)| Point::new(cx + x, cy + y))
            .collect();
    }
    pts.sort_by(|p, q| p.0.total_cmp(&q.0));
    pts.into_iter()
        .map(|(a, r)| Point::new(cx + r * a.cos(), cy + r * a.sin()))
        .collect()
}

/// Panics unless every move of `tp` ends at a finite point with a finite feed.
pub fn assert_finite(tp: &Toolpath, what: &str) {
    for (i, m) in tp.moves.iter().enumerate() {
        assert!(
            m.to.is_finite(),
            "{what}: move {i} ends at a non-finite point {:?}",
            m.to
        );
        assert!(
            m.feed.is_finite(),
            "{what}: move {i} has a non-finite feed {}",
            m.feed
        );
    }
}

/// With `FUZZ_TRACE` set, prints the decoded input (to reproduce a slow or failing input).
#[allow(clippy::print_stderr)]
pub fn trace(input: &dyn std::fmt::Debug) {
    if std::env::var_os("FUZZ_TRACE").is_some() {
        eprintln!("{input:#?}");
    }
}

/// `gcode_reader`: arbitrary bytes to the streaming reader (first byte picks dialect,
/// lenient, block delete) and to `read_str`.
pub fn gcode_reader(data: &[u8]) {
    let Some((&flags, body)) = data.split_first() else {
        return;
    };
    let opts = ReaderOptions::default()
        .with_dialect(match flags % 4 {
            0 => Dialect::LinuxCnc,
            1 => Dialect::Fanuc,
            2 => Dialect::Sinumerik,
            _ => Dialect::Grbl,
        })
        .with_lenient(flags & 4 != 0)
        .with_block_delete(flags & 8 != 0);
    let mut rd = Reader::new(std::io::Cursor::new(body), opts.clone());
    for rm in rd.by_ref().take(100_000).flatten() {
        assert!(!rm.mv.to.x.is_nan(), "reader produced a NaN target");
    }
    if let Ok(text) = std::str::from_utf8(body)
        && let Ok((tp, _)) = read_str(text, opts)
        && strict_verify()
    {
        round_trip(&tp, text);
    }
}

/// Writes what the reader read (LinuxCNC, 10 decimals) and reads it back: the same moves,
/// ends within 1e-9 of their magnitude (a rapid to the start first when the program's first
/// motion is an arc, as the writer writes it). A program the writer refuses (an input error:
/// an arc below its smallest radius, a coordinate it cannot write) is not checked.
pub fn round_trip(tp: &Toolpath, text: &str) {
    use millpath::gcode::{WriterOptions, write_to_string};
    if tp.moves.is_empty() {
        return;
    }
    let wopts = WriterOptions::default()
        .with_dialect(Dialect::LinuxCnc)
        .with_decimals(Some(10));
    let written = match write_to_string(tp, &wopts) {
        Ok((w, _)) => w,
        Err(millpath::Error::Input(_)) => return,
        Err(e) => panic!("the writer failed: {e}\n{text}"),
    };
    let ropts = ReaderOptions::default()
        .with_dialect(Dialect::LinuxCnc)
        .with_start(tp.start);
    let (back, _) = read_str(&written, ropts)
        .unwrap_or_else(|e| panic!("the written program does not read: {e}\n{written}"));
    let first_arc = tp
        .moves
        .iter()
        .find(|m| !matches!(m.kind, MoveKind::Dwell { .. }))
        .is_some_and(|m| matches!(m.kind, MoveKind::Arc { .. }));
    let skip = usize::from(first_arc);
    ROUND_TRIPS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    assert_eq!(
        tp.moves.len() + skip,
        back.moves.len(),
        "round trip: move count\n{text}\n--- written:\n{written}"
    );
    for (i, (a, b)) in tp
        .moves
        .iter()
        .zip(back.moves.iter().skip(skip))
        .enumerate()
    {
        let scale = 1.0 + a.to.x.abs().max(a.to.y.abs()).max(a.to.z.abs());
        let d = (a.to.x - b.to.x)
            .abs()
            .max((a.to.y - b.to.y).abs())
            .max((a.to.z - b.to.z).abs());
        assert!(
            d <= 1e-9 * scale || (a.to.x.is_nan() && b.to.x.is_nan()),
            "round trip: move {i} {a:?} read back as {b:?}\n{text}\n--- written:\n{written}"
        );
    }
}

/// `outline_importers`: arbitrary bytes to the DXF, SVG and outline-JSON importers and to the
/// machine-profile reader.
pub fn outline_importers(data: &[u8]) {
    let _ = dxf::parse(data, "fuzz.dxf", &dxf::DxfOptions::default());
    if let Ok(text) = std::str::from_utf8(data) {
        let _ = svg::parse(text, "fuzz.svg", 0.01);
        let _ = outline_json::parse(text, "fuzz.json");
        let _ = Machine::from_toml_str(text, "fuzz.toml");
    }
}

/// `points`: arbitrary text to the point-list parser, then the curve built through whatever
/// points it accepts, in all three curve kinds.
pub fn points(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    if let Ok(groups) = points::parse(text, "fuzz.csv") {
        for kind in [
            CurveKind::FourPoint,
            CurveKind::CatmullRom,
            CurveKind::Spline,
        ] {
            let _ = curve::build(&groups, kind, "fuzz");
        }
    }
}

/// A `pocket` input decoded: strategy, pocket, tool, options and simulation raster.
pub type PocketCase = (StrategyKind, PocketShape, Tool, PocketOptions, SimOptions);

/// `pocket`: a polygon (and maybe an island) with a tool and options from the bytes, through
/// `pocket::generate` (what `millpath pocket` runs) in the strategy the bytes pick.
pub fn pocket(data: &[u8]) {
    let Some((kind, shape, tool, opts, sim)) = pocket_case(data) else {
        return;
    };
    // The strategy, the stock simulation, the feed modulation and the verification of every
    // level.
    // Strict (like the planner's limits): no internal error (a gouge or uncut material that
    // `generate` refused is one) and, in what it returns, no gouge beyond `GOUGE_TOLERANCE`
    // and no uncut material beyond `UNCUT_AREA_TOLERANCE` (the stock simulation's coverage:
    // material the tool could have reached, the corner cusps aside). The gouge check is
    // geometric (distances to the walls, not the raster).
    generated(kind, &shape, &tool, &opts, &sim);
}

/// `adaptive`: the `pocket` target's pocket, tool and options (its inputs decode here too),
/// planned by the adaptive strategy, `--both-ways` and `--lift` derived from values the
/// `pocket` decoding draws (the finishing flag; the zigzag angle's share of the safe
/// height, which is NaN or out of range where those are), checked as `pocket` checks.
pub fn adaptive(data: &[u8]) {
    let Some((_, shape, tool, opts, sim)) = pocket_case(data) else {
        return;
    };
    let lift = opts.safe_height * opts.zigzag.angle.abs() / 3.2;
    let both = opts.finish;
    let opts = opts.with_both_ways(both).with_lift(lift);
    trace(&("adaptive", both, lift));
    generated(StrategyKind::Adaptive, &shape, &tool, &opts, &sim);
}

/// [`pocket::generate`] and the checks of the `pocket` and `adaptive` targets.
fn generated(
    kind: StrategyKind,
    shape: &PocketShape,
    tool: &Tool,
    opts: &PocketOptions,
    sim: &SimOptions,
) {
    match pocket::generate(kind, shape, tool, opts, sim) {
        Ok(r) => {
            assert_finite(&r.toolpath, "pocket");
            let v = &r.verification;
            assert!(!v.min_clearance_mm.is_nan(), "clearance NaN: {v:?}");
            if strict_verify() {
                assert!(
                    v.min_clearance_mm >= v.required_clearance_mm - pocket::GOUGE_TOLERANCE,
                    "gouge: {kind:?} {v:?}"
                );
                assert!(
                    v.uncut_area_mm2 <= millpath::stock::UNCUT_AREA_TOLERANCE,
                    "uncut material: {kind:?} {}",
                    v.uncut_text()
                );
            }
        }
        Err(millpath::Error::Internal(e)) if strict_verify() => {
            panic!("internal error: {kind:?}: {e}")
        }
        Err(_) => {}
    }
}

/// [`pocket_case`] with the walls left vertical whatever the bytes after the other values
/// say: the regression tests of inputs found before the target drew walls (eb03bd9), which
/// may have bytes left over that would now read as walls.
pub fn pocket_case_vertical(data: &[u8]) -> Option<PocketCase> {
    decode_pocket(data, false)
}

/// Decodes a `pocket` input; `None` when its outline or island is not a valid pocket.
pub fn pocket_case(data: &[u8]) -> Option<PocketCase> {
    decode_pocket(data, true)
}

fn decode_pocket(data: &[u8], walls: bool) -> Option<PocketCase> {
    let mut b = Bytes::new(data);
    let kind = match b.pick(3) {
        0 => StrategyKind::Zigzag,
        1 => StrategyKind::Offset,
        _ => StrategyKind::Spiral,
    };
    let size = b.unit(4.0, 60.0);
    let outer = polygon(&mut b, size);
    let island = b.flag().then(|| polygon(&mut b, size * 0.25));
    // Tool and stepover bounded below relative to the polygon (at most ~20 passes a level,
    // at most ~4 levels): the adaptive spiral takes seconds on a 60 mm triangle at a 0.6 mm
    // stepover, too slow for fuzzing.
    let d = b.num(size * 0.05, size * 0.6);
    let tool = Tool {
        diameter: d,
        flutes: b.pick(5) as u32,
        flute_length: b.num(5.0, 50.0),
        number: b.pick(100) as u32,
    };
    let depth = b.num(0.5, 8.0);
    let opts = PocketOptions::default()
        .with_stepover(if b.flag() {
            Stepover::Fraction(b.num(0.3, 1.0))
        } else {
            Stepover::Distance(b.num(size * 0.05, size * 0.3))
        })
        .with_depth(depth)
        .with_step_down(b.num(depth.abs().min(1e3) / 3.0 + 0.1, 10.0))
        .with_wall_stock(b.num(0.0, 0.5))
        .with_floor_stock(b.num(0.0, 0.3))
        .with_direction(if b.flag() {
            Direction::Climb
        } else {
            Direction::Conventional
        })
        .with_entry(if b.flag() {
            Entry::Helix {
                radius: b.num(0.5, 5.0),
                ramp_angle: b.num(0.02, 0.3),
            }
        } else {
            Entry::Ramp {
                ramp_angle: b.num(0.02, 0.3),
            }
        })
        .with_safe_height(b.num(0.5, 2.0))
        .with_clearance_height(b.num(2.0, 10.0))
        .with_feed(b.num(1.0, 50.0))
        .with_plunge_feed(b.num(1.0, 20.0))
        .with_slowdown(b.num(0.2, 1.0))
        .with_zigzag_angle(b.num(-3.2, 3.2))
        .with_transition(b.num(0.0, 1.0))
        .with_min_radius(b.num(0.1, 2.0))
        // The default morph on half the inputs; the paper's two on the rest (chosen by the
        // transition drawn above: no extra byte, so the committed corpus keeps decoding).
        .with_morph(if b.flag() {
            pocket::SpiralMorph::Offsets
        } else {
            pocket::SpiralMorph::Fronts
        })
        .with_arcs(false)
        // Curvature ramps (the default) unless the zigzag angle drawn is negative.
        .with_curvature_ramps(true)
        .with_finish(b.flag())
        .with_modulate_feed(false);
    let morph = match opts.spiral.morph {
        pocket::SpiralMorph::Fronts if opts.spiral.transition >= 0.5 => {
            pocket::SpiralMorph::Harmonic
        }
        m => m,
    };
    let ramps = opts.zigzag.angle >= 0.0;
    // `--arcs` on about half the inputs, derived from a drawn value so that the committed
    // corpus keeps its meaning (no extra byte drawn).
    let arcs = opts.spiral.min_radius > 1.05;
    let opts = opts
        .with_morph(morph)
        .with_curvature_ramps(ramps)
        .with_arcs(arcs);
    // Drawn after every other value, so that the committed corpus keeps its meaning (its
    // inputs end before these bytes, which then read as zeros: the finest cell, no
    // modulation). The stock simulation's raster as the CLI's `--cell` makes it after its
    // check (> 0 mm), coarse enough for fuzzing (at most ~80 cells across the pocket).
    let cell = b.unit(size / 80.0, size / 20.0);
    let opts = opts.with_modulate_feed(b.flag());
    let sim = SimOptions::default()
        .with_cell(cell)
        .with_step((2.0 * cell).max(0.1));
    // The walls, drawn after everything else (zeros: vertical; an older input with bytes left
    // over reads walls from them, hence `pocket_case_vertical` for the regression tests): a draft
    // angle in [0, 60°], or a bottom outline vertex for vertex like the top, the outer loop
    // shrunk towards its centroid and the island grown about its own (walls leaning into
    // the pocket; other shapes are refused as undercuts, as bad input).
    let walls_kind = b.pick(3);
    let lean = b.unit(0.0, 1.0);
    trace(&(&kind, &outer, &island, &tool, &opts, &sim, walls_kind, lean));
    let scaled = |pts: &[Point], f: f64| -> Vec<Point> {
        let n = pts.len().max(1) as f64;
        let c = pts.iter().fold(Point::new(0.0, 0.0), |c, p| {
            Point::new(c.x + p.x / n, c.y + p.y / n)
        });
        pts.iter()
            .map(|p| Point::new(c.x + (p.x - c.x) * f, c.y + (p.y - c.y) * f))
            .collect()
    };
    let bottom = (
        scaled(&outer, 1.0 - 0.4 * lean),
        island.as_ref().map(|p| scaled(p, 1.0 + 0.3 * lean)),
    );
    let loops = |outer: &[Point], island: &Option<Vec<Point>>, what: &str| {
        let o = Outline::from_points(outer, &format!("fuzz {what} outer")).ok()?;
        let islands: Vec<Outline> = island
            .iter()
            .filter_map(|p| Outline::from_points(p, &format!("fuzz {what} island")).ok())
            .collect();
        Some((o, islands))
    };
    let (top_outer, top_islands) = loops(&outer, &island, "top")?;
    let shape = PocketShape::new(top_outer, top_islands, "fuzz").ok()?;
    let shape = match walls_kind {
        _ if !walls => shape,
        0 => shape,
        1 => shape
            .with_walls(Walls::Draft((60.0 * lean).to_radians()), "fuzz draft")
            .ok()?,
        _ => {
            let (outer, islands) = loops(&bottom.0, &bottom.1, "bottom")?;
            shape
                .with_walls(Walls::Bottom { outer, islands }, "fuzz bottom")
                .ok()?
        }
    };
    Some((kind, shape, tool, opts, sim))
}

/// `contour`: points from the bytes grouped in fours, a curve kind, options; then
/// `curve::build` and `contour::contour`.
pub fn contour(data: &[u8]) {
    let Some((c, opt)) = contour_case(data) else {
        return;
    };
    let res = match contour::contour(&c, &opt) {
        Ok(res) => res,
        Err(millpath::Error::Internal(e)) if strict_verify() => {
            panic!("contour: internal error: {e}")
        }
        Err(_) => return,
    };
    {
        assert_finite(&res.toolpath, "contour");
        if strict_verify() {
            // The chordal deviation of the finishing pass, measured against the exact curve
            // (kurbo's nearest point, `curve::verify`), not by the pass's own measure: no
            // point of the pass farther than `r + T` from the curve. (How close it comes is
            // not asserted here: on ~20 chaotic corpus curves the pass comes nearer than `r`
            // to another part of the curve, a clearance defect left open, 2026-11-25.)
            let rad = if opt.side == Side::On {
                0.0
            } else {
                opt.tool.radius()
            };
            let (_, hi) = pass_distance(&c, &res.toolpath, opt.side == Side::On);
            assert!(
                hi <= rad + opt.tolerance + 1e-9,
                "contour: the finishing pass lies up to {hi:.6} mm from the curve, more than \
                 r + T = {:.6}",
                rad + opt.tolerance
            );
        }
    }
}

/// The curve and options `contour` decodes from `data` (`None`: the curve does not build).
pub fn contour_case(data: &[u8]) -> Option<(curve::CompositeCurve, ContourOptions)> {
    let mut b = Bytes::new(data);
    let kind = match b.pick(3) {
        0 => CurveKind::FourPoint,
        1 => CurveKind::CatmullRom,
        _ => CurveKind::Spline,
    };
    let size = b.unit(2.0, 80.0);
    let pts = polygon(&mut b, size);
    let groups: Vec<Vec<LabeledPoint>> = pts
        .chunks(4)
        .map(|c| {
            c.iter()
                .enumerate()
                .map(|(i, p)| LabeledPoint {
                    p: *p,
                    origin: format!("point {i}"),
                })
                .collect()
        })
        .collect();
    let opt = ContourOptions::default()
        .with_tool(Tool {
            diameter: b.num(0.2, size * 0.5),
            flutes: 2,
            flute_length: b.num(5.0, 50.0),
            number: 1,
        })
        .with_tolerance(b.num(size * 1e-4, size * 1e-2))
        .with_side(match b.pick(3) {
            0 => Side::Inside,
            1 => Side::Outside,
            _ => Side::On,
        })
        .with_top_z(b.num(-5.0, 5.0))
        .with_depth(b.num(0.5, 6.0))
        .with_step_down(b.num(1.0, 4.0))
        .with_finish_allowance(b.num(0.0, 1.0))
        .with_safe_height(b.num(1.0, 10.0))
        .with_clearance_height(b.num(0.5, 2.0))
        .with_feed(b.num(1.0, 50.0))
        .with_plunge_feed(b.num(1.0, 20.0))
        .with_lead_radius(b.num(0.0, 5.0))
        .with_rapid_speed(b.num(50.0, 200.0))
        .with_arcs(b.flag());
    trace(&(&kind, &pts, &opt));
    let c = curve::build(&groups, kind, "fuzz").ok()?;
    Some((c, opt))
}

/// The smallest and largest distance from the finishing level's cutting moves (those tagged
/// with a curve parameter: the loop, not its lead arcs) to the exact curve, at 8 points a
/// move; with `drawn`, to the curve as drawn (the fish-tail lobes cut off its corners
/// included: a pass on the outline traces them).
pub fn pass_distance(c: &curve::CompositeCurve, tp: &Toolpath, drawn: bool) -> (f64, f64) {
    pass_distance_dense(c, tp, drawn, 8)
}

/// [`pass_distance`] at `per_move` points a move.
pub fn pass_distance_dense(
    c: &curve::CompositeCurve,
    tp: &Toolpath,
    drawn: bool,
    per_move: u32,
) -> (f64, f64) {
    let Some(lv) = tp.levels.last() else {
        return (f64::INFINITY, f64::NEG_INFINITY);
    };
    let segs: Vec<(Point3, &Move)> = tp.segments().collect();
    // The lobes as dense polylines (a lobe is a few hundredths of a millimetre long).
    let lobes: Vec<Vec<Point>> = if drawn {
        c.lobes()
            .iter()
            .flat_map(|l| [l.to_tip, l.from_tip])
            .map(|k| (0..=256).map(|j| k.eval(f64::from(j) / 256.0)).collect())
            .collect()
    } else {
        Vec::new()
    };
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for (from, m) in segs.get(lv.start..lv.end).unwrap_or(&[]) {
        if m.tag.is_none() || !m.is_feed() {
            continue;
        }
        for j in 0..=per_move {
            let f = f64::from(j) / f64::from(per_move);
            let p = match (m.kind, m.sweep_from(*from)) {
                (MoveKind::Arc { center, .. }, Some((rad, sweep))) => {
                    let a0 = (from.xy() - center.xy()).angle();
                    center.xy() + millpath::Vec2::from_angle(a0 + sweep * f) * rad
                }
                _ => from.xy().lerp(m.to.xy(), f),
            };
            let d = lobes
                .iter()
                .flat_map(|l| l.windows(2))
                .map(|w| segment_distance(p, w[0], w[1]))
                .fold(curve::distance_to_curve(c, p), f64::min);
            lo = lo.min(d);
            hi = hi.max(d);
        }
    }
    (lo, hi)
}

/// Distance from `p` to the segment `a`–`b`.
pub fn segment_distance(p: Point, a: Point, b: Point) -> f64 {
    let d = b - a;
    let l2 = d.dot(d);
    let t = if l2 > 0.0 {
        ((p - a).dot(d) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    p.distance(a + d * t)
}

/// A machine: a preset, or a preset with limits from the bytes.
pub fn machine(b: &mut Bytes<'_>) -> Option<Machine> {
    let base = Machine::preset(Machine::PRESET_NAMES[b.pick(3)]).ok()?;
    if b.flag() {
        return Some(base);
    }
    let axis = |b: &mut Bytes<'_>| AxisLimits {
        max_velocity: b.num(5.0, 1000.0),
        max_acceleration: b.num(50.0, 20000.0),
        max_jerk: if b.byte() < 40 {
            f64::INFINITY
        } else {
            b.num(500.0, 1e6)
        },
    };
    Some(Machine {
        axes: [axis(b), axis(b), axis(b)],
        max_feed: b.num(5.0, 500.0),
        rapid: [
            b.num(50.0, 1000.0),
            b.num(50.0, 1000.0),
            b.num(50.0, 1000.0),
        ],
        path_tolerance: b.num(0.0, 0.1),
        ipo_cycle: b.num(0.0005, 0.01),
        curvature_accel_share: b.num(0.1, 0.9),
        curvature_jerk_share: b.num(0.1, 0.9),
        ..base
    })
}

/// A program of up to 48 moves from the bytes (lines, rapids, arcs in any plane with extra
/// turns, dwells, every corner mode), starting at the origin.
pub fn program(b: &mut Bytes<'_>) -> Toolpath {
    let mut tp = Toolpath::new(Tool::default(), Point3::ORIGIN);
    let mut at = Point3::ORIGIN;
    let n = b.pick(49);
    for _ in 0..n {
        if b.done() {
            break;
        }
        let step = if b.byte() < 20 { 1e-6 } else { 30.0 };
        let to = Point3::new(
            at.x + b.num(-step, step),
            at.y + b.num(-step, step),
            at.z + b.num(-step, step) * 0.2,
        );
        let feed = b.num(0.5, 300.0);
        let mut m = match b.pick(10) {
            0 => Move::rapid(to),
            1 => Move::dwell(at, b.num(0.0, 2.0)),
            2..=4 => {
                let c = Point3::new(at.x + b.num(-step, step), at.y + b.num(-step, step), at.z);
                let mut m = Move::arc_xy(to, c, b.flag(), feed);
                if let MoveKind::Arc { plane, turns, .. } = &mut m.kind {
                    *plane = match b.pick(3) {
                        0 => Plane::Xy,
                        1 => Plane::Zx,
                        _ => Plane::Yz,
                    };
                    *turns = u32::from(b.byte() % 3);
                }
                m
            }
            _ => Move::line(to, feed),
        };
        m = m.with_corner(match b.pick(5) {
            0 => Corner::ExactStop,
            1 => Corner::ExactPath,
            2 => Corner::Blend(b.num(0.001, 1.0)),
            _ => Corner::Machine,
        });
        if !matches!(m.kind, MoveKind::Dwell { .. }) {
            at = m.to;
        }
        tp.push(m);
    }
    tp
}

/// Most machine time a planner input may take before the verifier is skipped, s (1 kHz
/// sampling: at most ~60,000 samples an input).
pub const VERIFY_MAX_TIME: f64 = 60.0;

/// `planner`: a machine from the bytes, then a program (G-code text through the reader, or
/// moves generated from the bytes); plans it and, when it plans, checks the plan with the
/// independent limit verifier: a plan that violates its machine's limits is a failure.
pub fn planner(data: &[u8]) {
    let mut b = Bytes::new(data);
    let Some(m) = machine(&mut b) else {
        return;
    };
    let check = b.flag();
    let tp = if b.byte() < 64 {
        let Ok(text) = std::str::from_utf8(b.rest()) else {
            return;
        };
        let opts = ReaderOptions::default().with_lenient(true);
        match read_str(text, opts) {
            Ok((mut tp, _)) => {
                tp.moves.truncate(200);
                tp
            }
            Err(_) => return,
        }
    } else {
        program(&mut b)
    };
    trace(&(&m, &tp, check));
    let moves: Vec<(Point3, Move)> = tp.segments().map(|(f, mv)| (f, *mv)).collect();
    let opts = PlanOptions::default()
        .with_keep_geometry(true)
        .with_check_profiles(check);
    let Ok(plan) = plan_moves(moves.iter().map(|x| Ok(*x)), &m, &opts) else {
        return;
    };
    let t = plan.total_time();
    assert!(t.is_finite() && t >= 0.0, "total time {t}");
    for blk in &plan.blocks {
        assert!(
            blk.time.is_finite() && blk.time >= 0.0,
            "block time {}",
            blk.time
        );
    }
    if t <= VERIFY_MAX_TIME
        && let Ok(rep) = verify_plan(&plan, &moves, &m, &VerifyOptions::default())
        && strict_verify()
    {
        assert_eq!(
            rep.violations, 0,
            "the verifier found {} limit violations: {:?}",
            rep.violations, rep.first
        );
    }
}

/// Whether the targets verify what succeeds (`FUZZ_STRICT_VERIFY` set, or [`STRICT_VERIFY`]
/// from a test): `planner` fails on limit violations the verifier finds, `pocket` on a gouge,
/// uncut material or an internal error, `contour` on a pass farther than `r + T` from the
/// exact curve, `gcode_reader` on a program that does not read back as it was written. The
/// corpus replay in `hostile_corpus.rs` is strict; fuzz runs should set
/// `FUZZ_STRICT_VERIFY=1` (the `planner` runs of 2026-11-22 did). Off without it so that a
/// run can look for panics alone.
pub fn strict_verify() -> bool {
    STRICT_VERIFY.load(std::sync::atomic::Ordering::Relaxed)
        || std::env::var_os("FUZZ_STRICT_VERIFY").is_some()
}

/// How many programs [`round_trip`] has checked (the corpus replay asserts a minimum).
pub static ROUND_TRIPS: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);

/// Turns the strict check of [`strict_verify`] on from code (tests).
pub static STRICT_VERIFY: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);
