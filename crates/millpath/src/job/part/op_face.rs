//! A job's face operation: the stock's top rectangle cut down to the part's top (z = 0) with
//! `strategy::face`; the whole job's stock check verifies it (the part's top as drawn).

use super::context::{OpContext, OpResult, end_mill};
use super::spec::{FaceSettings, JobOperation, JobTool};
use crate::Error;
use crate::error::InputError;
use crate::strategy::face::{FaceOptions, face};

/// Plans the facing.
pub(crate) fn plan(
    cx: &OpContext<'_>,
    op: &JobOperation,
    tool: &JobTool,
    s: &FaceSettings,
) -> Result<OpResult, Error> {
    let depth = cx.stock.top;
    if depth <= 0.0 {
        return Err(InputError::new("[stock] top", depth)
            .at("the face operation")
            .expected(
                "the material above the part's top to face off, > 0 mm (the stock's top is \
                 the part's: leave the face operation out)",
            )
            .into());
    }
    let step_down = s.step_down.unwrap_or(tool.flute_length).min(depth);
    if step_down > tool.flute_length {
        return Err(InputError::new("step_down", step_down)
            .at("the face operation")
            .expected(format!(
                "at most the tool's flute length ({} mm)",
                tool.flute_length
            ))
            .into());
    }
    let opts = FaceOptions::default()
        .with_top_z(cx.stock.top)
        .with_depth(depth)
        .with_step_down(step_down)
        .with_stepover(s.stepover)
        .with_safe_height(cx.spec.clearance_height)
        .with_feed(op.feed.unwrap_or(tool.feed))
        .with_plunge_feed(op.plunge_feed.unwrap_or(tool.plunge_feed));
    let toolpath = face(cx.stock.bounds, &end_mill(tool)?, &opts)?;
    let b = cx.stock.bounds;
    Ok(OpResult {
        toolpath,
        cut: format!(
            "the stock's top, {:.3} × {:.3} mm, {:.3} mm down to z = 0",
            b.width(),
            b.height(),
            depth
        ),
        checks: vec![(
            "levels".to_owned(),
            format!(
                "{} of at most {step_down:.3} mm",
                (depth / step_down).ceil()
            ),
        )],
        tabs: Vec::new(),
        holes: Vec::new(),
    })
}
