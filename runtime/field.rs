//! The full nonlinear piecewise field (`docs/MODEL.md` §1) that the numerical reference
//! integrators and the hybrid method's contact phase integrate, with the switching function and
//! the regime of a state.
//!
//! The equations themselves are generated from the model statement in `codegen/src/model`
//! ([`coef::free_acceleration`], [`coef::contact_force`]); this module only feeds them and applies
//! the contact force in the contact regime. Comparisons of methods stay independent because the test suites keep
//! their own hand-written field (`tests/generated/field.rs`, `tests/reference`).

use crate::coefficients::{
    self as coef, ModelParams, Phasor, Position, Slip, SpeedChange, Velocity,
};
use crate::math;
use crate::params::{Params, State};
use crate::propagate::{EventKind, Regime};

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

/// Accelerations (x'', y'') of the regime's vector field at time τ (`docs/MODEL.md` §1, §10);
/// `slip` is the slip direction σ of slipping contact (±1), 0 when no slip is tracked.
#[inline]
pub fn acceleration(params: &Params, regime: Regime, slip: f64, tau: f64, s: &State) -> (f64, f64) {
    let (sin_t, cos_t) = math::sin_cos(params.speed_ratio * tau + params.phase);
    acceleration_with_phasor(params, regime, slip, cos_t, sin_t, s)
}

/// As [`acceleration`], with the forcing direction (cos θ, sin θ) supplied by the caller (for
/// integrators that carry the forcing as a rotating phasor). The hot path of DOP853 and the
/// hybrid method: the generated functions inline to straight-line arithmetic.
#[inline]
pub fn acceleration_with_phasor(
    params: &Params,
    regime: Regime,
    slip: f64,
    cos_theta: f64,
    sin_theta: f64,
    s: &State,
) -> (f64, f64) {
    acceleration_of_model(
        &ModelParams::of(params),
        regime,
        slip,
        cos_theta,
        sin_theta,
        s,
    )
}

/// As [`acceleration_with_phasor`], with the model parameters in the generated code's form
/// prepared by the caller (`ModelParams::of`, once per parameter set instead of once per call:
/// the same inputs, so the same bits).
#[inline]
pub fn acceleration_of_model(
    model: &ModelParams,
    regime: Regime,
    slip: f64,
    cos_theta: f64,
    sin_theta: f64,
    s: &State,
) -> (f64, f64) {
    let (at, rate, phasor) = state_inputs(cos_theta, sin_theta, s);
    let (ax, ay) = match regime {
        Regime::Free => {
            let a = coef::free_acceleration(model, &at, &rate, &phasor);
            (a.ax, a.ay)
        }
        Regime::Contact => return contact_acceleration(model, slip, cos_theta, sin_theta, s),
        // The rolling field has the input force inside G (it changes λ).
        Regime::Rolling => {
            let a = coef::rolling_acceleration(model, &at, &rate, &phasor);
            return (a.ax, a.ay);
        }
    };
    with_input_force(model, (ax, ay))
}

/// The acceleration `(ax, ay)` plus the input force's share (`docs/MODEL.md` §15): a constant
/// input force adds its acceleration in free flight and contact; without one nothing is added,
/// so the field keeps its bits.
#[inline(always)]
fn with_input_force(model: &ModelParams, (ax, ay): (f64, f64)) -> (f64, f64) {
    if model.force_x == 0.0 && model.force_y == 0.0 {
        return (ax, ay);
    }
    let u = coef::input_acceleration(model);
    (ax + u.ax, ay + u.ay)
}

/// [`acceleration_of_model`] in contact (`slip` as there): the contact phase's right-hand side,
/// inlined into the integrators' stages (the other regimes stay out of line).
#[inline(always)]
pub fn contact_acceleration(
    model: &ModelParams,
    slip: f64,
    cos_theta: f64,
    sin_theta: f64,
    s: &State,
) -> (f64, f64) {
    let (at, rate, phasor) = state_inputs(cos_theta, sin_theta, s);
    let a = coef::free_acceleration(model, &at, &rate, &phasor);
    // Frictionless contact (μ = 0 tracks no slip: σ = 0) adds the elastic contact force;
    // slipping adds the elastic force and friction μσN t.
    let acceleration = if slip == 0.0 {
        let f = coef::contact_force(model, &at);
        (a.ax - f.fx, a.ay - f.fy)
    } else {
        let f = coef::slipping_contact_force(model, &at, &Slip { sigma: slip });
        (a.ax - f.fx, a.ay - f.fy)
    };
    with_input_force(model, acceleration)
}

/// [`contact_acceleration`] for frictionless contact (σ = 0) without an input force: the same
/// arithmetic without its two run-time tests, for an integrator that picks its field once per
/// segment (the hybrid method's contact steps).
#[inline(always)]
pub fn frictionless_contact_acceleration(
    model: &ModelParams,
    cos_theta: f64,
    sin_theta: f64,
    s: &State,
) -> (f64, f64) {
    let (ax, ay) = unforced_free_acceleration(model, cos_theta, sin_theta, s);
    let f = coef::contact_force(model, &Position { x: s.x, y: s.y });
    (ax - f.fx, ay - f.fy)
}

/// [`acceleration_of_model`] in free flight without an input force: the generated free field
/// alone, inlined, for an integrator that picks its field once per segment (the reference
/// propagators' free steps). The same arithmetic, so the same bits.
#[inline(always)]
pub fn unforced_free_acceleration(
    model: &ModelParams,
    cos_theta: f64,
    sin_theta: f64,
    s: &State,
) -> (f64, f64) {
    let (at, rate, phasor) = state_inputs(cos_theta, sin_theta, s);
    let a = coef::free_acceleration(model, &at, &rate, &phasor);
    (a.ax, a.ay)
}

/// The force a changing running speed adds to the unbalance forcing F (cos θ, sin θ)
/// (`docs/MODEL.md` §14): −η_m ρ̂ η' (−sin θ, cos θ), generated from the model's
/// `unbalance_at_varying_speed`. It acts in every regime (it is part of the forcing).
#[inline]
pub fn speed_change_force(
    params: &Params,
    speed_rate: f64,
    cos_theta: f64,
    sin_theta: f64,
) -> (f64, f64) {
    let f = coef::speed_change_force(
        &ModelParams::of(params),
        &Phasor {
            ct: cos_theta,
            st: sin_theta,
        },
        &SpeedChange { speed_rate },
    );
    (f.fx, f.fy)
}

/// The regime's vector field s' = (x', y', x'', y'') at time τ.
#[inline]
pub fn derivative(params: &Params, regime: Regime, slip: f64, tau: f64, s: &State) -> State {
    let (ax, ay) = acceleration(params, regime, slip, tau, s);
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
        let (ax, ay) = acceleration(params, Regime::Free, 0.0, tau, state);
        state.vx * state.vx + state.vy * state.vy + u * ax + v * ay
    };
    if sign <= 0.0 {
        Regime::Free
    } else if params.friction_coefficient > 0.0 && friction_at(params, tau, state).rolls(params) {
        // A start in contact with w = 0 exactly and |λ| ≤ μN rolls (`docs/MODEL.md` §10).
        Regime::Rolling
    } else {
        Regime::Contact
    }
}

/// The friction quantities of a contact state (`docs/MODEL.md` §10), generated from the model:
/// the normal force N, the slip velocity w and λ, the tangential force that would keep w at 0.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Friction {
    /// N = nᵀK_s g, the normal elastic contact force (≥ 0 in contact).
    pub normal: f64,
    /// w = q'·t + ρ_R η, the slip velocity of the rotor surface at the contact point.
    pub slip_velocity: f64,
    /// λ = t·G − (q'·t)(q'·n)/z.
    pub lambda: f64,
}

impl Friction {
    /// Whether rolling holds: w = 0 exactly and |λ| ≤ μN.
    fn rolls(&self, params: &Params) -> bool {
        self.slip_velocity == 0.0 && self.within_cone(params)
    }

    /// |λ| ≤ μN: friction can keep w at 0.
    pub fn within_cone(&self, params: &Params) -> bool {
        math::abs(self.lambda) <= params.friction_coefficient * self.normal
    }

    /// w' while slipping in direction `slip`: λ − μσN.
    pub fn slip_acceleration(&self, params: &Params, slip: f64) -> f64 {
        self.lambda - params.friction_coefficient * slip * self.normal
    }

    /// sign λ as a slip direction (+1 when λ = 0).
    pub fn lambda_direction(&self) -> f64 {
        if self.lambda < 0.0 { -1.0 } else { 1.0 }
    }
}

/// [`Friction`] at a state and time.
#[inline]
pub fn friction_at(params: &Params, tau: f64, state: &State) -> Friction {
    let (sin_t, cos_t) = math::sin_cos(params.speed_ratio * tau + params.phase);
    friction_with_phasor(params, cos_t, sin_t, state)
}

/// [`friction_at`] with the forcing direction supplied by the caller.
#[inline]
pub fn friction_with_phasor(
    params: &Params,
    cos_theta: f64,
    sin_theta: f64,
    s: &State,
) -> Friction {
    let (model, at, rate, phasor) = inputs(params, cos_theta, sin_theta, s);
    let f = coef::friction_state(&model, &at, &rate, &phasor);
    Friction {
        normal: f.normal,
        slip_velocity: f.slip_velocity,
        lambda: f.lambda,
    }
}

/// What happens where the slip velocity w reaches 0 while slipping in direction `slip`
/// (`docs/MODEL.md` §10).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SlipZero {
    /// |λ| ≤ μN: the rotor rolls (`roll`).
    Roll,
    /// |λ| > μN with sign λ ≠ σ: the slip reverses (`reverse`).
    Reverse,
    /// |λ| > μN with sign λ = σ: w only touched 0; slipping goes on, no event.
    Touch,
}

/// The decision at w = 0 while slipping in direction `slip`.
pub fn at_slip_zero(params: &Params, tau: f64, state: &State, slip: f64) -> SlipZero {
    let f = friction_at(params, tau, state);
    if f.within_cone(params) {
        SlipZero::Roll
    } else if f.lambda_direction() == slip {
        SlipZero::Touch
    } else {
        SlipZero::Reverse
    }
}

/// The slip direction σ of slipping contact starting at `state` (`docs/MODEL.md` §10): 0 when no
/// slip is tracked (μ = 0); on entering contact (or a start in contact) sign w, or sign λ where
/// w = 0 exactly; after `reverse` or `slip` (w = 0, where w's own sign is rounding) sign λ.
pub fn slip_direction(params: &Params, tau: f64, state: &State, cause: Option<EventKind>) -> f64 {
    if params.friction_coefficient <= 0.0 {
        return 0.0;
    }
    let f = friction_at(params, tau, state);
    match cause {
        Some(EventKind::Reverse | EventKind::Slip) => f.lambda_direction(),
        _ if f.slip_velocity > 0.0 => 1.0,
        _ if f.slip_velocity < 0.0 => -1.0,
        _ => f.lambda_direction(),
    }
}

/// (N', λ') along the rolling field at a state, with the forcing direction supplied by the
/// caller: the slope of the `slip` switch function μN − |λ| (generated, `rolling_rates`).
#[inline]
pub fn rolling_rates_with_phasor(
    params: &Params,
    cos_theta: f64,
    sin_theta: f64,
    s: &State,
) -> (f64, f64) {
    let (model, at, rate, phasor) = inputs(params, cos_theta, sin_theta, s);
    let r = coef::rolling_rates(&model, &at, &rate, &phasor);
    (r.normal_rate, r.lambda_rate)
}

/// The generated functions' inputs for a state and forcing direction, without the model.
#[inline]
fn state_inputs(cos_theta: f64, sin_theta: f64, s: &State) -> (Position, Velocity, Phasor) {
    (
        Position { x: s.x, y: s.y },
        Velocity { vx: s.vx, vy: s.vy },
        Phasor {
            ct: cos_theta,
            st: sin_theta,
        },
    )
}

/// The generated functions' inputs for a state and forcing direction.
#[inline]
fn inputs(
    params: &Params,
    cos_theta: f64,
    sin_theta: f64,
    s: &State,
) -> (ModelParams, Position, Velocity, Phasor) {
    (
        ModelParams::of(params),
        Position { x: s.x, y: s.y },
        Velocity { vx: s.vx, vy: s.vy },
        Phasor {
            ct: cos_theta,
            st: sin_theta,
        },
    )
}
