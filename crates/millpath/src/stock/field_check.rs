//! What a whole job left, against what was drawn: the height field against the floors the
//! job meant to cut and the part it meant to keep.
//!
//! The job says where the material should go down to: regions ([`Floor`]: a boundary, its
//! islands, the floor z and the radius of the tool that finished it), and the part's
//! material ([`PartTop`]: inside its outline, outside its windows and every region, the
//! part's top). Every cell of the field is compared with the height it should have (the
//! lowest floor of the regions holding its centre; the part's top elsewhere in the part;
//! unchecked outside and in the windows):
//!
//! * **Cut into the part / below a floor**: a cell lower than its height by more than the z
//!   tolerance, unless its centre lies within the lateral tolerance of a wall (a boundary,
//!   island or the part's outline, exact distance): a tool running along a wall at the
//!   program's rounding, or the field's arc chords ([`super::ARC_SAGITTA`]), may take the
//!   cells on the wall.
//! * **Uncut**: a cell of a region higher than its floor by more than the z tolerance that
//!   the region's tool could have reached: its centre within `r − 2c` of a cell the tool
//!   centre may visit (at least `r` from every wall), by the distance transforms of
//!   [`super::reach`], not by offsetting the outlines. The corners and cusps a round tool
//!   cannot reach are not uncut. A region's uncut area beyond the tolerance
//!   ([`super::uncut_area_tolerance`] of its tool unless given) is a deviation.

use super::heightfield::{DEFAULT_Z_TOLERANCE, HeightField};
use super::nearest::IndexedWall;
use super::raster::Raster;
use super::reach::ReachMap;
use crate::geom::{Aabb, Outline, Point, Point3};
use cavalier_contours::polyline::Polyline;
use std::fmt;

/// A region the job cuts down to a floor.
#[derive(Debug, Clone, Copy)]
pub struct Floor<'a> {
    /// Its boundary.
    pub outer: &'a Outline,
    /// Its islands (material the region's cut leaves standing).
    pub islands: &'a [Outline],
    /// The floor z, mm.
    pub z: f64,
    /// The radius of the tool that finishes it, mm (where it can reach).
    pub tool_radius: f64,
}

/// The part's material: inside `outline`, outside its `windows` and every [`Floor`], at
/// `top_z`.
#[derive(Debug, Clone, Copy)]
pub struct PartTop<'a> {
    /// The part's outline.
    pub outline: &'a Outline,
    /// Outlines inside it that are not the part's (windows an inside profile cuts free:
    /// their slug may stay, held by tabs, or fall out); their walls are the part's.
    pub windows: &'a [Outline],
    /// Its top z (the faced top, or the stock's), mm.
    pub top_z: f64,
}

/// The tolerances of [`check_field`]. Built from [`Default`] with the `with_*` methods.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct CheckOptions {
    /// Height difference below which a cell is as drawn, mm.
    pub z_tolerance: f64,
    /// Distance from a wall within which a cell cut too low is not a deviation, mm.
    pub wall_tolerance: f64,
    /// Uncut area per region beyond which it is a deviation, mm² (`None`:
    /// [`super::uncut_area_tolerance`] of the region's tool).
    pub uncut_area: Option<f64>,
}

impl Default for CheckOptions {
    fn default() -> Self {
        CheckOptions {
            z_tolerance: DEFAULT_Z_TOLERANCE,
            wall_tolerance: super::GOUGE_RESOLUTION + super::heightfield::ARC_SAGITTA,
            uncut_area: None,
        }
    }
}

option_builders! {
    CheckOptions;
    /// Sets [`CheckOptions::z_tolerance`], mm.
    with_z_tolerance => z_tolerance: f64;
    /// Sets [`CheckOptions::wall_tolerance`], mm.
    with_wall_tolerance => wall_tolerance: f64;
}

impl CheckOptions {
    /// Sets [`CheckOptions::uncut_area`], mm².
    #[must_use]
    pub fn with_uncut_area(mut self, area: f64) -> Self {
        self.uncut_area = Some(area);
        self
    }
}

/// One way the field differs from the drawing.
#[derive(Debug, Clone, PartialEq)]
pub enum Deviation {
    /// Material of the part cut below its top.
    CutIntoPart {
        /// Area of the cells, mm².
        area_mm2: f64,
        /// The deepest, mm below the top.
        depth_mm: f64,
        /// Where the deepest is (its height as z).
        at: Point3,
    },
    /// A region cut below its floor.
    BelowFloor {
        /// The region, 0-based in the order given.
        floor: usize,
        /// Area of the cells, mm².
        area_mm2: f64,
        /// The deepest, mm below the floor.
        depth_mm: f64,
        /// Where the deepest is.
        at: Point3,
    },
    /// Material above a region's floor that its tool could have reached.
    Uncut {
        /// The region, 0-based.
        floor: usize,
        /// Area of the cells, mm².
        area_mm2: f64,
        /// The highest, mm above the floor.
        height_mm: f64,
        /// Where the highest is.
        at: Point3,
    },
}

impl fmt::Display for Deviation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let at = |p: &Point3| format!("({:.3}, {:.3}) at z = {:.3}", p.x, p.y, p.z);
        match self {
            Deviation::CutIntoPart {
                area_mm2,
                depth_mm,
                at: p,
            } => write!(
                f,
                "cut into the part: {area_mm2:.3} mm², up to {depth_mm:.3} mm deep, around {}",
                at(p)
            ),
            Deviation::BelowFloor {
                floor,
                area_mm2,
                depth_mm,
                at: p,
            } => write!(
                f,
                "region {}: cut below its floor over {area_mm2:.3} mm², up to {depth_mm:.3} mm, around {}",
                floor + 1,
                at(p)
            ),
            Deviation::Uncut {
                floor,
                area_mm2,
                height_mm,
                at: p,
            } => write!(
                f,
                "region {}: uncut material over {area_mm2:.3} mm², up to {height_mm:.3} mm above its floor, around {}",
                floor + 1,
                at(p)
            ),
        }
    }
}

/// What [`check_field`] found.
#[derive(Debug, Clone, PartialEq)]
pub struct FieldCheck {
    /// The deviations; empty when the field is the drawing.
    pub deviations: Vec<Deviation>,
    /// Uncut area of each region (reachable material above its floor), mm², whether or not
    /// beyond the tolerance.
    pub uncut_mm2: Vec<f64>,
    /// The field's cell, mm.
    pub cell_mm: f64,
}

impl FieldCheck {
    /// True when nothing deviates.
    pub fn passes(&self) -> bool {
        self.deviations.is_empty()
    }
}

impl fmt::Display for FieldCheck {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.deviations.is_empty() {
            return f.write_str("as drawn");
        }
        for (i, d) in self.deviations.iter().enumerate() {
            if i > 0 {
                f.write_str("; ")?;
            }
            write!(f, "{d}")?;
        }
        Ok(())
    }
}

/// The cells of the field inside some loops (even-odd), on a raster aligned with the field.
struct Mask {
    ras: Raster,
    i0: usize,
    j0: usize,
}

impl Mask {
    /// The cells of `field` whose centres lie inside an odd number of `loops`.
    fn new(field: &HeightField, loops: &[&Polyline<f64>], bounds: Aabb) -> Option<Self> {
        let fb = field.bounds();
        let c = field.cell();
        let (nx, ny) = field.dims();
        let b = bounds.inflate(2.0 * c);
        if b.max.x < fb.min.x || b.min.x > fb.max.x || b.max.y < fb.min.y || b.min.y > fb.max.y {
            return None;
        }
        let index =
            |x: f64, o: f64, n: usize| ((x - o) / c).floor().clamp(0.0, n as f64 - 1.0) as usize;
        let (i0, i1) = (index(b.min.x, fb.min.x, nx), index(b.max.x, fb.min.x, nx));
        let (j0, j1) = (index(b.min.y, fb.min.y, ny), index(b.max.y, fb.min.y, ny));
        // Raster::new puts its cell (0, 0) one cell below and left of its bounds.
        let min = Point::new(
            fb.min.x + (i0 + 1) as f64 * c,
            fb.min.y + (j0 + 1) as f64 * c,
        );
        let span = |n: usize| (n as f64 - 2.0).max(0.0) * c;
        let rb = Aabb {
            min,
            max: Point::new(min.x + span(i1 - i0 + 1), min.y + span(j1 - j0 + 1)),
        };
        let mut ras = Raster::new(rb, c);
        ras.fill(loops);
        Some(Mask { ras, i0, j0 })
    }

    /// True when field cell `(i, j)` is inside.
    fn contains(&self, i: usize, j: usize) -> bool {
        let (nx, ny) = self.ras.dims();
        i >= self.i0
            && j >= self.j0
            && i - self.i0 < nx
            && j - self.j0 < ny
            && self.ras.get(i - self.i0, j - self.j0)
    }

    /// The field cells inside, row by row.
    fn cells(&self) -> impl Iterator<Item = (usize, usize)> + '_ {
        let (nx, ny) = self.ras.dims();
        (0..ny).flat_map(move |b| {
            (0..nx)
                .filter(move |&a| self.ras.get(a, b))
                .map(move |a| (self.i0 + a, self.j0 + b))
        })
    }
}

/// A running area, extreme and where it is.
#[derive(Default)]
struct Worst {
    cells: usize,
    amount: f64,
    at: Option<Point3>,
}

impl Worst {
    fn add(&mut self, amount: f64, p: Point, h: f64) {
        self.cells += 1;
        if amount > self.amount || self.at.is_none() {
            self.amount = amount;
            self.at = Some(Point3::new(p.x, p.y, h));
        }
    }
}

/// The boundary and islands of a region.
fn loops_of<'a>(f: &Floor<'a>) -> Vec<&'a Polyline<f64>> {
    std::iter::once(f.outer.polyline())
        .chain(f.islands.iter().map(Outline::polyline))
        .collect()
}

/// Compares `field` with the job's `floors` and its `part` (module docs).
pub fn check_field(
    field: &HeightField,
    part: Option<PartTop<'_>>,
    floors: &[Floor<'_>],
    opts: &CheckOptions,
) -> FieldCheck {
    let c = field.cell();
    let ztol = opts.z_tolerance.max(0.0);
    let masks: Vec<Option<Mask>> = floors
        .iter()
        .map(|f| Mask::new(field, &loops_of(f), f.outer.bounds()))
        .collect();
    // Every wall, for the lateral tolerance of cells cut too low.
    let mut walls: Vec<&Polyline<f64>> = floors.iter().flat_map(|f| loops_of(f)).collect();
    if let Some(p) = part {
        walls.push(p.outline.polyline());
        walls.extend(p.windows.iter().map(Outline::polyline));
    }
    let indexed: Vec<IndexedWall<'_>> = walls.iter().map(|w| IndexedWall::new(w)).collect();
    let near_wall = |p: Point| indexed.iter().any(|w| w.distance(p) <= opts.wall_tolerance);
    // The lowest floor of the regions holding a cell.
    let floor_at = |i: usize, j: usize| -> Option<f64> {
        floors
            .iter()
            .zip(&masks)
            .filter(|(_, m)| m.as_ref().is_some_and(|m| m.contains(i, j)))
            .map(|(f, _)| f.z)
            .reduce(f64::min)
    };
    let area = |n: usize| n as f64 * c * c;
    let mut out = FieldCheck {
        deviations: Vec::new(),
        uncut_mm2: vec![0.0; floors.len()],
        cell_mm: c,
    };
    for (k, (f, mask)) in floors.iter().zip(&masks).enumerate() {
        let Some(mask) = mask else { continue };
        let walls = loops_of(f);
        let reach = ReachMap::new(&mask.ras, &walls, f.tool_radius.max(0.0));
        let limit = f.tool_radius - 2.0 * c;
        let (mut below, mut uncut) = (Worst::default(), Worst::default());
        for (i, j) in mask.cells() {
            let Some(h) = field.height(i, j) else {
                continue;
            };
            let p = field.centre(i, j);
            let want = floor_at(i, j).unwrap_or(f.z);
            if h < want - ztol {
                // Counted once, by the region whose floor it is.
                if (want - f.z).abs() <= 1e-12 && !near_wall(p) {
                    below.add(want - h, p, h);
                }
            } else if h > f.z + ztol && want >= f.z - 1e-12 {
                let d = reach.distance(mask.ras.centre(i - mask.i0, j - mask.j0));
                if d == 0.0 || d <= limit {
                    uncut.add(h - f.z, p, h);
                }
            }
        }
        if let Some(at) = below.at {
            out.deviations.push(Deviation::BelowFloor {
                floor: k,
                area_mm2: area(below.cells),
                depth_mm: below.amount,
                at,
            });
        }
        out.uncut_mm2[k] = area(uncut.cells);
        let allowed = opts.uncut_area.unwrap_or_else(|| {
            super::UNCUT_AREA_TOLERANCE
                * crate::toolpath::tolerance_scale(2.0 * f.tool_radius).powi(2)
        });
        if let Some(at) = uncut.at.filter(|_| area(uncut.cells) > allowed) {
            out.deviations.push(Deviation::Uncut {
                floor: k,
                area_mm2: area(uncut.cells),
                height_mm: uncut.amount,
                at,
            });
        }
    }
    if let Some(p) = part {
        let loops: Vec<&Polyline<f64>> = std::iter::once(p.outline)
            .chain(p.windows)
            .map(Outline::polyline)
            .collect();
        if let Some(mask) = Mask::new(field, &loops, p.outline.bounds()) {
            let mut cut = Worst::default();
            for (i, j) in mask.cells() {
                let Some(h) = field.height(i, j) else {
                    continue;
                };
                if h < p.top_z - ztol && floor_at(i, j).is_none() {
                    let q = field.centre(i, j);
                    if !near_wall(q) {
                        cut.add(p.top_z - h, q, h);
                    }
                }
            }
            if let Some(at) = cut.at {
                out.deviations.insert(
                    0,
                    Deviation::CutIntoPart {
                        area_mm2: area(cut.cells),
                        depth_mm: cut.amount,
                        at,
                    },
                );
            }
        }
    }
    out
}
