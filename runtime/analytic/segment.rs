//! What every closed-form segment offers the switch search: the state with the switching
//! function at any local time, and bounds that make the search rigorous.

use crate::params::State;

/// The state at a local time, with h = z² − 1 and h' (`docs/MODEL.md` eq. (10), squared).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Point {
    /// The state.
    pub state: State,
    /// h = z² − 1: negative in free flight, positive in contact.
    pub h: f64,
    /// h' = dh/dτ = 2(u x' + v y').
    pub dh: f64,
}

/// Bounds over a local-time interval: |r − ε| ≤ radius, |r'| ≤ speed, |r''| ≤ accel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bounds {
    /// Upper bound of |r − ε|.
    pub radius: f64,
    /// Upper bound of |r'|.
    pub speed: f64,
    /// Upper bound of |r''|.
    pub accel: f64,
}

impl Bounds {
    /// An upper bound of |h''| = |2(|r'|² + (r − ε)·r'')| on the interval.
    pub fn second_derivative(&self) -> f64 {
        2.0 * (self.speed * self.speed + self.radius * self.accel)
    }
}

/// A closed-form piece of trajectory in local time s = τ − τ0.
pub trait Segment {
    /// State, h and h' at local time `s`.
    fn point(&self, s: f64) -> Point;
    /// Bounds on s ∈ [lo, hi] (rigorous, possibly loose).
    fn bounds(&self, lo: f64, hi: f64) -> Bounds;
}

/// h = z² − 1 and h' for a state (the switching function of `docs/MODEL.md` eq. (10), squared so
/// that it is smooth and cheap).
#[inline]
pub fn point_of(state: State, offset_x: f64, offset_y: f64) -> Point {
    let u = state.x - offset_x;
    let v = state.y - offset_y;
    Point {
        state,
        h: u * u + v * v - 1.0,
        dh: 2.0 * (u * state.vx + v * state.vy),
    }
}
