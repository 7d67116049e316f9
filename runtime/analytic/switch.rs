//! Switch location: the first time a closed-form segment crosses z = 1, found so that no crossing
//! can be skipped, and refined to near machine precision.
//!
//! # Why a root cannot be skipped
//! On an interval [a, b] of length L the search knows g = ±h and g' at both ends (exactly, from
//! the closed form) and a rigorous bound M ≥ |h''| on the interval (from the segment's amplitudes
//! and frequencies, [`Segment::bounds`]). Then g(t) ≤ min(g(a) + g'(a)t + Mt²/2,
//! g(b) − g'(b)(L − t) + M(L − t)²/2). Each parabola is convex and g(a) ≤ 0 (a is the start or
//! a point already examined), so g < 0 on (a, b] follows from g(b) < 0 and a negative value of
//! either parabola at the point where they meet (or of one of them at the far end). If so the
//! interval holds no crossing and is discarded — a start on z = 1 that leaves at once included; otherwise it is halved and both halves examined, left
//! first. Every discarded interval is *proven* crossing-free, so a contact of any duration,
//! grazing ones included, is found; only intervals shorter than [`MIN_INTERVAL`] relative, where
//! g stays ≤ 0 at every sampled point, are dropped as tangential touches (z reaches 1 but does not
//! exceed it). Intervals where g' > 0 throughout (g'(a) > M·L) hold at most one crossing, which is
//! refined by safeguarded Newton steps on the exact derivative.
//!
//! Work is bounded: ≤ [`MAX_SPLITS`] splits per chunk, recursion depth ≤ [`MAX_DEPTH`],
//! refinement ≤ [`MAX_REFINE`] steps.

use super::segment::{Point, Segment};
use crate::math;

/// Which way the crossing goes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Direction {
    /// h becomes positive: contact starts.
    Up,
    /// h becomes negative: contact ends.
    Down,
}

impl Direction {
    fn sign(self) -> f64 {
        match self {
            Direction::Up => 1.0,
            Direction::Down => -1.0,
        }
    }
}

/// Intervals shorter than this (relative to 1 + |s|) are not split further.
pub const MIN_INTERVAL: f64 = 1e-13;
/// Most interval splits (one evaluation each) per searched chunk. Exhausted, an interval whose
/// ends do not change sign is taken as a tangential touch, so a contact shallower than what the
/// bounds resolved by then could be missed. Measured over `tests/analytic.rs` (2000 random
/// degenerate-corner problems and the Fig. 2 agreement runs): never exhausted, at most 255
/// splits in one chunk.
pub const MAX_SPLITS: u32 = 512;
/// Largest recursion depth of the interval search.
pub const MAX_DEPTH: u32 = 60;
/// Largest number of refinement steps.
pub const MAX_REFINE: u32 = 80;

/// The first crossing in `direction` on (lo, hi], given the point at `lo` (treated as inside the
/// current regime, so a start exactly on z = 1 is not reported again) and a largest search
/// chunk. Returns the local time and point of the crossing.
pub fn first_crossing<S: Segment>(
    seg: &S,
    lo: f64,
    start: Point,
    hi: f64,
    direction: Direction,
    max_chunk: f64,
) -> Option<(f64, Point)> {
    let sign = direction.sign();
    let mut a = lo;
    // The start belongs to the current regime whatever rounding says.
    let mut pa = Point {
        h: if sign * start.h > 0.0 { 0.0 } else { start.h },
        ..start
    };
    while a < hi {
        let b = (a + max_chunk).min(hi);
        let pb = seg.point(b);
        if let Some(found) = search(seg, a, pa, b, pb, sign, 0, &mut MAX_SPLITS.clone()) {
            return Some(found);
        }
        a = b;
        pa = pb;
    }
    None
}

/// As [`first_crossing`] over the single chunk (lo, hi], with the point at `hi` already known
/// (`end`, for example a sub-step's end state): one evaluation fewer.
pub fn first_crossing_to<S: Segment>(
    seg: &S,
    lo: f64,
    start: Point,
    hi: f64,
    end: Point,
    direction: Direction,
) -> Option<(f64, Point)> {
    if lo >= hi || lo.is_nan() || hi.is_nan() {
        return None;
    }
    let sign = direction.sign();
    let pa = Point {
        h: if sign * start.h > 0.0 { 0.0 } else { start.h },
        ..start
    };
    search(seg, lo, pa, hi, end, sign, 0, &mut MAX_SPLITS.clone())
}

#[allow(clippy::too_many_arguments)]
fn search<S: Segment>(
    seg: &S,
    a: f64,
    pa: Point,
    b: f64,
    pb: Point,
    sign: f64,
    depth: u32,
    budget: &mut u32,
) -> Option<(f64, Point)> {
    let (ga, gb) = (sign * pa.h, sign * pb.h);
    let (dga, dgb) = (sign * pa.dh, sign * pb.dh);
    let len = b - a;
    let m2 = seg.bounds(a, b).second_derivative();
    let tiny = len <= MIN_INTERVAL * (1.0 + math::abs(b)) || depth >= MAX_DEPTH || *budget == 0;
    if gb > 0.0 {
        if dga > m2 * len || tiny {
            return Some(refine(seg, a, ga, dga, b, pb, sign));
        }
    } else {
        if upper_bound(ga, dga, gb, dgb, m2, len) < 0.0 || tiny {
            return None;
        }
    }
    let mid = a + 0.5 * len;
    let pm = seg.point(mid);
    *budget -= 1;
    search(seg, a, pa, mid, pm, sign, depth + 1, budget)
        .or_else(|| search(seg, mid, pm, b, pb, sign, depth + 1, budget))
}

/// A value that is negative only if g < 0 on the half-open (0, len], from end values, end
/// slopes and |g''| ≤ m2, given ga ≤ 0 (the left end is never a crossing: it is the start,
/// treated as inside, or a point already examined with g ≤ 0).
///
/// Ua(t) = ga + dga t + m2 t²/2 and Ub(t) = gb − dgb (len − t) + m2 (len − t)²/2 both bound g
/// from above; each is convex, so with Ua(0) = ga ≤ 0, Ua(t) < 0 on (0, T] as soon as
/// Ua(T) < 0, and Ub < 0 on (0, len] as soon as Ub(0) ≤ 0 and gb < 0. Three certificates:
/// Ua(len) < 0; Ub(0) ≤ 0 and gb < 0; or, with t* where Ua = Ub (Ua − Ub is linear, Ua ≤ Ub
/// before t*), Ua(t*) < 0 and gb < 0. The left end excluded, a start exactly on z = 1 that
/// leaves at once (g(0) = 0, g'(0) < 0) is discarded at the first level instead of being halved
/// down to [`MIN_INTERVAL`].
fn upper_bound(ga: f64, dga: f64, gb: f64, dgb: f64, m2: f64, len: f64) -> f64 {
    let ua = |t: f64| ga + dga * t + 0.5 * m2 * t * t;
    // Ua − Ub = c0 + c1 t.
    let c0 = ga - gb + dgb * len - 0.5 * m2 * len * len;
    let c1 = dga - dgb + m2 * len;
    let by_a = ua(len);
    let ub0 = ga - c0;
    let by_b = if ub0 <= 0.0 { gb } else { ub0 };
    let mut bound = by_a.min(by_b);
    if c1 > 0.0 {
        let t = -c0 / c1;
        if t > 0.0 && t < len {
            bound = bound.min(ua(t).max(gb));
        }
    }
    // NaN (a non-finite segment): as before, the larger end value decides.
    if bound.is_nan() { ga.max(gb) } else { bound }
}

/// Safeguarded Newton on g over a bracket with g(a) ≤ 0 < g(b).
fn refine<S: Segment>(
    seg: &S,
    mut a: f64,
    mut ga: f64,
    mut dga: f64,
    mut b: f64,
    mut pb: Point,
    sign: f64,
) -> (f64, Point) {
    let mut best = (b, pb);
    let mut gb = sign * pb.h;
    for _ in 0..MAX_REFINE {
        if b - a <= 4.0 * f64::EPSILON * (1.0 + math::abs(b)) {
            break;
        }
        // Newton from the end with the smaller residual, else the secant, else bisection.
        let (gs, ds, s0) = if -ga < gb {
            (ga, dga, a)
        } else {
            (gb, sign * pb.dh, b)
        };
        let mut t = if ds != 0.0 { s0 - gs / ds } else { f64::NAN };
        if !(t > a && t < b) {
            t = if gb != ga {
                a - ga * (b - a) / (gb - ga)
            } else {
                f64::NAN
            };
        }
        if !(t > a && t < b) {
            t = a + 0.5 * (b - a);
        }
        let pt = seg.point(t);
        let gt = sign * pt.h;
        if math::abs(pt.h) <= math::abs(best.1.h) {
            best = (t, pt);
        }
        if math::abs(pt.h) <= 1e-15 {
            break;
        }
        if gt > 0.0 {
            b = t;
            gb = gt;
            pb = pt;
        } else {
            a = t;
            ga = gt;
            dga = sign * pt.dh;
        }
    }
    best
}
