//! The adaptive spiral: one continuous, curvature-continuous path per band of the pocket,
//! as long as the contour-parallel loops and without their stops.
//!
//! # The default morph ([`offsets`], `--morph offsets`)
//!
//! Let `h = min(s, 0.95·r)` (stepover `s`, tool radius `r`) and `d₀ = r + stock`. The loops
//! are the region's offsets at `d₀ + k·h` ([`super::loops`]), `k = 0` the walls' loop; every
//! point of loop `k + 1` is exactly `h` from loop `k`. They are the `offset` strategy's
//! loops, so the two cover a pocket the same way and the spiral is never longer than them
//! by more than its lane changes.
//!
//! 1. **Rounding** ([`rounding`]): every interior loop `X` is replaced by its opening `X_ρ`
//!    (erode by `ρ`, dilate by `ρ`; exact offsets): convex corners become arcs of radius `ρ`.
//!    `ρ` is the largest (bisection) that keeps, for every sample `y` of the rounded loop cut
//!    after it, `dist(y, X_ρ) ≤ max(g, dist(y, X) + ε)` with `g = 1.8·h` ([`offsets::CORNER_GAP`]),
//!    and keeps the loops inside it at least `h/4` inside. At a right-angle corner a loop can
//!    be rounded `(1.8 − √2)·h / (√2 − 1) ≈ 0.93·h` more than the loop outside it, so radii
//!    grow towards the middle. `1.8·h ≤ 1.71·r` stays below the tool's diameter: no ridge of
//!    material between passes. The engagement rises along the rounded corners (the feed
//!    modulation charges that). With `--arcs`, a loop no radius keeps within the bound (a
//!    cusp on the medial axis) gets a small fillet moving it in by at most `h/10`, so that
//!    arcs meet arcs tangentially.
//! 2. **Chains** ([`super::loops::OffsetLoops::chains`]): consecutive loops with nothing else
//!    attached are one band; L, T, U, star and crescent pockets are one chain, a neck that
//!    pinches the loops off or islands make several, cut innermost first, linked by a
//!    straight feed move where it is short and stays in the tool-centre region, else entered
//!    again (helix or ramp, then direct entries over cleared material). A leaf loop whose
//!    inside the loops it feeds reach anyway (each of its points within
//!    `reach − len/(2π)` of them) is not run round.
//! 3. **Lane changes** ([`lanes`]): each loop once round, then from `P_i` on loop `R_i` onto
//!    `R_{i+1}` over a window `D = min(6·h, L_i/4)`:
//!    `x(u) = a(u) + σ(u/D)·(b(u) − a(u))`, `σ(t) = 10t³ − 15t⁴ + 6t⁵`, `a(u) = R_i(P_i + u)`,
//!    `b(u)` its nearest point on `R_{i+1}` (followed along the loop, never jumping). `σ'` and
//!    `σ''` vanish at both ends: the path leaves and joins the loops with their tangent and
//!    curvature. The windows are stacked (`P_{i+1}` is the point of `R_{i+1}` nearest `P_i`),
//!    so each change runs `h` outside the previous one and the radial depth stays `h`; they
//!    are placed where the loops turn least. Where no change follows the loops (they differ
//!    too much there), a straight step joins them, as `offset` does.
//! 4. **Output**: interior loops' arcs as chords of sagitta ≤ 2 µm (at most 1 mm; with
//!    `--arcs` exact arcs, lane changes fitted with biarcs within [`ARC_TOLERANCE`]); the
//!    walls' loops exact, 5 µm ([`LAST_LOOP_MARGIN`]) inside, unless that drops a zero-width
//!    bridge or crosses another wall's clearance; the first chain led in from its helix by a
//!    tangent biarc.
//!
//! The paper's construction, a central spiral of radius `C·ρ_B` morphed into the walls
//! (`--morph fronts`, `--morph harmonic`, the transition `C`), is in [`classic`].

pub(crate) mod classic;
pub(crate) mod common;
pub(crate) mod fronts;
pub(crate) mod harmonic;
mod keep_inside;
pub(crate) mod lanes;
pub(crate) mod laps;
pub(crate) mod offsets;
pub(crate) mod ring;
pub(crate) mod rounding;
pub(crate) mod smooth;

use super::levels::LevelPlan;
use super::options::PocketOptions;
use super::shape::PocketShape;
use crate::error::InputError;
use crate::toolpath::Tool;

pub use super::options::SpiralMorph;
pub use common::{Construction, LAST_LOOP_MARGIN, SpiralStats, last_loop_margin};

/// The spiral strategy's plan for one level.
pub fn plan(
    shape: &PocketShape,
    tool: &Tool,
    opts: &PocketOptions,
) -> Result<LevelPlan, InputError> {
    plan_with_stats(shape, tool, opts).map(|(p, _)| p)
}

/// The plan and what was measured on the way.
pub fn plan_with_stats(
    shape: &PocketShape,
    tool: &Tool,
    opts: &PocketOptions,
) -> Result<(LevelPlan, SpiralStats), InputError> {
    if opts.spiral.morph == SpiralMorph::Offsets {
        let (plan, st) = offsets::plan(shape, tool, opts)?;
        let stats = SpiralStats {
            morph_laps: st.loops,
            chains: st.chains,
            max_loop_distance: st.max_radius,
            ..SpiralStats::default()
        };
        return Ok((plan, stats));
    }
    classic::plan(shape, tool, opts)
}
