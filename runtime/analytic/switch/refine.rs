//! Refining a bracketed switch to rounding: safeguarded Newton on the event function.

use super::{Budget, CONVERGED, EventFunction, Knot, hermite};
use crate::math;

/// Safeguarded Newton on g over a bracket g(a) ≤ 0 < g(b): Newton from the end with the smaller
/// residual, else the secant, else bisection, and a bisection whenever two iterations in a row
/// halved neither the residual |g| nor the bracket. Returns the point with the smallest |g|
/// seen in (a, b] and whether it converged to rounding within the budget's `refine` steps.
/// With `hermite_start` the first step goes to the root of the bracket's Hermite interpolant.
pub(super) fn refine<F: EventFunction>(
    f: &F,
    lo: Knot<F::Point>,
    hi: Knot<F::Point>,
    budget: &Budget,
) -> (Knot<F::Point>, bool) {
    let (mut a, mut b) = (lo, hi);
    let mut best = b;
    let mut slow = 0;
    let mut start = if budget.hermite_start {
        let w = b.s - a.s;
        hermite::root(a.g, a.dg * w, b.g, b.dg * w).map(|tau| a.s + tau * w)
    } else {
        None
    };
    for _ in 0..budget.refine {
        let width = b.s - a.s;
        if width <= 4.0 * f64::EPSILON * (1.0 + math::abs(b.s)) || math::abs(best.g) <= CONVERGED {
            return (best, true);
        }
        let (g0, d0, s0) = if -a.g < b.g {
            (a.g, a.dg, a.s)
        } else {
            (b.g, b.dg, b.s)
        };
        let inside = |t: f64| t > a.s && t < b.s;
        let mut t = match start.take() {
            Some(t) => t,
            None if d0 != 0.0 => s0 - g0 / d0,
            None => f64::NAN,
        };
        if !inside(t) {
            t = a.s - a.g * width / (b.g - a.g);
        }
        if !inside(t) || slow >= 2 {
            t = a.s + 0.5 * width;
        }
        let k = Knot::at(f, t, f.point(t));
        // Progress is the residual or the bracket halving: Newton converging from one side
        // keeps one end, so its bracket does not halve, but needs no bisection.
        let halved = math::abs(k.g) <= 0.5 * math::abs(best.g);
        if math::abs(k.g) <= math::abs(best.g) {
            best = k;
        }
        if k.g > 0.0 {
            b = k;
        } else {
            a = k;
        }
        slow = if halved || b.s - a.s <= 0.5 * width {
            0
        } else {
            slow + 1
        };
    }
    let converged = math::abs(best.g) <= CONVERGED;
    (best, converged)
}
