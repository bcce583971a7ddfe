//! The report of a pocket job (`millpath pocket`): the JSON written by `--report` and the
//! text lines, for one pocket or a whole part (each pocket and the totals).

use crate::strategy::pocket::{self, part::PartPocket, part::PartResult};
use serde::Serialize;

/// The report written by `--report`.
#[derive(Debug, Clone, Serialize)]
pub struct Report {
    /// Strategy name.
    pub strategy: String,
    /// Cycle time, s.
    pub cycle_time_s: f64,
    /// How the cycle time was computed.
    pub cycle_time_model: String,
    /// The same program at its programmed feeds, s (rapids at the machine's rapid speed, no
    /// acceleration): `cycle_time_s` less this is the time lost to slowing down.
    pub time_at_programmed_feed_s: f64,
    /// Cutting path length, mm.
    pub path_length_mm: f64,
    /// Rapid length, mm.
    pub rapid_length_mm: f64,
    /// Largest engagement, degrees.
    pub max_engagement_deg: f64,
    /// Mean engagement, degrees.
    pub mean_engagement_deg: f64,
    /// Nominal engagement, degrees.
    pub nominal_engagement_deg: f64,
    /// Share of the cutting length above the nominal engagement.
    pub share_above_nominal: f64,
    /// The stepover asked for, mm.
    pub stepover_mm: f64,
    /// Largest radial depth of cut measured (slotting included), mm.
    pub max_stepover_mm: f64,
    /// Levels.
    pub levels: usize,
    /// Moves.
    pub moves: usize,
    /// The verifier's findings.
    pub verification: crate::stock::Verification,
    /// Material removed per second of the cycle time, mm³/s (the simulation's volume over
    /// `cycle_time_s`).
    pub removal_rate_mm3_s: f64,
    /// Time in moves that remove no material (links through cleared material, lifts,
    /// retracts, rapids), the entries aside, s, by the planner on the machine
    /// ([`air_times`]).
    pub air_time_s: f64,
    /// The rapids' part of `air_time_s`, s.
    pub rapid_time_s: f64,
    /// Time in the entries, s ([`air_times`]): the descents by helix or ramp and the flat
    /// turns on their track (`stock::entry_moves`).
    pub entry_time_s: f64,
    /// The engagement the sharpest corner of the pockets' tool-centre regions forces on any
    /// program, degrees (`pocket::engagement_floor`).
    pub engagement_floor_deg: f64,
    /// Problems found (empty when the path passes).
    pub problems: Vec<String>,
    /// What was changed from the options asked for, and why (a fallback after a gouge).
    pub notes: Vec<String>,
    /// With `--strategy auto`: every strategy tried, in `pocket::auto::ORDER` then the
    /// adaptive where the flute length was given (on a
    /// drawing of one pocket; each pocket's list is in `pockets`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub auto: Option<Vec<AutoEntry>>,
    /// Every pocket asked for, in cutting order (those left out last).
    pub pockets: Vec<PocketEntry>,
}

/// One pocket of the drawing in the report.
#[derive(Debug, Clone, Serialize)]
pub struct PocketEntry {
    /// Its index in the drawing (1-based, as `--list` and `--select` number them).
    pub index: usize,
    /// Area of material, mm².
    pub area_mm2: f64,
    /// The strategy that cut it.
    pub strategy: String,
    /// Its cycle time alone, s (`null` when left out).
    pub cycle_time_s: Option<f64>,
    /// Cutting path length, mm.
    pub path_length_mm: f64,
    /// The whole program's verification of this pocket found no problem.
    pub verified: bool,
    /// Why it was left out.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub skipped: Option<String>,
    /// With `--strategy auto`: every strategy tried on it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub auto: Option<Vec<AutoEntry>>,
}

/// One strategy tried by `--strategy auto`.
#[derive(Debug, Clone, Serialize)]
pub struct AutoEntry {
    /// Strategy name.
    pub strategy: String,
    /// Cycle time on the machine, s (`null` when not planned or not timed).
    pub cycle_time_s: Option<f64>,
    /// Cutting path length, mm (`null` when not planned).
    pub path_length_mm: Option<f64>,
    /// The verifier found no problem.
    pub verified: bool,
    /// Why it was not verified, or why it could not be planned.
    pub why_not: Option<String>,
    /// This one was written: the fastest verified.
    pub chosen: bool,
}

/// The report's entries of `auto`'s candidates; `chosen` is the index written.
pub fn auto_entries(candidates: &[pocket::auto::Candidate], chosen: usize) -> Vec<AutoEntry> {
    candidates
        .iter()
        .enumerate()
        .map(|(i, c)| AutoEntry {
            strategy: c.kind.name().to_owned(),
            cycle_time_s: c.cycle_time_s(),
            path_length_mm: c.path_length_mm(),
            verified: c.verified(),
            why_not: c.why_not(),
            chosen: i == chosen,
        })
        .collect()
}

/// One line per pocket of a part.
pub fn pocket_line(p: &PocketEntry) -> String {
    match (&p.skipped, p.cycle_time_s) {
        (Some(why), _) => format!(
            "pocket {}: area {:.1} mm², left out: {why}",
            p.index, p.area_mm2
        ),
        (None, t) => format!(
            "pocket {}: area {:.1} mm², {}, cycle time {:.2} s alone, path {:.1} mm, {}",
            p.index,
            p.area_mm2,
            p.strategy,
            t.unwrap_or(0.0),
            p.path_length_mm,
            if p.verified {
                "verified"
            } else {
                "NOT verified"
            }
        ),
    }
}

/// One line per strategy `auto` tried.
pub fn auto_line(e: &AutoEntry) -> String {
    let mut line = format!("auto: {}:", e.strategy);
    if let Some(t) = e.cycle_time_s {
        line.push_str(&format!(" cycle time {t:.2} s,"));
    }
    if let Some(l) = e.path_length_mm {
        line.push_str(&format!(" path {l:.1} mm,"));
    }
    match (&e.why_not, e.path_length_mm) {
        (None, _) => line.push_str(" verified"),
        (Some(w), Some(_)) => line.push_str(&format!(" not verified: {w}")),
        (Some(w), None) => line.push_str(&format!(" not planned: {w}")),
    }
    if e.chosen {
        line.push_str(" (fastest verified: written)");
    }
    line
}

/// How the report's cycle time is computed.
pub const REPORT_TIME_MODEL: &str =
    "millpath estimate on the written program (G-code reader, jerk-limited look-ahead planner)";

/// Builds the report of a generated part; `cycle_time_s` and `time_at_programmed_feed_s`
/// are the written program's ([`super::program::program_times`]).
pub fn report(part: &PartResult, cycle_time_s: f64, time_at_programmed_feed_s: f64) -> Report {
    let tp = &part.toolpath;
    let v = &part.verification;
    let cut: Vec<&PartPocket> = part.pockets.iter().filter(|p| p.result.is_some()).collect();
    let several = part.pockets.len() > 1;
    let name = match cut.first() {
        Some(first) if cut.iter().all(|p| p.kind == first.kind) => first.kind.name().to_owned(),
        _ => "mixed".to_owned(),
    };
    let first = cut.first().and_then(|p| p.result.as_ref());
    let mut notes = Vec::new();
    for p in &part.pockets {
        for n in p.result.iter().flat_map(|r| r.notes.iter()) {
            notes.push(if several {
                format!("pocket {}: {n}", p.index)
            } else {
                n.to_string()
            });
        }
        if let Some(why) = &p.skipped {
            notes.push(format!("pocket {} left out: {why}", p.index));
        }
    }
    let resolution = crate::stock::GOUGE_RESOLUTION;
    let mut k = 0;
    let pockets = part
        .pockets
        .iter()
        .map(|p| {
            let verified = if p.result.is_some() {
                k += 1;
                v.pockets
                    .get(k - 1)
                    .is_some_and(|pv| pv.problems_within(resolution).is_empty())
            } else {
                false
            };
            PocketEntry {
                index: p.index,
                area_mm2: p.area_mm2,
                strategy: p.kind.name().to_owned(),
                cycle_time_s: p.cycle_time_s,
                path_length_mm: p.result.as_ref().map_or(0.0, |r| r.toolpath.cut_length()),
                verified,
                skipped: p.skipped.clone(),
                auto: p
                    .auto
                    .as_ref()
                    .and_then(|c| pocket::auto::choose(c).map(|i| auto_entries(c, i))),
            }
        })
        .collect();
    Report {
        strategy: name,
        cycle_time_s,
        cycle_time_model: REPORT_TIME_MODEL.to_owned(),
        time_at_programmed_feed_s,
        path_length_mm: tp.cut_length(),
        rapid_length_mm: tp.rapid_length(),
        max_engagement_deg: v.total.max_engagement_deg,
        mean_engagement_deg: v.total.mean_engagement_deg,
        nominal_engagement_deg: first.map_or(0.0, |r| r.nominal_engagement_deg),
        share_above_nominal: v.total.share_above_nominal,
        stepover_mm: first.map_or(0.0, |r| r.stepover_mm),
        max_stepover_mm: v.total.max_radial_depth_mm,
        levels: tp.levels.len(),
        moves: tp.moves.len(),
        verification: v.total.clone(),
        removal_rate_mm3_s: if cycle_time_s > 0.0 {
            v.total.removed_mm3 / cycle_time_s
        } else {
            0.0
        },
        air_time_s: 0.0,
        rapid_time_s: 0.0,
        entry_time_s: 0.0,
        engagement_floor_deg: 0.0,
        problems: v.problems().iter().map(ToString::to_string).collect(),
        notes,
        auto: None,
        pockets,
    }
}

/// Where the time of a plan goes, s ([`air_times`]).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct AirTimes {
    /// In moves that remove no material, the entries aside.
    pub air: f64,
    /// The rapids' part of `air`.
    pub rapid: f64,
    /// In the entries (`entry[k]` true for move `k`).
    pub entry: f64,
}

/// The time `plan` spends in the entries' blocks (`entry[k]` true for move `k`, from
/// `stock::entry_moves`), and in the other blocks whose move removes no material
/// (`cutting[k]` false, or no flag), with the rapids' part of those. The entries are apart
/// because the stock simulation is a stack of 2D slabs: a helix's first turn in a slab
/// clears it and its other turns there remove nothing it can see, though each cuts its
/// own layer; counted as not cutting, a full-depth descent made most of a narrow pocket's
/// program read as air.
pub fn air_times(plan: &crate::motion::Plan, cutting: &[bool], entry: &[bool]) -> AirTimes {
    let mut t = AirTimes::default();
    for b in &plan.blocks {
        if entry.get(b.origin).copied().unwrap_or(false) {
            t.entry += b.time;
            continue;
        }
        if cutting.get(b.origin).copied().unwrap_or(false) {
            continue;
        }
        t.air += b.time;
        if matches!(b.kind, crate::toolpath::MoveKind::Rapid) {
            t.rapid += b.time;
        }
    }
    t
}
