//! A job file's `pocket` operation: its keys are `millpath pocket`'s flags (with `_` for
//! `-`), read into [`PocketSettings`]; the tool's diameter and feed come from the tool table.

use super::keys::Keys;
use crate::error::InputError;
use crate::job::pocket::PocketSettings;

/// The keys a pocket operation takes besides the common ones.
pub(crate) const KEYS: &[&str] = &[
    "select",
    "strategy",
    "stepover",
    "depth",
    "step_down",
    "wall_stock",
    "floor_stock",
    "conventional",
    "entry",
    "helix_radius",
    "ramp_angle",
    "slowdown",
    "angle",
    "transition",
    "min_radius",
    "morph",
    "arcs",
    "both_ways",
    "lift",
    "finish",
    "no_feed_modulation",
    "cell",
    "rest_from",
];

/// What a pocket operation takes from its tool: diameter and flute length (mm), feed (mm/s).
#[derive(Debug, Clone, Copy)]
pub(crate) struct ToolSize {
    pub(crate) diameter: f64,
    pub(crate) flute_length: f64,
    pub(crate) feed: f64,
}

/// Reads a pocket operation's settings (checked later by the pocket job, with these keys'
/// names) and its `select`.
pub(crate) fn read(
    k: &Keys<'_, '_>,
    tool: ToolSize,
) -> Result<(PocketSettings, Option<String>), InputError> {
    let mut s = PocketSettings {
        tool_diameter: tool.diameter,
        feed: format!("{}", tool.feed * 60.0),
        ..PocketSettings::default()
    };
    if let Some(v) = k.str("strategy")? {
        s.strategy = v;
    }
    s.stepover = crate::job::pocket::default_stepover(&s.strategy).to_owned();
    if let Some(v) = k.text("stepover")? {
        s.stepover = v;
    }
    s.depth = k.positive("depth", "mm")?.ok_or_else(|| {
        InputError::new("depth", "missing")
            .at(k.at_line(k.line()))
            .expected("depth = 3.0 (mm below the part's top)")
    })?;
    s.step_down = k.positive("step_down", "mm")?.unwrap_or_else(|| {
        if s.strategy == "adaptive" {
            s.depth.min(tool.flute_length)
        } else {
            s.depth.min(tool.flute_length).min(tool.diameter)
        }
    });
    let set = |x: &mut f64, v: Option<f64>| {
        if let Some(v) = v {
            *x = v;
        }
    };
    set(&mut s.wall_stock, k.non_negative("wall_stock", "mm")?);
    set(&mut s.floor_stock, k.non_negative("floor_stock", "mm")?);
    if let Some(v) = k.positive("helix_radius", "mm")? {
        s.helix_radius = Some(v);
    }
    set(&mut s.ramp_angle, k.positive("ramp_angle", "degrees")?);
    set(&mut s.slowdown, k.fraction("slowdown")?);
    set(&mut s.angle, k.f64("angle")?);
    set(&mut s.min_radius, k.non_negative("min_radius", "mm")?);
    s.transition = k.f64("transition")?;
    s.cell = k.positive("cell", "mm")?;
    if let Some(v) = k.str("entry")? {
        s.entry = v;
    }
    s.morph = k.str("morph")?;
    s.conventional = k.bool("conventional")?.unwrap_or(false);
    s.arcs = k.bool("arcs")?.unwrap_or(false);
    s.both_ways = k.bool("both_ways")?.unwrap_or(false);
    set(&mut s.lift, k.non_negative("lift", "mm")?);
    s.finish = k.bool("finish")?.unwrap_or(false);
    s.no_feed_modulation = k.bool("no_feed_modulation")?.unwrap_or(false);
    Ok((s, k.text("select")?))
}
