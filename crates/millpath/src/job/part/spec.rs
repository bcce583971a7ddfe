//! The job file: a drawing, the stock, a tool table and an ordered list of operations, read
//! from TOML into checked settings (every refusal names the key, the table and the line).
//!
//! ```toml
//! drawing = "part.dxf"       # relative to the job file
//! machine = "hsm"            # preset or TOML profile, for the cycle time
//! dialect = "linuxcnc"       # linuxcnc, fanuc, sinumerik or grbl
//!
//! [stock]
//! margin = 12.0              # mm around the drawing's extents (or size = [x, y], origin = [x, y]);
//!                             # default: two diameters of the largest end mill, at least 5
//! thickness = 6.0            # mm: the part's bottom is at z = -thickness
//! top = 0.5                  # mm of material above the part's top (z = 0), faced off
//!
//! [[tool]]
//! number = 1
//! type = "end mill"          # or "drill"
//! diameter = 6.0
//! feed = 1200                # mm/min, or "48ipm"
//! spindle = 12000
//!
//! [[operation]]
//! type = "pocket"            # face, pocket, profile, drill or bore
//! tool = 1
//! depth = 3.0
//! ```
//!
//! Coordinates: the drawing's XY, z = 0 at the finished part's top, the stock from
//! `-thickness` to `top`. Depths are measured down from z = 0; `"through"` is the stock's
//! thickness plus `[stock] breakthrough`.

use super::keys::{Keys, line_of};
use crate::error::InputError;
use crate::gcode::{Coolant, Dialect, Units};
use crate::io::ImportSettings;
use crate::job::pocket::{PocketSettings, parse_feed};
use toml::de::DeTable;

/// The top-level keys of a job file.
const TOP_KEYS: &[&str] = &[
    "drawing",
    "layer",
    "drawing_units",
    "join_tolerance",
    "machine",
    "dialect",
    "units",
    "decimals",
    "line_numbers",
    "coolant",
    "tolerance",
    "clearance_height",
    "safe_height",
    "stock",
    "tool",
    "operation",
];

const STOCK_KEYS: &[&str] = &[
    "margin",
    "size",
    "origin",
    "thickness",
    "top",
    "breakthrough",
];

const TOOL_KEYS: &[&str] = &[
    "number",
    "name",
    "type",
    "diameter",
    "flutes",
    "flute_length",
    "feed",
    "plunge_feed",
    "spindle",
];

/// Keys every operation takes.
const OPERATION_KEYS: &[&str] = &["type", "tool", "name", "feed", "plunge_feed"];

/// What a tool is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ToolKind {
    /// A flat end mill: cuts with its side and its bottom (not at its centre).
    EndMill,
    /// A twist drill: cuts only along its axis.
    Drill,
}

impl ToolKind {
    /// The name the job file uses.
    pub fn name(self) -> &'static str {
        match self {
            ToolKind::EndMill => "end mill",
            ToolKind::Drill => "drill",
        }
    }
}

/// One tool of the job's tool table.
#[derive(Debug, Clone, PartialEq)]
pub struct JobTool {
    /// Tool number (`T`), 1..=9999, unique in the table.
    pub number: u32,
    /// A name for the setup sheet.
    pub name: String,
    /// End mill or drill.
    pub kind: ToolKind,
    /// Diameter, mm.
    pub diameter: f64,
    /// Flutes.
    pub flutes: u32,
    /// Flute length, mm.
    pub flute_length: f64,
    /// Cutting feed, mm/s.
    pub feed: f64,
    /// Plunge feed, mm/s.
    pub plunge_feed: f64,
    /// Spindle speed, rev/min.
    pub spindle: f64,
    /// Line of its `[[tool]]` header.
    pub line: usize,
}

/// How deep an operation cuts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Depth {
    /// This far below the part's top (z = 0), mm.
    Mm(f64),
    /// Through the stock: its thickness plus the breakthrough.
    Through,
}

/// Facing: the stock's top down to the part's top.
#[derive(Debug, Clone, PartialEq)]
pub struct FaceSettings {
    /// Step-down per level, mm (`None`: the whole allowance in one level when the tool's
    /// flutes are long enough).
    pub step_down: Option<f64>,
    /// Stepover as a fraction of the diameter.
    pub stepover: f64,
}

/// Profiling the drawing's outlines.
#[derive(Debug, Clone, PartialEq)]
pub struct ProfileSettings {
    /// Which parts (outermost outlines) by their 1-based order; all when `None`.
    pub select: Option<String>,
    /// `auto` (outermost outside, their holes inside), `outside`, `inside` or `on`.
    pub side: String,
    /// Depth.
    pub depth: Depth,
    /// Step-down per level, mm (`None`: the tool's flute length, at most the depth).
    pub step_down: Option<f64>,
    /// Stock left for the finishing pass, mm (0: no finishing pass).
    pub stock_to_leave: f64,
    /// Conventional milling instead of climb.
    pub conventional: bool,
    /// Lead-in/out arc radius, mm (`None`: the strategy's default).
    pub lead_radius: Option<f64>,
    /// `ramp` or `helix`.
    pub entry: String,
    /// Chordal tolerance, mm.
    pub tolerance: f64,
    /// Tabs: `auto`, a count, or `0` for none.
    pub tabs: String,
    /// Tab width along the outline, mm (`None`: the strategy's default).
    pub tab_width: Option<f64>,
    /// Tab height above the profile's bottom, mm (`None`: the strategy's default).
    pub tab_height: Option<f64>,
    /// `square` or `ramped`.
    pub tab_shape: String,
}

/// Drilling holes whose diameter is the drill's.
#[derive(Debug, Clone, PartialEq)]
pub struct DrillSettings {
    /// Smallest hole diameter taken, mm.
    pub min_diameter: f64,
    /// Largest hole diameter taken, mm.
    pub max_diameter: f64,
    /// Depth.
    pub depth: Depth,
    /// Peck depth (G83), mm.
    pub peck: Option<f64>,
    /// Chip-breaking peck (G73), mm.
    pub chip_break: Option<f64>,
    /// Dwell at the bottom, s.
    pub dwell: Option<f64>,
}

/// Boring holes larger than the tool by a helix and a finishing circle.
#[derive(Debug, Clone, PartialEq)]
pub struct BoreSettings {
    /// Smallest hole diameter taken, mm.
    pub min_diameter: f64,
    /// Largest hole diameter taken, mm.
    pub max_diameter: f64,
    /// Depth.
    pub depth: Depth,
    /// Helix pitch (depth per turn), mm (`None`: the strategy's default).
    pub pitch: Option<f64>,
}

/// What an operation does, with its own settings.
#[derive(Debug, Clone, PartialEq)]
pub enum OperationKind {
    /// Face the stock's top.
    Face(FaceSettings),
    /// Pocket the drawing's inner outlines (settings as `millpath pocket`'s flags).
    Pocket(Box<PocketSettings>, Option<String>),
    /// Profile the drawing's outlines.
    Profile(ProfileSettings),
    /// Drill holes.
    Drill(DrillSettings),
    /// Bore holes.
    Bore(BoreSettings),
}

impl OperationKind {
    /// The type name the job file uses.
    pub fn name(&self) -> &'static str {
        match self {
            OperationKind::Face(_) => "face",
            OperationKind::Pocket(..) => "pocket",
            OperationKind::Profile(_) => "profile",
            OperationKind::Drill(_) => "drill",
            OperationKind::Bore(_) => "bore",
        }
    }
}

/// One operation of the job.
#[derive(Debug, Clone, PartialEq)]
pub struct JobOperation {
    /// Its name (the `name` key, or `2 pocket`).
    pub name: String,
    /// The tool number it cuts with (a tool of the table).
    pub tool: u32,
    /// Cutting feed override, mm/s.
    pub feed: Option<f64>,
    /// Plunge feed override, mm/s.
    pub plunge_feed: Option<f64>,
    /// What it does.
    pub kind: OperationKind,
    /// Line of its `[[operation]]` header.
    pub line: usize,
    /// A pocket operation's `rest_from`: the name of an earlier pocket operation with a
    /// larger tool; this one then cuts only what that one left (rest machining,
    /// [`crate::strategy::rest`]).
    pub rest_from: Option<String>,
}

/// The stock block.
#[derive(Debug, Clone, PartialEq)]
pub struct StockSettings {
    /// Margin around the drawing's extents, mm (when no size is given).
    pub margin: f64,
    /// Size in X and Y, mm (`None`: the extents plus the margin).
    pub size: Option<[f64; 2]>,
    /// Lower-left corner, mm (`None`: centred on the drawing's extents).
    pub origin: Option<[f64; 2]>,
    /// The part's thickness, mm: the stock's bottom is at `-thickness`.
    pub thickness: f64,
    /// Material above the part's top (z = 0), mm: the stock's top is at `top`.
    pub top: f64,
    /// How far a cut "through" goes below the stock's bottom, mm.
    pub breakthrough: f64,
}

/// A whole job, read and checked.
#[derive(Debug, Clone, PartialEq)]
pub struct JobSpec {
    /// The job file's name, for messages.
    pub origin: String,
    /// The drawing's path (relative paths are the job file's folder's).
    pub drawing: String,
    /// How the drawing is read.
    pub import: ImportSettings,
    /// Machine preset or profile for the cycle time.
    pub machine: String,
    /// Dialect.
    pub dialect: Dialect,
    /// Program units.
    pub units: Units,
    /// Decimals (`None`: the dialect's, raised to what the tolerances need).
    pub decimals: Option<u32>,
    /// N numbers.
    pub line_numbers: bool,
    /// Coolant.
    pub coolant: Coolant,
    /// The program's path tolerance, mm (`None`: the machine's where above 0, else 0.01).
    pub tolerance: Option<f64>,
    /// Clearance height above the stock's top, mm.
    pub clearance_height: f64,
    /// Safe height above a level's top, mm.
    pub safe_height: f64,
    /// The stock.
    pub stock: StockSettings,
    /// The tool table.
    pub tools: Vec<JobTool>,
    /// The operations, in order.
    pub operations: Vec<JobOperation>,
}

impl JobSpec {
    /// The tool numbered `n`.
    pub fn tool(&self, n: u32) -> Option<&JobTool> {
        self.tools.iter().find(|t| t.number == n)
    }

    /// A depth in mm below z = 0.
    pub fn depth_mm(&self, d: Depth) -> f64 {
        match d {
            Depth::Mm(x) => x,
            Depth::Through => self.stock.thickness + self.stock.breakthrough,
        }
    }
}

/// Reads a job file's text; `origin` names it in messages and `folder` is where a relative
/// `drawing` path starts from.
pub fn parse(
    text: &str,
    origin: &str,
    folder: Option<&std::path::Path>,
) -> Result<JobSpec, InputError> {
    let doc = DeTable::parse(text).map_err(|e| {
        let line = e.span().map_or(1, |s| line_of(text, s.start));
        InputError::new("TOML", e.message().trim().to_owned())
            .at(format!("{origin} line {line}"))
            .expected("a job file in TOML (see `millpath job --help`)")
    })?;
    let top = Keys::new(doc.get_ref(), text, origin, "", 1);
    top.only(TOP_KEYS)?;
    let drawing = top.str("drawing")?.ok_or_else(|| {
        InputError::new("drawing", "missing")
            .at(origin.to_owned())
            .expected("drawing = \"part.dxf\" (a DXF or SVG file, relative to the job file)")
    })?;
    let drawing = match folder {
        Some(f) if std::path::Path::new(&drawing).is_relative() => {
            f.join(&drawing).to_string_lossy().into_owned()
        }
        _ => drawing,
    };
    let mut import = ImportSettings {
        layer: top.str("layer")?,
        drawing_units: top.str("drawing_units")?,
        ..ImportSettings::default()
    };
    if let Some(j) = top.non_negative("join_tolerance", "mm")? {
        import.join_tolerance = j;
    }
    let dialect = match top.str("dialect")? {
        None => Dialect::LinuxCnc,
        Some(d) => d.parse::<Dialect>().map_err(|_| {
            top.error("dialect", &d)
                .expected("linuxcnc, fanuc, sinumerik or grbl")
        })?,
    };
    let units = match top.str("units")?.as_deref() {
        None | Some("mm") => Units::Mm,
        Some("in" | "inch") => Units::Inch,
        Some(u) => return Err(top.error("units", u).expected("mm or in")),
    };
    let coolant = match top.str("coolant")?.as_deref() {
        None | Some("flood") => Coolant::Flood,
        Some("mist") => Coolant::Mist,
        Some("off") => Coolant::Off,
        Some(c) => return Err(top.error("coolant", c).expected("flood, mist or off")),
    };
    let tools = tools(&top)?;
    let stock = stock(&top, &tools)?;
    let operations = operations(&top, &tools)?;
    Ok(JobSpec {
        origin: origin.to_owned(),
        drawing,
        import,
        machine: top.str("machine")?.unwrap_or_else(|| "hsm".to_owned()),
        dialect,
        units,
        decimals: top.u32("decimals", 0..=crate::gcode::format::MAX_DECIMALS)?,
        line_numbers: top.bool("line_numbers")?.unwrap_or(false),
        coolant,
        tolerance: top.non_negative("tolerance", "mm")?,
        clearance_height: top.positive("clearance_height", "mm")?.unwrap_or(5.0),
        safe_height: top.positive("safe_height", "mm")?.unwrap_or(1.0),
        stock,
        tools,
        operations,
    })
}

fn stock(top: &Keys<'_, '_>, tools: &[JobTool]) -> Result<StockSettings, InputError> {
    let empty = DeTable::new();
    let (t, line) = top.table("stock")?.unwrap_or((&empty, 1));
    let k = Keys::new(t, top_text(top), top_origin(top), "[stock]", line);
    k.only(STOCK_KEYS)?;
    let size = k.numbers("size", 2)?.map(|v| [v[0], v[1]]);
    if let Some(s) = size
        && !(s[0] > 0.0 && s[1] > 0.0)
    {
        return Err(k
            .error("size", format_args!("[{}, {}]", s[0], s[1]))
            .expected("two lengths > 0 mm"));
    }
    Ok(StockSettings {
        margin: k
            .non_negative("margin", "mm")?
            .unwrap_or_else(|| default_margin(tools)),
        size,
        origin: k.numbers("origin", 2)?.map(|v| [v[0], v[1]]),
        thickness: k.positive("thickness", "mm")?.unwrap_or(10.0),
        top: k.non_negative("top", "mm")?.unwrap_or(0.0),
        breakthrough: k.non_negative("breakthrough", "mm")?.unwrap_or(0.5),
    })
}

/// The margin when the file gives none: two diameters of the largest end mill, at least 5 mm.
/// A part cut out through the stock is held by tabs to the frame the profile's slot (a
/// diameter wide) and its leads leave around it; a narrower margin leaves no frame.
fn default_margin(tools: &[JobTool]) -> f64 {
    tools
        .iter()
        .filter(|t| t.kind == ToolKind::EndMill)
        .map(|t| 2.0 * t.diameter)
        .fold(5.0, f64::max)
}

// `Keys` keeps its text and origin private; these read them back for sub-tables.
fn top_text<'a>(k: &Keys<'a, '_>) -> &'a str {
    k.text_ref()
}

fn top_origin<'a>(k: &Keys<'a, '_>) -> &'a str {
    k.origin_ref()
}

fn feed_of(k: &Keys<'_, '_>, key: &str) -> Result<Option<f64>, InputError> {
    match k.text(key)? {
        None => Ok(None),
        Some(t) => parse_feed(&t).map(Some).map_err(|_| {
            k.error(key, &t)
                .expected("a feed in mm/min (1200) or in/min (\"48ipm\") > 0")
        }),
    }
}

fn tools(top: &Keys<'_, '_>) -> Result<Vec<JobTool>, InputError> {
    let mut out: Vec<JobTool> = Vec::new();
    for (i, (t, line)) in top.tables("tool")?.into_iter().enumerate() {
        let name = format!("[[tool]] {}", i + 1);
        let k = Keys::new(t, top_text(top), top_origin(top), &name, line);
        k.only(TOOL_KEYS)?;
        let number = k
            .u32("number", 1..=crate::job::program::MAX_TOOL_NUMBER)?
            .ok_or_else(|| {
                InputError::new("number", "missing")
                    .at(k.at_line(line))
                    .expected("number = 1 (the tool's T number, 1 to 9999)")
            })?;
        if let Some(other) = out.iter().find(|o| o.number == number) {
            return Err(k.error("number", number).expected(format!(
                "a number no other tool has (line {} has T{number})",
                other.line
            )));
        }
        let kind = match k.str("type")?.as_deref() {
            None | Some("end mill" | "endmill" | "flat") => ToolKind::EndMill,
            Some("drill") => ToolKind::Drill,
            Some(x) => return Err(k.error("type", x).expected("\"end mill\" or \"drill\"")),
        };
        let diameter = k.positive("diameter", "mm")?.ok_or_else(|| {
            InputError::new("diameter", "missing")
                .at(k.at_line(line))
                .expected("diameter = 6.0 (mm)")
        })?;
        let flutes = k.u32("flutes", 1..=64)?.unwrap_or(match kind {
            ToolKind::EndMill => 3,
            ToolKind::Drill => 2,
        });
        let feed = feed_of(&k, "feed")?.unwrap_or(1000.0 / 60.0);
        out.push(JobTool {
            number,
            name: k
                .str("name")?
                .unwrap_or_else(|| format!("{} D{diameter} mm", kind.name())),
            kind,
            diameter,
            flutes,
            flute_length: k.positive("flute_length", "mm")?.unwrap_or(3.0 * diameter),
            feed,
            plunge_feed: feed_of(&k, "plunge_feed")?.unwrap_or(feed / 3.0),
            spindle: k.non_negative("spindle", "rev/min")?.unwrap_or(10_000.0),
            line,
        });
    }
    Ok(out)
}

fn depth_of(k: &Keys<'_, '_>, required: bool) -> Result<Option<Depth>, InputError> {
    if k.has("depth")
        && let Ok(Some(s)) = k.str("depth")
    {
        return if s == "through" {
            Ok(Some(Depth::Through))
        } else {
            Err(k
                .error("depth", format_args!("\"{s}\""))
                .expected("a depth in mm > 0 or \"through\""))
        };
    }
    match k.positive("depth", "mm (or \"through\")")? {
        Some(d) => Ok(Some(Depth::Mm(d))),
        None if required => Err(InputError::new("depth", "missing")
            .at(k.at_line(k.line()))
            .expected("depth = 3.0 (mm below the part's top) or depth = \"through\"")),
        None => Ok(None),
    }
}

fn operations(top: &Keys<'_, '_>, tools: &[JobTool]) -> Result<Vec<JobOperation>, InputError> {
    let mut out = Vec::new();
    for (i, (t, line)) in top.tables("operation")?.into_iter().enumerate() {
        let pre = Keys::new(t, top_text(top), top_origin(top), "", line);
        let kind = pre.str("type")?.unwrap_or_default();
        let name = format!("[[operation]] {} ({kind})", i + 1);
        let k = Keys::new(t, top_text(top), top_origin(top), &name, line);
        let extra: &[&str] = match kind.as_str() {
            "face" => &["step_down", "stepover"],
            "pocket" => super::pocket_keys::KEYS,
            "profile" => &[
                "select",
                "side",
                "depth",
                "step_down",
                "stock_to_leave",
                "conventional",
                "lead_radius",
                "entry",
                "tolerance",
                "tabs",
                "tab_width",
                "tab_height",
                "tab_shape",
            ],
            "drill" => &[
                "min_diameter",
                "max_diameter",
                "depth",
                "peck",
                "chip_break",
                "dwell",
            ],
            "bore" => &["min_diameter", "max_diameter", "depth", "pitch"],
            "" => {
                return Err(InputError::new("type", "missing")
                    .at(k.at_line(line))
                    .expected("type = \"face\", \"pocket\", \"profile\", \"drill\" or \"bore\""));
            }
            other => {
                return Err(k
                    .error("type", format_args!("\"{other}\""))
                    .expected("face, pocket, profile, drill or bore"));
            }
        };
        let allowed: Vec<&str> = OPERATION_KEYS.iter().chain(extra).copied().collect();
        k.only(&allowed)?;
        let tool_n = k
            .u32("tool", 1..=crate::job::program::MAX_TOOL_NUMBER)?
            .ok_or_else(|| {
                InputError::new("tool", "missing")
                    .at(k.at_line(line))
                    .expected("tool = 1 (the number of a [[tool]] of this file)")
            })?;
        let Some(tool) = tools.iter().find(|t| t.number == tool_n) else {
            let have: Vec<String> = tools.iter().map(|t| format!("T{}", t.number)).collect();
            return Err(k.error("tool", tool_n).expected(if have.is_empty() {
                "a tool of the tool table, which has none: add a [[tool]]".to_owned()
            } else {
                format!("a tool of the tool table ({})", have.join(", "))
            }));
        };
        let kind = match kind.as_str() {
            "face" => OperationKind::Face(FaceSettings {
                step_down: k.positive("step_down", "mm")?,
                stepover: k.fraction("stepover")?.unwrap_or(0.7),
            }),
            "pocket" => {
                let (s, select) = super::pocket_keys::read(
                    &k,
                    super::pocket_keys::ToolSize {
                        diameter: tool.diameter,
                        flute_length: tool.flute_length,
                        feed: tool.feed,
                    },
                )?;
                OperationKind::Pocket(Box::new(s), select)
            }
            "profile" => OperationKind::Profile(ProfileSettings {
                select: k.text("select")?,
                side: k.str("side")?.unwrap_or_else(|| "auto".to_owned()),
                depth: depth_of(&k, false)?.unwrap_or(Depth::Through),
                step_down: k.positive("step_down", "mm")?,
                stock_to_leave: k.non_negative("stock_to_leave", "mm")?.unwrap_or(0.0),
                conventional: k.bool("conventional")?.unwrap_or(false),
                lead_radius: k.non_negative("lead_radius", "mm")?,
                entry: k.str("entry")?.unwrap_or_else(|| "ramp".to_owned()),
                tolerance: k.positive("tolerance", "mm")?.unwrap_or(0.01),
                tabs: k.text("tabs")?.unwrap_or_else(|| "auto".to_owned()),
                tab_width: k.positive("tab_width", "mm")?,
                tab_height: k.positive("tab_height", "mm")?,
                tab_shape: k.str("tab_shape")?.unwrap_or_else(|| "ramped".to_owned()),
            }),
            "drill" | "bore" => {
                let min = k.non_negative("min_diameter", "mm")?.unwrap_or(0.0);
                let max = k.positive("max_diameter", "mm")?.unwrap_or(f64::INFINITY);
                if min > max {
                    return Err(k
                        .error("min_diameter", min)
                        .expected(format!("at most max_diameter ({max} mm)")));
                }
                let depth = depth_of(&k, false)?.unwrap_or(Depth::Through);
                if kind == "drill" {
                    OperationKind::Drill(DrillSettings {
                        min_diameter: min,
                        max_diameter: max,
                        depth,
                        peck: k.positive("peck", "mm")?,
                        chip_break: k.positive("chip_break", "mm")?,
                        dwell: k.non_negative("dwell", "s")?,
                    })
                } else {
                    OperationKind::Bore(BoreSettings {
                        min_diameter: min,
                        max_diameter: max,
                        depth,
                        pitch: k.positive("pitch", "mm")?,
                    })
                }
            }
            _ => unreachable_kind()?,
        };
        let name = k.str("name")?.unwrap_or_else(|| kind.name().to_owned());
        let rest_from = match k.str("rest_from")? {
            Some(from) => {
                check_rest_from(&k, &from, &out, tool)?;
                Some(from)
            }
            None => None,
        };
        out.push(JobOperation {
            name,
            tool: tool_n,
            feed: feed_of(&k, "feed")?,
            plunge_feed: feed_of(&k, "plunge_feed")?,
            kind,
            line,
            rest_from,
        });
    }
    Ok(out)
}

/// A pocket operation's `rest_from = "NAME"` (with `tool`) names the last earlier operation
/// called `NAME`: a pocket operation, not itself a rest pass, with a larger tool.
fn check_rest_from(
    k: &Keys<'_, '_>,
    from: &str,
    earlier: &[JobOperation],
    tool: &JobTool,
) -> Result<(), InputError> {
    let names: Vec<String> = earlier
        .iter()
        .filter(|o| matches!(o.kind, OperationKind::Pocket(..)) && o.rest_from.is_none())
        .map(|o| format!("\"{}\"", o.name))
        .collect();
    let expected = || {
        if names.is_empty() {
            "the name of an earlier pocket operation (this job has none before this one)".to_owned()
        } else {
            format!(
                "the name of an earlier pocket operation with a larger tool ({})",
                names.join(", ")
            )
        }
    };
    let Some(op) = earlier.iter().rev().find(|o| o.name == from) else {
        return Err(k
            .error("rest_from", format_args!("\"{from}\""))
            .expected(expected()));
    };
    if !matches!(op.kind, OperationKind::Pocket(..)) || op.rest_from.is_some() {
        return Err(k
            .error("rest_from", format_args!("\"{from}\" ({})", op.kind.name()))
            .expected(format!(
                "{}; a rest pass follows a whole pocket operation",
                expected()
            )));
    }
    let previous = match &op.kind {
        OperationKind::Pocket(s, _) => s.tool_diameter,
        _ => f64::NAN,
    };
    if tool.diameter >= previous {
        return Err(k
            .error("rest_from", format_args!("\"{from}\" (D{previous} mm)"))
            .expected(format!(
                "an operation with a tool larger than this one's (D{} mm): the smaller tool \
                 cuts what the larger one left",
                tool.diameter
            )));
    }
    Ok(())
}

fn unreachable_kind() -> Result<OperationKind, InputError> {
    Err(InputError::new("operation type", "unknown")
        .expected("face, pocket, profile, drill or bore"))
}
