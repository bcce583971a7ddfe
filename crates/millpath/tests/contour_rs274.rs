//! The contour pipeline's LinuxCNC output passes LinuxCNC's own interpreter `rs274`
//! (Debian package linuxcnc-uspace; `.ci/run` installs it), for lines and biarcs, inside
//! and outside, at the decimals the tolerance budget asks for.

mod rs274_common;

use millpath::curve;
use millpath::gcode::{self, Units, WriterOptions};
use millpath::strategy::contour::{self, ContourOptions, Side};
use rs274_common::rs274;

#[test]
fn contour_programs_pass_rs274() {
    // The checker itself must be able to fail.
    assert!(rs274("G21 G90\nG1 X10 F100\nQ5\nM2\n").is_err());
    let c = curve::paper_outline().unwrap();
    for (side, arcs) in [
        (Side::Inside, false),
        (Side::Inside, true),
        (Side::Outside, true),
    ] {
        let tol = 1e-3;
        let decimals = gcode::required_decimals(tol, Units::Mm);
        let o = ContourOptions::default()
            .with_tolerance(tol)
            .with_rounding(gcode::rounding_error_mm(decimals, Units::Mm))
            .with_side(side)
            .with_arcs(arcs);
        let r = contour::contour(&c, &o).unwrap();
        let mut w = WriterOptions::default().with_decimals(Some(decimals));
        w.path_tolerance = Some(tol); // at these decimals: `with_path_tolerance` may add some
        let (text, _) = gcode::write_to_string(&r.toolpath, &w).unwrap();
        rs274(&text).unwrap_or_else(|e| panic!("{side:?} arcs {arcs}: {e}"));
        // The program as read back (rounded, flat arcs written as chords) keeps the tool at
        // least the offset from the outline on the finishing level (one-sided budget).
        let (back, _) = gcode::read_str(&text, gcode::ReaderOptions::default()).unwrap();
        let d = o.tool.radius();
        let mut min = f64::INFINITY;
        let mut from = back.start;
        for m in &back.moves {
            let start = from;
            from = m.to;
            let z = r.toolpath.levels.last().unwrap().z;
            if !m.is_feed() || (m.to.z - z).abs() > 1e-6 || (start.z - z).abs() > 1e-6 {
                continue;
            }
            let len = m.length_from(start);
            let n = ((len / 0.05).ceil() as usize).clamp(1, 10_000);
            for k in 0..=n {
                let p = m.point_at(start, len * k as f64 / n as f64);
                min = min.min(curve::distance_to_curve(&c, p.xy()));
            }
        }
        assert!(min >= d - 1e-9, "{side:?} arcs {arcs}: {min} < {d}");
    }
}
