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
        let o = ContourOptions {
            tolerance: tol,
            rounding: gcode::rounding_error_mm(decimals, Units::Mm),
            side,
            arcs,
            ..ContourOptions::default()
        };
        let r = contour::contour(&c, &o).unwrap();
        let w = WriterOptions {
            decimals: Some(decimals),
            path_tolerance: Some(tol),
            ..WriterOptions::default()
        };
        let (text, summary) = gcode::write_to_string(&r.toolpath, &w).unwrap();
        assert_eq!(summary.arcs_as_lines, 0, "{side:?} arcs {arcs}");
        rs274(&text).unwrap_or_else(|e| panic!("{side:?} arcs {arcs}: {e}"));
    }
}
