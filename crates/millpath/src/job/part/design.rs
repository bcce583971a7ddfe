//! What a job means to make, from its file and its drawing alone (never from the toolpaths):
//! the regions its operations cut down to a floor, the outlines its profiles cut free with the
//! tabs asked for, and the parts' material, which no operation may cut into.
//!
//! * a pocket operation: each pocket it selects, down to its depth (less the floor stock),
//!   its tool keeping the wall stock;
//! * a drill or bore operation: each hole in its diameter range, down to its depth (a drill's
//!   point below a through hole's depth is the stock's bottom: nothing is below it);
//! * a profile operation: each outline it cuts, outside (the parts) or inside (their pockets
//!   as windows), through the stock or not, with its tabs;
//! * the parts' material: inside each part, outside every region and every window an inside
//!   profile cuts free (its slug may stay, held by tabs, or fall out), at the part's top
//!   (z = 0).
//!
//! [`JobDesign::compare`] compares a height field with it, cell by cell
//! (`stock::check_field`): nothing cut into a part or below a floor; no material a region's
//! tool could reach left above its floor. Features no operation cuts are left as the stock
//! has them.

use super::model::PartModel;
use super::spec::{JobSpec, OperationKind};
use crate::Error;
use crate::geom::{Hole, Outline, Point};
use crate::job::pocket::parse_select;
use crate::stock::{CheckOptions, CutSide, FieldCheck, Floor, HeightField, PartTop, check_field};
use rayon::prelude::*;

/// A region an operation cuts down to a floor.
#[derive(Debug, Clone)]
pub struct FloorRegion {
    /// The part it is in (index into the model's parts).
    pub part: usize,
    /// Its boundary.
    pub outer: Outline,
    /// Its islands.
    pub islands: Vec<Outline>,
    /// The floor, mm.
    pub z: f64,
    /// The radius the tool keeps from its walls (tool radius plus wall stock), mm.
    pub reach_radius: f64,
}

/// The tabs a profile asks for on an outline.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TabsAsked {
    /// None: the piece falls free.
    None,
    /// This many.
    Count(usize),
    /// As many as the perimeter calls for (at least one).
    Auto,
}

/// An outline a profile cuts free.
#[derive(Debug, Clone)]
pub struct ProfiledOutline {
    /// The operation's index in the job.
    pub operation: usize,
    /// The outline's index among the operation's targets.
    pub target: usize,
    /// The part it is (outside) or is in (inside; index into the model's parts).
    pub part: usize,
    /// The outline.
    pub outline: Outline,
    /// Outside (a part) or inside (a window).
    pub side: CutSide,
    /// The cut goes through the stock.
    pub through: bool,
    /// The tabs asked for.
    pub tabs: TabsAsked,
    /// The tabs' height above the stock's bottom, mm.
    pub tab_height: f64,
    /// The tabs' top width along the outline, mm.
    pub tab_width: f64,
    /// The radius of the profile's tool, mm.
    pub tool_radius: f64,
}

/// What a job means to make.
#[derive(Debug, Clone)]
pub struct JobDesign {
    /// The regions cut down to a floor.
    pub floors: Vec<FloorRegion>,
    /// The outlines profiles cut.
    pub profiles: Vec<ProfiledOutline>,
}

/// The comparison of every part with its drawing.
#[derive(Debug, Clone, PartialEq)]
pub struct DesignCheck {
    /// Per part, in the model's order.
    pub parts: Vec<FieldCheck>,
}

impl DesignCheck {
    /// The deviations, as sentences.
    pub fn problems(&self) -> Vec<String> {
        self.parts
            .iter()
            .enumerate()
            .filter(|(_, c)| !c.passes())
            .map(|(i, c)| format!("part {}: {c}", i + 1))
            .collect()
    }

    /// One row per part.
    pub fn rows(&self) -> Vec<(String, String)> {
        self.parts
            .iter()
            .enumerate()
            .map(|(i, c)| {
                let uncut: f64 = c.uncut_mm2.iter().sum();
                (
                    format!("part {} against the drawing", i + 1),
                    format!("{c} (reachable material left {uncut:.3} mm²)"),
                )
            })
            .collect()
    }
}

/// The default tab height of a job's profile: a third of the stock's thickness, at most
/// the tool's radius (so that a ramped tab's ramps, twice its height either side, run a
/// tool diameter at most: a small tool cuts a small part, whose tabs are small too).
pub fn default_tab_height(thickness: f64, tool_diameter: f64) -> f64 {
    (thickness / 3.0).min(0.5 * tool_diameter)
}

/// The default tab width of a job's profile: twice the tool's diameter, at least 3 mm.
pub fn default_tab_width(tool_diameter: f64) -> f64 {
    (2.0 * tool_diameter).max(3.0)
}

/// A hole's circle as an outline (two half arcs).
pub fn circle(h: &Hole) -> Result<Outline, Error> {
    let r = h.radius();
    Ok(Outline::new(
        &[
            (Point::new(h.center.x + r, h.center.y), 1.0),
            (Point::new(h.center.x - r, h.center.y), 1.0),
        ],
        "a hole's circle",
    )?)
}

impl JobDesign {
    /// The design of `spec` on the drawing's `model` (module docs). Errors are the job
    /// file's: a selection or a side that does not parse.
    pub fn new(spec: &JobSpec, model: &PartModel) -> Result<Self, Error> {
        let mut floors = Vec::new();
        let mut profiles = Vec::new();
        let thickness = spec.stock.thickness;
        for (k, op) in spec.operations.iter().enumerate() {
            let Some(tool) = spec.tool(op.tool) else {
                continue;
            };
            let r = 0.5 * tool.diameter;
            match &op.kind {
                OperationKind::Face(_) => {}
                OperationKind::Pocket(s, select) => {
                    if model.pockets.is_empty() {
                        continue;
                    }
                    for i in parse_select(select.as_deref(), model.pockets.len())? {
                        let p = &model.pockets[i - 1];
                        floors.push(FloorRegion {
                            part: p.part,
                            outer: p.outer.clone(),
                            islands: p.islands.clone(),
                            z: -s.depth + s.floor_stock,
                            reach_radius: r + s.wall_stock,
                        });
                    }
                }
                OperationKind::Drill(s) => {
                    for h in model
                        .holes
                        .iter()
                        .filter(|h| h.diameter >= s.min_diameter && h.diameter <= s.max_diameter)
                    {
                        floors.push(FloorRegion {
                            part: h.part,
                            outer: circle(&Hole::new(h.center, h.diameter))?,
                            islands: Vec::new(),
                            z: -spec.depth_mm(s.depth),
                            // A drill of the hole's size leaves nothing in it; taking half
                            // its radius for the reach asks for the hole's disc less 2 cells.
                            reach_radius: 0.25 * h.diameter,
                        });
                    }
                }
                OperationKind::Bore(s) => {
                    for h in model
                        .holes
                        .iter()
                        .filter(|h| h.diameter >= s.min_diameter && h.diameter <= s.max_diameter)
                    {
                        floors.push(FloorRegion {
                            part: h.part,
                            outer: circle(&Hole::new(h.center, h.diameter))?,
                            islands: Vec::new(),
                            z: -spec.depth_mm(s.depth),
                            reach_radius: r,
                        });
                    }
                }
                OperationKind::Profile(s) => {
                    let selected = parse_select(s.select.as_deref(), model.parts.len())?;
                    let inside = s.side == "inside";
                    let on = s.side == "on";
                    let through = spec.depth_mm(s.depth) >= thickness;
                    let tabs = if !through || on {
                        TabsAsked::None
                    } else {
                        match s.tabs.as_str() {
                            "auto" => TabsAsked::Auto,
                            "0" | "none" => TabsAsked::None,
                            n => n.parse().map_or(TabsAsked::Auto, TabsAsked::Count),
                        }
                    };
                    let mut outlines: Vec<(usize, Outline)> = Vec::new();
                    for &i in &selected {
                        if inside {
                            outlines.extend(
                                model
                                    .pockets
                                    .iter()
                                    .filter(|p| p.part == i - 1)
                                    .map(|p| (p.part, p.outer.clone())),
                            );
                        } else if !on {
                            outlines.push((i - 1, model.parts[i - 1].clone()));
                        }
                    }
                    for (target, (part, outline)) in outlines.into_iter().enumerate() {
                        profiles.push(ProfiledOutline {
                            operation: k,
                            target,
                            part,
                            outline,
                            side: if inside {
                                CutSide::Inside
                            } else {
                                CutSide::Outside
                            },
                            through,
                            tabs,
                            tab_height: s
                                .tab_height
                                .unwrap_or_else(|| default_tab_height(thickness, tool.diameter)),
                            tab_width: s
                                .tab_width
                                .unwrap_or_else(|| default_tab_width(tool.diameter)),
                            tool_radius: r,
                        });
                    }
                }
            }
        }
        Ok(JobDesign { floors, profiles })
    }

    /// Compares `field` (after every operation) with the design, part by part; the field
    /// stops at the stock's bottom (`bottom`), so floors below it are taken at it.
    pub fn compare(&self, model: &PartModel, field: &HeightField, bottom: f64) -> DesignCheck {
        let opts = CheckOptions::default();
        // Each part's comparison reads the field alone: side by side, in the model's order.
        let parts = model
            .parts
            .par_iter()
            .enumerate()
            .map(|(i, outline)| {
                let floors: Vec<Floor<'_>> = self
                    .floors
                    .iter()
                    .filter(|f| f.part == i)
                    .map(|f| Floor {
                        outer: &f.outer,
                        islands: &f.islands,
                        z: f.z.max(bottom),
                        tool_radius: f.reach_radius,
                    })
                    .collect();
                let windows: Vec<Outline> = self
                    .profiles
                    .iter()
                    .filter(|p| p.part == i && p.side == CutSide::Inside)
                    .map(|p| p.outline.clone())
                    .collect();
                check_field(
                    field,
                    Some(PartTop {
                        outline,
                        windows: &windows,
                        top_z: 0.0,
                    }),
                    &floors,
                    &opts,
                )
            })
            .collect();
        DesignCheck { parts }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A tab is at most a third of the stock and the tool's radius high, so that its ramps
    /// (twice its height either side) run a tool diameter at most: a 0.0766 mm tool on a
    /// 0.5 mm part got 0.2 mm tabs, whose ramps no flank of a 3.5 mm gear held.
    #[test]
    fn tabs_are_sized_from_the_stock_and_the_tool() {
        let mut checked = 0;
        for t in [0.5, 1.0, 3.0, 16.0, 40.0] {
            for d in [0.0291, 0.0766, 0.2326, 1.0, 3.0, 16.0] {
                let h = default_tab_height(t, d);
                assert!(
                    h > 0.0 && h <= t / 3.0 + 1e-12 && h <= 0.5 * d + 1e-12,
                    "{t} {d}: {h}"
                );
                // The larger of the two bounds is not the one that holds.
                assert!((h - (t / 3.0).min(0.5 * d)).abs() < 1e-12, "{t} {d}: {h}");
                assert!(crate::strategy::profile::TAB_RAMP_RUN * h <= d + 1e-12);
                checked += 1;
            }
        }
        assert_eq!(checked, 30);
    }
}
