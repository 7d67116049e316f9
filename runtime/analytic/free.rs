//! The free-flight segment (`model.md` §4): exact closed form in local time.

use super::basis::{free_basis, free_basis_bound};
use super::segment::{Bounds, Point, Segment};
use crate::coefficients::{
    self as coef, FreeBasis, FreeDampedFrequency, FreeHomogeneous, FreeParticular, ModelParams,
    Phasor,
};
use crate::math;
use crate::params::{Params, State};

/// Free flight from a state at time τ0, valid for all s = τ − τ0 ≥ 0 until contact.
#[derive(Clone, Copy, Debug)]
pub struct FreeSegment {
    nu: f64,
    eta: f64,
    beta_sq: f64,
    offset: (f64, f64),
    phase0: (f64, f64),
    particular: FreeParticular,
    homogeneous: FreeHomogeneous,
    /// Constants of [`Segment::bounds`]: |X|, |P| of the homogeneous part, the particular
    /// amplitude and |ε|.
    reach: Reach,
}

/// The amplitudes [`FreeSegment::bounds`] combines, computed once per segment.
#[derive(Clone, Copy, Debug)]
struct Reach {
    pos: f64,
    vel: f64,
    amp: f64,
    off: f64,
}

/// The largest |(c11 cos θ + c22 sin θ, c33 cos θ + c44 sin θ)| over θ: the largest singular
/// value of [[c11, c22], [c33, c44]] (σ² = (S + √(S² − 4 det²))/2, S the sum of squares), with a
/// relative margin for rounding. The particular velocity and acceleration are η and η² times the
/// same matrix applied to a unit vector.
pub(crate) fn harmonic_amplitude(c11: f64, c22: f64, c33: f64, c44: f64) -> f64 {
    let sum = c11 * c11 + c22 * c22 + c33 * c33 + c44 * c44;
    let det = c11 * c44 - c22 * c33;
    let disc = (sum * sum - 4.0 * det * det).max(0.0);
    let sigma = math::sqrt(0.5 * (sum + math::sqrt(disc)));
    // Never above the Frobenius norm (the bound used before), never below it by rounding.
    (sigma * (1.0 + 1e-12)).min(math::sqrt(sum))
}

/// Per-parameter-set constants of free flight (computed once per propagation).
#[derive(Clone, Copy, Debug)]
pub struct FreeConstants {
    /// β² = 1 − ν².
    pub beta_sq: f64,
    /// Steady-state harmonic response.
    pub particular: FreeParticular,
}

impl FreeConstants {
    /// Derived constants for `params`.
    pub fn new(params: &Params) -> Self {
        FreeConstants {
            beta_sq: coef::free_damped_frequency_sq(&ModelParams::of(params)).beta_sq,
            particular: coef::free_particular(&ModelParams::of(params)),
        }
    }
}

impl FreeSegment {
    /// The free segment through `state` at absolute time `t0`.
    pub fn new(params: &Params, constants: &FreeConstants, t0: f64, state: State) -> Self {
        let (st, ct) = math::sin_cos(math::wrap_angle(params.speed_ratio * t0 + params.phase));
        let p = constants.particular;
        let model = ModelParams::of(params);
        let homogeneous = coef::free_homogeneous(&model, &state.into(), &Phasor { ct, st }, &p);
        let reach = Reach {
            pos: math::hypot(homogeneous.xh, homogeneous.yh),
            vel: math::hypot(homogeneous.px, homogeneous.py),
            amp: harmonic_amplitude(p.c11, p.c22, p.c33, p.c44),
            off: math::hypot(params.offset_x, params.offset_y),
        };
        FreeSegment {
            nu: params.damping_ratio,
            eta: params.speed_ratio,
            beta_sq: constants.beta_sq,
            offset: (params.offset_x, params.offset_y),
            phase0: (ct, st),
            particular: p,
            homogeneous,
            reach,
        }
    }

    /// Forcing phasor (cos θ, sin θ) at local time s by angle addition from the segment start.
    fn phasor(&self, s: f64) -> (f64, f64) {
        let (sd, cd) = math::sin_cos(self.eta * s);
        let (c0, s0) = self.phase0;
        (c0 * cd - s0 * sd, s0 * cd + c0 * sd)
    }

    /// Upper bound of |r − ε| for all s ≥ `lo`: the steady orbit's reach plus the decaying
    /// transient. Below 1 means no contact can ever happen again after `lo`.
    pub fn reach_after(&self, lo: f64) -> f64 {
        let b = self.bounds(lo, f64::INFINITY);
        b.radius
    }
}

impl Segment for FreeSegment {
    fn point(&self, s: f64) -> Point {
        let (ec, es) = free_basis(self.nu, self.beta_sq, s);
        let (ct, st) = self.phasor(s);
        let (h, p) = (&self.homogeneous, &self.particular);
        let model = ModelParams {
            nu: self.nu,
            eta: self.eta,
            ex: self.offset.0,
            ey: self.offset.1,
            ..ModelParams::default()
        };
        let beta = FreeDampedFrequency {
            beta_sq: self.beta_sq,
        };
        let r = coef::free_eval(
            &model,
            &Phasor { ct, st },
            p,
            &beta,
            h,
            &FreeBasis { ec, es },
        );
        Point {
            state: State::new(r.x, r.y, r.vx, r.vy),
            h: r.h,
            dh: r.dh,
        }
    }

    fn bounds(&self, lo: f64, hi: f64) -> Bounds {
        let (ec, es) = free_basis_bound(self.nu, self.beta_sq, lo, hi);
        let Reach { pos, vel, amp, off } = self.reach;
        let (nu, b2) = (self.nu, math::abs(self.beta_sq));
        // EC' = −νEC − β²ES, ES' = EC − νES, applied twice, bounded term by term.
        let (dec, des) = (nu * ec + b2 * es, ec + nu * es);
        let (ddec, ddes) = (nu * dec + b2 * des, dec + nu * des);
        Bounds {
            radius: pos * ec + vel * es + amp + off,
            speed: pos * dec + vel * des + self.eta * amp,
            accel: pos * ddec + vel * ddes + self.eta * self.eta * amp,
        }
    }
}
