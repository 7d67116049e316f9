//! Saltation matrices (`docs/MODEL.md` §18): how a perturbation crosses a switch. A switch at
//! h(s) = 0 from the field f⁻ to f⁺ moves with the start state, and the perturbation after it is
//!
//! ```text
//! S = I + (f⁺ − f⁻) ∇hᵀ / (∇h·f⁻)        (h without explicit time dependence)
//! ```
//!
//! applied to the one before. Where the field is continuous across the switch, S = I:
//!
//! - `enter`, `exit` between free flight and contact, with or without slipping friction: on
//!   z = 1 the elastic force K_s·g = K_s (z − 1) n vanishes, and so does the friction μσN t
//!   (N = (z − 1) nᵀK_s n), so f⁺ = f⁻ there (checked by `tests/orbit.rs`);
//! - `slip` (rolling → slipping): it happens where |λ| = μN with σ = sign λ, where rolling's
//!   tangential force λ t equals slipping's μσN t.
//!
//! The friction force jumps at `reverse` (σ → −σ: by 2μN t) and `roll` (μσN t → λ t), and the
//! rolling force λ t at rolling's `exit`: there S is the formula above, with h the slip velocity
//! w (generated `slip_velocity_gradient`) or z² − 1 (generated `switching_gradient`). After `roll`
//! S maps every perturbation into the surface w = 0 (∇w·f_roll = 0: rolling keeps w): the
//! monodromy of a rolling orbit is singular, with a multiplier 0.

use super::matrix::{IDENTITY, Mat4, dot};
use crate::coefficients::{self as coef, ModelParams, StateGradient};
use crate::field::{self, Field};
use crate::geometry::{position, velocity};
use crate::params::State;
use crate::propagate::{Event, EventKind};

/// Why a saltation matrix does not exist.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tangential {
    /// The switch's time.
    pub time: f64,
    /// Its kind.
    pub kind: EventKind,
}

/// The state's rate (x', y', x'', y'') in `field` at `s` and time `t`.
fn rate(model: &ModelParams, field: Field, t: f64, s: &State) -> [f64; 4] {
    let (ax, ay) = field::acceleration(model, field, &field::phasor(model, t), s);
    [s.vx, s.vy, ax, ay]
}

/// Whether the field is continuous across a switch of `kind` from `before` to `after` (S = I;
/// see the module documentation).
pub fn continuous(kind: EventKind, before: Field) -> bool {
    match kind {
        EventKind::Enter | EventKind::Slip => true,
        EventKind::Exit => before != Field::Rolling,
        EventKind::Reverse | EventKind::Roll => false,
    }
}

/// The saltation matrix at `event`, from the field `before` to `after`.
///
/// # Errors
/// `Tangential` where the switch is tangential to the old field (∇h·f⁻ = 0: the formula
/// divides by it; the switch time does not depend smoothly on the start there).
pub fn saltation(
    model: &ModelParams,
    event: &Event,
    before: Field,
    after: Field,
) -> Result<Mat4, Tangential> {
    if continuous(event.kind, before) {
        return Ok(IDENTITY);
    }
    let s = &event.state;
    let g: StateGradient = match event.kind {
        EventKind::Exit | EventKind::Enter => coef::switching_gradient(model, &position(s)),
        _ => coef::slip_velocity_gradient(model, &position(s), &velocity(s)),
    };
    let normal = [g.x, g.y, g.vx, g.vy];
    let f_before = rate(model, before, event.time, s);
    let f_after = rate(model, after, event.time, s);
    let denominator = dot(normal, f_before);
    if !(denominator.is_finite() && denominator != 0.0) {
        return Err(Tangential {
            time: event.time,
            kind: event.kind,
        });
    }
    let mut out = IDENTITY;
    for (row, (fa, fb)) in out.iter_mut().zip(f_after.iter().zip(f_before)) {
        let jump = (fa - fb) / denominator;
        for (entry, n) in row.iter_mut().zip(normal) {
            *entry += jump * n;
        }
    }
    Ok(out)
}
