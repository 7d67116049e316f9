//! A changing speed held constant over a step (`docs/MODEL.md` §14): how the closed-form methods
//! (the analytic method and the fixed-step stepper) run a speed profile.
//!
//! Over a step [t0, t1] the speed is held at its mean η_h = (θ(t1) − θ(t0))/(t1 − t0), so the
//! forcing phase is exact at both ends of every step and its error inside a step is at most
//! |η'| (t1 − t0)²/8; the rate is held too (η'_h = (η(t1) − η(t0))/(t1 − t0), exactly η' on a
//! linear piece). With η and η' constant the unbalance forcing
//! η_m ρ̂ (η² (cos θ, sin θ) − η' (−sin θ, cos θ)) is one harmonic of frequency η_h,
//! A (cos(θ − δ), sin(θ − δ)) with A = η_m ρ̂ √(η_h⁴ + η'_h²), δ = atan2(η'_h, η_h²) (the
//! generated `held_speed_forcing`): the constant-speed closed forms apply exactly to it, with the
//! unbalance scaled to A/η_h² and the phase moved by −δ. What is left out is only the change of
//! η within the step: an amplitude error of relative size ≈ 2|η'|(t1 − t0)/η that averages out
//! over the step, and the phase error above.

use super::piece::{SpeedPiece, phase_constant};
use crate::coefficients::{self as coef, ModelParams, SpeedChange};
use crate::math;
use crate::params::{Parameter, Params};

/// How many times its rounding (ε of the phases' size) a phase difference must exceed for the
/// held speed to be taken from it (it then errs by less than 1e-6 relative).
const UNRESOLVED_PHASE: f64 = 1e6;

/// The speed and rate held over one step, with the phase that goes with them:
/// θ(τ) ≈ η_h τ + c_h on the step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HeldSpeed {
    /// η_h: the mean speed ratio over the step.
    pub speed_ratio: f64,
    /// η'_h: the rate held over the step.
    pub rate: f64,
    /// c_h: the phase constant, θ ≈ η_h τ + c_h.
    pub phase_constant: f64,
}

impl HeldSpeed {
    /// A piece's speed as it is: exact (and the constant-speed phase, bit for bit) when the
    /// piece holds its speed (η' = 0).
    pub fn of_piece(piece: &SpeedPiece) -> Self {
        HeldSpeed {
            speed_ratio: piece.speed_ratio,
            rate: piece.rate,
            phase_constant: piece.phase_constant,
        }
    }

    /// The speed held over [t0, t1] from the speed and phase at both ends (taken from the
    /// pieces holding them).
    ///
    /// Over an interval too short for its phase difference (that difference within
    /// `UNRESOLVED_PHASE` of the phases' rounding: a sliver of ~1e-13 left at a piece's end)
    /// the speed is the mean of the end speeds — the exact mean on one linear piece — and the
    /// rate the piece's, instead of a cancelled difference over the length (which gave 0, or
    /// 1.43 for 1.47, issue 32).
    pub fn between(start: (&SpeedPiece, f64), end: (&SpeedPiece, f64)) -> Self {
        let ((p0, t0), (p1, t1)) = (start, end);
        let length = t1 - t0;
        let (theta0, theta1) = (p0.phase_at(t0), p1.phase_at(t1));
        let (eta0, eta1) = (p0.speed_at(t0), p1.speed_at(t1));
        let rounding = f64::EPSILON * math::abs(theta0).max(math::abs(theta1));
        let resolved = math::abs(theta1 - theta0) > UNRESOLVED_PHASE * rounding;
        if !resolved {
            let speed_ratio = 0.5 * (eta0 + eta1);
            return HeldSpeed {
                speed_ratio,
                rate: if p0 == p1 {
                    p0.rate
                } else {
                    (eta1 - eta0) / length
                },
                phase_constant: phase_constant(speed_ratio, theta0, t0),
            };
        }
        let speed_ratio = (theta1 - theta0) / length;
        HeldSpeed {
            speed_ratio,
            rate: (eta1 - eta0) / length,
            phase_constant: phase_constant(speed_ratio, theta0, t0),
        }
    }

    /// The constant-speed parameters whose forcing is this held forcing: `base` with the held
    /// speed, the unbalance scaled by the held forcing's amplitude over the constant-speed one
    /// (eccentricity ratio ρ̂ √(r_c² + r_s²), the generated `held_speed_forcing`'s ratios) and the
    /// phase moved by its lag δ = atan2(r_s, r_c). With η'_h = 0 only the speed and the phase
    /// change (the phase constant itself when it lies in the parameter table's range, else
    /// reduced to [0, 2π)). The result is not validated: the scaled eccentricity can leave its
    /// range at very low speeds (checked by the caller, [`HeldSpeed::eccentricity_scale`]).
    pub fn params(&self, base: &Params) -> Params {
        let at_speed = Params {
            speed_ratio: self.speed_ratio,
            ..*base
        };
        if self.rate == 0.0 {
            return Params {
                phase: phase_parameter(self.phase_constant),
                ..at_speed
            };
        }
        let (scale, lag) = self.eccentricity_scale(&at_speed);
        Params {
            eccentricity_ratio: base.eccentricity_ratio * scale,
            phase: phase_parameter(self.phase_constant - lag),
            ..at_speed
        }
    }

    /// The factor √(r_c² + r_s²) the held step scales the unbalance by, and the lag δ, at the
    /// parameters `at_speed` (which carry the held speed).
    pub fn eccentricity_scale(&self, at_speed: &Params) -> (f64, f64) {
        let forcing = coef::held_speed_forcing(
            &ModelParams::of(at_speed),
            &SpeedChange {
                speed_rate: self.rate,
            },
        );
        let (c, s) = (forcing.in_phase_ratio, forcing.quadrature_ratio);
        (math::hypot(c, s), math::atan2(s, c))
    }
}

/// A phase constant as the `phase` parameter: itself inside the table's range, else reduced to
/// [0, 2π) (the same forcing direction).
fn phase_parameter(phase: f64) -> f64 {
    if Parameter::Phase.info().range.contains(phase) {
        phase
    } else {
        math::wrap_angle(phase)
    }
}
