//! Free flight over one fixed step as a precomputed affine map, and the bound that proves a free
//! step contact-free.
//!
//! The free equations (`model.md` §4) are linear with a harmonic forcing, so over a step of
//! length `dt` the end state is w(dt) = Φ(dt)·w(0) + G(dt)·(cos θ0, sin θ0): Φ is the 4×4
//! transition matrix of the homogeneous system and G carries the particular solution across the
//! step (its columns are the particular state at θ0 = 0 and θ0 = π/2 rotated by η·dt, minus
//! their homogeneous propagation). Both are built by evaluating the *generated* free formulas
//! (`coefficients::free_homogeneous`, `coefficients::free_eval` with the basis of
//! [`free_basis`]) on unit inputs: the map is linear in (w, cos θ0, sin θ0), so its columns are
//! its values at the unit vectors. No closed form is typed here.

use super::search::local_curvature;
use crate::analytic::basis::{free_basis, free_basis_bound};
use crate::analytic::free::FreeConstants;
use crate::coefficients::{self as coef, FreeBasis, FreeDampedFrequency, ModelParams, Phasor};
use crate::math;
use crate::params::{Params, State};

/// The exact free-flight map over one step of fixed length, with the constants of the switch
/// bound on that step. Computing it costs one `exp`, two `sin_cos`, the basis bounds (`exp`)
/// and six evaluations of the generated free formulas (≈ 0.1 µs with `set_params`'s other
/// work), paid once per step length and parameter set.
#[derive(Clone, Copy, Debug)]
pub struct FreeTransition {
    dt: f64,
    /// Φ(dt), row-major: `phi[i][j]` is component i of the end state for a unit component j
    /// at the start (order x, y, x', y').
    phi: [[f64; 4]; 4],
    /// G(dt): the end state for a zero start state and the forcing phasor (1, 0), (0, 1).
    g: [[f64; 2]; 4],
    /// (cos η·dt, sin η·dt): the forcing phasor's rotation over one step.
    rotation: (f64, f64),
    eta: f64,
    /// ν and η for the generated formulas.
    model: ModelParams,
    particular: coef::FreeParticular,
    /// Bounds of |EC|, |ES| and of their first and second derivatives on [0, dt].
    basis: [f64; 6],
    /// sqrt(c11² + c22² + c33² + c44²): bound of the particular solution's amplitude.
    amplitude: f64,
    /// |ε̂|.
    offset: f64,
}

impl FreeTransition {
    /// The map over `dt` (> 0) for `params`, with their free constants.
    pub fn new(params: &Params, constants: &FreeConstants, dt: f64) -> Self {
        let nu = params.damping_ratio;
        let eta = params.speed_ratio;
        let beta_sq = constants.beta_sq;
        let p = constants.particular;
        let (ec, es) = free_basis(nu, beta_sq, dt);
        let (sd, cd) = math::sin_cos(eta * dt);
        // The generated free step from start state `w` and start phasor (ct, st), offsets zero.
        let model = ModelParams {
            nu,
            eta,
            ..ModelParams::default()
        };
        let (beta, basis) = (FreeDampedFrequency { beta_sq }, FreeBasis { ec, es });
        let map = |w: [f64; 4], ct: f64, st: f64| -> [f64; 4] {
            let start = State::from_array(w).into();
            let h = coef::free_homogeneous(&model, &start, &Phasor { ct, st }, &p);
            let (ce, se) = (ct * cd - st * sd, st * cd + ct * sd);
            let phasor = Phasor { ct: ce, st: se };
            let r = coef::free_eval(&model, &phasor, &p, &beta, &h, &basis);
            [r.x, r.y, r.vx, r.vy]
        };
        let mut phi = [[0.0; 4]; 4];
        for j in 0..4 {
            let mut unit = [0.0; 4];
            unit[j] = 1.0;
            let column = map(unit, 0.0, 0.0);
            for (row, value) in phi.iter_mut().zip(column) {
                row[j] = value;
            }
        }
        let (gc, gs) = (map([0.0; 4], 1.0, 0.0), map([0.0; 4], 0.0, 1.0));
        let mut g = [[0.0; 2]; 4];
        for i in 0..4 {
            g[i] = [gc[i], gs[i]];
        }
        // Derivative bounds exactly as `FreeSegment::bounds`: EC' = −νEC − β²ES, ES' = EC − νES.
        let (ecb, esb) = free_basis_bound(nu, beta_sq, 0.0, dt);
        let b2 = math::abs(beta_sq);
        let (dec, des) = (nu * ecb + b2 * esb, ecb + nu * esb);
        let (ddec, ddes) = (nu * dec + b2 * des, dec + nu * des);
        FreeTransition {
            dt,
            phi,
            g,
            rotation: (cd, sd),
            eta,
            model,
            particular: p,
            basis: [ecb, esb, dec, des, ddec, ddes],
            amplitude: math::sqrt(p.c11 * p.c11 + p.c22 * p.c22 + p.c33 * p.c33 + p.c44 * p.c44),
            offset: math::hypot(params.offset_x, params.offset_y),
        }
    }

    /// The step length this map is for.
    pub fn dt(&self) -> f64 {
        self.dt
    }

    /// The forcing phasor after one step from `phasor` = (cos θ0, sin θ0).
    #[inline]
    pub fn rotate(&self, phasor: (f64, f64)) -> (f64, f64) {
        let (c, s) = phasor;
        let (cd, sd) = self.rotation;
        (c * cd - s * sd, s * cd + c * sd)
    }

    /// The free state one step after `w`, with forcing phasor `phasor` at the start:
    /// Φ·w + G·phasor (24 multiplications, 20 additions).
    #[inline]
    pub fn apply(&self, w: &State, phasor: (f64, f64)) -> State {
        let a = w.to_array();
        let mut out = [0.0; 4];
        for (o, (row, g)) in out.iter_mut().zip(self.phi.iter().zip(&self.g)) {
            *o = row[0] * a[0]
                + row[1] * a[1]
                + row[2] * a[2]
                + row[3] * a[3]
                + g[0] * phasor.0
                + g[1] * phasor.1;
        }
        State::from_array(out)
    }

    /// A rigorous upper bound of |h''| (h = z² − 1) over the free step from `w` with forcing
    /// phasor `phasor` at the start, where |r − ε| = `r0`: the bounds of `FreeSegment::bounds`
    /// on [0, dt] (homogeneous constants from the generated `free_homogeneous`), with radius
    /// and speed tightened around the start as in [`super::search::curvature`] (about 50
    /// flops, 4 `sqrt`).
    #[inline]
    pub fn curvature_bound(&self, w: &State, phasor: (f64, f64), r0: f64) -> f64 {
        let p = &self.particular;
        let (ct, st) = phasor;
        let h = coef::free_homogeneous(&self.model, &(*w).into(), &Phasor { ct, st }, p);
        let pos = math::sqrt(h.xh * h.xh + h.yh * h.yh);
        let vel = math::sqrt(h.px * h.px + h.py * h.py);
        let [ec, es, dec, des, ddec, ddes] = self.basis;
        let radius = pos * ec + vel * es + self.amplitude + self.offset;
        let speed = pos * dec + vel * des + self.eta * self.amplitude;
        let accel = pos * ddec + vel * ddes + self.eta * self.eta * self.amplitude;
        let v0 = math::sqrt(w.vx * w.vx + w.vy * w.vy);
        local_curvature(r0, v0, radius, speed, accel, self.dt)
    }
}
