//! A height field (Z-map) of a block of stock, cut by whole toolpaths one after another.
//!
//! The block is a rectangle in XY between a bottom and a top z. The field keeps, per square
//! cell of side `c`, the height of the material's top at the cell's centre: cell `(i, j)`
//! covers `[x₀ + i·c, x₀ + (i+1)·c) × [y₀ + j·c, y₀ + (j+1)·c)` from the block's lower-left
//! corner `(x₀, y₀)`, and the field covers the block rounded up to whole cells. A fresh
//! field is the block's top everywhere; nothing is ever added, only cut.
//!
//! **The cut.** Every tool is a cylinder of radius `r` standing on its tip (a flat end mill;
//! a drill is taken flat at its tip, so a blind hole's floor is the tip's depth). A tool at
//! `(x, y, z)` lowers every cell whose centre lies within `r` of `(x, y)` to `min(h, z)`.
//! Along a straight move from `a` to `b` (a line or a rapid, tip z linear in the travel),
//! the tool axis passes within `r` of a cell centre `p` for the travel interval
//! `t ∈ [t_c − w, t_c + w] ∩ [0, L]` (`t_c` the projection of `p` on the move, `w =
//! √(r² − s²)`, `s` its distance across the move), and since z is linear in `t` the lowest
//! tip over that interval is at one of its two ends: the cell gets exactly that height, with
//! no samples and no scallops between samples. The cells visited are those of each row
//! within `r` of the segment (the capsule's interval on the row). An XY arc (a helix, its z
//! changing, or an arc at one z) is swept whole, the same way in its angle: the axis on the
//! circle of radius `R` about the centre passes within `r` of a cell at distance `ρ` and
//! angle `φ` from it for the angles `|θ − φ| ≤ arccos((R² + ρ² − r²) / (2Rρ))` (modulo full
//! turns), z is linear in the angle turned, and the cell gets the tip at the end of those
//! intervals that lies lowest (an arc whose end is off its start circle by the program's
//! rounding is taken on the mean circle, the tool widened by half the difference). At one z
//! the test needs no angle: a cell whose direction lies in the arc's sector is `|ρ − R|` from
//! the arc, any other is nearest one of its ends. Only the cells of the annulus `|ρ − R| ≤ r`
//! are read, so an arc costs its band whatever its radius. Arcs in the other planes (and
//! arcs of a radius within [`ARC_SAGITTA`]) are swept as chords of at most [`ARC_SAGITTA`]
//! sagitta, each a straight move whose radius is widened by its sagitta, so that it holds the
//! arc's own sweep: along such arcs the field cuts at most that much wider than the tool did
//! (their chords' z linear in their travel).
//!
//! A move that starts where the previous one ended, at the same or a higher z, and does not
//! descend leaves the cells within the previous stamp's radius of its start alone: they were
//! lowered to the previous end's z or below, and the move's lowest tip over them is its start
//! z. So a chain of short moves costs the area it sweeps, `2r` per unit of travel, not a disc
//! per move. Going down, the cells within `r` of the move's end get the end's z outright
//! (their interval reaches the end), and a move wholly at or above the block's top cuts
//! nothing.
//!
//! Nothing lies below the block's bottom: a through cut leaves the cells at the bottom.
//!
//! **Per operation** ([`OperationCut`]): the volume and the area the operation lowered, the
//! **rapids through material** (a rapid that lowers some cell by more than the z tolerance;
//! a vertical retract never does: it sweeps the column the tool stands in), and the
//! **plunges**: feed moves steeper than 45° going down (beyond the program's rounding,
//! [`PLUNGE_SLOPE_SLACK`]) that find material above their end
//! within `r − rim` of their end (`rim = c/√2 +` [`super::GOUGE_RESOLUTION`]: a cell stands
//! for its centre, and the program is written to 3 decimals). A flat end mill does not cut
//! at its centre; a drill ([`Cutter::Drill`]) is made to plunge, and its plunges are not
//! counted.
//!
//! **Resolution.** Heights are `f32`: at a height of up to 1000 mm in magnitude they hold
//! the z written to within 10⁻⁴ mm, below the z tolerance ([`DEFAULT_Z_TOLERANCE`], the
//! program's rounding) every comparison allows. Laterally a cell stands for its centre: an
//! edge is resolved to `c/√2`. The default cell is the 2-D simulation's
//! ([`super::DEFAULT_CELL`], 0.05 mm, scaled with the smallest tool above 12.7 mm), enlarged
//! when the block would need more than [`FieldOptions::max_cells`] cells (16 M, 64 MB: a
//! 400 × 300 mm block gets cells of 0.087 mm).

mod arc;
mod deepest_first;
mod pieces;

use super::problem::Problem;
use crate::error::InputError;
use crate::geom::{Aabb, Point, Point3};
use crate::toolpath::{MoveKind, Toolpath, tolerance_scale};
use deepest_first::{Tiles, tile_end};
use pieces::{Piece, push_pieces};
use std::fmt;

/// The largest sagitta of the chords an arc outside the XY plane is swept as, mm; each
/// chord's sweep is widened by its own sagitta (at most this), so the field holds the arc's
/// sweep. XY arcs are swept whole (module docs).
pub const ARC_SAGITTA: f64 = 1e-3;

/// The default z tolerance, mm: a cell lowered by less than this is not counted as cut
/// (the program's rounding: coordinates written to 3 decimals).
pub const DEFAULT_Z_TOLERANCE: f64 = 1e-3;

/// How much more a move may fall than it runs across before it is steeper than 45°, mm: a
/// written program's ends are each within half its last decimal (0.5 µm) of the planned
/// ones, so a planned 45° move (or a shallower one a few µm long, a ramp's piece) may read
/// up to `2·0.5 µm` deeper and `2·0.5·√2 µm` ([`super::GOUGE_RESOLUTION`]) shorter.
pub const PLUNGE_SLOPE_SLACK: f64 = 1e-3 + super::GOUGE_RESOLUTION;

/// The most cells a field has by default (64 MB of `f32` heights).
pub const DEFAULT_FIELD_MAX_CELLS: usize = 16_000_000;

/// How the field is laid out. Built from [`Default`] with the `with_*` methods.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct FieldOptions {
    /// Cell side, mm (`None`: [`super::DEFAULT_CELL`] scaled with
    /// [`FieldOptions::tool_diameter`], and at most an eighth of its radius); enlarged when
    /// the block would need more than `max_cells` cells.
    pub cell: Option<f64>,
    /// The smallest tool's diameter, mm, for the default cell (`None`: tools up to 12.7 mm).
    pub tool_diameter: Option<f64>,
    /// Most cells in the field.
    pub max_cells: usize,
}

impl Default for FieldOptions {
    fn default() -> Self {
        FieldOptions {
            cell: None,
            tool_diameter: None,
            max_cells: DEFAULT_FIELD_MAX_CELLS,
        }
    }
}

option_builders! {
    FieldOptions;
    /// Sets [`FieldOptions::max_cells`].
    with_max_cells => max_cells: usize;
}

impl FieldOptions {
    /// Sets [`FieldOptions::cell`], mm.
    #[must_use]
    pub fn with_cell(mut self, cell: f64) -> Self {
        self.cell = Some(cell);
        self
    }

    /// Sets [`FieldOptions::tool_diameter`], mm.
    #[must_use]
    pub fn with_tool_diameter(mut self, diameter: f64) -> Self {
        self.tool_diameter = Some(diameter);
        self
    }
}

/// What cuts: how its plunges are judged.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Cutter {
    /// A flat end mill: it does not cut at its centre, so a steep feed down into material is
    /// a plunge.
    #[default]
    EndMill,
    /// A drill (canned cycles): made to plunge; its point is taken flat at the tip.
    Drill,
}

/// How one operation is cut. Built from [`Default`] with the `with_*` methods.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct CutOptions {
    /// The kind of tool.
    pub cutter: Cutter,
    /// A cell lowered by less than this (mm) is not counted as cut: not in the area
    /// removed, not a rapid through material, not a plunge.
    pub z_tolerance: f64,
}

impl Default for CutOptions {
    fn default() -> Self {
        CutOptions {
            cutter: Cutter::EndMill,
            z_tolerance: DEFAULT_Z_TOLERANCE,
        }
    }
}

option_builders! {
    CutOptions;
    /// Sets [`CutOptions::cutter`].
    with_cutter => cutter: Cutter;
    /// Sets [`CutOptions::z_tolerance`], mm.
    with_z_tolerance => z_tolerance: f64;
}

/// What one operation did to the field.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct OperationCut {
    /// Volume of material removed, mm³.
    pub removed_volume_mm3: f64,
    /// Area (in XY) of the cells lowered by more than the z tolerance, mm².
    pub removed_area_mm2: f64,
    /// Indices (in the toolpath) of the rapid moves that cut material.
    pub rapids_through_material: Vec<usize>,
    /// Indices of the feed moves that plunge into material (never for a drill).
    pub plunges: Vec<usize>,
}

impl OperationCut {
    /// The problems found: rapids through material and plunges; empty when there are none.
    pub fn problems(&self) -> Vec<Problem> {
        let mut out = Vec::new();
        if !self.rapids_through_material.is_empty() {
            out.push(Problem::RapidsThroughMaterial(
                self.rapids_through_material.len(),
            ));
        }
        if !self.plunges.is_empty() {
            out.push(Problem::Plunges(self.plunges.len()));
        }
        out
    }
}

impl fmt::Display for OperationCut {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "removed {:.3} mm³ over {:.3} mm²; {} rapid moves through material; {} plunges",
            self.removed_volume_mm3,
            self.removed_area_mm2,
            self.rapids_through_material.len(),
            self.plunges.len()
        )
    }
}

/// The material of a block of stock as the top height over every cell (module docs).
#[derive(Debug, Clone)]
pub struct HeightField {
    origin: Point,
    cell: f64,
    nx: usize,
    ny: usize,
    bottom: f64,
    top: f64,
    h: Vec<f32>,
}

/// The last disc stamped: its centre, tip z and radius.
#[derive(Debug, Clone, Copy)]
struct Stamp {
    at: Point,
    z: f64,
    r: f64,
}

/// What an operation's sweeps add up: the cells lowered by more than `ztol` (a bit each;
/// none kept when `touched` is empty) and the heights removed, mm (times the cell area: the
/// volume).
#[derive(Debug)]
struct Tally {
    ztol: f64,
    touched: Vec<u64>,
    volume: f64,
    /// Set when a cell's stored height changes.
    changed: bool,
}

/// What one sweep found: the largest lowering of a cell and what it added up to.
#[derive(Debug, Clone, Copy, Default)]
struct Swept {
    max_cut: f64,
}

impl HeightField {
    /// A block of stock over `block` (XY) from `bottom` to `top` (z, mm), every cell at the
    /// top. `block` must have a positive finite width and height, `bottom < top` finite, and a
    /// cell asked for a positive finite length.
    pub fn new(
        block: Aabb,
        bottom: f64,
        top: f64,
        opts: &FieldOptions,
    ) -> Result<Self, InputError> {
        let corners = [block.min.x, block.min.y, block.max.x, block.max.y];
        if corners.iter().any(|v| !v.is_finite()) || block.width() <= 0.0 || block.height() <= 0.0 {
            return Err(InputError::new(
                "stock block",
                format!(
                    "({}, {}) to ({}, {})",
                    block.min.x, block.min.y, block.max.x, block.max.y
                ),
            )
            .at("height field")
            .expected("a rectangle of positive finite width and height, mm"));
        }
        if !(bottom.is_finite() && top.is_finite() && bottom < top) {
            return Err(
                InputError::new("stock bottom and top", format!("{bottom} and {top}"))
                    .at("height field")
                    .expected("finite z values, the bottom below the top, mm"),
            );
        }
        let asked = match (opts.cell, opts.tool_diameter) {
            (Some(c), _) => crate::error::require_positive("cell", c, "height field")?,
            (None, d) => {
                let d = d.filter(|d| d.is_finite() && *d > 0.0);
                let scaled = super::DEFAULT_CELL * d.map_or(1.0, tolerance_scale);
                d.map_or(scaled, |d| scaled.min(super::MAX_CELL_RADII * 0.5 * d))
            }
        };
        let max_cells = opts.max_cells.max(1) as f64;
        let mut cell = asked.max((block.width() * block.height() / max_cells).sqrt());
        let dims = |c: f64| {
            (
                ((block.width() / c).ceil() as usize).max(1),
                ((block.height() / c).ceil() as usize).max(1),
            )
        };
        while {
            let (nx, ny) = dims(cell);
            (nx as f64) * (ny as f64) > max_cells
        } {
            cell *= 1.0 + 1e-3;
        }
        let (nx, ny) = dims(cell);
        Ok(HeightField {
            origin: block.min,
            cell,
            nx,
            ny,
            bottom,
            top,
            h: vec![top as f32; nx * ny],
        })
    }

    /// Cell side, mm.
    pub fn cell(&self) -> f64 {
        self.cell
    }

    /// Cells along x and along y.
    pub fn dims(&self) -> (usize, usize) {
        (self.nx, self.ny)
    }

    /// The stock's bottom z, mm.
    pub fn bottom(&self) -> f64 {
        self.bottom
    }

    /// The stock's top z, mm.
    pub fn top(&self) -> f64 {
        self.top
    }

    /// The rectangle the cells cover (the block rounded up to whole cells).
    pub fn bounds(&self) -> Aabb {
        Aabb {
            min: self.origin,
            max: Point::new(
                self.origin.x + self.nx as f64 * self.cell,
                self.origin.y + self.ny as f64 * self.cell,
            ),
        }
    }

    /// Centre of cell `(i, j)`.
    pub fn centre(&self, i: usize, j: usize) -> Point {
        Point::new(
            self.origin.x + (i as f64 + 0.5) * self.cell,
            self.origin.y + (j as f64 + 0.5) * self.cell,
        )
    }

    /// Height of the material at cell `(i, j)`, mm (`None` off the field).
    pub fn height(&self, i: usize, j: usize) -> Option<f64> {
        (i < self.nx && j < self.ny).then(|| f64::from(self.h[j * self.nx + i]))
    }

    /// The cell whose square holds `p`, if on the field.
    pub fn cell_at(&self, p: Point) -> Option<(usize, usize)> {
        let fi = ((p.x - self.origin.x) / self.cell).floor();
        let fj = ((p.y - self.origin.y) / self.cell).floor();
        (fi >= 0.0 && fj >= 0.0 && (fi as usize) < self.nx && (fj as usize) < self.ny)
            .then_some((fi as usize, fj as usize))
    }

    /// Height of the material at the cell holding `p`, mm (`None` off the field).
    pub fn height_at(&self, p: Point) -> Option<f64> {
        self.cell_at(p).and_then(|(i, j)| self.height(i, j))
    }

    /// Volume of material left above the bottom, mm³.
    pub fn volume(&self) -> f64 {
        let b = self.bottom;
        self.h
            .iter()
            .map(|&h| (f64::from(h) - b).max(0.0))
            .sum::<f64>()
            * self.cell
            * self.cell
    }

    /// Heights row by row (`j·nx + i`), mm.
    pub(crate) fn heights(&self) -> &[f32] {
        &self.h
    }

    /// Cuts `tp` (a flat end mill of its tool's diameter) into the field
    /// ([`HeightField::cut_with`] with the default options).
    pub fn cut(&mut self, tp: &Toolpath) -> OperationCut {
        self.cut_with(tp, &CutOptions::default())
    }

    /// Cuts `tp` into the field, every move in order, and reports what the operation did.
    pub fn cut_with(&mut self, tp: &Toolpath, opts: &CutOptions) -> OperationCut {
        let r = tp.tool.radius().max(0.0);
        let ztol = opts.z_tolerance.max(0.0);
        let mut tally = Tally {
            ztol,
            touched: vec![0u64; (self.nx * self.ny).div_ceil(64)],
            volume: 0.0,
            changed: false,
        };
        let mut out = OperationCut::default();
        let rim = self.cell * std::f64::consts::FRAC_1_SQRT_2 + super::GOUGE_RESOLUTION;
        // Where the tool stands before the first move is not a cut (how it got there is not
        // in this program).
        let mut last: Option<Stamp> = None;
        let mut pieces = Vec::new();
        for (k, (from, m)) in tp.segments().enumerate() {
            let feed = match m.kind {
                MoveKind::Dwell { .. } => continue,
                MoveKind::Rapid | MoveKind::Line => m.is_feed(),
                MoveKind::Arc { .. } => true,
            };
            if feed
                && opts.cutter == Cutter::EndMill
                && self.plunges(from, m.to, r - rim, ztol, m.length_from(from))
            {
                out.plunges.push(k);
            }
            pieces.clear();
            push_pieces(from, m, r, &mut last, &mut pieces);
            for piece in &pieces {
                let s = self.sweep_piece(piece, &mut tally, None);
                if matches!(m.kind, MoveKind::Rapid) && s.max_cut > ztol {
                    out.rapids_through_material.push(k);
                }
            }
        }
        let cell_area = self.cell * self.cell;
        out.removed_volume_mm3 = tally.volume * cell_area;
        out.removed_area_mm2 = tally
            .touched
            .iter()
            .map(|w| w.count_ones() as f64)
            .sum::<f64>()
            * cell_area;
        out
    }

    /// True when a feed from `from` to `to` is steeper than 45° going down and finds material
    /// above its end (by more than `ztol`) within `reach` of its end.
    fn plunges(&self, from: Point3, to: Point3, reach: f64, ztol: f64, len: f64) -> bool {
        let dz = from.z - to.z;
        let xy = (len * len - dz * dz).max(0.0).sqrt();
        if dz <= xy + PLUNGE_SLOPE_SLACK || reach <= 0.0 {
            return false;
        }
        let c = to.xy();
        let limit = to.z.max(self.bottom) + ztol;
        let mut found = false;
        self.for_rows(c.y - reach, c.y + reach, |j, y| {
            if found {
                return;
            }
            let w2 = reach * reach - (y - c.y) * (y - c.y);
            if w2 < 0.0 {
                return;
            }
            let w = w2.sqrt();
            if let Some((i0, i1)) = self.columns(c.x - w, c.x + w) {
                let row = &self.h[j * self.nx..(j + 1) * self.nx];
                found = row[i0..=i1].iter().any(|&h| f64::from(h) > limit);
            }
        });
        found
    }

    /// Calls `f(j, y)` for every row whose centre `y` lies in `[y0, y1]`.
    fn for_rows(&self, y0: f64, y1: f64, mut f: impl FnMut(usize, f64)) {
        let j0 = ((y0 - self.origin.y) / self.cell - 0.5).ceil().max(0.0);
        let j1 = ((y1 - self.origin.y) / self.cell - 0.5).floor();
        if j1 < 0.0 || !j0.is_finite() || !j1.is_finite() {
            return;
        }
        let j1 = (j1 as usize).min(self.ny - 1);
        for j in j0 as usize..=j1 {
            f(j, self.origin.y + (j as f64 + 0.5) * self.cell);
        }
    }

    /// The columns `i0..=i1` whose centres lie in `[x0, x1]`, if any.
    fn columns(&self, x0: f64, x1: f64) -> Option<(usize, usize)> {
        let i0 = ((x0 - self.origin.x) / self.cell - 0.5).ceil().max(0.0);
        let i1 = ((x1 - self.origin.x) / self.cell - 0.5).floor();
        if i1 < 0.0 || !i0.is_finite() || !i1.is_finite() {
            return None;
        }
        let (i0, i1) = (i0 as usize, (i1 as usize).min(self.nx - 1));
        (i0 <= i1).then_some((i0, i1))
    }

    /// Lowers cell `k` to `z` (not below the block's bottom: there is no material to cut
    /// there), counting it in `tally`; returns how much it lowered it, mm (0 within the z
    /// tolerance).
    fn lower(&mut self, k: usize, z: f64, tally: &mut Tally) -> f64 {
        let z = z.max(self.bottom);
        let old = f64::from(self.h[k]);
        if old <= z {
            return 0.0;
        }
        let cut = old - z;
        tally.volume += cut;
        let new = z as f32;
        tally.changed |= new.to_bits() != self.h[k].to_bits();
        self.h[k] = new;
        if cut <= tally.ztol {
            return 0.0;
        }
        if let Some(w) = tally.touched.get_mut(k / 64) {
            *w |= 1 << (k % 64);
        }
        cut
    }

    /// Sweeps one piece of a move; `tiles`, when given, skips the tiles no lower than the
    /// piece's lowest tip and records the tiles it lowers.
    fn sweep_piece(
        &mut self,
        piece: &Piece,
        tally: &mut Tally,
        tiles: Option<&mut Tiles>,
    ) -> Swept {
        match *piece {
            Piece::Line { a, b, r, last } => self.sweep(a, b, r, last, tally, tiles),
            Piece::Arc {
                from,
                to,
                centre,
                sweep,
                r,
            } => {
                self.sweep_arc((from, to), centre, sweep, r, tally, tiles);
                Swept::default()
            }
        }
    }

    /// Sweeps the tool of radius `r` from `a` to `b` (module docs); `last` is the disc the
    /// previous move stamped, whose cells a non-descending move from its centre leaves alone.
    fn sweep(
        &mut self,
        a: Point3,
        b: Point3,
        r: f64,
        last: Option<Stamp>,
        tally: &mut Tally,
        mut tiles: Option<&mut Tiles>,
    ) -> Swept {
        let (pa, pb) = (a.xy(), b.xy());
        let d = pb - pa;
        let len = d.length();
        let u = if len > 1e-12 { d / len } else { d * 0.0 };
        let dz = b.z - a.z;
        let flat = dz.abs() <= 1e-12;
        let skip = last.filter(|s| s.at.distance(pa) <= 1e-9 && s.z <= a.z + 1e-12 && dz >= 0.0);
        let mut swept = Swept::default();
        // Nothing stands above the block's top.
        if a.z.min(b.z) >= self.top {
            return swept;
        }
        let nx = self.nx;
        let (cell, origin) = (self.cell, self.origin);
        // No tip this sweep computes, stored as f32, lies below this: a tile whose highest
        // cell is at or below it keeps every height (its z's round to no lower one).
        let floor = ((a.z.min(b.z) - 1e-6).max(self.bottom)) as f32;
        // Deepest first, a cell at or below it is left as it is without its tip (the same
        // bound as a tile's, cell by cell).
        let keep = tiles.as_ref().map(|_| floor);
        let (ylo, yhi) = (pa.y.min(pb.y) - r, pa.y.max(pb.y) + r);
        let mut rows = Vec::new();
        self.for_rows(ylo, yhi, |j, y| rows.push((j, y)));
        for (j, y) in rows {
            let Some((lo, hi)) = capsule_row(pa, pb, u, len, r, y) else {
                continue;
            };
            let Some((i0, i1)) = self.columns(lo, hi) else {
                continue;
            };
            // The cells of the last stamp on this row, left alone.
            let hole = skip.and_then(|s| {
                let w2 = s.r * s.r - (y - s.at.y) * (y - s.at.y);
                (w2 >= 0.0)
                    .then(|| self.columns(s.at.x - w2.sqrt(), s.at.x + w2.sqrt()))
                    .flatten()
            });
            let ranges = match hole {
                Some((h0, h1)) => [(i0, h0.min(i1 + 1)), ((h1 + 1).max(i0), i1 + 1)],
                None => [(i0, i1 + 1), (0, 0)],
            };
            // Going down, the cells within r of the end get its z: their travel interval
            // reaches the end (`t_c + w ≥ L`).
            let end_disc = if dz < 0.0 {
                let w2 = r * r - (y - pb.y) * (y - pb.y);
                (w2 >= 0.0)
                    .then(|| self.columns(pb.x - w2.sqrt(), pb.x + w2.sqrt()))
                    .flatten()
            } else {
                None
            };
            let ay = y - pa.y;
            for (s0, s1) in ranges {
                let mut i0 = s0;
                while i0 < s1 {
                    let i1 = if tiles.is_some() {
                        tile_end(i0, s1)
                    } else {
                        s1
                    };
                    if let Some(t) = tiles.as_deref_mut()
                        && t.at_or_below(self, i0, j, floor)
                    {
                        i0 = i1;
                        continue;
                    }
                    tally.changed = false;
                    for i in i0..i1 {
                        if keep.is_some_and(|f| self.h[j * nx + i] <= f) {
                            continue;
                        }
                        let z = if flat {
                            a.z
                        } else if len <= 1e-12 {
                            a.z.min(b.z)
                        } else if end_disc.is_some_and(|(e0, e1)| (e0..=e1).contains(&i)) {
                            b.z
                        } else {
                            let x = origin.x + (i as f64 + 0.5) * cell;
                            let (wx, wy) = (x - pa.x, ay);
                            let tc = wx * u.x + wy * u.y;
                            let s = wx * u.y - wy * u.x;
                            let w = (r * r - s * s).max(0.0).sqrt();
                            let t0 = (tc - w).clamp(0.0, len);
                            let t1 = (tc + w).clamp(0.0, len);
                            let t = if dz < 0.0 { t1 } else { t0 };
                            a.z + dz * t / len
                        };
                        let cut = self.lower(j * nx + i, z, tally);
                        swept.max_cut = swept.max_cut.max(cut);
                    }
                    if tally.changed
                        && let Some(t) = tiles.as_deref_mut()
                    {
                        t.mark(i0, j);
                    }
                    i0 = i1;
                }
            }
        }
        swept
    }
}

/// The x-interval of row `y` within `r` of the segment `a`–`b` (`u` its unit direction,
/// `len` its length): the hull of where the row meets the end discs and the band `0 ≤ t ≤
/// len`, `|s| ≤ r` (the region is convex, so each row meets it in one interval).
fn capsule_row(
    a: Point,
    b: Point,
    u: crate::geom::Vec2,
    len: f64,
    r: f64,
    y: f64,
) -> Option<(f64, f64)> {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for c in [a, b] {
        let w2 = r * r - (y - c.y) * (y - c.y);
        if w2 >= 0.0 {
            let w = w2.sqrt();
            lo = lo.min(c.x - w);
            hi = hi.max(c.x + w);
        }
    }
    if len > 1e-12 {
        // t(x) = u.x·(x − a.x) + u.y·(y − a.y) ∈ [0, len];
        // s(x) = u.y·(x − a.x) − u.x·(y − a.y) ∈ [−r, r].
        let (t0, s0) = (u.y * (y - a.y), -u.x * (y - a.y));
        let mut band = Some((f64::NEG_INFINITY, f64::INFINITY));
        for (k, c0, min, max) in [(u.x, t0, 0.0, len), (u.y, s0, -r, r)] {
            band = band.and_then(|(l, h)| {
                if k.abs() < 1e-12 {
                    (min..=max).contains(&c0).then_some((l, h))
                } else {
                    let (x0, x1) = ((min - c0) / k + a.x, (max - c0) / k + a.x);
                    Some((l.max(x0.min(x1)), h.min(x0.max(x1))))
                }
            });
        }
        if let Some((l, h)) = band.filter(|(l, h)| l <= h) {
            lo = lo.min(l);
            hi = hi.max(h);
        }
    }
    (lo <= hi).then_some((lo, hi))
}

/// How many chords an arc of (start radius, signed sweep) is swept as, and their sagitta (at most
/// [`ARC_SAGITTA`], pieces of at most a quarter turn).
fn arc_pieces(sweep: Option<(f64, f64)>) -> (usize, f64) {
    let Some((r0, sweep)) = sweep else {
        return (1, 0.0);
    };
    let radius = r0.abs();
    let theta = sweep.abs();
    if radius <= ARC_SAGITTA || theta <= 0.0 {
        // Every point of the arc lies within its diameter of its start.
        return (1, 2.0 * radius);
    }
    // r·(1 − cos(φ/2)) ≤ s  ⇔  φ ≤ 2·acos(1 − s/r).
    let max_piece = 2.0 * (1.0 - ARC_SAGITTA / radius).acos();
    let n =
        ((theta / max_piece.min(std::f64::consts::FRAC_PI_2)).ceil() as usize).clamp(1, 10_000_000);
    let phi = theta / n as f64;
    (n, radius * (1.0 - (0.5 * phi).cos()))
}
