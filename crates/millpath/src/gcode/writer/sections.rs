//! Programs of several tools: one [`Toolpath`] per section, each with its own tool, spindle
//! speed and coolant, written one after the other into one program.
//!
//! The header is written once (the tools listed in comments, units, safety block, work
//! offset, path tolerance). Each section then names itself in a comment; unless it keeps
//! the previous section's tool, spindle speed and coolant, it first stops the previous
//! section's coolant and spindle (`M9`, `M5`), then changes the tool (`T n M6`; a comment and
//! an `M0` pause on Grbl, which has no tool changer), starts the spindle and the coolant, and
//! writes its moves; its first motion block carries the tool length compensation (`G43` on
//! LinuxCNC, `G43 H n` on Fanuc; Sinumerik's `D1` is active with the tool) and every axis,
//! since a new length offset changes what the programmed Z means.
//!
//! The writer never moves the tool on its own: each section's toolpath must begin and end
//! where a tool change is safe (at the job's clearance height), which the job layer that
//! composes the sections sees to.

use super::{Emitter, WriteSummary, WriterOptions};
use crate::error::{Error, InputError};
use crate::gcode::dialect::Coolant;
use crate::toolpath::Toolpath;
use std::io::Write;

/// One section of a program: a toolpath and the tool that cuts it.
#[derive(Debug, Clone, Copy)]
pub struct ProgramSection<'a> {
    /// The moves.
    pub toolpath: &'a Toolpath,
    /// Tool number (`T`; Fanuc's `H` length offset register).
    pub tool_number: u32,
    /// What the tool is, for the header's tool list (`flat end mill D6 mm, 3 flutes`).
    pub tool_description: &'a str,
    /// Spindle speed, rev/min (0: the spindle is left alone).
    pub spindle_rpm: f64,
    /// Coolant during the section.
    pub coolant: Coolant,
    /// The section's title, written as a comment before its tool change.
    pub title: &'a str,
}

/// What [`write_sections`] wrote.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct SectionsSummary {
    /// The whole program's summary.
    pub summary: WriteSummary,
    /// The 1-based line each section begins on (its coolant and spindle stop, title and tool
    /// change): a move read back from a line at or after it and before the next section's is
    /// the section's.
    pub section_lines: Vec<usize>,
}

/// Writes `sections` in order as one program to `out` (see the module docs). `opts` gives
/// the dialect, units, decimals, numbering, work offset, path tolerance and header; its
/// tool number, spindle and coolant are the sections'. Each section's tool change is written
/// when [`WriterOptions::tool_change`] is on.
///
/// Errors: no section, a tool number above 9999 (named by section), and what
/// [`super::write_program`] refuses in a move.
pub fn write_sections(
    sections: &[ProgramSection<'_>],
    opts: &WriterOptions,
    out: &mut dyn Write,
) -> Result<SectionsSummary, Error> {
    opts.validate()?;
    if sections.is_empty() {
        return Err(InputError::new("program sections", 0)
            .at("the program")
            .expected("at least one section")
            .into());
    }
    for (k, s) in sections.iter().enumerate() {
        if s.tool_number > 9999 || !(s.spindle_rpm.is_finite() && s.spindle_rpm >= 0.0) {
            return Err(InputError::new(
                "tool and spindle",
                format_args!("T{} S{}", s.tool_number, s.spindle_rpm),
            )
            .at(format!("section {} ({})", k + 1, s.title))
            .expected("a tool number 0..9999 and a spindle speed >= 0 rev/min")
            .into());
        }
    }
    let mut w = Emitter::new(opts, out);
    let mut tools: Vec<(u32, String)> = Vec::new();
    for s in sections {
        if !tools.iter().any(|(n, _)| *n == s.tool_number) {
            tools.push((s.tool_number, s.tool_description.to_owned()));
        }
    }
    w.header_common(&tools)?;
    let mut section_lines = Vec::with_capacity(sections.len());
    for (k, s) in sections.iter().enumerate() {
        section_lines.push(w.summary.lines + 1);
        let same = k > 0
            && w.tool == s.tool_number
            && w.spindle_on.to_bits() == s.spindle_rpm.to_bits()
            && w.coolant_on == s.coolant;
        if same {
            // The same tool, turning and cooled alike: no stop, no tool change.
            w.comment(s.title)?;
        } else {
            w.tool_stop()?;
            w.comment(s.title)?;
            w.tool_start(s.tool_number, s.spindle_rpm, s.coolant)?;
        }
        w.moves(s.toolpath)?;
    }
    w.footer()?;
    Ok(SectionsSummary {
        summary: w.finish()?,
        section_lines,
    })
}
