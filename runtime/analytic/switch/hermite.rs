//! A start for the refinement of a bracketed switch from what the bracket already knows: the
//! cubic Hermite interpolant of g on [a, b] from g and g' at both ends, and its root. Its error
//! is O(L⁴ max|g''''|/384) on a bracket of length L — about 1e-11 in g for a contact sub-step of
//! 1e-3 with contact frequencies near 6 — so one Newton step on the closed form from it
//! converges to rounding: one or two closed-form evaluations instead of the three to eight
//! Newton and secant steps from an end. Used where a caller opts in (`Budget::hermite_start`):
//! the refined switch is the same to rounding, not to the bit.

use crate::refine::{Knot, Refinement, refine};

/// The root in (0, 1) of the cubic Hermite interpolant with values `g0` ≤ 0 < `g1` and
/// (scaled) slopes `d0`, `d1` at 0 and 1, by the one refinement ([`crate::refine`]) on the
/// cubic; `None` when the data are not finite.
pub(super) fn root(g0: f64, d0: f64, g1: f64, d1: f64) -> Option<f64> {
    if !(g0.is_finite() && d0.is_finite() && g1.is_finite() && d1.is_finite()) || g0 > 0.0 {
        return None;
    }
    if g1 <= 0.0 {
        return None;
    }
    // p(τ) = g0 + d0 τ + c2 τ² + c3 τ³.
    let c2 = 3.0 * (g1 - g0) - 2.0 * d0 - d1;
    let c3 = 2.0 * (g0 - g1) + d0 + d1;
    let knot = |t: f64| Knot {
        s: t,
        g: g0 + t * (d0 + t * (c2 + t * c3)),
        dg: d0 + t * (2.0 * c2 + t * 3.0 * c3),
        point: (),
    };
    let settings = Refinement {
        max_steps: 40,
        residual: f64::EPSILON * (g1 - g0),
        scale: 1.0,
        first_guess: Some(-g0 / (g1 - g0)),
        close: false,
    };
    let t = refine(knot, knot(0.0), knot(1.0), &settings).best.s;
    (t > 0.0 && t < 1.0).then_some(t)
}
