//! One linear piece of a speed profile: η(τ) = η_k + η'_k (τ − τ_k) on [τ_k, τ_{k+1}), and the
//! forcing phase θ(τ) = ∫η that goes with it (`docs/MODEL.md` §14).

use crate::coefficients::{self as coef, SpeedRamp, Time};
use crate::math;

/// A piece of a speed profile on which the speed ratio changes linearly in time.
///
/// The forcing phase on the piece is θ(τ) = η_k τ + c + ½ η'_k (τ − τ_k)²: written with the
/// absolute time τ like the constant-speed phase η τ + φ0, so that a piece with η' = 0 and
/// c = φ0 computes the constant-speed phase bit for bit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpeedPiece {
    /// Index of the profile point the piece starts at.
    pub index: usize,
    /// Index of the point it ends at (the number of points for the last piece).
    pub end_index: usize,
    /// τ_k, where the piece starts.
    pub start: f64,
    /// Where the piece ends: the next point's time, or +∞ after the last point (the last speed
    /// is then held).
    pub end: f64,
    /// η_k, the speed ratio at `start`.
    pub speed_ratio: f64,
    /// η'_k = dη/dτ on the piece.
    pub rate: f64,
    /// c, the phase constant: θ(τ) = η_k τ + c + ½ η'_k (τ − τ_k)².
    pub phase_constant: f64,
}

impl SpeedPiece {
    /// η at time `t`.
    #[inline]
    pub fn speed_at(&self, t: f64) -> f64 {
        if self.rate == 0.0 {
            self.speed_ratio
        } else {
            self.speed_ratio + self.rate * (t - self.start)
        }
    }

    /// The forcing phase θ at time `t` (generated `ramp_phase`; with η' = 0 the constant-speed
    /// η τ + φ0, bit for bit: the ramp's term is then +0).
    #[inline]
    pub fn phase_at(&self, t: f64) -> f64 {
        coef::ramp_phase(
            &Time { t },
            &SpeedRamp {
                speed_ratio: self.speed_ratio,
                rate: self.rate,
                start: self.start,
                phase_constant: self.phase_constant,
            },
        )
        .theta
    }

    /// Whether `t` lies on the piece, [start, end).
    #[inline]
    pub fn contains(&self, t: f64) -> bool {
        t >= self.start && t < self.end
    }

    /// The time at which the phase reaches `phase` (≥ the phase at `start`), if that is on the
    /// piece. Solves ½ η' s² + η_k s = Δθ for s = τ − τ_k in the form
    /// s = 2Δθ / (η_k + √(η_k² + 2η'Δθ)), which does not cancel; the speed stays positive on a
    /// piece, so the root exists wherever the piece reaches the phase.
    pub fn time_of_phase(&self, phase: f64) -> Option<f64> {
        let delta = phase - self.phase_at(self.start);
        let root = self.speed_ratio * self.speed_ratio + 2.0 * self.rate * delta;
        if !(delta >= 0.0 && root >= 0.0) {
            return None;
        }
        let denominator = self.speed_ratio + math::sqrt(root);
        if denominator <= 0.0 {
            return None;
        }
        let t = self.start + 2.0 * delta / denominator;
        (t < self.end).then_some(t)
    }

    /// `next` (the piece after this one) with the phase constant that keeps θ continuous.
    pub(crate) fn continued_by(&self, next: SpeedPiece) -> SpeedPiece {
        let phase = self.phase_at(self.end);
        SpeedPiece {
            phase_constant: phase - next.speed_ratio * self.end,
            ..next
        }
    }
}
