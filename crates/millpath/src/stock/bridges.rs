//! The bridge verdict: what holds a profiled piece to the stock, read from the height field.
//!
//! A profile cuts a slot one tool diameter wide along an outline, outside it for a part
//! ([`CutSide::Outside`]) or inside it for a window whose slug drops out
//! ([`CutSide::Inside`]). The **piece** is what the slot frees (the part, or the slug); the
//! **stock** is the rest. Down to the through-cut floor the slot separates the two; what the
//! program leaves standing in it (tabs, and whatever it failed to cut) is a **bridge**.
//!
//! 1. **The band.** Every cell of the field near the outline gets its distance to the outline
//!    from a Euclidean distance transform (exact on the grid, computed over the band alone) seeded with the
//!    cells on the piece's side of the outline (even-odd fill at cell centres) and the cells
//!    holding points of the outline sampled every `c/2`: within `c` of the exact distance.
//!    The band is the cells on the slot's side at a distance in `[ρ, 2r − ρ]`, the slot less
//!    a rim `ρ` on either side ([`BridgeOptions::rim`], by default `2c` plus
//!    [`super::GOUGE_RESOLUTION`]): what the tool's path, written to 3 decimals, may leave
//!    along the slot's walls (and the transform's error) is not in the band, so it cannot
//!    join bridges along a wall. Cells nearer the outline than `ρ` count with the piece,
//!    cells beyond `2r − ρ` with the stock.
//! 2. **Material**: a cell whose height is above the floor by more than the z tolerance.
//! 3. **Bridges**: the 8-connected components of the band's material (a diagonal contact
//!    connects, so a thread one cell wide still counts). Each bridge says what it touches
//!    (an 8-neighbour holding material): the piece, the stock, both ([`Touches::Both`]: it
//!    holds the piece), or neither (a loose chip).
//!
//!    For an outside cut the far side is the stock only where material off the piece (far or
//!    band cells) joins it to the box's border: a bay of the outline behind a mouth narrower
//!    than the tool, left standing, is cut off from the plate by the slot across its mouth and
//!    holds nothing (a breadth-first search from each bridge touching both sides, its cells
//!    remembered for the next).
//!
//! Every path from the piece to the stock crosses the band (it is `2r − 2ρ` wide, many cells),
//! so the piece is held exactly by the bridges that touch both, and falls free without them:
//! [`BridgeVerdict::hold`] is [`Hold::Free`] when no bridge touches both.
//!
//! Each bridge has its area, its centroid, its top (the least and the greatest height of its
//! cells), its extent along the outline: the arc-length interval (from the outline's first
//! vertex, in its direction) covered by the nearest outline points of its cells, taken as the
//! shortest interval round the loop holding them all; and its **neck**, the least such
//! extent over the layers of its cells one cell thick across the slot (cells at the same
//! distance from the outline, by the transform). A tab a program leaves by lifting over a
//! stretch `w + 2r` of its path is `w` wide at the slot's middle (its neck) and wider towards
//! the walls (its extent, within the band). At a cell of `c` both are within about `2c`
//! (a bridge of more than 50 000 cells, a stretch of slot left uncut, is measured on every
//! k-th of its cells, as finely as they lie).

use super::heightfield::{DEFAULT_Z_TOLERANCE, HeightField};
use super::nearest::IndexedWall;
use super::raster::Raster;
use super::reach::BandDistance;
use crate::error::{InputError, require_finite, require_positive};
use crate::geom::{Aabb, Outline, Point};
use cavalier_contours::polyline::{PlineSource, seg_arc_radius_and_center};
use std::fmt;

/// Which side of the outline the profile cut.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum CutSide {
    /// Outside the outline: the piece is the part inside it.
    #[default]
    Outside,
    /// Inside the outline: the piece is the slug the window leaves.
    Inside,
}

/// How the band is read. Built from [`Default`] with the `with_*` methods.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct BridgeOptions {
    /// The side the profile cut.
    pub side: CutSide,
    /// The rim left out of the band along each wall of the slot, mm (`None`: two cells plus
    /// [`super::GOUGE_RESOLUTION`]).
    pub rim: Option<f64>,
    /// Height above the floor beyond which a cell holds material, mm.
    pub z_tolerance: f64,
}

impl Default for BridgeOptions {
    fn default() -> Self {
        BridgeOptions {
            side: CutSide::Outside,
            rim: None,
            z_tolerance: DEFAULT_Z_TOLERANCE,
        }
    }
}

option_builders! {
    BridgeOptions;
    /// Sets [`BridgeOptions::side`].
    with_side => side: CutSide;
    /// Sets [`BridgeOptions::z_tolerance`], mm.
    with_z_tolerance => z_tolerance: f64;
}

impl BridgeOptions {
    /// Sets [`BridgeOptions::rim`], mm.
    #[must_use]
    pub fn with_rim(mut self, rim: f64) -> Self {
        self.rim = Some(rim);
        self
    }
}

/// What a bridge touches.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Touches {
    /// The piece and the stock: it holds the piece.
    Both,
    /// Only the piece (material left on its wall).
    Piece,
    /// Only the stock (material left on the slot's outer wall).
    Stock,
    /// Neither: a loose chip.
    Neither,
}

impl fmt::Display for Touches {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Touches::Both => "holds the piece to the stock",
            Touches::Piece => "touches only the piece",
            Touches::Stock => "touches only the stock",
            Touches::Neither => "loose",
        })
    }
}

/// Material left standing in the slot: one connected component.
#[derive(Debug, Clone, PartialEq)]
pub struct Bridge {
    /// What it touches.
    pub touches: Touches,
    /// Where it starts along the outline, mm of arc length from the outline's first vertex
    /// (in `[0, perimeter)`).
    pub start_mm: f64,
    /// Its extent along the outline, mm (it ends at `start_mm + length_mm`, modulo the
    /// perimeter).
    pub length_mm: f64,
    /// Its narrowest extent along the outline over the layers one cell thick across the slot
    /// (at the same distance from the outline), mm: a square tab cut by a round tool is
    /// narrowest at the slot's middle, `2r` less than where it meets the walls.
    pub neck_mm: f64,
    /// Centroid of its cells.
    pub centroid: Point,
    /// Area of its cells, mm².
    pub area_mm2: f64,
    /// The lowest top of its cells, mm.
    pub top_min: f64,
    /// The highest top of its cells, mm.
    pub top_max: f64,
}

impl Bridge {
    /// True when it holds the piece to the stock.
    pub fn holds(&self) -> bool {
        self.touches == Touches::Both
    }

    /// The middle of its extent along the outline, mm (modulo the perimeter).
    pub fn middle_mm(&self) -> f64 {
        self.start_mm + 0.5 * self.length_mm
    }
}

impl fmt::Display for Bridge {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{:.3} mm along the outline from {:.3} mm (neck {:.3} mm), around ({:.3}, {:.3}), top z {:.3} to {:.3}, {:.3} mm²: {}",
            self.length_mm,
            self.start_mm,
            self.neck_mm,
            self.centroid.x,
            self.centroid.y,
            self.top_min,
            self.top_max,
            self.area_mm2,
            self.touches
        )
    }
}

/// Whether the piece is held.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Hold {
    /// No bridge touches both: the piece falls free.
    Free,
    /// Held by this many bridges.
    Held {
        /// The bridges touching the piece and the stock.
        bridges: usize,
    },
}

impl fmt::Display for Hold {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Hold::Free => f.write_str("falls free"),
            Hold::Held { bridges: 1 } => f.write_str("held by 1 bridge"),
            Hold::Held { bridges } => write!(f, "held by {bridges} bridges"),
        }
    }
}

/// Everything left standing in the slot.
#[derive(Debug, Clone, PartialEq)]
pub struct BridgeVerdict {
    /// Every bridge, in the order of `start_mm`.
    pub bridges: Vec<Bridge>,
    /// The outline's length, mm.
    pub perimeter_mm: f64,
    /// The band's distances from the outline, mm (`ρ` and `2r − ρ`).
    pub band_mm: (f64, f64),
    /// The field's cell, mm.
    pub cell_mm: f64,
}

impl BridgeVerdict {
    /// The bridges that hold the piece to the stock.
    pub fn holding(&self) -> impl Iterator<Item = &Bridge> + '_ {
        self.bridges.iter().filter(|b| b.holds())
    }

    /// Whether the piece is held, and by how many bridges.
    pub fn hold(&self) -> Hold {
        match self.holding().count() {
            0 => Hold::Free,
            n => Hold::Held { bridges: n },
        }
    }
}

impl fmt::Display for BridgeVerdict {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.hold())?;
        for b in &self.bridges {
            write!(f, "; {b}")?;
        }
        Ok(())
    }
}

/// Cell classes of the band's neighbourhood.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Class {
    Piece,
    Band,
    Stock,
}

/// The bridges left in the slot a profile of tool radius `tool_radius` cut along `outline`
/// down to `floor_z` (the stock's bottom for a through cut, or the profile's bottom), read
/// from `field` (module docs). Errors name a radius or floor that is not a finite positive
/// length or z, a rim leaving no band, and an outline off the field.
pub fn held_by(
    field: &HeightField,
    outline: &Outline,
    floor_z: f64,
    tool_radius: f64,
    opts: &BridgeOptions,
) -> Result<BridgeVerdict, InputError> {
    let r = require_positive("tool radius", tool_radius, "bridge verdict")?;
    let floor = require_finite("floor z", floor_z, "bridge verdict")?;
    let c = field.cell();
    let rim = opts
        .rim
        .unwrap_or(2.0 * c + super::GOUGE_RESOLUTION)
        .max(0.0);
    let (inner, outer) = (rim, 2.0 * r - rim);
    if outer - inner < 2.0 * c {
        return Err(InputError::new("tool radius", r)
            .at("bridge verdict")
            .expected(format!(
                "a slot wider than its rims ({rim:.4} mm each) and two cells ({c:.4} mm)"
            )));
    }
    // The sub-grid of the field around the outline.
    let ob = outline.bounds().inflate(2.0 * r + 3.0 * c);
    let fb = field.bounds();
    let (nx, ny) = field.dims();
    let index =
        |x: f64, o: f64, n: usize| ((x - o) / c).floor().clamp(0.0, n as f64 - 1.0) as usize;
    let (i0, i1) = (index(ob.min.x, fb.min.x, nx), index(ob.max.x, fb.min.x, nx));
    let (j0, j1) = (index(ob.min.y, fb.min.y, ny), index(ob.max.y, fb.min.y, ny));
    if ob.max.x < fb.min.x || ob.min.x > fb.max.x || ob.max.y < fb.min.y || ob.min.y > fb.max.y {
        return Err(InputError::new(
            "outline",
            format!(
                "({:.3}, {:.3}) to ({:.3}, {:.3})",
                ob.min.x, ob.min.y, ob.max.x, ob.max.y
            ),
        )
        .at("bridge verdict")
        .expected("an outline over the stock's height field"));
    }
    let (sx, sy) = (i1 - i0 + 1, j1 - j0 + 1);
    // Inside the outline, cell by cell, on a raster whose cell (0, 0) is the field's (i0, j0).
    let min = Point::new(
        fb.min.x + (i0 + 1) as f64 * c,
        fb.min.y + (j0 + 1) as f64 * c,
    );
    let ras_bounds = Aabb {
        min,
        max: Point::new(
            min.x + (sx as f64 - 2.0).max(0.0) * c,
            min.y + (sy as f64 - 2.0).max(0.0) * c,
        ),
    };
    let mut ras = Raster::new(ras_bounds, c);
    ras.fill(&[outline.polyline()]);
    let (rx, ry) = ras.dims();
    let inside = |a: usize, b: usize| a < rx && b < ry && ras.get(a, b);
    let on_slot_side = |a: usize, b: usize| match opts.side {
        CutSide::Outside => !inside(a, b),
        CutSide::Inside => inside(a, b),
    };
    // Distance to the outline over the slot's side, out to just past the band: seeds on the
    // walls (the outline sampled every `c/2`) and on the other side. Of the other side's
    // cells only those with a 4-neighbour on the slot's side are seeds: the nearest cell of
    // the other side to any cell of the slot's is one of them (a step from a cell whose four
    // neighbours are all on the other side, towards the slot's cell, comes nearer), and the
    // outline passes within a cell of each, so within two of a sample's cell.
    let pl = outline.polyline();
    let samples = ((pl.path_length() / (0.5 * c)).ceil() as usize).max(8);
    let mut seeds: Vec<(usize, usize)> = Vec::with_capacity(2 * samples);
    for p in crate::geom::region::sample_loop(pl, samples) {
        let a = ((p.x - fb.min.x) / c - 0.5).round() - i0 as f64;
        let b = ((p.y - fb.min.y) / c - 0.5).round() - j0 as f64;
        if a >= 0.0 && b >= 0.0 && (a as usize) < sx && (b as usize) < sy {
            seeds.push((a as usize, b as usize));
        }
    }
    let on_walls = seeds.len();
    for k in 0..on_walls {
        let (a, b) = seeds[k];
        for na in a.saturating_sub(3)..(a + 4).min(sx) {
            for nb in b.saturating_sub(3)..(b + 4).min(sy) {
                let by_slot = [(1, 0), (-1, 0), (0, 1), (0, -1)].iter().any(|&(da, db)| {
                    let (xa, xb) = (na as isize + da, nb as isize + db);
                    xa >= 0
                        && xb >= 0
                        && (xa as usize) < sx
                        && (xb as usize) < sy
                        && on_slot_side(xa as usize, xb as usize)
                });
                if !on_slot_side(na, nb) && by_slot {
                    seeds.push((na, nb));
                }
            }
        }
    }
    let d2 = BandDistance::new(&seeds, sx, sy, outer / c + 2.0);
    drop(seeds);
    // The wall's side of the slot (the outline's other side and the near rim) and its far
    // side: the piece and the stock for an outside cut, the other way round inside.
    let (near, far) = match opts.side {
        CutSide::Outside => (Class::Piece, Class::Stock),
        CutSide::Inside => (Class::Stock, Class::Piece),
    };
    // Each cell's class, from its side and its distance (read where needed: most cells of
    // the box are far from the slot's material).
    let class_of = |a: usize, b: usize| {
        if !on_slot_side(a, b) {
            return near;
        }
        match d2.d2(b * sx + a) {
            Some(g) => {
                let d = f64::from(g).sqrt() * c;
                if d < inner {
                    near
                } else if d <= outer {
                    Class::Band
                } else {
                    far
                }
            }
            None => far,
        }
    };
    let heights = field.heights();
    let limit = floor + opts.z_tolerance.max(0.0);
    let solid = |a: usize, b: usize| f64::from(heights[(j0 + b) * nx + i0 + a]) > limit;
    // 8-connected components of the band's material.
    let mut seen = vec![false; sx * sy];
    // Outside cuts: the far side's material is the stock only where it reaches the box's
    // border through material off the piece (far or band cells); what the slot cut off from
    // the plate (a bay behind a mouth narrower than the tool, left uncut) holds nothing.
    // Searched from each bridge that touches the piece and the far side, cells cached.
    let mut reach = ReachCache::default();
    let off_piece = |a: usize, b: usize| solid(a, b) && class_of(a, b) != Class::Piece;
    let lengths = SegmentLengths::new(outline);
    let mut bridges = Vec::new();
    for &start in d2.within() {
        let (a, b) = (start % sx, start / sx);
        if seen[start] || !solid(a, b) || class_of(a, b) != Class::Band {
            continue;
        }
        seen[start] = true;
        let mut stack = vec![start];
        let mut cells = Vec::new();
        let (mut piece, mut stock) = (false, false);
        while let Some(k) = stack.pop() {
            cells.push(k);
            let (a, b) = ((k % sx) as isize, (k / sx) as isize);
            for (da, db) in NEIGHBOURS {
                let (na, nb) = (a + da, b + db);
                if na < 0 || nb < 0 || na as usize >= sx || nb as usize >= sy {
                    continue;
                }
                let (na, nb) = (na as usize, nb as usize);
                if !solid(na, nb) {
                    continue;
                }
                let nk = nb * sx + na;
                match class_of(na, nb) {
                    Class::Band => {
                        if !seen[nk] {
                            seen[nk] = true;
                            stack.push(nk);
                        }
                    }
                    Class::Piece => piece = true,
                    Class::Stock => stock = true,
                }
            }
        }
        if far == Class::Stock && piece && stock {
            stock = reach.reaches_border(&cells, sx, sy, &off_piece);
        }
        let touches = match (piece, stock) {
            (true, true) => Touches::Both,
            (true, false) => Touches::Piece,
            (false, true) => Touches::Stock,
            (false, false) => Touches::Neither,
        };
        let centre = |k: usize| field.centre(i0 + k % sx, j0 + k / sx);
        let n = cells.len() as f64;
        let (sum_x, sum_y) = cells.iter().fold((0.0, 0.0), |acc, &k| {
            let p = centre(k);
            (acc.0 + p.x, acc.1 + p.y)
        });
        let tops = cells
            .iter()
            .map(|&k| f64::from(heights[(j0 + k / sx) * nx + i0 + k % sx]));
        let (top_min, top_max) = tops.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), h| {
            (lo.min(h), hi.max(h))
        });
        // The extent of all its cells, and of each layer one cell thick across the slot.
        let stride = cells.len().div_ceil(MAX_MEASURED_CELLS).max(1);
        let arcs: Vec<(f64, usize)> = cells
            .iter()
            .step_by(stride)
            .map(|&k| {
                let layer = f64::from(d2.d2(k).unwrap_or(u32::MAX)).sqrt() as usize;
                (lengths.at(centre(k)), layer)
            })
            .collect();
        let (start_mm, length_mm) =
            circular_extent(arcs.iter().map(|a| a.0).collect(), lengths.total);
        let mut layers: std::collections::BTreeMap<usize, Vec<f64>> = Default::default();
        for (s, layer) in arcs {
            layers.entry(layer).or_default().push(s);
        }
        let neck_mm = layers
            .into_values()
            .map(|v| circular_extent(v, lengths.total).1)
            .fold(f64::INFINITY, f64::min);
        bridges.push(Bridge {
            touches,
            start_mm,
            length_mm,
            neck_mm,
            centroid: Point::new(sum_x / n, sum_y / n),
            area_mm2: n * c * c,
            top_min,
            top_max,
        });
    }
    bridges.sort_by(|x, y| x.start_mm.total_cmp(&y.start_mm));
    Ok(BridgeVerdict {
        bridges,
        perimeter_mm: lengths.total,
        band_mm: (inner, outer),
        cell_mm: c,
    })
}

/// Which material cells off the piece reach the box's border (module docs of `held_by`'s
/// outside case): cells found by earlier searches, with the answer of their search. Dense
/// per cell of the box, allocated zeroed at the first search (pages no search reaches are
/// never written).
#[derive(Debug, Default)]
struct ReachCache {
    /// Per cell: 0 unknown, 1 reaches the border, 2 does not.
    known: Vec<u8>,
    /// Per cell: the number of the last search that visited it.
    visited: Vec<u32>,
    /// Searches so far.
    searches: u32,
}

impl ReachCache {
    /// Whether material off the piece joins the cells `from` (a bridge) to the border of the
    /// `sx` × `sy` box: a breadth-first search over the cells `off` lets through, stopped at
    /// the first border cell or cell known to reach it; every cell it visits is remembered
    /// with the answer.
    fn reaches_border(
        &mut self,
        from: &[usize],
        sx: usize,
        sy: usize,
        off: &impl Fn(usize, usize) -> bool,
    ) -> bool {
        if self.known.len() != sx * sy {
            self.known = vec![0; sx * sy];
            self.visited = vec![0; sx * sy];
        }
        self.searches += 1;
        let id = self.searches;
        let mut seen: Vec<usize> = Vec::with_capacity(from.len());
        for &k in from {
            if self.visited[k] != id {
                self.visited[k] = id;
                seen.push(k);
            }
        }
        let mut queue: std::collections::VecDeque<usize> = seen.iter().copied().collect();
        let mut found = false;
        'search: while let Some(k) = queue.pop_front() {
            match self.known[k] {
                1 => {
                    found = true;
                    break;
                }
                2 => continue,
                _ => {}
            }
            let (a, b) = ((k % sx) as isize, (k / sx) as isize);
            if a == 0 || b == 0 || a as usize == sx - 1 || b as usize == sy - 1 {
                found = true;
                break;
            }
            for (da, db) in NEIGHBOURS {
                let (na, nb) = (a + da, b + db);
                if na < 0 || nb < 0 || na as usize >= sx || nb as usize >= sy {
                    continue;
                }
                let nk = nb as usize * sx + na as usize;
                if self.visited[nk] != id && off(na as usize, nb as usize) {
                    self.visited[nk] = id;
                    seen.push(nk);
                    if self.known[nk] == 1 {
                        found = true;
                        break 'search;
                    }
                    queue.push_back(nk);
                }
            }
        }
        // A search that found the border leaves unexplored cells behind: only those it
        // explored are known to reach it, and all of them do (each joins a start cell).
        let answer = if found { 1 } else { 2 };
        for k in seen {
            self.known[k] = answer;
        }
        found
    }
}

/// Most cells of one bridge whose nearest outline point is found for its extent and neck; a
/// larger bridge (a stretch of the slot left uncut) is measured on every k-th cell.
const MAX_MEASURED_CELLS: usize = 50_000;

/// The eight neighbours of a cell.
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

/// Arc length along an outline of the nearest point to a point.
struct SegmentLengths<'a> {
    outline: &'a Outline,
    wall: IndexedWall<'a>,
    /// Arc length at the start of each segment, mm.
    before: Vec<f64>,
    total: f64,
}

impl<'a> SegmentLengths<'a> {
    fn new(outline: &'a Outline) -> Self {
        let mut before = Vec::new();
        let mut total = 0.0;
        for (v1, v2) in outline.polyline().iter_segments() {
            before.push(total);
            total += if v1.bulge_is_zero() {
                (v2.x - v1.x).hypot(v2.y - v1.y)
            } else {
                let (radius, _) = seg_arc_radius_and_center(v1, v2);
                radius * (4.0 * v1.bulge.atan()).abs()
            };
        }
        SegmentLengths {
            outline,
            wall: IndexedWall::new(outline.polyline()),
            before,
            total,
        }
    }

    /// Arc length of the outline's point nearest to `p`, mm.
    fn at(&self, p: Point) -> f64 {
        let pl = self.outline.polyline();
        let Some((i, q)) = self.wall.closest(p) else {
            return 0.0;
        };
        let v1 = pl.at(i);
        let v2 = pl.at(pl.next_wrapping_index(i));
        let part = if v1.bulge_is_zero() {
            (q.x - v1.x).hypot(q.y - v1.y)
        } else {
            let (radius, centre) = seg_arc_radius_and_center(v1, v2);
            let a0 = (v1.y - centre.y).atan2(v1.x - centre.x);
            let a = (q.y - centre.y).atan2(q.x - centre.x);
            let turn = if v1.bulge > 0.0 { a - a0 } else { a0 - a };
            radius * turn.rem_euclid(std::f64::consts::TAU)
        };
        (self.before.get(i).copied().unwrap_or(0.0) + part).rem_euclid(self.total.max(1e-300))
    }
}

/// The shortest arc of a circle of circumference `total` holding every value: its start (in
/// `[0, total)`) and its length.
fn circular_extent(mut values: Vec<f64>, total: f64) -> (f64, f64) {
    values.sort_by(f64::total_cmp);
    let (Some(&first), Some(&last)) = (values.first(), values.last()) else {
        return (0.0, 0.0);
    };
    // The largest gap between consecutive values, the wrap-around one included; the arc
    // starts after it.
    let mut gap = (total - last + first, first);
    for w in values.windows(2) {
        if w[1] - w[0] > gap.0 {
            gap = (w[1] - w[0], w[1]);
        }
    }
    (gap.1, (total - gap.0).max(0.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn circular_extent_takes_the_shortest_arc() {
        let (s, l) = circular_extent(vec![1.0, 2.0, 3.0], 10.0);
        assert!((s - 1.0).abs() < 1e-12 && (l - 2.0).abs() < 1e-12);
        let (s, l) = circular_extent(vec![9.5, 0.5, 9.0], 10.0);
        assert!(
            (s - 9.0).abs() < 1e-12 && (l - 1.5).abs() < 1e-12,
            "{s} {l}"
        );
        assert_eq!(circular_extent(Vec::new(), 10.0), (0.0, 0.0));
    }
}
