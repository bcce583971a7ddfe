//! The adaptive planner's entries: where material is left that no pass reaches, a
//! racetrack along the ridge of the wall distance, a helix, or a ramp where neither fits
//! (see the parent module).

use super::{BLOCK, CutEntry, MIN_HELIX_RADII, Planner, RAMP_REACH};
use crate::geom::{Point, Vec2};
use crate::strategy::pocket::levels::Cut;
use crate::strategy::pocket::segments::Seg;
use crate::strategy::pocket::shape::PocketShape;

impl Planner<'_, '_> {
    /// An entry where material is left that no pass reaches, at the cells farthest from the
    /// walls whose tool disc is at least half material (a racetrack along them where they
    /// run along a line, else a helix at the one nearest their centroid), and the first pass
    /// from it; false when there is none.
    pub(super) fn new_helix(&mut self, shape: &PocketShape, clear: f64, helix: f64) -> bool {
        let st = self.stepper;
        let (nx, ny) = self.field.size();
        // At least half of the disc's cells: `n ≥ π r² / 2` for a count `n`.
        let half_disc =
            ((0.5 * (std::f64::consts::PI * (st.r / self.field.h).powi(2))).ceil() as u32).max(1);
        // Cells whose disc is at least half material, on a grid of blocks; of those within
        // a block of the largest wall distance, the one nearest their centroid (the middle of
        // a ridge of equal distances, not its end).
        let mut found: Vec<(f64, Point)> = Vec::new();
        let mut top: f64 = 0.0;
        let hc = self.field.h * BLOCK as f64;
        for j in (0..ny).step_by(BLOCK) {
            for i in (0..nx).step_by(BLOCK) {
                let w = self.field.wall_at(i, j);
                if w < st.walls.clear || w < top - hc {
                    continue;
                }
                let c = self.field.centre(i, j);
                if self.field.disc_holds_more_than(c, st.r, half_disc - 1) {
                    top = top.max(w);
                    found.push((w, c));
                }
            }
        }
        found.retain(|f| f.0 >= top - hc);
        if found.is_empty() {
            return false;
        }
        let n = found.len() as f64;
        let mid = found.iter().fold(Point::ORIGIN, |a, f| {
            Point::new(a.x + f.1.x / n, a.y + f.1.y / n)
        });
        let c = found
            .iter()
            .map(|f| f.1)
            .min_by(|a, b| a.distance(mid).total_cmp(&b.distance(mid)))
            .unwrap_or(mid);
        // The helix must fit: the exact distance to the walls decides.
        let room = shape.distance_to(c) - clear - 2.0 * self.field.h;
        // At most `r`: a wider helix or racetrack leaves a core of material inside it.
        let rho = helix.min(room).min(st.r).max(0.0);
        if rho < MIN_HELIX_RADII * st.r {
            return self.new_ramp(c);
        }
        let ridge: Vec<Point> = found.iter().map(|f| f.1).collect();
        let (head, p0, theta, entry) =
            match ridge_track(shape, clear + 2.0 * self.field.h, &ridge, rho, self.field.h) {
                Some((a, b)) => {
                    let u = (b - a) / a.distance(b);
                    let n = Vec2::new(-u.y, u.x) * (rho * st.side);
                    let head = vec![
                        Seg::line(a - n, b - n),
                        Seg::from_bulge(b - n, b + n, st.side),
                        Seg::line(b + n, a + n),
                        Seg::from_bulge(a + n, a - n, st.side),
                    ];
                    let len = head.iter().map(Seg::length).sum::<f64>();
                    let steps = ((a.distance(b) / self.field.h).ceil() as usize).max(1);
                    for k in 0..=steps {
                        self.field
                            .clear_disc(a.lerp(b, k as f64 / steps as f64), rho + st.r);
                    }
                    (head, a - n, u.y.atan2(u.x), CutEntry::Lap { len })
                }
                None => {
                    self.field.clear_disc(c, rho + st.r);
                    let entry = CutEntry::Helix {
                        center: c,
                        radius: rho,
                        flat_turn: true,
                    };
                    let theta = st.side * std::f64::consts::FRAC_PI_2;
                    (Vec::new(), c + Vec2::new(rho, 0.0), theta, entry)
                }
            };
        self.field.record();
        let (mut pts, _) = st.run(self.field, p0, theta);
        if pts.len() < 2 {
            pts = vec![p0, p0 + Vec2::new(theta.cos(), theta.sin()) * 1e-3];
        }
        let mut path = head;
        path.extend(self.fitted(&pts));
        self.field.undo();
        self.cut_along(&path);
        self.cuts.push(Cut { entry, path });
        self.pos = pts.last().copied();
        true
    }

    /// Where there is no room for a helix (a region barely wider than the tool): a ramp
    /// along the longest straight run of positions the tool centre may stand at on a line
    /// from `c` (16 headings, at most [`RAMP_REACH`] radii), cleared on the field. The
    /// material around `c` is marked cleared whatever is found, so the planner moves on (the
    /// verifier refuses a program that leaves it).
    fn new_ramp(&mut self, c: Point) -> bool {
        let (st, h) = (self.stepper, self.field.h);
        // The longest run of allowed positions (`h` apart) along each heading from `c`.
        let mut best: Option<(Point, Point, f64)> = None;
        for k in 0..16 {
            let a = std::f64::consts::TAU * f64::from(k) / 16.0;
            let u = Vec2::new(a.cos(), a.sin());
            let mut run: Option<(f64, f64)> = None;
            let mut t = 0.0;
            while t <= RAMP_REACH * st.r {
                match (st.walls.allows(self.field, c + u * t), run) {
                    (true, None) => run = Some((t, t)),
                    (true, Some((t0, _))) => run = Some((t0, t)),
                    (false, Some(_)) => break,
                    (false, None) => {}
                }
                t += h;
            }
            if let Some((t0, t1)) = run
                && best.is_none_or(|b| t1 - t0 > b.2)
            {
                best = Some((c + u * t0, c + u * t1, t1 - t0));
            }
        }
        // Marked cleared whatever is found: what a line cannot reach there is left to the
        // walls' loops (and the verifier), not tried again.
        self.field.clear_disc(c, st.r);
        self.given_up.push(c);
        // At least four cells and a step long (finer cells for a thin stepover do not make
        // room): shorter, the pocket layer finds none to ramp down a flute length in.
        let Some((from, end, len)) = best.filter(|b| b.2 >= (4.0 * h).max(st.delta)) else {
            return true;
        };
        let n = (len / st.delta).ceil() as usize;
        for k in 0..=n {
            self.field
                .clear_disc(from.lerp(end, k as f64 / n as f64), st.r);
        }
        self.cuts.push(Cut {
            entry: CutEntry::Ramp,
            path: vec![Seg::line(from, end)],
        });
        self.pos = Some(end);
        true
    }
}

/// A racetrack entry's axis along the ridge `ridge` (the cells nearest the top of the wall
/// distance): the ends of its principal axis, where that is longer than `2·rho` and every
/// point of it lies at least `clear + rho` from the walls; else `None` (a helix).
fn ridge_track(
    shape: &PocketShape,
    clear: f64,
    ridge: &[Point],
    rho: f64,
    h: f64,
) -> Option<(Point, Point)> {
    if ridge.len() < 2 || rho <= 0.0 {
        return None;
    }
    let n = ridge.len() as f64;
    let c = ridge.iter().fold(Point::ORIGIN, |a, p| {
        Point::new(a.x + p.x / n, a.y + p.y / n)
    });
    let (mut sxx, mut sxy, mut syy) = (0.0, 0.0, 0.0);
    for p in ridge {
        let d = *p - c;
        sxx += d.x * d.x;
        sxy += d.x * d.y;
        syy += d.y * d.y;
    }
    let ang = 0.5 * (2.0 * sxy).atan2(sxx - syy);
    let u = Vec2::new(ang.cos(), ang.sin());
    let (lo, hi) = ridge
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            let t = (*p - c).dot(u);
            (lo.min(t), hi.max(t))
        });
    if hi - lo < 2.0 * rho {
        return None;
    }
    let (a, b) = (c + u * lo, c + u * hi);
    let steps = ((hi - lo) / h).ceil() as usize;
    (0..=steps)
        .all(|k| shape.distance_to(a.lerp(b, k as f64 / steps as f64)) >= clear + rho)
        .then_some((a, b))
}
