//! Each operation of a job planned with its tool on the part model, and verified by its own
//! verifier before it goes into the program: the pockets by the pocket verifier
//! (`stock::verify_part`), the profile by the exact clearance and the dense check against the
//! drawn outline, the holes by their cut envelopes, the face by the whole job's height field.

use super::context::{OpContext, OpResult, in_op, op_at};
use super::spec::{JobOperation, JobTool, OperationKind};
use crate::Error;
use crate::toolpath::Toolpath;

/// Plans operation `op` with `tool`.
pub fn plan(
    cx: &OpContext<'_>,
    op: &JobOperation,
    tool: &JobTool,
    note: &mut dyn FnMut(String),
) -> Result<OpResult, Error> {
    let r = match &op.kind {
        OperationKind::Pocket(settings, select) => {
            super::op_pocket::plan(cx, op, tool, settings, select.as_deref(), note)
        }
        OperationKind::Face(s) => super::op_face::plan(cx, op, tool, s),
        OperationKind::Profile(s) => super::op_profile::plan(cx, op, tool, s, note),
        OperationKind::Drill(s) => super::op_holes::drill(cx, op, tool, s, note),
        OperationKind::Bore(s) => super::op_holes::bore(cx, op, tool, s, note),
    }
    .map_err(|e| in_op(e, cx.spec, op))?;
    at_clearance(cx, op, r)
}

/// Plans pocket operation `op`, whose `rest_from` names the earlier operation whose toolpath
/// is `previous`, with `tool`: the rest pass.
pub fn plan_rest(
    cx: &OpContext<'_>,
    op: &JobOperation,
    tool: &JobTool,
    previous: &Toolpath,
) -> Result<OpResult, Error> {
    let r = match &op.kind {
        OperationKind::Pocket(settings, select) => {
            super::op_pocket::plan_rest(cx, op, tool, settings, select.as_deref(), previous)
        }
        other => Err(Error::internal(format!(
            "{}: rest_from on a {} operation",
            op_at(cx.spec, op),
            other.name()
        ))),
    }
    .map_err(|e| in_op(e, cx.spec, op))?;
    at_clearance(cx, op, r)
}

/// `r`, if its toolpath runs from and to the clearance height; else an internal error.
fn at_clearance(cx: &OpContext<'_>, op: &JobOperation, r: OpResult) -> Result<OpResult, Error> {
    let start = r.toolpath.start;
    let end = r.toolpath.end();
    let z = cx.clearance_z();
    if (start.z - z).abs() > 1e-6 || (end.z - z).abs() > 1e-6 {
        return Err(Error::internal(format!(
            "{}: the toolpath runs from {start:?} to {end:?}, not from and to the clearance \
             height z = {z}",
            op_at(cx.spec, op)
        )));
    }
    Ok(r)
}
