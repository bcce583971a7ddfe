//! `millpath job --init DRAWING`: a starting job file for a drawing, so that a user edits
//! rather than writes from nothing. It holds an operation for everything the drawing shows
//! (the part model: faced top, every pocket, every hole, every part profiled outside with
//! automatic tabs) and a tool table sized from the drawing, every value commented.
//!
//! # Sizing
//! `L` is the smaller side of the parts' extents.
//! * The main end mill is the largest of the usual sizes ([`END_MILLS`]) at most `L/15`
//!   (beyond the list, `L/15` to two significant digits). It faces and profiles; the
//!   profile's tool is smaller where two parts are closer than 1.5 diameters, and smaller
//!   again (the next usual sizes down, to a tenth of the main one) until every part it cuts
//!   out has room for a tab and its lift (a gear's flanks, a curve drawn in short lines).
//! * No end mill is smaller than a tenth of the main one ([`SMALLEST_TOOL`]): a pocket that
//!   only a smaller tool could sweep, and a part closer to another than 1.5 such tools, is
//!   left out of its operation, and the file says which and why (a tool that small would
//!   make the job hours long, when it fits at all).
//! * Each pocket gets the largest usual end mill, at most the main one, whose diameter is at
//!   most the radius of the largest circle inside the pocket: the tool sweeps the pocket with
//!   room to turn, and leaves only what its radius must leave in the corners. Pockets of the
//!   same tool go into one operation.
//! * A hole up to [`DRILL_MAX`] (12 mm) is drilled with a drill of its diameter rounded down
//!   to 0.01 mm (a larger drill would cut the part's wall; [`DRILL_OVER`]); a larger one
//!   is bored with the largest usual end mill at most 0.6 of its diameter (and the main one).
//! * The tabs: a third of the stock's thickness high, at most the profile tool's radius
//!   ([`super::design::default_tab_height`]: a ramped tab's ramps, twice its height either
//!   side, run a tool diameter at most, so a small tool on a small part makes small tabs), and
//!   as wide as the widest of the default ([`super::design::default_tab_width`]), `2d`, `d`
//!   and `d/2` with which every part gets its tabs (`d` the profile tool's diameter).
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

/// How much larger than a hole its drill may be, mm: a drawing's rounding. A drill larger
/// than its hole cuts the part's wall by half the difference, here at most 0.25 µm, below
/// what the whole-job check reads as a cut into the part (the program's resolution).
pub const DRILL_OVER: f64 = 0.0005;

/// The drill for a hole of `diameter` mm: the diameter rounded down to 0.01 mm (at least
/// 0.01 mm), allowing [`DRILL_OVER`]: never larger than the hole beyond that.
fn drill_for(diameter: f64) -> f64 {
    (((diameter + DRILL_OVER) / 0.01).floor() * 0.01).max(0.01)
}

/// Holes up to this diameter are drilled, larger ones bored, mm.
pub const DRILL_MAX: f64 = 12.0;

/// The smallest end mill a starting job uses, as a fraction of the main one.
pub const SMALLEST_TOOL: f64 = 0.1;

/// A profile's tool passes between two parts this many of its diameters apart.
const PASS_BETWEEN: f64 = 1.5;

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

/// The distance between two outlines (infinite when their boxes are `beyond` mm apart or
/// more), mm, from points sampled every tenth of a millimetre at most 4096 per outline, on
/// each outline against the other.
fn outline_gap(a: &Outline, b: &Outline, beyond: f64) -> f64 {
    let (ba, bb) = (a.bounds(), b.bounds());
    let dx = (ba.min.x - bb.max.x).max(bb.min.x - ba.max.x).max(0.0);
    let dy = (ba.min.y - bb.max.y).max(bb.min.y - ba.max.y).max(0.0);
    if dx.hypot(dy) >= beyond {
        return f64::INFINITY;
    }
    let one_way = |a: &Outline, b: &Outline| {
        let n = ((a.length() / 0.1).ceil() as usize).clamp(64, 4096);
        a.sample(n)
            .into_iter()
            .map(|p| b.distance_to(p))
            .fold(f64::INFINITY, f64::min)
    };
    one_way(a, b).min(one_way(b, a))
}

/// The parts a profile cuts out: those at least `PASS_BETWEEN` times `least` from every
/// other part (1-based), the parts left out, each with the nearest part and their distance,
/// and the least distance between two parts cut (infinite for one), mm. Distances of
/// `PASS_BETWEEN` times `largest` or more are not measured.
fn profiled_parts(
    parts: &[Outline],
    least: f64,
    largest: f64,
) -> (Vec<usize>, Vec<(usize, usize, f64)>, f64) {
    let n = parts.len();
    let beyond = PASS_BETWEEN * largest;
    let mut gaps = vec![f64::INFINITY; n * n];
    for i in 0..n {
        for j in i + 1..n {
            let g = outline_gap(&parts[i], &parts[j], beyond);
            gaps[i * n + j] = g;
            gaps[j * n + i] = g;
        }
    }
    let nearest = |i: usize| {
        (0..n)
            .filter(|&j| j != i)
            .map(|j| (j, gaps[i * n + j]))
            .min_by(|a, b| a.1.total_cmp(&b.1))
    };
    let mut cut = Vec::new();
    let mut left = Vec::new();
    for i in 0..n {
        match nearest(i) {
            Some((j, g)) if g < PASS_BETWEEN * least => left.push((i + 1, j + 1, g)),
            _ => cut.push(i + 1),
        }
    }
    let mut gap = f64::INFINITY;
    for (k, &i) in cut.iter().enumerate() {
        for &j in &cut[k + 1..] {
            gap = gap.min(gaps[(i - 1) * n + j - 1]);
        }
    }
    (cut, left, gap)
}

/// The tab width for the parts `profiled` (1-based) cut out by an end mill of `d` mm: the
/// widest of the job's default ([`super::design::default_tab_width`]), `2d`, `d` and `d/2`
/// (none wider than the default) with which every part gets two tabs (one where its
/// automatic count asks for fewer) by `strategy::profile::tab_counts` (the profile's own
/// placement rule, the other parts' slots included), else the widest with which every part
/// gets one, else the narrowest; and whether every part gets a tab. The tabs are the job's:
/// ramped, as high as the job's default for a part `thickness` mm thick, on a cut through
/// at the job's default tolerance (0.01 mm) and no stock left.
fn tab_width(parts: &[Outline], profiled: &[usize], d: f64, thickness: f64) -> (f64, bool) {
    use crate::strategy::profile::{
        ProfileOptions, ProfileSide, ProfileTarget, TabCount, TabOptions, TabShape, tab_counts,
    };
    let default = super::design::default_tab_width(d);
    let mut widths: Vec<f64> = vec![default, 2.0 * d, d, 0.5 * d];
    widths.retain(|&w| w <= default);
    widths.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
    let targets: Vec<ProfileTarget> = profiled
        .iter()
        .map(|&i| ProfileTarget {
            outline: parts[i - 1].clone(),
            side: ProfileSide::Outside,
        })
        .collect();
    let Ok(tool) = crate::toolpath::Tool::flat(d) else {
        return (default, false);
    };
    let counts = |w: f64| -> Vec<(usize, usize)> {
        let opts = ProfileOptions::default()
            .with_top_z(0.0)
            .with_depth(thickness + 0.5)
            .with_stock_thickness(Some(thickness))
            .with_tolerance(0.01)
            .with_tabs(
                TabOptions::default()
                    .with_count(TabCount::Auto)
                    .with_width(w)
                    .with_height(super::design::default_tab_height(thickness, d))
                    .with_shape(TabShape::Ramped),
            );
        tab_counts(&targets, &tool, &opts)
    };
    let all: Vec<(f64, Vec<(usize, usize)>)> = widths.iter().map(|&w| (w, counts(w))).collect();
    for need in [2, 1] {
        if let Some((w, _)) = all
            .iter()
            .find(|(_, c)| c.iter().all(|&(n, asked)| n >= need.min(asked)))
        {
            return (*w, true);
        }
    }
    (widths.last().copied().unwrap_or(default), false)
}

/// The profile's end mill and tab width: the largest end mill from `d` down to `least` (the
/// usual sizes below `d`, or halves beyond the list) with which every part cut out gets a
/// tab ([`tab_width`]); else `d` and its narrowest tab, which the job refuses, saying why.
fn profile_tool_and_tabs(
    parts: &[Outline],
    profiled: &[usize],
    d: f64,
    least: f64,
    thickness: f64,
) -> (f64, f64) {
    let mut t = d;
    for _ in 0..8 {
        if t < least - 1e-12 {
            break;
        }
        let (w, fits) = tab_width(parts, profiled, t, thickness);
        if fits {
            return (t, w);
        }
        let largest = END_MILLS[END_MILLS.len() - 1];
        let below = END_MILLS.iter().rev().find(|&&s| s < t - 1e-9).copied();
        t = match below {
            Some(s) if t <= largest + 1e-9 => s,
            _ => end_mill_at_most(0.5 * t),
        };
    }
    (d, tab_width(parts, profiled, d, thickness).0)
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
    let least = SMALLEST_TOOL * main;
    let (profiled, too_close, gap) = profiled_parts(&model.parts, least, main);
    let gap_d = end_mill_at_most(main.min(gap / PASS_BETWEEN)).max(least);
    let thickness = round_to(main, 0.5).max(0.5);
    let (profile_d, tw) = profile_tool_and_tabs(&model.parts, &profiled, gap_d, least, thickness);
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
    let mut narrow: Vec<(usize, f64)> = Vec::new();
    for (i, p) in model.pockets.iter().enumerate() {
        let room = inscribed_radius(&p.outer);
        let d = end_mill_at_most(main.min(room));
        if d < least - 1e-12 {
            narrow.push((i + 1, room));
            continue;
        }
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
            let d = drill_for(h.diameter);
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
    let profile_tool = if profiled.is_empty() {
        0
    } else {
        tool(false, profile_d)
    };

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
    for (i, room) in &narrow {
        line(&format!(
            "# Pocket {i} is left out: only an end mill under D{} mm (the largest circle inside \
             it has radius {}) would sweep it, below a tenth of the main D{} mm.",
            num(least),
            num(*room),
            num(main)
        ));
    }
    for (i, j, g) in &too_close {
        line(&format!(
            "# Part {i} is not cut out: it is {} mm from part {j}, too close for an end mill of \
             D{} mm or more to pass between; move the parts apart in the drawing, or cut them \
             out by hand.",
            num(*g),
            num(least)
        ));
    }
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
        line(&format!("min_diameter = {}", num(d - DRILL_OVER)));
        line(&format!("max_diameter = {}", num(d + 0.01 - DRILL_OVER)));
        line("depth = \"through\"");
        if thickness > 3.0 * d {
            line(&format!(
                "peck = {}                  # mm per peck (G83)",
                num(*d)
            ));
        }
    }
    if profiled.is_empty() {
        return s;
    }
    line("");
    line("[[operation]]");
    line("type = \"profile\"");
    line("name = \"cut the part out\"");
    line(&format!("tool = {profile_tool}"));
    if !too_close.is_empty() {
        line(&format!(
            "select = \"{}\"        # the parts far enough apart to cut out",
            profiled
                .iter()
                .map(ToString::to_string)
                .collect::<Vec<_>>()
                .join(",")
        ));
    }
    line("side = \"auto\"              # the parts outside (\"inside\": their pockets as windows)");
    line("depth = \"through\"");
    line(&format!(
        "step_down = {}",
        num((0.5 * profile_d).min(thickness))
    ));
    line("tabs = \"auto\"              # a count, \"auto\" (from the perimeter) or 0");
    if (tw - super::design::default_tab_width(profile_d)).abs() > 1e-9 {
        line(&format!(
            "tab_width = {}            # mm: narrower than the default, to fit the outlines",
            num(tw)
        ));
    }
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
