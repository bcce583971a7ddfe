//! Material-removal simulation: engagement, gouge and coverage checks.
//!
//! This module reads a finished [`Toolpath`] and the pocket's
//! outline; it shares no code with the strategies that made the path (it uses the geometry
//! library directly).
//!
//! * `raster`: the material of one slab as a bitset of cells ([`DEFAULT_CELL`], 0.05 mm, by
//!   default, at most an eighth of the tool radius, [`MAX_CELL_RADII`]).
//! * `simulate`: sweeps the tool disc along every move, sample by sample ([`DEFAULT_STEP`],
//!   0.1 mm apart, at most a quarter of the tool radius), clearing between consecutive
//!   samples the cells within `r` of the segment joining them (along an arc, within `r` plus
//!   the sagitta of the arc between them): the swept area itself, with no scallop between
//!   samples, so that passes exactly one diameter apart leave nothing. A straight move at
//!   one height is swept as one capsule, each material cell counted to the first sample
//!   step whose capsule holds it (the step holding `t − √(r² − s²)`, the cell `t` along the
//!   move and `s` across it): the steps' counts and the cells left as clearing the steps
//!   one after the other gives, read in one pass over the capsule's rows. A move gets
//!   `⌈len/step⌉` evenly spaced positions, a length within [`STEP_TIE`] (10⁻⁹, relative) above
//!   a whole number of steps counting as that number ([`sample_count`]): the count is a
//!   discrete decision, and lengths of whole steps (a zigzag's links, one stepover long) would
//!   otherwise be decided by their last bit, which differs between math libraries. It measures, at every
//!   sample, the **true radial depth of cut** as the area removed per unit of travel,
//!   `a_e = ΔA / Δs`, averaged over [`DEFAULT_WINDOW`] (0.5 mm) of travel. For a straight cut
//!   removing a band of width `a_e` this is exact; the **engagement angle** follows from the
//!   chord geometry of a one-sided cut, `φ = arccos(1 − a_e/r)` (0 at `a_e = 0`, 90° at
//!   `a_e = r`, 180° at slotting, `a_e = 2r`). With [`SimOptions::record_samples`] it keeps
//!   the engagement at every tool position ([`EngagementSample`]), which the pockets' feed
//!   profile is made from. It also finds rapid moves through material (a vertical retract
//!   from where the tool stands is never one: it sweeps the column the tool occupies),
//!   plunges (feed moves steeper than 45° ending on material inside the rim the raster cannot
//!   resolve, `simulate::plunge_rim`), and the material left.
//! * Coverage: a material cell left after a slab is *uncut* when the tool could have reached
//!   it: its centre lies within `r − 2c` of the region the tool centre may visit (the points
//!   of the pocket at least `r + wall stock` from the walls), found on the raster from
//!   distances alone (`reach`), not from the curve offsets the strategies use. Cells
//!   farther away are the corner cusps and the wall stock the tool radius implies.
//! * `gouge`: the exact clearance between every move below the stock top and the outline
//!   and islands, against `r + stock −` [`GOUGE_RESOLUTION`] (the resolution a program is
//!   written at: closer than that is rounding, not a gouge).
//! * Scale: the default cell, step and window are millimetres for tools up to 12.7 mm and
//!   grow with the tool above ([`crate::toolpath::Tool::tolerance_scale`], `λ = D/12.7 mm`:
//!   a cell of `D/254`), and so does the uncut-area tolerance, with `λ²`
//!   ([`uncut_area_tolerance`]): a pocket and its enlargement cut with the tool enlarged
//!   alike are simulated on the same raster, cell for cell, with the same tool positions
//!   ([`Verification::raster_cells`], [`Verification::tool_positions`] count them). A cell,
//!   step or window given ([`SimOptions::with_cell`]) is used as given. The gouge verdict's
//!   [`GOUGE_RESOLUTION`] stays the written program's resolution at every scale.
//! * Holes ([`verify_holes`], module `holes`): a drilling or boring program against its
//!   holes, with exact geometry on the moves rather than the raster: nothing cut outside a
//!   hole, no rapid through material, each hole's envelope at its bottom on the drawn centre
//!   and diameter, its bottom cleared.
//! * Inclined walls ([`verify_levels`]): each level has its own section of the pocket; a
//!   slab's material is its level's section, and a level's moves are checked against its
//!   section and the section of the slab's top (the tool is a cylinder through the slab).
//! * Whole jobs ([`HeightField`]): a block of stock as the height of its top over every cell,
//!   cut by one operation after another (each tool on what the previous ones left), with
//!   each operation's volume and area removed, rapids through material and plunges
//!   ([`OperationCut`]); the material a profile leaves standing in its slot, as bridges
//!   holding the piece or not ([`held_by`]); and at the end what is left against the floors
//!   the job meant to cut and the part it meant to keep ([`check_field`]).

pub(crate) mod bridges;
pub(crate) mod corner_floor;
pub(crate) mod engagement;
pub(crate) mod field_check;
pub(crate) mod gouge;
pub(crate) mod heightfield;
pub(crate) mod holes;
pub(crate) mod nearest;
pub(crate) mod part;
mod problem;
pub(crate) mod raster;
pub(crate) mod reach;
pub(crate) mod rest_need;
pub(crate) mod simulate;
pub(crate) mod tally;

pub use bridges::{Bridge, BridgeOptions, BridgeVerdict, CutSide, Hold, Touches, held_by};
pub use corner_floor::{corner_floor, corner_turn};
pub use engagement::engagement_stats;
pub use field_check::{CheckOptions, Deviation, FieldCheck, Floor, PartTop, check_field};
pub use gouge::{Clearance, min_clearance, min_clearance_levels};
pub use heightfield::{
    ARC_SAGITTA, CutOptions, Cutter, DEFAULT_FIELD_MAX_CELLS, DEFAULT_Z_TOLERANCE, FieldOptions,
    HeightField, OperationCut, PLUNGE_SLOPE_SLACK,
};
pub use holes::{HoleCheck, HoleProblem, HoleVerification, verify_holes};
pub use part::{PartVerification, verify_part};
pub use problem::{Problem, problems_text};
pub use rest_need::{
    CONTACT_CELLS, CONTACT_DEPTH_CELLS, CONTACT_GAP_CELLS, CONTACT_SLACK, FLOOR_Z_TOLERANCE,
    RestNeed, UncutRegion, floor_cut_length, rest_need,
};
pub use simulate::{
    CUTTING_SHARE, DEFAULT_CELL, DEFAULT_STEP, DEFAULT_WINDOW, EngagementSample, MAX_CELL_RADII,
    MoveEngagement, STEP_TIE, SimOptions, Simulation, cutting_moves, reachable, sample_count,
    simulate, simulate_levels,
};
pub use tally::{EngagementStats, EngagementTally, TALLY_BIN_DEG, entry_moves};

use crate::geom::Outline;
use crate::toolpath::Toolpath;
use serde::Serialize;

/// The pocket as the verifier sees it.
#[derive(Debug, Clone, Copy)]
pub struct StockSpec<'a> {
    /// Outer outline.
    pub outer: &'a Outline,
    /// Islands.
    pub islands: &'a [Outline],
    /// Material the path must leave on the walls, mm.
    pub wall_stock: f64,
}

/// Everything the verifier found.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Verification {
    /// Smallest distance between the tool centre and a wall below the stock top, mm.
    pub min_clearance_mm: f64,
    /// The clearance required: tool radius + wall stock, mm.
    pub required_clearance_mm: f64,
    /// Area of material the tool could have reached but left, mm².
    pub uncut_area_mm2: f64,
    /// Where most of it lies (the centroid of the fullest tool-radius square of uncut cells,
    /// at its level's depth); `None` when nothing is uncut.
    pub uncut_at: Option<crate::geom::Point3>,
    /// Rapid moves that sweep through material.
    pub rapids_through_material: usize,
    /// Feed moves steeper than 45° ending in material.
    pub plunges: usize,
    /// Largest engagement angle, degrees.
    pub max_engagement_deg: f64,
    /// Mean engagement over the cutting samples, degrees.
    pub mean_engagement_deg: f64,
    /// Largest radial depth of cut, mm.
    pub max_radial_depth_mm: f64,
    /// Share of the cutting length above the nominal engagement (+2°).
    pub share_above_nominal: f64,
    /// Raster cell used, mm.
    pub cell_mm: f64,
    /// Cells of one slab's raster (the simulation's memory and the work of filling and
    /// checking a slab; the same for a drawing and its enlargement cut with the tool enlarged
    /// alike, [`SimOptions`]).
    pub raster_cells: usize,
    /// Tool positions the simulation swept along the feed moves (the work of the sweep).
    pub tool_positions: usize,
    /// The uncut area beyond which coverage fails, mm² ([`uncut_area_tolerance`] of the
    /// tool).
    pub uncut_tolerance_mm2: f64,
    /// The engagement's distribution along the cutting path, the entries aside, with the
    /// share above 1.1 × the nominal engagement ([`Simulation::engagement`]).
    pub engagement: EngagementStats,
    /// Material removed, mm³ ([`Simulation::removed_mm3`]).
    pub removed_mm3: f64,
}

/// How much closer than the required clearance the tool centre may come before it is a
/// gouge, mm: twice the rounding of a program written to 3 decimals in mm (`√2·½·10⁻³`
/// mm, the coordinates'), once for the coordinates and once for an arc that the writer
/// writes as its chord because its sagitta is below that rounding (a concave arc's chord
/// lies on the wall's side). A program read back cannot be checked more finely than it is
/// written; a plan is held to the same.
pub const GOUGE_RESOLUTION: f64 = 2.0 * 0.5e-3 * std::f64::consts::SQRT_2;

/// [`GOUGE_RESOLUTION`] for a program written to `decimals` decimals (in mm):
/// `2·½·10^−decimals·√2`, the coordinates' rounding and an arc written as its chord.
pub fn gouge_resolution(decimals: u32) -> f64 {
    2.0 * 0.5 * 10f64.powi(-(decimals.min(12) as i32)) * std::f64::consts::SQRT_2
}

/// How far uncut material may add up, mm², before coverage fails (a few cells along a
/// boundary where the raster's rounding leaves single cells), for tools up to
/// [`crate::toolpath::REFERENCE_DIAMETER`]; [`uncut_area_tolerance`] scales it for larger
/// ones.
pub const UNCUT_AREA_TOLERANCE: f64 = 0.05;

/// The uncut area beyond which coverage fails for `tool`, mm²: [`UNCUT_AREA_TOLERANCE`] times
/// the square of [`Tool::tolerance_scale`](crate::toolpath::Tool::tolerance_scale) (the
/// raster's cells, and the slivers they leave, grow with the tool's square).
pub fn uncut_area_tolerance(tool: &crate::toolpath::Tool) -> f64 {
    UNCUT_AREA_TOLERANCE * tool.tolerance_scale().powi(2)
}

impl Verification {
    /// The uncut area and where most of it lies, in words: `"1.234 mm², most of it around
    /// (x, y) at z = …"`.
    pub fn uncut_text(&self) -> String {
        problem::uncut_text(self.uncut_area_mm2, self.uncut_at)
    }

    /// The problems found; empty when the path passes ([`GOUGE_RESOLUTION`]: a
    /// program written to 3 decimals).
    pub fn problems(&self) -> Vec<Problem> {
        self.problems_within(GOUGE_RESOLUTION)
    }

    /// The problems found, a gouge being a clearance more than `resolution` (mm, the
    /// program's rounding, [`gouge_resolution`]) short of the required one.
    pub fn problems_within(&self, resolution: f64) -> Vec<Problem> {
        let mut out = Vec::new();
        if self.min_clearance_mm < self.required_clearance_mm - resolution {
            out.push(Problem::Gouge {
                clearance_mm: self.min_clearance_mm,
                required_mm: self.required_clearance_mm,
            });
        }
        if self.uncut_area_mm2 > self.uncut_tolerance_mm2 {
            out.push(Problem::Uncut {
                area_mm2: self.uncut_area_mm2,
                at: self.uncut_at,
            });
        }
        if self.rapids_through_material > 0 {
            out.push(Problem::RapidsThroughMaterial(self.rapids_through_material));
        }
        if self.plunges > 0 {
            out.push(Problem::Plunges(self.plunges));
        }
        out
    }
}

/// Runs the simulation and the gouge check; `nominal_deg` is the engagement the stepover
/// implies.
pub fn verify(
    tp: &Toolpath,
    spec: StockSpec<'_>,
    nominal_deg: f64,
    sim: &SimOptions,
) -> Verification {
    let s = simulate(tp, spec, nominal_deg, sim);
    combine(tp, spec, &s)
}

/// The verification from a simulation already run (and a fresh gouge check).
pub fn combine(tp: &Toolpath, spec: StockSpec<'_>, s: &Simulation) -> Verification {
    combine_levels(tp, &[spec], s)
}

/// [`verify`] with a pocket per level (inclined walls): `specs[i]` is the section of
/// `tp.levels[i]`; see [`simulate_levels`] and [`min_clearance_levels`].
pub fn verify_levels(
    tp: &Toolpath,
    specs: &[StockSpec<'_>],
    nominal_deg: f64,
    sim: &SimOptions,
) -> Verification {
    let s = simulate_levels(tp, specs, nominal_deg, sim);
    combine_levels(tp, specs, &s)
}

/// [`combine`] with a pocket per level. The clearance is reported against the last level's
/// stock (levels with more wall stock are measured less their extra stock).
pub fn combine_levels(tp: &Toolpath, specs: &[StockSpec<'_>], s: &Simulation) -> Verification {
    let c = min_clearance_levels(tp, specs);
    let stock = specs.last().map_or(0.0, |sp| sp.wall_stock);
    Verification {
        min_clearance_mm: c.distance,
        required_clearance_mm: tp.tool.radius() + stock,
        uncut_area_mm2: s.uncut_area_mm2,
        uncut_at: s.uncut_at,
        rapids_through_material: s.rapids_through_material,
        plunges: s.plunges,
        max_engagement_deg: s.max_engagement_deg,
        mean_engagement_deg: s.mean_engagement_deg,
        max_radial_depth_mm: s.max_radial_depth_mm,
        share_above_nominal: s.share_above_nominal,
        cell_mm: s.cell_mm,
        raster_cells: s.raster_cells,
        tool_positions: s.tool_positions,
        uncut_tolerance_mm2: uncut_area_tolerance(&tp.tool),
        engagement: s.engagement.stats(),
        removed_mm3: s.removed_mm3,
    }
}

/// Rebuilds the levels of a toolpath read back from G-code: the moves between two retracts
/// (rapids going up from below the stock top, `z < 0`: to or above it, or only to the next
/// level's safe height over the pocket just cleared) form a chunk whose depth is the lowest z
/// of its level feed moves (start and end at the same z below 0); consecutive chunks at the
/// same depth are one level. Chunks that cut nothing below the top are left out.
pub fn infer_levels(tp: &mut Toolpath) {
    use crate::toolpath::{Level, LevelKind};
    let mut levels: Vec<Level> = Vec::new();
    let mut chunk_start = 0;
    let mut depth: Option<f64> = None;
    let flush = |start: usize, end: usize, depth: Option<f64>, levels: &mut Vec<Level>| {
        let Some(z) = depth else { return };
        match levels.last_mut() {
            Some(l) if (l.z - z).abs() < 1e-9 && l.end == start => l.end = end,
            _ => levels.push(Level {
                z,
                kind: LevelKind::Roughing,
                start,
                end,
            }),
        }
    };
    let mut from = tp.start;
    for (k, m) in tp.moves.iter().enumerate() {
        if m.is_feed() && (m.to.z - from.z).abs() < 1e-9 && m.to.z < 0.0 {
            depth = Some(depth.map_or(m.to.z, |d: f64| d.min(m.to.z)));
        }
        if matches!(m.kind, crate::toolpath::MoveKind::Rapid)
            && m.to.z > from.z + 1e-9
            && from.z < 0.0
        {
            flush(chunk_start, k + 1, depth.take(), &mut levels);
            chunk_start = k + 1;
        }
        from = m.to;
    }
    flush(chunk_start, tp.moves.len(), depth, &mut levels);
    tp.levels = levels;
}
