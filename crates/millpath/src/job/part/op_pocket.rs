//! A job's pocket operation: the selected pockets of the part model cut with the pocket
//! strategies (`strategy::pocket::part`), verified by the pocket verifier; or, with
//! `rest_from`, only what an earlier pocket operation's larger tool left in them
//! (`strategy::rest`), the pair verified on one height field (`job::rest`'s check).

use super::context::{OpContext, OpResult, end_mill};
use super::spec::{JobOperation, JobTool};
use crate::Error;
use crate::job::pocket::{Choice, PocketSettings, parse_choice, parse_select};
use crate::strategy::pocket::PocketShape;
use crate::strategy::pocket::part::{PartStrategy, generate_part};
use crate::strategy::rest::{self, RestOptions};
use crate::toolpath::Toolpath;

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
    let time = |tp: &Toolpath| crate::motion::cycle_time(tp, machine);
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

/// The rest pass of operation `op` (its `rest_from`) after `previous`, the toolpath of the
/// earlier pocket operation it names: in the pockets `select` names (all when `None`), only
/// what `previous`'s larger tool left within this tool's reach. Checked before it is
/// returned: both toolpaths cut into one height field leave nothing this tool reaches, cut
/// no wall and nothing below the floor (`job::rest`'s check).
pub(crate) fn plan_rest(
    cx: &OpContext<'_>,
    op: &JobOperation,
    tool: &JobTool,
    settings: &PocketSettings,
    select: Option<&str>,
    previous: &Toolpath,
) -> Result<OpResult, Error> {
    let from = op.rest_from.as_deref().unwrap_or_default();
    for (key, v) in [
        ("wall_stock", settings.wall_stock),
        ("floor_stock", settings.floor_stock),
    ] {
        if v != 0.0 {
            return Err(crate::InputError::new(key, v)
                .at(format!("{}, with rest_from", cx.spec.origin))
                .expected("0: a rest pass cuts to the walls and the floor")
                .into());
        }
    }
    let mut s = settings.clone();
    s.machine = cx.spec.machine.clone();
    if let Some(f) = op.feed {
        s.feed = format!("{}", f * 60.0);
    }
    let (_, popts) = s.options()?;
    let t = end_mill(tool)?;
    let opts = RestOptions::default()
        .with_depth(popts.depth)
        .with_step_down(popts.step_down)
        .with_stepover((popts.stepover.distance(t.diameter) / t.diameter).min(1.0))
        .with_feed(popts.feed)
        .with_plunge_feed(op.plunge_feed.unwrap_or(tool.plunge_feed))
        .with_safe_height(cx.clearance_z());
    let n = cx.model.pockets.len();
    let selected = parse_select(select, n).map_err(|e| e.at("--select"))?;
    let mut toolpath = Toolpath::new(
        t,
        crate::geom::Point3::new(0.0, 0.0, opts.top_z + opts.safe_height),
    );
    let (mut left, mut runs) = (0.0, 0);
    let mut shapes = Vec::with_capacity(selected.len());
    for &i in &selected {
        let p = &cx.model.pockets[i - 1];
        let shape = PocketShape::new(
            p.outer.clone(),
            p.islands.clone(),
            &format!("{}, pocket {i}", cx.spec.drawing),
        )?;
        let r = rest::generate(&shape, previous, &t, &opts)?;
        left += r.left_mm2;
        runs += r.runs;
        toolpath.append(&r.toolpath);
        shapes.push(shape);
    }
    let verdict = crate::job::rest::judge(&shapes, previous, &toolpath, popts.depth)?;
    let list: Vec<String> = selected.iter().map(ToString::to_string).collect();
    Ok(OpResult {
        toolpath,
        cut: format!("pockets {} (rest after {from})", list.join(", ")),
        checks: vec![
            (
                format!("left by {from} (D{} mm)", previous.tool.diameter),
                format!("{left:.3} mm² within reach, {runs} run(s)"),
            ),
            (format!("after {from} and this operation"), verdict),
        ],
        tabs: Vec::new(),
        holes: Vec::new(),
    })
}
