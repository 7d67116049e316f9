//! One linear piece of a speed profile: η(τ) = η_k + η'_k (τ − τ_k) on [τ_k, τ_{k+1}), and the
//! forcing phase θ(τ) = ∫η that goes with it (`docs/MODEL.md` §14).

use crate::coefficients::{self as coef, PhaseAdvance, SpeedRamp, Time};

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
    /// η at time `t` (generated `ramp_speed`; η_k itself when η' = 0).
    #[inline]
    pub fn speed_at(&self, t: f64) -> f64 {
        if self.rate == 0.0 {
            self.speed_ratio
        } else {
            coef::ramp_speed(&Time { t }, &self.ramp()).eta
        }
    }

    /// The forcing phase θ at time `t` (generated `ramp_phase`; with η' = 0 the constant-speed
    /// η τ + φ0, bit for bit: the ramp's term is then +0).
    #[inline]
    pub fn phase_at(&self, t: f64) -> f64 {
        coef::ramp_phase(&Time { t }, &self.ramp()).theta
    }

    /// The piece as the generated formulas' input.
    #[inline]
    fn ramp(&self) -> SpeedRamp {
        SpeedRamp {
            speed_ratio: self.speed_ratio,
            rate: self.rate,
            start: self.start,
            phase_constant: self.phase_constant,
        }
    }

    /// Whether `t` lies on the piece, [start, end).
    #[inline]
    pub fn contains(&self, t: f64) -> bool {
        t >= self.start && t < self.end
    }

    /// The time at which the phase reaches `phase` (≥ the phase at `start`), if that is on the
    /// piece: the generated `ramp_time_to_phase` (½ η' s² + η_k s = Δθ solved without
    /// cancellation); the speed stays positive on a piece, so the root exists wherever the piece
    /// reaches the phase.
    pub fn time_of_phase(&self, phase: f64) -> Option<f64> {
        let delta = phase - self.phase_at(self.start);
        let time = coef::ramp_time_to_phase(&self.ramp(), &PhaseAdvance { theta: delta });
        if !(delta >= 0.0 && time.disc >= 0.0 && time.s.is_finite() && time.s >= 0.0) {
            return None;
        }
        let t = self.start + time.s;
        (t < self.end).then_some(t)
    }

    /// `next` (the piece after this one) with the phase constant that keeps θ continuous.
    pub(crate) fn continued_by(&self, next: SpeedPiece) -> SpeedPiece {
        SpeedPiece {
            phase_constant: phase_constant(next.speed_ratio, self.phase_at(self.end), self.end),
            ..next
        }
    }
}

/// The phase constant c of a piece of speed η_k whose phase is `theta` at time `t` (its start):
/// the generated `ramp_phase_constant`, c = θ − η_k τ.
#[inline]
pub(crate) fn phase_constant(speed_ratio: f64, theta: f64, t: f64) -> f64 {
    let ramp = SpeedRamp {
        speed_ratio,
        rate: 0.0,
        start: t,
        phase_constant: 0.0,
    };
    coef::ramp_phase_constant(&Time { t }, &ramp, &PhaseAdvance { theta }).c
}
