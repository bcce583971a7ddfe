//! The job's report (`--report` JSON) and its setup sheet: the stock and where its origin is,
//! the tools to load, the operations in order with what each cuts, its tool and its time, and
//! the verifiers' verdicts.

use super::run::JobRun;
use super::spec::JobSpec;
use crate::report::html::{HtmlReport, Table};
use serde::Serialize;

/// A tool as the setup sheet lists it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ToolRow {
    /// T number.
    pub number: u32,
    /// Name.
    pub name: String,
    /// `end mill` or `drill`.
    pub kind: &'static str,
    /// Diameter, mm.
    pub diameter_mm: f64,
    /// Flutes.
    pub flutes: u32,
    /// Flute length, mm.
    pub flute_length_mm: f64,
    /// Spindle, rev/min.
    pub spindle_rpm: f64,
    /// Feed, mm/min.
    pub feed_mm_min: f64,
}

/// An operation as the setup sheet lists it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct OperationRow {
    /// Name.
    pub name: String,
    /// `face`, `pocket`, `profile`, `drill`, `bore`.
    pub kind: &'static str,
    /// T number.
    pub tool: u32,
    /// What it cuts.
    pub cut: String,
    /// Its share of the cycle time, s.
    pub time_s: f64,
    /// The length of its cutting moves, mm.
    pub path_mm: f64,
    /// Its verifier's figures.
    pub checks: Vec<(String, String)>,
}

/// The job's report.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct JobReport {
    /// The job file.
    pub job: String,
    /// The drawing.
    pub drawing: String,
    /// Machine the cycle time is for.
    pub machine: String,
    /// Dialect written.
    pub dialect: String,
    /// Cycle time of the written program, tool changes included, s.
    pub cycle_time_s: f64,
    /// Tool changes in the program (not counting the first tool's loading).
    pub tool_changes: usize,
    /// The machine's time per tool change, s.
    pub tool_change_time_s: f64,
    /// Stock: lower-left corner and size in XY, bottom and top z, mm.
    pub stock: [f64; 6],
    /// Parts, pockets and holes the drawing shows.
    pub features: [usize; 3],
    /// The tools.
    pub tools: Vec<ToolRow>,
    /// The operations, in order.
    pub operations: Vec<OperationRow>,
    /// The whole job's check on the stock simulation (name, value).
    pub check: Vec<(String, String)>,
}

/// The report of `run` made from `spec`.
pub fn report(spec: &JobSpec, run: &JobRun) -> JobReport {
    let mut changes = 0;
    let mut last = None;
    for op in &run.operations {
        if last.is_some_and(|t| t != op.tool.number) {
            changes += 1;
        }
        last = Some(op.tool.number);
    }
    let b = run.stock.bounds;
    JobReport {
        job: spec.origin.clone(),
        drawing: spec.drawing.clone(),
        machine: run.machine.name.clone(),
        dialect: spec.dialect.to_string(),
        cycle_time_s: run.cycle_time_s,
        tool_changes: changes,
        tool_change_time_s: run.machine.tool_change_time,
        stock: [
            b.min.x,
            b.min.y,
            b.width(),
            b.height(),
            run.stock.bottom,
            run.stock.top,
        ],
        features: [
            run.model.parts.len(),
            run.model.pockets.len(),
            run.model.holes.len(),
        ],
        tools: spec
            .tools
            .iter()
            .filter(|t| spec.operations.iter().any(|o| o.tool == t.number))
            .map(|t| ToolRow {
                number: t.number,
                name: t.name.clone(),
                kind: t.kind.name(),
                diameter_mm: t.diameter,
                flutes: t.flutes,
                flute_length_mm: t.flute_length,
                spindle_rpm: t.spindle,
                feed_mm_min: t.feed * 60.0,
            })
            .collect(),
        operations: run
            .operations
            .iter()
            .map(|o| OperationRow {
                name: o.name.clone(),
                kind: o.kind,
                tool: o.tool.number,
                cut: o.result.cut.clone(),
                time_s: o.time_s,
                path_mm: o.result.toolpath.cut_length(),
                checks: o.result.checks.clone(),
            })
            .collect(),
        check: run.check.rows(),
    }
}

fn n(x: f64) -> String {
    let s = format!("{x:.3}");
    s.trim_end_matches('0').trim_end_matches('.').to_owned()
}

/// Adds the setup sheet to `html`: a summary (stock, origin, machine, cycle time), the
/// tools and the operations as tables (`id` `setup-tools`, `setup-operations`), the check.
pub fn setup_sheet(html: &mut HtmlReport, r: &JobReport) {
    let [x, y, w, h, bottom, top] = r.stock;
    html.section(
        "setup sheet",
        [
            ("job".to_owned(), r.job.clone()),
            ("drawing".to_owned(), r.drawing.clone()),
            (
                "stock".to_owned(),
                format!(
                    "{} × {} × {} mm, from ({}, {}) to ({}, {}) in X, Y",
                    n(w),
                    n(h),
                    n(top - bottom),
                    n(x),
                    n(y),
                    n(x + w),
                    n(y + h)
                ),
            ),
            (
                "origin".to_owned(),
                format!(
                    "the drawing's X, Y; Z = 0 on the finished part's top ({} mm below the \
                     stock's top, {} mm above its bottom)",
                    n(top),
                    n(-bottom)
                ),
            ),
            (
                "features".to_owned(),
                format!(
                    "{} part(s), {} pocket(s), {} hole(s)",
                    r.features[0], r.features[1], r.features[2]
                ),
            ),
            ("machine".to_owned(), r.machine.clone()),
            ("dialect".to_owned(), r.dialect.clone()),
            (
                "cycle time".to_owned(),
                format!(
                    "{:.2} s ({} tool change(s) at {} s)",
                    r.cycle_time_s,
                    r.tool_changes,
                    n(r.tool_change_time_s)
                ),
            ),
        ],
    );
    html.table(Table {
        title: "tools".to_owned(),
        id: "setup-tools".to_owned(),
        columns: [
            "T",
            "tool",
            "type",
            "diameter",
            "flutes",
            "flute length",
            "spindle",
            "feed",
        ]
        .map(String::from)
        .to_vec(),
        rows: r
            .tools
            .iter()
            .map(|t| {
                vec![
                    format!("T{}", t.number),
                    t.name.clone(),
                    t.kind.to_owned(),
                    format!("{} mm", n(t.diameter_mm)),
                    t.flutes.to_string(),
                    format!("{} mm", n(t.flute_length_mm)),
                    format!("{} rev/min", n(t.spindle_rpm)),
                    format!("{} mm/min", n(t.feed_mm_min)),
                ]
            })
            .collect(),
    });
    html.table(Table {
        title: "operations, in order".to_owned(),
        id: "setup-operations".to_owned(),
        columns: ["#", "operation", "type", "tool", "cuts", "time", "verified"]
            .map(String::from)
            .to_vec(),
        rows: r
            .operations
            .iter()
            .enumerate()
            .map(|(i, o)| {
                vec![
                    (i + 1).to_string(),
                    o.name.clone(),
                    o.kind.to_owned(),
                    format!("T{}", o.tool),
                    o.cut.clone(),
                    format!("{:.2} s", o.time_s),
                    o.checks
                        .iter()
                        .map(|(k, v)| format!("{k}: {v}"))
                        .collect::<Vec<_>>()
                        .join("; "),
                ]
            })
            .collect(),
    });
    html.section("the whole job on the stock simulation", r.check.clone());
}
