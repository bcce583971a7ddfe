//! The whole job verified on one stock: the height field of the stock block cut by every
//! section of the program in order, each tool on what the previous ones left
//! (`stock::HeightField`), with per section the rapids through material and the plunges
//! (none allowed: a drill's plunges are its work; a square tab's ends are counted apart: a
//! move straight down by at most the tab's height, from no higher than its top, on a through
//! profile's path with that profile's tool, 0.05 mm allowed on heights), and at the end:
//!
//! * every outline a profile cuts through held by exactly its tabs: the bridges its slot
//!   leaves (`stock::held_by`) that join the piece to the stock are its tabs and nothing
//!   else, and without them it falls free (every path from the piece to the stock crosses
//!   the slot). A bridge is a tab when its top is at most the tab height above the stock's
//!   bottom and its neck no wider than the tab's top, ramps and lift across gentle corners
//!   (`widest_neck`; measured on the grid of cell `c`, within `4c`); when the tabs' places are known (the job's own plan) each tab must have exactly
//!   one bridge centred on it along the outline (within half its width and two cells), and
//!   when they are not (a program verified against its job file) their number must be the
//!   one asked for (at least one for `auto`);
//! * the drawn part left ([`super::design::JobDesign::compare`]).
//!
//! It reads only the toolpaths' moves and the job's design, never the strategies' results.

use super::block::StockBlock;
use super::design::{JobDesign, ProfiledOutline, TabsAsked};
use super::model::PartModel;
use super::spec::{JobTool, ToolKind};
use crate::Error;
use crate::geom::Point3;
use crate::stock::{
    BridgeOptions, CutOptions, Cutter, FieldOptions, HeightField, OperationCut, held_by,
};
use crate::strategy::profile::{BEND_MAX, PlacedTab, TAB_RAMP_RUN};
use crate::toolpath::Toolpath;
use rayon::prelude::*;

/// One section of a program: the moves of one operation (or of one tool, for a program read
/// back) and the tool that cuts them.
#[derive(Debug, Clone, Copy)]
pub struct Section<'a> {
    /// A name for messages.
    pub name: &'a str,
    /// The moves.
    pub toolpath: &'a Toolpath,
    /// The tool.
    pub tool: &'a JobTool,
}

/// One section's cut, and where its first rapid through material or plunge ends (the move's
/// index and end point).
#[derive(Debug, Clone, PartialEq)]
pub struct SectionCut {
    /// The section's name.
    pub name: String,
    /// What it did to the stock.
    pub cut: OperationCut,
    /// The first bad move, if any.
    pub first_bad: Option<(usize, Point3)>,
    /// Plunges at square tabs' ends, left out of the cut's plunges: straight down by at most
    /// a tab's height, from no higher than a tab's top, on a through profile's path (what a
    /// square tab is; ramped tabs have none).
    pub tab_end_plunges: usize,
}

/// How a profiled outline is held after the job.
#[derive(Debug, Clone, PartialEq)]
pub struct HoldCheck {
    /// The profile operation's index in the job.
    pub operation: usize,
    /// The outline's index among the operation's targets.
    pub target: usize,
    /// Tabs expected: placed by the plan, or asked for by the job file (`None`: `auto`).
    pub tabs: Option<usize>,
    /// Bridges holding the piece to the stock that look like tabs.
    pub holding: usize,
    /// With known places: the tabs with exactly one bridge on them.
    pub matched: Option<usize>,
    /// Holding bridges that are not tabs (too high, or off every tab): their centroids.
    pub stray: Vec<crate::geom::Point>,
    /// The first of them: its neck and top, and a tab's bounds, for the message.
    pub stray_detail: Option<String>,
}

impl HoldCheck {
    /// Held by exactly its tabs (with none, free).
    pub fn ok(&self) -> bool {
        self.stray.is_empty()
            && match (self.tabs, self.matched) {
                (Some(n), Some(m)) => m == n && self.holding == n,
                (Some(n), None) => self.holding == n,
                (None, _) => self.holding >= 1,
            }
    }
}

/// The whole job's check.
#[derive(Debug, Clone, PartialEq)]
pub struct JobCheck {
    /// The field's cell, mm.
    pub cell_mm: f64,
    /// Each section's cut, in order.
    pub cuts: Vec<SectionCut>,
    /// Each through-profiled outline's hold.
    pub holds: Vec<HoldCheck>,
    /// The comparison with the drawn part.
    pub design: super::design::DesignCheck,
}

impl JobCheck {
    /// What went wrong, as sentences; empty when the job passes.
    pub fn problems(&self) -> Vec<String> {
        let mut out = Vec::new();
        for c in &self.cuts {
            for p in c.cut.problems() {
                let at = c.first_bad.map_or(String::new(), |(k, q)| {
                    format!(
                        " (the first: move {k}, ending at ({:.3}, {:.3}, {:.3}))",
                        q.x, q.y, q.z
                    )
                });
                out.push(format!("{}: {p}{at}", c.name));
            }
        }
        for h in &self.holds {
            if !h.ok() {
                out.push(format!(
                    "profile {} outline {}: held by {} tab bridge(s) for {} tab(s){}{}{}",
                    h.operation + 1,
                    h.target + 1,
                    h.holding,
                    h.tabs.map_or("auto".to_owned(), |n| n.to_string()),
                    h.matched
                        .map(|m| format!(", {m} on their places"))
                        .unwrap_or_default(),
                    h.stray
                        .first()
                        .map(|p| format!(", material left joining it at ({:.3}, {:.3})", p.x, p.y))
                        .unwrap_or_default(),
                    h.stray_detail
                        .as_ref()
                        .map(|d| format!(" ({d})"))
                        .unwrap_or_default()
                ));
            }
        }
        out.extend(self.design.problems());
        out
    }

    /// The verdict when nothing is wrong: how the drawn part is left, held by its tabs,
    /// cut free (every profile without tabs) or still in the stock (no profile cuts it
    /// out).
    pub fn verdict(&self) -> &'static str {
        if self.holds.is_empty() {
            "the drawn part, left in the stock (no profile cuts it out)"
        } else if self
            .holds
            .iter()
            .all(|h| h.tabs == Some(0) && h.holding == 0)
        {
            "the drawn part, cut free (no tabs asked for)"
        } else {
            "the drawn part, held by its tabs"
        }
    }

    /// The figures, for the report.
    pub fn rows(&self) -> Vec<(String, String)> {
        let mut rows = vec![(
            "stock simulation cell".to_owned(),
            format!("{:.4} mm", self.cell_mm),
        )];
        for c in &self.cuts {
            let ends = if c.tab_end_plunges > 0 {
                format!(
                    "; {} at square tabs' ends (a tab's height)",
                    c.tab_end_plunges
                )
            } else {
                String::new()
            };
            rows.push((c.name.clone(), format!("{}{ends}", c.cut)));
        }
        for h in &self.holds {
            rows.push((
                format!("profile {} outline {} held", h.operation + 1, h.target + 1),
                if h.tabs == Some(0) && h.holding == 0 {
                    "falls free (no tabs asked for)".to_owned()
                } else {
                    format!("by {} tab(s); free without them", h.holding)
                },
            ));
        }
        rows.extend(self.design.rows());
        let p = self.problems();
        rows.push((
            "verdict".to_owned(),
            if p.is_empty() {
                self.verdict().to_owned()
            } else {
                p.join("; ")
            },
        ));
        rows
    }
}

/// Cuts `sections` into the stock in order and checks the result against `design`;
/// `placed` gives, per operation index, the tabs its plan placed (the job's own check), or
/// `None` (a program verified against its job file).
pub fn check_sections(
    model: &PartModel,
    stock: StockBlock,
    design: &JobDesign,
    sections: &[Section<'_>],
    placed: Option<&[Vec<PlacedTab>]>,
) -> Result<JobCheck, Error> {
    let smallest = sections
        .iter()
        .map(|s| s.tool.diameter)
        .fold(f64::INFINITY, f64::min);
    let fopts = FieldOptions::default().with_tool_diameter(if smallest.is_finite() {
        smallest
    } else {
        1.0
    });
    let mut field = HeightField::new(stock.bounds, stock.bottom, stock.top, &fopts)
        .map_err(|e| Error::from(e).engine_made("making the job's stock"))?;
    let mut cuts = Vec::with_capacity(sections.len());
    for s in sections {
        let cutter = if s.tool.kind == ToolKind::Drill {
            Cutter::Drill
        } else {
            Cutter::EndMill
        };
        let mut cut = field.cut_with(s.toolpath, &CutOptions::default().with_cutter(cutter));
        let before = cut.plunges.len();
        cut.plunges
            .retain(|&k| !at_a_tab_end(design, stock.bottom, s.toolpath, s.tool, k));
        let tab_end_plunges = before - cut.plunges.len();
        let first_bad = cut
            .rapids_through_material
            .iter()
            .chain(&cut.plunges)
            .min()
            .and_then(|&k| s.toolpath.moves.get(k).map(|m| (k, m.to)));
        cuts.push(SectionCut {
            name: s.name.to_owned(),
            cut,
            first_bad,
            tab_end_plunges,
        });
    }
    // Each outline's hold reads the field alone: side by side, in the design's order, and
    // beside the comparison with the drawn part.
    let holds = || -> Vec<Result<HoldCheck, Error>> {
        design
            .profiles
            .par_iter()
            .filter(|p| p.through)
            .map(|p| {
                let tabs = placed.map(|all| {
                    all.get(p.operation)
                        .map(|t| {
                            t.iter()
                                .filter(|t| t.target == p.target)
                                .cloned()
                                .collect::<Vec<PlacedTab>>()
                        })
                        .unwrap_or_default()
                });
                hold(&field, p, stock.bottom, tabs.as_deref())
            })
            .collect()
    };
    let (holds, design_check) = rayon::join(holds, || design.compare(model, &field, stock.bottom));
    let holds = holds.into_iter().collect::<Result<Vec<_>, _>>()?;
    Ok(JobCheck {
        cell_mm: field.cell(),
        cuts,
        holds,
        design: design_check,
    })
}

/// The hold of one through-profiled outline.
fn hold(
    field: &HeightField,
    p: &ProfiledOutline,
    bottom: f64,
    placed: Option<&[PlacedTab]>,
) -> Result<HoldCheck, Error> {
    let verdict = held_by(
        field,
        &p.outline,
        bottom,
        p.tool_radius,
        &BridgeOptions::default().with_side(p.side),
    )
    .map_err(|e| Error::from(e).engine_made("reading the bridges of a profile"))?;
    // A tab's top is at most its height above the bottom (and the z rounding), and it is no
    // wider at its neck than its top, its ramps and its lift across gentle corners.
    let tab_top = bottom + p.tab_height + 0.01;
    let widest = widest_neck(p.tab_width, p.tab_height, p.tool_radius) + 4.0 * verdict.cell_mm;
    let holding: Vec<_> = verdict.holding().collect();
    let (tabs, low): (Vec<&crate::stock::Bridge>, Vec<&crate::stock::Bridge>) = holding
        .iter()
        .copied()
        .partition(|b| b.top_max <= tab_top && b.neck_mm <= widest);
    let mut stray: Vec<_> = low.iter().map(|b| b.centroid).collect();
    let detail = |b: &crate::stock::Bridge| {
        format!(
            "neck {:.3} mm, top z {:.3}; a tab's: at most {widest:.3} mm, z {tab_top:.3}",
            b.neck_mm, b.top_max
        )
    };
    let mut stray_detail = low.first().map(|b| detail(b));
    let perimeter = verdict.perimeter_mm;
    let along = |a: f64, b: f64| {
        let d = (a - b).rem_euclid(perimeter);
        d.min(perimeter - d)
    };
    let slack = 2.0 * verdict.cell_mm;
    let matched = placed.map(|placed| {
        let mut used = vec![false; tabs.len()];
        let mut matched = 0;
        for t in placed {
            let on: Vec<usize> = tabs
                .iter()
                .enumerate()
                .filter(|(_, b)| along(b.middle_mm(), t.s) <= 0.5 * t.width + slack)
                .map(|(k, _)| k)
                .collect();
            if let [k] = on[..] {
                matched += 1;
                used[k] = true;
            }
        }
        let unused: Vec<_> = tabs.iter().zip(&used).filter(|(_, u)| !**u).collect();
        if stray_detail.is_none() {
            stray_detail = unused.first().map(|(b, _)| detail(b));
        }
        stray.extend(unused.iter().map(|(b, _)| b.centroid));
        matched
    });
    let expected = match (placed, p.tabs) {
        (Some(t), _) => Some(t.len()),
        (None, TabsAsked::None) => Some(0),
        (None, TabsAsked::Count(n)) => Some(n),
        (None, TabsAsked::Auto) => None,
    };
    Ok(HoldCheck {
        operation: p.operation,
        target: p.target,
        tabs: expected,
        holding: tabs.len(),
        matched,
        stray,
        stray_detail,
    })
}

/// The widest neck a tab of top width `w` and height `h` cut by a tool of radius `r` may
/// have, mm, before the grid's error: a tab may sit across gentle corners of a run of lines
/// turning `β ≤` [`BEND_MAX`] in all, where the tool is lifted over `w/2 + dβ + r/cos(β/2)`
/// of path either side (`d` the path's offset, `r` here: a through profile's finishing
/// offset is the radius and half its tolerance). At the slot's middle (the path) the tool
/// at the lift's ends takes at least `r` of path, so at most `w + 2dβ + 2r(1/cos(β/2) − 1)`
/// of path stands; measured along the outline, the path's outside corners shrink and its
/// inside corners stretch it by `2d·tan(τ/2)` for a turn `τ`, at most `2d·tan(β/2)` in all
/// (`tan` grows faster than linearly). A ramped tab adds `TAB_RAMP_RUN·h` either side.
fn widest_neck(w: f64, h: f64, r: f64) -> f64 {
    let b = BEND_MAX;
    w + 2.0 * TAB_RAMP_RUN * h
        + 2.0 * r * b
        + 2.0 * r * (1.0 / (0.5 * b).cos() - 1.0)
        + 2.0 * r * (0.5 * b).tan()
}

/// Move `k` of `tp` goes straight down at a square tab's end of one of the design's through
/// profiles cut with `tool` (module docs); below the stock's bottom there is no material.
fn at_a_tab_end(
    design: &JobDesign,
    stock_bottom: f64,
    tp: &Toolpath,
    tool: &JobTool,
    k: usize,
) -> bool {
    const TOL: f64 = 0.05;
    let Some((from, m)) = tp.segments().nth(k) else {
        return false;
    };
    let (a, b) = (from, m.to);
    if a.xy().distance(b.xy()) > 1e-6 || b.z >= a.z {
        return false;
    }
    let r = 0.5 * tool.diameter;
    design.profiles.iter().any(|p| {
        p.through
            && p.tabs != TabsAsked::None
            && (p.tool_radius - r).abs() <= 1e-9
            && a.z - b.z.max(stock_bottom) <= p.tab_height + TOL
            && a.z <= stock_bottom + p.tab_height + TOL
            && {
                let d = p.outline.distance_to(b.xy());
                d >= r - TOL && d <= r + 1.0
            }
    })
}
