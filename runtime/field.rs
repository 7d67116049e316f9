//! The full nonlinear piecewise equations of motion (`model.md` §1), stated directly.
//!
//! This is the *independent* statement of the model that the numerical reference integrators and
//! the hybrid method's contact phase integrate. It deliberately shares nothing with the generated
//! closed forms, so that comparing the two checks the generator.

use crate::math;
use crate::params::{Params, State};
use crate::propagate::Regime;

/// z = √((x − ε̂x)² + (y − ε̂y)²): the distance from the stator centre in clearances (`model.md`
/// notation). Contact when z > 1.
#[inline]
pub fn radius(params: &Params, x: f64, y: f64) -> f64 {
    math::hypot(x - params.offset_x, y - params.offset_y)
}

/// The contact force K_s·g(u, v) with g = (1 − 1/z)(u, v) (`model.md` §1, restoring sign).
#[inline]
pub fn contact_force(params: &Params, x: f64, y: f64) -> (f64, f64) {
    let u = x - params.offset_x;
    let v = y - params.offset_y;
    // √(u² + v²) rather than hypot: states are bounded by the divergence limit, so nothing
    // overflows, and this is the hot path of the numerical methods in contact.
    let z = math::sqrt(u * u + v * v);
    let scale = if z > 0.0 { 1.0 - 1.0 / z } else { 0.0 };
    let (gx, gy) = (scale * u, scale * v);
    (
        params.k_xx * gx + params.k_xy * gy,
        params.k_yx * gx + params.k_yy * gy,
    )
}

/// Accelerations (x'', y'') of the regime's vector field at time τ (`model.md` §1):
/// free: x'' = −2ν x' − x + F cos θ; contact adds −K_s g.
#[inline]
pub fn acceleration(params: &Params, regime: Regime, tau: f64, s: &State) -> (f64, f64) {
    let (sin_t, cos_t) = math::sin_cos(params.speed_ratio * tau + params.phase);
    acceleration_with_phasor(params, regime, cos_t, sin_t, s)
}

/// As [`acceleration`], with the forcing direction (cos θ, sin θ) supplied by the caller (for
/// integrators that carry the forcing as a rotating phasor).
#[inline]
pub fn acceleration_with_phasor(
    params: &Params,
    regime: Regime,
    cos_theta: f64,
    sin_theta: f64,
    s: &State,
) -> (f64, f64) {
    let f = params.forcing_amplitude();
    let nu2 = 2.0 * params.damping_ratio;
    let mut ax = f * cos_theta - nu2 * s.vx - s.x;
    let mut ay = f * sin_theta - nu2 * s.vy - s.y;
    if regime == Regime::Contact {
        let (fx, fy) = contact_force(params, s.x, s.y);
        ax -= fx;
        ay -= fy;
    }
    (ax, ay)
}

/// The regime's vector field s' = (x', y', x'', y'') at time τ.
#[inline]
pub fn derivative(params: &Params, regime: Regime, tau: f64, s: &State) -> State {
    let (ax, ay) = acceleration(params, regime, tau, s);
    State::new(s.vx, s.vy, ax, ay)
}

/// h = z² − 1 and its time derivative h' = 2(u u' + v v'): the switching function used by event
/// location (its sign is the regime, its derivative the radial velocity).
#[inline]
pub fn switching_function(params: &Params, s: &State) -> (f64, f64) {
    let u = s.x - params.offset_x;
    let v = s.y - params.offset_y;
    (u * u + v * v - 1.0, 2.0 * (u * s.vx + v * s.vy))
}

/// The regime of a state (`model.md` §6 case 14): by the sign of h = z² − 1; on z = 1 (|h| within
/// rounding, 4ε), by the sign of z' (radial velocity) unless it too is within its rounding (a
/// tangential start: deciding by the rounding's sign would start a zero-length regime), then of
/// z'' (both fields agree on z = 1, where g = 0, so the free acceleration is used); free when
/// all three vanish.
pub fn regime_of(params: &Params, tau: f64, state: &State) -> Regime {
    let (h, dh) = switching_function(params, state);
    let (u, v) = (state.x - params.offset_x, state.y - params.offset_y);
    let dh_rounding = 8.0 * f64::EPSILON * (math::abs(u * state.vx) + math::abs(v * state.vy));
    let sign = if math::abs(h) > 4.0 * f64::EPSILON {
        h
    } else if math::abs(dh) > dh_rounding {
        dh
    } else {
        let (ax, ay) = acceleration(params, Regime::Free, tau, state);
        state.vx * state.vx + state.vy * state.vy + u * ax + v * ay
    };
    if sign > 0.0 {
        Regime::Contact
    } else {
        Regime::Free
    }
}
