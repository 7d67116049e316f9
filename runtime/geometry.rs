//! The contact surface's geometry on a state: the switching function h = z² − 1 with its rates,
//! the offset from the stator centre and the distance z. Every formula comes from the model
//! statement (the generated `switching_function`, `switching_curvature`, `stator_offset`,
//! `position_at_offset`); this module is the one place the runtime reads them, and the one place
//! that says how much rounding their values carry.

use crate::coefficients::{
    self as coef, Acceleration, ModelParams, Position, StatorOffset, Velocity,
};
use crate::math;
use crate::params::State;
use crate::rounding;

/// A state with its switching function: h = z² − 1 and h' (`docs/MODEL.md` eq. (10), squared so
/// that it is smooth and cheap).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Point {
    /// The state.
    pub state: State,
    /// h = z² − 1: negative in free flight, positive in contact.
    pub h: f64,
    /// h' = dh/dτ.
    pub dh: f64,
}

/// The switching function of `state` ([`Point`]).
#[inline(always)]
pub fn point(model: &ModelParams, state: State) -> Point {
    let s = coef::switching_function(model, &position(&state), &velocity(&state));
    Point {
        state,
        h: s.h,
        dh: s.dh,
    }
}

/// h'' along a motion with acceleration `(ax, ay)` at `state`.
#[inline]
pub fn curvature(model: &ModelParams, state: &State, (ax, ay): (f64, f64)) -> f64 {
    coef::switching_curvature(
        model,
        &position(state),
        &velocity(state),
        &Acceleration { ax, ay },
    )
    .d2h
}

/// The offset (u, v) = q − ε̂ of the position (x, y) from the stator centre.
#[inline]
pub fn offset(model: &ModelParams, x: f64, y: f64) -> (f64, f64) {
    let d = coef::stator_offset(model, &Position { x, y });
    (d.u, d.v)
}

/// The position at offset (u, v) from the stator centre.
#[inline]
pub fn at_offset(model: &ModelParams, (u, v): (f64, f64)) -> (f64, f64) {
    let q = coef::position_at_offset(model, &StatorOffset { u, v });
    (q.x, q.y)
}

/// z = |q − ε̂|, the distance of (x, y) from the stator centre in clearances (contact when
/// z > 1), without undue overflow or underflow.
#[inline]
pub fn distance(model: &ModelParams, x: f64, y: f64) -> f64 {
    let (u, v) = offset(model, x, y);
    math::hypot(u, v)
}

/// The rounding h' = 2(u x' + v y') of `state` carries: [`rounding::RATE`] of the size of its
/// terms (the rounding of h itself near z = 1 is [`rounding::VALUE`]).
#[inline]
pub fn dh_rounding(model: &ModelParams, state: &State) -> f64 {
    let (u, v) = offset(model, state.x, state.y);
    rounding::RATE * (math::abs(u * state.vx) + math::abs(v * state.vy))
}

/// A state's position as the generated functions take it.
#[inline(always)]
pub fn position(s: &State) -> Position {
    Position { x: s.x, y: s.y }
}

/// A state's velocity as the generated functions take it.
#[inline(always)]
pub fn velocity(s: &State) -> Velocity {
    Velocity { vx: s.vx, vy: s.vy }
}
