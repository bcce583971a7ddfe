//! Rest machining: a smaller tool cuts only the material a previous program left in a pocket.
//!
//! **The material left.** The pocket's region `F` (inside the outer wall, outside the
//! islands) is rasterised at a cell `c`; every feed move of the previous program at the
//! floor (`z ≤ floor + z_tol`) clears the cells within `R − c` of it (`R` its tool's radius;
//! one cell less than it swept, so that rounding never hides material). A flat end mill at
//! the floor clears the whole column above the floor where it passes, so what is left at the
//! floor is all that is left at any level above it. Moves above the floor are not counted:
//! the material they cleared was cleared again at the floor, or is counted as left (cut
//! again, never missed).
//!
//! **The passes.** The rest tool (radius `r`) follows the offsets of `F`'s walls at
//! `d_k = r + ε + k·s` (`s` the stepover, `ε` = [`WALL_BAND`]), from the largest `d_k` at
//! which material is still within reach down to the walls' own offset (`k = 0`): each pass
//! cuts from the cleared side towards the wall, so the tool meets the material a stepover at a
//! time. Along each offset loop, sampled every `h = min(2c, r/4)`, a sample **cuts** when it
//! lies in the pocket at `d_k` from its walls (within [`LOOP_SLACK`]) and a material cell lies
//! within `r − c` of it; the
//! loop is cut over the runs of cutting samples, each lengthened by [`RUN_EXTENSION`] tool
//! radii at either end (the tool enters and leaves in cleared space), as exact pieces of the
//! offset's lines and arcs. After a pass its runs clear the raster, so that an inner pass's
//! work is not repeated by the next.
//!
//! **Links.** Between runs at most [`LOW_LINK_MAX`] tool diameters apart the tool stays at
//! its level, lifted by `lift`, and feeds straight to the next run where the segment keeps
//! `r` from the walls (its exact clearance) and `r − c` from every cell of the material left
//! (the initial rest, so at any level); else it retracts to the safe height.
//! Each level (the step-down's, as the pocket's) repeats the runs. A run that starts in
//! material the previous tool never reached (a slot narrower than it) is entered by a ramp
//! at `ramp_angle`, back and forth along its first stretch, from the level above (cleared by
//! the same run there).
//!
//! **What is checked elsewhere.** The generator trusts no one: the job layer simulates the
//! previous program and this one on the whole-job height field (`stock::HeightField`, its own
//! sweep of the tool, not this raster) and refuses the pair if anything the rest tool could
//! reach is left, or if a wall is cut.

use super::pocket::PocketShape;
use crate::error::{Error, InputError, require_positive};
use crate::geom::{Outline, Point, Point3};
use crate::stock::raster::Raster;
use crate::strategy::contour::leads::layer_depths;
use crate::toolpath::{Move, MoveKind, Tool, Toolpath};
use cavalier_contours::polyline::{PlineSource, seg_arc_radius_and_center};

/// How far inside its exact offset the rest tool's walls loop is cut, mm (as the pockets'
/// walls loop: the written program's rounding never brings it closer than the tool radius).
pub const WALL_BAND: f64 = 0.005;

/// The longest link made at the lifted height, in tool diameters: farther, a retract and a
/// rapid are quicker than the feed.
pub const LOW_LINK_MAX: f64 = 4.0;

/// How far from its distance a sample of an offset loop may lie and still be followed, mm.
pub const LOOP_SLACK: f64 = 0.001;

/// How far each run of a pass is lengthened at either end, in tool radii: past the last
/// sample whose disc meets material, so that the tool enters and leaves where it cuts
/// nothing, and no farther (the pass cuts only what was left).
pub const RUN_EXTENSION: f64 = 1.0;

/// The rest pass's settings. Built from [`Default`] with the `with_*` methods; checked by
/// [`RestOptions::validate`].
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct RestOptions {
    /// Top of the stock, mm.
    pub top_z: f64,
    /// Depth of the pocket below the top, mm.
    pub depth: f64,
    /// Step-down between levels, mm.
    pub step_down: f64,
    /// Distance between passes, as a fraction of the rest tool's diameter.
    pub stepover: f64,
    /// Cutting feed, mm/s.
    pub feed: f64,
    /// Plunge feed, mm/s.
    pub plunge_feed: f64,
    /// Safe height above the top for rapids, mm.
    pub safe_height: f64,
    /// Lift above the level for links through cleared material, mm.
    pub lift: f64,
    /// Angle of the ramp down into a run that starts in material left, rad.
    pub ramp_angle: f64,
    /// The raster's cell, mm (`None`: a twentieth of the rest tool's radius, at most 0.05).
    pub cell: Option<f64>,
    /// Height above the floor within which a previous move counts as cutting the floor, mm.
    pub z_tolerance: f64,
}

impl Default for RestOptions {
    fn default() -> Self {
        RestOptions {
            top_z: 0.0,
            depth: 5.0,
            step_down: 5.0,
            stepover: 0.4,
            feed: 20.0,
            plunge_feed: 5.0,
            safe_height: 5.0,
            lift: 0.5,
            ramp_angle: 3f64.to_radians(),
            cell: None,
            z_tolerance: 0.01,
        }
    }
}

option_builders! {
    RestOptions;
    /// Sets [`RestOptions::top_z`], mm.
    with_top_z => top_z: f64;
    /// Sets [`RestOptions::depth`], mm.
    with_depth => depth: f64;
    /// Sets [`RestOptions::step_down`], mm.
    with_step_down => step_down: f64;
    /// Sets [`RestOptions::stepover`] (fraction of the diameter).
    with_stepover => stepover: f64;
    /// Sets [`RestOptions::feed`], mm/s.
    with_feed => feed: f64;
    /// Sets [`RestOptions::plunge_feed`], mm/s.
    with_plunge_feed => plunge_feed: f64;
    /// Sets [`RestOptions::safe_height`], mm.
    with_safe_height => safe_height: f64;
    /// Sets [`RestOptions::lift`], mm.
    with_lift => lift: f64;
    /// Sets [`RestOptions::ramp_angle`], rad.
    with_ramp_angle => ramp_angle: f64;
}

impl RestOptions {
    /// Sets [`RestOptions::cell`], mm.
    #[must_use]
    pub fn with_cell(mut self, cell: f64) -> Self {
        self.cell = Some(cell);
        self
    }

    /// Checks every value; errors name it.
    pub fn validate(&self) -> Result<(), InputError> {
        let at = "rest machining";
        require_positive("depth", self.depth, at)?;
        require_positive("step down", self.step_down, at)?;
        require_positive("feed", self.feed, at)?;
        require_positive("plunge feed", self.plunge_feed, at)?;
        require_positive("safe height", self.safe_height, at)?;
        if !(self.stepover > 0.0 && self.stepover <= 1.0) {
            return Err(InputError::new("stepover", self.stepover)
                .at(at)
                .expected("a fraction of the tool's diameter in (0, 1]"));
        }
        if !(self.ramp_angle > 0.0 && self.ramp_angle <= std::f64::consts::FRAC_PI_2) {
            return Err(InputError::new("ramp angle", self.ramp_angle)
                .at(at)
                .expected("an angle in (0, 90°]"));
        }
        if !(self.lift.is_finite() && self.lift >= 0.0) {
            return Err(InputError::new("lift", self.lift)
                .at(at)
                .expected("a height >= 0 mm"));
        }
        if !self.top_z.is_finite() {
            return Err(InputError::new("top z", self.top_z)
                .at(at)
                .expected("a finite height"));
        }
        if let Some(c) = self.cell {
            require_positive("cell", c, at)?;
        }
        Ok(())
    }
}

/// What [`generate`] made.
#[derive(Debug, Clone)]
pub struct RestResult {
    /// The rest tool's moves.
    pub toolpath: Toolpath,
    /// The material the previous program left within the rest tool's reach, mm² (before).
    pub left_mm2: f64,
    /// The material still there after the rest pass, by the generator's raster, mm².
    pub after_mm2: f64,
    /// Runs cut per level.
    pub runs: usize,
    /// Length of the runs per level, mm.
    pub run_length_mm: f64,
}

/// A cut along one stretch of an offset loop.
struct Run {
    moves: Vec<Move>,
    start: Point,
    end: Point,
}

/// The sampling step along loops for a cell `c` and tool radius `r`, mm.
fn sample_step(c: f64, r: f64) -> f64 {
    (2.0 * c).min(0.25 * r)
}

/// The moves of a closed outline at height 0, one per segment, from its first vertex.
fn loop_moves(o: &Outline) -> (Point3, Vec<Move>) {
    let pl = o.polyline();
    let v0 = pl.at(0);
    let start = Point3::new(v0.x, v0.y, 0.0);
    let moves = pl
        .iter_segments()
        .map(|(a, b)| {
            let to = Point3::new(b.x, b.y, 0.0);
            if a.bulge_is_zero() {
                Move::line(to, 1.0)
            } else {
                let (_, c) = seg_arc_radius_and_center(a, b);
                Move::arc_xy(to, Point3::new(c.x, c.y, 0.0), a.bulge > 0.0, 1.0)
            }
        })
        .collect();
    (start, moves)
}

/// The previous program's floor moves cleared from `raster` (module docs).
fn clear_previous(raster: &mut Raster, previous: &Toolpath, floor: f64, opts: &RestOptions) {
    let c = raster.cell();
    let r = previous.tool.radius() - c;
    if r <= 0.0 {
        return;
    }
    let zmax = floor + opts.z_tolerance;
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
            raster.clear_capsule(a, b, r);
            a = b;
        }
    }
}

/// The runs of one offset loop at which the tool reaches material (module docs).
fn runs_of(o: &Outline, shape: &PocketShape, d: f64, raster: &Raster, r: f64, h: f64) -> Vec<Run> {
    let c = raster.cell();
    let (start, moves) = loop_moves(o);
    let mut froms = Vec::with_capacity(moves.len());
    let mut lens = Vec::with_capacity(moves.len());
    let mut p = start;
    for m in &moves {
        froms.push(p);
        lens.push(m.length_from(p));
        p = m.to;
    }
    let total: f64 = lens.iter().sum();
    if total <= 0.0 {
        return Vec::new();
    }
    let n = ((total / h).ceil() as usize).max(8);
    let step = total / n as f64;
    let at = |s: f64| -> Point {
        let mut s = s.rem_euclid(total);
        for (k, m) in moves.iter().enumerate() {
            if s <= lens[k] || k + 1 == moves.len() {
                return m.point_at(froms[k], s).xy();
            }
            s -= lens[k];
        }
        start.xy()
    };
    // A sample is on the loop where it lies in the pocket at `d` from its walls (an offset
    // loop that strays, as one can at a sharp tip, is not followed there), and it cuts where
    // material left lies within `r − c` of it.
    let pts: Vec<Point> = (0..n).map(|k| at(step * k as f64)).collect();
    let valid: Vec<bool> = pts
        .iter()
        .map(|&p| shape.contains(p) && (shape.distance_to(p) - d).abs() <= LOOP_SLACK)
        .collect();
    let cuts: Vec<bool> = (0..n)
        .map(|k| valid[k] && raster.count_disc(pts[k], r - c) > 0)
        .collect();
    if !cuts.iter().any(|&b| b) {
        return Vec::new();
    }
    // Runs of cutting samples as index intervals [i0, i1] (i1 may pass n: the loop wraps),
    // lengthened over valid samples by the extension.
    let ext = ((RUN_EXTENSION * r) / step).ceil() as isize + 1;
    let ni = n as isize;
    let ok = |i: isize| valid[i.rem_euclid(ni) as usize];
    let mut intervals: Vec<(isize, isize)> = Vec::new();
    if cuts.iter().all(|&b| b) {
        intervals.push((0, ni));
    } else {
        let first = cuts.iter().position(|&b| !b).unwrap_or(0) as isize;
        let mut k: isize = 0;
        while k < ni {
            if !cuts[(first + k).rem_euclid(ni) as usize] {
                k += 1;
                continue;
            }
            let i0 = first + k;
            while k < ni && cuts[(first + k).rem_euclid(ni) as usize] {
                k += 1;
            }
            let i1 = first + k - 1;
            let mut a = i0;
            while i0 - a < ext && ok(a - 1) && a - 1 > i1 - ni {
                a -= 1;
            }
            let mut b = i1;
            while b - i1 < ext && ok(b + 1) && b + 1 < a + ni {
                b += 1;
            }
            intervals.push((a, b));
        }
        // Lengthened runs that now overlap become one.
        let mut merged: Vec<(isize, isize)> = Vec::new();
        for iv in intervals {
            match merged.last_mut() {
                Some(last) if iv.0 <= last.1 + 1 => last.1 = last.1.max(iv.1),
                _ => merged.push(iv),
            }
        }
        if merged.len() > 1 {
            let (f, l) = (merged[0], merged[merged.len() - 1]);
            if l.1 + 1 >= f.0 + ni {
                merged[0] = (l.0, f.1 + ni);
                merged.pop();
            }
        }
        intervals = merged
            .into_iter()
            .map(|(a, b)| if b >= a + ni { (a, a + ni) } else { (a, b) })
            .collect();
    }
    let intervals: Vec<(f64, f64)> = intervals
        .into_iter()
        .map(|(a, b)| (a as f64 * step, b as f64 * step))
        .collect();
    intervals
        .into_iter()
        .map(|(s0, s1)| {
            let mut out = Vec::new();
            // Walk the loop (twice over, for a wrapping run) and keep the pieces in [s0, s1].
            let base = s0.div_euclid(total) * total;
            let mut acc = base;
            'outer: for _ in 0..3 {
                for (k, m) in moves.iter().enumerate() {
                    let (a, b) = (acc, acc + lens[k]);
                    acc = b;
                    if b <= s0 {
                        continue;
                    }
                    if a >= s1 {
                        break 'outer;
                    }
                    let (t0, t1) = ((s0 - a).max(0.0), (s1 - a).min(lens[k]));
                    if t1 - t0 > 1e-9 {
                        out.push(m.piece(froms[k], t0, t1));
                    }
                }
            }
            Run {
                start: at(s0),
                end: at(s1),
                moves: out,
            }
        })
        .collect()
}

/// `m` (from `from`) moved to run from `from` to `to` in height, linearly in length.
fn at_heights(m: &Move, z: f64) -> Move {
    let mut m = *m;
    m.to.z = z;
    if let MoveKind::Arc { center, .. } = &mut m.kind {
        center.z = z;
    }
    m
}

/// `m` (from `from`) run backwards: from its end to `from`.
fn reversed(m: &Move, from: Point3) -> Move {
    let mut r = *m;
    r.to = from;
    if let MoveKind::Arc { ccw, .. } = &mut r.kind {
        *ccw = !*ccw;
    }
    r
}

/// The ramp into a run from `z_from` down to `z`: back and forth along the run's first
/// stretch (at most `stretch` long) at `angle`, ending at the run's start at `z`; then the
/// run is cut from there at `z`. Moves at `feed`.
fn ramp_into(run: &Run, z_from: f64, z: f64, stretch: f64, angle: f64, feed: f64) -> Vec<Move> {
    // The stretch's pieces, from the run's start.
    let mut pieces: Vec<(Point3, Move)> = Vec::new();
    let mut from = Point3::from_xy(run.start, 0.0);
    let mut acc = 0.0;
    for m in &run.moves {
        let len = m.length_from(from);
        if len <= 0.0 {
            continue;
        }
        let take = (stretch - acc).min(len);
        pieces.push((from, m.piece(from, 0.0, take)));
        acc += take;
        from = m.to;
        if acc >= stretch - 1e-9 {
            break;
        }
    }
    let out_len: f64 = pieces.iter().map(|(f, m)| m.length_from(*f)).sum();
    if out_len <= 1e-6 {
        return vec![Move::line(Point3::from_xy(run.start, z), feed)];
    }
    let drop = (z_from - z).max(0.0);
    let per_len = angle.tan();
    // Whole back-and-forth trips: out along the stretch, back to the start.
    let trips = (drop / (2.0 * out_len * per_len)).ceil().max(1.0);
    let slope = drop / (2.0 * trips * out_len);
    let mut moves = Vec::new();
    let mut zc = z_from;
    for _ in 0..trips as usize {
        for (f, m) in &pieces {
            zc -= m.length_from(*f) * slope;
            let mut mm = at_heights(m, zc.max(z));
            mm.feed = feed;
            moves.push(mm);
        }
        for (f, m) in pieces.iter().rev() {
            zc -= m.length_from(*f) * slope;
            let mut mm = at_heights(&reversed(m, *f), zc.max(z));
            mm.feed = feed;
            moves.push(mm);
        }
    }
    moves
}

/// Clears from `raster` what a run cuts (radius `r`, sampled every `h`).
fn clear_run(raster: &mut Raster, run: &Run, r: f64, h: f64) {
    let mut from = Point3::from_xy(run.start, 0.0);
    for m in &run.moves {
        let len = m.length_from(from);
        let n = ((len / h).ceil() as usize).max(1);
        let mut a = from.xy();
        for k in 1..=n {
            let b = m.point_at(from, len * k as f64 / n as f64).xy();
            raster.clear_capsule(a, b, r);
            a = b;
        }
        from = m.to;
    }
}

/// The rest pass of `tool` in `shape` after the `previous` program (module docs). Errors:
/// options out of range (named), a rest tool no smaller than the previous one.
pub fn generate(
    shape: &PocketShape,
    previous: &Toolpath,
    tool: &Tool,
    opts: &RestOptions,
) -> Result<RestResult, Error> {
    opts.validate()?;
    let r = tool.radius();
    if tool.diameter >= previous.tool.diameter {
        return Err(InputError::new("rest tool diameter", tool.diameter)
            .at("rest machining")
            .expected(format!(
                "a tool smaller than the previous program's ({} mm)",
                previous.tool.diameter
            ))
            .into());
    }
    let c = opts.cell.unwrap_or((r / 20.0).min(0.05));
    let h = sample_step(c, r);
    let floor = opts.top_z - opts.depth;
    let mut raster = Raster::new(shape.outer.bounds(), c);
    let walls: Vec<_> = shape.loops().map(Outline::polyline).collect();
    raster.fill(&walls);
    clear_previous(&mut raster, previous, floor, opts);
    // Only what the rest tool can reach counts: cells within r of a point r from the walls.
    let d0 = r + WALL_BAND;
    let reach = shape.offset_loops(d0);
    let reachable = |p: Point| -> bool {
        reach.iter().any(|o| o.distance_to(p) <= r - c)
            || (shape.distance_to(p) >= d0 && shape.contains(p))
    };
    let cells: Vec<Point> = raster.material_cells().collect();
    let mut dmax: f64 = 0.0;
    let mut left = 0usize;
    for &p in &cells {
        if reachable(p) {
            left += 1;
            dmax = dmax.max(shape.distance_to(p));
        }
    }
    let initial = raster.clone();
    let s = opts.stepover * tool.diameter;
    let kmax = ((dmax + r - d0) / s).ceil().max(0.0) as usize;
    let mut runs: Vec<Run> = Vec::new();
    for k in (0..=kmax).rev() {
        let d = d0 + k as f64 * s;
        let mut pass: Vec<Run> = Vec::new();
        for o in shape.offset_loops(d) {
            pass.extend(runs_of(&o, shape, d, &raster, r, h));
        }
        for run in &pass {
            clear_run(&mut raster, run, r, h);
        }
        runs.extend(pass);
    }
    let after = raster.material_cells().filter(|&p| reachable(p)).count();
    // Order: each pass inwards-out as made; within the whole, nearest next run first among
    // those of the same pass is kept by their order of making (passes from the inside out).
    let safe = opts.top_z + opts.safe_height;
    let mut tp = Toolpath::new(*tool, Point3::new(0.0, 0.0, safe));
    // A link keeps `r` from the walls (the exact clearance of the straight move) and does not
    // meet the material left (within `r − c`, as a run's samples: sampled every `h`).
    let spec = crate::stock::StockSpec {
        outer: &shape.outer,
        islands: &shape.islands,
        wall_stock: 0.0,
    };
    let link_clear = |a: Point, b: Point| -> bool {
        let len = a.distance(b);
        if len > LOW_LINK_MAX * tool.diameter {
            return false;
        }
        let n = ((len / h).ceil() as usize).max(1);
        let mut probe = Toolpath::new(*tool, Point3::from_xy(a, -1.0));
        probe.push(Move::line(Point3::from_xy(b, -1.0), opts.feed));
        crate::stock::min_clearance(&probe, spec).distance >= r + 0.5 * WALL_BAND
            && (0..=n).all(|k| {
                let p = a.lerp(b, k as f64 / n as f64);
                shape.contains(p) && initial.count_disc(p, r - c) == 0
            })
    };
    let mut run_length = 0.0;
    let mut z_prev = opts.top_z;
    for z in layer_depths(opts.top_z, opts.depth, opts.step_down) {
        let lifted = z + opts.lift;
        let mut here: Option<Point> = None;
        for run in &runs {
            match here {
                Some(p) if link_clear(p, run.start) => {
                    tp.push(Move::line(Point3::from_xy(p, lifted), opts.plunge_feed));
                    tp.push(Move::line(Point3::from_xy(run.start, lifted), opts.feed));
                }
                _ => {
                    if tp.end().z < safe {
                        tp.push(Move::rapid(Point3::from_xy(tp.end().xy(), safe)));
                    }
                    tp.push(Move::rapid(Point3::from_xy(run.start, safe)));
                    // Where the tool's disc at the run's start holds no material left, the
                    // column above it is cleared down to the floor; else down to the level
                    // above, which this pass cleared.
                    let down = if initial.count_disc(run.start, r - c) > 0 {
                        z_prev.min(opts.top_z) + opts.lift
                    } else {
                        lifted
                    };
                    tp.push(Move::rapid(Point3::from_xy(run.start, down)));
                }
            }
            if initial.count_disc(run.start, r - c) > 0 {
                // The run starts in material the previous tool never reached: ramp down
                // from the level above (this pass cleared it there) along the run.
                let z_from = z_prev.min(opts.top_z);
                tp.push(Move::line(
                    Point3::from_xy(run.start, z_from),
                    opts.plunge_feed,
                ));
                let stretch = (4.0 * tool.diameter).max(2.0);
                for m in ramp_into(run, z_from, z, stretch, opts.ramp_angle, opts.feed) {
                    tp.push(m);
                }
            } else {
                tp.push(Move::line(Point3::from_xy(run.start, z), opts.plunge_feed));
            }
            let mut from = Point3::from_xy(run.start, z);
            for m in &run.moves {
                let mut m = at_heights(m, z);
                m.feed = opts.feed;
                run_length += m.length_from(from);
                from = m.to;
                tp.push(m);
            }
            here = Some(run.end);
        }
        z_prev = z;
    }
    if tp.end().z < safe {
        tp.push(Move::rapid(Point3::from_xy(tp.end().xy(), safe)));
    }
    let levels = layer_depths(opts.top_z, opts.depth, opts.step_down)
        .len()
        .max(1);
    let cell_area = c * c;
    Ok(RestResult {
        toolpath: tp,
        left_mm2: left as f64 * cell_area,
        after_mm2: after as f64 * cell_area,
        runs: runs.len(),
        run_length_mm: run_length / levels as f64,
    })
}
