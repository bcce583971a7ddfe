//! DXF entities to pieces (vertices with bulges) in mm, blocks expanded.
//!
//! Each entity is read in its own coordinates and mapped to the drawing's by the current
//! [`Affine`]: the drawing unit's scale to mm, times every enclosing INSERT's
//! `translate(insertion) · rotate(50) · translate(column·44, row·45) · scale(41, 42) ·
//! translate(−block base)`, times the mirror `x → −x` of an entity whose extrusion direction
//! is `(0, 0, −1)` (its object coordinate system seen from below; any other tilted extrusion
//! is not a plan view and is skipped). LINE, SPLINE and ELLIPSE are in world coordinates.
//!
//! * LINE; ARC (split in two halves so no bulge exceeds 1); CIRCLE (two half circles);
//!   LWPOLYLINE and 2D POLYLINE/VERTEX with bulges (3D polylines projected on XY; meshes
//!   skipped; spline-frame control vertices skipped, the fitted vertices kept).
//! * ELLIPSE, full or partial: `c + M·cos t + r·(ẑ × M)·sin t`, flattened with equal
//!   parameter steps `Δ` such that `a·(1 − cos(Δ/2)) ≤ tolerance` (`a = |M|`: the ellipse is
//!   the image of the circle of radius `a` under a map that shrinks, so chord deviations
//!   shrink too).
//! * SPLINE ([`super::spline`]).
//! * HATCH boundary paths: polyline paths (with bulges) and edge paths (lines, circular and
//!   elliptic arcs, splines); a clockwise edge arc (flag 73 = 0) stores its angles mirrored,
//!   from `−start` to `−end` clockwise.
//! * INSERT of a block, nested up to 32 deep, arrays (70 × 71) included; block entities on
//!   layer `0` take the INSERT's layer.
//!
//! Everything else (TEXT, MTEXT, DIMENSION, POINT, 3DFACE, …) is counted and skipped.

use super::codes::Record;
use super::spline::{self, SplineData};
use crate::error::InputError;
use crate::geom::Point;
use crate::io::affine::{Affine, Piece, transform_piece};
use crate::io::drawing::{Drawing, ReadOptions};
use crate::io::join::join;
use std::collections::HashMap;
use std::f64::consts::{PI, TAU};

/// A block definition.
#[derive(Debug, Clone, Default)]
pub struct Block {
    /// Base point (groups 10/20).
    pub base: Point,
    /// Its entities.
    pub records: Vec<Record>,
}

/// The most entities a drawing may expand to (blocks inserted into blocks multiply).
pub const MAX_EXPANDED: usize = 1_000_000;
const MAX_DEPTH: usize = 32;

/// Reads entities into pieces (mm) and counts into the drawing.
#[derive(Debug)]
pub struct Reader<'a> {
    /// Blocks by upper-case name.
    pub blocks: &'a HashMap<String, Block>,
    /// Options.
    pub opts: &'a ReadOptions,
    /// The file's name.
    pub origin: &'a str,
    /// Pieces read.
    pub pieces: Vec<Piece>,
    /// Counts and notes.
    pub drawing: &'a mut Drawing,
    expanded: usize,
}

/// Where entities are being read: the map to mm, the INSERT's layer, the nesting depth.
#[derive(Debug, Clone)]
pub struct Ctx {
    /// Entity coordinates to mm.
    pub t: Affine,
    /// Layer inherited by entities on layer `0`.
    pub layer: Option<String>,
    /// INSERT nesting depth.
    pub depth: usize,
}

fn angle_point(c: Point, r: f64, a: f64) -> Point {
    Point::new(c.x + r * a.cos(), c.y + r * a.sin())
}

/// The arc of centre `c`, radius `r`, from angle `a0` sweeping `sweep` (signed, radians), as a
/// piece of two halves.
fn arc_piece(c: Point, r: f64, a0: f64, sweep: f64) -> Piece {
    let h = 0.5 * sweep;
    let b = (h / 4.0).tan();
    vec![
        (angle_point(c, r, a0), b),
        (angle_point(c, r, a0 + h), b),
        (angle_point(c, r, a0 + sweep), 0.0),
    ]
}

/// Counter-clockwise sweep from `a0` to `a1` (radians), a full turn when they coincide.
fn ccw_sweep(a0: f64, a1: f64) -> f64 {
    let s = (a1 - a0).rem_euclid(TAU);
    if s <= 1e-12 { TAU } else { s }
}

/// Points of the ellipse `c + m·cos t + n·sin t` for t from `t0` to `t0 + sweep` within `tol`.
fn ellipse_points(
    c: Point,
    m: (f64, f64),
    n: (f64, f64),
    t0: f64,
    sweep: f64,
    tol: f64,
) -> Vec<Point> {
    let a = m.0.hypot(m.1).max(n.0.hypot(n.1));
    let step = if tol >= a {
        PI
    } else {
        2.0 * (1.0 - tol / a).acos()
    };
    let k = ((sweep.abs() / step).ceil() as usize).clamp(4, 100_000);
    (0..=k)
        .map(|i| {
            let t = t0 + sweep * i as f64 / k as f64;
            let (s, co) = t.sin_cos();
            Point::new(c.x + m.0 * co + n.0 * s, c.y + m.1 * co + n.1 * s)
        })
        .collect()
}

impl<'a> Reader<'a> {
    /// A reader over `blocks`.
    pub fn new(
        blocks: &'a HashMap<String, Block>,
        opts: &'a ReadOptions,
        origin: &'a str,
        drawing: &'a mut Drawing,
    ) -> Self {
        Reader {
            blocks,
            opts,
            origin,
            pieces: Vec::new(),
            drawing,
            expanded: 0,
        }
    }

    fn push(&mut self, local: Piece, t: &Affine) {
        self.pieces
            .push(transform_piece(local, t, self.opts.tolerance));
    }

    /// Reads `recs` under `ctx`.
    pub fn entities(&mut self, recs: &[Record], ctx: &Ctx) -> Result<(), InputError> {
        let mut i = 0;
        while i < recs.len() {
            let (rec, index) = (&recs[i], i);
            i += 1;
            self.expanded += 1;
            if self.expanded > MAX_EXPANDED {
                return Err(
                    InputError::new("DXF entities", format!("more than {MAX_EXPANDED}"))
                        .at(self.origin)
                        .expected("a drawing whose blocks expand to at most a million entities"),
                );
            }
            let own = rec.text(8);
            let layer = match (&ctx.layer, own) {
                (Some(l), "0") => l.clone(),
                (_, "") => "0".to_owned(),
                _ => own.to_owned(),
            };
            // A POLYLINE's VERTEX records (and an INSERT's ATTRIBs) follow it up to SEQEND.
            let mut tail: &[Record] = &[];
            let has_tail = rec.kind == "POLYLINE" || (rec.kind == "INSERT" && rec.int(66, 0) == 1);
            if has_tail {
                let start = i;
                while i < recs.len() && recs[i].kind != "SEQEND" && recs[i].kind != rec.kind {
                    i += 1;
                }
                tail = &recs[start..i];
                if i < recs.len() && recs[i].kind == "SEQEND" {
                    i += 1;
                }
            }
            if matches!(rec.kind.as_str(), "SEQEND" | "VERTEX" | "ENDBLK" | "BLOCK") {
                continue;
            }
            if rec.kind != "INSERT" {
                self.drawing.layers.insert(layer.clone());
                if let Some(want) = &self.opts.layer
                    && !want.eq_ignore_ascii_case(&layer)
                {
                    self.drawing.skip(&rec.kind, "on another layer");
                    continue;
                }
            }
            let at = match ctx.depth {
                0 => format!(
                    "{}, entity {index} ({} on layer {layer})",
                    self.origin, rec.kind
                ),
                d => format!(
                    "{}, block entity {index} ({} on layer {layer}, insert depth {d})",
                    self.origin, rec.kind
                ),
            };
            let outcome = self.entity(rec, tail, ctx, &layer, &at)?;
            match outcome {
                Ok(()) => self.drawing.count(&rec.kind),
                Err(why) => self.drawing.skip(&rec.kind, why),
            }
        }
        Ok(())
    }

    /// One entity; `Ok(Err(why))` when it is skipped.
    fn entity(
        &mut self,
        rec: &Record,
        tail: &[Record],
        ctx: &Ctx,
        layer: &str,
        at: &str,
    ) -> Result<Result<(), &'static str>, InputError> {
        let ocs = |rec: &Record| -> Option<Affine> {
            rec.extrusion().map(|mirror| {
                if mirror {
                    ctx.t.after(Affine::scale(-1.0, 1.0))
                } else {
                    ctx.t
                }
            })
        };
        let local_tol = self.opts.tolerance / ctx.t.max_stretch();
        match rec.kind.as_str() {
            "LINE" => {
                let piece = vec![(rec.point(10), 0.0), (rec.point(11), 0.0)];
                self.push(piece, &ctx.t);
            }
            "ARC" | "CIRCLE" => {
                let Some(t) = ocs(rec) else {
                    return Ok(Err("not in the XY plane"));
                };
                let (c, r) = (rec.point(10), rec.real(40, 0.0));
                if !(r > 0.0 && r.is_finite()) {
                    return Ok(Err("zero or invalid radius"));
                }
                let piece = if rec.kind == "CIRCLE" {
                    arc_piece(c, r, 0.0, TAU)
                } else {
                    let a0 = rec.real(50, 0.0).to_radians();
                    arc_piece(c, r, a0, ccw_sweep(a0, rec.real(51, 360.0).to_radians()))
                };
                self.push(piece, &t);
            }
            "LWPOLYLINE" => {
                let Some(t) = ocs(rec) else {
                    return Ok(Err("not in the XY plane"));
                };
                let mut v: Piece = Vec::new();
                for g in &rec.groups {
                    match g.code {
                        10 => v.push((Point::new(g.real(), 0.0), 0.0)),
                        20 => {
                            if let Some(last) = v.last_mut() {
                                last.0.y = g.real();
                            }
                        }
                        42 => {
                            if let Some(last) = v.last_mut() {
                                last.1 = g.real();
                            }
                        }
                        _ => {}
                    }
                }
                if rec.int(70, 0) & 1 == 1
                    && let Some(&(p, _)) = v.first()
                {
                    v.push((p, 0.0));
                }
                self.push(v, &t);
            }
            "POLYLINE" => {
                let flags = rec.int(70, 0);
                if flags & (16 | 64) != 0 {
                    return Ok(Err("a 3D mesh"));
                }
                let t = if flags & 8 != 0 {
                    ctx.t // 3D polyline: world coordinates, projected on XY
                } else {
                    match ocs(rec) {
                        Some(t) => t,
                        None => return Ok(Err("not in the XY plane")),
                    }
                };
                let mut v: Piece = tail
                    .iter()
                    .filter(|r| r.kind == "VERTEX" && r.int(70, 0) & (16 | 128) == 0)
                    .map(|r| (r.point(10), r.real(42, 0.0)))
                    .collect();
                if flags & 1 == 1
                    && let Some(&(p, _)) = v.first()
                {
                    v.push((p, 0.0));
                }
                self.push(v, &t);
            }
            "ELLIPSE" => {
                let Some(mirror) = rec.extrusion() else {
                    return Ok(Err("not in the XY plane"));
                };
                let (c, m) = (rec.point(10), rec.point(11));
                let ratio = rec.real(40, 1.0);
                let z = if mirror { -1.0 } else { 1.0 };
                let n = (-z * ratio * m.y, z * ratio * m.x);
                let (t0, t1) = (rec.real(41, 0.0), rec.real(42, TAU));
                if !(ratio > 0.0 && ratio.is_finite() && m.x.hypot(m.y) > 0.0) {
                    return Ok(Err("zero or invalid axes"));
                }
                let pts = ellipse_points(c, (m.x, m.y), n, t0, ccw_sweep(t0, t1), local_tol);
                self.push(pts.into_iter().map(|p| (p, 0.0)).collect(), &ctx.t);
            }
            "SPLINE" => {
                let mut s = SplineData {
                    degree: usize::try_from(rec.int(71, 3)).unwrap_or(0),
                    ..Default::default()
                };
                let mut last: Option<i32> = None;
                for g in &rec.groups {
                    match g.code {
                        40 => s.knots.push(g.real()),
                        41 => s.weights.push(g.real()),
                        10 => s.control.push(Point::new(g.real(), 0.0)),
                        11 => s.fit.push(Point::new(g.real(), 0.0)),
                        20 | 21 => {
                            let list = if g.code == 20 {
                                &mut s.control
                            } else {
                                &mut s.fit
                            };
                            if last == Some(g.code - 10)
                                && let Some(p) = list.last_mut()
                            {
                                p.y = g.real();
                            }
                        }
                        _ => {}
                    }
                    last = Some(g.code);
                }
                let mut pts = spline::flatten(&s, local_tol, at)?;
                if rec.int(70, 0) & 1 == 1
                    && let Some(&p) = pts.first()
                {
                    pts.push(p);
                }
                self.push(pts.into_iter().map(|p| (p, 0.0)).collect(), &ctx.t);
            }
            "HATCH" => {
                let Some(t) = ocs(rec) else {
                    return Ok(Err("not in the XY plane"));
                };
                for path in super::hatch::boundary_paths(rec, local_tol, at)? {
                    let mm: Vec<Piece> = path
                        .into_iter()
                        .map(|p| transform_piece(p, &t, self.opts.tolerance))
                        .collect();
                    let joined = join(mm, self.opts.join_tolerance);
                    for mut lp in joined.closed {
                        let first = lp[0].0;
                        lp.push((first, 0.0));
                        self.pieces.push(lp);
                    }
                    self.pieces.extend(joined.open_pieces);
                }
            }
            "INSERT" => return self.insert(rec, ctx, layer, at),
            "TEXT" | "MTEXT" | "ATTRIB" | "ATTDEF" => return Ok(Err("text")),
            "DIMENSION" | "LEADER" | "MLEADER" | "TOLERANCE" => return Ok(Err("annotation")),
            "POINT" => return Ok(Err("a point")),
            _ => return Ok(Err("not an outline entity")),
        }
        Ok(Ok(()))
    }

    fn insert(
        &mut self,
        rec: &Record,
        ctx: &Ctx,
        layer: &str,
        at: &str,
    ) -> Result<Result<(), &'static str>, InputError> {
        let name = rec.text(2).to_ascii_uppercase();
        let Some(block) = self.blocks.get(&name) else {
            return Ok(Err("its block is missing"));
        };
        let Some(mirror) = rec.extrusion() else {
            return Ok(Err("not in the XY plane"));
        };
        if ctx.depth >= MAX_DEPTH {
            return Err(
                InputError::new("INSERT nesting", format!("deeper than {MAX_DEPTH}"))
                    .at(at.to_owned())
                    .expected("blocks nested at most 32 deep (a block inserting itself?)"),
            );
        }
        let (sx, sy) = (rec.real(41, 1.0), rec.real(42, 1.0));
        let rot = rec.real(50, 0.0).to_radians();
        let (cols, rows) = (rec.int(70, 1).max(1), rec.int(71, 1).max(1));
        let (dc, dr) = (rec.real(44, 0.0), rec.real(45, 0.0));
        let p = rec.point(10);
        let base = if mirror {
            ctx.t.after(Affine::scale(-1.0, 1.0))
        } else {
            ctx.t
        };
        for r in 0..rows {
            for c in 0..cols {
                let local = Affine::translate(p.x, p.y)
                    .after(Affine::rotate(rot))
                    .after(Affine::translate(c as f64 * dc, r as f64 * dr))
                    .after(Affine::scale(sx, sy))
                    .after(Affine::translate(-block.base.x, -block.base.y));
                let t = base.after(local);
                if !t.is_valid() {
                    return Ok(Err("zero or invalid scale"));
                }
                let inner = Ctx {
                    t,
                    layer: Some(layer.to_owned()),
                    depth: ctx.depth + 1,
                };
                let recs = &block.records;
                self.entities(recs, &inner)?;
                if self.expanded > MAX_EXPANDED {
                    break;
                }
            }
        }
        Ok(Ok(()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ellipse_points_within_tolerance() {
        let (a, b) = (10.0, 4.0);
        let pts = ellipse_points(Point::ORIGIN, (a, 0.0), (0.0, b), 0.0, TAU, 0.001);
        for w in pts.windows(2) {
            let m = Point::new(0.5 * (w[0].x + w[1].x), 0.5 * (w[0].y + w[1].y));
            // Implicit form: the mid point is inside, by less than the tolerance along the
            // normal (checked by scaling it out to the ellipse).
            let s = ((m.x / a).powi(2) + (m.y / b).powi(2)).sqrt();
            assert!(s <= 1.0 + 1e-12);
            let on = Point::new(m.x / s, m.y / s);
            assert!(on.distance(m) <= 0.001 + 1e-9, "{}", on.distance(m));
        }
        assert!(pts[0].distance(Point::new(a, 0.0)) < 1e-12);
    }
}
