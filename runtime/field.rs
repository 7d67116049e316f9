//! Each regime's field (`docs/MODEL.md` §1, §10, §15) as the numerical methods integrate it, the
//! forcing phase, the regime of a state and friction's decisions.
//!
//! Every formula is generated from the model statement in `codegen/src/model`: the regime fields
//! (`free_field`, `contact_field`, `slipping_field`, `rolling_acceleration`, each with the
//! unbalance and the input force), the forcing phase (`forcing_phase`), the friction quantities
//! (`friction_state`, `friction_cone`) and the switching function (through [`crate::geometry`]).
//! This module only picks and feeds them. Comparisons of methods stay independent because the
//! test suites keep their own hand-written field (`tests/generated/field.rs`, `tests/reference`).

use crate::coefficients::{self as coef, ModelParams, Phasor, Slip, SpeedChange, Time};
use crate::geometry::{self, position, velocity};
use crate::math;
use crate::params::{Params, State};
use crate::propagate::{EventKind, Regime};
use crate::rounding;

/// The forcing direction (cos θ, sin θ) at time `t`, θ = ητ + φ0 (the generated
/// `forcing_phase`): the one place the runtime turns a time into the forcing's phase. θ is not
/// reduced before its sine and cosine (`math::sin_cos` reduces it exactly), so the phase has the
/// rounding of θ itself and no more.
#[inline]
pub fn phasor(model: &ModelParams, t: f64) -> Phasor {
    let theta = coef::forcing_phase(model, &Time { t }).theta;
    let (st, ct) = math::sin_cos(theta);
    Phasor { ct, st }
}

/// `phasor`, the forcing direction at some time, turned by the phase the forcing advances in a
/// further time `s` at constant speed (η·s): the direction at the later time, as [`phasor`]
/// gives it to rounding. For a short `s` the angle needs no argument reduction, so this is the
/// cheaper of the two inside a step or a sub-step.
#[inline]
pub fn phasor_after(model: &ModelParams, phasor: &Phasor, s: f64) -> Phasor {
    turn(phasor, math::sin_cos(model.speed_ratio * s))
}

/// [`phasor_after`] for a time inside an integration step, where η·s is a small angle: its
/// sine and cosine by their polynomials (`math::sin_cos_small`, within an ulp of
/// `math::sin_cos`; libm's beyond `math::SMALL_ANGLE`), the cheaper at every stage.
#[inline]
pub fn phasor_within_step(model: &ModelParams, phasor: &Phasor, s: f64) -> Phasor {
    turn(phasor, math::sin_cos_small(model.speed_ratio * s))
}

/// `phasor` turned by the angle whose (sine, cosine) is `(sd, cd)`.
#[inline(always)]
fn turn(phasor: &Phasor, (sd, cd): (f64, f64)) -> Phasor {
    let (c0, s0) = (phasor.ct, phasor.st);
    Phasor {
        ct: c0 * cd - s0 * sd,
        st: s0 * cd + c0 * sd,
    }
}

/// Which field acts: a regime, and in slipping contact the slip direction σ.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Field {
    /// Free flight.
    Free,
    /// Frictionless contact (μ = 0 tracks no slip).
    Contact,
    /// Contact slipping in direction σ = ±1.
    Slipping(f64),
    /// Rolling contact (w ≡ 0).
    Rolling,
}

impl Field {
    /// The field of `regime` with slip direction `slip` (±1 while slipping, 0 when no slip is
    /// tracked).
    #[inline]
    pub fn of(regime: Regime, slip: f64) -> Field {
        match regime {
            Regime::Free => Field::Free,
            Regime::Contact if slip == 0.0 => Field::Contact,
            Regime::Contact => Field::Slipping(slip),
            Regime::Rolling => Field::Rolling,
        }
    }
}

/// The acceleration (x'', y'') of `field` at `s` with the forcing direction `phasor`: the
/// generated field of the regime, inlined into the integrators' stages.
#[inline(always)]
pub fn acceleration(model: &ModelParams, field: Field, phasor: &Phasor, s: &State) -> (f64, f64) {
    let (at, rate) = (position(s), velocity(s));
    let a = match field {
        Field::Free => coef::free_field(model, &at, &rate, phasor),
        Field::Contact => coef::contact_field(model, &at, &rate, phasor),
        Field::Slipping(sigma) => coef::slipping_field(model, &at, &rate, phasor, &Slip { sigma }),
        Field::Rolling => coef::rolling_acceleration(model, &at, &rate, phasor),
    };
    (a.ax, a.ay)
}

/// The field of `regime` (slip direction `slip`) at time τ: s' = (x', y', x'', y'').
#[inline]
pub fn derivative(params: &Params, regime: Regime, slip: f64, tau: f64, s: &State) -> State {
    let model = ModelParams::of(params);
    let (ax, ay) = acceleration(&model, Field::of(regime, slip), &phasor(&model, tau), s);
    State::new(s.vx, s.vy, ax, ay)
}

/// The force a changing running speed adds to the unbalance forcing F (cos θ, sin θ)
/// (`docs/MODEL.md` §14): −η_m ρ̂ η' (−sin θ, cos θ), generated from the model's
/// `unbalance_at_varying_speed`. It acts in every regime (it is part of the forcing).
#[inline]
pub fn speed_change_force(model: &ModelParams, speed_rate: f64, phasor: &Phasor) -> (f64, f64) {
    let f = coef::speed_change_force(model, phasor, &SpeedChange { speed_rate });
    (f.fx, f.fy)
}

/// The regime of a state (`docs/MODEL.md` §6 case 14): by the sign of h = z² − 1; on z = 1 (|h|
/// within [`rounding::VALUE`]), by the sign of h' (the radial velocity) unless it too is within its
/// rounding (a tangential start: deciding by the rounding's sign would start a zero-length
/// regime), then of h'' (both fields agree on z = 1, where g = 0, so the free field is used);
/// free when all three vanish.
pub fn regime_of(params: &Params, tau: f64, state: &State) -> Regime {
    let model = ModelParams::of(params);
    let p = geometry::point(&model, *state);
    let sign = if math::abs(p.h) > rounding::VALUE {
        p.h
    } else if math::abs(p.dh) > geometry::dh_rounding(&model, state) {
        p.dh
    } else {
        let free = acceleration(&model, Field::Free, &phasor(&model, tau), state);
        geometry::curvature(&model, state, free)
    };
    if sign <= 0.0 {
        Regime::Free
    } else if model.friction_coefficient > 0.0 && friction_at(params, tau, state).rolls() {
        // A start in contact with w = 0 exactly and |λ| ≤ μN rolls (`docs/MODEL.md` §10).
        Regime::Rolling
    } else {
        Regime::Contact
    }
}

/// The friction quantities of a contact state (`docs/MODEL.md` §10), generated from the model:
/// the normal force N, the slip velocity w, λ (the tangential force that would keep w at 0) and
/// the friction cone's margins μN ∓ λ.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Friction {
    /// N = nᵀK_s g, the normal elastic contact force (≥ 0 in contact).
    pub normal: f64,
    /// w = q'·t + ρ_R η, the slip velocity of the rotor surface at the contact point.
    pub slip_velocity: f64,
    /// λ = t·G − (q'·t)(q'·n)/z.
    pub lambda: f64,
    /// μN − λ and μN + λ: friction can keep w at 0 while both are ≥ 0.
    pub cone: (f64, f64),
}

impl Friction {
    /// Whether rolling holds: w = 0 exactly and |λ| ≤ μN.
    pub fn rolls(&self) -> bool {
        self.slip_velocity == 0.0 && self.within_cone()
    }

    /// |λ| ≤ μN: friction can keep w at 0.
    pub fn within_cone(&self) -> bool {
        self.cone.0 >= 0.0 && self.cone.1 >= 0.0
    }

    /// sign λ as a slip direction (+1 when λ = 0).
    pub fn lambda_direction(&self) -> f64 {
        if self.lambda < 0.0 { -1.0 } else { 1.0 }
    }

    /// The slip direction σ of slipping contact starting here after a switch of kind `cause`
    /// (`docs/MODEL.md` §10): on entering contact (or a start in contact) sign w, or sign λ
    /// where w = 0 exactly; after `reverse` or `slip` (w = 0, where w's own sign is rounding)
    /// sign λ. The one rule for every model.
    pub fn slip_direction(&self, cause: Option<EventKind>) -> f64 {
        match cause {
            Some(EventKind::Reverse | EventKind::Slip) => self.lambda_direction(),
            _ if self.slip_velocity > 0.0 => 1.0,
            _ if self.slip_velocity < 0.0 => -1.0,
            _ => self.lambda_direction(),
        }
    }

    /// The decision where w reaches 0 while slipping in direction `slip` ([`SlipZero`]): the one
    /// rule for every model.
    pub fn at_slip_zero(&self, slip: f64) -> SlipZero {
        if self.within_cone() {
            SlipZero::Roll
        } else if self.lambda_direction() == slip {
            SlipZero::Touch
        } else {
            SlipZero::Reverse
        }
    }
}

/// [`Friction`] at a state and time.
#[inline]
pub fn friction_at(params: &Params, tau: f64, state: &State) -> Friction {
    let model = ModelParams::of(params);
    friction_with_phasor(&model, &phasor(&model, tau), state)
}

/// [`friction_at`] with the forcing direction supplied by the caller.
#[inline]
pub fn friction_with_phasor(model: &ModelParams, phasor: &Phasor, s: &State) -> Friction {
    let (at, rate) = (position(s), velocity(s));
    let f = coef::friction_state(model, &at, &rate, phasor);
    let cone = coef::friction_cone(model, &at, &rate, phasor);
    Friction {
        normal: f.normal,
        slip_velocity: f.slip_velocity,
        lambda: f.lambda,
        cone: (cone.upper, cone.lower),
    }
}

/// The `slip` switch function of rolling, min(μN − λ, μN + λ) = μN − |λ| (positive while
/// rolling holds), and its rate along the rolling field (generated `friction_cone_rates`).
#[inline]
pub fn cone_margin(model: &ModelParams, phasor: &Phasor, s: &State) -> (f64, f64) {
    let c = coef::friction_cone_rates(model, &position(s), &velocity(s), phasor);
    if c.upper <= c.lower {
        (c.upper, c.upper_rate)
    } else {
        (c.lower, c.lower_rate)
    }
}

/// The slip velocity w = q'·t + ρ_R η of a state (generated `slip_velocity`).
#[inline]
pub fn slip_velocity(model: &ModelParams, s: &State) -> f64 {
    coef::slip_velocity(model, &position(s), &velocity(s)).w
}

/// w' while slipping in direction `slip` (generated `slip_rate`: λ − μσN).
#[inline]
pub fn slip_rate(model: &ModelParams, phasor: &Phasor, s: &State, slip: f64) -> f64 {
    coef::slip_rate(
        model,
        &position(s),
        &velocity(s),
        phasor,
        &Slip { sigma: slip },
    )
    .rate
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

/// The decision at w = 0 while slipping in direction `slip`, with the forcing direction
/// `phasor`.
pub fn at_slip_zero(model: &ModelParams, phasor: &Phasor, state: &State, slip: f64) -> SlipZero {
    friction_with_phasor(model, phasor, state).at_slip_zero(slip)
}

/// The slip direction σ of slipping contact starting at `state` (`docs/MODEL.md` §10): 0 when no
/// slip is tracked (μ = 0); on entering contact (or a start in contact) sign w, or sign λ where
/// w = 0 exactly; after `reverse` or `slip` (w = 0, where w's own sign is rounding) sign λ.
pub fn slip_direction(params: &Params, tau: f64, state: &State, cause: Option<EventKind>) -> f64 {
    if params.friction_coefficient <= 0.0 {
        return 0.0;
    }
    friction_at(params, tau, state).slip_direction(cause)
}
