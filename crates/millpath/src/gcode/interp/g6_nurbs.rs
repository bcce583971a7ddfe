//! LinuxCNC's `G6.2` NURBS (LinuxCNC master; 2.9 refuses G6.2), read as the true curve: a
//! polyline on the NURBS within [`super::nurbs::CHORD_TOLERANCE_MM`], evaluated by the same
//! de Boor evaluator as G5.2 but over the program's own knots.
//!
//! # The blocks (LinuxCNC master, `interp_convert.cc` `convert_nurbs`, mode `G_6_2`)
//! ```text
//! G6.2 X63.562 Y106.120 R1 K0 P3 Q1     first entry: order P and method Q (1..3)
//!      X64.124 Y106.120 R1 K0           entry: control point, weight R > 0, knot K
//!      …
//! G6.2 K14                              knot-only entries close the knot vector
//! ```
//! Every block in G6.2 mode with the plane's two axis words (G17: X Y, G18: Z X, G19: Y Z)
//! or a K adds an *entry* (point, weight R, knot K). The entries' K values are the knot
//! vector; the first `n + 1 = entries − P` entries are the control points. The curve ends
//! (and is cut) on the entry whose K equals the K of the entry P − 1 before it (the last P
//! knots equal, a clamped end); after it no motion mode is in effect, as after G5.3.
//! Coordinates are found as for any move (G91: relative to where the tool was when the curve
//! began; LinuxCNC does not move the tool until the curve is complete).
//!
//! # The curve
//! Order k = P, knots t₀ ≤ … ≤ t_{n+k}, control points Pᵢ with weights Rᵢ: C(u) =
//! Σ Nᵢₖ(u) Rᵢ Pᵢ / Σ Nᵢₖ(u) Rᵢ for u in [t_{k−1}, t_{n+1}]. LinuxCNC's canon layer
//! (`emccanon.cc` `NURBS_G6_FEED`) first feeds in a straight line to C(t₀), then follows the
//! curve with lines (Q3, NICL), arcs (Q2, NICC) or biarcs (Q1, NICU) sampled at constant
//! arc length or parameter; all three approximate C. The reader follows C itself within the
//! chord tolerance whatever Q is, so the times of Q1–Q3 are the same here.
//!
//! # Refused (with the word and line)
//! A start that is not clamped (the first P knots not all equal: LinuxCNC evaluates the
//! curve outside its domain there), decreasing knots, control-point entries without K or
//! without a weight R > 0, a knot-only entry among the control points, fewer control points
//! than the order, an order outside 2..=[`MAX_ORDER`], the plane's normal axis word, G53,
//! polar words, inverse-time feed (G93), another motion code before the curve is complete.
//!
//! # Differences from LinuxCNC master
//! After a G6.2 curve in G18/G19 LinuxCNC master sets its interpreter position from the
//! curve's plane coordinates as if they were X and Y (`convert_nurbs`); the machine is at the
//! curve's end. The reader takes the machine's position (the curve's end in its plane), which
//! the repository's G18/G19 programs make moot by giving all axes in the next move.

use super::nurbs::axis_letter;
use super::{Block, BlockError, FeedMode, ReadMove, State, plane_axes};
use crate::toolpath::Plane;

/// Highest order (P) accepted: far above the 6 of LinuxCNC's programs, low enough that
/// de Boor's algorithm stays cheap.
pub(crate) const MAX_ORDER: usize = 20;

/// One entry: the point in the plane (program mm), its weight (None on knot-only entries)
/// and its knot.
#[derive(Debug, Clone, Copy)]
struct Entry {
    u: f64,
    v: f64,
    weight: Option<f64>,
    knot: f64,
}

/// A G6.2 curve being read.
#[derive(Debug, Clone)]
pub(crate) struct G6State {
    entries: Vec<Entry>,
    order: usize,
    plane: Plane,
}

impl State {
    /// Whether a G6.2 curve is open (entries read, not yet complete).
    pub(crate) fn g6_open(&self) -> bool {
        self.g6.is_some()
    }

    /// A block in G6.2 mode: adds its entry, and moves along the curve once it is complete.
    pub(crate) fn g6_block(
        &mut self,
        b: &mut Block,
        axes: [Option<f64>; 3],
        line: usize,
        out: &mut Vec<ReadMove>,
    ) -> Result<(), BlockError> {
        let plane = self.modal.plane;
        let (ua, va, na) = plane_axes(plane);
        let words = |l: u8| {
            b.words
                .get(super::letter_index(l))
                .copied()
                .flatten()
                .is_some()
        };
        if axes.iter().all(Option::is_none)
            && !b"KPQR".iter().any(|&l| words(l))
            && b.leftover().is_none()
        {
            // A block without the curve's words (F, S, a comment): nothing to add.
            return Ok(());
        }
        let (p, q, r, k) = (b.take(b'P'), b.take(b'Q'), b.take(b'R'), b.take(b'K'));
        let expected = "G6.2 with the plane's two axis words (G17: X Y, G18: Z X, G19: Y Z), \
                        R (weight), K (knot), P (order) and Q (1..3) in the first block";
        if let Some(n) = axes.get(na).copied().flatten() {
            return Err(BlockError::unsupported(
                format!("G6.2 with {}{n}", axis_letter(na)),
                expected,
            ));
        }
        if let Some((letter, v)) = b.leftover() {
            return Err(BlockError::unsupported(
                format!("{}{v} in a G6.2 block", char::from(letter)),
                expected,
            ));
        }
        if self.modal.feed_mode != FeedMode::PerMinute || !self.feed.is_some_and(|f| f > 0.0) {
            return Err(BlockError::new(
                "G6.2",
                "without a feed",
                "an F > 0 in G94 before a NURBS",
            ));
        }
        let (x, y) = (
            axes.get(ua).copied().flatten(),
            axes.get(va).copied().flatten(),
        );
        if x.is_some() != y.is_some() {
            return Err(BlockError::new(
                "G6.2",
                format!("{} without {}", axis_letter(ua), axis_letter(va)),
                "both axis words of the plane for a control point",
            ));
        }
        if let Some(c) = &self.g6
            && c.plane != plane
        {
            return Err(BlockError::new(
                "G6.2",
                "a plane change inside the curve",
                "one plane (G17, G18 or G19) for the whole G6.2 curve",
            ));
        }
        if self.g6.is_none() {
            let Some(p) = p else {
                return Err(BlockError::new(
                    "G6.2",
                    "without P",
                    "the order P in the first G6.2 block",
                ));
            };
            if q.is_none() {
                return Err(BlockError::new(
                    "G6.2",
                    "without Q",
                    "the method Q (1, 2 or 3) in the first G6.2 block",
                ));
            }
            self.g6 = Some(G6State {
                entries: Vec::new(),
                order: order(p)?,
                plane,
            });
        } else if let Some(p) = p {
            let o = order(p)?;
            if let Some(c) = self.g6.as_mut() {
                c.order = o;
            }
        }
        if let Some(q) = q
            && !(q.fract() == 0.0 && (1.0..=3.0).contains(&q))
        {
            return Err(BlockError::new("G6.2 Q", q, "1, 2 or 3"));
        }
        if x.is_none() && k.is_none() {
            return Ok(());
        }
        let Some(knot) = k else {
            return Err(BlockError::new(
                "G6.2",
                "a control point without K",
                "a knot K on every G6.2 control point",
            ));
        };
        let weight = match (x, r) {
            (None, _) => None,
            (Some(_), Some(r)) if r > 0.0 => Some(r),
            (Some(_), r) => {
                return Err(BlockError::new(
                    "G6.2 R",
                    format!("{r:?}"),
                    "a weight R > 0 on every G6.2 control point",
                ));
            }
        };
        let unit = self.unit();
        let here = self.program_mm();
        let coord = |k: usize, v: Option<f64>| {
            let c = here.get(k).copied().unwrap_or(0.0);
            match v {
                Some(v) if self.modal.absolute => v * unit,
                Some(v) => c + v * unit,
                None => c,
            }
        };
        let entry = Entry {
            u: coord(ua, x),
            v: coord(va, y),
            weight,
            knot,
        };
        let Some(curve) = self.g6.as_mut() else {
            return Ok(());
        };
        if let Some(last) = curve.entries.last()
            && knot < last.knot
        {
            return Err(BlockError::new(
                "G6.2 K",
                knot,
                format!(
                    "knots that do not decrease (the previous K is {})",
                    last.knot
                ),
            ));
        }
        curve.entries.push(entry);
        let n = curve.entries.len();
        let k = curve.order;
        // The knots do not decrease, so "the K P − 1 entries back is not below this one"
        // is LinuxCNC's exact equality of the last P knots.
        let complete = n > k && curve.entries.get(n - k).is_some_and(|e| e.knot >= knot);
        if complete && let Some(curve) = self.g6.take() {
            self.g6_emit(&curve, line, out)?;
            self.motion = None;
        }
        Ok(())
    }

    /// The moves of a complete curve: a line to its start, then the curve.
    fn g6_emit(
        &mut self,
        curve: &G6State,
        line: usize,
        out: &mut Vec<ReadMove>,
    ) -> Result<(), BlockError> {
        let k = curve.order;
        let count = curve.entries.len() - k;
        if count < k {
            return Err(BlockError::new(
                "G6.2",
                format!("{count} control points"),
                format!("at least as many control points as the order P = {k}"),
            ));
        }
        let mut cp = Vec::with_capacity(count);
        for (i, e) in curve.entries.iter().take(count).enumerate() {
            let Some(w) = e.weight else {
                return Err(BlockError::new(
                    "G6.2",
                    format!("the knot-only entry {} (K{})", i + 1, e.knot),
                    format!(
                        "control points (axis words and R) on the first {count} entries, \
                         knot-only entries (K) only on the last {k}"
                    ),
                ));
            };
            cp.push((e.u, e.v, w));
        }
        let t: Vec<f64> = curve.entries.iter().map(|e| e.knot).collect();
        let (t0, tk) = (t.first().copied(), t.get(k - 1).copied());
        if t0 != tk {
            return Err(BlockError::new(
                "G6.2 K",
                format!("{t0:?} … {tk:?}"),
                format!("a clamped start: the first P = {k} knots equal"),
            ));
        }
        if t.get(k - 1) >= t.get(count) {
            return Err(BlockError::new(
                "G6.2 K",
                "an empty knot span",
                "knots whose domain t[P−1] … t[n+1] has a length",
            ));
        }
        // LinuxCNC feeds to the curve's start first (left out here when the tool is there).
        let (ua, va, _) = plane_axes(curve.plane);
        let here = self.program_mm();
        if let Some(&(u, v, _)) = cp.first()
            && (here.get(ua) != Some(&u) || here.get(va) != Some(&v))
        {
            self.push_curve(&[(u, v)], curve.plane, line, out);
        }
        let uv = super::nurbs::polyline(&cp, k, &t);
        self.push_curve(&uv, curve.plane, line, out);
        Ok(())
    }
}

/// The order P: an integer 2..=MAX_ORDER.
fn order(p: f64) -> Result<usize, BlockError> {
    if p.fract() != 0.0 || !(2.0..=MAX_ORDER as f64).contains(&p) {
        return Err(BlockError::new(
            "G6.2 P",
            p,
            format!("an integer order from 2 to {MAX_ORDER}"),
        ));
    }
    Ok(p as usize)
}
