//! `millpath verify PROGRAM --job part.toml`: any program (ours or another CAM system's)
//! checked against what a job file means to make, with the job's own whole-stock check
//! ([`super::check::check_sections`]) and nothing of the job's plan: the program is read back,
//! split into sections where the tool changes (`T n M6`; on Grbl, which has no tool changer,
//! at millpath's `(tool change: load Tn by hand …)` comments), each section cut with its tool
//! from the job's tool table into the height-field stock; the holds are judged by the tabs the
//! job file asks for (their number and height), not by where a plan placed them.
//!
//! The tool is taken to start above the stock: the reader's start is at the job's clearance
//! height over the origin, so that the program's first rapid is not read as one through the
//! stock.

use super::block::stock_block;
use super::check::{JobCheck, Section, check_sections};
use super::design::JobDesign;
use super::model::PartModel;
use super::spec::JobSpec;
use crate::Error;
use crate::error::InputError;
use crate::gcode::{Dialect, DialectChoice, ReadMove, Reader, ReaderOptions};
use crate::geom::{Hole, Point3};
use crate::job::estimate::{Choosing, Failure};
use crate::toolpath::Toolpath;

/// What `verify --job` found.
#[derive(Debug)]
pub struct JobVerifyRun {
    /// The whole-stock check.
    pub check: JobCheck,
    /// The sections read: tool number and moves.
    pub sections: Vec<(u32, usize)>,
    /// The dialect the program was read in, and why.
    pub dialect: DialectChoice,
}

impl JobVerifyRun {
    /// What went wrong; empty when the program makes the job's part.
    pub fn problems(&self) -> Vec<String> {
        self.check.problems()
    }

    /// The JSON `verify --job --json` prints.
    pub fn json(&self) -> serde_json::Value {
        let problems = self.problems();
        serde_json::json!({
            "passed": problems.is_empty(),
            "problems": problems,
            "sections": self.sections.iter().map(|(t, n)| serde_json::json!({"tool": t, "moves": n})).collect::<Vec<_>>(),
            "check": self.check.rows().into_iter().map(|(k, v)| serde_json::json!([k, v])).collect::<Vec<_>>(),
            "dialect": self.dialect.dialect.to_string(),
        })
    }
}

/// The tool a Grbl program's line names in millpath's tool-change comment, if any.
fn grbl_tool(line: &str) -> Option<u32> {
    let rest = line.split("tool change: load T").nth(1)?;
    let digits: String = rest.chars().take_while(char::is_ascii_digit).collect();
    digits.parse().ok()
}

/// Reads `text` (named `origin`) in `dialect` from `start`: every move with its line and tool.
fn read_moves(
    text: &str,
    origin: &str,
    dialect: Dialect,
    start: Point3,
) -> Result<Vec<ReadMove>, Error> {
    let opts = ReaderOptions::default()
        .with_dialect(dialect)
        .with_origin(origin)
        .with_start(start);
    Reader::new(text.as_bytes(), opts).collect()
}

/// Checks the program `text` (named `origin`, read in `dialect`: a name or `auto`) against
/// the job `spec`.
pub fn verify_program(
    spec: &JobSpec,
    text: &str,
    origin: &str,
    dialect: &str,
) -> Result<JobVerifyRun, Error> {
    let (loops, _) = super::load_drawing(&spec.drawing, &spec.import)?;
    let pockets = loops.pockets();
    let model = PartModel::new(&pockets, &|o| {
        Hole::from_outline(o, crate::geom::CIRCLE_TOLERANCE).map(|h| (h.center, h.diameter))
    });
    let stock = stock_block(spec, &model)?;
    let design = JobDesign::new(spec, &model)?;
    let start = Point3::new(0.0, 0.0, stock.top + spec.clearance_height);
    let choosing = Choosing::new(dialect, Some(std::path::Path::new(origin)), text)?;
    let read = |d: Dialect| {
        read_moves(text, origin, d, start).map_err(|error| Failure {
            error,
            by_reader: true,
        })
    };
    let (moves, choice) = choosing.run(read, |d| read(d).is_ok())?;
    // The tool of each line on Grbl: from the tool-change comments.
    let grbl_tools: Vec<(usize, u32)> = if choice.dialect == Dialect::Grbl {
        text.lines()
            .enumerate()
            .filter_map(|(i, l)| grbl_tool(l).map(|t| (i + 1, t)))
            .collect()
    } else {
        Vec::new()
    };
    let tool_at = |m: &ReadMove| -> u32 {
        if choice.dialect == Dialect::Grbl {
            grbl_tools
                .iter()
                .take_while(|(l, _)| *l <= m.line)
                .last()
                .map_or(0, |(_, t)| *t)
        } else {
            m.modal.tool
        }
    };
    let mut runs: Vec<(u32, usize, Toolpath)> = Vec::new();
    let mut from = start;
    for m in &moves {
        let t = tool_at(m);
        let new = runs.last().is_none_or(|(last, _, _)| *last != t);
        if new {
            let Some(tool) = spec.tool(t) else {
                let have: Vec<String> = spec
                    .tools
                    .iter()
                    .map(|t| format!("T{}", t.number))
                    .collect();
                return Err(InputError::new("tool", format!("T{t}"))
                    .at(format!("{origin} line {}", m.line))
                    .expected(format!(
                        "a tool of the job file's table ({}){}",
                        have.join(", "),
                        if t == 0 {
                            ": the program moves before any tool change"
                        } else {
                            ""
                        }
                    ))
                    .into());
            };
            let tp = Toolpath::new(super::context::end_mill(tool)?, from);
            runs.push((t, m.line, tp));
        }
        if let Some((_, _, tp)) = runs.last_mut() {
            tp.push(m.mv);
        }
        from = m.mv.to;
    }
    let names: Vec<String> = runs
        .iter()
        .map(|(t, line, _)| format!("T{t} from line {line}"))
        .collect();
    let sections: Vec<Section<'_>> = runs
        .iter()
        .zip(&names)
        .filter_map(|((t, _, tp), name)| {
            spec.tool(*t).map(|tool| Section {
                name,
                toolpath: tp,
                tool,
            })
        })
        .collect();
    let check = check_sections(&model, stock, &design, &sections, None)?;
    Ok(JobVerifyRun {
        check,
        sections: runs.iter().map(|(t, _, tp)| (*t, tp.moves.len())).collect(),
        dialect: choice,
    })
}

#[cfg(test)]
mod tests {
    use super::grbl_tool;

    #[test]
    fn grbl_tool_comments() {
        assert_eq!(
            grbl_tool("(tool change: load T12 by hand, grbl has no tool-change command)"),
            Some(12)
        );
        assert_eq!(grbl_tool("; tool change: load T3 by hand"), Some(3));
        assert_eq!(grbl_tool("G1 X1"), None);
    }
}
