//! The job's cycle time, read back from its written program as `millpath estimate` reads it
//! (LinuxCNC's sync points on a `linuxcnc` machine, the machine's tool change time at every
//! change of tool), and each operation's share of it: the time of the planned blocks whose
//! moves come from the operation's lines of the program (a tool change belongs to the
//! operation it starts).

use crate::Error;
use crate::gcode::{ReadMove, Reader, ReaderOptions, WriterOptions};
use crate::machine::{Controller, Machine};
use crate::motion::{PlanOptions, plan_moves};

/// The program's cycle time and each section's share, s.
#[derive(Debug, Clone, PartialEq)]
pub struct SectionTimes {
    /// The whole program.
    pub total: f64,
    /// Per section, in order; they add up to `total`.
    pub per_section: Vec<f64>,
}

/// Times `gcode` (written with `wopts`) on `machine`; `section_lines` are the 1-based lines
/// the sections begin on.
pub fn section_times(
    gcode: &[u8],
    wopts: &WriterOptions,
    section_lines: &[usize],
    machine: &Machine,
) -> Result<SectionTimes, Error> {
    let opts = ReaderOptions::default()
        .with_dialect(wopts.dialect)
        .with_origin("the job's program")
        .with_sync_points((machine.controller == Controller::LinuxCnc).then_some(machine.sync_wait))
        .with_tool_change_time(Some(machine.tool_change_time));
    let mut from = opts.start;
    let mut moves = Vec::new();
    let mut lines = Vec::new();
    for item in Reader::new(gcode, opts) {
        let ReadMove { mv, line, .. } = item?;
        moves.push((from, mv));
        lines.push(line);
        from = mv.to;
    }
    let plan = plan_moves(
        moves.iter().map(|m| Ok(*m)),
        machine,
        &PlanOptions::default(),
    )?;
    let section_of = |line: usize| {
        section_lines
            .partition_point(|&s| s <= line)
            .saturating_sub(1)
    };
    let mut per_section = vec![0.0; section_lines.len().max(1)];
    for b in &plan.blocks {
        let line = lines.get(b.origin).copied().unwrap_or(0);
        if let Some(t) = per_section.get_mut(section_of(line)) {
            *t += b.time;
        }
    }
    Ok(SectionTimes {
        total: plan.total_time(),
        per_section,
    })
}
