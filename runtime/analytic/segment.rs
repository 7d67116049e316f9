//! What every closed-form segment offers the switch search: the state with the switching
//! function at any local time, and bounds that make the search rigorous.

pub use crate::geometry::Point;

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
