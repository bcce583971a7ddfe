//! LinuxCNC's blend arcs (`src/emc/tp/blendmath.c`): the arc that replaces a corner between
//! two segments, its radius, speed and how much of each segment it takes.
//!
//! # The rule (`blendComputeParameters`)
//! With `θ` half the angle between the reversed incoming and the outgoing direction (`θ = π/2`
//! for a straight continuation) and `φ = π − 2θ` the deflection:
//! * tolerance `T = min(T₁, T₂, ¼L₁ⁿ, ¼L₂ⁿ)` with `Tᵢ` the segments' `G64 P` (or `¼Lᵢⁿ` where
//!   P is 0 or absent: `G64` alone blends without a tolerance limit) and `Lᵢⁿ` their
//!   programmed lengths (`tcFindBlendTolerance`);
//! * the distance along each segment the tolerance allows, `d_tol = cos θ·T/(1 − sin θ)`;
//! * the lengths available, `L₁ = min(L₁ now, ½L₁ⁿ)` and `L₂ = ½L₂` for lines
//!   (`BLEND_DIST_FRACTION` = ½; on arcs a chord or angle limit), `d = min(L₁, L₂, d_tol)`;
//! * the largest radius `R = d·tan θ`, its speed `v_plan = min(√(0.866·a·R), v_goal)` with `a`
//!   the smallest axis acceleration in the blend's plane (`calculateInscribedDiameter`) and
//!   `v_goal` the faster segment's feed;
//! * the radius actually used, `R_plan = max(v_plan²/(0.866·a), min(s_b/φ, R))`, with `s_b`
//!   the distance of a parabolic blend at `a/2`: a long segment only gives up what it needs
//!   for the cornering speed; the arc starts `d_plan = R_plan / tan θ` before the corner.
//!
//! A line left shorter than 4 cycles at `v_plan` (`ARC_BLEND_GAP_CYCLES`) is consumed: it
//! becomes a straight lead of the arc (`blendCheckConsume`).

use super::circle::Circle;
use crate::geom::{Point3, Vec3};
use std::f64::consts::PI;

/// `BLEND_ACC_RATIO_TANGENTIAL`.
pub(super) const ACC_RATIO_TANGENTIAL: f64 = 0.5;
/// `BLEND_ACC_RATIO_NORMAL` = √(1 − 0.5²).
pub(super) fn acc_ratio_normal() -> f64 {
    (1.0 - ACC_RATIO_TANGENTIAL * ACC_RATIO_TANGENTIAL).sqrt()
}
/// `BLEND_DIST_FRACTION`.
pub(super) const DIST_FRACTION: f64 = 0.5;
/// `TP_ANGLE_EPSILON`.
const ANGLE_EPSILON: f64 = 1e-6;
/// `TP_POS_EPSILON`.
const POS_EPSILON: f64 = 1e-12;
/// `TP_MIN_ARC_LENGTH`.
const MIN_ARC_LENGTH: f64 = 1e-6;
/// `ARC_MIN_RADIUS` (spherical_arc.h).
const ARC_MIN_RADIUS: f64 = 1e-12;
/// `ARC_MIN_ANGLE` (spherical_arc.h).
const ARC_MIN_ANGLE: f64 = 1e-6;

/// One side of a corner: a line or a circle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Piece {
    /// A straight line.
    Line {
        /// Start.
        start: Point3,
        /// End.
        end: Point3,
    },
    /// An arc or helix.
    Circle(Circle),
}

impl Piece {
    pub fn line_dir(&self) -> Vec3 {
        match self {
            Piece::Line { start, end } => (*end - *start).normalize().unwrap_or(Vec3::ZERO),
            Piece::Circle(c) => c.tangent(0.0),
        }
    }
    pub fn start_tangent(&self) -> Vec3 {
        match self {
            Piece::Line { .. } => self.line_dir(),
            Piece::Circle(c) => c.tangent(0.0),
        }
    }
    pub fn end_tangent(&self) -> Vec3 {
        match self {
            Piece::Line { .. } => self.line_dir(),
            Piece::Circle(c) => c.tangent(c.angle),
        }
    }
}

/// What the blend code needs of a segment.
#[derive(Debug, Clone, Copy)]
pub(super) struct Side {
    pub piece: Piece,
    /// Current length (`target`).
    pub target: f64,
    /// Programmed length.
    pub nominal: f64,
    /// Its `G64 P` (0: none).
    pub tolerance: f64,
    /// `maxvel`.
    pub maxvel: f64,
    /// `tcGetMaxTargetVel(tc, 1)` = min(requested, maxvel).
    pub target_vel: f64,
    /// Whether a blend may consume it (`tcCanConsume`).
    pub can_consume: bool,
}

/// The blend arc LinuxCNC makes (`SphericalArc` from `arcFromBlendPoints3`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Arc {
    pub start: Point3,
    pub end: Point3,
    pub center: Point3,
    pub radius: f64,
    pub angle: f64,
    pub binormal: Vec3,
    /// End radius − start radius.
    pub spiral: f64,
    /// Straight part before the arc (a consumed line), along `u_tan`.
    pub line_length: f64,
    pub u_tan: Vec3,
}

impl Arc {
    pub fn length(&self) -> f64 {
        self.radius * self.angle + self.line_length
    }

    /// `arcTangent` at the start or the end.
    pub fn tangent(&self, at_end: bool) -> Vec3 {
        let r = if at_end {
            self.end - self.center
        } else {
            self.start - self.center
        };
        let radial = r.normalize().unwrap_or(Vec3::ZERO) * (self.spiral / self.angle);
        (self.binormal.cross(r) + radial)
            .normalize()
            .unwrap_or(Vec3::ZERO)
    }
}

/// The outcome of a blend computation.
#[derive(Debug, Clone, Copy)]
pub(super) struct Blend {
    pub arc: Arc,
    /// The incoming segment after the blend (`None` when consumed).
    pub prev: Option<Piece>,
    /// The outgoing segment after the blend.
    pub next: Piece,
    /// Requested speed of the arc (`v_req`).
    pub v_req: f64,
    /// Its maximum speed (`v_plan`).
    pub v_plan: f64,
    /// Its acceleration limit (`a_max`).
    pub a_max: f64,
}

#[derive(Debug, Clone, Copy, Default)]
struct Geom3 {
    u_tan1: Vec3,
    u_tan2: Vec3,
    u1: Vec3,
    u2: Vec3,
    p: Vec3,
    theta_tan: f64,
    binormal: Vec3,
    normal: Vec3,
    center1: Vec3,
    center2: Vec3,
    radius1: f64,
    radius2: f64,
}

#[derive(Debug, Clone, Copy, Default)]
struct Params {
    tolerance: f64,
    l1: f64,
    l2: f64,
    v_req: f64,
    a_max: f64,
    theta: f64,
    phi: f64,
    a_n_max: f64,
    r_plan: f64,
    d_plan: f64,
    v_goal: f64,
    v_plan: f64,
    convex1: bool,
    convex2: bool,
    phi1_max: f64,
    phi2_max: f64,
}

/// `calculateInscribedDiameter`: the smallest axis bound within the plane of `normal`.
pub(super) fn inscribed_diameter(normal: Vec3, bounds: [f64; 3]) -> Option<f64> {
    if (1.0 - normal.dot(normal)).abs() > 1e-6 {
        return None;
    }
    let n = normal.to_array();
    let mut extents = [0.0; 3];
    for i in 0..3 {
        let mut planar = [-n[0] * n[i], -n[1] * n[i], -n[2] * n[i]];
        planar[i] += 1.0;
        let mut planar = planar.map(f64::abs);
        planar[i] = planar[i].max(POS_EPSILON);
        let scale = Vec3::new(planar[0], planar[1], planar[2]).length();
        extents[i] = if bounds[i] != 0.0 {
            bounds[i] / scale
        } else {
            0.0
        };
    }
    let mut d = extents[0].max(extents[1]).max(extents[2]);
    for i in 0..3 {
        if bounds[i] != 0.0 {
            d = d.min(extents[i]);
        }
    }
    Some(d)
}

/// `findIntersectionAngle`: half the angle between `−u1` and `u2`.
pub(super) fn intersection_angle(u1: Vec3, u2: Vec3) -> f64 {
    (-u1.dot(u2).clamp(-1.0, 1.0)).acos() / 2.0
}

fn unit(v: Vec3) -> Vec3 {
    v.normalize().unwrap_or(Vec3::ZERO)
}

/// `blendGeom3Init`.
fn geom3_init(prev: &Side, next: &Side) -> Option<Geom3> {
    let u_tan1 = prev.piece.end_tangent();
    let u_tan2 = next.piece.start_tangent();
    let p = match (&prev.piece, &next.piece) {
        (_, Piece::Line { start, .. }) => *start,
        (Piece::Line { end, .. }, _) => *end,
        (_, Piece::Circle(c)) => c.point(0.0),
    };
    let theta_tan = intersection_angle(u_tan1, u_tan2);
    if PI / 2.0 - theta_tan < ANGLE_EPSILON || theta_tan < ANGLE_EPSILON {
        return None;
    }
    Some(Geom3 {
        u_tan1,
        u_tan2,
        u1: u_tan1,
        u2: u_tan2,
        p: p - Point3::ORIGIN,
        theta_tan,
        binormal: unit(u_tan1.cross(u_tan2)),
        normal: unit(u_tan2 - u_tan1),
        ..Geom3::default()
    })
}

/// `findSpiralApproximation`: centre moved along the tangent by the spiral rate, and the
/// distance from it to the corner.
fn spiral_approximation(c: &Circle, base: Vec3, u_tan: Vec3) -> (Vec3, f64) {
    let dr = c.spiral / c.angle;
    let center = u_tan * dr + (c.center - Point3::ORIGIN);
    (center, (base - center).length())
}

/// `arcConvexTest`.
fn convex(center: Vec3, p: Vec3, u: Vec3, reverse: bool) -> bool {
    reverse ^ ((p - center).dot(u) < 0.0)
}

/// `tcFindBlendTolerance`.
fn blend_tolerance(prev: &Side, next: &Side) -> f64 {
    let ratio = 0.25;
    let t1 = if prev.tolerance == 0.0 {
        prev.nominal * ratio
    } else {
        prev.tolerance
    };
    let t2 = if next.tolerance == 0.0 {
        next.nominal * ratio
    } else {
        next.tolerance
    };
    t1.min(t2)
        .min(prev.nominal * ratio)
        .min(next.nominal * ratio)
}

/// `blendParamKinematics`.
fn kinematics(
    g: &Geom3,
    p: &mut Params,
    prev: &Side,
    next: &Side,
    acc: [f64; 3],
    vel: [f64; 3],
) -> Option<()> {
    p.phi = PI - p.theta * 2.0;
    p.tolerance = blend_tolerance(prev, next);
    p.a_max = inscribed_diameter(g.binormal, acc)?;
    p.a_n_max = p.a_max * acc_ratio_normal();
    p.v_req = prev.target_vel.max(next.target_vel);
    p.v_goal = p.v_req;
    let v_planar_max = inscribed_diameter(g.binormal, vel)?;
    let phi_eff = p.phi.min(PI * 0.49);
    let v_max1 = prev.maxvel.min(next.maxvel / phi_eff.cos());
    let v_max2 = next.maxvel.min(prev.maxvel / phi_eff.cos());
    let v_area = v_max1 * v_max2 / 2.0 * p.phi.sin();
    let base = (g.u2 * v_max2 - g.u1 * v_max1).length();
    let mut v_max_alt = 2.0 * v_area / base;
    if !matches!(
        (&prev.piece, &next.piece),
        (Piece::Line { .. }, Piece::Line { .. })
    ) {
        v_max_alt = 0.0;
    }
    let v_max = v_max_alt.max(v_planar_max);
    p.v_goal = p.v_goal.min(v_max);
    Some(())
}

/// `blendComputeParameters`.
fn compute(p: &mut Params) -> Option<()> {
    let h_tol = p.tolerance / (1.0 - p.theta.sin());
    let d_tol = p.theta.cos() * h_tol;
    let d_geom = p.l1.min(p.l2).min(d_tol);
    let r_geom = p.theta.tan() * d_geom;
    let v_normal = (p.a_n_max * r_geom).sqrt();
    p.v_plan = v_normal.min(p.v_goal);
    let a_parabolic = p.a_max * 0.5;
    let v_triangle = (2.0 * a_parabolic * d_geom).sqrt();
    let t_blend = v_triangle.min(p.v_plan) / a_parabolic;
    let s_blend = t_blend * p.v_plan;
    let r_blend = (s_blend / p.phi).min(r_geom);
    p.r_plan = (p.v_plan * p.v_plan / p.a_n_max).max(r_blend);
    p.d_plan = p.r_plan / p.theta.tan();
    let s_arc = p.r_plan * p.phi;
    (p.r_plan >= POS_EPSILON && s_arc >= MIN_ARC_LENGTH && p.r_plan.is_finite()).then_some(())
}

/// `blendFindPoints3`: (arc start, arc end, arc centre).
fn find_points(g: &Geom3, p: &Params) -> (Vec3, Vec3, Vec3) {
    let center = g.normal * (p.r_plan / p.theta.sin()) + g.p;
    let start = g.p - g.u1 * p.d_plan;
    let end = g.u2 * p.d_plan + g.p;
    (start, end, center)
}

/// `arcInitFromPoints` (with `arcFromBlendPoints3`'s lead).
fn arc_from_points(
    start: Vec3,
    end: Vec3,
    center: Vec3,
    g: &Geom3,
    line_length: f64,
) -> Option<Arc> {
    let r0 = (start - center).length();
    let r1 = (end - center).length();
    if r0 < ARC_MIN_RADIUS || r1 < ARC_MIN_RADIUS {
        return None;
    }
    let dot = ((start - center) * (1.0 / r0)).dot((end - center) * (1.0 / r1));
    let angle = dot.clamp(-1.0, 1.0).acos();
    if dot.is_nan() || angle < ARC_MIN_ANGLE {
        return None;
    }
    Some(Arc {
        start: Point3::ORIGIN + start,
        end: Point3::ORIGIN + end,
        center: Point3::ORIGIN + center,
        radius: r0,
        angle,
        binormal: g.binormal,
        spiral: r1 - r0,
        line_length,
        u_tan: g.u_tan1,
    })
}

fn quadratic(a: f64, b: f64, c: f64) -> Option<(f64, f64)> {
    let disc = b * b - 4.0 * a * c;
    if disc < 0.0 {
        return None;
    }
    let t = disc.sqrt();
    Some(((-b + t) / (2.0 * a), (-b - t) / (2.0 * a)))
}

/// `findTrimAngle`.
fn trim_angle(p: Vec3, arc_center: Vec3, center: Vec3) -> f64 {
    unit(arc_center - center)
        .dot(unit(p - center))
        .min(1.0)
        .acos()
}

/// `blendCheckConsume`: the line before the blend, left shorter than `gap_cycles` cycles at
/// the blend's speed, is consumed; returns the consumed length (`None`: kept).
fn consume(p: &Params, prev: &Side, trim1: f64, gap_cycles: f64, cycle: f64) -> Option<f64> {
    if !matches!(prev.piece, Piece::Line { .. }) {
        return None;
    }
    let l_prev = prev.target - trim1;
    let t = l_prev / p.v_plan;
    (t < gap_cycles * cycle && prev.can_consume).then_some(l_prev)
}

/// Machine bounds and settings the blend code reads.
#[derive(Debug, Clone, Copy)]
pub(super) struct Bounds {
    pub acc: [f64; 3],
    pub vel: [f64; 3],
    pub cycle: f64,
    pub gap_cycles: f64,
}

/// `tpCreateLineLineBlend` up to the choice of the best blend.
pub(super) fn line_line(prev: &Side, next: &Side, b: &Bounds) -> Option<Blend> {
    let (Piece::Line { start: s1, .. }, Piece::Line { end: e2, .. }) = (prev.piece, next.piece)
    else {
        return None;
    };
    let g = geom3_init(prev, next)?;
    let mut p = Params {
        theta: g.theta_tan,
        ..Params::default()
    };
    p.l1 = prev.target.min(prev.nominal * DIST_FRACTION);
    p.l2 = next.target * DIST_FRACTION;
    kinematics(&g, &mut p, prev, next, b.acc, b.vel)?;
    compute(&mut p)?;
    let (start, end, center) = find_points(&g, &p);
    let consumed = consume(&p, prev, p.d_plan, b.gap_cycles, b.cycle);
    let arc = arc_from_points(start, end, center, &g, consumed.unwrap_or(0.0))?;
    let prev_piece = consumed.is_none().then_some(Piece::Line {
        start: s1,
        end: Point3::ORIGIN + start,
    });
    Some(Blend {
        arc,
        prev: prev_piece,
        next: Piece::Line {
            start: Point3::ORIGIN + end,
            end: e2,
        },
        v_req: p.v_req,
        v_plan: p.v_plan,
        a_max: p.a_max,
    })
}

/// `blendInit3FromLineArc` / `blendInit3FromArcLine` / `blendInit3FromArcArc`, their
/// post-processing, the stretch of both segments and the tangent check
/// (`tpCreateLineArcBlend`, `tpCreateArcLineBlend`, `tpCreateArcArcBlend`).
pub(super) fn with_arcs(prev: &Side, next: &Side, b: &Bounds) -> Option<Blend> {
    let mut g = geom3_init(prev, next)?;
    let mut p = Params {
        theta: g.theta_tan,
        ..Params::default()
    };
    let c1 = match prev.piece {
        Piece::Circle(c) => Some(c),
        Piece::Line { .. } => None,
    };
    let c2 = match next.piece {
        Piece::Circle(c) => Some(c),
        Piece::Line { .. } => None,
    };
    if c1.is_none() && c2.is_none() {
        return None;
    }
    let colinear = |a: Vec3, n: Vec3| {
        let d = a - n;
        let s = a + n;
        d.dot(d) < ANGLE_EPSILON * ANGLE_EPSILON || s.dot(s) < ANGLE_EPSILON * ANGLE_EPSILON
    };
    if let (Some(a), Some(c)) = (c1, c2)
        && !colinear(a.normal, c.normal)
    {
        return None;
    }
    if let Some(c) = c1 {
        let (center, radius) = spiral_approximation(&c, g.p, g.u_tan1);
        g.center1 = center;
        g.radius1 = radius;
    }
    if let Some(c) = c2 {
        let (center, radius) = spiral_approximation(&c, g.p, g.u_tan2);
        g.center2 = center;
        g.radius2 = radius;
    }
    if let (Some(_), Some(c)) = (c1, c2) {
        // Arc–arc: the intersection point from the second circle's start.
        g.p = c.point(0.0) - Point3::ORIGIN;
    }
    if let Some(c) = c1 {
        p.convex1 = convex(g.center1, g.p, g.u_tan2, false);
        let blend_angle = if p.convex1 { g.theta_tan } else { PI / 2.0 };
        p.phi1_max = (c.angle * 2.0 / 3.0).min(blend_angle);
        if p.convex1 {
            let bp = c.point(c.angle - p.phi1_max / 2.0) - Point3::ORIGIN;
            g.u1 = unit(g.p - bp);
            p.theta = p.theta.min(g.theta_tan - p.phi1_max / 4.0);
        }
    }
    if let Some(c) = c2 {
        p.convex2 = convex(g.center2, g.p, g.u_tan1, true);
        let blend_angle = if p.convex2 { g.theta_tan } else { PI / 2.0 };
        p.phi2_max = (c.angle / 3.0).min(blend_angle);
        if p.convex2 {
            let bp = c.point(p.phi2_max / 2.0) - Point3::ORIGIN;
            g.u2 = unit(bp - g.p);
            p.theta = p.theta.min(g.theta_tan - p.phi2_max / 4.0);
        }
    }
    if c1.is_some() && c2.is_some() && p.theta < PI / 12.0 {
        return None;
    }
    p.phi = PI - p.theta * 2.0;
    p.l1 = match c1 {
        None => prev.target.min(prev.nominal / 2.0),
        Some(_) if p.convex1 => (p.phi1_max / 4.0).sin() * g.radius1,
        Some(_) => p.phi1_max * g.radius1,
    };
    p.l2 = match c2 {
        None => next.nominal / 2.0,
        Some(_) if p.convex2 => (p.phi2_max / 4.0).sin() * g.radius2,
        Some(_) => p.phi2_max * g.radius2,
    };
    kinematics(&g, &mut p, prev, next, b.acc, b.vel)?;
    // Coplanarity of the blend with the circles.
    for c in [c1, c2].into_iter().flatten() {
        if !colinear(g.binormal, c.normal) {
            return None;
        }
    }
    compute(&mut p)?;
    let neg = |r: f64, convex: bool| if convex { -r } else { r };
    // Post-processing: the exact blend centre and the trims (length on lines, angle on arcs).
    let (center, trim1, trim2) = match (c1, c2) {
        (None, Some(_)) => {
            let d2 = neg(p.r_plan, p.convex2) + g.radius2;
            let n1 = unit(g.binormal.cross(g.u1));
            let r_pc2 = g.center2 - g.p;
            let (c2u, c2n) = (r_pc2.dot(g.u1), r_pc2.dot(n1));
            let (r0, r1) = quadratic(
                1.0,
                2.0 * c2u,
                c2u * c2u - d2 * d2 + (p.r_plan - c2n).powi(2),
            )?;
            let d_l = r0.abs().min(r1.abs());
            let r_pc = g.u1 * (-d_l) + n1 * p.r_plan;
            if r_pc.length() - p.r_plan > p.tolerance {
                return None;
            }
            let center = g.p + r_pc;
            (center, d_l, trim_angle(g.p, center, g.center2))
        }
        (Some(_), None) => {
            let d1 = neg(p.r_plan, p.convex1) + g.radius1;
            let n2 = unit(g.binormal.cross(g.u2));
            let r_pc1 = g.center1 - g.p;
            let (c1u, c1n) = (r_pc1.dot(g.u2), r_pc1.dot(n2));
            let (r0, r1) = quadratic(
                1.0,
                2.0 * c1u,
                c1u * c1u - d1 * d1 + (p.r_plan - c1n).powi(2),
            )?;
            let d_l = r0.abs().min(r1.abs());
            let r_pc = g.u2 * d_l + n2 * p.r_plan;
            if r_pc.length() - p.r_plan > p.tolerance {
                return None;
            }
            let center = g.p + r_pc;
            (center, trim_angle(g.p, center, g.center1), d_l)
        }
        (Some(_), Some(_)) => {
            let d1 = neg(p.r_plan, p.convex1) + g.radius1;
            let d2 = neg(p.r_plan, p.convex2) + g.radius2;
            let r_c1c2 = g.center2 - g.center1;
            let c2x = r_c1c2.length();
            let cx = (-d1 * d1 + d2 * d2 - c2x * c2x) / (-2.0 * c2x);
            let cy = (d1 * d1 - cx * cx).sqrt();
            let uc = r_c1c2.normalize()?;
            let mut nc = g.binormal.cross(uc);
            if g.normal.dot(nc) < 0.0 {
                nc = -nc;
            }
            let nc = nc.normalize()?;
            let c_x = uc * cx;
            let mut c_y = nc * cy;
            let r_pc1 = g.center1 - g.p;
            let test1 = r_pc1 + c_x + c_y;
            let test2 = r_pc1 + c_x - c_y;
            if test2.length() < test1.length() {
                c_y = -c_y;
            }
            let center = g.center1 + c_x + c_y;
            if (center - g.p).length() - p.r_plan > p.tolerance || !cy.is_finite() {
                return None;
            }
            (
                center,
                trim_angle(g.p, center, g.center1),
                trim_angle(g.p, center, g.center2),
            )
        }
        (None, None) => return None,
    };
    if c1.is_some() && trim1 > p.phi1_max {
        return None;
    }
    if c2.is_some() && trim2 > p.phi2_max {
        return None;
    }
    let consumed = consume(&p, prev, trim1, b.gap_cycles, b.cycle);
    // Stretch both segments.
    let new_prev = match prev.piece {
        Piece::Line { start, end } => {
            let len = start.distance(end) - trim1;
            if len <= 1e-10 {
                return None;
            }
            let u = unit(end - start);
            Piece::Line {
                start,
                end: start + u * len,
            }
        }
        Piece::Circle(c) => Piece::Circle(c.stretched(c.angle - trim1, false)?),
    };
    let new_next = match next.piece {
        Piece::Line { start, end } => {
            let len = start.distance(end) - trim2;
            if len <= 1e-10 {
                return None;
            }
            let u = unit(end - start);
            Piece::Line {
                start: end - u * len,
                end,
            }
        }
        Piece::Circle(c) => Piece::Circle(c.stretched(c.angle - trim2, true)?),
    };
    let arc_start = match new_prev {
        Piece::Line { end, .. } => end,
        Piece::Circle(c) => c.point(c.angle),
    };
    let arc_end = match new_next {
        Piece::Line { start, .. } => start,
        Piece::Circle(c) => c.point(0.0),
    };
    let arc = arc_from_points(
        arc_start - Point3::ORIGIN,
        arc_end - Point3::ORIGIN,
        center,
        &g,
        consumed.unwrap_or(0.0),
    )?;
    // checkTangentAngle against each circle.
    let angle_max = (acc_ratio_normal() * 0.25 * p.a_max) / (p.v_plan / b.cycle);
    for (piece, at_end) in [(new_prev, false), (new_next, true)] {
        if let Piece::Circle(c) = piece {
            let u_circ = if at_end {
                c.tangent(0.0)
            } else {
                c.tangent(c.angle)
            };
            let u_arc = arc.tangent(at_end);
            if u_circ.dot(u_arc).min(1.0).acos() > angle_max {
                return None;
            }
        }
    }
    Some(Blend {
        arc,
        prev: consumed.is_none().then_some(new_prev),
        next: new_next,
        v_req: p.v_req,
        v_plan: p.v_plan,
        a_max: p.a_max,
    })
}
