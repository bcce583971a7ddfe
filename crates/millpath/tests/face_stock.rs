//! Facing (`strategy::face`) verified on the height-field stock: the stock's top rectangle,
//! faced to a depth, is down to the faced z everywhere and nowhere below it, with no plunge
//! and no rapid through material; on seeded random rectangles, tools, depths and stepovers,
//! zigzag and one-way; one-way rows all climb (material on the right of travel).

use millpath::geom::{Aabb, Point};
use millpath::stock::{FieldOptions, HeightField};
use millpath::strategy::face::{FaceOptions, face};
use millpath::toolpath::{MoveKind, Tool};

fn rect(x0: f64, y0: f64, w: f64, h: f64) -> Aabb {
    Aabb {
        min: Point::new(x0, y0),
        max: Point::new(x0 + w, y0 + h),
    }
}

struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }
}

/// Faces `top` and checks the field of that stock: every cell at `top_z − depth` within
/// the z tolerance, none lower; nothing else found.
fn faced_flat(top: Aabb, tool: &Tool, opts: &FaceOptions, cell: f64) {
    let tp = face(top, tool, opts).expect("a facing");
    let fo = FieldOptions::default().with_cell(cell);
    let mut field =
        HeightField::new(top, opts.top_z - 3.0 * opts.depth, opts.top_z, &fo).expect("a block");
    let cut = field.cut(&tp);
    assert!(cut.problems().is_empty(), "{cut}");
    let want = opts.top_z - opts.depth;
    let (nx, ny) = field.dims();
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for j in 0..ny {
        for i in 0..nx {
            // The field covers the rectangle rounded up to whole cells: only cells whose
            // centre lies on the stock count.
            if !top.contains(field.centre(i, j)) {
                continue;
            }
            let h = field.height(i, j).expect("on the field");
            lo = lo.min(h);
            hi = hi.max(h);
        }
    }
    assert!(
        lo >= want - 1e-3 && hi <= want + 1e-3,
        "faced to {lo} .. {hi}, want {want} ({top:?}, {tool:?}, {opts:?})"
    );
    let volume = top.width() * top.height() * opts.depth;
    assert!(
        (cut.removed_volume_mm3 - volume).abs()
            < 2.0 * (top.width() + top.height()) * cell * opts.depth + 1e-6 * volume,
        "{cut}: want {volume}"
    );
}

#[test]
fn a_faced_top_is_flat_at_the_depth() {
    let tool = Tool::flat(10.0).expect("a tool");
    let opts = FaceOptions::default().with_depth(2.5).with_step_down(1.0);
    faced_flat(rect(0.0, 0.0, 100.0, 60.0), &tool, &opts, 0.1);
    faced_flat(
        rect(-20.0, 5.0, 30.0, 80.0),
        &tool,
        &opts.with_one_way(true),
        0.1,
    );
}

#[test]
fn random_facings_are_flat_at_their_depth() {
    let mut rng = Lcg(2026);
    let cases = 16;
    let mut accepted = 0;
    for _ in 0..cases {
        let tool = Tool::flat(rng.range(2.0, 25.0)).expect("a tool");
        let top = rect(
            rng.range(-50.0, 50.0),
            rng.range(-50.0, 50.0),
            rng.range(1.0, 80.0),
            rng.range(1.0, 80.0),
        );
        let opts = FaceOptions::default()
            .with_top_z(rng.range(-5.0, 5.0))
            .with_depth(rng.range(0.1, 4.0))
            .with_step_down(rng.range(0.3, 2.0))
            .with_stepover(rng.range(0.2, 1.0))
            .with_overrun(rng.range(0.0, 3.0))
            .with_one_way(rng.next() < 0.5);
        faced_flat(top, &tool, &opts, 0.2);
        accepted += 1;
    }
    assert_eq!(accepted, cases);
}

/// One-way rows all run with the uncut material (the side the rows advance to) on their
/// right; zigzag rows alternate. Read from the moves at the cutting depth that span the
/// rectangle.
#[test]
fn one_way_rows_climb_and_zigzag_rows_alternate() {
    let tool = Tool::flat(6.0).expect("a tool");
    for (top, one_way) in [
        (rect(0.0, 0.0, 50.0, 20.0), true),
        (rect(0.0, 0.0, 20.0, 50.0), true),
        (rect(0.0, 0.0, 50.0, 20.0), false),
    ] {
        let opts = FaceOptions::default().with_one_way(one_way);
        let tp = face(top, &tool, &opts).expect("a facing");
        let long = top.width().max(top.height());
        let rows: Vec<(Point, Point)> = tp
            .segments()
            .filter(|(from, m)| {
                matches!(m.kind, MoveKind::Line)
                    && (from.z - m.to.z).abs() < 1e-12
                    && from.xy().distance(m.to.xy()) > long
            })
            .map(|(from, m)| (from.xy(), m.to.xy()))
            .collect();
        assert!(rows.len() >= 3, "{rows:?}");
        for w in rows.windows(2) {
            let ((a, b), (c, _)) = (w[0], w[1]);
            // The next row lies on the side the material is.
            let travel = b - a;
            let to_next = c - a;
            let right = travel.cross(to_next) < 0.0;
            if one_way {
                assert!(right, "{top:?}: row {a:?} → {b:?}, next at {c:?}");
            }
        }
        if !one_way {
            for w in rows.windows(2) {
                let (d0, d1) = (w[0].1 - w[0].0, w[1].1 - w[1].0);
                assert!(d0.dot(d1) < 0.0, "{rows:?}");
            }
        }
    }
}

#[test]
fn bad_facing_options_are_refused_by_name() {
    let tool = Tool::flat(6.0).expect("a tool");
    let top = rect(0.0, 0.0, 50.0, 20.0);
    let e = face(top, &tool, &FaceOptions::default().with_depth(0.0)).unwrap_err();
    assert!(e.to_string().contains("facing depth"), "{e}");
    let e = face(top, &tool, &FaceOptions::default().with_stepover(1.5)).unwrap_err();
    assert!(e.to_string().contains("facing stepover"), "{e}");
    let e = face(rect(0.0, 0.0, 0.0, 20.0), &tool, &FaceOptions::default()).unwrap_err();
    assert!(e.to_string().contains("facing rectangle"), "{e}");
    assert_eq!(e.exit_code(), 2);
}
