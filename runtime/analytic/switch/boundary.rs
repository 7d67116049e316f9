//! The switching function of contact, g = ±(z² − 1), as an [`EventFunction`] on a closed-form
//! [`Segment`], its curvature bound, and the analytic method's entry points to the kernel.

use super::{Budget, EventFunction, TOUCH, locate, no_crossing};
use crate::analytic::segment::{Point, Segment};
use crate::math;

/// Which way a z = 1 crossing goes.
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

/// The switching function of contact, g = ±h with h = z² − 1, on a [`Segment`].
#[derive(Clone, Copy, Debug)]
pub struct Boundary<'a, S> {
    segment: &'a S,
    sign: f64,
}

impl<'a, S: Segment> Boundary<'a, S> {
    /// Crossings of z = 1 in `direction` along `segment`.
    pub fn new(segment: &'a S, direction: Direction) -> Self {
        Boundary {
            segment,
            sign: direction.sign(),
        }
    }
}

impl<S: Segment> EventFunction for Boundary<'_, S> {
    type Point = Point;

    #[inline]
    fn point(&self, s: f64) -> Point {
        self.segment.point(s)
    }

    #[inline]
    fn value(&self, point: &Point) -> (f64, f64) {
        (self.sign * point.h, self.sign * point.dh)
    }

    #[inline]
    fn curvature(&self, lo: f64, at_lo: &Point, hi: f64) -> f64 {
        curvature(self.segment, lo, at_lo, hi)
    }
}

/// A bound of |h''| on [x, y]: the segment's bounds, with the radius and speed tightened
/// around the known point at x (|r(s) − ε| ≤ |r(x) − ε| + (s − x)·speed and
/// |r'(s)| ≤ |r'(x)| + (s − x)·accel): the closed forms' bounds add the amplitudes of terms
/// that largely cancel, the local ones do not.
pub fn curvature<S: Segment>(seg: &S, x: f64, px: &Point, y: f64) -> f64 {
    let b = seg.bounds(x, y);
    let s = &px.state;
    let r0 = math::sqrt((px.h + 1.0).max(0.0));
    let v0 = math::sqrt(s.vx * s.vx + s.vy * s.vy);
    local_curvature(r0, v0, b.radius, b.speed, b.accel, y - x)
}

/// 2(v² + r·a) with r = min(radius, r0 + len·speed) and v = min(speed, v0 + len·accel): the
/// bound of |h''| = |2(|r'|² + (r − ε)·r'')| from bounds of |r − ε|, |r'|, |r''| on an interval
/// of length `len` and the values r0 = |r − ε|, v0 = |r'| at its start.
#[inline]
pub fn local_curvature(r0: f64, v0: f64, radius: f64, speed: f64, accel: f64, len: f64) -> f64 {
    let r = radius.min(r0 + len * speed);
    let v = speed.min(v0 + len * accel);
    2.0 * (v * v + r * accel)
}

/// The analytic method's search for the first z = 1 crossing of `seg` in `direction` on
/// (lo, hi], in chunks of at most `max_chunk`: [`locate`] with [`Budget::EXPLORE`]; an
/// unresolved part is taken as a touch.
pub fn first_crossing<S: Segment>(
    seg: &S,
    lo: f64,
    start: Point,
    hi: f64,
    direction: Direction,
    max_chunk: f64,
) -> Option<(f64, Point)> {
    let f = Boundary::new(seg, direction);
    locate(&f, lo, start, hi, None, max_chunk, &Budget::EXPLORE, None).found()
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
    let f = Boundary::new(seg, direction);
    // The common case, a sub-step proved free by one bound test, as `locate` decides it (its
    // chunk's first test: the same values, bound and comparison) without setting up the search;
    // when the test fails, the search takes its bound instead of computing it again.
    let mut known = None;
    if lo < hi {
        let (ga, dga) = f.value(&start);
        let (gb, dgb) = f.value(&end);
        let len = hi - lo;
        if gb <= TOUCH && len > Budget::EXPLORE.min_interval * (1.0 + math::abs(hi)) {
            let m2 = f.curvature(lo, &start, hi);
            if no_crossing(ga.min(0.0), dga, gb, dgb, m2, len, TOUCH) {
                return None;
            }
            known = Some((lo, hi, m2));
        }
    }
    locate(
        &f,
        lo,
        start,
        hi,
        Some(end),
        f64::INFINITY,
        &Budget::EXPLORE,
        known,
    )
    .found()
}
