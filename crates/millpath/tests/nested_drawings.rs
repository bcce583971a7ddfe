//! Drawings nested 100,000 levels deep: SVG groups, nested `svg` elements, `use` chains and
//! `use` cycles, DXF blocks inserting blocks, JSON outlines in nested arrays. Each is read on
//! a test thread (2 MiB of stack, less than the CLI's main thread) and must end with the
//! drawing read or an input error naming what was too deep, never a stack overflow.
//!
//! Where the nesting only wraps a drawable element (groups, nested `svg`), the element must
//! be read exactly as it is without the wrapping: the same outline, the same extents.

use millpath::io::{ReadOptions, dxf, outline_json, svg};

const DEPTH: usize = 100_000;

const SQUARE: &str = r#"<rect x="10" y="10" width="50" height="30"/>"#;

fn page(body: &str) -> String {
    format!(
        r#"<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink" width="100mm" height="100mm" viewBox="0 0 100 100">{body}</svg>"#
    )
}

/// The one outline's extents (min x, min y, max x, max y), mm.
fn extents(d: &millpath::io::Drawing) -> [f64; 4] {
    assert_eq!(d.outlines.len(), 1, "one outline: {:?}", d.counts);
    let pts = d.outlines[0].sample(400);
    let mut e = [f64::INFINITY, f64::INFINITY, -f64::INFINITY, -f64::INFINITY];
    for p in pts {
        e = [e[0].min(p.x), e[1].min(p.y), e[2].max(p.x), e[3].max(p.y)];
    }
    e
}

fn assert_same_extents(a: [f64; 4], b: [f64; 4]) {
    for (x, y) in a.iter().zip(b) {
        assert!((x - y).abs() < 1e-9, "extents {a:?} against {b:?}");
    }
}

#[test]
fn groups_nested_100000_deep_draw_their_square() {
    let flat = svg::read_loops(&page(SQUARE), "flat.svg", &ReadOptions::default()).unwrap();
    let body = format!("{}{SQUARE}{}", "<g>".repeat(DEPTH), "</g>".repeat(DEPTH));
    let deep = svg::read_loops(&page(&body), "deep.svg", &ReadOptions::default()).unwrap();
    assert_same_extents(extents(&deep), extents(&flat));
    assert_same_extents(extents(&flat), [10.0, 60.0, 60.0, 90.0]);
}

#[test]
fn groups_each_translating_compose_100000_deep() {
    // Every group moves its content by 0.0001 user units (mm) in x: 10 mm in all.
    let body = format!(
        "{}{SQUARE}{}",
        r#"<g transform="translate(0.0001 0)">"#.repeat(DEPTH),
        "</g>".repeat(DEPTH)
    );
    let deep = svg::read_loops(&page(&body), "deep.svg", &ReadOptions::default()).unwrap();
    let e = extents(&deep);
    assert!(
        (e[0] - 20.0).abs() < 1e-6 && (e[2] - 70.0).abs() < 1e-6,
        "{e:?}"
    );
}

#[test]
fn nested_svg_elements_100000_deep_draw_their_square() {
    let body = format!(
        "{}{SQUARE}{}",
        r#"<svg x="0" y="0">"#.repeat(DEPTH),
        "</svg>".repeat(DEPTH)
    );
    let deep = svg::read_loops(&page(&body), "deep.svg", &ReadOptions::default()).unwrap();
    assert_same_extents(extents(&deep), [10.0, 60.0, 60.0, 90.0]);
}

#[test]
fn a_use_chain_100000_long_stops_at_the_use_depth_with_a_reason() {
    // u0 → g1 ⊃ u1 → g2 ⊃ u2 → … → g100000 ⊃ square: only the first few links are followed.
    let mut body = String::from(r##"<use xlink:href="#g1"/><defs>"##);
    for i in 1..DEPTH {
        body.push_str(&format!(
            r##"<g id="g{i}"><use xlink:href="#g{}"/></g>"##,
            i + 1
        ));
    }
    body.push_str(&format!(r#"<g id="g{DEPTH}">{SQUARE}</g></defs>"#));
    let d = svg::read_loops(&page(&body), "chain.svg", &ReadOptions::default()).unwrap();
    assert!(d.outlines.is_empty());
    let reasons: Vec<&String> = d.skipped.keys().map(|(_, why)| why).collect();
    assert!(
        reasons.iter().any(|w| w.contains("`use` references deep")),
        "{reasons:?}"
    );
    // A chain within the bound is followed to its end.
    let mut body = String::from(r##"<use xlink:href="#g1"/><defs>"##);
    for i in 1..10 {
        body.push_str(&format!(
            r##"<g id="g{i}"><use xlink:href="#g{}"/></g>"##,
            i + 1
        ));
    }
    body.push_str(&format!(r#"<g id="g10">{SQUARE}</g></defs>"#));
    let d = svg::read_loops(&page(&body), "short.svg", &ReadOptions::default()).unwrap();
    assert_same_extents(extents(&d), [10.0, 60.0, 60.0, 90.0]);
}

#[test]
fn use_cycles_and_doubling_uses_end_with_a_reason() {
    // Two groups that use each other.
    let body = r##"<defs><g id="a"><use xlink:href="#b"/></g><g id="b"><use xlink:href="#a"/></g></defs><use xlink:href="#a"/>"##;
    let d = svg::read_loops(&page(body), "cycle.svg", &ReadOptions::default()).unwrap();
    assert!(d.outlines.is_empty());
    assert!(!d.skipped.is_empty(), "the cycle is reported as skipped");
    // Each level uses the one below twice: 2^40 squares if followed to the end.
    let mut body = format!(r#"<defs><g id="l0">{SQUARE}</g>"#);
    for i in 1..=40 {
        body.push_str(&format!(
            r##"<g id="l{i}"><use xlink:href="#l{0}"/><use xlink:href="#l{0}"/></g>"##,
            i - 1
        ));
    }
    body.push_str(r##"</defs><use xlink:href="#l40"/>"##);
    match svg::read_loops(&page(&body), "bomb.svg", &ReadOptions::default()) {
        Ok(d) => assert!(!d.skipped.is_empty(), "the expansion was cut short: {d:?}"),
        Err(e) => assert!(e.to_string().contains("SVG elements"), "{e}"),
    }
}

/// A DXF whose entities insert block B0, B0 inserts B1, …, the last draws a square.
fn block_chain(n: usize) -> String {
    let mut s = String::from("0\nSECTION\n2\nBLOCKS\n");
    for i in 0..n {
        s.push_str(&format!("0\nBLOCK\n2\nB{i}\n10\n0\n20\n0\n"));
        if i + 1 < n {
            s.push_str(&format!("0\nINSERT\n2\nB{}\n10\n1\n20\n0\n", i + 1));
        } else {
            s.push_str(
                "0\nLWPOLYLINE\n90\n4\n70\n1\n10\n0\n20\n0\n10\n50\n20\n0\n10\n50\n20\n30\n10\n0\n20\n30\n",
            );
        }
        s.push_str("0\nENDBLK\n");
    }
    s.push_str("0\nENDSEC\n0\nSECTION\n2\nENTITIES\n0\nINSERT\n2\nB0\n10\n0\n20\n0\n");
    s.push_str("0\nENDSEC\n0\nEOF\n");
    s
}

#[test]
fn dxf_blocks_inserting_blocks_100000_deep_are_refused_by_name() {
    let e = dxf::read_loops(
        block_chain(DEPTH).as_bytes(),
        "deep.dxf",
        &ReadOptions::default(),
    )
    .unwrap_err();
    let m = e.to_string();
    assert!(
        m.contains("INSERT nesting") && m.contains("deep.dxf"),
        "{m}"
    );
    // A shallow chain is read, each level moving the square by 1 in x.
    let d = dxf::read_loops(block_chain(5).as_bytes(), "ok.dxf", &ReadOptions::default()).unwrap();
    assert_same_extents(extents(&d), [4.0, 0.0, 54.0, 30.0]);
}

#[test]
fn a_dxf_block_inserting_itself_is_refused_by_name() {
    let s = "0\nSECTION\n2\nBLOCKS\n0\nBLOCK\n2\nSELF\n10\n0\n20\n0\n0\nINSERT\n2\nSELF\n10\n1\n20\n0\n\
             0\nENDBLK\n0\nENDSEC\n0\nSECTION\n2\nENTITIES\n0\nINSERT\n2\nSELF\n10\n0\n20\n0\n\
             0\nENDSEC\n0\nEOF\n";
    let e = dxf::read_loops(s.as_bytes(), "self.dxf", &ReadOptions::default()).unwrap_err();
    assert!(e.to_string().contains("INSERT nesting"), "{e}");
}

#[test]
fn json_outlines_in_arrays_100000_deep_are_refused_with_a_message() {
    let text = format!("{}{}", "[".repeat(DEPTH), "]".repeat(DEPTH));
    let e = outline_json::parse(&text, "deep.json").unwrap_err();
    assert!(e.to_string().contains("deep.json"), "{e}");
    let text = format!("{}{}", "{\"a\":".repeat(DEPTH), "}".repeat(DEPTH));
    let e = outline_json::parse(&text, "deep.json").unwrap_err();
    assert!(e.to_string().contains("deep.json"), "{e}");
}
