//! `millpath job --init DRAWING`: a starting job file for a drawing, so that a user edits
//! rather than writes from nothing. It holds an operation for everything the drawing shows
//! (the part model: faced top, every pocket, every hole, every part profiled outside with
//! automatic tabs) and a tool table sized from the drawing, every value commented.
//!
//! # Sizing
//! `L` is the smaller side of the parts' extents.
//! * The main end mill is the largest of the usual sizes ([`END_MILLS`]) at most `L/15`
//!   (beyond the list, `L/15` to two significant digits). It faces and profiles; the
//!   profile's tool is smaller where two parts are closer than 1.5 diameters.
//! * Each pocket gets the largest usual end mill, at most the main one, whose diameter is at
//!   most the radius of the largest circle inside the pocket: the tool sweeps the pocket with
//!   room to turn, and leaves only what its radius must leave in the corners. Pockets of the
//!   same tool go into one operation.
//! * A hole up to [`DRILL_MAX`] (12 mm) is drilled with a drill of its diameter; a larger one
//!   is bored with the largest usual end mill at most 0.6 of its diameter (and the main one).
//! * The stock: thickness 1.5 main diameters (to 0.5 mm), pockets half as deep, `top` a
//!   twentieth of the main diameter (at least 0.2 mm) to face off, a margin of two profile
//!   tool diameters (at least 5 mm).
//! * Speeds and feeds for aluminium: 250 m/min at the edge (within 2,000–24,000 rev/min),
//!   0.004 mm per tooth per mm of diameter (0.005–0.1 mm); drills 80 m/min and 0.02 mm per
//!   revolution per mm of diameter. They are a start: the file says to check them.

use super::model::PartModel;
use crate::geom::Outline;

/// The usual end mill diameters, mm.
pub const END_MILLS: &[f64] = &[
    0.5, 0.8, 1.0, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0, 10.0, 12.0, 16.0, 20.0, 25.0,
];

/// Holes up to this diameter are drilled, larger ones bored, mm.
pub const DRILL_MAX: f64 = 12.0;

/// The largest usual end mill at most `d` mm (beyond the list, `d` to two significant
/// digits; below it, `d` itself).
pub fn end_mill_at_most(d: f64) -> f64 {
    let largest = END_MILLS[END_MILLS.len() - 1];
    if d >= 2.0 * largest {
        let e = d.log10().floor() - 1.0;
        let unit = 10f64.powf(e);
        return (d / unit).floor() * unit;
    }
    END_MILLS
        .iter()
        .rev()
        .find(|&&s| s <= d + 1e-9)
        .copied()
        .unwrap_or(d)
}

/// The radius of the largest circle inside `outer` (within 1 %), mm: the largest inward
/// offset that leaves something, by bisection.
fn inscribed_radius(outer: &Outline) -> f64 {
    let b = outer.bounds();
    let (mut lo, mut hi) = (0.0, 0.5 * b.width().min(b.height()));
    let ccw = outer
        .clone()
        .with_winding(crate::geom::Winding::CounterClockwise);
    let inside = |r: f64| ccw.offset(r).iter().any(|o| o.signed_area().abs() > 0.0);
    for _ in 0..30 {
        let mid = 0.5 * (lo + hi);
        if inside(mid) {
            lo = mid;
        } else {
            hi = mid;
        }
        if hi - lo < 0.01 * hi {
            break;
        }
    }
    lo
}

/// The smallest distance between two parts' outlines (infinite for one part), mm, from
/// points sampled every tenth of a millimetre at most 4096 per outline.
fn part_gap(parts: &[Outline]) -> f64 {
    let mut gap = f64::INFINITY;
    for (i, a) in parts.iter().enumerate() {
        let n = ((a.length() / 0.1).ceil() as usize).clamp(64, 4096);
        let pts = a.sample(n);
        for b in parts.iter().skip(i + 1) {
            for p in &pts {
                gap = gap.min(b.distance_to(*p));
            }
        }
    }
    gap
}

/// A tool of the table being made.
#[derive(Debug, Clone, PartialEq)]
struct InitTool {
    number: u32,
    drill: bool,
    diameter: f64,
}

/// Rounds to `step`.
fn round_to(x: f64, step: f64) -> f64 {
    (x / step).round() * step
}

/// Writes a number the way the file shows it (no trailing zeros).
fn num(x: f64) -> String {
    let s = format!("{x:.4}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s.contains('.') || s.contains('e') {
        s.to_owned()
    } else {
        format!("{s}.0")
    }
}

/// The job file text for the drawing `drawing` (as the file should name it) whose part model
/// is `model`; `dialect` and `machine` are written as given.
pub fn job_file(drawing: &str, model: &PartModel, dialect: &str, machine: &str) -> String {
    let Some(ext) = model.bounds() else {
        return String::new();
    };
    let l = ext.width().min(ext.height());
    let main = end_mill_at_most(l / 15.0);
    let gap = part_gap(&model.parts);
    let profile_d = end_mill_at_most(main.min(gap / 1.5));
    let thickness = round_to(main, 0.5).max(0.5);
    let top = round_to((main / 20.0).max(0.2), 0.1);
    let pocket_depth = round_to(0.5 * thickness, 0.1).max(0.1);
    let margin = (2.0 * profile_d).max(5.0);

    let mut tools: Vec<InitTool> = Vec::new();
    let mut tool = |drill: bool, d: f64| -> u32 {
        if let Some(t) = tools
            .iter()
            .find(|t| t.drill == drill && (t.diameter - d).abs() < 1e-9)
        {
            return t.number;
        }
        let number = tools.len() as u32 + 1;
        tools.push(InitTool {
            number,
            drill,
            diameter: d,
        });
        number
    };
    let face_tool = tool(false, main);
    // Pockets grouped by tool, largest tool first.
    let mut pocket_groups: Vec<(f64, Vec<usize>)> = Vec::new();
    for (i, p) in model.pockets.iter().enumerate() {
        let d = end_mill_at_most(main.min(inscribed_radius(&p.outer)));
        match pocket_groups.iter_mut().find(|g| (g.0 - d).abs() < 1e-9) {
            Some(g) => g.1.push(i + 1),
            None => pocket_groups.push((d, vec![i + 1])),
        }
    }
    pocket_groups.sort_by(|a, b| b.0.total_cmp(&a.0));
    let pocket_ops: Vec<(u32, f64, Vec<usize>)> = pocket_groups
        .into_iter()
        .map(|(d, ps)| (tool(false, d), d, ps))
        .collect();
    // One bore for every hole over DRILL_MAX, with an end mill already in the table where
    // one is small enough; then drills by diameter.
    let mut drills: Vec<f64> = Vec::new();
    let mut bored: Option<(f64, f64)> = None;
    for h in &model.holes {
        let d = round_to(h.diameter, 0.01);
        if d <= DRILL_MAX {
            if !drills.iter().any(|x| (x - d).abs() < 1e-9) {
                drills.push(d);
            }
        } else {
            bored = Some(bored.map_or((d, d), |(lo, hi)| (lo.min(d), hi.max(d))));
        }
    }
    drills.sort_by(f64::total_cmp);
    let bore_ops: Vec<(u32, f64, f64, f64)> = match bored {
        None => Vec::new(),
        Some((lo, hi)) => {
            let limit = main.min(0.6 * lo);
            let have = pocket_ops
                .iter()
                .map(|(_, d, _)| *d)
                .chain([main])
                .filter(|&d| d <= limit + 1e-9)
                .fold(0.0f64, f64::max);
            let t = if have > 0.0 {
                have
            } else {
                end_mill_at_most(limit)
            };
            vec![(tool(false, t), t, lo, hi)]
        }
    };
    let drill_ops: Vec<(u32, f64)> = drills.into_iter().map(|d| (tool(true, d), d)).collect();
    let profile_tool = tool(false, profile_d);

    let mut s = String::new();
    let mut line = |t: &str| {
        s.push_str(t);
        s.push('\n');
    };
    line("# millpath job, written by `millpath job --init`: edit it, then run");
    line("#   millpath job THIS_FILE -o part.ngc --html part.html");
    line(&format!(
        "# The drawing holds {} part(s), {} pocket(s) and {} hole(s); its extents are {} x {} mm.",
        model.parts.len(),
        model.pockets.len(),
        model.holes.len(),
        num(ext.width()),
        num(ext.height())
    ));
    line("# Z = 0 is the finished part's top; depths are measured down from it.");
    line("# Tools, speeds and feeds are a start sized from the drawing: check them for your");
    line("# machine, material and tools.");
    line("");
    line(&format!(
        "drawing = \"{}\"",
        drawing.replace('\\', "\\\\").replace('"', "\\\"")
    ));
    line(&format!(
        "machine = \"{machine}\"          # preset or a TOML machine profile, for the cycle time"
    ));
    line(&format!(
        "dialect = \"{dialect}\"       # linuxcnc, fanuc, sinumerik or grbl"
    ));
    line("clearance_height = 5.0      # mm above the stock's top, for rapids between cuts");
    line("");
    line("[stock]");
    line(&format!(
        "margin = {}                # mm around the drawing's parts",
        num(margin)
    ));
    line(&format!(
        "thickness = {}             # mm: the part's bottom is at z = -thickness",
        num(thickness)
    ));
    line(&format!(
        "top = {}                   # mm of material above the part's top, faced off",
        num(top)
    ));
    line("breakthrough = 0.5          # mm below the stock's bottom for cuts \"through\"");
    for t in &tools {
        line("");
        line("[[tool]]");
        line(&format!("number = {}", t.number));
        let (rpm, feed, plunge) = speeds(t);
        if t.drill {
            line("type = \"drill\"");
            line(&format!("diameter = {}", num(t.diameter)));
            line("flutes = 2");
        } else {
            line("type = \"end mill\"");
            line(&format!("diameter = {}", num(t.diameter)));
            line(&format!(
                "flutes = {}",
                if t.diameter < 3.0 { 2 } else { 3 }
            ));
        }
        line(&format!(
            "flute_length = {}    # mm",
            num((3.0 * t.diameter).max(round_to(thickness + 2.0, 0.5)))
        ));
        line(&format!("spindle = {}         # rev/min", num(rpm)));
        line(&format!("feed = {}            # mm/min", num(feed)));
        line(&format!("plunge_feed = {}     # mm/min", num(plunge)));
    }
    line("");
    line("# Operations run in this order, each with its tool; the profile comes last, so that");
    line("# the part is held by the stock until it is cut out (and then by its tabs).");
    line("");
    line("[[operation]]");
    line("type = \"face\"");
    line("name = \"face the stock's top\"");
    line(&format!("tool = {face_tool}"));
    line("stepover = 0.7             # of the tool's diameter");
    for (t, d, ps) in &pocket_ops {
        line("");
        line("[[operation]]");
        line("type = \"pocket\"");
        line(&format!("name = \"pockets with D{} mm\"", num(*d)));
        line(&format!("tool = {t}"));
        line(&format!(
            "select = \"{}\"        # the drawing's pockets, largest first",
            ps.iter()
                .map(ToString::to_string)
                .collect::<Vec<_>>()
                .join(",")
        ));
        line(
            "strategy = \"spiral\"        # spiral, offset, zigzag or auto (the fastest verified)",
        );
        line(&format!(
            "depth = {}                 # mm below the part's top",
            num(pocket_depth)
        ));
        line(&format!("step_down = {}", num((0.5 * d).min(pocket_depth))));
        line("stepover = 0.4             # of the tool's diameter");
    }
    for (t, d, lo, hi) in &bore_ops {
        line("");
        line("[[operation]]");
        line("type = \"bore\"");
        line(&format!(
            "name = \"bore holes D{}..D{} mm\"",
            num(*lo),
            num(*hi)
        ));
        line(&format!("tool = {t}"));
        line(&format!("min_diameter = {}", num(lo - 0.005)));
        line(&format!("max_diameter = {}", num(hi + 0.005)));
        line("depth = \"through\"");
        line(&format!(
            "pitch = {}                 # mm of depth per turn of the helix",
            num((0.25 * d).max(0.1))
        ));
    }
    for (t, d) in &drill_ops {
        line("");
        line("[[operation]]");
        line("type = \"drill\"");
        line(&format!("name = \"drill holes D{} mm\"", num(*d)));
        line(&format!("tool = {t}"));
        line(&format!("min_diameter = {}", num(d - 0.005)));
        line(&format!("max_diameter = {}", num(d + 0.005)));
        line("depth = \"through\"");
        if thickness > 3.0 * d {
            line(&format!(
                "peck = {}                  # mm per peck (G83)",
                num(*d)
            ));
        }
    }
    line("");
    line("[[operation]]");
    line("type = \"profile\"");
    line("name = \"cut the part out\"");
    line(&format!("tool = {profile_tool}"));
    line("side = \"auto\"              # outermost outlines outside, their holes inside");
    line("depth = \"through\"");
    line(&format!(
        "step_down = {}",
        num((0.5 * profile_d).min(thickness))
    ));
    line("tabs = \"auto\"              # a count, \"auto\" (from the perimeter) or 0");
    s
}

/// Spindle speed, feed and plunge feed (rev/min, mm/min, mm/min) for a tool (module docs).
fn speeds(t: &InitTool) -> (f64, f64, f64) {
    let d = t.diameter;
    if t.drill {
        let rpm = (80_000.0 / (std::f64::consts::PI * d)).clamp(500.0, 10_000.0);
        let feed = rpm * (0.02 * d).clamp(0.01, 0.3);
        (
            round_to(rpm, 10.0),
            round_to(feed, 1.0).max(1.0),
            round_to(feed, 1.0).max(1.0),
        )
    } else {
        let rpm = (250_000.0 / (std::f64::consts::PI * d)).clamp(2_000.0, 24_000.0);
        let flutes = if d < 3.0 { 2.0 } else { 3.0 };
        let feed = rpm * flutes * (0.004 * d).clamp(0.005, 0.1);
        (
            round_to(rpm, 10.0),
            round_to(feed, 1.0).max(1.0),
            round_to(feed / 3.0, 1.0).max(1.0),
        )
    }
}
