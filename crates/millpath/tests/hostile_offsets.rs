//! Offsets and contours on the fuzz corpus's outlines: the committed, minimised corpus
//! (`fuzz/corpus-min/TARGET/*`) decoded by the fuzz targets' own harness
//! (`fuzz/harness/mod.rs`, included here), its offset loops and contours checked against the
//! walls.

#[path = "../../../fuzz/harness/mod.rs"]
mod harness;
mod hostile_common;

use hostile_common::corpus;
use millpath::strategy::pocket;

/// The spiral (`--morph fronts`) of the corpus' `51e5f8bd…` left 0.40 mm² round its centre
/// and was refused (an internal error) until 2026-11-26: cavalier_contours' offset returned
/// the boundary offset `B` (and `B_ε`, the spiral's last loop, offset from it) as an *open*
/// polyline whose last two vertices repeat its first two. Its winding number is 0
/// everywhere, so `spiral::inside` took every lap sample for outside `B_ε` and moved it onto
/// `B_ε`: the laps ran along the wall and the middle stood uncut. Every offset loop is now
/// closed (`geom::region::closed_loop`): the loops are closed and the program clears the
/// pocket without a gouge.
#[test]
fn open_offset_loops_are_closed() {
    let data = corpus("pocket")
        .into_iter()
        .find(|(n, _)| n == "51e5f8bde544a3cd51d1f55a81e9ead7cfacf6d9")
        .map(|(_, d)| d)
        .expect("in the corpus");
    let (kind, shape, tool, opts, sim) = harness::pocket_case(&data).expect("a pocket");
    let d0 = tool.radius() + opts.wall_stock;
    let b = shape.offset_loops(d0);
    assert!(!b.is_empty());
    // An open loop has no area (its winding number is 0 everywhere): every loop of `B` and
    // of `B_ε` encloses one.
    for l in &b {
        assert!(
            l.signed_area().abs() > 1e-6,
            "an open loop of {} vertices",
            l.len()
        );
        let eps = l.offset(pocket::LAST_LOOP_MARGIN);
        assert!(!eps.is_empty());
        for e in &eps {
            assert!(
                e.signed_area().abs() > 1e-6,
                "B_ε: {} vertices, open",
                e.len()
            );
        }
    }
    let v = pocket::generate(kind, &shape, &tool, &opts, &sim)
        .unwrap_or_else(|e| panic!("{e}"))
        .verification;
    assert!(
        v.uncut_area_mm2 <= millpath::stock::UNCUT_AREA_TOLERANCE,
        "{}",
        v.uncut_text()
    );
    assert!(v.min_clearance_mm >= v.required_clearance_mm - 1e-3);
}

/// Six corpus pockets whose spirals were refused because cavalier_contours' offsets were
/// wrong (found on 2026-11-25): with its default fuzzy epsilons (1e-4 mm) on outlines with
/// micrometre features, the shape offset ran loops 0.16–0.66 mm into the walls (`250d691f…`,
/// `57cf7b3e…`, `c2ebea30…`: gouges) or dropped a loop (`c3df108e…`: no finishing loop at the
/// tool radius; `bc4af3dc…`: a level without loops between two with loops), and the
/// single-polyline offset of the fronts' ridge search returned nothing at 8.7–14.7 mm on
/// `0e2b2de6…`, where the region's offset has up to 619 mm² (uncut 0.09–1.1 mm²). Every loop
/// of `PocketShape::offset` at the distances the spiral and its finishing pass use must lie
/// at that distance from the walls (dense samples, within 1e-4 mm), no level may be empty
/// between two that are not, and the programs are written without a gouge or uncut material.
#[test]
fn offsets_are_checked_against_the_walls() {
    for name in [
        "250d691fe17ccc4290ce474e5850faf3f694e6cd",
        "57cf7b3ed747979999cee1f7e3641566756092fa",
        "c2ebea30be4c1b22ea44a427c5670eb2bc61ed11",
        "0e2b2de663265032f559833ede4fafa560d01857",
        "bc4af3dc85eebec6136b1d42157a0c9d0cff290b",
        "c3df108ee370bae6ee73f0aba6ec17652b1625f1",
    ] {
        let data = corpus("pocket")
            .into_iter()
            .find(|(n, _)| n == name)
            .map(|(_, d)| d)
            .expect("in the corpus");
        let (kind, shape, tool, opts, sim) = harness::pocket_case(&data).expect("a pocket");
        let r = tool.radius();
        let h = opts.stepover_mm(&tool).min(0.95 * r);
        for sh in pocket::level_shapes(&shape, &opts).expect("sections") {
            let ds = [r, r + opts.wall_stock]
                .into_iter()
                .chain((1..40).map(|k| r + opts.wall_stock + k as f64 * h));
            let mut emptied = None;
            for d in ds {
                let reg = sh.offset_loops(d);
                match emptied {
                    Some(e) => assert!(
                        reg.is_empty(),
                        "{name}: loops at {d:.4} mm, none at {e:.4} mm"
                    ),
                    None if reg.is_empty() => emptied = Some(d),
                    None => {}
                }
                for l in &reg {
                    for p in l.sample(400) {
                        let w = sh.distance_to(p);
                        assert!(
                            (w - d).abs() < 1e-4,
                            "{name}: the loop at {d:.4} mm passes {w:.4} mm from the walls at {p:?}"
                        );
                    }
                }
            }
        }
        let v = pocket::generate(kind, &shape, &tool, &opts, &sim)
            .unwrap_or_else(|e| panic!("{name}: {e}"))
            .verification;
        assert!(
            v.min_clearance_mm >= v.required_clearance_mm - 1e-3,
            "{name}: gouges {:.4} mm",
            v.required_clearance_mm - v.min_clearance_mm
        );
        assert!(
            v.uncut_area_mm2 <= millpath::stock::UNCUT_AREA_TOLERANCE,
            "{name}: {}",
            v.uncut_text()
        );
    }
}

/// Contour inputs whose finishing pass ran farther than `r + T` from the curve (found on
/// 2026-11-25 by the strict contour replay), held to the band by dense sampling (64 points a
/// move) against the exact curve. `c2eb47c6…` (0.045 mm beyond): a piece of one chord between
/// two crossings of the raw offset was judged against the band's middle, not the chords'
/// floor, and dropped; the walk round the kept slices could not close and the loop was closed
/// by a 1.44 mm chord of its own (`contour::offset::trim`). `d19e6c61…` (1.9e7 mm): a
/// near-straight biarc of radius 9.7e6 mm sweeping 6.7e-13 rad, which `Move::sweep_from`
/// reads as a full circle (`curve::MIN_ARC_SWEEP`). (The band's inner edge is not
/// asserted: on `d19e6c61…`, a sliver 0.002 mm thick, the pass comes 0.9 µm nearer than `r`
/// to the far side, the clearance defect of chaotic curves that `harness::contour` notes.)
#[test]
fn contours_stay_in_the_band_on_fuzz_outlines() {
    for name in [
        "c2eb47c609729b35512d62deafff972cf612849d",
        "d19e6c6172dc629bfd1fbce396445c5c0b37df3e",
    ] {
        let data = corpus("contour")
            .into_iter()
            .find(|(n, _)| n == name)
            .map(|(_, d)| d)
            .expect("in the corpus");
        let (c, opt) = harness::contour_case(&data).expect("a curve");
        let res = millpath::strategy::contour::contour(&c, &opt)
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        let r = opt.tool.radius();
        let (lo, hi) = harness::pass_distance_dense(&c, &res.toolpath, false, 64);
        assert!(
            hi <= r + opt.tolerance + 1e-9,
            "{name}: the pass lies {lo:.6}–{hi:.6} mm from the curve, more than r + T = {:.6}",
            r + opt.tolerance
        );
    }
}
