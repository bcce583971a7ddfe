//! LinuxCNC's segment queue (`src/emc/tp/tp.c`, `tc.c`): segments as `tpAddLine` and
//! `tpAddCircle` set them up, the corner decision of `tpHandleBlendArc` (tangent within the
//! kink ratio, blend arc, parabolic blend or stop), and the look-ahead of
//! `tpRunOptimization`, whose final speeds become the planner's junction caps.

use super::blend::{self, Arc, Bounds, Piece, Side};
use super::circle::Circle;
use crate::geom::{Point3, Vec3};
use crate::machine::Machine;
use crate::motion::path::BlockGeometry;
use crate::motion::profile::Limits1;
use crate::toolpath::{Move, Rotary};
use std::collections::VecDeque;
use std::f64::consts::PI;

/// `TP_MIN_SEGMENT_CYCLES`: a segment lasts at least this many servo cycles.
pub(super) const MIN_SEGMENT_CYCLES: f64 = 1.02;
/// `ARC_BLEND_OPTIMIZATION_DEPTH` (LinuxCNC's default): segments the look-ahead reaches back.
pub(super) const OPTIMIZATION_DEPTH: usize = 50;
/// `ARC_BLEND_GAP_CYCLES` (default): a line left shorter than this many cycles at the blend
/// speed is consumed by the blend.
pub(super) const GAP_CYCLES: f64 = 4.0;
/// `ARC_BLEND_KINK_RATIO` (default): the share of the axis acceleration an unblended,
/// nearly tangent junction may take.
pub(super) const KINK_RATIO: f64 = 0.1;
/// `TP_OPTIMIZATION_CUTOFF`: peaks after which the look-ahead stops.
const OPTIMIZATION_CUTOFF: usize = 4;
/// Reversals within this angle stop (`SHARP_CORNER_DEG` of `tpSetupTangent`).
const SHARP_CORNER_DEG: f64 = 2.0;

/// Rotary displacements below it (rad) do not count.
pub(super) const ROT_FUZZ: f64 = 1e-9;

/// The rotary displacement from `r0` to `r1`, rad.
pub(super) fn turn(r0: Rotary, r1: Rotary) -> [f64; 3] {
    [r1.a - r0.a, r1.b - r0.b, r1.c - r0.c]
}

/// True when the rotary axes move between `r0` and `r1` (LinuxCNC's `tmag_zero` of the
/// `abc` line, false).
pub(super) fn turns(r0: Rotary, r1: Rotary) -> bool {
    turn(r0, r1).iter().any(|x| x.abs() >= ROT_FUZZ)
}

/// `tc_term_cond_t`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Term {
    Stop,
    Exact,
    Parabolic,
    Tangent,
}

/// `tc->motion_type` with its geometry.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Shape {
    Line { start: Point3, end: Point3 },
    Circle(Circle),
    Blend(Arc),
}

/// One segment (`TC_STRUCT`), with the input move it came from.
#[derive(Debug, Clone, Copy)]
pub(super) struct Tc {
    pub shape: Shape,
    pub target: f64,
    pub nominal: f64,
    pub reqvel: f64,
    pub maxvel: f64,
    pub maxaccel: f64,
    pub acc_ratio_tan: f64,
    pub term: Term,
    pub tolerance: f64,
    pub kink_vel: f64,
    pub kink_reduce: f64,
    pub kink_reduce_prev: f64,
    pub blend_prev: bool,
    pub finalized: bool,
    pub finalvel: f64,
    pub at_max: bool,
    pub traverse: bool,
    pub origin: usize,
    pub mv: Move,
    /// The rotary axes at the start and the end.
    pub rot: (Rotary, Rotary),
}

impl Tc {
    /// A new line or circle segment (`tcInit`, `tcSetupState`, `tcSetupMotion`).
    pub fn new(shape: Shape, target: f64, vel: f64, ini_maxvel: f64, acc: f64) -> Tc {
        Tc {
            shape,
            target,
            nominal: target,
            reqvel: vel,
            maxvel: ini_maxvel,
            maxaccel: acc,
            acc_ratio_tan: blend::ACC_RATIO_TANGENTIAL,
            term: Term::Parabolic,
            tolerance: 0.0,
            kink_vel: -1.0,
            kink_reduce: 0.0,
            kink_reduce_prev: 0.0,
            blend_prev: false,
            finalized: false,
            finalvel: 0.0,
            at_max: false,
            traverse: false,
            origin: 0,
            mv: Move::rapid(Point3::ORIGIN),
            rot: (Rotary::default(), Rotary::default()),
        }
    }

    /// `tcRotaryMotionCheck`: the segment turns a rotary axis.
    pub fn turns(&self) -> bool {
        turns(self.rot.0, self.rot.1)
    }

    /// `tcPureRotaryCheck`: a line that turns rotary axes only (its `target` is their
    /// chord, rad).
    pub fn pure_rotary(&self) -> bool {
        matches!(self.shape, Shape::Line { start, end } if start.distance(end) < 1e-12)
            && self.turns()
    }

    fn curved(&self) -> bool {
        !matches!(self.shape, Shape::Line { .. })
    }

    /// `tcGetOverallMaxAccel`.
    pub fn overall_accel(&self) -> f64 {
        let mut scale = 1.0 - self.kink_reduce.max(self.kink_reduce_prev);
        if self.blend_prev || self.term == Term::Parabolic {
            scale *= 0.5;
        }
        self.maxaccel * scale
    }

    /// `tcGetTangentialMaxAccel`.
    pub fn tangential_accel(&self) -> f64 {
        let a = self.overall_accel();
        if self.curved() {
            a * self.acc_ratio_tan
        } else {
            a
        }
    }

    /// `tcGetMaxTargetVel(tc, 1)`.
    pub fn target_vel(&self) -> f64 {
        self.reqvel.min(self.maxvel)
    }

    /// `tcClampVelocityByLength`.
    fn clamp_by_length(&mut self, cycle: f64) {
        self.maxvel = self.maxvel.min(self.target / cycle);
    }

    /// `tcFinalizeLength`: the per-cycle cap and the arc's tangential acceleration ratio
    /// (`pmCircleActualMaxVel`).
    fn finalize(&mut self, cycle: f64) {
        if self.finalized {
            return;
        }
        self.clamp_by_length(cycle);
        if let Shape::Circle(c) = self.shape {
            let a_max = self.overall_accel();
            let cutoff = blend::acc_ratio_normal() * a_max;
            let r = c.effective_min_radius();
            let a_n = self.maxvel * self.maxvel / r.max(1e-300);
            if a_n > cutoff {
                self.maxvel = (cutoff * r).sqrt();
                self.acc_ratio_tan = blend::ACC_RATIO_TANGENTIAL;
            } else {
                self.acc_ratio_tan = (1.0 - (a_n / a_max).powi(2)).sqrt();
            }
        }
        self.finalized = true;
    }

    fn piece(&self) -> Option<Piece> {
        match self.shape {
            Shape::Line { start, end } => Some(Piece::Line { start, end }),
            Shape::Circle(c) => Some(Piece::Circle(c)),
            Shape::Blend(_) => None,
        }
    }

    fn start_tangent(&self) -> Vec3 {
        match self.shape {
            Shape::Blend(a) => a.u_tan,
            _ => self.piece().map_or(Vec3::ZERO, |p| p.start_tangent()),
        }
    }

    fn end_tangent(&self) -> Vec3 {
        match self.shape {
            Shape::Blend(a) => a.tangent(true),
            _ => self.piece().map_or(Vec3::ZERO, |p| p.end_tangent()),
        }
    }

    /// `tcGetStartAccelUnitVector` / `tcGetEndAccelUnitVector` (lines: the direction; circles:
    /// the start mixes the tangent with the centripetal direction).
    fn accel_dir(&self, at_start: bool) -> Vec3 {
        if self.pure_rotary() {
            // pmCartLineInit: the unit vector of a zero X Y Z line is (1, 0, 0).
            return Vec3::new(1.0, 0.0, 0.0);
        }
        match self.shape {
            Shape::Circle(c) if at_start => {
                let start = c.point(0.0);
                let tan = c
                    .normal
                    .cross(start - c.center)
                    .normalize()
                    .unwrap_or(Vec3::ZERO);
                let perp = (c.center - start).normalize().unwrap_or(Vec3::ZERO);
                let v =
                    tan * self.overall_accel() + perp * ((0.5 * self.reqvel).powi(2) / c.radius);
                v.normalize().unwrap_or(Vec3::ZERO)
            }
            Shape::Circle(c) => {
                let end = c.point(c.angle);
                c.normal
                    .cross(end - c.center)
                    .normalize()
                    .unwrap_or(Vec3::ZERO)
            }
            _ => self.start_tangent(),
        }
    }

    fn side(&self) -> Option<Side> {
        Some(Side {
            piece: self.piece()?,
            target: self.target,
            nominal: self.nominal,
            tolerance: self.tolerance,
            maxvel: self.maxvel,
            target_vel: self.target_vel(),
            can_consume: !self.blend_prev,
        })
    }

    /// The planner geometry of the segment.
    pub fn geom(&self) -> Option<BlockGeometry> {
        match self.shape {
            Shape::Line { start, .. } if self.pure_rotary() => Some(BlockGeometry::Line {
                from: start,
                dir: Vec3::ZERO,
                length: self.target,
            }),
            Shape::Line { start, end } => {
                let d = end - start;
                let length = d.length();
                (length > 1e-12).then(|| BlockGeometry::Line {
                    from: start,
                    dir: d / length,
                    length,
                })
            }
            Shape::Circle(c) => Some(c.geom()),
            Shape::Blend(a) => {
                let e0 = (a.start - a.center).normalize()?;
                let e1 = a.binormal.cross(e0).normalize()?;
                Some(BlockGeometry::Arc3 {
                    start: a.start - a.u_tan * a.line_length,
                    lead_dir: a.u_tan,
                    lead: a.line_length,
                    center: a.center,
                    e0,
                    e1,
                    radius: a.radius,
                    angle: a.angle,
                    length: a.length(),
                })
            }
        }
    }

    /// Start point.
    pub fn start(&self) -> Point3 {
        match self.shape {
            Shape::Line { start, .. } => start,
            Shape::Circle(c) => c.point(0.0),
            Shape::Blend(a) => a.start - a.u_tan * a.line_length,
        }
    }

    /// End point.
    pub fn end(&self) -> Point3 {
        match self.shape {
            Shape::Line { end, .. } => end,
            Shape::Circle(c) => c.point(c.angle),
            Shape::Blend(a) => a.end,
        }
    }
}

/// `tpCalculateTriangleVel`.
fn triangle_vel(tc: &Tc) -> f64 {
    let len = if tc.finalized {
        tc.target
    } else {
        tc.target / 2.0
    };
    (tc.tangential_accel() * len).sqrt()
}

/// `tpComputeBlendVelocity`: the speeds at which a parabolic blend starts on `tc` and ends
/// on `next`, and the net speed along the blend.
pub(super) fn blend_velocity(tc: &Tc, next: &Tc, v_this: f64, v_next: f64) -> (f64, f64, f64) {
    let acc_this = tc.tangential_accel();
    let acc_next = next.tangential_accel();
    let reach_this = triangle_vel(tc).min(v_this);
    let reach_next = triangle_vel(next).min(v_next);
    let t_max = (tc.target / reach_this).min(next.target / reach_next);
    let t_min_blend = (reach_this / acc_this).max(reach_next / acc_next);
    let t_blend = t_max.min(t_min_blend);
    let mut b_this = reach_this.min(t_blend * acc_this);
    let mut b_next = reach_next.min(t_blend * acc_next);
    let theta = blend::intersection_angle(tc.accel_dir(false), next.accel_dir(true));
    let cos_theta = theta.cos();
    if tc.tolerance > 0.0 {
        let min_cos = (PI / 2.0 - 1e-3).cos();
        if cos_theta > min_cos {
            let v = 2.0 * (acc_this * tc.tolerance / cos_theta).sqrt();
            b_this = b_this.min(v);
            b_next = b_next.min(v);
        }
    }
    let net = theta.sin() * (b_this + b_next) / 2.0;
    (b_this, b_next, net)
}

/// The queue and LinuxCNC's settings.
pub(super) struct Tp {
    pub queue: VecDeque<Tc>,
    pub cycle: f64,
    pub v_limit: f64,
    pub acc_bound: [f64; 3],
    pub vel_bound: [f64; 3],
}

impl Tp {
    pub fn new(machine: &Machine) -> Tp {
        Tp {
            queue: VecDeque::new(),
            cycle: machine.ipo_cycle,
            v_limit: machine.max_feed,
            acc_bound: machine.axes.map(|a| a.max_acceleration),
            vel_bound: machine.axes.map(|a| a.max_velocity),
        }
    }

    /// `tpGetMaxTargetVel` (feed override 1): the segment's speed limit, `[TRAJ]` limit
    /// included.
    pub fn max_target_vel(&self, tc: &Tc) -> f64 {
        if tc.pure_rotary() {
            // The [TRAJ] limit is a linear speed: not applied to rotary-only moves.
            return tc.target_vel();
        }
        tc.target_vel().min(self.v_limit)
    }

    /// `tpAddLine` / `tpAddCircle` after the segment is set up.
    pub fn add(&mut self, mut tc: Tc) {
        tc.clamp_by_length(self.cycle);
        if let Some(prev) = self.queue.back_mut()
            && prev.traverse != tc.traverse
        {
            // handleModeChange: no blending between rapids and feeds.
            prev.term = Term::Stop;
            tc.blend_prev = false;
        }
        // Finalizes the previous segment (`tcFinalizeLength`) too.
        self.handle_blend_arc(&mut tc);
        self.queue.push_back(tc);
        self.optimize();
    }

    /// `tpSetTermCond(prev, tc, cond)`.
    fn set_term(prev: &mut Tc, tc: &mut Tc, term: Term) {
        tc.blend_prev = term == Term::Parabolic;
        prev.term = term;
    }

    /// `tpHandleBlendArc`, then `tcFinalizeLength` of the previous segment.
    fn handle_blend_arc(&mut self, tc: &mut Tc) {
        let Some(mut prev) = self.queue.back().copied() else {
            return;
        };
        let cycle = self.cycle;
        match self.setup_tangent(&mut prev, tc) {
            Tangency::Fail | Tangency::Tangent => {
                prev.finalize(cycle);
                if let Some(b) = self.queue.back_mut() {
                    *b = prev;
                }
                return;
            }
            Tangency::Blend => {}
        }
        let blend = self.create_blend(&prev, tc);
        match blend {
            Some((blend_tc, b)) => {
                let mut blend_tc = blend_tc;
                if self.choose_best(&mut prev, tc, Some(&blend_tc)) == BlendKind::Arc {
                    prev.term = Term::Tangent;
                    tc.blend_prev = false;
                    tc.shape = match b.next {
                        Piece::Line { start, end } => Shape::Line { start, end },
                        Piece::Circle(c) => Shape::Circle(c),
                    };
                    tc.target = match tc.shape {
                        Shape::Circle(c) => c.length(),
                        _ => tc.start().distance(tc.end()),
                    };
                    match b.prev {
                        None => {
                            self.queue.pop_back();
                        }
                        Some(piece) => {
                            prev.shape = match piece {
                                Piece::Line { start, end } => Shape::Line { start, end },
                                Piece::Circle(c) => Shape::Circle(c),
                            };
                            prev.target = match prev.shape {
                                Shape::Circle(c) => c.length(),
                                _ => prev.start().distance(prev.end()),
                            };
                            prev.finalize(cycle);
                            if let Some(back) = self.queue.back_mut() {
                                *back = prev;
                            }
                        }
                    }
                    blend_tc.origin = prev.origin;
                    blend_tc.mv = prev.mv;
                    self.queue.push_back(blend_tc);
                    return;
                }
                // Not the best: the choice is made again without the arc.
                self.choose_best(&mut prev, tc, None);
            }
            None => {
                self.choose_best(&mut prev, tc, None);
            }
        }
        prev.finalize(cycle);
        if let Some(b) = self.queue.back_mut() {
            *b = prev;
        }
    }

    /// `tpSetupTangent`.
    fn setup_tangent(&self, prev: &mut Tc, tc: &mut Tc) -> Tangency {
        // Rotary motion on either side: neither tangent nor a blend arc (the corner keeps its
        // parabolic blend, exact path or stop).
        if prev.term == Term::Stop || prev.turns() || tc.turns() {
            return Tangency::Fail;
        }
        let prev_tan = prev.end_tangent();
        let this_tan = tc.start_tangent();
        let sharp = (PI * SHARP_CORNER_DEG / 180.0).powi(2);
        let sum = prev_tan + this_tan;
        if sum.dot(sum) < sharp {
            Self::set_term(prev, tc, Term::Stop);
            return Tangency::Fail;
        }
        let v_max = prev.target_vel().min(tc.target_vel());
        let a_inst = v_max / self.cycle + tc.maxaccel;
        let diff = (this_tan - prev_tan) * a_inst;
        let mut scale = 0.0f64;
        for (d, b) in diff.to_array().iter().zip(self.acc_bound) {
            if b != 0.0 {
                scale = scale.max((d / b).abs());
            }
        }
        if matches!(prev.shape, Shape::Circle(_)) || matches!(tc.shape, Shape::Circle(_)) {
            scale /= blend::ACC_RATIO_TANGENTIAL;
        }
        if scale < KINK_RATIO {
            Self::set_term(prev, tc, Term::Tangent);
            Self::set_kink(prev, tc, v_max, scale);
            Tangency::Tangent
        } else {
            Self::set_kink(prev, tc, v_max * KINK_RATIO / scale, KINK_RATIO);
            Tangency::Blend
        }
    }

    /// `tcSetKinkProperties`.
    fn set_kink(prev: &mut Tc, tc: &mut Tc, kink_vel: f64, reduce: f64) {
        prev.kink_vel = kink_vel;
        prev.kink_reduce = prev.kink_reduce.max(reduce);
        tc.kink_reduce_prev = tc.kink_reduce_prev.max(reduce);
    }

    /// `tcRemoveKinkProperties`.
    fn remove_kink(prev: &mut Tc, tc: &mut Tc) {
        prev.kink_vel = -1.0;
        prev.kink_reduce = 0.0;
        tc.kink_reduce_prev = 0.0;
    }

    /// `tpCheckBlendArcType` and the `tpCreate*Blend` functions: the blend arc segment, if
    /// LinuxCNC can make one.
    fn create_blend(&self, prev: &Tc, tc: &Tc) -> Option<(Tc, blend::Blend)> {
        if prev.term != Term::Parabolic || prev.finalized || tc.finalized {
            return None;
        }
        let (p, n) = (prev.side()?, tc.side()?);
        let bounds = Bounds {
            acc: self.acc_bound,
            vel: self.vel_bound,
            cycle: self.cycle,
            gap_cycles: GAP_CYCLES,
        };
        let b = match (p.piece, n.piece) {
            (Piece::Line { .. }, Piece::Line { .. }) => blend::line_line(&p, &n, &bounds)?,
            _ => blend::with_arcs(&p, &n, &bounds)?,
        };
        // tpInitBlendArcFromPrev.
        let mut btc = Tc::new(
            Shape::Blend(b.arc),
            b.arc.length(),
            b.v_req,
            b.v_plan,
            b.a_max,
        );
        btc.traverse = prev.traverse;
        btc.tolerance = tc.tolerance;
        btc.term = Term::Tangent;
        btc.finalize(self.cycle);
        Some((btc, b))
    }

    /// `tpChooseBestBlend`.
    fn choose_best(&self, prev: &mut Tc, tc: &mut Tc, blend_tc: Option<&Tc>) -> BlendKind {
        if matches!(prev.term, Term::Exact | Term::Stop) {
            return BlendKind::None;
        }
        let (_, _, net) =
            blend_velocity(prev, tc, self.max_target_vel(prev), self.max_target_vel(tc));
        let perf = [net / 2.0, prev.kink_vel, blend_tc.map_or(0.0, |b| b.maxvel)];
        let mut best = 0;
        for (k, v) in perf.iter().enumerate() {
            if *v > perf[best] {
                best = k;
            }
        }
        match best {
            0 => {
                Self::remove_kink(prev, tc);
                Self::set_term(prev, tc, Term::Parabolic);
                BlendKind::Parabolic
            }
            1 => {
                Self::set_term(prev, tc, Term::Tangent);
                BlendKind::Tangent
            }
            _ => {
                Self::remove_kink(prev, tc);
                BlendKind::Arc
            }
        }
    }

    /// `tpRunOptimization`: the rising-tide backward pass over the queue's tail.
    fn optimize(&mut self) {
        let len = self.queue.len();
        let mut hit_peaks = 0;
        let mut hit_non_tangent = false;
        for x in 1..OPTIMIZATION_DEPTH + 2 {
            if x + 1 > len {
                return;
            }
            let ind = len - x;
            let (mut tc, mut prev1) = (self.queue[ind], self.queue[ind - 1]);
            if prev1.term != Term::Tangent {
                if hit_non_tangent {
                    return;
                }
                hit_non_tangent = true;
                continue;
            }
            if !tc.finalized {
                let initial = (tc.tangential_accel() * tc.target)
                    .sqrt()
                    .min(self.max_target_vel(&tc));
                prev1.finalvel = prev1.maxvel.min(initial);
                if prev1.kink_vel >= 0.0 && prev1.term == Term::Tangent {
                    prev1.finalvel = prev1.finalvel.min(prev1.kink_vel);
                }
                tc.finalvel = 0.0;
            } else {
                // tpComputeOptimalVelocity.
                let a = tc.tangential_accel();
                let mut vs_back = (tc.finalvel * tc.finalvel + 2.0 * a * tc.target).sqrt();
                let mut vf_limit_prev = prev1.maxvel;
                if prev1.kink_vel >= 0.0 && prev1.term == Term::Tangent {
                    vf_limit_prev = vf_limit_prev.min(prev1.kink_vel);
                }
                let vf_limit = tc.maxvel.min(vf_limit_prev);
                if vs_back >= vf_limit {
                    vs_back = vf_limit;
                    prev1.at_max = true;
                }
                prev1.finalvel = vs_back;
                tc.maxvel = tc.maxvel.min(tc.target / (self.cycle * MIN_SEGMENT_CYCLES));
            }
            let at_max = tc.at_max;
            self.queue[ind] = tc;
            self.queue[ind - 1] = prev1;
            if at_max {
                hit_peaks += 1;
            }
            if hit_peaks > OPTIMIZATION_CUTOFF {
                return;
            }
        }
    }

    /// The speed at the end of `tc` into `next` (`tpGetRealFinalVel` at run time; the
    /// equivalent junction speed of a parabolic blend).
    pub fn junction(&self, tc: &Tc, next: Option<&Tc>) -> f64 {
        let Some(next) = next else {
            return 0.0;
        };
        let (v_this, v_next) = (self.max_target_vel(tc), self.max_target_vel(next));
        match tc.term {
            Term::Tangent => tc.finalvel.min(v_this).min(v_next),
            Term::Parabolic => {
                let (b_this, b_next, _) = blend_velocity(tc, next, v_this, v_next);
                // The overlap lasts while `tc` slows from `b_this` to rest; `next` reaches
                // at most its own acceleration times that (`tpUpdateBlend`).
                let t_blend = b_this / tc.tangential_accel();
                b_this.min(b_next).min(next.tangential_accel() * t_blend)
            }
            Term::Stop | Term::Exact => 0.0,
        }
    }

    /// The path limits the planner gives the segment.
    pub fn limits(&self, tc: &Tc) -> Limits1 {
        Limits1 {
            v: self.max_target_vel(tc),
            a: tc.tangential_accel(),
            j: f64::INFINITY,
        }
    }
}

/// Outcome of `tpSetupTangent`.
enum Tangency {
    /// No blend (a stop, or an exact stop already set).
    Fail,
    /// Taken as tangent within the kink ratio.
    Tangent,
    /// Not tangent: try a blend.
    Blend,
}

/// `tc_blend_type_t`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum BlendKind {
    None,
    Parabolic,
    Tangent,
    Arc,
}
