//! The outline importers (DXF, SVG, outline JSON) and machine profiles over arbitrary bytes:
//! they must return outlines or input errors, never panic.
#![no_main]

use libfuzzer_sys::fuzz_target;
use millpath::io::{dxf, outline_json, svg};
use millpath::machine::Machine;

fuzz_target!(|data: &[u8]| {
    let _ = dxf::parse(data, "fuzz.dxf", &dxf::DxfOptions::default());
    if let Ok(text) = std::str::from_utf8(data) {
        let _ = svg::parse(text, "fuzz.svg", 0.01);
        let _ = outline_json::parse(text, "fuzz.json");
        let _ = Machine::from_toml_str(text, "fuzz.toml");
    }
});
