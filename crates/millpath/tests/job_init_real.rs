//! `job --init` on real drawings (`../shared/real-inputs/files/`) whose starting jobs were
//! not made: each job file written from the drawing alone, then planned whole. A job made
//! must pass the job's whole-stock check holding every part it cuts out by its tabs, and
//! `verify_program` (the program read back, apart from the plan) must accept it; a job that
//! cannot be made is refused as bad input naming what to change; the choices the file makes
//! (the smallest tool, the parts left out) are checked against the drawing.

use millpath::Error;
use millpath::gcode::Dialect;
use millpath::geom::Outline;
use millpath::io::ImportSettings;
use millpath::job::part;
use std::path::{Path, PathBuf};

fn drawing(name: &str) -> PathBuf {
    let d = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/real-inputs/files");
    assert!(d.is_dir(), "{} is missing", d.display());
    d.join(name)
}

/// The starting job file of `name`, written into `dir` as `NAME.toml`; its path and text.
fn init(name: &str, dir: &Path) -> (PathBuf, String) {
    let out = dir.join(format!("{name}.toml"));
    let text = part::init_file(
        &drawing(name),
        &out,
        &ImportSettings::default(),
        Dialect::LinuxCnc,
        "hsm",
        &mut |_| {},
    )
    .unwrap_or_else(|e| panic!("{name}: {e}"));
    std::fs::write(&out, &text).unwrap();
    (out, text)
}

/// The diameters of the file's end mills, in its order.
fn end_mills(text: &str) -> Vec<f64> {
    text.split("[[tool]]")
        .skip(1)
        .filter(|t| t.contains("type = \"end mill\""))
        .filter_map(|t| {
            t.lines()
                .find_map(|l| l.strip_prefix("diameter = "))
                .and_then(|v| v.split_whitespace().next())
                .and_then(|v| v.parse().ok())
        })
        .collect()
}

/// Plans the job file at `path`; on success the program passes the job's own check, holds
/// every part cut out by at least one tab, and `verify_program` accepts it.
fn made(path: &Path) -> Result<(), Error> {
    let run = part::run_file(path, None, None, &mut |_| {})?;
    let rep = &run.report;
    assert_eq!(
        rep.check.last().map(|(_, v)| v.as_str()),
        Some("the drawn part, held by its tabs"),
        "{}: {:?}",
        path.display(),
        rep.check
    );
    let holds: Vec<&String> = rep
        .check
        .iter()
        .filter(|(k, _)| k.ends_with(" held"))
        .map(|(_, v)| v)
        .collect();
    assert!(!holds.is_empty(), "{:?}", rep.check);
    for v in holds {
        let n: usize = v
            .strip_prefix("by ")
            .and_then(|s| s.split(' ').next())
            .and_then(|s| s.parse().ok())
            .unwrap_or(0);
        assert!(n >= 1, "{}: {v}", path.display());
    }
    let text = String::from_utf8(run.run.gcode.clone()).unwrap();
    let v = part::verify_program(&run.spec, &text, "part.ngc", "linuxcnc").unwrap();
    assert!(
        v.problems().is_empty(),
        "{}: {:?}",
        path.display(),
        v.problems()
    );
    Ok(())
}

/// An SVG arrow of 7 mm, whose profile once fed down through its own tab: held by its tabs.
#[test]
fn a_small_svg_part_is_held_by_its_tabs() {
    let dir = tempfile::tempdir().unwrap();
    let (path, _) = init("pb_white_arrow.svg", dir.path());
    made(&path).unwrap();
}

/// Pockets only an end mill under a tenth of the main one could sweep (one once asked for a
/// 0.0035 mm tool) are left out, each named in the file; every end mill is at least a tenth
/// of the main one, and every pocket is either named or in an operation.
#[test]
fn pockets_too_narrow_for_a_tenth_of_the_main_tool_are_left_out_and_named() {
    let dir = tempfile::tempdir().unwrap();
    let (_, text) = init("s2g_smooth_curves.svg", dir.path());
    let mills = end_mills(&text);
    let main = mills[0];
    assert!(mills.iter().all(|&d| d >= 0.1 * main - 1e-9), "{mills:?}");
    let pockets: usize = text
        .lines()
        .find_map(|l| {
            l.split(" pocket(s)")
                .next()?
                .rsplit(' ')
                .next()?
                .parse()
                .ok()
        })
        .unwrap();
    let named = text
        .lines()
        .filter(|l| l.starts_with("# Pocket ") && l.contains(" is left out"))
        .count();
    assert!(named >= 1, "{text}");
    let pocket_selected: usize = text
        .split("[[operation]]")
        .filter(|op| op.contains("type = \"pocket\""))
        .filter_map(|op| op.lines().find_map(|l| l.strip_prefix("select = \"")))
        .map(|l| l.split('"').next().unwrap_or("").split(',').count())
        .sum();
    assert_eq!(named + pocket_selected, pockets, "{text}");
}

/// Parts closer to each other than 1.5 of the smallest tool the file allows are not cut
/// out: the file names each with its neighbour and their distance, the profile selects the
/// others, and the distance named is the drawing's (sampled independently). The drawing's
/// two parts, 0.098 mm apart, once asked for a 0.066 mm tool.
#[test]
fn parts_too_close_to_cut_apart_are_named_and_left_uncut() {
    let dir = tempfile::tempdir().unwrap();
    let (_, text) = init("pb_4_spoke_gear.svg", dir.path());
    let main = end_mills(&text)[0];
    let left: Vec<(usize, usize, f64)> = text
        .lines()
        .filter_map(|l| {
            let rest = l.strip_prefix("# Part ")?;
            let (i, rest) = rest.split_once(" is not cut out: it is ")?;
            let (g, rest) = rest.split_once(" mm from part ")?;
            let j = rest.split(',').next()?;
            Some((i.parse().ok()?, j.parse().ok()?, g.parse().ok()?))
        })
        .collect();
    assert!(!left.is_empty(), "{text}");
    // The profile's parts (none when every part is too close to another).
    let select: Vec<usize> = text
        .split("[[operation]]")
        .find(|op| op.contains("type = \"profile\""))
        .and_then(|op| op.lines().find_map(|l| l.strip_prefix("select = \"")))
        .map(|l| {
            let list = l.split('"').next().unwrap_or("");
            list.split(',').map(|s| s.parse().unwrap()).collect()
        })
        .unwrap_or_default();
    let (loops, _) = millpath::job::load_outline(
        &drawing("pb_4_spoke_gear.svg").to_string_lossy(),
        &ImportSettings::default(),
    )
    .unwrap();
    // The parts as the file numbers them: the outermost outlines, largest first.
    let mut parts: Vec<Outline> = loops.pockets().iter().map(|p| p.outer.clone()).collect();
    parts.sort_by(|a, b| b.signed_area().abs().total_cmp(&a.signed_area().abs()));
    for &(i, j, g) in &left {
        assert!(!select.contains(&i), "{i} {select:?}");
        assert!(g < 1.5 * 0.1 * main, "{g}");
        // The distance, sampled every 0.05 mm each way, within 0.05 mm of the file's.
        let (a, b) = (&parts[i - 1], &parts[j - 1]);
        let d = |a: &Outline, b: &Outline| {
            let n = ((a.length() / 0.05).ceil() as usize).max(64);
            a.sample(n)
                .into_iter()
                .map(|p| b.distance_to(p))
                .fold(f64::INFINITY, f64::min)
        };
        let measured = d(a, b).min(d(b, a));
        assert!((measured - g).abs() <= 0.05, "{i}-{j}: {measured} vs {g}");
    }
    assert_eq!(select.len() + left.len(), parts.len());
}

/// Small curved parts beside others (`s2g_smooth_curves.svg`: letters 0.7 mm apart cut by a
/// 0.34 mm end mill) get tabs sized by the profile's own placement rule, clear of the other
/// parts' slots; asked for tabs five times as wide as the starting file's, the job is
/// refused as bad input naming the tab width and what to change, and writes nothing.
#[test]
fn a_part_without_room_for_a_tab_is_refused_naming_the_tab_width() {
    let dir = tempfile::tempdir().unwrap();
    let (path, text) = init("s2g_smooth_curves.svg", dir.path());
    let width: f64 = text
        .lines()
        .find_map(|l| l.strip_prefix("tab_width = "))
        .and_then(|l| l.split_whitespace().next()?.parse().ok())
        .expect("a tab width");
    let wide = text.replace(
        &format!("tab_width = {width}"),
        &format!("tab_width = {}", 5.0 * width),
    );
    std::fs::write(&path, wide).unwrap();
    let e = made(&path).unwrap_err();
    let Error::Input(e) = &e else {
        panic!("not bad input: {e}");
    };
    let m = e.to_string();
    assert!(
        m.contains("tab width") && m.contains("tabs = 0") && m.contains("fall free"),
        "{m}"
    );
}
