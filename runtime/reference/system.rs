//! The rotor's equations of motion as [`OdeSystem`]s: the 4-state field the reference
//! propagators integrate, and the 6-state form with the forcing carried as a rotating phasor (for
//! the hybrid method's contact phase, `docs/MODEL.md` §8).

use super::ode::OdeSystem;
use crate::coefficients::{ModelParams, Phasor};
use crate::field::{self, Field};
use crate::geometry;
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
/// field picked once (the constant-speed reference propagators build one per step): the
/// arithmetic of [`field::derivative`], so the same bits, without rebuilding the parameters and
/// picking the field at every stage.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PreparedRotorSystem {
    model: ModelParams,
    field: Field,
}

impl PreparedRotorSystem {
    /// The field of `regime` (slip direction `slip`) for `params`.
    #[inline]
    pub fn new(params: &Params, regime: Regime, slip: f64) -> Self {
        PreparedRotorSystem {
            model: ModelParams::of(params),
            field: Field::of(regime, slip),
        }
    }
}

impl OdeSystem<4> for PreparedRotorSystem {
    #[inline(always)]
    fn rhs(&self, t: f64, y: &[f64; 4]) -> [f64; 4] {
        let s = State::from_array(*y);
        let phasor = field::phasor(&self.model, t);
        let (ax, ay) = field::acceleration(&self.model, self.field, &phasor, &s);
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
        let p = field::phasor(&ModelParams::of(params), t);
        [s.x, s.y, s.vx, s.vy, p.ct, p.st]
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
        let model = ModelParams::of(&self.params);
        let field = Field::of(self.regime, self.slip);
        let (ax, ay) = field::acceleration(&model, field, &Phasor { ct: c, st: s }, &state);
        let eta = self.params.speed_ratio;
        [vx, vy, ax, ay, -eta * s, eta * c]
    }
}

/// The switching function oriented so that it is positive inside `regime`:
/// `(σ h, σ h')` with h = z² − 1 ([`crate::geometry::point`]), σ = +1 in contact and −1 in free
/// flight. Works on any state vector whose first four components are `[x, y, x', y']`.
#[inline]
pub fn inside_measure<const N: usize>(
    model: &ModelParams,
    regime: Regime,
    y: &[f64; N],
) -> (f64, f64) {
    let mut s = [0.0; 4];
    for (a, b) in s.iter_mut().zip(y.iter()) {
        *a = *b;
    }
    let p = geometry::point(model, State::from_array(s));
    match regime {
        Regime::Contact | Regime::Rolling => (p.h, p.dh),
        Regime::Free => (-p.h, -p.dh),
    }
}
