//! The stock block a job cuts: the drawing's parts' extents plus the margin (or the size and
//! corner the job file gives), from `-thickness` to the material `top` above the part's top.

use super::model::PartModel;
use super::spec::JobSpec;
use crate::error::InputError;
use crate::geom::{Aabb, Point};

/// The stock block, as the job places it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StockBlock {
    /// Its extent in XY, mm.
    pub bounds: Aabb,
    /// Its bottom, mm (`-thickness`).
    pub bottom: f64,
    /// Its top, mm (the material above the part's top, z = 0).
    pub top: f64,
}

/// The stock block of `spec` around `model`.
pub fn stock_block(spec: &JobSpec, model: &PartModel) -> Result<StockBlock, InputError> {
    let s = &spec.stock;
    let extents = model.bounds().ok_or_else(|| {
        InputError::new("parts", 0)
            .at(spec.drawing.clone())
            .expected("a drawing with at least one closed outline")
    })?;
    let size = s.size.unwrap_or([
        extents.width() + 2.0 * s.margin,
        extents.height() + 2.0 * s.margin,
    ]);
    let origin = s.origin.unwrap_or_else(|| {
        let c = extents.center();
        [c.x - 0.5 * size[0], c.y - 0.5 * size[1]]
    });
    let bounds = Aabb::from_points([
        Point::new(origin[0], origin[1]),
        Point::new(origin[0] + size[0], origin[1] + size[1]),
    ]);
    if !(bounds.min.x <= extents.min.x
        && bounds.min.y <= extents.min.y
        && bounds.max.x >= extents.max.x
        && bounds.max.y >= extents.max.y)
    {
        return Err(InputError::new(
            "stock",
            format_args!(
                "{:.3} × {:.3} mm from ({:.3}, {:.3})",
                size[0], size[1], origin[0], origin[1]
            ),
        )
        .at(format!("{} [stock]", spec.origin))
        .expected(format!(
            "a block around the drawing's parts, ({:.3}, {:.3}) to ({:.3}, {:.3})",
            extents.min.x, extents.min.y, extents.max.x, extents.max.y
        )));
    }
    Ok(StockBlock {
        bounds,
        bottom: -s.thickness,
        top: s.top,
    })
}
