//! What the material a previous program left needs of a rest tool: a lower bound on the
//! length of any rest pass that clears it, computed from the verifier's own raster and
//! reach map, never from the rest generator.
//!
//! **The material left.** The pocket (`spec`) is rasterised at a cell `c`; every feed move of
//! the previous program at the floor (both ends within [`FLOOR_Z_TOLERANCE`] of it) clears
//! the cells within its tool's radius `R` of it, sampled every `c` (an arc's chords clear a
//! sagitta more on its inside: the material left is, if anything, under-counted, which keeps
//! the bound a lower bound). Of what is left, the material the rest tool (radius `r`) must
//! clear is what the coverage check asks of it: the cells within `r − 2c` of the region its
//! centre may visit (the reach map, `super::reach`). These cells are split into connected
//! regions (8-neighbours).
//!
//! **One region's need.** Two bounds, the larger counts:
//!
//! * *Width of cut.* A pass whose radial width of cut is at most `w` (the rest tool's
//!   stepover) removes at most `w` mm² of material per mm of travel: the region's area `A`
//!   needs `A / w` mm of cutting.
//! * *Along the wall.* A wall point `q` the previous tool never came near (its exact distance
//!   to the previous floor moves above `R` by more than [`CONTACT_DEPTH_CELLS`] cells) has
//!   material left against it, which only a tool
//!   centre within `r` of `q` and at least `r` from every wall clears: where the rest tool
//!   touches `q` at all, that is the single point `t = q + r·n` (`n` the inward normal;
//!   on a straight wall or a concave arc wider than `r`). The tool centre's path passes
//!   through every such `t`, and a curve through a set is at least as long as the set (its
//!   one-dimensional measure). The walls are sampled every half cell; a contact belongs to
//!   the region whose cell centre lies nearest within `r` (none: material too thin for the
//!   raster, not counted); the region's wall
//!   length is the length of its `t`s in wall order, steps longer than [`CONTACT_GAP_CELLS`]
//!   cells skipped (a gap, not a stretch to follow). In a square corner a large tool left as
//!   a fillet of radius `R`, the contact is the two straight stretches `R − r` long at the
//!   rest tool's offset; along a fillet of radius `ρ` with `r < ρ < R`, the fillet's arc at
//!   the tool radius, `θ·(ρ − r)`, and the short stretches of wall beside it where the large
//!   tool's circle leaves the wall.
//!
//! **Links.** The tool centre visits every region; between two regions `i` and `j` it
//! travels at least the distance between their cells' bounding boxes less `2r` (it clears
//! a cell from `r` away). Any order of visits is a path through all regions, at least as
//! long as their minimum spanning tree (Prim's algorithm on those distances): the links'
//! bound.
//!
//! **Exactness.** Each step under-counts: the arcs' sagitta and the `r − 2c` reach (the
//! area), the bounding boxes (the links), material thinner than a cell against the walls (the
//! contact); the wall contact is otherwise exact geometry on the walls and the previous moves
//! (to [`CONTACT_SLACK`]), sampled every half cell (a stretch's ends to within half a cell).

use super::StockSpec;
use super::nearest::IndexedWall;
use super::raster::Raster;
use super::reach::ReachMap;
use crate::error::{InputError, require_positive};
use crate::geom::{Aabb, Point};
use crate::toolpath::{MoveKind, Tool, Toolpath};
use cavalier_contours::polyline::{PlineSource, Polyline, seg_arc_radius_and_center};
use serde::Serialize;
use std::collections::HashMap;
use std::fmt;

/// Height above the floor within which a previous move counts as cutting the floor, mm.
pub const FLOOR_Z_TOLERANCE: f64 = 0.01;

/// The longest step between consecutive wall contacts counted as one stretch, in cells.
pub const CONTACT_GAP_CELLS: f64 = 4.0;

/// The first window searched for the region a wall contact belongs to, in cells (the
/// search widens up to the rest tool's radius).
pub const CONTACT_CELLS: f64 = 4.0;

/// The slack of the contact's exact test, mm: the rest tool's centre touching a wall point
/// lies no closer than its radius less this to any wall.
pub const CONTACT_SLACK: f64 = 1e-3;

/// How much farther than its radius the previous tool must have passed from a wall point for
/// it to be a contact, in cells: material thinner than the raster's cell is not seen by the
/// simulation, and a rest pass that leaves it passes every check.
pub const CONTACT_DEPTH_CELLS: f64 = 1.0;

/// One connected region of material left within the rest tool's reach.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct UncutRegion {
    /// Its area, mm².
    pub area_mm2: f64,
    /// The length of its wall contact at the rest tool's centre, mm (module docs).
    pub wall_length_mm: f64,
    /// What it needs: `max(area / w, wall length)`, mm.
    pub need_mm: f64,
    /// The centroid of its cells.
    pub centroid: Point,
}

/// What the material a previous program left needs of the rest tool ([`rest_need`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RestNeed {
    /// The regions, in raster order.
    pub regions: Vec<UncutRegion>,
    /// The links' lower bound (the regions' minimum spanning tree), mm.
    pub links_mm: f64,
}

impl RestNeed {
    /// What the regions need of cutting, mm.
    pub fn cut_mm(&self) -> f64 {
        self.regions.iter().map(|r| r.need_mm).sum()
    }

    /// The area left within reach, mm².
    pub fn area_mm2(&self) -> f64 {
        self.regions.iter().map(|r| r.area_mm2).sum()
    }

    /// Cutting and links, mm.
    pub fn total_mm(&self) -> f64 {
        self.cut_mm() + self.links_mm
    }
}

impl fmt::Display for RestNeed {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} region(s), {:.3} mm² within reach, need ≥ {:.1} mm of cut and {:.1} mm of links",
            self.regions.len(),
            self.area_mm2(),
            self.cut_mm(),
            self.links_mm
        )
    }
}

/// The length of `rest`'s feed moves at the floor `floor_z` (both ends within
/// [`FLOOR_Z_TOLERANCE`]), in the plane, mm: its cutting at the floor, to set against
/// [`RestNeed::cut_mm`].
pub fn floor_cut_length(rest: &Toolpath, floor_z: f64) -> f64 {
    let zmax = floor_z + FLOOR_Z_TOLERANCE;
    rest.segments()
        .filter(|(from, m)| m.is_feed() && from.z <= zmax && m.to.z <= zmax)
        .map(|(from, m)| {
            let len = m.length_from(from);
            let dz = from.z - m.to.z;
            (len * len - dz * dz).max(0.0).sqrt()
        })
        .sum()
}

/// What the material `previous` left at the floor `floor_z` of `spec` needs of `tool` cutting
/// at most `width` mm wide, on a raster of cell `cell` (module docs). Errors: a width or cell
/// that is not positive, a cell above a quarter of the tool's radius.
pub fn rest_need(
    spec: StockSpec<'_>,
    previous: &Toolpath,
    floor_z: f64,
    tool: &Tool,
    width: f64,
    cell: f64,
) -> Result<RestNeed, InputError> {
    let at = "rest machining's need";
    require_positive("width of cut", width, at)?;
    require_positive("cell", cell, at)?;
    let r = tool.radius();
    if cell > 0.25 * r {
        return Err(InputError::new("cell", cell).at(at).expected(format!(
            "at most a quarter of the tool's radius ({} mm)",
            0.25 * r
        )));
    }
    let c = cell;
    let walls: Vec<&Polyline<f64>> = std::iter::once(spec.outer.polyline())
        .chain(spec.islands.iter().map(|i| i.polyline()))
        .collect();
    let mut ras = Raster::new(spec.outer.bounds(), c);
    ras.fill(&walls);
    let reach = ReachMap::new(&ras, &walls, r + spec.wall_stock);
    sweep(&mut ras, previous, floor_z, c);
    let limit = r - 2.0 * c;
    let (nx, ny) = ras.dims();
    let mut left: HashMap<(usize, usize), usize> = HashMap::new();
    for j in 0..ny {
        for i in 0..nx {
            if ras.get(i, j) {
                let d = reach.distance(ras.centre(i, j));
                if d == 0.0 || d <= limit {
                    left.insert((i, j), usize::MAX);
                }
            }
        }
    }
    let indexed: Vec<IndexedWall<'_>> = walls.iter().map(|w| IndexedWall::new(w)).collect();
    let mut cells: Vec<(usize, usize)> = left.keys().copied().collect();
    cells.sort_unstable_by_key(|&(i, j)| (j, i));
    let mut members_of: Vec<Vec<(usize, usize)>> = Vec::new();
    for seed in cells {
        if left[&seed] != usize::MAX {
            continue;
        }
        let id = members_of.len();
        let mut members = vec![seed];
        left.insert(seed, id);
        let mut k = 0;
        while k < members.len() {
            let (i, j) = members[k];
            k += 1;
            for (di, dj) in NEIGHBOURS {
                let n = (i.wrapping_add_signed(di), j.wrapping_add_signed(dj));
                if left.get(&n) == Some(&usize::MAX) {
                    left.insert(n, id);
                    members.push(n);
                }
            }
        }
        members_of.push(members);
    }
    let path = FloorPath::new(previous, floor_z, c);
    let walls_len = wall_lengths(
        members_of.len(),
        &left,
        &ras,
        &walls,
        &indexed,
        &path,
        previous.tool.radius(),
        r,
    );
    let mut regions = Vec::new();
    let mut boxes = Vec::new();
    for (members, wall) in members_of.iter().zip(walls_len) {
        let pts: Vec<Point> = members.iter().map(|&(i, j)| ras.centre(i, j)).collect();
        let area = pts.len() as f64 * c * c;
        let n = pts.len() as f64;
        let centroid = Point::new(
            pts.iter().map(|p| p.x).sum::<f64>() / n,
            pts.iter().map(|p| p.y).sum::<f64>() / n,
        );
        let bb = pts.iter().fold(
            Aabb {
                min: pts[0],
                max: pts[0],
            },
            |b, p| Aabb {
                min: Point::new(b.min.x.min(p.x), b.min.y.min(p.y)),
                max: Point::new(b.max.x.max(p.x), b.max.y.max(p.y)),
            },
        );
        boxes.push(bb);
        regions.push(UncutRegion {
            area_mm2: area,
            wall_length_mm: wall,
            need_mm: (area / width).max(wall),
            centroid,
        });
    }
    let links_mm = spanning_tree(&boxes, 2.0 * r);
    Ok(RestNeed { regions, links_mm })
}

/// The 8-neighbours of a cell.
const NEIGHBOURS: [(isize, isize); 8] = [
    (-1, -1),
    (0, -1),
    (1, -1),
    (-1, 0),
    (1, 0),
    (-1, 1),
    (0, 1),
    (1, 1),
];

/// Clears from `ras` what `previous`'s floor moves swept (module docs).
fn sweep(ras: &mut Raster, previous: &Toolpath, floor_z: f64, c: f64) {
    let rr = previous.tool.radius();
    let zmax = floor_z + FLOOR_Z_TOLERANCE;
    for (from, m) in previous.segments() {
        if !m.is_feed() || from.z > zmax || m.to.z > zmax {
            continue;
        }
        let len = m.length_from(from);
        let n = ((len / c).ceil() as usize).max(1);
        let mut a = from.xy();
        for k in 1..=n {
            let b = m.point_at(from, len * k as f64 / n as f64).xy();
            ras.clear_capsule(a, b, rr);
            a = b;
        }
    }
}

/// The previous program's floor moves as chords (arcs every cell), bucketed on a grid of
/// side `bucket` for the distance queries of [`wall_lengths`].
struct FloorPath {
    chords: Vec<(Point, Point)>,
    buckets: HashMap<(i64, i64), Vec<usize>>,
    bucket: f64,
}

impl FloorPath {
    fn new(previous: &Toolpath, floor_z: f64, c: f64) -> Self {
        let zmax = floor_z + FLOOR_Z_TOLERANCE;
        let mut chords = Vec::new();
        for (from, m) in previous.segments() {
            if !m.is_feed() || from.z > zmax || m.to.z > zmax {
                continue;
            }
            let len = m.length_from(from);
            let n = match m.kind {
                MoveKind::Arc { .. } => ((len / c).ceil() as usize).max(1),
                _ => 1,
            };
            let mut a = from.xy();
            for k in 1..=n {
                let b = m.point_at(from, len * k as f64 / n as f64).xy();
                chords.push((a, b));
                a = b;
            }
        }
        let bucket = previous.tool.radius().max(c);
        let mut buckets: HashMap<(i64, i64), Vec<usize>> = HashMap::new();
        let key = |v: f64| (v / bucket).floor() as i64;
        for (k, (a, b)) in chords.iter().enumerate() {
            for i in key(a.x.min(b.x))..=key(a.x.max(b.x)) {
                for j in key(a.y.min(b.y))..=key(a.y.max(b.y)) {
                    buckets.entry((i, j)).or_default().push(k);
                }
            }
        }
        FloorPath {
            chords,
            buckets,
            bucket,
        }
    }

    /// True when a chord passes within `d` (at most the bucket) of `q`.
    fn within(&self, q: Point, d: f64) -> bool {
        let (i0, j0) = (
            (q.x / self.bucket).floor() as i64,
            (q.y / self.bucket).floor() as i64,
        );
        (i0 - 1..=i0 + 1).any(|i| {
            (j0 - 1..=j0 + 1).any(|j| {
                self.buckets.get(&(i, j)).is_some_and(|ks| {
                    ks.iter()
                        .any(|&k| q.distance_to_segment(self.chords[k].0, self.chords[k].1) <= d)
                })
            })
        })
    }
}

/// The wall contact length of each region at the rest tool's centre (module docs): the walls
/// sampled every half cell; a sample `q` is a contact of the region nearest it when the previous tool never came within its radius of it (exact distance to
/// its floor moves) and the rest tool touches it (`q + r·n` at least `r` from every wall).
#[allow(clippy::too_many_arguments)]
fn wall_lengths(
    regions: usize,
    label: &HashMap<(usize, usize), usize>,
    ras: &Raster,
    walls: &[&Polyline<f64>],
    indexed: &[IndexedWall<'_>],
    path: &FloorPath,
    big_r: f64,
    r: f64,
) -> Vec<f64> {
    let c = ras.cell();
    let o = ras.centre(0, 0);
    let far = (r / c).ceil() as i64;
    // (loop, length along it, tool centre) per region.
    let mut contacts: Vec<Vec<(usize, f64, Point)>> = vec![Vec::new(); regions];
    let mut consider = |k: usize, along: f64, q: Point, normal: (f64, f64)| {
        if path.within(q, big_r + CONTACT_DEPTH_CELLS * c) {
            return;
        }
        let (ci, cj) = (
            ((q.x - o.x) / c).round() as i64,
            ((q.y - o.y) / c).round() as i64,
        );
        // The nearest region's cell within `r`, in windows growing from CONTACT_CELLS.
        let mut best: Option<(f64, usize, Point)> = None;
        let mut w = (CONTACT_CELLS.ceil() as i64).max(1);
        while best.is_none() && w <= 2 * far {
            let w_now = w.min(far);
            for i in ci - w_now..=ci + w_now {
                for j in cj - w_now..=cj + w_now {
                    if i < 0 || j < 0 {
                        continue;
                    }
                    let Some(&id) = label.get(&(i as usize, j as usize)) else {
                        continue;
                    };
                    let p = ras.centre(i as usize, j as usize);
                    let d = p.distance(q);
                    if d <= r && best.is_none_or(|b| d < b.0) {
                        best = Some((d, id, p));
                    }
                }
            }
            if w_now == far {
                break;
            }
            w *= 2;
        }
        let Some((_, id, p)) = best else { return };
        let sign = if normal.0 * (p.x - q.x) + normal.1 * (p.y - q.y) >= 0.0 {
            1.0
        } else {
            -1.0
        };
        let t = Point::new(q.x + sign * r * normal.0, q.y + sign * r * normal.1);
        if indexed.iter().all(|w| w.distance(t) >= r - CONTACT_SLACK) {
            contacts[id].push((k, along, t));
        }
    };
    for (k, pl) in walls.iter().enumerate() {
        let mut along = 0.0;
        for (a, b) in pl.iter_segments() {
            let (pa, pb) = (Point::new(a.x, a.y), Point::new(b.x, b.y));
            if a.bulge_is_zero() {
                let len = pa.distance(pb);
                if len <= 0.0 {
                    continue;
                }
                let normal = (-(pb.y - pa.y) / len, (pb.x - pa.x) / len);
                let n = ((2.0 * len / c).ceil() as usize).max(1);
                for s in 0..=n {
                    let f = s as f64 / n as f64;
                    consider(k, along + f * len, pa.lerp(pb, f), normal);
                }
                along += len;
            } else {
                let (rad, cen) = seg_arc_radius_and_center(a, b);
                let sweep = 4.0 * a.bulge.atan();
                let a0 = (pa.y - cen.y).atan2(pa.x - cen.x);
                let len = rad * sweep.abs();
                let n = ((2.0 * len / c).ceil() as usize).max(1);
                for s in 0..=n {
                    let f = s as f64 / n as f64;
                    let ang = a0 + f * sweep;
                    let (cs, sn) = (ang.cos(), ang.sin());
                    let q = Point::new(cen.x + rad * cs, cen.y + rad * sn);
                    consider(k, along + f * len, q, (cs, sn));
                }
                along += len;
            }
        }
    }
    contacts
        .into_iter()
        .map(|mut cs| {
            cs.sort_by(|a, b| a.0.cmp(&b.0).then(a.1.total_cmp(&b.1)));
            cs.windows(2)
                .filter(|w| w[0].0 == w[1].0)
                .map(|w| w[0].2.distance(w[1].2))
                .filter(|&d| d <= CONTACT_GAP_CELLS * c)
                .sum()
        })
        .collect()
}

/// The weight of the minimum spanning tree of `boxes` at their distances less `shrink`
/// (at least 0), mm.
fn spanning_tree(boxes: &[Aabb], shrink: f64) -> f64 {
    let dist = |a: &Aabb, b: &Aabb| {
        let dx = (a.min.x - b.max.x).max(b.min.x - a.max.x).max(0.0);
        let dy = (a.min.y - b.max.y).max(b.min.y - a.max.y).max(0.0);
        (dx.hypot(dy) - shrink).max(0.0)
    };
    let n = boxes.len();
    if n < 2 {
        return 0.0;
    }
    let mut best = vec![f64::INFINITY; n];
    let mut done = vec![false; n];
    best[0] = 0.0;
    let mut total = 0.0;
    for _ in 0..n {
        let Some(u) = (0..n)
            .filter(|&i| !done[i])
            .min_by(|&a, &b| best[a].total_cmp(&best[b]))
        else {
            break;
        };
        done[u] = true;
        total += best[u];
        for v in 0..n {
            if !done[v] {
                best[v] = best[v].min(dist(&boxes[u], &boxes[v]));
            }
        }
    }
    total
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::{Outline, Point3};
    use crate::toolpath::Move;
    use std::f64::consts::FRAC_PI_2;

    /// Square loops of feed moves of `tool` in the square `[0, side]²` at the floor `z`, at
    /// `d`, `2d`, … from its walls (`d` the tool's radius): it clears all but the corners.
    fn around(tool: Tool, side: f64, z: f64) -> Toolpath {
        let d = tool.radius();
        let mut tp = Toolpath::new(tool, Point3::new(d, d, z));
        let mut e = d;
        while e <= 0.5 * side {
            let pts = [
                Point::new(e, e),
                Point::new(side - e, e),
                Point::new(side - e, side - e),
                Point::new(e, side - e),
                Point::new(e, e),
            ];
            for p in pts {
                tp.push(Move::line(Point3::from_xy(p, z), 10.0));
            }
            e += d;
        }
        tp
    }

    fn square(side: f64) -> Outline {
        let pts = [
            Point::new(0.0, 0.0),
            Point::new(side, 0.0),
            Point::new(side, side),
            Point::new(0.0, side),
        ];
        Outline::from_points(&pts, "test square").unwrap()
    }

    /// A 40 mm square, a 12 mm tool around its walls: four square corners left as fillets of
    /// radius 6; a 4 mm tool must follow both walls from 6 to 2 mm of each corner (the
    /// contact set is 2·(R − r) = 8 mm per corner), and the corners are at least
    /// 40 − 12 − 4 = 24 mm apart (three links).
    #[test]
    fn a_square_corner_needs_both_walls_from_the_large_radius_to_the_small_one() {
        let o = square(40.0);
        let spec = StockSpec {
            outer: &o,
            islands: &[],
            wall_stock: 0.0,
        };
        let (rr, r) = (6.0, 2.0);
        let prev = around(Tool::flat(2.0 * rr).unwrap(), 40.0, -5.0);
        let c = 0.05;
        let need = rest_need(spec, &prev, -5.0, &Tool::flat(2.0 * r).unwrap(), 1.6, c).unwrap();
        assert_eq!(need.regions.len(), 4, "{need}");
        for reg in &need.regions {
            // Exact but at the stretches' far ends, where the large tool's circle leaves the
            // wall thinner than a cell (√(2·R·c) each) and half a sample.
            let full = 2.0 * (rr - r);
            let ends = 2.0 * (2.0 * rr * c + c * c).sqrt() + c;
            assert!(
                reg.wall_length_mm <= full + c && reg.wall_length_mm >= full - ends,
                "{reg:?}"
            );
            // The corner's reachable area: the square less the large disc's quarter, less the
            // small tool's own unreachable corner; the coverage's reach leaves a band of a few
            // cells along its edge (about 17 mm long).
            let area = (rr * rr - r * r) * (1.0 - FRAC_PI_2 / 2.0);
            assert!(
                reg.area_mm2 <= area && reg.area_mm2 >= area - 17.0 * 5.0 * c,
                "{reg:?} vs {area}"
            );
            assert!((reg.need_mm - reg.wall_length_mm).abs() < 1e-12, "{reg:?}");
        }
        // Three links along the sides: no less than the corners' squares allow, no more than
        // the contact stretches' ends are apart.
        let ends = (2.0 * rr * c + c * c).sqrt() + c;
        let (lo, hi) = (
            3.0 * (40.0 - 2.0 * rr - 2.0 * r),
            3.0 * (40.0 - 2.0 * (rr - ends)),
        );
        assert!(
            need.links_mm >= lo && need.links_mm <= hi,
            "{need}: {lo}..{hi}"
        );
    }

    /// A rounded corner of radius 5 after a 12 mm tool: the sliver along the fillet needs at
    /// least the fillet's arc at the 4 mm tool's radius, `π/2·(ρ − r)`, and at most that and
    /// the straight stretches where the large tool's circle leaves the wall (`R − ρ` each).
    #[test]
    fn a_fillet_tighter_than_the_large_tool_needs_its_arc_at_the_small_radius() {
        let (side, rho, rr, r, c) = (40.0, 5.0, 6.0, 2.0, 0.05);
        let b = (std::f64::consts::PI / 8.0).tan();
        let v = |x: f64, y: f64, bulge: f64| (Point::new(x, y), bulge);
        let o = Outline::new(
            &[
                v(rho, 0.0, 0.0),
                v(side - rho, 0.0, b),
                v(side, rho, 0.0),
                v(side, side - rho, b),
                v(side - rho, side, 0.0),
                v(rho, side, b),
                v(0.0, side - rho, 0.0),
                v(0.0, rho, b),
            ],
            "test rounded square",
        )
        .unwrap();
        let spec = StockSpec {
            outer: &o,
            islands: &[],
            wall_stock: 0.0,
        };
        let prev = around(Tool::flat(2.0 * rr).unwrap(), side, 0.0);
        let need = rest_need(spec, &prev, 0.0, &Tool::flat(2.0 * r).unwrap(), 1.6, c).unwrap();
        assert_eq!(need.regions.len(), 4, "{need}");
        let arc = FRAC_PI_2 * (rho - r);
        for reg in &need.regions {
            // Less at the ends, where the sliver is thinner than a cell.
            let ends = 2.0 * (2.0 * rr * c + c * c).sqrt() + c;
            assert!(reg.wall_length_mm >= arc - ends, "{reg:?} vs {arc}");
            assert!(
                reg.wall_length_mm <= arc + 2.0 * (rr - rho) + 3.0 * c,
                "{reg:?} vs {arc}"
            );
        }
    }

    /// Nothing cut before: a 10 mm square holds 100 mm² within a 4 mm tool's reach, and at
    /// 1.6 mm wide that is 62.5 mm of cut, more than its wall contact (the 6 mm square at the
    /// tool's radius, 24 mm).
    #[test]
    fn a_region_wider_than_its_walls_needs_its_area_over_the_width() {
        let o = square(10.0);
        let spec = StockSpec {
            outer: &o,
            islands: &[],
            wall_stock: 0.0,
        };
        let prev = Toolpath::new(Tool::flat(12.0).unwrap(), Point3::new(0.0, 0.0, 5.0));
        let c = 0.05;
        let need = rest_need(spec, &prev, -5.0, &Tool::flat(4.0).unwrap(), 1.6, c).unwrap();
        assert_eq!(need.regions.len(), 1, "{need}");
        let reg = &need.regions[0];
        // Within `r − 2c` of the 6 mm square of centres, give or take a cell: a square with
        // the tool's corners rounded.
        let area = |reach: f64| {
            (6.0 + 2.0 * reach).powi(2) - 4.0 * reach * reach * (1.0 - FRAC_PI_2 / 2.0)
        };
        let (lo, hi) = (area(2.0 - 3.0 * c), area(2.0 - c));
        assert!(
            reg.area_mm2 >= lo && reg.area_mm2 <= hi,
            "{reg:?}: {lo}..{hi}"
        );
        assert!((reg.wall_length_mm - 24.0).abs() <= 4.0 * c, "{reg:?}");
        assert!((reg.need_mm - reg.area_mm2 / 1.6).abs() < 1e-9, "{reg:?}");
        assert!(need.links_mm.abs() < 1e-12, "{need}");
    }

    #[test]
    fn a_width_or_cell_out_of_range_is_refused_by_name() {
        let o = square(10.0);
        let spec = StockSpec {
            outer: &o,
            islands: &[],
            wall_stock: 0.0,
        };
        let prev = Toolpath::new(Tool::flat(12.0).unwrap(), Point3::new(0.0, 0.0, 5.0));
        let e = rest_need(spec, &prev, 0.0, &Tool::flat(4.0).unwrap(), 0.0, 0.05).unwrap_err();
        assert!(e.to_string().contains("width of cut"), "{e}");
        let e = rest_need(spec, &prev, 0.0, &Tool::flat(4.0).unwrap(), 1.0, 1.0).unwrap_err();
        assert!(e.to_string().contains("cell"), "{e}");
    }

    /// The floor cut of a path: its feed at the floor in the plane, not its plunge or links.
    #[test]
    fn the_floor_cut_counts_only_feed_at_the_floor() {
        let mut tp = Toolpath::new(Tool::flat(4.0).unwrap(), Point3::new(0.0, 0.0, 5.0));
        tp.push(Move::line(Point3::new(0.0, 0.0, -5.0), 1.0));
        tp.push(Move::line(Point3::new(3.0, 4.0, -5.0), 1.0));
        tp.push(Move::line(Point3::new(3.0, 4.0, -4.5), 1.0));
        tp.push(Move::line(Point3::new(9.0, 4.0, -4.5), 1.0));
        tp.push(Move::line(Point3::new(9.0, 4.0, -5.0), 1.0));
        tp.push(Move::line(Point3::new(9.0, 6.0, -5.0), 1.0));
        tp.push(Move::rapid(Point3::new(9.0, 6.0, 5.0)));
        assert!((floor_cut_length(&tp, -5.0) - 7.0).abs() < 1e-9);
    }
}
