//! Switch location inside one step with a hard cap on the work: the interval-bound search of
//! `analytic::switch` (two-parabola bound, left first) without recursion, with a budget of
//! segment evaluations, and a safeguarded Newton refinement with an iteration cap. When the
//! chunk ends past a switch, the sign change is refined first and a single bound test over
//! the part before it proves it the first; the interval search runs only when that fails.
//!
//! Why not `analytic::switch::first_crossing` itself: its search explores both halves of every
//! inconclusive interval down to 1e-13 relative, so along a stretch where h stays within
//! rounding of 0 (a trajectory sliding on z = 1) its work grows like 2^depth — a random problem
//! in `tests/stepper.rs` ran for minutes inside one sub-step. Here intervals where the bound
//! keeps g below [`TOUCH`] (a touch within the rounding of h = z² − 1) are discarded, and the
//! number of evaluations is capped by [`MAX_SEARCH_EVALUATIONS`].

use crate::analytic::segment::{Point, Segment};
use crate::analytic::switch::Direction;
use crate::math;

/// Most segment evaluations (a point and a bound each) in the interval search of one piece.
pub const MAX_SEARCH_EVALUATIONS: u32 = 32;
/// Most Newton/bisection iterations refining one located switch.
pub const MAX_REFINE_ITERATIONS: u32 = 40;
/// Deepest interval split (each split costs an evaluation, so the budget bounds it too).
const MAX_DEPTH: u32 = MAX_SEARCH_EVALUATIONS;
/// |h| a contact must exceed to count: h = z² − 1 is only known to ~4ε near z = 1, so a touch
/// below 8ε (penetration z − 1 < 1e-15) is not a switch.
pub const TOUCH: f64 = 8.0 * f64::EPSILON;

/// What a search found.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Search {
    /// No switch in the interval (proved, up to touches below [`TOUCH`]).
    None,
    /// The first switch, at local time `s`. `certain` is false when a cap was hit: the
    /// refinement stopped at [`MAX_REFINE_ITERATIONS`] (the time is then known to its last
    /// bracket, not to rounding), or the budget ran out before the part of the interval left
    /// of a sign change was proved free (then an earlier, shallower contact may exist).
    Found {
        /// Local time of the switch.
        s: f64,
        /// The point there (state on z = 1 to about 1e-15 when converged).
        point: Point,
        /// Whether the switch is proved first and refined to rounding.
        certain: bool,
    },
    /// The evaluation budget ran out with no sign change of h left to refine: a shallow
    /// contact (entered and left inside the unresolved part) may be missed there.
    Unresolved,
}

/// Whether g = ±h provably stays ≤ `slack` on [0, len], from its values and slopes at both
/// ends and a bound `m2` ≥ |g''| on the interval. g ≤ min(Ua, Ub) with the parabolas
/// Ua(t) = ga + dga t + m2 t²/2, Ub(t) = gb − dgb (len − t) + m2 (len − t)²/2; by convexity the
/// maximum of that minimum is at an end or where they meet (`analytic::switch`). False when
/// the bound does not prove it.
#[inline]
pub fn no_crossing(ga: f64, dga: f64, gb: f64, dgb: f64, m2: f64, len: f64, slack: f64) -> bool {
    if !(ga <= slack && gb <= slack && m2 >= 0.0 && m2.is_finite()) {
        return false;
    }
    // Ua − Ub = c0 + c1 t; c1 ≥ 0 whenever m2 is a valid bound.
    let c0 = ga - gb + dgb * len - 0.5 * m2 * len * len;
    let c1 = dga - dgb + m2 * len;
    let meet = if c1 > 0.0 {
        let t = (-c0 / c1).clamp(0.0, len);
        ga + dga * t + 0.5 * m2 * t * t
    } else if c1 == 0.0 {
        ga.max(gb)
    } else {
        return false;
    };
    meet <= slack
}

/// The first crossing of z = 1 in `direction` on (lo, hi] of `seg`, searched in chunks of at
/// most `chunk`, given the point at `lo` (counted inside the current regime).
pub fn locate<S: Segment>(
    seg: &S,
    lo: f64,
    start: Point,
    hi: f64,
    direction: Direction,
    chunk: f64,
) -> Search {
    let sign = match direction {
        Direction::Up => 1.0,
        Direction::Down => -1.0,
    };
    let g = |p: &Point| (sign * p.h, sign * p.dh);
    let mut evaluations = 0;
    let (mut a, mut pa) = (lo, start);
    if sign * pa.h > 0.0 {
        pa.h = 0.0;
    }
    while a < hi {
        let b = (a + chunk).min(hi);
        let pb = seg.point(b);
        if sign * pb.h > 0.0 {
            // A sign change: refine it first, then one bound test proves that no earlier
            // crossing precedes it (the common case: one transversal switch in the chunk).
            let found = refine(seg, (a, pa), (b, pb), sign, true);
            if let Search::Found { s, point, .. } = found {
                let ((ga, dga), (gs, dgs)) = (g(&pa), g(&point));
                let m2 = curvature(seg, a, &pa, s);
                if s > a && no_crossing(ga, dga, gs, dgs, m2, s - a, TOUCH) {
                    return found;
                }
            }
        }
        // Left-first depth-first search over [a, b]: the current interval is [x, top of the
        // stack]; a discarded interval moves x to its right end.
        let mut stack = [(b, pb, 0u32); MAX_DEPTH as usize + 1];
        let mut top: usize = 1;
        let (mut x, mut px) = (a, pa);
        while let Some(&(y, py, depth)) = top.checked_sub(1).and_then(|i| stack.get(i)) {
            let ((gx, dgx), (gy, dgy)) = (g(&px), g(&py));
            let len = y - x;
            let m2 = curvature(seg, x, &px, y);
            evaluations += 1;
            let tiny = len <= 4.0 * f64::EPSILON * (1.0 + math::abs(y)) || depth >= MAX_DEPTH;
            if gy > 0.0 && (dgx > m2 * len || tiny) {
                // g(x) ≤ 0 < g(y), and g increases throughout (or the interval is tiny).
                return refine(seg, (x, px), (y, py), sign, true);
            }
            if gy <= 0.0 && (tiny || no_crossing(gx, dgx, gy, dgy, m2, len, TOUCH)) {
                top -= 1;
                (x, px) = (y, py);
                continue;
            }
            if evaluations >= MAX_SEARCH_EVALUATIONS {
                // Out of budget: refine the nearest sign change, if any (entries above hold
                // increasing right ends, the top is the current interval's).
                let change = stack[..top].iter().rev().find(|(_, p, _)| sign * p.h > 0.0);
                return match change {
                    Some(&(y, py, _)) => refine(seg, (x, px), (y, py), sign, false),
                    None => Search::Unresolved,
                };
            }
            let mid = x + 0.5 * len;
            if let Some(slot) = stack.get_mut(top) {
                *slot = (mid, seg.point(mid), depth + 1);
                top += 1;
            } else {
                return Search::Unresolved;
            }
        }
        (a, pa) = (b, pb);
    }
    Search::None
}

/// A bound of |h''| on [x, y]: the segment's bounds, with the radius and speed tightened
/// around the known point at x (|r(s) − ε| ≤ |r(x) − ε| + (s − x)·speed and
/// |r'(s)| ≤ |r'(x)| + (s − x)·accel): the closed forms' bounds add the amplitudes of terms
/// that largely cancel, the local ones do not.
pub fn curvature<S: Segment>(seg: &S, x: f64, px: &Point, y: f64) -> f64 {
    let b = seg.bounds(x, y);
    let len = y - x;
    let (s, r0) = (&px.state, math::sqrt((px.h + 1.0).max(0.0)));
    let v0 = math::sqrt(s.vx * s.vx + s.vy * s.vy);
    local_curvature(r0, v0, b.radius, b.speed, b.accel, len)
}

/// 2(v² + r·a) with r = min(radius, r0 + len·speed) and v = min(speed, v0 + len·accel).
#[inline]
pub fn local_curvature(r0: f64, v0: f64, radius: f64, speed: f64, accel: f64, len: f64) -> f64 {
    let r = radius.min(r0 + len * speed);
    let v = speed.min(v0 + len * accel);
    2.0 * (v * v + r * accel)
}

/// Safeguarded Newton on g over a bracket g(a) ≤ 0 < g(b): Newton from the end with the smaller
/// residual, else the secant, else bisection, and a bisection whenever two iterations in a row
/// failed to halve the bracket. `first`: whether the bracket is proved to hold the first switch.
fn refine<S: Segment>(
    seg: &S,
    lo: (f64, Point),
    hi: (f64, Point),
    sign: f64,
    first: bool,
) -> Search {
    let ((mut a, mut pa), (mut b, mut pb)) = (lo, hi);
    let mut best = (b, pb);
    let mut slow = 0;
    for _ in 0..MAX_REFINE_ITERATIONS {
        let width = b - a;
        if width <= 4.0 * f64::EPSILON * (1.0 + math::abs(b)) || math::abs(best.1.h) <= 1e-15 {
            return Search::Found {
                s: best.0,
                point: best.1,
                certain: first,
            };
        }
        let (ga, gb) = (sign * pa.h, sign * pb.h);
        let (g0, d0, s0) = if -ga < gb {
            (ga, sign * pa.dh, a)
        } else {
            (gb, sign * pb.dh, b)
        };
        let inside = |t: f64| t > a && t < b;
        let mut t = if d0 != 0.0 { s0 - g0 / d0 } else { f64::NAN };
        if !inside(t) {
            t = a - ga * width / (gb - ga);
        }
        if !inside(t) || slow >= 2 {
            t = a + 0.5 * width;
        }
        let pt = seg.point(t);
        if math::abs(pt.h) <= math::abs(best.1.h) {
            best = (t, pt);
        }
        if sign * pt.h > 0.0 {
            (b, pb) = (t, pt);
        } else {
            (a, pa) = (t, pt);
        }
        slow = if b - a > 0.5 * width { slow + 1 } else { 0 };
    }
    Search::Found {
        s: best.0,
        point: best.1,
        certain: first && math::abs(best.1.h) <= 1e-15,
    }
}
