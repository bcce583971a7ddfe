//! Pocket strategies: zigzag, contour-offset, adaptive spiral.
//!
//! [`generate`] turns a [`PocketShape`], a [`Tool`] and [`PocketOptions`] into a
//! [`Toolpath`]: the strategy plans one level in the plane (`levels::LevelPlan`: cuts of
//! lines and exact arcs, each with its entry), `levels::assemble` repeats it at every
//! step-down with entries and heights, the stock simulation ([`crate::stock`]) measures the
//! engagement along the path and `feed` lays a feed profile along it, slowing down where
//! the engagement exceeds the nominal one (rate-limited in arc length, the same for every
//! strategy);
//! the same simulation and the exact gouge check give the [`Verification`].
//!
//! **Levels and sections.** [`plan_levels`] asks [`walls::level_shapes`] for the section of
//! the pocket at every level (the top outline for vertical walls; the outline shrunk by the
//! draft, or interpolated towards a bottom outline, for inclined ones) and plans each level
//! in its own section with [`plan_level`]; a pocket with vertical walls is planned once.
//! Every strategy's `plan(&PocketShape, &Tool, &PocketOptions)` therefore receives a planar
//! pocket (outline and islands of one level) and need not know about walls. After planning,
//! `levels::direct_entries` enters every later cut of a level over material an earlier cut
//! of that level has cleared, where one is near (no ramp, no plunge); [`generate`] verifies
//! each level against its own section ([`crate::stock::verify_levels`]).
//!
//! **Gouge guard.** The verification's clearance is exact (distances from the tool centre to
//! the walls, not the raster): [`Verification::problems`] reports any gouge deeper than
//! 1e-6 mm, and [`generate`] refuses, as an internal error, a toolpath whose tool centre
//! comes closer to a wall than the tool radius plus the wall stock minus [`GOUGE_TOLERANCE`]
//! (0.01 mm), after retrying the spiral's fronts morph with the harmonic one and `--arcs`
//! laps as chords. The tolerance sits above the spiral's arc fit (its last lap is
//! [`spiral::LAST_LOOP_MARGIN`] inside the boundary offset, its arcs within
//! `spiral::ARC_TOLERANCE` of the lap) and below any machining tolerance.
//!
//! **Plunge guard.** [`generate`] refuses, as an internal error, a toolpath the simulation
//! finds plunging into material (after the zigzag's retry with its ramp back along the
//! row): `verify` would refuse it.
//!
//! **Coverage guard.** Likewise [`generate`] refuses, as an internal error naming the area and
//! where most of it lies, a toolpath that leaves more than [`stock::UNCUT_AREA_TOLERANCE`]
//! (0.05 mm²) of material the tool could have reached: the stock simulation's uncut cells,
//! the corner cusps and wall stock the tool radius implies aside. Every pocket of the fuzz
//! corpus is held to both in the test command (`tests/hostile_corpus.rs`, `corpus_pocket`).
//!
//! * `zigzag`: parallel passes at an angle plus a boundary clean-up pass;
//! * `offset`: contour-parallel offsets from the inside out;
//! * `spiral`: the adaptive spiral, a central spiral morphing harmonically into the
//!   boundary offset.
//!
//! `auto` plans all three, verifies and times each, and keeps the fastest verified one.
//!
//! **Scale.** Every length above written in millimetres (the gouge and uncut-area
//! tolerances, the spiral's margin and arc tolerance, sample spacings and chords, the stock
//! simulation's cell and step) holds for tools up to 12.7 mm and grows with the tool above
//! it ([`crate::toolpath::Tool::tolerance_scale`], an area with its square): a pocket and its
//! enlargement cut with the tool, depths and heights enlarged alike plan the same path,
//! scaled, with the same work. What stays in millimetres is the written program's resolution
//! (arcs flatter than [`ARC_AS_LINE_SAGITTA`] are lines, the gouge verdict's resolution),
//! the offsets' numerical tolerances, and the feed profile's rate and shortest piece (the
//! machine's deceleration and the planner's cost of a knot, `feed`): the larger pocket's
//! feed changes are split into more pieces.

pub(crate) mod auto;
pub mod builtin;
pub(crate) mod feed;
pub(crate) mod gouge_retry;
pub(crate) mod levels;
pub(crate) mod loops;
pub(crate) mod offset;
pub(crate) mod offset_check;
pub(crate) mod options;
pub(crate) mod part;
pub(crate) mod segments;
pub(crate) mod shape;
pub(crate) mod spiral;
pub(crate) mod walls;
pub(crate) mod zigzag;

pub use crate::strategy::order::{order_tour as order_pockets, tour_length};
pub use auto::{Candidate, ORDER as AUTO_ORDER, Outcome, arcs_or_chords, choose, plan_all};
pub use feed::{FeedProfile, factor as feed_factor};
pub use levels::level_depths;
pub use options::{
    AdaptiveOptions, Direction, Entry, PocketOptions, SpiralMorph, SpiralOptions, Stepover,
    StrategyKind, ZigzagOptions,
};
pub use part::{PartPocket, PartResult, PartStrategy, generate_part};
pub use segments::ARC_AS_LINE_SAGITTA;
pub use shape::PocketShape;
pub use spiral::{
    Construction, LAST_LOOP_MARGIN, SpiralStats, plan_with_stats as spiral_with_stats,
};
pub use walls::{Walls, level_shapes};

use crate::error::Result;
use crate::stock::{self, SimOptions, StockSpec, Verification};
use crate::toolpath::{Tool, Toolpath};
use cavalier_contours::polyline::PlineSource;

/// A generated pocket toolpath and what the verifier measured on it.
#[derive(Debug, Clone)]
pub struct PocketResult {
    /// The toolpath, feeds modulated.
    pub toolpath: Toolpath,
    /// The verifier's findings.
    pub verification: Verification,
    /// Per move of the toolpath: true where the simulation found it removing material.
    pub cutting_moves: Vec<bool>,
    /// The nominal engagement the stepover implies, degrees.
    pub nominal_engagement_deg: f64,
    /// The stepover in mm.
    pub stepover_mm: f64,
    /// What [`generate`] changed from the options asked for, and why (empty when nothing):
    /// the fallbacks it took because the first path gouged.
    pub notes: Vec<PocketNote>,
}

/// The nominal engagement angle (rad) for stepover `s` and tool radius `r`: `arccos(1 − s/r)`.
pub fn nominal_engagement(s: f64, r: f64) -> f64 {
    (1.0 - (s / r).clamp(0.0, 2.0)).acos()
}

/// The engagement, radians, that a program clearing `shape` with `tool` (leaving
/// `wall_stock` on the walls) reaches where it feeds into the sharpest corner of the
/// tool-centre region (`stock::corner_floor`: `acos(2·sin(α/2) − 1)` for a corner of
/// interior angle `α`), the region's turn summed over a stretch as long as the smaller of
/// the stock simulation's averaging window and a tenth of the tool's radius (a corner
/// rounded by less reads as sharp). 0 when the tool does not fit.
pub fn engagement_floor(shape: &PocketShape, tool: &Tool, wall_stock: f64) -> f64 {
    let loops = shape.offset_loops(tool.radius() + wall_stock.max(0.0));
    let within = SimOptions::default()
        .window_for(tool)
        .min(0.1 * tool.radius());
    stock::corner_floor(&loops, within)
}

/// Plans one level with `kind` (no feeds, no levels) in the planar `shape` (a level's
/// section: its walls are ignored). The spiral's `fronts` and `harmonic` morphs refuse
/// islands; its default morph (`offsets`) takes them.
pub fn plan_level(
    kind: StrategyKind,
    shape: &PocketShape,
    tool: &Tool,
    opts: &PocketOptions,
) -> Result<levels::LevelPlan> {
    check_path_size(shape, tool, opts, 1.0)?;
    let mut plan = match kind {
        StrategyKind::Zigzag => zigzag::plan(shape, tool, opts)?,
        StrategyKind::Offset => offset::plan(shape, tool, opts)?,
        StrategyKind::Spiral => {
            if !shape.islands.is_empty() && opts.spiral.morph != SpiralMorph::Offsets {
                return Err(crate::InputError::new("islands", shape.islands.len())
                    .at("--strategy spiral")
                    .expected("a pocket without islands for the spiral (use --strategy offset)")
                    .into());
            }
            spiral::plan(shape, tool, opts)?
        }
        StrategyKind::Adaptive => crate::strategy::adaptive::plan(shape, tool, opts)?,
    };
    let region = shape.offset(tool.radius() + opts.wall_stock.max(0.0));
    // The adaptive planner chooses its entries against its own picture of the material (a
    // lead-in from an earlier cut can cross material this rule does not see): only its cuts
    // too short to ramp along get one here.
    levels::direct_entries(
        &mut plan,
        &region,
        DIRECT_ENTRY_REACH * tool.diameter,
        levels::min_ramp_path(opts),
        kind == StrategyKind::Adaptive,
    );
    Ok(plan)
}

/// Longest lead-in of a direct entry, in tool diameters (see `levels::direct_entries`).
pub const DIRECT_ENTRY_REACH: f64 = 3.0;

/// The roughing plans of every level (one per level of [`levels::level_depths`]), each in
/// its section ([`walls::level_shapes`]); a pocket with vertical walls is planned once.
pub fn plan_levels(
    kind: StrategyKind,
    shape: &PocketShape,
    tool: &Tool,
    opts: &PocketOptions,
) -> Result<(Vec<PocketShape>, Vec<levels::LevelPlan>)> {
    let levels = if opts.step_down > 0.0 {
        (opts.depth / opts.step_down).ceil().max(1.0)
    } else {
        1.0
    };
    check_path_size(shape, tool, opts, levels)?;
    let sections = level_shapes(shape, opts)?;
    let plans = if shape.is_prismatic() {
        match sections.first() {
            Some(s) => vec![plan_level(kind, s, tool, opts)?],
            None => Vec::new(),
        }
    } else {
        sections
            .iter()
            .map(|s| plan_level(kind, s, tool, opts))
            .collect::<Result<Vec<_>>>()?
    };
    Ok((sections, plans))
}

/// The toolpath without feed modulation or verification.
pub fn toolpath(
    kind: StrategyKind,
    shape: &PocketShape,
    tool: &Tool,
    opts: &PocketOptions,
) -> Result<Toolpath> {
    toolpath_and_sections(kind, shape, tool, opts).map(|(tp, _)| tp)
}

/// The toolpath and the section of each of its levels (the finishing level's is the last
/// roughing level's).
fn toolpath_and_sections(
    kind: StrategyKind,
    shape: &PocketShape,
    tool: &Tool,
    opts: &PocketOptions,
) -> Result<(Toolpath, Vec<PocketShape>)> {
    opts.validate(tool)?;
    let (mut sections, rough) = plan_levels(kind, shape, tool, opts)?;
    let finish = match (opts.finish, sections.last()) {
        (true, Some(last)) => {
            let fo = opts.clone().with_wall_stock(0.0);
            let plan = finishing_plan(last, tool, &fo, opts.wall_stock)?;
            sections.push(last.clone());
            Some(plan)
        }
        _ => None,
    };
    // The region a prismatic pocket's tool centre sweeps at every level: the way between
    // levels may cross it at the safe height. Sections of a drafted pocket or one with a
    // bottom outline change between the levels' heights, so there the tool rises to the
    // clearance height as before.
    let d0 = tool.radius() + opts.wall_stock.max(0.0);
    let regions: Vec<_> = if shape.is_prismatic() {
        sections.iter().take(1).map(|s| s.offset(d0)).collect()
    } else {
        Vec::new()
    };
    let tp = levels::assemble(*tool, opts, &rough, finish.as_ref(), &regions)?;
    Ok((tp, sections))
}

pub use gouge_retry::{GOUGE_TOLERANCE, PocketNote, gouge_tolerance};

/// Generates, modulates the feed and verifies: every level against its own section (and the
/// section of the slab's top, see [`crate::stock::verify_levels`]).
///
/// A toolpath that gouges by more than [`GOUGE_TOLERANCE`] is never returned. The spiral's
/// default morph ([`spiral::SpiralMorph::Fronts`]) is then planned again with the harmonic
/// one, and `--arcs` paths again as chords (`gouge_retry`: the fuzzer found chaotic outlines
/// on which the spiral cut up to 2.9 mm into a wall, and biarcs overshooting a sharp corner by
/// 0.011 mm, fuzz/README.md, 2026-11-22; the spiral now keeps its laps and arcs inside itself,
/// and no input of the fuzz corpora needs a fallback), and [`PocketResult::notes`] says which
/// fallback was taken and how deep the path asked for cut; what still gouges is an internal
/// error naming the depth, the move and the point. A toolpath that leaves uncut material
/// the tool could have reached (beyond [`stock::UNCUT_AREA_TOLERANCE`]) is an internal error
/// naming the area and where most of it lies.
pub fn generate(
    kind: StrategyKind,
    shape: &PocketShape,
    tool: &Tool,
    opts: &PocketOptions,
    sim: &SimOptions,
) -> Result<PocketResult> {
    let attempt = |o: &PocketOptions| generate_unchecked(kind, shape, tool, o, sim);
    let r = match gouge_retry::first_clear(kind, opts, attempt)? {
        gouge_retry::Attempts::Clears(r) => {
            // The zigzag's half-circle turns leave material on some fuzzed outlines (the
            // cause is not found yet): its straight turns then.
            let uncut = r.verification.uncut_area_mm2 > r.verification.uncut_tolerance_mm2;
            // Where the passes beside the zigzag's first row leave what its ramp left, or a
            // later entry feeds down onto it (a plunge: `ez_forms.dxf`, 10 mm tool): the
            // ramp back along the row and the row cut again.
            let plunges = r.verification.plunges > 0;
            if kind == StrategyKind::Zigzag && (uncut || plunges) && !opts.zigzag.ramp_recut {
                let mut o = opts.clone();
                o.zigzag.ramp_recut = true;
                return generate(kind, shape, tool, &o, sim);
            }
            if kind == StrategyKind::Zigzag && uncut && !opts.zigzag.straight_turns {
                let mut o = opts.clone();
                o.zigzag.straight_turns = true;
                return generate(kind, shape, tool, &o, sim);
            }
            return refuse_uncut(kind, r);
        }
        gouge_retry::Attempts::Gouges(r) => r,
    };
    let (_, sections) = toolpath_and_sections(kind, shape, tool, opts)?;
    let specs: Vec<StockSpec<'_>> = sections
        .iter()
        .map(|sec| StockSpec {
            outer: &sec.outer,
            islands: &sec.islands,
            wall_stock: 0.0,
        })
        .collect();
    let c = stock::min_clearance_levels(&r.toolpath, &specs);
    Err(crate::Error::internal(format!(
        "the {} toolpath gouges: the tool centre comes within {:.4} mm of a wall (needs {:.4}, \
         {:.4} mm deep) at ({:.4}, {:.4}, {:.4}), move {}; nothing written. Another strategy \
         (or --morph harmonic) may avoid it; please report the outline",
        kind.name(),
        r.verification.min_clearance_mm,
        r.verification.required_clearance_mm,
        gouge_retry::gouge(&r.verification),
        c.at.x,
        c.at.y,
        c.at.z,
        c.move_index
    )))
}

/// The longest cutting path planned, mm (5 km): the pocket's area over the
/// stepover, times the levels. Planning, verifying and modulating take about 0.6 kB of memory
/// and 5 ms per metre of path, so a pocket at this limit takes about 3 GB and half a minute;
/// a metre-sized drawing read as millimetres, or a tool far too small for the pocket, would
/// otherwise take tens of gigabytes. A 1 × 1 m pocket cut 50 mm deep with a 6 mm tool at 40 %
/// is about 3.3 km.
pub const MAX_PATH_MM: f64 = 5.0e6;

/// Refuses a pocket whose path would be longer than [`MAX_PATH_MM`] (area / stepover ×
/// `levels`, what every strategy cuts within a small factor), naming the pocket, the estimate
/// and what to check. [`plan_levels`] asks it for all the levels, [`plan_level`] for one: every
/// public way to a toolpath passes one of them.
fn check_path_size(
    shape: &PocketShape,
    tool: &Tool,
    opts: &PocketOptions,
    levels: f64,
) -> Result<()> {
    let area = crate::geom::area_less_islands(&shape.outer, &shape.islands);
    let step = opts.stepover_mm(tool);
    let length = area / step.max(f64::MIN_POSITIVE) * levels;
    if length.is_finite() && length <= MAX_PATH_MM {
        return Ok(());
    }
    let b = shape.outer.bounds();
    Err(
        crate::InputError::new("pocket area", format!("{area:.0} mm²"))
            .at(format!(
                "the pocket from ({:.3}, {:.3}) to ({:.3}, {:.3}) mm",
                b.min.x, b.min.y, b.max.x, b.max.y
            ))
            .expected(format!(
                "a path of at most {:.0} km; this pocket needs about {:.0} km ({} level{} at a \
             stepover of {:.3} mm): check the drawing's units (--drawing-units) or the tool",
                MAX_PATH_MM / 1.0e6,
                length / 1.0e6,
                levels,
                if levels < 1.5 { "" } else { "s" },
                step
            ))
            .into(),
    )
}

/// `r`, unless it plunges into material (an internal error: every entry is a helix, a ramp
/// or a feed down over cleared material), or leaves material the tool could have reached (more than
/// [`stock::uncut_area_tolerance`] of the tool, [`stock::UNCUT_AREA_TOLERANCE`] up to a
/// 12.7 mm tool, beyond the corner cusps and wall stock the tool radius
/// implies): then an internal error naming the area and where most of it lies, as for a
/// gouge. A strategy that leaves such material is a bug in the strategy.
fn refuse_uncut(kind: StrategyKind, r: PocketResult) -> Result<PocketResult> {
    if r.verification.plunges > 0 {
        return Err(crate::Error::internal(format!(
            "the {} toolpath plunges into material {} times (a feed move steeper than 45° \
             that lands on material); nothing written. Another strategy may avoid it; please \
             report the outline",
            kind.name(),
            r.verification.plunges
        )));
    }
    if r.verification.uncut_area_mm2 <= r.verification.uncut_tolerance_mm2 {
        return Ok(r);
    }
    Err(crate::Error::internal(format!(
        "the {} toolpath leaves material the tool could reach: {}; nothing written. Another \
         strategy may clear it; please report the outline",
        kind.name(),
        r.verification.uncut_text()
    )))
}

/// [`generate`] without the gouge guard.
fn generate_unchecked(
    kind: StrategyKind,
    shape: &PocketShape,
    tool: &Tool,
    opts: &PocketOptions,
    sim: &SimOptions,
) -> Result<PocketResult> {
    let (mut tp, sections) = toolpath_and_sections(kind, shape, tool, opts)?;
    let s = opts.stepover_mm(tool);
    let nominal = nominal_engagement(s, tool.radius());
    // The roughing levels leave the wall stock; a finishing pass (on the last level's slab)
    // takes the walls of that slab to zero stock.
    let last_slab_stock = if opts.finish { 0.0 } else { opts.wall_stock };
    let n_rough = level_depths(opts).len();
    let specs: Vec<StockSpec<'_>> = sections
        .iter()
        .enumerate()
        .map(|(i, sec)| StockSpec {
            outer: &sec.outer,
            islands: &sec.islands,
            wall_stock: if i + 1 >= n_rough {
                last_slab_stock
            } else {
                opts.wall_stock
            },
        })
        .collect();
    let sim = sim.with_record_samples(opts.modulate_feed);
    let simulation = stock::simulate_levels(&tp, &specs, nominal.to_degrees(), &sim);
    let mut cutting_moves = stock::cutting_moves(&tp, &simulation);
    if opts.modulate_feed {
        let (modulated, index) = feed::modulate(&tp, &simulation.samples, nominal, opts.slowdown);
        let mut flags = vec![false; modulated.moves.len()];
        for (i, w) in index.windows(2).enumerate() {
            let cut = cutting_moves.get(i).copied().unwrap_or(false);
            for f in flags.iter_mut().take(w[1]).skip(w[0]) {
                *f = cut;
            }
        }
        (tp, cutting_moves) = (modulated, flags);
    }
    let verification = stock::combine_levels(&tp, &specs, &simulation);
    Ok(PocketResult {
        toolpath: tp,
        verification,
        cutting_moves,
        nominal_engagement_deg: nominal.to_degrees(),
        stepover_mm: s,
        notes: Vec::new(),
    })
}

/// The finishing pass: each boundary loop at `r` (no stock), entered from the roughing's last
/// loop. Where the wall stock is wider than a step `h = min(s, 0.95·r)`, one loop at `r`
/// would leave a band of it standing (its disc reaches `r` out from the loop, the roughing's
/// last loop `r` in from `r + stock`: on a stock over `2r` a ridge of `stock − 2r` between
/// them, found by the `pocket` fuzzer on 2026-11-25: 4 mm² left on a 0.33 mm tool with
/// 0.48 mm of stock). So the loops at `r + k·h` for `k = ⌈stock/h⌉ − 1, …, 1, 0` are cut,
/// outermost last, each entered from the one before (the roughing's last loop for the first).
fn finishing_plan(
    shape: &PocketShape,
    tool: &Tool,
    opts: &PocketOptions,
    rough_stock: f64,
) -> Result<levels::LevelPlan> {
    let r = tool.radius();
    let h = opts.stepover_mm(tool).min(offset::RIDGE_SPACING * r);
    let stock = rough_stock.max(0.0);
    let steps = if h > 0.0 && stock > h {
        ((stock / h).ceil() as usize).clamp(1, MAX_FINISH_LOOPS)
    } else {
        1
    };
    // The roughing's last loops, a little inside: the spiral cuts its walls' loops
    // LAST_LOOP_MARGIN inside them, so a lead-in from the exact loop would feed down into
    // that sliver (a plunge, and the rapid above it through material).
    let mut rough = shape.offset(r + stock + 2.0 * spiral::last_loop_margin(tool));
    let mut cuts = Vec::new();
    for k in (0..steps).rev() {
        let region = shape.offset(r + k as f64 * h);
        cuts.extend(finishing_loops(&region, &rough, opts));
        rough = region;
    }
    Ok(levels::LevelPlan { cuts })
}

/// Most finishing loops (wall stock over steps).
const MAX_FINISH_LOOPS: usize = 1000;

/// Each loop of `region` as a finishing cut, entered from `rough` (cleared before).
fn finishing_loops(
    region: &shape::OffsetRegion,
    rough: &shape::OffsetRegion,
    opts: &PocketOptions,
) -> Vec<levels::Cut> {
    let mut cuts = Vec::new();
    for lp in region.loops() {
        let lp = if opts.direction == Direction::Climb {
            lp.clone()
        } else {
            shape::reversed(lp)
        };
        let first = lp.at(0).pos();
        let start = crate::geom::Point::new(first.x, first.y);
        // The lead-in: from the nearest point of the roughed region whose straight feed move
        // to the loop's start stays inside the tool-centre region (the nearest point itself
        // can lie across a thin wall spike: a 0.09 mm gouge found by the fuzzer), else from
        // the nearest vertex of the roughed region that qualifies, else a ramp along the
        // loop (straight down at its start fed onto the wall stock: a plunge).
        let nearest = rough
            .loops()
            .filter_map(|l| l.closest_point(shape::v2(start), 1e-12))
            .map(|c| shape::pt(c.seg_point));
        let vertices = rough
            .loops()
            .flat_map(|l| (0..l.vertex_count()).map(move |i| shape::pt(l.at(i).pos())));
        let mut candidates: Vec<crate::geom::Point> = nearest.chain(vertices).collect();
        candidates.sort_by(|a, b| a.distance(start).total_cmp(&b.distance(start)));
        let entry = candidates
            .into_iter()
            .find(|&q| !shape::crosses(region, q, start))
            .map_or(levels::CutEntry::Ramp, |from| levels::CutEntry::Direct {
                from,
            });
        cuts.push(levels::Cut {
            entry,
            path: segments::segs_from_vertices(&shape::closed_chain(&lp)),
        });
    }
    cuts
}
