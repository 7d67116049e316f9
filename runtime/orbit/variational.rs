//! The variational equations of a contact segment (`docs/MODEL.md` §18): the state s and its
//! state-transition matrix Φ = ∂s(τ)/∂s(τ0) integrated together,
//!
//! ```text
//! s' = f(τ, s),     Φ' = A(τ, s) Φ,     A = [[0, I], [∂q''/∂q, ∂q''/∂q']],     Φ(τ0) = I,
//! ```
//!
//! as one 20-state system by DOP853 (the same integrator core as the reference methods), with
//! the field and its Jacobian generated from the model (`contact_field_jacobian`,
//! `slipping_field_jacobian`, `rolling_field_jacobian`). Free flight needs no integration: its
//! transition matrix is the closed form's (`free_step_transition`, see [`super::segments`]).

use super::matrix::{Mat4, combine};
use crate::coefficients::{self as coef, FieldJacobian, ModelParams, Phasor, Slip};
use crate::field::{self, Field};
use crate::geometry::{position, velocity};
use crate::params::State;
use crate::reference::OdeSystem;

/// The 20 states of the augmented system: s (4) then Φ row by row (16).
pub const AUGMENTED: usize = 20;

/// The Jacobian ∂q''/∂(x, y, x', y') of a contact regime's `field` at `s` (forcing direction
/// `phasor`): the generated Jacobian of the regime's field. `None` for free flight, whose
/// transition matrix is in closed form and never integrated.
#[inline]
pub fn jacobian(
    model: &ModelParams,
    field: Field,
    phasor: &Phasor,
    s: &State,
) -> Option<FieldJacobian> {
    let at = position(s);
    match field {
        Field::Free => None,
        Field::Contact => Some(coef::contact_field_jacobian(model, &at)),
        Field::Slipping(sigma) => Some(coef::slipping_field_jacobian(model, &at, &Slip { sigma })),
        Field::Rolling => Some(coef::rolling_field_jacobian(
            model,
            &at,
            &velocity(s),
            phasor,
        )),
    }
}

/// The augmented field (s, Φ)' = (f(τ, s), A Φ) of one contact regime.
#[derive(Clone, Copy, Debug)]
pub struct Augmented<'a> {
    /// The model's parameters.
    pub model: &'a ModelParams,
    /// The regime's field.
    pub field: Field,
}

/// s and Φ from the augmented state.
#[inline]
pub fn unpack(y: &[f64; AUGMENTED]) -> (State, Mat4) {
    let mut it = y.iter().copied();
    let mut next = move || it.next().unwrap_or(0.0);
    let s = State::new(next(), next(), next(), next());
    let m: Mat4 = core::array::from_fn(|_| core::array::from_fn(|_| next()));
    (s, m)
}

/// The augmented state of s and Φ.
#[inline]
pub fn pack(s: &State, m: &Mat4) -> [f64; AUGMENTED] {
    let mut out = [0.0; AUGMENTED];
    let values = s.to_array().into_iter().chain(m.iter().flatten().copied());
    for (o, v) in out.iter_mut().zip(values) {
        *o = v;
    }
    out
}

impl Augmented<'_> {
    /// The acceleration of the field at `s` and time `t`.
    #[inline]
    pub fn acceleration(&self, t: f64, s: &State) -> (f64, f64) {
        field::acceleration(self.model, self.field, &field::phasor(self.model, t), s)
    }
}

impl OdeSystem<AUGMENTED> for Augmented<'_> {
    #[inline]
    fn rhs(&self, t: f64, y: &[f64; AUGMENTED]) -> [f64; AUGMENTED] {
        let (s, phi) = unpack(y);
        let phasor = field::phasor(self.model, t);
        let (ax, ay) = field::acceleration(self.model, self.field, &phasor, &s);
        // A free field never reaches here (segments integrate contact only): zero rows then.
        let j = jacobian(self.model, self.field, &phasor, &s).unwrap_or_default();
        // Rows of AΦ: the velocity rows are Φ's rows 2 and 3; the acceleration rows are the
        // Jacobian's rows times Φ.
        let rows = [
            phi[2],
            phi[3],
            combine([j.xx, j.xy, j.xvx, j.xvy], &phi),
            combine([j.yx, j.yy, j.yvx, j.yvy], &phi),
        ];
        pack(&State::new(s.vx, s.vy, ax, ay), &rows)
    }
}
