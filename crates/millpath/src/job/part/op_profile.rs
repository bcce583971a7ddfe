//! A job's profile operation: the selected parts cut out (outside, or on the line), or their
//! pockets' outlines cut through as windows (inside), with `strategy::profile`; verified by
//! the profile's own checks (the dense band against the drawn outline, the exact clearance,
//! the tabs' middle lines) before the whole job's stock check reads the tabs' bridges.

use super::context::{OpContext, OpResult, end_mill};
use super::spec::{Depth, JobOperation, JobTool, ProfileSettings};
use crate::Error;
use crate::error::InputError;
use crate::job::pocket::parse_select;
use crate::strategy::pocket::Direction;
use crate::strategy::profile::{
    self, ProfileEntry, ProfileOptions, ProfileSide, ProfileTarget, TabCount, TabOptions, TabShape,
};

/// Plans the profile.
pub(crate) fn plan(
    cx: &OpContext<'_>,
    op: &JobOperation,
    tool: &JobTool,
    s: &ProfileSettings,
    note: &mut dyn FnMut(String),
) -> Result<OpResult, Error> {
    let t = end_mill(tool)?;
    let model = cx.model;
    let selected =
        parse_select(s.select.as_deref(), model.parts.len()).map_err(|e| e.at("--select"))?;
    let side = match s.side.as_str() {
        "auto" | "outside" => ProfileSide::Outside,
        "inside" => ProfileSide::Inside,
        "on" => ProfileSide::On,
        other => {
            return Err(InputError::new("side", other)
                .at("--side")
                .expected("auto, outside, inside or on")
                .into());
        }
    };
    let mut targets = Vec::new();
    for &i in &selected {
        if side == ProfileSide::Inside {
            for p in model.pockets.iter().filter(|p| p.part == i - 1) {
                targets.push(ProfileTarget {
                    outline: p.outer.clone(),
                    side,
                });
            }
        } else {
            targets.push(ProfileTarget {
                outline: model.parts[i - 1].clone(),
                side,
            });
        }
    }
    if targets.is_empty() {
        return Err(InputError::new("outlines to profile", 0)
            .at("--side")
            .expected(
                "a side with outlines to cut: the selected parts have no pockets to cut inside",
            )
            .into());
    }
    let thickness = cx.spec.stock.thickness;
    let depth = cx.spec.depth_mm(s.depth);
    let through = depth >= thickness;
    if depth > tool.flute_length {
        return Err(InputError::new("depth", depth)
            .at("--depth")
            .expected(format!(
                "at most the tool's flute length, {} mm (T{}): a longer tool",
                tool.flute_length, tool.number
            ))
            .into());
    }
    let count = match s.tabs.as_str() {
        "auto" => TabCount::Auto,
        "0" | "none" => TabCount::None,
        n => match n.parse::<usize>() {
            Ok(k) => TabCount::Count(k),
            Err(_) => {
                return Err(InputError::new("tabs", n)
                    .at("--tabs")
                    .expected("a count, \"auto\" or 0")
                    .into());
            }
        },
    };
    let count = if through && side != ProfileSide::On {
        count
    } else {
        TabCount::None
    };
    let tab_height = s
        .tab_height
        .unwrap_or_else(|| super::design::default_tab_height(thickness, tool.diameter));
    if count != TabCount::None && tab_height >= thickness {
        return Err(InputError::new("tab height", tab_height)
            .at("--tab-height")
            .expected(format!("less than the stock's thickness {thickness} mm"))
            .into());
    }
    if count != TabCount::None && side != ProfileSide::Inside {
        frame_for_tabs(cx, &targets, &selected, tool.diameter + s.stock_to_leave)?;
    }
    let mut opts = ProfileOptions::default()
        .with_top_z(0.0)
        .with_depth(depth)
        .with_stock_thickness(Some(thickness))
        .with_step_down(s.step_down.unwrap_or(tool.diameter.min(depth)))
        .with_stock_to_leave(s.stock_to_leave)
        .with_direction(if s.conventional {
            Direction::Conventional
        } else {
            Direction::Climb
        })
        .with_entry(match s.entry.as_str() {
            "ramp" => ProfileEntry::Ramp,
            "helix" => ProfileEntry::Helix,
            e => {
                return Err(InputError::new("entry", e)
                    .at("--entry")
                    .expected("ramp or helix")
                    .into());
            }
        })
        .with_tolerance(s.tolerance)
        .with_rounding(cx.rounding)
        .with_feed(op.feed.unwrap_or(tool.feed))
        .with_plunge_feed(op.plunge_feed.unwrap_or(tool.plunge_feed))
        .with_safe_height(cx.clearance_z())
        .with_clearance_height(cx.spec.safe_height.min(cx.clearance_z()))
        .with_tabs(
            TabOptions::default()
                .with_count(count)
                .with_width(
                    s.tab_width
                        .unwrap_or_else(|| super::design::default_tab_width(tool.diameter)),
                )
                .with_height(tab_height)
                .with_shape(match s.tab_shape.as_str() {
                    "square" => TabShape::Square,
                    "ramped" => TabShape::Ramped,
                    e => {
                        return Err(InputError::new("tab shape", e)
                            .at("--tab-shape")
                            .expected("square or ramped")
                            .into());
                    }
                }),
        );
    if let Some(r) = s.lead_radius {
        opts = opts.with_lead_radius(r);
    } else {
        opts = opts.with_lead_radius((0.5 * tool.diameter).max(0.5));
    }
    let result = profile::generate(&targets, &t, &opts)?;
    for n in &result.notes {
        note(format!("{}: {n}", op.name));
    }
    // Tabs asked for and none fit: the piece would fall free as it is cut out.
    for n in &result.notes {
        if let profile::ProfileNote::FewerTabs {
            target,
            asked,
            placed: 0,
        } = n
            && *asked > 0
        {
            let width = opts.tabs.width;
            return Err(InputError::new("tab width", width)
                .at("--tab-width")
                .expected(format!(
                    "tabs that fit on outline {} ({} of the operation's): none of the {asked} \
                     tabs of {width} mm fits on its straight stretches and long arcs, and the \
                     piece would fall free; a narrower tab_width, or tabs = 0 to let it fall",
                    target + 1,
                    targets.len()
                ))
                .into());
        }
    }
    let (rows, min_clearance) = crate::job::profile_check::verify(&targets, &result, &t, &opts)?;
    let band = rows
        .iter()
        .map(|r| (r.band_min_mm - r.offset_mm, r.band_max_mm - r.offset_mm))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |a, b| {
            (a.0.min(b.0), a.1.max(b.1))
        });
    let what = if side == ProfileSide::Inside {
        format!("{} window(s) inside", targets.len())
    } else {
        format!(
            "part(s) {} {side}",
            selected
                .iter()
                .map(ToString::to_string)
                .collect::<Vec<_>>()
                .join(", ")
        )
    };
    let depth_text = match s.depth {
        Depth::Through => format!("through ({depth:.3} mm)"),
        Depth::Mm(d) => format!("{d:.3} mm deep"),
    };
    Ok(OpResult {
        toolpath: result.toolpath,
        cut: format!("{what}, {depth_text}, {} tab(s)", result.tabs.len()),
        checks: vec![
            (
                "path from the exact offset (dense check)".to_owned(),
                format!(
                    "{:+.4} to {:+.4} mm (tolerance {} mm)",
                    band.0, band.1, s.tolerance
                ),
            ),
            (
                "min clearance".to_owned(),
                format!("{min_clearance:.4} mm (needs {:.4})", t.radius()),
            ),
        ],
        tabs: result.tabs,
        holes: Vec::new(),
    })
}

/// Refuses a block with no frame for the tabs to hold to: a through profile outside a part
/// cuts a slot one tool diameter `slot` (plus the stock left) wide around it, and where
/// that slot reaches past the block's edge the tabs join the part to nothing (the job's
/// stock check would find the part held by fewer bridges than tabs). Names the `[stock]`
/// key to change; `parts` numbers the targets' parts (from 1).
fn frame_for_tabs(
    cx: &OpContext<'_>,
    targets: &[ProfileTarget],
    parts: &[usize],
    slot: f64,
) -> Result<(), Error> {
    let block = cx.stock.bounds;
    // Rounding of the block's corners from the text: far below any cell the check uses.
    let eps = 1e-9 * (1.0 + block.width().max(block.height()));
    for (i, t) in targets.iter().enumerate() {
        let b = t.outline.bounds();
        let room = (b.min.x - block.min.x)
            .min(b.min.y - block.min.y)
            .min(block.max.x - b.max.x)
            .min(block.max.y - b.max.y);
        if room + eps < slot {
            let s = &cx.spec.stock;
            let (key, value, fix) = if s.size.is_some() || s.origin.is_some() {
                (
                    "stock size",
                    format!("{:.3} × {:.3} mm", block.width(), block.height()),
                    format!("a block reaching at least {slot} mm past every part"),
                )
            } else {
                (
                    "stock margin",
                    format!("{} mm", s.margin),
                    format!("a margin of at least {slot} mm"),
                )
            };
            return Err(InputError::new(key, value)
                .at("[stock]")
                .expected(format!(
                    "a block leaving the slot around part {} ({slot} mm: the profile tool's \
                     diameter and the stock left) inside it, for its tabs to hold to a frame \
                     ({room:.3} mm from the part to the block's edge): {fix}, or tabs = 0",
                    parts.get(i).copied().unwrap_or(i + 1)
                ))
                .into());
        }
    }
    Ok(())
}
