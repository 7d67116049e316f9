//! How finely the stepper steps contact ([`ContactResolution`]): the contact mode's rate bound
//! for the parameters in force and the sub-steps a step of `dt` needs for it. Kept with the
//! free map ([`super::FreeTransition`]), which is rebuilt whenever `dt` or the parameters
//! change.

use super::MAX_SUBSTEPS;
use super::polynomial::MAX_RATE_STEP;
use crate::analytic::linear::max_contact_stiffness;
use crate::analytic::series::rate;
use crate::params::Params;

/// How finely contact must be stepped for the parameters in force: the contact mode's rate
/// bound ρ_c = ν + √(ν² + S), S = `max_contact_stiffness` (the generated bound of ‖Kl‖₂ over
/// every linearization with z ≥ 1, friction included), and the sub-steps per step of `dt` that
/// keep every contact sub-step at ρ_c·h ≤ [`MAX_RATE_STEP`] = 0.5. Why that bound: it is where
/// a sub-step's continuous extension is its Taylor polynomial to rounding (`polynomial.rs`,
/// the exit search's tight bounds), inside the resonant series' reach (ρh ≤ 2, else the
/// linearization is refused as singular) and the analytic method's contact cap (ρh ≤ 1); past
/// it, at ρ_c·dt ≈ 1–4, the stepper's answers went wrong without a word (switches missed or
/// spurious, `tests/stepper_coarse.rs`). Recomputed only when what S depends on changes (a
/// speed ramp keeps it).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct ContactResolution {
    /// ρ_c (1/time).
    rate: f64,
    /// ⌈ρ_c·dt / [`MAX_RATE_STEP`]⌉, in [1, [`MAX_SUBSTEPS`]].
    substeps: u32,
    /// The parameters ρ_c depends on: K̂xx, K̂xy, K̂yx, K̂yy, μ, ν, ε̂x, ε̂y.
    key: [f64; 8],
}

impl ContactResolution {
    /// The resolution for `params` at steps of `dt`.
    pub(super) fn new(params: &Params, dt: f64) -> Self {
        let rate = rate(max_contact_stiffness(params), params.damping_ratio);
        ContactResolution {
            rate,
            substeps: substeps_for(rate, dt),
            key: Self::key_of(params),
        }
    }

    /// ρ_c (1/time).
    pub(super) fn rate(&self) -> f64 {
        self.rate
    }

    /// The contact sub-steps per step of `dt`.
    pub(super) fn substeps(&self) -> u32 {
        self.substeps
    }

    /// Whether `params` differ from this resolution's in what ρ_c depends on.
    pub(super) fn changed_by(&self, params: &Params) -> bool {
        Self::key_of(params) != self.key
    }

    /// The parameters ρ_c depends on.
    fn key_of(p: &Params) -> [f64; 8] {
        [
            p.k_xx,
            p.k_xy,
            p.k_yx,
            p.k_yy,
            p.friction_coefficient,
            p.damping_ratio,
            p.offset_x,
            p.offset_y,
        ]
    }
}

/// ⌈rate·dt / [`MAX_RATE_STEP`] − 1e-9⌉ clamped to [1, [`MAX_SUBSTEPS`]] (the cast saturates;
/// the slack keeps a dt of exactly k·[`MAX_RATE_STEP`]/rate at k sub-steps despite rounding).
fn substeps_for(rate: f64, dt: f64) -> u32 {
    let q = rate * dt / MAX_RATE_STEP - 1e-9;
    let k = q as u32;
    let k = if f64::from(k) < q {
        k.saturating_add(1)
    } else {
        k
    };
    k.clamp(1, MAX_SUBSTEPS)
}
