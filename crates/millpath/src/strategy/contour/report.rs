//! The contour report (`--report OUT.json`).
//!
//! Top-level fields scripts rely on: `segments` (one finishing pass around the outline),
//! `max_deviation_mm` (largest measured deviation of any layer from its nominal offset),
//! `layers`, `blocks`.

use super::{ContourOptions, ContourWarning, Pass};
use crate::curve::flatten as fl_;
use crate::curve::{self, CompositeCurve};
use crate::toolpath::{LevelKind, Toolpath};
use serde::{Deserialize, Serialize};

/// One layer of the report.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LayerReport {
    /// 1-based layer number.
    pub index: usize,
    /// Cutting depth (Z of the tool tip), mm.
    pub z: f64,
    /// Roughing or finishing.
    pub kind: LevelKind,
    /// Nominal cutter offset from the outline (tool radius + allowance), mm.
    pub offset_mm: f64,
    /// Line (or arc) segments of the pass.
    pub segments: usize,
    /// Measured max distance of the pass from its nominal offset (mm).
    pub max_deviation_mm: f64,
    /// Feed length of the layer (lead arcs and plunge included), mm.
    pub cut_length_mm: f64,
}

/// The outline's own flattening figures at the user's tolerance.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CurveReport {
    /// Cubic pieces (input groups and blends).
    pub pieces: usize,
    /// Corners (tangent breaks).
    pub corners: usize,
    /// Length of the outline, mm.
    pub length_mm: f64,
    /// Enclosed area, mm².
    pub area_mm2: f64,
    /// Chords of the greedy exact flattening of the outline at the tolerance.
    pub segments: usize,
    /// Lower bound on any flattening's chord count (see `curve::flatten`).
    pub lower_bound: usize,
    /// Asymptotic optimum ∫√(|κ|/8T) ds.
    pub asymptotic_segments: f64,
    /// kurbo::flatten's count for the same curve and tolerance.
    pub kurbo_segments: usize,
}

/// The report of a contour run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ContourReport {
    /// Segments of one (finishing) pass around the outline.
    pub segments: usize,
    /// Largest measured deviation of any layer from its nominal offset (mm).
    pub max_deviation_mm: f64,
    /// Per layer.
    pub layers: Vec<LayerReport>,
    /// Motion blocks of the program (the toolpath's moves until the G-code writer counts).
    pub blocks: usize,
    /// Lines of the program (0 until written).
    pub lines: usize,
    /// Time at the programmed feeds (rapids at the options' rapid speed), s.
    pub time_at_programmed_feed_s: f64,
    /// Total feed length, mm.
    pub cut_length_mm: f64,
    /// Tolerance T, mm.
    pub tolerance_mm: f64,
    /// Output rounding allowance ρ, mm.
    pub rounding_mm: f64,
    /// Decimals of the G-code (0 until written).
    pub decimals: u32,
    /// The outline's flattening figures.
    pub curve: CurveReport,
    /// Warnings (places the tool cannot reach...).
    pub warnings: Vec<String>,
}

impl ContourReport {
    /// Builds the report.
    pub fn build(
        c: &CompositeCurve,
        opt: &ContourOptions,
        finish: &Pass,
        layers: Vec<LayerReport>,
        tp: &Toolpath,
        warnings: &[ContourWarning],
    ) -> Self {
        let t = opt.tolerance;
        let fl = fl_::flatten(c, t).ok();
        let curve = CurveReport {
            pieces: c.len(),
            corners: c.corners().len(),
            length_mm: c.length(),
            area_mm2: c.signed_area(),
            segments: fl.as_ref().map_or(0, curve::Flattening::segments),
            lower_bound: fl.as_ref().map_or(0, |f| f.lower_bound(c.corners().len())),
            asymptotic_segments: fl_::asymptotic_count(c, t),
            kurbo_segments: fl_::kurbo_count(c, t),
        };
        ContourReport {
            segments: finish.segments(),
            max_deviation_mm: layers
                .iter()
                .map(|l| l.max_deviation_mm)
                .fold(0.0, f64::max),
            layers,
            blocks: tp.moves.len(),
            lines: 0,
            time_at_programmed_feed_s: tp.time_at_programmed_feed(opt.rapid_speed),
            cut_length_mm: tp.cut_length(),
            tolerance_mm: t,
            rounding_mm: opt.rounding,
            decimals: 0,
            curve,
            warnings: warnings.iter().map(ToString::to_string).collect(),
        }
    }
}
