//! The one refinement of a bracketed switch, used by every search: the closed forms' switch
//! kernel (`analytic::switch`), the numerical methods' dense output (`reference::events`) and the
//! taylor method's switch polynomials (`taylor::roots`, `taylor::expansion`).
//!
//! Safeguarded Newton on a bracket g(below) ≤ 0 < g(above): each step is Newton from the end
//! with the smaller residual |g| when g' is known there, else the secant through the two ends
//! (Illinois: an end kept twice in a row has its weight halved), else (the step leaves the
//! bracket, or two steps in a row halved neither the residual nor the bracket) bisection. Newton converging from one side keeps one end fixed: a halved residual
//! counts as progress as well as a halved bracket, so it is not forced into a bisection. It
//! stops when the bracket is [`rounding::BRACKET`] narrow (relative to the caller's `scale`),
//! the residual is within the caller's `residual`, a step moves the point by less than that
//! width, or after `max_steps` steps.

use crate::math;
use crate::rounding;

/// One evaluation of a switch function g at s: its value, its rate g' (NaN where the caller has
/// none: the step is then a secant) and whatever the caller computed them from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Knot<P> {
    /// Where.
    pub s: f64,
    /// g(s).
    pub g: f64,
    /// g'(s), or NaN.
    pub dg: f64,
    /// What g was computed from (a state, a closed form's point; `()` for none).
    pub point: P,
}

/// How a refinement runs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Refinement {
    /// Most evaluations.
    pub max_steps: u32,
    /// |g| at or below which the point found is the root (0: refine to the bracket's width).
    pub residual: f64,
    /// The size of s the resolution is relative to: the bracket is narrow enough at
    /// [`rounding::BRACKET`] × (`scale` + |s|) (1 for a local time, whose rounding is that of the
    /// absolute time it is added to; 0 for a root wanted to its own relative precision).
    pub scale: f64,
    /// Where the first step goes instead of Newton's (a better start the caller knows: the
    /// closed forms' Hermite root), if inside the bracket.
    pub first_guess: Option<f64>,
    /// Whether to close the bracket on both sides of a root Newton converged to from one side
    /// (a few ulps' steps): for a caller that wants the end past the crossing
    /// ([`Refined::at_or_past`]); one that takes `best` leaves it off.
    pub close: bool,
}

/// What a refinement found.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Refined<P> {
    /// The point with the smallest |g| seen (the root to rounding when converged).
    pub best: Knot<P>,
    /// The final bracket's end with g ≤ 0.
    pub below: Knot<P>,
    /// The final bracket's end with g > 0.
    pub above: Knot<P>,
    /// Whether it stopped at rounding rather than at `max_steps`.
    pub converged: bool,
}

impl<P: Copy> Refined<P> {
    /// The crossing as a point where g ≥ 0 (on the far side of the switch, or on it): `best`
    /// when it lies there, else the bracket's end `above` (as close as the bracket is narrow).
    pub fn at_or_past(&self) -> Knot<P> {
        if self.best.g >= 0.0 {
            self.best
        } else {
            self.above
        }
    }
}

/// Refine the bracket `below`, `above` (g(below) ≤ 0 < g(above); s in either order) with
/// `eval`, which computes the knot at an s strictly inside it (see the module documentation).
pub fn refine<P: Copy>(
    mut eval: impl FnMut(f64) -> Knot<P>,
    below: Knot<P>,
    above: Knot<P>,
    settings: &Refinement,
) -> Refined<P> {
    let (mut a, mut b) = (below, above);
    let mut best = b;
    let mut slow = 0;
    // The secant's weights: each end's g, halved while the other end moves (Illinois), so that
    // an end that stays is not kept for ever; and which end moved last (+1: above, −1: below).
    let (mut weight_a, mut weight_b) = (a.g, b.g);
    let mut moved = 0i8;
    // Whether each end was evaluated here (a caller's end may be clamped: a start counted as
    // inside the regime whatever its g, never a root).
    let (mut found_a, mut found_b) = (false, false);
    let mut start = settings.first_guess;
    for _ in 0..settings.max_steps {
        let width = math::abs(b.s - a.s);
        let resolution =
            (rounding::BRACKET * (settings.scale + math::abs(b.s))).max(f64::MIN_POSITIVE);
        if width <= resolution || math::abs(best.g) <= settings.residual {
            return Refined {
                best,
                below: a,
                above: b,
                converged: true,
            };
        }
        let (near, near_found) = if -a.g < b.g {
            (a, found_a)
        } else {
            (b, found_b)
        };
        let newton = if near.dg.is_finite() && near.dg != 0.0 {
            near.s - near.g / near.dg
        } else {
            f64::NAN
        };
        let toward_bracket = newton == near.s || (newton - a.s) * (newton - b.s) < 0.0;
        if near_found
            && start.is_none()
            && toward_bracket
            && math::abs(newton - near.s) <= resolution
        {
            // Newton's step from `near`, into the bracket, is below the resolution: the root is
            // there (whatever smaller |g| was seen elsewhere: g can be as flat as that far from
            // its root). A step out of the bracket says g runs away from a root at `near`.
            return closed(&mut eval, (a, b), near, resolution, settings.close);
        }
        let inside = |t: f64| (t - a.s) * (t - b.s) < 0.0;
        let mut t = start.take().unwrap_or(newton);
        if !inside(t) {
            t = a.s - weight_a * (b.s - a.s) / (weight_b - weight_a);
        }
        if !inside(t) || slow >= 2 {
            t = a.s + 0.5 * (b.s - a.s);
        }
        if !inside(t) {
            // The bracket holds no double strictly inside: it is as narrow as it gets.
            return Refined {
                best,
                below: a,
                above: b,
                converged: true,
            };
        }
        let k = eval(t);
        let halved = math::abs(k.g) <= 0.5 * math::abs(best.g);
        if math::abs(k.g) <= math::abs(best.g) {
            best = k;
        }
        if k.g > 0.0 {
            b = k;
            found_b = true;
            weight_b = k.g;
            if moved == 1 {
                weight_a *= 0.5;
            }
            moved = 1;
        } else {
            a = k;
            found_a = true;
            weight_a = k.g;
            if moved == -1 {
                weight_b *= 0.5;
            }
            moved = -1;
        }
        slow = if halved || math::abs(b.s - a.s) <= 0.5 * width {
            0
        } else {
            slow + 1
        };
    }
    let converged = math::abs(best.g) <= settings.residual;
    Refined {
        best,
        below: a,
        above: b,
        converged,
    }
}

/// A root found at `best`, within `resolution` of the bracket (a, b): with `close` and `best`
/// before the crossing (g ≤ 0), the bracket's end past it is brought in (steps of one ulp of s,
/// then 4, 16, … up to the resolution: the first across the root ends it), so that
/// [`Refined::at_or_past`] is as near as the doubles allow.
fn closed<P: Copy>(
    eval: &mut impl FnMut(f64) -> Knot<P>,
    (mut a, mut b): (Knot<P>, Knot<P>),
    mut best: Knot<P>,
    resolution: f64,
    close: bool,
) -> Refined<P> {
    if close && best.g <= 0.0 {
        // Steps toward `above` until g turns positive; if it does not within the resolution,
        // g is flat at 0 to rounding there and the last step is the end past the crossing.
        let direction = (b.s - best.s).signum();
        let mut d = (f64::EPSILON * math::abs(best.s)).max(f64::MIN_POSITIVE);
        let mut last = best;
        while d <= resolution && math::abs(b.s - best.s) > d {
            last = eval(best.s + direction * d);
            if last.g > 0.0 {
                break;
            }
            a = last;
            d *= 4.0;
        }
        if last.g > 0.0 || last.s != best.s {
            // The end past the crossing: the first step across it, or the last within the
            // resolution (marked as at the crossing).
            b = Knot {
                g: last.g.max(0.0),
                ..last
            };
            if last.g > 0.0 && math::abs(last.g) < math::abs(best.g) {
                best = last;
            }
        }
    }
    Refined {
        best,
        below: a,
        above: b,
        converged: true,
    }
}

/// A root of `knot`'s g near `s`, polished: the other end of a bracket is sought past the
/// Newton step from `s` (twice it, then four times wider, up to 8 tries) inside [0, `h`], and
/// the bracket refined by [`refine`] (40 steps, to the resolution of `f64`); `s` itself when g
/// is not finite there, is zero there, or no bracket is found. For a root already located on an
/// approximation (a Taylor polynomial's) that the exact state puts back on h = 0.
pub fn polish_about(knot: impl Fn(f64) -> Knot<()>, s: f64, h: f64) -> f64 {
    let at = knot(s);
    if !(at.g.is_finite() && at.dg.is_finite()) || at.g == 0.0 {
        return s;
    }
    let toward = if at.g > 0.0 { -1.0 } else { 1.0 };
    let mut width = 2.0 * math::abs(at.g / at.dg);
    let mut other = None;
    for _ in 0..8 {
        let t = (s + toward * width).clamp(0.0, h);
        let k = knot(t);
        if (k.g > 0.0) != (at.g > 0.0) {
            other = Some(k);
            break;
        }
        if t == 0.0 || t == h {
            break;
        }
        width *= 4.0;
    }
    let Some(other) = other else {
        return s;
    };
    let (below, above) = if at.g > 0.0 { (other, at) } else { (at, other) };
    let settings = Refinement {
        max_steps: 40,
        residual: 0.0,
        scale: 1.0,
        first_guess: None,
        close: false,
    };
    refine(knot, below, above, &settings).best.s
}

#[cfg(test)]
mod tests {
    use super::*;

    fn knot(s: f64, (g, dg): (f64, f64)) -> Knot<()> {
        Knot {
            s,
            g,
            dg,
            point: (),
        }
    }

    fn settings(close: bool) -> Refinement {
        Refinement {
            max_steps: 200,
            residual: 0.0,
            scale: 1.0,
            first_guess: None,
            close,
        }
    }

    fn solve(f: impl Fn(f64) -> (f64, f64), a: f64, b: f64, close: bool) -> Refined<()> {
        refine(
            |t| knot(t, f(t)),
            knot(a, f(a)),
            knot(b, f(b)),
            &settings(close),
        )
    }

    #[test]
    fn a_transversal_root_to_the_last_bits() {
        let f = |t: f64| (t * t - 2.0, 2.0 * t);
        let r = solve(f, 0.0, 2.0, true);
        let root = core::f64::consts::SQRT_2;
        assert!(r.converged);
        assert!((r.best.s - root).abs() <= 2.0 * f64::EPSILON * root);
        let past = r.at_or_past();
        assert!(past.g >= 0.0 && past.s - root <= 4.0 * f64::EPSILON * root);
    }

    #[test]
    fn a_clamped_start_is_not_a_root() {
        // g(0) is 1e-3 in truth, handed in clamped to 0 (a start counted as inside); the
        // crossing the refinement must find is the one at 1 (g = (t − 1)·(1e-3 + 0) … ).
        let f = |t: f64| (t - 1.0, 1.0);
        let below = Knot {
            s: 0.0,
            g: 0.0,
            dg: -5.0,
            point: (),
        };
        let r = refine(
            |t| knot(t, f(t)),
            below,
            knot(2.0, f(2.0)),
            &settings(false),
        );
        assert!((r.best.s - 1.0).abs() < 1e-15, "{:?}", r.best);
    }

    #[test]
    fn a_small_residual_far_from_the_root_is_not_the_root() {
        // g falls steeply from a small negative start and rises to its root much later (the
        // free flight just after an exit at high speed): |g| near the start is smaller than
        // near the root for a while.
        let f = |t: f64| {
            let g = -1e-13 - 1e5 * t + 1e9 * t * t;
            (g, -1e5 + 2e9 * t)
        };
        let r = solve(f, 0.0, 1e-3, false);
        let root = (1e5 + (1e10 + 4e9 * 1e-13f64).sqrt()) / 2e9;
        assert!((r.best.s - root).abs() < 1e-15, "{:?} vs {root}", r.best);
    }

    #[test]
    fn without_a_rate_the_secant_converges() {
        let f = |t: f64| (t * t * t - 0.001, f64::NAN);
        let r = solve(f, 0.0, 1.0, true);
        assert!(r.converged);
        assert!((r.at_or_past().s - 0.1).abs() < 1e-15, "{:?}", r.best);
    }

    #[test]
    fn a_flat_crossing_ends_within_the_resolution() {
        // g = 0 to rounding on a stretch: the end past the crossing is within the resolution
        // of the root found, never the bracket's far end.
        let f = |t: f64| {
            let x: f64 = t - 0.5;
            let g = if x.abs() < 1e-15 { 0.0 } else { x * x * x };
            (g, 3.0 * x * x)
        };
        let r = solve(f, 0.0, 1.0, true);
        assert!(
            (r.at_or_past().s - 0.5).abs() < 1e-5,
            "{:?}",
            r.at_or_past()
        );
    }
}
