//! A job's drill and bore operations: the part model's holes in a diameter range, drilled
//! with the dialect's canned cycles (a drill of the hole's diameter) or helix-bored with a
//! finishing circle (an end mill smaller than the hole), in a short order
//! (`strategy::drill`); each hole's cut envelope checked against the drawn circle.
//!
//! A drilled hole "through" goes the stock's thickness, the breakthrough and the drill's
//! point (0.3 of its diameter, a 118° point) deep, so that its full diameter runs through.

use super::context::{OpContext, OpResult};
use super::spec::{BoreSettings, Depth, DrillSettings, JobOperation, JobTool};
use crate::Error;
use crate::error::InputError;
use crate::geom::Hole;
use crate::strategy::drill::{self, DrillCycle, HoleOptions, HoleResult};
use crate::toolpath::Tool;

/// The length of a 118° drill point, as a share of the diameter.
const POINT_SHARE: f64 = 0.3;

/// The model's holes within `[min, max]` mm, each with its 1-based index.
fn holes_in(cx: &OpContext<'_>, min: f64, max: f64) -> Vec<(usize, Hole)> {
    cx.model
        .holes
        .iter()
        .enumerate()
        .filter(|(_, h)| h.diameter >= min && h.diameter <= max)
        .map(|(i, h)| (i + 1, Hole::new(h.center, h.diameter)))
        .collect()
}

fn tool_of(tool: &JobTool) -> Result<Tool, InputError> {
    super::context::end_mill(tool)
}

fn none_in_range(min: f64, max: f64, what: &str) -> Error {
    InputError::new("holes in the diameter range", 0)
        .at(format!("min_diameter {min} mm, max_diameter {max} mm"))
        .expected(format!(
            "a range holding some of the drawing's holes (circles inside a part) to {what}"
        ))
        .into()
}

fn base_options(cx: &OpContext<'_>, depth: f64) -> HoleOptions {
    HoleOptions::default()
        .with_top(0.0)
        .with_depth(depth)
        .with_clearance_height(cx.clearance_z())
        .with_retract_height(cx.spec.safe_height.min(cx.clearance_z()))
}

/// What a hole plan made, as an operation's result.
fn result(planned: HoleResult, t: &Tool, depth: f64, what: &str) -> Result<OpResult, Error> {
    let cut: Vec<_> = planned.holes.iter().filter(|h| h.op.is_cut()).collect();
    let holes: Vec<Hole> = cut.iter().map(|h| h.hole).collect();
    let moves: Vec<_> = planned.toolpath.segments().map(|(f, m)| (f, *m)).collect();
    let v = crate::stock::verify_holes(
        &holes,
        &moves,
        t,
        0.0,
        -depth,
        crate::geom::CIRCLE_TOLERANCE,
    );
    if !v.ok() {
        return Err(Error::internal(format!(
            "the {what} holes' toolpath fails its check against the drawn circles: {}; \
             nothing written",
            v.problems
                .iter()
                .map(ToString::to_string)
                .collect::<Vec<_>>()
                .join("; ")
        )));
    }
    let (centre, round) = v.holes.iter().flatten().fold((0.0f64, 0.0f64), |a, h| {
        (a.0.max(h.center_error_mm), a.1.max(h.roundness_mm))
    });
    let mut sizes: Vec<String> = Vec::new();
    for h in &cut {
        let s = format!("⌀{:.3}", h.hole.diameter);
        if !sizes.contains(&s) {
            sizes.push(s);
        }
    }
    Ok(OpResult {
        toolpath: planned.toolpath,
        cut: format!(
            "{} hole(s) {what} ({} mm), {depth:.3} mm deep",
            cut.len(),
            sizes.join(", ")
        ),
        checks: vec![(
            "holes against the drawn circles".to_owned(),
            format!(
                "centres within {centre:.4} mm, radius within {round:.4} mm all round (to {} mm)",
                crate::geom::CIRCLE_TOLERANCE
            ),
        )],
        tabs: Vec::new(),
        holes,
    })
}

/// Drills the holes in the range with `tool` (a drill of their diameter).
pub(crate) fn drill(
    cx: &OpContext<'_>,
    op: &JobOperation,
    tool: &JobTool,
    s: &DrillSettings,
    note: &mut dyn FnMut(String),
) -> Result<OpResult, Error> {
    let found = holes_in(cx, s.min_diameter, s.max_diameter);
    if found.is_empty() {
        return Err(none_in_range(s.min_diameter, s.max_diameter, "drill"));
    }
    let depth = match s.depth {
        Depth::Mm(d) => d,
        Depth::Through => cx.spec.depth_mm(Depth::Through) + POINT_SHARE * tool.diameter,
    };
    let cycle = match (s.peck, s.chip_break, s.dwell) {
        (Some(q), None, _) => DrillCycle::Peck { step: q },
        (None, Some(q), _) => DrillCycle::ChipBreak { step: q },
        (None, None, Some(t)) if t > 0.0 => DrillCycle::Dwell { seconds: t },
        (None, None, _) => DrillCycle::Drill,
        (Some(_), Some(_), _) => {
            return Err(InputError::new("peck and chip_break", "both")
                .at("--peck")
                .expected("one of them: peck (G83) or chip_break (G73)")
                .into());
        }
    };
    let opts = base_options(cx, depth)
        .with_cycle(cycle)
        .with_drill_feed(op.feed.unwrap_or(tool.feed));
    let t = tool_of(tool)?;
    let planned = drill::drill(&found, &t, &opts)?;
    for h in planned.holes.iter().filter(|h| !h.op.is_cut()) {
        note(format!(
            "{}: {} {}",
            op.name,
            drill::describe(h.index, &h.hole),
            h.op
        ));
    }
    result(planned, &t, depth, "drilled")
}

/// Bores the holes in the range with `tool` (an end mill smaller than them).
pub(crate) fn bore(
    cx: &OpContext<'_>,
    op: &JobOperation,
    tool: &JobTool,
    s: &BoreSettings,
    note: &mut dyn FnMut(String),
) -> Result<OpResult, Error> {
    let found = holes_in(cx, s.min_diameter, s.max_diameter);
    if found.is_empty() {
        return Err(none_in_range(s.min_diameter, s.max_diameter, "bore"));
    }
    let depth = cx.spec.depth_mm(s.depth);
    if depth > tool.flute_length {
        return Err(InputError::new("depth", depth)
            .at("--depth")
            .expected(format!(
                "at most the tool's flute length, {} mm (T{}): a longer tool",
                tool.flute_length, tool.number
            ))
            .into());
    }
    let opts = base_options(cx, depth)
        .with_bore_feed(op.feed.unwrap_or(tool.feed))
        .with_pitch(s.pitch.unwrap_or((0.2 * tool.diameter).max(0.05)));
    let t = tool_of(tool)?;
    let planned = drill::bore(&found, &t, &opts)?;
    for h in planned.holes.iter().filter(|h| !h.op.is_cut()) {
        note(format!(
            "{}: {} {}",
            op.name,
            drill::describe(h.index, &h.hole),
            h.op
        ));
    }
    result(planned, &t, depth, "bored")
}
