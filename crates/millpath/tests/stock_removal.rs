//! What the stock simulation reports beside its checks: the volume removed, which moves cut,
//! and the engagement's distribution outside the entries, measured against figures worked
//! out by hand from the geometry of a slot.

use millpath::geom::{Outline, Point, Point3};
use millpath::stock::{SimOptions, StockSpec, cutting_moves, infer_levels, simulate};
use millpath::toolpath::{Move, Tool, Toolpath};
use std::f64::consts::PI;

fn square(side: f64) -> Outline {
    let p = [
        Point::new(0.0, 0.0),
        Point::new(side, 0.0),
        Point::new(side, side),
        Point::new(0.0, side),
    ];
    Outline::from_points(&p, "square").unwrap()
}

/// A 10 mm tool feeds down 3 mm at (20, 50) from above the stock, cuts a slot to (80, 50),
/// comes back along it (a link through the cleared slot, cutting nothing) and retracts.
fn slot_and_back(depth: f64) -> Toolpath {
    let tool = Tool::flat(10.0).unwrap();
    let mut tp = Toolpath::new(tool, Point3::new(20.0, 50.0, 5.0));
    tp.push(Move::line(Point3::new(20.0, 50.0, -depth), 300.0));
    tp.push(Move::line(Point3::new(80.0, 50.0, -depth), 1000.0));
    tp.push(Move::line(Point3::new(20.0, 50.0, -depth), 1000.0));
    tp.push(Move::rapid(Point3::new(20.0, 50.0, 5.0)));
    infer_levels(&mut tp);
    tp
}

#[test]
fn a_slot_removes_its_volume_and_the_link_back_through_it_cuts_nothing() {
    let outer = square(100.0);
    let spec = StockSpec {
        outer: &outer,
        islands: &[],
        wall_stock: 0.0,
    };
    for depth in [3.0, 7.5] {
        let tp = slot_and_back(depth);
        let sim = simulate(&tp, spec, 90.0, &SimOptions::default());
        // The stadium the tool sweeps: a 60 × 10 mm band and the two half discs.
        let want = (60.0 * 10.0 + PI * 25.0) * depth;
        let got = sim.removed_mm3;
        assert!(
            (got - want).abs() < 0.005 * want,
            "depth {depth}: removed {got:.1} mm³ against {want:.1}"
        );
        assert_eq!(cutting_moves(&tp, &sim), vec![true, true, false, false]);
        let st = sim.engagement.stats();
        // The feed down is the entry; the slot is cut at 180° over its 60 mm, the way back
        // at 0° once the simulation's averaging window (0.5 mm) has left the slot's end.
        let window = SimOptions::default().window_for(&tp.tool);
        assert!(
            st.cutting_mm >= 60.0 - 0.1 && st.cutting_mm <= 60.0 + window + 0.1,
            "{}",
            st.cutting_mm
        );
        assert!(st.max_deg > 179.0 && st.p95_deg > 179.0, "{st:?}");
        assert!(st.entry_mm > 0.0, "{st:?}");
        assert!(
            (st.share_above_bound * st.cutting_mm - 60.0).abs() < 0.2,
            "all of the slot, and only the slot, is above 1.1 × 90°: {st:?}"
        );
    }
}
