//! A job's pocket operation: the selected pockets of the part model cut with the pocket
//! strategies (`strategy::pocket::part`), verified by the pocket verifier.

use super::context::{OpContext, OpResult, end_mill};
use super::spec::{JobOperation, JobTool};
use crate::Error;
use crate::job::pocket::{Choice, PocketSettings, parse_choice, parse_select};
use crate::strategy::pocket::PocketShape;
use crate::strategy::pocket::part::{PartStrategy, generate_part};

/// Plans the pockets `select` names (all when `None`) with `settings` and `tool`.
pub(crate) fn plan(
    cx: &OpContext<'_>,
    op: &JobOperation,
    tool: &JobTool,
    settings: &PocketSettings,
    select: Option<&str>,
    note: &mut dyn FnMut(String),
) -> Result<OpResult, Error> {
    let mut s = settings.clone();
    s.machine = cx.spec.machine.clone();
    s.clearance_height = cx.clearance_z();
    s.safe_height = cx.spec.safe_height;
    if let Some(f) = op.feed {
        s.feed = format!("{}", f * 60.0);
    }
    let (_, mut opts) = s.options()?;
    if let Some(p) = op.plunge_feed {
        opts.plunge_feed = p;
    } else {
        opts.plunge_feed = tool.plunge_feed;
    }
    let t = end_mill(tool)?;
    let n = cx.model.pockets.len();
    if n == 0 {
        return Err(crate::InputError::new("pockets", 0)
            .at("the drawing")
            .expected("a drawing with pockets (outlines inside a part) for a pocket operation")
            .into());
    }
    let selected = parse_select(select, n).map_err(|e| e.at("--select"))?;
    let mut shapes = Vec::with_capacity(selected.len());
    for &i in &selected {
        let p = &cx.model.pockets[i - 1];
        let shape = PocketShape::new(
            p.outer.clone(),
            p.islands.clone(),
            &format!("{}, pocket {i}", cx.spec.drawing),
        )?;
        shapes.push((i, shape));
    }
    let machine = cx.machine;
    let time = |tp: &crate::toolpath::Toolpath| crate::motion::cycle_time(tp, machine);
    let strategy = match parse_choice(&s.strategy)? {
        Choice::One(kind) => PartStrategy::One(kind),
        Choice::Auto => PartStrategy::Auto,
    };
    let part = generate_part(&shapes, strategy, &t, &opts, &s.sim(), &time)?;
    let mut cut = Vec::new();
    for p in &part.pockets {
        match &p.skipped {
            Some(why) => note(format!("{}: pocket {} left out: {why}", op.name, p.index)),
            None => {
                cut.push(format!("{} ({})", p.index, p.kind.name()));
            }
        }
    }
    let problems = part
        .verification
        .problems_within(crate::stock::GOUGE_RESOLUTION);
    if !problems.is_empty() {
        return Err(Error::internal(format!(
            "{}: the joined pockets' program fails its verification: {}; nothing written",
            op.name,
            crate::stock::problems_text(&problems)
        )));
    }
    let v = &part.verification.total;
    let checks = vec![
        (
            "min clearance to the walls".to_owned(),
            format!(
                "{:.4} mm (needs {:.4})",
                v.min_clearance_mm, v.required_clearance_mm
            ),
        ),
        (
            "uncut material".to_owned(),
            format!("{:.3} mm²", v.uncut_area_mm2),
        ),
        (
            "engagement".to_owned(),
            format!(
                "max {:.1}°, mean {:.1}°",
                v.max_engagement_deg, v.mean_engagement_deg
            ),
        ),
    ];
    let mut toolpath = part.toolpath;
    toolpath.tool = t;
    Ok(OpResult {
        toolpath,
        cut: format!("pockets {}", cut.join(", ")),
        checks,
        tabs: Vec::new(),
        holes: Vec::new(),
    })
}
