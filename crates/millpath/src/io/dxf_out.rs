//! Writes closed outlines as a DXF drawing: one closed LWPOLYLINE per outline, arcs as
//! bulges (`tan(θ/4)`, positive counter-clockwise: the outline's own bulges, exact), in
//! millimetres (`$INSUNITS` 4, `$MEASUREMENT` 1).
//!
//! The file is the ASCII DXF a CAD program's "R12/R2000 minimal" export gives: a HEADER with
//! the units, then ENTITIES. Coordinates are written with 9 decimals (1 nm, far below any
//! machining tolerance), so a drawing read back through [`super::dxf`] gives the same
//! outlines to 1e-9 mm.
//!
//! ```text
//!   0 LWPOLYLINE   8 POCKETS   90 <vertex count>   70 1 (closed)
//!  10 x  20 y  [42 bulge]      … one group per vertex
//! ```

use crate::geom::Outline;
use std::fmt::Write;

/// The DXF text of `outlines` on layer `layer`.
pub fn write_outlines<'a>(outlines: impl IntoIterator<Item = &'a Outline>, layer: &str) -> String {
    let mut s = String::new();
    let mut pair = |code: i32, value: &str| {
        let _ = writeln!(s, "{code:>3}\n{value}");
    };
    pair(0, "SECTION");
    pair(2, "HEADER");
    pair(9, "$ACADVER");
    pair(1, "AC1015");
    pair(9, "$INSUNITS");
    pair(70, "4");
    pair(9, "$MEASUREMENT");
    pair(70, "1");
    pair(0, "ENDSEC");
    pair(0, "SECTION");
    pair(2, "ENTITIES");
    for o in outlines {
        let n = o.len();
        pair(0, "LWPOLYLINE");
        pair(8, layer);
        pair(100, "AcDbEntity");
        pair(100, "AcDbPolyline");
        pair(90, &n.to_string());
        pair(70, "1");
        for (p, bulge) in o.vertices() {
            pair(10, &format!("{:.9}", p.x));
            pair(20, &format!("{:.9}", p.y));
            if bulge != 0.0 {
                pair(42, &format!("{bulge:.12}"));
            }
        }
    }
    pair(0, "ENDSEC");
    pair(0, "EOF");
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Point;

    #[test]
    fn reads_back_through_the_dxf_reader() {
        // A slot (two half circles) with a square island, and a second pocket beside it.
        let slot = Outline::new(
            &[
                (Point::new(0.0, 0.0), 0.0),
                (Point::new(40.0, 0.0), 1.0),
                (Point::new(40.0, 20.0), 0.0),
                (Point::new(0.0, 20.0), 1.0),
            ],
            "slot",
        )
        .expect("slot");
        let island = Outline::from_points(
            &[
                Point::new(15.0, 5.0),
                Point::new(25.0, 5.0),
                Point::new(25.0, 15.0),
                Point::new(15.0, 15.0),
            ],
            "isl",
        )
        .expect("island");
        let other = Outline::from_points(
            &[
                Point::new(80.0, 0.0),
                Point::new(100.0, 0.0),
                Point::new(100.0, 10.0),
                Point::new(80.0, 10.0),
            ],
            "other",
        )
        .expect("other");
        let text = write_outlines([&slot, &island, &other], "POCKETS");
        let l = super::super::dxf::parse(
            text.as_bytes(),
            "written.dxf",
            &super::super::dxf::DxfOptions::default(),
        )
        .expect("reads back");
        assert_eq!(l.len(), 2);
        let area = 40.0 * 20.0 + std::f64::consts::PI * 100.0 - 100.0;
        assert!(
            (l.pockets()[0].area() - area).abs() < 1e-6,
            "{}",
            l.pockets()[0].area()
        );
        assert_eq!(l.islands.len(), 1);
        assert!((l.others[0].area() - 200.0).abs() < 1e-6);
    }
}
