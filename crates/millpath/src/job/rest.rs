//! Rest machining for the front ends: `millpath pocket DRAWING --rest-from PREVIOUS.ngc
//! --tool-diameter d`. The previous program (ours or another CAM's) is read as `verify` reads
//! one; its tool's diameter comes from `--rest-from-diameter`, else from our programs' header
//! line `(tool Tn: flat end mill Dx mm ...)` ([`super::verify::header_diameter`]). Each selected pocket gets the rest pass of
//! `strategy::rest` with the pocket settings' depth, step-down, stepover and feed; then the
//! pair is judged on the whole-job height field (both programs cut one block, each with its
//! own tool): nothing cut into the walls or below the floor, no rapid through material, no
//! plunge, nothing left that the rest tool could reach. A pair that fails is not written.

use super::pocket::{PocketSettings, program_options};
use super::program::{ProgramSettings, program_times};
use super::verify::{VerifySettings, header_diameter};
use crate::gcode::write_program;
use crate::geom::{Aabb, Outline, Point};
use crate::io::outline_json::Loops;
use crate::stock::{
    CheckOptions, FieldOptions, Floor, HeightField, PartTop, RestNeed, StockSpec, check_field,
    floor_cut_length, rest_need,
};
use crate::strategy::pocket::PocketShape;
use crate::strategy::rest::{self, RestOptions};
use crate::toolpath::{Tool, Toolpath};
use crate::{Error, InputError};

/// Where the previous program comes from.
#[derive(Debug, Clone, Default)]
pub struct RestFrom {
    /// The previous program's file.
    pub program: String,
    /// Its tool's diameter, mm (`None`: read from its header).
    pub diameter: Option<f64>,
}

/// What a rest run made.
#[derive(Debug, Clone)]
pub struct RestRun {
    /// The rest program.
    pub gcode: Vec<u8>,
    /// Its moves.
    pub toolpath: Toolpath,
    /// The previous tool.
    pub previous_tool: Tool,
    /// Material the previous program left within the rest tool's reach, mm².
    pub left_mm2: f64,
    /// Runs cut over all pockets, per level.
    pub runs: usize,
    /// Cycle time of the rest program on the machine, s.
    pub time_s: f64,
    /// The height field's verdict on the pair.
    pub check: String,
    /// What the material left needs of the rest tool at one level (the verifier's lower
    /// bound, `stock::rest_need`), over all pockets.
    pub need: Vec<RestNeed>,
    /// The rest program's cutting at the floor, mm (`stock::floor_cut_length`).
    pub floor_cut_mm: f64,
}

impl RestRun {
    /// What the regions left need of cutting at one level, mm, over all pockets.
    pub fn need_mm(&self) -> f64 {
        self.need.iter().map(RestNeed::cut_mm).sum()
    }

    /// The floor's cutting over its need (1 when nothing is left and nothing cut).
    pub fn need_ratio(&self) -> f64 {
        let need = self.need_mm();
        if need > 0.0 {
            self.floor_cut_mm / need
        } else if self.floor_cut_mm > 0.0 {
            f64::INFINITY
        } else {
            1.0
        }
    }
}

impl RestRun {
    /// The line the front ends print for it: what was left, the runs, the path, the time and
    /// the height field's verdict on the pair.
    pub fn summary(&self) -> String {
        format!(
            "rest after D{} mm: {:.3} mm² left within reach of D{} mm, {} run(s), path {:.1} mm, \
             cut at the floor {:.1} mm against a need of {:.1} mm (ratio {:.3}), cycle time \
             {:.2} s; after both programs: {}",
            self.previous_tool.diameter,
            self.left_mm2,
            self.toolpath.tool.diameter,
            self.runs,
            self.toolpath.cut_length(),
            self.floor_cut_mm,
            self.need_mm(),
            self.need_ratio(),
            self.time_s,
            self.check
        )
    }
}

/// The rest pass after `from` in the selected pockets of `loops` (module docs).
pub fn run(
    loops: &Loops,
    outline: &str,
    settings: &PocketSettings,
    program: &ProgramSettings,
    select: Option<&str>,
    from: &RestFrom,
) -> Result<RestRun, Error> {
    let machine = settings.program_machine(&super::load_machine(&settings.machine)?)?;
    let wopts = program_options("rest", &machine, program)?;
    let (tool, popts) = settings.options()?;
    let text = std::fs::read_to_string(&from.program).map_err(|e| {
        InputError::new("previous program", &from.program)
            .at("--rest-from")
            .expected(format!("a readable G-code file ({e})"))
    })?;
    let previous_d = match from.diameter.or_else(|| header_diameter(&text)) {
        Some(d) => d,
        None => {
            return Err(InputError::new("previous tool diameter", "none")
                .at(format!("--rest-from {}", from.program))
                .expected(
                    "the diameter of the tool that cut the previous program: \
                     --rest-from-diameter D (the program's header names none)",
                )
                .into());
        }
    };
    if tool.diameter >= previous_d {
        return Err(InputError::new("tool diameter", tool.diameter)
            .at("--tool-diameter with --rest-from")
            .expected(format!(
                "a tool smaller than the previous program's ({previous_d} mm), which cut \
                 everything a tool this size reaches"
            ))
            .into());
    }
    let vs = VerifySettings {
        tool_diameter: previous_d,
        select: select.map(str::to_owned),
        ..VerifySettings::default()
    };
    let previous = super::verify::run(loops, &text, &from.program, &vs)?.toolpath;
    let opts = RestOptions::default()
        .with_depth(popts.depth)
        .with_step_down(popts.step_down)
        .with_stepover((popts.stepover.distance(tool.diameter) / tool.diameter).min(1.0))
        .with_feed(popts.feed)
        .with_plunge_feed(popts.plunge_feed)
        .with_safe_height(popts.safe_height);
    let selected = super::pocket::parse_select(select, loops.len())?;
    let all = loops.pockets();
    let mut tp = Toolpath::new(tool, crate::geom::Point3::new(0.0, 0.0, popts.safe_height));
    let (mut left, mut runs) = (0.0, 0);
    let mut need = Vec::new();
    let mut shapes = Vec::new();
    for &i in &selected {
        let p = &all[i - 1];
        let shape = PocketShape::new(p.outer.clone(), p.islands.clone(), outline)?;
        let res = rest::generate(&shape, &previous, &tool, &opts)?;
        let spec = StockSpec {
            outer: &shape.outer,
            islands: &shape.islands,
            wall_stock: 0.0,
        };
        need.push(
            rest_need(
                spec,
                &previous,
                -popts.depth,
                &tool,
                opts.stepover * tool.diameter,
                (tool.radius() / 20.0).min(0.05),
            )
            .map_err(|e| Error::internal(format!("the rest pass's need: {e}")))?,
        );
        left += res.left_mm2;
        runs += res.runs;
        tp.append(&res.toolpath);
        shapes.push(shape);
    }
    let check = judge(&shapes, &previous, &tp, popts.depth)?;
    let mut gcode = Vec::new();
    write_program(&tp, &wopts, &mut gcode)
        .map_err(|e| e.engine_made("writing the rest program"))?;
    let (time_s, _) = program_times(&gcode, wopts.dialect, "the written rest program", &machine)
        .map_err(|e| e.engine_made("timing the written rest program"))?;
    let floor_cut_mm = floor_cut_length(&tp, -popts.depth);
    Ok(RestRun {
        gcode,
        toolpath: tp,
        previous_tool: previous.tool,
        left_mm2: left,
        runs,
        time_s,
        check,
        floor_cut_mm,
        need,
    })
}

/// Both programs on one block (module docs); the verdict, or an internal error.
pub(crate) fn judge(
    shapes: &[PocketShape],
    previous: &Toolpath,
    rest: &Toolpath,
    depth: f64,
) -> Result<String, Error> {
    let mut b: Option<Aabb> = None;
    for s in shapes {
        let o = s.outer.bounds();
        b = Some(b.map_or(o, |a| a.union(o)));
    }
    let Some(b) = b else {
        return Ok("nothing to cut".to_owned());
    };
    let m = 2.0 * previous.tool.diameter + 1.0;
    let bounds = Aabb {
        min: Point::new(b.min.x - m, b.min.y - m),
        max: Point::new(b.max.x + m, b.max.y + m),
    };
    let corners = [
        bounds.min,
        Point::new(bounds.max.x, bounds.min.y),
        bounds.max,
        Point::new(bounds.min.x, bounds.max.y),
    ];
    let block = Outline::from_points(&corners, "rest machining block")?;
    let mut field = HeightField::new(
        bounds,
        -2.0 * depth - 1.0,
        0.0,
        &FieldOptions::default().with_tool_diameter(rest.tool.diameter),
    )?;
    field.cut(previous);
    let cut = field.cut(rest);
    let mut problems: Vec<String> = cut.problems().iter().map(ToString::to_string).collect();
    let floors: Vec<Floor<'_>> = shapes
        .iter()
        .map(|s| Floor {
            outer: &s.outer,
            islands: &s.islands,
            z: -depth,
            tool_radius: rest.tool.radius(),
        })
        .collect();
    let windows: Vec<Outline> = shapes.iter().map(|s| s.outer.clone()).collect();
    let top = PartTop {
        outline: &block,
        windows: &windows,
        top_z: 0.0,
    };
    let check = check_field(&field, Some(top), &floors, &CheckOptions::default());
    if !check.passes() {
        problems.push(check.to_string());
    }
    if problems.is_empty() {
        Ok(check.to_string())
    } else {
        Err(Error::internal(format!(
            "the rest program fails the stock check after the previous program: {}; nothing \
             written",
            problems.join("; ")
        )))
    }
}
