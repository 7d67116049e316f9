//! How much rounding the runtime's computed switch functions and times carry: the one set of
//! bands every search and decision uses, each in units of the double's epsilon ε = 2⁻⁵².
//!
//! A switch function (h = z² − 1, σw, μN − |λ|) evaluated on a state carries the rounding of the
//! terms it is computed from; a value within its band of 0 is rounding, not a side. Where a
//! method's own solution adds to that (a closed form's evaluation, a dense output, a Taylor
//! polynomial), the wider band applies.

/// h = z² − 1 of a state near z = 1 is known to ~4 ulps of 1: within it a state is on z = 1
/// (the regime of a state, `field::regime_of`).
pub const VALUE: f64 = 4.0 * f64::EPSILON;

/// The rate h' = 2(u x' + v y') (and any switch function's rate) is known to ~8 ulps of the
/// size of its terms.
pub const RATE: f64 = 8.0 * f64::EPSILON;

/// A touch: g up to 8 ulps above 0 when an interval is discarded by the closed forms' switch
/// search is not a crossing (a penetration z − 1 below 1e-15; twice [`VALUE`]).
pub const TOUCH: f64 = 8.0 * f64::EPSILON;

/// A switch function evaluated along a method's solution (a closed form re-evaluated from a
/// segment start, a dense output, a Taylor polynomial of the step) carries ~64 ulps of its
/// scale: a start within it counts as on the switch surface (the driver's starts on z = 1, the
/// taylor method's switch polynomials), and a dip within it is rounding, not a switch.
pub const SOLUTION: f64 = 64.0 * f64::EPSILON;

/// A bracket no wider than 4 ulps of its position (relative to 1 + |s|) holds its root to
/// rounding: refinement stops there (`refine`).
pub const BRACKET: f64 = 4.0 * f64::EPSILON;
