//! Sweeping the tool through the stock, slab by slab (see the module docs of [`super`]).

use super::StockSpec;
use super::raster::Raster;
use super::reach::ReachMap;
use crate::geom::{Point, Point3};
use crate::toolpath::{Move, MoveKind, Tool, Toolpath};
use cavalier_contours::polyline::Polyline;
use std::collections::VecDeque;

/// The raster cell for tools up to 12.7 mm
/// ([`REFERENCE_DIAMETER`](crate::toolpath::REFERENCE_DIAMETER)), mm; larger tools get it
/// times their [`Tool::tolerance_scale`] (`D/254`).
pub const DEFAULT_CELL: f64 = 0.05;
/// The spacing of the tool positions for tools up to 12.7 mm, mm (scaled like
/// [`DEFAULT_CELL`]).
pub const DEFAULT_STEP: f64 = 0.1;
/// The travel the radial depth of cut is averaged over for tools up to 12.7 mm, mm (scaled
/// like [`DEFAULT_CELL`]).
pub const DEFAULT_WINDOW: f64 = 0.5;

/// Simulation resolution. Built from [`Default`] with the `with_*` methods (the struct is
/// `#[non_exhaustive]`: new settings do not break callers). A length left at `None` is its
/// default for the toolpath's tool ([`DEFAULT_CELL`], [`DEFAULT_STEP`], [`DEFAULT_WINDOW`]
/// times [`Tool::tolerance_scale`]: a drawing and its enlargement with the tool enlarged
/// alike are simulated on the same raster, cell for cell); a length set is used as given.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct SimOptions {
    /// Raster cell side, mm (`None`: [`DEFAULT_CELL`] scaled with the tool): at most
    /// [`MAX_CELL_RADII`] tool radii whatever is asked, and enlarged if the raster would
    /// exceed `max_cells`.
    pub cell: Option<f64>,
    /// Spacing of the tool positions along a move, mm (`None`: [`DEFAULT_STEP`] scaled with
    /// the tool); at most `MAX_STEP_RADII` tool radii whatever is asked (discs farther
    /// apart would leave slivers of their own between them, uncut material no toolpath
    /// left).
    pub step: Option<f64>,
    /// Travel over which the radial depth of cut is averaged, mm (`None`:
    /// [`DEFAULT_WINDOW`] scaled with the tool).
    pub window: Option<f64>,
    /// Most cells in one raster.
    pub max_cells: usize,
    /// Keep the engagement at every tool position of every feed move
    /// ([`Simulation::samples`]); off by default (a long program has millions).
    pub record_samples: bool,
}

impl Default for SimOptions {
    fn default() -> Self {
        SimOptions {
            cell: None,
            step: None,
            window: None,
            max_cells: 40_000_000,
            record_samples: false,
        }
    }
}

option_builders! {
    SimOptions;
    /// Sets [`SimOptions::max_cells`].
    with_max_cells => max_cells: usize;
    /// Sets [`SimOptions::record_samples`].
    with_record_samples => record_samples: bool;
}

impl SimOptions {
    /// Sets [`SimOptions::cell`], mm (used as given, whatever the tool).
    #[must_use]
    pub fn with_cell(mut self, cell: f64) -> Self {
        self.cell = Some(cell);
        self
    }

    /// Sets [`SimOptions::step`], mm (used as given, whatever the tool).
    #[must_use]
    pub fn with_step(mut self, step: f64) -> Self {
        self.step = Some(step);
        self
    }

    /// Sets [`SimOptions::window`], mm (used as given, whatever the tool).
    #[must_use]
    pub fn with_window(mut self, window: f64) -> Self {
        self.window = Some(window);
        self
    }

    /// The cell asked for `tool`, mm: the one set, else [`DEFAULT_CELL`] scaled with the
    /// tool (before the bounds of [`SimOptions::cell`]).
    pub fn cell_for(&self, tool: &Tool) -> f64 {
        self.cell.unwrap_or(DEFAULT_CELL * tool.tolerance_scale())
    }

    /// The spacing of the tool positions asked for `tool`, mm (before the bound of
    /// [`SimOptions::step`]).
    pub fn step_for(&self, tool: &Tool) -> f64 {
        self.step.unwrap_or(DEFAULT_STEP * tool.tolerance_scale())
    }

    /// The averaging travel for `tool`, mm.
    pub fn window_for(&self, tool: &Tool) -> f64 {
        self.window
            .unwrap_or(DEFAULT_WINDOW * tool.tolerance_scale())
    }
}

/// Engagement measured along one move.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct MoveEngagement {
    /// Largest radial depth of cut along the move, mm.
    pub max_radial_depth: f64,
    /// Largest engagement angle along the move, rad.
    pub max_angle: f64,
    /// Area of material the move removed from its slab, mm².
    pub removed_mm2: f64,
}

/// The engagement at one tool position of a feed move (see [`SimOptions::record_samples`]).
///
/// A move of length `L` from `from` is sampled at `n = ⌈L / step⌉` positions `L·k/n`,
/// `k = 1..n` (the end included, not the start); the sample at `L·k/n` stands for the travel
/// from the previous one. Its engagement is the simulation's, averaged over the last
/// [`SimOptions::window`] of travel in the slab.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct EngagementSample {
    /// Index of the move in the toolpath.
    pub move_index: usize,
    /// Path length from the move's start to this position, mm.
    pub at: f64,
    /// Engagement angle, rad: 0 where the tool cuts nothing (above the slab, in cleared
    /// material), π when slotting.
    pub angle: f64,
}

/// What the simulation found.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Simulation {
    /// Per move (same indices as the toolpath's moves): engagement, `None` when it cut nothing.
    pub per_move: Vec<Option<MoveEngagement>>,
    /// With [`SimOptions::record_samples`]: every tool position of every feed move inside a
    /// level, in path order; empty otherwise.
    pub samples: Vec<EngagementSample>,
    /// Largest engagement, degrees.
    pub max_engagement_deg: f64,
    /// Mean engagement over the cutting samples, degrees.
    pub mean_engagement_deg: f64,
    /// Largest radial depth of cut, mm.
    pub max_radial_depth_mm: f64,
    /// Share of the cutting length above `nominal + 2°`.
    pub share_above_nominal: f64,
    /// Uncut area the tool could have reached, mm².
    pub uncut_area_mm2: f64,
    /// Where the most of it lies: the centroid of the uncut cells in the tool-radius square
    /// that holds the most of them, at its slab's depth (`None` when nothing is uncut).
    pub uncut_at: Option<Point3>,
    /// Rapids through material.
    pub rapids_through_material: usize,
    /// Steep feed moves into material.
    pub plunges: usize,
    /// The raster cell used, mm.
    pub cell_mm: f64,
    /// Cells of the raster of one slab (what a slab costs to fill and to check).
    pub raster_cells: usize,
    /// Tool positions swept along the feed moves (what the sweep costs).
    pub tool_positions: usize,
    /// The engagement's distribution along the cutting path, the entries aside
    /// ([`super::entry_moves`]), with the length above 1.1 × the nominal engagement.
    pub engagement: super::EngagementTally,
    /// Material removed, mm³: each slab's cells cleared times the slab's thickness (the
    /// simulation clears a slab's cell whole where the tool passes within it).
    pub removed_mm3: f64,
}

/// The share of the tool's diameter a move's mean radial depth of cut (the area it removed
/// over its length) must reach for [`cutting_moves`] to count it as cutting: a link that
/// grazes a few cells of material is not a cut.
pub const CUTTING_SHARE: f64 = 0.02;

/// Per move of `tp`: true where the simulation `sim` of it found the move removing more than
/// [`CUTTING_SHARE`] of the tool's diameter times its length.
pub fn cutting_moves(tp: &Toolpath, sim: &Simulation) -> Vec<bool> {
    let d = tp.tool.diameter;
    tp.segments()
        .zip(&sim.per_move)
        .map(|((from, m), e)| {
            e.is_some_and(|e| e.removed_mm2 > CUTTING_SHARE * d * m.length_from(from))
        })
        .collect()
}

/// Engagement angle (rad) of a one-sided cut of radial depth `ae` with a tool of radius `r`.
pub fn engagement_angle(ae: f64, r: f64) -> f64 {
    (1.0 - (ae / r).clamp(0.0, 2.0)).acos()
}

/// The largest spacing of the tool positions, in tool radii: the engagement is measured
/// per step, and a plunge or a rapid is looked for at the samples.
pub const MAX_STEP_RADII: f64 = 0.25;

/// The largest raster cell, in tool radii. The coverage check looks at material within
/// `r − 2c` of where the tool may reach (module docs of `super`), and the engagement is
/// measured in cells swept per step: with a cell of `r/8` the first still reaches `3r/4`
/// and a disc covers about 200 cells.
pub const MAX_CELL_RADII: f64 = 0.125;

/// How close to a whole number of steps a move's length counts as that number, relative:
/// [`sample_count`] rounds `len/step` down to `k` when it lies within `STEP_TIE·k` above `k`.
pub const STEP_TIE: f64 = 1e-9;

/// How many tool positions the simulation puts on a move `len` mm long, `step` mm apart:
/// `⌈len/step⌉`, except that a quotient within [`STEP_TIE`] (relative) above a whole number
/// `k` gives `k` (the positions are then up to `step·(1 + STEP_TIE)` apart); at least one.
///
/// Lengths of a whole number of steps are common by design (a zigzag's link between rows is
/// the stepover, 1.2 mm for a 3 mm tool at 0.4, twelve steps of 0.1 mm), and there the plain
/// ceiling follows the last bit of the length: 1.2000000000000028 mm gives 13 positions,
/// 1.1999999999999957 mm twelve. Those bits come from transcendental functions (the
/// offsets' arcs, a spline's points) whose last place differs between math libraries (the
/// platform's libm and wasm32's), and a different count moves every position of the move,
/// the engagement measured there and so the feed the pockets' feed profile sets
/// ([`crate::strategy::pocket::FeedProfile`]). The tolerance puts the decision a billionth of the
/// length away from where such lengths land, so that every build counts alike.
pub fn sample_count(len: f64, step: f64) -> usize {
    let q = len / step;
    let whole = q.round();
    let q = if q > whole && q - whole <= STEP_TIE * whole {
        whole
    } else {
        q
    };
    (q.ceil() as usize).clamp(1, 10_000_000)
}

/// Positions along a move from `from`, [`sample_count`] of them evenly spaced at most about
/// `step` apart (the end included, not the start).
fn samples(from: Point3, m: &Move, step: f64) -> Vec<Point3> {
    let len = m.length_from(from);
    let n = sample_count(len, step);
    match (m.kind, m.sweep_from(from)) {
        (MoveKind::Arc { center, .. }, Some((r, sweep))) => {
            let a0 = (from.y - center.y).atan2(from.x - center.x);
            (1..=n)
                .map(|k| {
                    let f = k as f64 / n as f64;
                    let a = a0 + sweep * f;
                    Point3::new(
                        center.x + r * a.cos(),
                        center.y + r * a.sin(),
                        from.z + (m.to.z - from.z) * f,
                    )
                })
                .collect()
        }
        _ => (1..=n)
            .map(|k| from.lerp(m.to, k as f64 / n as f64))
            .collect(),
    }
}

/// The rim of the tool's end face that a feed straight down may find material under without
/// it being a plunge, mm: what the raster cannot tell from a cleared column. A cell stands
/// for its centre (half a diagonal, `c/√2`); two swept discs `step` apart leave a scallop
/// `r − √(r² − step²/4)` deep between them; and the landing point and the cut that cleared it
/// are read from G-code rounded to 3 decimals ([`super::GOUGE_RESOLUTION`]: an arc's end lies
/// up to ~1 µm off the circle through its start). Fresh material fills the whole disc, so a
/// real plunge is found whatever this rim; 0.037 mm at the default 0.05 mm cell.
fn plunge_rim(cell: f64, step: f64, r: f64) -> f64 {
    let half = 0.5 * step.min(r);
    cell * std::f64::consts::FRAC_1_SQRT_2
        + (r - (r * r - half * half).sqrt())
        + super::GOUGE_RESOLUTION
}

/// Sweeps the tool through each slab; `nominal_deg` is the engagement the stepover implies.
/// Every level has the same pocket, `spec`.
pub fn simulate(
    tp: &Toolpath,
    spec: StockSpec<'_>,
    nominal_deg: f64,
    opts: &SimOptions,
) -> Simulation {
    simulate_levels(tp, &vec![spec; tp.levels.len().max(1)], nominal_deg, opts)
}

/// [`simulate`] with a pocket per level: `specs[i]` is the section of `tp.levels[i]` (the last
/// one stands for levels beyond the list). A slab's material is its level's section; the
/// uncut material of a slab is measured against the section of its last level (the
/// finishing level, where there is one).
pub fn simulate_levels(
    tp: &Toolpath,
    specs: &[StockSpec<'_>],
    nominal_deg: f64,
    opts: &SimOptions,
) -> Simulation {
    let Some(&first_spec) = specs.first() else {
        return Simulation {
            per_move: vec![None; tp.moves.len()],
            ..Simulation::default()
        };
    };
    let spec_of = |li: usize| {
        specs
            .get(li)
            .or(specs.last())
            .copied()
            .unwrap_or(first_spec)
    };
    let r = tp.tool.radius();
    let bounds = specs
        .iter()
        .flat_map(|sp| std::iter::once(sp.outer).chain(sp.islands.iter()))
        .fold(first_spec.outer.bounds(), |b, o| b.union(o.bounds()));
    let area = bounds.width() * bounds.height();
    let cell = opts
        .cell_for(&tp.tool)
        .min(MAX_CELL_RADII * r)
        .max((area / opts.max_cells as f64).sqrt());
    let fresh = |spec: StockSpec<'_>| {
        let loops: Vec<&Polyline<f64>> = std::iter::once(spec.outer.polyline())
            .chain(spec.islands.iter().map(|i| i.polyline()))
            .collect();
        let mut ras = Raster::new(bounds, cell);
        ras.fill(&loops);
        ras
    };
    // The reach region of each distinct spec (consecutive levels usually share one).
    let mut reach_cache: Vec<(usize, Reach)> = Vec::new();
    let mut reach_of = |li: usize| -> Reach {
        let spec = spec_of(li);
        if let Some((_, rr)) = reach_cache
            .iter()
            .find(|(j, _)| same_spec(spec_of(*j), spec))
        {
            return rr.clone();
        }
        let walls: Vec<&Polyline<f64>> = std::iter::once(spec.outer.polyline())
            .chain(spec.islands.iter().map(|i| i.polyline()))
            .collect();
        let rr = std::rc::Rc::new(ReachMap::new(&fresh(spec), &walls, r + spec.wall_stock));
        reach_cache.push((li, rr.clone()));
        rr
    };
    let entry = super::entry_moves(tp);
    let mut out = Simulation {
        per_move: vec![None; tp.moves.len()],
        engagement: super::EngagementTally::new(1.1 * nominal_deg),
        cell_mm: cell,
        raster_cells: {
            let (nx, ny) = Raster::dims_of(bounds, cell);
            nx * ny
        },
        ..Simulation::default()
    };
    let cell_area = cell * cell;
    let step = opts.step_for(&tp.tool).min(MAX_STEP_RADII * r).max(1e-3);
    let rim = plunge_rim(cell, step, r);
    let window_n = ((opts.window_for(&tp.tool) / step).ceil() as usize).max(1);
    let (mut sum_angle, mut cut_len, mut above_len) = (0.0, 0.0, 0.0);
    let nominal = nominal_deg.to_radians() + 2f64.to_radians();
    let mut uncut_cells = 0usize;
    let mut densest = Densest::default();

    // Slab per distinct level depth, in order; the slab top is the previous depth.
    let mut slab: Option<(f64, f64, Raster)> = None; // (top, bottom, raster)
    let mut slab_level = 0usize; // the last level seen in the current slab
    let mut level_of_move = vec![None; tp.moves.len()];
    for (li, lv) in tp.levels.iter().enumerate() {
        for slot in level_of_move
            .iter_mut()
            .take(lv.end.min(tp.moves.len()))
            .skip(lv.start)
        {
            *slot = Some(li);
        }
    }
    let mut window: VecDeque<(u64, f64)> = VecDeque::new();
    // The last tool position whose disc the slab's raster cleared, and the disc's radius: a
    // step from there clears only the crescent beyond it (cells are never refilled in a
    // slab).
    let mut cleared_at: Option<(Point, f64)> = None;
    let mut from = tp.start;
    for (k, m) in tp.moves.iter().enumerate() {
        let start = from;
        from = m.to;
        let Some(li) = level_of_move[k] else { continue };
        let z = tp.levels[li].z;
        let need_new = slab
            .as_ref()
            .is_none_or(|(_, bottom, _)| (bottom - z).abs() > 1e-9);
        if need_new {
            if let Some((_, bottom, ras)) = slab.take() {
                let reach = reach_of(slab_level);
                let cells = uncut(&ras, &reach, r, cell);
                uncut_cells += cells.len();
                densest.add(&cells, r, bottom);
            }
            let top = tp.levels[..li]
                .iter()
                .rev()
                .find(|l| (l.z - z).abs() > 1e-9)
                .map_or(0.0, |l| l.z);
            slab = Some((top, z, fresh(spec_of(li))));
            cleared_at = None;
            window.clear();
        }
        slab_level = li;
        let Some((top, bottom, ras)) = slab.as_mut() else {
            continue;
        };
        let (top, thick) = (*top, (*top - *bottom).max(0.0));
        match m.kind {
            MoveKind::Dwell { .. } => {}
            MoveKind::Rapid => {
                window.clear();
                // A vertical retract sweeps only the column above where the tool stands: air
                // (the tool is a cylinder), never material.
                let retract = m.to.z >= start.z && start.xy().distance(m.to.xy()) <= 1e-9;
                if !retract && start.z.min(m.to.z) < top - 1e-9 {
                    let hit = samples(start, m, step)
                        .iter()
                        .any(|p| p.z < top - 1e-9 && ras.count_disc(p.xy(), r) > 0);
                    if hit {
                        out.rapids_through_material += 1;
                    }
                }
            }
            MoveKind::Line | MoveKind::Arc { .. } => {
                let dz = start.z - m.to.z;
                let xy = (m.length_from(start).powi(2) - dz * dz).max(0.0).sqrt();
                if m.to.z < start.z && m.to.z < top - 1e-9 && (start.z - m.to.z) > xy {
                    // Steeper than 45°: a plunge if it lands in material.
                    if ras.count_disc(m.to.xy(), r - rim) > 0 {
                        out.plunges += 1;
                    }
                }
                let mut eng: Option<MoveEngagement> = None;
                let mut prev = start;
                let at = samples(start, m, step);
                out.tool_positions += at.len();
                let (len, n) = (m.length_from(start), at.len() as f64);
                // The tool sweeps the capsule between consecutive samples; along an arc the
                // chord's capsule is widened by the sagitta of the arc between them, so that
                // it holds the arc's own sweep.
                let widen = match (m.kind, m.sweep_from(start)) {
                    (MoveKind::Arc { .. }, Some((rad, sweep))) => {
                        rad * (1.0 - (0.5 * sweep / n).cos())
                    }
                    _ => 0.0,
                };
                // A straight move at one height inside the slab: its steps' counts from one
                // sweep of the whole capsule ([`Raster::sweep_steps`]), the same cells.
                let flat = m.kind == MoveKind::Line
                    && (start.z - m.to.z).abs() <= 1e-12
                    && start.z.max(m.to.z) < top - 1e-9
                    && len > 0.0;
                let mut swept = Vec::new();
                if flat {
                    swept = vec![0; at.len()];
                    ras.sweep_steps(start.xy(), m.to.xy(), r, &mut swept);
                }
                for (j, p) in at.into_iter().enumerate() {
                    let ds = prev.distance(p);
                    let from = std::mem::replace(&mut prev, p);
                    let mut record = |angle: f64| {
                        if opts.record_samples {
                            out.samples.push(EngagementSample {
                                move_index: k,
                                at: len * (j + 1) as f64 / n,
                                angle,
                            });
                        }
                    };
                    if p.z >= top - 1e-9 {
                        record(0.0);
                        continue;
                    }
                    // From a sample above the slab the tool enters it at this one.
                    let removed = if flat {
                        cleared_at = Some((p.xy(), r));
                        swept[j]
                    } else if from.z >= top - 1e-9 {
                        cleared_at = Some((p.xy(), r));
                        ras.clear_disc(p.xy(), r)
                    } else {
                        let rr = r + widen;
                        let a_clear = cleared_at.is_some_and(|(c, cr)| c == from.xy() && cr >= rr);
                        cleared_at = Some((p.xy(), rr));
                        ras.clear_capsule_from(from.xy(), p.xy(), rr, a_clear)
                    };
                    out.removed_mm3 += removed as f64 * cell_area * thick;
                    window.push_back((removed, ds));
                    if window.len() > window_n {
                        window.pop_front();
                    }
                    let (cells, travel) = window
                        .iter()
                        .fold((0u64, 0.0), |acc, w| (acc.0 + w.0, acc.1 + w.1));
                    let ae = if travel > 1e-12 {
                        (cells as f64 * cell_area / travel).min(2.0 * r)
                    } else if cells > 0 {
                        2.0 * r
                    } else {
                        0.0
                    };
                    if removed > 0 {
                        eng.get_or_insert_with(MoveEngagement::default).removed_mm2 +=
                            removed as f64 * cell_area;
                    }
                    if removed == 0 && ae <= 0.0 {
                        record(0.0);
                        continue;
                    }
                    let phi = engagement_angle(ae, r);
                    record(phi);
                    if entry.get(k).copied().unwrap_or(false) {
                        out.engagement.entry(ds);
                    } else {
                        out.engagement.cut(phi.to_degrees(), ds);
                    }
                    sum_angle += phi * ds;
                    cut_len += ds;
                    if phi > nominal {
                        above_len += ds;
                    }
                    let e = eng.get_or_insert_with(MoveEngagement::default);
                    e.max_radial_depth = e.max_radial_depth.max(ae);
                    e.max_angle = e.max_angle.max(phi);
                    out.max_radial_depth_mm = out.max_radial_depth_mm.max(ae);
                    out.max_engagement_deg = out.max_engagement_deg.max(phi.to_degrees());
                }
                out.per_move[k] = eng;
            }
        }
    }
    if let Some((_, bottom, ras)) = slab.take() {
        let reach = reach_of(slab_level);
        let cells = uncut(&ras, &reach, r, cell);
        uncut_cells += cells.len();
        densest.add(&cells, r, bottom);
    }
    out.uncut_area_mm2 = uncut_cells as f64 * cell_area;
    out.uncut_at = densest.at;
    if cut_len > 0.0 {
        out.mean_engagement_deg = (sum_angle / cut_len).to_degrees();
        out.share_above_nominal = above_len / cut_len;
    }
    out
}

/// Where the tool centre may go, on the raster ([`super::reach`]).
/// Shared between the levels of one section.
type Reach = std::rc::Rc<ReachMap>;

/// True when two specs describe the same pocket (the same outlines, by address or by value).
pub(crate) fn same_spec(a: StockSpec<'_>, b: StockSpec<'_>) -> bool {
    let eq = |x: &crate::geom::Outline, y: &crate::geom::Outline| {
        std::ptr::eq(x, y) || (x.len() == y.len() && x.vertices().eq(y.vertices()))
    };
    (a.wall_stock - b.wall_stock).abs() <= 1e-12
        && eq(a.outer, b.outer)
        && a.islands.len() == b.islands.len()
        && a.islands.iter().zip(b.islands).all(|(x, y)| eq(x, y))
}

/// False only when no tool position of radius `r` can fit in the pocket: no point of the
/// pocket lies `r + wall stock` from its walls, by the reach map on a raster of `cell`
/// (`ReachMap::fits`: its distance transform bounds the cells to search, the exact
/// distance decides). A pocket narrower than the tool leaves no such position, and no program
/// can cut it.
pub fn reachable(spec: StockSpec<'_>, r: f64, cell: f64) -> bool {
    let loops: Vec<&Polyline<f64>> = std::iter::once(spec.outer.polyline())
        .chain(spec.islands.iter().map(|i| i.polyline()))
        .collect();
    let cell = cell.max(
        spec.outer
            .bounds()
            .width()
            .max(spec.outer.bounds().height())
            / 2000.0,
    );
    let mut ras = Raster::new(spec.outer.bounds().inflate(cell), cell);
    ras.fill(&loops);
    let d = r + spec.wall_stock;
    ReachMap::new(&ras, &loops, d).fits()
}

/// The densest cluster of uncut cells seen so far, over the slabs.
#[derive(Default)]
struct Densest {
    count: usize,
    at: Option<Point3>,
}

impl Densest {
    /// Buckets `cells` (of the slab at `z`) into squares of side `r` and keeps the centroid of
    /// the fullest square when it beats the slabs before.
    fn add(&mut self, cells: &[Point], r: f64, z: f64) {
        // Ordered, so that a tie between squares is broken the same way on every run.
        let mut buckets: std::collections::BTreeMap<(i64, i64), (usize, f64, f64)> =
            std::collections::BTreeMap::new();
        let side = r.max(1e-9);
        for p in cells {
            let key = ((p.x / side).floor() as i64, (p.y / side).floor() as i64);
            let e = buckets.entry(key).or_insert((0, 0.0, 0.0));
            e.0 += 1;
            e.1 += p.x;
            e.2 += p.y;
        }
        if let Some((n, sx, sy)) = buckets.into_values().max_by_key(|b| b.0)
            && n > self.count
        {
            self.count = n;
            self.at = Some(Point3::new(sx / n as f64, sy / n as f64, z));
        }
    }
}

/// Material cells within `r − 2c` of the reachable region, or in it: material the tool could
/// have cut. (A cell whose centre the tool centre may visit counts however coarse the cells:
/// with `c > r/2` the limit is negative, found by the `pocket` fuzzer on 2026-11-25.)
fn uncut(ras: &Raster, reach: &Reach, r: f64, c: f64) -> Vec<Point> {
    let limit = r - 2.0 * c;
    ras.material_cells()
        .filter(|&p| {
            let d = reach.distance(p);
            d == 0.0 || d <= limit
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A length of `k` steps a few units in the last place either side is `k` positions; any
    /// length gets positions at most `step·(1 + STEP_TIE)` apart and fewer would be farther.
    #[test]
    fn whole_steps_count_alike_whatever_their_last_bits() {
        for step in [0.1, 0.05, 0.3175, 1.0 / 3.0] {
            for k in 1..=2000u32 {
                let len = f64::from(k) * step;
                for d in -8i64..=8 {
                    let l = f64::from_bits(len.to_bits().wrapping_add_signed(d));
                    assert_eq!(sample_count(l, step), k as usize, "{l} / {step}");
                }
            }
            let mut len = 1e-6;
            while len < 500.0 {
                let n = sample_count(len, step);
                let spacing = len / n as f64;
                assert!(spacing <= step * (1.0 + STEP_TIE), "{len} / {step}: {n}");
                assert!(n == 1 || len / (n - 1) as f64 > step, "{len} / {step}: {n}");
                len *= 1.000_37;
            }
        }
    }
}
