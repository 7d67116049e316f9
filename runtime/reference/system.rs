//! The rotor's equations of motion as [`OdeSystem`]s: the 4-state field the reference
//! propagators integrate, and the 6-state form with the forcing carried as a rotating phasor (for
//! the hybrid method's contact phase, `docs/MODEL.md` §8).

use super::ode::OdeSystem;
use crate::coefficients::ModelParams;
use crate::field;
use crate::params::{Params, State};
use crate::propagate::Regime;

/// The regime's vector field on `[x, y, x', y']` ([`field::derivative`]): the regime is fixed,
/// not chosen by the sign of the switching function, so a trajectory just past a switch keeps the
/// field it was given.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RotorSystem {
    /// The model parameters.
    pub params: Params,
    /// Which field to integrate.
    pub regime: Regime,
    /// The slip direction σ of slipping contact (±1), 0 when none is tracked.
    pub slip: f64,
}

impl OdeSystem<4> for RotorSystem {
    #[inline]
    fn rhs(&self, t: f64, y: &[f64; 4]) -> [f64; 4] {
        field::derivative(
            &self.params,
            self.regime,
            self.slip,
            t,
            &State::from_array(*y),
        )
        .to_array()
    }
}

/// [`RotorSystem`] with the model's parameters prepared once, in the generated code's form, and the
/// field picked once (the constant-speed reference propagators build one per step): free flight
/// and frictionless contact without an input force run [`field::unforced_free_acceleration`] and
/// [`field::frictionless_contact_acceleration`] inlined, every other case
/// [`field::acceleration_of_model`] — the arithmetic of [`field::derivative`], so the same bits,
/// without rebuilding the parameters and testing regime, friction and input force at every stage.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PreparedRotorSystem {
    model: ModelParams,
    speed_ratio: f64,
    phase: f64,
    regime: Regime,
    slip: f64,
    field: PreparedField,
}

/// Which field a [`PreparedRotorSystem`] runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum PreparedField {
    /// Free flight without an input force.
    UnforcedFree,
    /// Frictionless contact without an input force.
    UnforcedFrictionlessContact,
    /// Any other regime, slip or input force.
    General,
}

impl PreparedRotorSystem {
    /// The field of `regime` (slip direction `slip`) for `params`.
    #[inline]
    pub fn new(params: &Params, regime: Regime, slip: f64) -> Self {
        let model = ModelParams::of(params);
        let unforced = model.force_x == 0.0 && model.force_y == 0.0;
        let field = match regime {
            Regime::Free if unforced => PreparedField::UnforcedFree,
            Regime::Contact if unforced && slip == 0.0 => {
                PreparedField::UnforcedFrictionlessContact
            }
            _ => PreparedField::General,
        };
        PreparedRotorSystem {
            model,
            speed_ratio: params.speed_ratio,
            phase: params.phase,
            regime,
            slip,
            field,
        }
    }
}

impl OdeSystem<4> for PreparedRotorSystem {
    #[inline(always)]
    fn rhs(&self, t: f64, y: &[f64; 4]) -> [f64; 4] {
        let s = State::from_array(*y);
        let (sin_t, cos_t) = crate::math::sin_cos(self.speed_ratio * t + self.phase);
        let (ax, ay) = match self.field {
            PreparedField::UnforcedFree => {
                field::unforced_free_acceleration(&self.model, cos_t, sin_t, &s)
            }
            PreparedField::UnforcedFrictionlessContact => {
                field::frictionless_contact_acceleration(&self.model, cos_t, sin_t, &s)
            }
            PreparedField::General => {
                field::acceleration_of_model(&self.model, self.regime, self.slip, cos_t, sin_t, &s)
            }
        };
        [s.vx, s.vy, ax, ay]
    }
}

/// The regime's vector field on `[x, y, x', y', c, s]`, where (c, s) = (cos θ, sin θ) is the
/// forcing phasor with c' = −η s, s' = η c: no trigonometry in the right-hand side. Start it with
/// `c = cos(η t0 + φ0)`, `s = sin(η t0 + φ0)`; the time argument is not used.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PhasorRotorSystem {
    /// The model parameters.
    pub params: Params,
    /// Which field to integrate.
    pub regime: Regime,
    /// The slip direction σ of slipping contact (±1), 0 when none is tracked.
    pub slip: f64,
}

impl PhasorRotorSystem {
    /// The 6-state vector `[x, y, x', y', cos θ, sin θ]` at time `t` for rotor state `s`.
    pub fn initial(params: &Params, t: f64, s: &State) -> [f64; 6] {
        let (sin_t, cos_t) = crate::math::sin_cos(params.speed_ratio * t + params.phase);
        [s.x, s.y, s.vx, s.vy, cos_t, sin_t]
    }

    /// The rotor part of a 6-state vector.
    pub fn rotor_state(y: &[f64; 6]) -> State {
        let [x, yy, vx, vy, _, _] = *y;
        State::new(x, yy, vx, vy)
    }
}

impl OdeSystem<6> for PhasorRotorSystem {
    #[inline]
    fn rhs(&self, _t: f64, y: &[f64; 6]) -> [f64; 6] {
        let [x, yy, vx, vy, c, s] = *y;
        let state = State::new(x, yy, vx, vy);
        let (ax, ay) =
            field::acceleration_with_phasor(&self.params, self.regime, self.slip, c, s, &state);
        let eta = self.params.speed_ratio;
        [vx, vy, ax, ay, -eta * s, eta * c]
    }
}

/// The switching function oriented so that it is positive inside `regime`:
/// `(σ h, σ h')` with h = z² − 1, σ = +1 in contact and −1 in free flight. Works on any state
/// vector whose first four components are `[x, y, x', y']`.
#[inline]
pub fn inside_measure<const N: usize>(params: &Params, regime: Regime, y: &[f64; N]) -> (f64, f64) {
    let mut s = [0.0; 4];
    for (a, b) in s.iter_mut().zip(y.iter()) {
        *a = *b;
    }
    let (h, dh) = field::switching_function(params, &State::from_array(s));
    match regime {
        Regime::Contact | Regime::Rolling => (h, dh),
        Regime::Free => (-h, -dh),
    }
}
