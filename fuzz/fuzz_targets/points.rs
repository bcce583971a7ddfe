//! The point-list parser (CSV and JSON) over arbitrary text, then the free-form curve built
//! through whatever points it accepts: input errors are fine, panics are not.
#![no_main]

use libfuzzer_sys::fuzz_target;
use millpath::curve::{self, CurveKind};
use millpath::io::points;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    if let Ok(groups) = points::parse(text, "fuzz.csv") {
        for kind in [
            CurveKind::FourPoint,
            CurveKind::CatmullRom,
            CurveKind::Spline,
        ] {
            let _ = curve::build(&groups, kind, "fuzz");
        }
    }
});
