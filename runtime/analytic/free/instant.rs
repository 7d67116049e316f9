//! A free segment's closed form at one local time: the time-dependent values every segment of
//! a parameter set shares ([`FreeInstant`]) and the evaluation of one form there ([`evaluate`]).

use super::super::segment::Point;
use super::{Form, FreeConstants};
use crate::coefficients::{
    self as coef, ForcedBasis, FreeBasis, FreeDampedFrequency, ModelParams, Phasor,
};
use crate::math;
use crate::params::State;

/// The time-dependent part of the free closed form at local time `s`: the basis (EC, ES), the
/// forcing's rotation (cos ηs, sin ηs) and, in the resonance-stable form, the forced basis. It
/// depends on the free constants only, so segments of one parameter set evaluated at the same
/// `s` share it (the stepper's transition evaluates six unit segments at its step length).
#[derive(Clone, Copy, Debug)]
pub(crate) struct FreeInstant {
    s: f64,
    basis: FreeBasis,
    /// (cos ηs, sin ηs).
    rotation: (f64, f64),
    forced: Option<ForcedBasis>,
}

impl FreeInstant {
    /// The values at `s` for segments of `constants`.
    pub(crate) fn at(constants: &FreeConstants, s: f64) -> Self {
        let (ec, es) = constants.rates.basis(s);
        Self::with_basis(constants, s, FreeBasis { ec, es })
    }

    /// [`Self::at`] given the basis at `s`, which depends on ν and β² only: the stepper keeps
    /// it across parameter changes that leave them ([`FreeConstants::damping_key`]).
    pub(crate) fn with_basis(constants: &FreeConstants, s: f64, basis: FreeBasis) -> Self {
        let (sd, cd) = math::sin_cos(constants.model.speed_ratio * s);
        FreeInstant {
            s,
            basis,
            rotation: (cd, sd),
            forced: constants
                .resonance
                .map(|r| r.basis(s, basis.ec, basis.es, (cd, sd))),
        }
    }

    /// The basis (EC, ES) at `s`.
    pub(crate) fn basis(&self) -> FreeBasis {
        self.basis
    }

    /// (cos ηs, sin ηs): the forcing phasor's rotation over `s`.
    pub(crate) fn rotation(&self) -> (f64, f64) {
        self.rotation
    }
}

/// A free segment's point at `at`: its closed form (`form`, from start phasor `phase0`)
/// evaluated with the model `model` and moved back by the static deflection of `c`.
#[inline(always)]
pub(super) fn evaluate(
    c: &FreeConstants,
    model: &ModelParams,
    phase0: (f64, f64),
    form: &Form,
    at: &FreeInstant,
) -> Point {
    let beta = FreeDampedFrequency {
        beta_sq: c.beta_sq(),
    };
    let (x, y, vx, vy, h, dh) = match form {
        Form::Steady(homogeneous) => {
            // The forcing phasor at s by angle addition from the segment start.
            let (c0, s0) = phase0;
            let (cd, sd) = at.rotation;
            let phasor = Phasor {
                ct: c0 * cd - s0 * sd,
                st: s0 * cd + c0 * sd,
            };
            let r = coef::free_eval(model, &phasor, &c.particular, &beta, homogeneous, &at.basis);
            (r.x, r.y, r.vx, r.vy, r.h, r.dh)
        }
        Form::Forced {
            start,
            forcing,
            resonance,
        } => {
            let basis = at.basis;
            let forced = at
                .forced
                .unwrap_or_else(|| resonance.basis(at.s, basis.ec, basis.es, at.rotation));
            let r = coef::free_forced_eval(model, &beta, start, &basis, forcing, &forced);
            (r.x, r.y, r.vx, r.vy, r.h, r.dh)
        }
    };
    let shift = c.deflection;
    let (x, y) = if shift == (0.0, 0.0) {
        (x, y)
    } else {
        (x + shift.0, y + shift.1)
    };
    Point {
        state: State::new(x, y, vx, vy),
        h,
        dh,
    }
}
