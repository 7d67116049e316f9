//! Free flight over one step of fixed length as an affine map of its start (`docs/MODEL.md` §4):
//! w(s) = Φ(s)·w(0) + G(s)·(cos θ0, sin θ0), the stepper's fast path. Both come from the
//! generated step formulas (`free_step_transition`, `free_step_forcing`: the closed form at unit
//! inputs, simplified at build time), except G in the resonance-stable form (§11), whose columns
//! are that form evaluated on the unit start phasors.

use super::{FreeConstants, FreeInstant, FreeSegment};
use crate::coefficients::{self as coef, ForcingRotation, FreeDampedFrequency};
use crate::params::State;

/// Φ(s) at `at` for `constants` without input force, row-major (`phi[i][j]` is component i of
/// the end state for a unit component j at the start; order x, y, x', y'). The homogeneous
/// response is the same in both forms.
#[inline(always)]
pub(crate) fn transition_matrix(constants: &FreeConstants, at: &FreeInstant) -> [[f64; 4]; 4] {
    let beta = FreeDampedFrequency {
        beta_sq: constants.beta_sq(),
    };
    let p = coef::free_step_transition(&constants.model, &beta, &at.basis());
    [
        [p.p00, p.p01, p.p02, p.p03],
        [p.p10, p.p11, p.p12, p.p13],
        [p.p20, p.p21, p.p22, p.p23],
        [p.p30, p.p31, p.p32, p.p33],
    ]
}

/// G(s) at `at` for `constants` without input force: row i is component i of the end state
/// from rest, for the start phasors (1, 0) and (0, 1). Inlined with [`transition_matrix`] into
/// the caller, which has just written `at` and `constants`: values stay in registers instead of
/// being reloaded, with wider loads than their stores, from memory.
#[inline(always)]
pub(crate) fn forcing_matrix(constants: &FreeConstants, at: &FreeInstant) -> [[f64; 2]; 4] {
    if constants.resonant() {
        return resonant_forcing_matrix(constants, at);
    }
    let beta = FreeDampedFrequency {
        beta_sq: constants.beta_sq(),
    };
    let (ce, se) = at.rotation();
    let g = coef::free_step_forcing(
        &constants.model,
        &constants.particular,
        &beta,
        &at.basis(),
        &ForcingRotation { ce, se },
    );
    [
        [g.g00, g.g01],
        [g.g10, g.g11],
        [g.g20, g.g21],
        [g.g30, g.g31],
    ]
}

/// [`forcing_matrix`] in the resonance-stable form: its columns are that form evaluated on the
/// unit start phasors.
#[inline(never)]
fn resonant_forcing_matrix(constants: &FreeConstants, at: &FreeInstant) -> [[f64; 2]; 4] {
    let column = |phasor| FreeSegment::state_at(constants, phasor, State::default(), at);
    let (c, s) = (column((1.0, 0.0)), column((0.0, 1.0)));
    [[c.x, s.x], [c.y, s.y], [c.vx, s.vx], [c.vy, s.vy]]
}
