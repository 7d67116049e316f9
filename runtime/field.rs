//! The full nonlinear piecewise field (`docs/MODEL.md` §1) that the numerical reference
//! integrators and the hybrid method's contact phase integrate, with the switching function and
//! the regime of a state.
//!
//! The equations themselves are generated from the model statement in `codegen/src/model`
//! ([`coef::free_acceleration`], [`coef::contact_force`]); this module only feeds them and applies
//! the contact force in the contact regime. Comparisons of methods stay independent because the test suites keep
//! their own hand-written field (`tests/generated/field.rs`, `tests/reference`).

use crate::coefficients::{self as coef, ModelParams, Phasor, Position, Velocity};
use crate::math;
use crate::params::{Params, State};
use crate::propagate::Regime;

/// z = √((x − ε̂x)² + (y − ε̂y)²): the distance from the stator centre in clearances (`docs/MODEL.md`
/// notation). Contact when z > 1.
#[inline]
pub fn radius(params: &Params, x: f64, y: f64) -> f64 {
    math::hypot(x - params.offset_x, y - params.offset_y)
}

/// The contact force K_s·g(u, v) with g = (1 − 1/z)(u, v) (`docs/MODEL.md` §1, restoring sign),
/// generated from the model statement.
#[inline]
pub fn contact_force(params: &Params, x: f64, y: f64) -> (f64, f64) {
    let f = coef::contact_force(&ModelParams::of(params), &Position { x, y });
    (f.fx, f.fy)
}

/// Accelerations (x'', y'') of the regime's vector field at time τ (`docs/MODEL.md` §1).
#[inline]
pub fn acceleration(params: &Params, regime: Regime, tau: f64, s: &State) -> (f64, f64) {
    let (sin_t, cos_t) = math::sin_cos(params.speed_ratio * tau + params.phase);
    acceleration_with_phasor(params, regime, cos_t, sin_t, s)
}

/// As [`acceleration`], with the forcing direction (cos θ, sin θ) supplied by the caller (for
/// integrators that carry the forcing as a rotating phasor). The hot path of DOP853 and the
/// hybrid method: the generated functions inline to straight-line arithmetic.
#[inline]
pub fn acceleration_with_phasor(
    params: &Params,
    regime: Regime,
    cos_theta: f64,
    sin_theta: f64,
    s: &State,
) -> (f64, f64) {
    let model = ModelParams::of(params);
    let at = Position { x: s.x, y: s.y };
    let rate = Velocity { vx: s.vx, vy: s.vy };
    let phasor = Phasor {
        ct: cos_theta,
        st: sin_theta,
    };
    let a = coef::free_acceleration(&model, &at, &rate, &phasor);
    match regime {
        Regime::Free => (a.ax, a.ay),
        // The contact regime adds the contact force (every contact piece of the model).
        Regime::Contact => {
            let f = coef::contact_force(&model, &at);
            (a.ax - f.fx, a.ay - f.fy)
        }
    }
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

/// The regime of a state (`docs/MODEL.md` §6 case 14): by the sign of h = z² − 1; on z = 1 (|h| within
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
