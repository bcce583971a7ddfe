//! A whole program against every pocket of a drawing.
//!
//! The program is split where it leaves the stock: a **chunk** runs from one rapid that rises
//! from below the stock top (`z < 0`) to or above it, to the next. A chunk that never goes
//! below the top cuts nothing. Every other chunk belongs to the pocket containing its first
//! position below the top (inside the boundary, outside the islands), found from the geometry
//! alone, not from how the program was made; a chunk that starts below the top outside every
//! pocket is a **cut outside the pockets** (a problem).
//!
//! Each pocket's chunks, joined in program order by rapids above the stock (their ends are at
//! or above the top, so the join cannot touch material), are one program for that pocket;
//! its levels are found from its retracts ([`super::infer_levels`]) and it is verified against
//! that pocket alone with the simulation and the gouge check ([`super::verify`]'s): gouges (a chunk that wanders into another pocket
//! crosses its own pocket's wall, at clearance 0), uncut material, rapids through material and
//! plunges. The moves between chunks all lie at or above the stock top, so no rapid between
//! pockets can pass through material. A pocket no chunk cuts is uncut, its whole area
//! counting — unless no tool position fits in it (its outline offset inward by the tool
//! radius and wall stock is empty, [`super::simulate::reachable`], the verifier's own offset
//! of the outline): then it is **not reachable with this tool**, listed, and no failure.
//!
//! The whole program's figures add up (uncut area, rapids, plunges), take the worst
//! (clearance, largest engagement) or weigh by cutting length (mean engagement, share above
//! nominal); the engagement's distribution (entries aside) is the pockets' tallies merged.
//! Each move of the program is marked cutting or not from its pocket's simulation
//! ([`PartVerification::cutting_moves`]: the time a plan spends in the others is the time
//! not cutting).

use super::{
    EngagementTally, Problem, SimOptions, StockSpec, Verification, combine, infer_levels, simulate,
};
use crate::geom::{Point, Point3};
use crate::toolpath::{Move, MoveKind, Toolpath};
use rayon::prelude::*;
use serde::Serialize;

/// What the verifier found on a whole program.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PartVerification {
    /// The whole program's figures.
    pub total: Verification,
    /// Each pocket's, in the order given.
    pub pockets: Vec<Verification>,
    /// Per move of the program: true where it removed material (in the pocket it belongs
    /// to); false for rapids, moves in the air or through cleared material, and moves
    /// outside every pocket.
    #[serde(skip)]
    pub cutting_moves: Vec<bool>,
    /// Chunks of the program that cut below the stock top outside every pocket.
    pub cuts_outside: usize,
    /// Pockets (0-based, in the order given) no tool position of this diameter can enter,
    /// which the program leaves alone: not uncut material, not a failure.
    pub unreachable: Vec<usize>,
}

impl PartVerification {
    /// The problems found (see [`Verification::problems_within`]); empty when the
    /// program passes. `resolution` is the program's rounding allowance, mm.
    pub fn problems_within(&self, resolution: f64) -> Vec<Problem> {
        let mut out = self.total.problems_within(resolution);
        if self.cuts_outside > 0 {
            out.push(Problem::CutsOutside(self.cuts_outside));
        }
        if self.pockets.len() > 1 {
            for (k, v) in self.pockets.iter().enumerate() {
                let problems = v.problems_within(resolution);
                if !problems.is_empty() {
                    out.push(Problem::InPocket {
                        pocket: k + 1,
                        problems,
                    });
                }
            }
        }
        out
    }

    /// [`Self::problems_within`] at [`super::GOUGE_RESOLUTION`] (3 decimals).
    pub fn problems(&self) -> Vec<Problem> {
        self.problems_within(super::GOUGE_RESOLUTION)
    }
}

/// The pocket (index into `pockets`) containing `p`, if any.
fn pocket_at(pockets: &[StockSpec<'_>], p: Point) -> Option<usize> {
    pockets
        .iter()
        .position(|s| s.outer.contains(p) && !s.islands.iter().any(|i| i.contains(p)))
}

/// Verifies the whole program `tp` against `pockets` (see the module docs); `nominal_deg` is
/// the engagement the stepover implies.
pub fn verify_part(
    tp: &Toolpath,
    pockets: &[StockSpec<'_>],
    nominal_deg: f64,
    sim: &SimOptions,
) -> PartVerification {
    // Chunks: (first move, one past the last, the pocket of the first position below 0).
    let mut subs: Vec<Option<Toolpath>> = vec![None; pockets.len()];
    // Each sub-program's moves' index in `tp` (`None`: a joining rapid).
    let mut origins: Vec<Vec<Option<usize>>> = vec![Vec::new(); pockets.len()];
    let mut cuts_outside = 0;
    let mut chunk_start = 0;
    let mut chunk_from = tp.start;
    let mut owner: Option<Option<usize>> = None; // None: not below the top yet
    let mut from = tp.start;
    let mut flush = |start: usize, end: usize, at: Point3, owner: Option<Option<usize>>| match owner
    {
        Some(Some(k)) => {
            let sub = subs[k].get_or_insert_with(|| Toolpath::new(tp.tool, at));
            if sub.end() != at {
                sub.push(Move::rapid(at));
                origins[k].push(None);
            }
            sub.moves.extend_from_slice(&tp.moves[start..end]);
            origins[k].extend((start..end).map(Some));
        }
        Some(None) => cuts_outside += 1,
        None => {}
    };
    for (k, m) in tp.moves.iter().enumerate() {
        if owner.is_none() && !matches!(m.kind, MoveKind::Dwell { .. }) {
            let below = if from.z < 0.0 {
                Some(from)
            } else if m.to.z < 0.0 {
                Some(m.to)
            } else {
                None
            };
            if let Some(p) = below {
                owner = Some(pocket_at(pockets, p.xy()));
            }
        }
        let leaves = matches!(m.kind, MoveKind::Rapid) && m.to.z >= 0.0 && from.z < 0.0;
        from = m.to;
        if leaves {
            flush(chunk_start, k + 1, chunk_from, owner.take());
            chunk_start = k + 1;
            chunk_from = m.to;
        }
    }
    flush(chunk_start, tp.moves.len(), chunk_from, owner.take());
    let mut per = Vec::with_capacity(pockets.len());
    let mut unreachable = Vec::new();
    let mut lengths = Vec::with_capacity(pockets.len());
    // Each pocket's moves are simulated on their own, side by side.
    type Checked = (f64, Verification, EngagementTally, Vec<bool>);
    let checked: Vec<Option<Checked>> = pockets
        .par_iter()
        .zip(subs)
        .map(|(spec, sub)| {
            sub.map(|mut sub| {
                infer_levels(&mut sub);
                let s = simulate(&sub, *spec, nominal_deg, sim);
                let v = combine(&sub, *spec, &s);
                let cut = super::cutting_moves(&sub, &s);
                (sub.cut_length(), v, s.engagement, cut)
            })
        })
        .collect();
    let mut tally = EngagementTally::new(1.1 * nominal_deg);
    let mut cutting_moves = vec![false; tp.moves.len()];
    for ((spec, sub), origin) in pockets.iter().zip(checked).zip(&origins) {
        match sub {
            Some((length, v, t, cut)) => {
                tally.merge(&t);
                for (c, o) in cut.iter().zip(origin) {
                    if let (true, Some(k)) = (*c, o) {
                        cutting_moves[*k] = true;
                    }
                }
                lengths.push(length);
                per.push(v);
            }
            None => {
                lengths.push(0.0);
                let area = if simulate::reachable(*spec, tp.tool.radius(), sim.cell_for(&tp.tool)) {
                    crate::geom::area_less_islands(spec.outer, spec.islands)
                } else {
                    unreachable.push(per.len());
                    0.0
                };
                per.push(Verification {
                    min_clearance_mm: f64::INFINITY,
                    required_clearance_mm: tp.tool.radius() + spec.wall_stock,
                    uncut_area_mm2: area,
                    // The whole pocket is uncut: the pocket's index says where.
                    uncut_at: None,
                    rapids_through_material: 0,
                    plunges: 0,
                    max_engagement_deg: 0.0,
                    mean_engagement_deg: 0.0,
                    max_radial_depth_mm: 0.0,
                    share_above_nominal: 0.0,
                    cell_mm: sim.cell_for(&tp.tool),
                    raster_cells: 0,
                    tool_positions: 0,
                    uncut_tolerance_mm2: super::uncut_area_tolerance(&tp.tool),
                    engagement: super::EngagementStats::default(),
                    removed_mm3: 0.0,
                });
            }
        }
    }
    let mut total = combine_all(&per, &lengths, tp.tool.radius());
    total.engagement = tally.stats();
    PartVerification {
        total,
        cutting_moves,
        pockets: per,
        cuts_outside,
        unreachable,
    }
}

/// The whole program's figures from each pocket's (`lengths`: each pocket's cutting length).
fn combine_all(per: &[Verification], lengths: &[f64], r: f64) -> Verification {
    let total_len: f64 = lengths.iter().sum();
    let weigh = |f: fn(&Verification) -> f64| {
        if total_len > 0.0 {
            per.iter().zip(lengths).map(|(v, l)| f(v) * l).sum::<f64>() / total_len
        } else {
            0.0
        }
    };
    Verification {
        min_clearance_mm: per
            .iter()
            .map(|v| v.min_clearance_mm)
            .fold(f64::INFINITY, f64::min),
        required_clearance_mm: per
            .iter()
            .map(|v| v.required_clearance_mm)
            .fold(r, f64::max),
        uncut_area_mm2: per.iter().map(|v| v.uncut_area_mm2).sum(),
        uncut_at: per
            .iter()
            .filter(|v| v.uncut_at.is_some())
            .max_by(|a, b| a.uncut_area_mm2.total_cmp(&b.uncut_area_mm2))
            .and_then(|v| v.uncut_at),
        rapids_through_material: per.iter().map(|v| v.rapids_through_material).sum(),
        plunges: per.iter().map(|v| v.plunges).sum(),
        max_engagement_deg: per.iter().map(|v| v.max_engagement_deg).fold(0.0, f64::max),
        mean_engagement_deg: weigh(|v| v.mean_engagement_deg),
        max_radial_depth_mm: per
            .iter()
            .map(|v| v.max_radial_depth_mm)
            .fold(0.0, f64::max),
        share_above_nominal: weigh(|v| v.share_above_nominal),
        cell_mm: per.iter().map(|v| v.cell_mm).fold(0.0, f64::max),
        raster_cells: per.iter().map(|v| v.raster_cells).sum(),
        tool_positions: per.iter().map(|v| v.tool_positions).sum(),
        uncut_tolerance_mm2: per
            .iter()
            .map(|v| v.uncut_tolerance_mm2)
            .fold(super::UNCUT_AREA_TOLERANCE, f64::max),
        engagement: super::EngagementStats::default(),
        removed_mm3: per.iter().map(|v| v.removed_mm3).sum(),
    }
}
