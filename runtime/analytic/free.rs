//! The free-flight segment (`docs/MODEL.md` §4, §11): exact closed form in local time, in one of
//! two forms chosen per parameter set.
//!
//! * Steady-state form (§4): x = xp(θ) + X·EC + P·ES, the harmonic steady state plus the
//!   homogeneous transient that matches the start state. Accurate away from resonance.
//! * Resonance-stable form (§11), within [`super::forced::RESONANT_BAND`] of resonance: x = X·EC + P·ES +
//!   ax·FC + bx·FS, the homogeneous response to the start state plus the zero-state response to
//!   the forcing ([`super::forced`]). Near resonance the steady state ~F/|1 − η² + 2iνη| and the
//!   transient nearly cancel in the first form; the second has no such cancellation and stays
//!   valid at ν = 0, η = 1 exactly (secular growth).
//!
//! # The free-flight bound
//! One bound serves the analytic search ([`Segment::bounds`]) and the stepper's transition:
//! `FreeReach::bounds`. Each form writes r − ε = X·EC + P·ES + M·b(s) − ε with constant
//! vectors X = (X, Y), P = (P, Q), a constant real 2×2 matrix M and a vector b of scalar
//! functions: b = (cos θ, sin θ) for the steady state (M = [[c11, c22], [c33, c44]]) and
//! b = (FC, FS) for the forced form (M = [[ax, bx], [ay, by]]). So on [lo, hi]
//! |r − ε| ≤ |X|·max|EC| + |P|·max|ES| + σ(M)·max|b| + |ε|, and likewise for r' and r'' with the
//! derivative bounds of EC, ES (`BasisBound`) and of b: |b| = 1, |b'| = η, |b''| = η² for the
//! phasor; max|K|, max|K'| ≤ κ and max|K''| ≤ κ + 1 for the forced basis (`super::forced`).
//! σ(M) is the largest singular value (`harmonic_amplitude`), the tightest constant with
//! |M·b| ≤ σ|b| (the Frobenius norm it replaces is larger by up to √2). Where both forms are
//! available, each bound is the smaller of the two (both bound the same trajectory).

use super::basis::{free_basis, free_basis_bound};
use super::forced::Resonance;
use super::segment::{Bounds, Point, Segment};
use crate::coefficients::{
    self as coef, FreeBasis, FreeDampedFrequency, FreeForcing, FreeHomogeneous, FreeParticular,
    ModelParams, Phasor,
};
use crate::math;
use crate::params::{Params, State};

/// The largest |(c11 cos θ + c22 sin θ, c33 cos θ + c44 sin θ)| over θ: the largest singular
/// value of [[c11, c22], [c33, c44]] (σ² = (S + √(S² − 4 det²))/2, S the sum of squares), with a
/// relative margin for rounding, never above the Frobenius norm √S.
pub(crate) fn harmonic_amplitude(c11: f64, c22: f64, c33: f64, c44: f64) -> f64 {
    let sum = c11 * c11 + c22 * c22 + c33 * c33 + c44 * c44;
    let det = c11 * c44 - c22 * c33;
    let disc = (sum * sum - 4.0 * det * det).max(0.0);
    let sigma = math::sqrt(0.5 * (sum + math::sqrt(disc)));
    (sigma * (1.0 + 1e-12)).min(math::sqrt(sum))
}

/// √(x² + y²) with one rounded root, where libm's `hypot` (four times the instructions) guards
/// against overflow and keeps extra precision. For the stepper's per-step free-flight bound,
/// which only decides whether a step is provably free: its rounding (a few ulps of the bound)
/// moves that decision only when the two-parabola test's margin is at rounding level, and an
/// overflowing square gives an infinite bound, which sends the step to the exact path.
#[inline]
pub(crate) fn plain_norm(x: f64, y: f64) -> f64 {
    math::sqrt(x * x + y * y)
}

/// Per-parameter-set constants of free flight (computed once per propagation).
#[derive(Clone, Copy, Debug)]
pub struct FreeConstants {
    /// β² = 1 − ν².
    pub beta_sq: f64,
    /// Steady-state harmonic response (not finite at ν = 0, η = 1).
    pub particular: FreeParticular,
    /// σ of the steady-state response, when finite.
    steady_amplitude: Option<f64>,
    /// The forced basis, within [`super::forced::RESONANT_BAND`] of resonance.
    resonance: Option<Resonance>,
    /// The static deflection under the input force u (generated `input_static_deflection`;
    /// exactly (0, 0) without one, and then never applied: the unforced path is unchanged).
    deflection: (f64, f64),
    /// ν, η, F (and ε̂, replaced per segment) for the generated formulas.
    model: ModelParams,
}

impl FreeConstants {
    /// Derived constants for `params`.
    pub fn new(params: &Params) -> Self {
        let model = ModelParams::of(params);
        let beta_sq = coef::free_damped_frequency_sq(&model).beta_sq;
        let p = coef::free_particular(&model);
        let amp = harmonic_amplitude(p.c11, p.c22, p.c33, p.c44);
        FreeConstants {
            deflection: deflection(&model),
            beta_sq,
            particular: p,
            steady_amplitude: amp.is_finite().then_some(amp),
            resonance: Resonance::near(model.nu, beta_sq, model.eta),
            model,
        }
    }

    /// The same constants for another input force (`docs/MODEL.md` §15): only the static
    /// deflection changes (one generated call), so a controller may change u every step.
    pub fn with_input(&self, force: (f64, f64)) -> Self {
        let model = ModelParams {
            force_x: force.0,
            force_y: force.1,
            ..self.model
        };
        FreeConstants {
            deflection: deflection(&model),
            model,
            ..*self
        }
    }

    /// The static deflection under the input force ((0, 0) without one).
    pub fn deflection(&self) -> (f64, f64) {
        self.deflection
    }

    /// Whether free flight uses the resonance-stable form (`docs/MODEL.md` §11).
    pub fn resonant(&self) -> bool {
        self.resonance.is_some()
    }
}

/// The static deflection of free flight under the model's input force: (0, 0) exactly when
/// there is none.
fn deflection(model: &ModelParams) -> (f64, f64) {
    if model.force_x == 0.0 && model.force_y == 0.0 {
        return (0.0, 0.0);
    }
    let d = coef::input_static_deflection(model);
    (d.x, d.y)
}

/// Bounds of the scalar basis functions and their derivatives on one interval.
#[derive(Clone, Copy, Debug)]
pub(crate) struct BasisBound {
    /// max |EC|, |ES|, |EC'|, |ES'|, |EC''|, |ES''|.
    e: [f64; 6],
    /// κ ≥ max(|FC + iFS|, |FC' + iFS'|) (forced form only).
    kappa: f64,
    eta: f64,
}

impl BasisBound {
    /// The bounds on s ∈ [lo, hi] (`hi` may be infinite).
    pub(crate) fn on(constants: &FreeConstants, lo: f64, hi: f64) -> Self {
        let (nu, b2) = (constants.model.nu, math::abs(constants.beta_sq));
        let (ec, es) = free_basis_bound(nu, constants.beta_sq, lo, hi);
        // EC' = −νEC − β²ES, ES' = EC − νES, applied twice, bounded term by term.
        let (dec, des) = (nu * ec + b2 * es, ec + nu * es);
        let (ddec, ddes) = (nu * dec + b2 * des, dec + nu * des);
        BasisBound {
            e: [ec, es, dec, des, ddec, ddes],
            kappa: constants.resonance.map_or(0.0, |r| r.bound(hi)),
            eta: constants.model.eta,
        }
    }
}

/// |X|, |P| and σ(M) of one form (module docs).
#[derive(Clone, Copy, Debug)]
struct Amplitudes {
    pos: f64,
    vel: f64,
    drive: f64,
}

impl Amplitudes {
    /// Radius, speed and acceleration bounds for drive-function bounds `b` (value, first and
    /// second derivative).
    fn bounds(&self, e: &[f64; 6], b: [f64; 3], off: f64) -> Bounds {
        let [ec, es, dec, des, ddec, ddes] = *e;
        Bounds {
            radius: self.pos * ec + self.vel * es + self.drive * b[0] + off,
            speed: self.pos * dec + self.vel * des + self.drive * b[1],
            accel: self.pos * ddec + self.vel * ddes + self.drive * b[2],
        }
    }
}

/// The amplitudes of one free segment that [`FreeReach::bounds`] combines with interval bounds of
/// the basis: the one free-flight bound (module docs).
#[derive(Clone, Copy, Debug)]
pub(crate) struct FreeReach {
    steady: Option<Amplitudes>,
    forced: Option<Amplitudes>,
    off: f64,
}

impl FreeReach {
    /// Bounds on the interval `basis` was computed for.
    #[inline]
    pub(crate) fn bounds(&self, basis: &BasisBound) -> Bounds {
        let eta = basis.eta;
        let steady = self
            .steady
            .map(|a| a.bounds(&basis.e, [1.0, eta, eta * eta], self.off));
        let forced = self.forced.map(|a| {
            let k = basis.kappa;
            a.bounds(&basis.e, [k, k, k + 1.0], self.off)
        });
        match (steady, forced) {
            (Some(s), Some(f)) => Bounds {
                radius: s.radius.min(f.radius),
                speed: s.speed.min(f.speed),
                accel: s.accel.min(f.accel),
            },
            (Some(b), None) | (None, Some(b)) => b,
            (None, None) => Bounds {
                radius: f64::INFINITY,
                speed: f64::INFINITY,
                accel: f64::INFINITY,
            },
        }
    }
}

/// The constants of the closed form in use.
#[derive(Clone, Copy, Debug)]
enum Form {
    Steady(FreeHomogeneous),
    Forced {
        start: FreeHomogeneous,
        forcing: FreeForcing,
        resonance: Resonance,
    },
}

/// Free flight from a state at time τ0, valid for all s = τ − τ0 ≥ 0 until contact.
#[derive(Clone, Copy, Debug)]
pub struct FreeSegment {
    constants: FreeConstants,
    /// The parameters with this segment's offset.
    model: ModelParams,
    phase0: (f64, f64),
    form: Form,
    reach: FreeReach,
    /// The static deflection the closed form is written about (`docs/MODEL.md` §15): the form
    /// describes q − shift, with the stator offset moved by −shift; (0, 0) without input force.
    shift: (f64, f64),
}

impl FreeSegment {
    /// The free segment through `state` at absolute time `t0`.
    pub fn new(params: &Params, constants: &FreeConstants, t0: f64, state: State) -> Self {
        let (st, ct) = math::sin_cos(math::wrap_angle(params.speed_ratio * t0 + params.phase));
        Self::with_phasor(
            constants,
            (params.offset_x, params.offset_y),
            (ct, st),
            state,
        )
    }

    /// The free segment through `state` with forcing phasor `phasor` = (cos θ0, sin θ0) at its
    /// start and stator offset `offset` (the stepper's transition uses unit inputs and no offset).
    /// Under an input force the closed form is written about the static deflection d: free
    /// flight of q − d, with the offset ε − d (`docs/MODEL.md` §15).
    pub(crate) fn with_phasor(
        constants: &FreeConstants,
        offset: (f64, f64),
        phasor: (f64, f64),
        state: State,
    ) -> Self {
        let off = Self::offset_distance(constants, offset);
        let (model, form, reach) = Self::parts(constants, offset, off, phasor, state, math::hypot);
        FreeSegment {
            constants: *constants,
            model,
            phase0: phasor,
            form,
            reach,
            shift: constants.deflection,
        }
    }

    /// Only the bound amplitudes of [`Self::with_phasor`]'s segment, without building the
    /// segment: the stepper's per-step curvature bound needs nothing else, and building the
    /// segment copies the free constants. `off` is [`Self::offset_distance`] of `constants` and
    /// `offset` (constant per step length and parameter set, so the caller keeps it). The
    /// amplitudes' norms are [`plain_norm`] instead of `hypot` (the bound only decides whether
    /// the stepper's step is free; see there).
    #[inline]
    pub(crate) fn reach_with_phasor(
        constants: &FreeConstants,
        offset: (f64, f64),
        off: f64,
        phasor: (f64, f64),
        state: State,
    ) -> FreeReach {
        Self::parts(constants, offset, off, phasor, state, plain_norm).2
    }

    /// |ε − d|: the stator offset's distance from the point the closed form is written about
    /// (the static deflection d under an input force, else the rest position).
    #[inline]
    pub(crate) fn offset_distance(constants: &FreeConstants, offset: (f64, f64)) -> f64 {
        let shift = constants.deflection;
        if shift == (0.0, 0.0) {
            math::hypot(offset.0, offset.1)
        } else {
            math::hypot(offset.0 - shift.0, offset.1 - shift.1)
        }
    }

    /// The model with the segment's offset, the closed form's constants and the bound amplitudes
    /// of the free segment through `state` (see [`Self::with_phasor`]), with `norm` the
    /// Euclidean norm the amplitudes are taken with.
    #[inline(always)]
    fn parts(
        constants: &FreeConstants,
        offset: (f64, f64),
        off: f64,
        phasor: (f64, f64),
        state: State,
        norm: impl Fn(f64, f64) -> f64,
    ) -> (ModelParams, Form, FreeReach) {
        let c = constants;
        let shift = c.deflection;
        let (offset, state) = if shift == (0.0, 0.0) {
            (offset, state)
        } else {
            (
                (offset.0 - shift.0, offset.1 - shift.1),
                State::new(state.x - shift.0, state.y - shift.1, state.vx, state.vy),
            )
        };
        let model = ModelParams {
            ex: offset.0,
            ey: offset.1,
            ..c.model
        };
        let (ct, st) = phasor;
        let start = state.into();
        let steady_homogeneous =
            || coef::free_homogeneous(&model, &start, &Phasor { ct, st }, &c.particular);
        let amplitudes = |h: &FreeHomogeneous, drive: f64| Amplitudes {
            pos: norm(h.xh, h.yh),
            vel: norm(h.px, h.py),
            drive,
        };
        let (form, reach) = match c.resonance {
            None => {
                let h = steady_homogeneous();
                let steady = c.steady_amplitude.map(|amp| amplitudes(&h, amp));
                let reach = FreeReach {
                    steady,
                    forced: None,
                    off,
                };
                (Form::Steady(h), reach)
            }
            Some(resonance) => {
                let start = coef::free_start(&model, &start);
                let forcing = coef::free_forcing(&model, &Phasor { ct, st });
                let reach = FreeReach {
                    steady: c
                        .steady_amplitude
                        .map(|amp| amplitudes(&steady_homogeneous(), amp)),
                    forced: Some(Amplitudes {
                        pos: norm(start.xh, start.yh),
                        vel: norm(start.px, start.py),
                        drive: harmonic_amplitude(
                            forcing.fxc,
                            forcing.fxs,
                            forcing.fyc,
                            forcing.fys,
                        ),
                    }),
                    off,
                };
                let form = Form::Forced {
                    start,
                    forcing,
                    resonance,
                };
                (form, reach)
            }
        };
        (model, form, reach)
    }

    /// Upper bound of |r − ε| for all s ≥ `lo`: the steady orbit's reach plus the decaying
    /// transient. Below 1 means no contact can ever happen again after `lo`.
    pub fn reach_after(&self, lo: f64) -> f64 {
        self.bounds(lo, f64::INFINITY).radius
    }
}

impl Segment for FreeSegment {
    fn point(&self, s: f64) -> Point {
        let c = &self.constants;
        let model = &self.model;
        let (ec, es) = free_basis(model.nu, c.beta_sq, s);
        let (sd, cd) = math::sin_cos(model.eta * s);
        let basis = FreeBasis { ec, es };
        let beta = FreeDampedFrequency { beta_sq: c.beta_sq };
        let (x, y, vx, vy, h, dh) = match &self.form {
            Form::Steady(homogeneous) => {
                // The forcing phasor at s by angle addition from the segment start.
                let (c0, s0) = self.phase0;
                let phasor = Phasor {
                    ct: c0 * cd - s0 * sd,
                    st: s0 * cd + c0 * sd,
                };
                let r = coef::free_eval(model, &phasor, &c.particular, &beta, homogeneous, &basis);
                (r.x, r.y, r.vx, r.vy, r.h, r.dh)
            }
            Form::Forced {
                start,
                forcing,
                resonance,
            } => {
                let forced = resonance.basis(s, ec, es, (cd, sd));
                let r = coef::free_forced_eval(model, &beta, start, &basis, forcing, &forced);
                (r.x, r.y, r.vx, r.vy, r.h, r.dh)
            }
        };
        let (x, y) = if self.shift == (0.0, 0.0) {
            (x, y)
        } else {
            (x + self.shift.0, y + self.shift.1)
        };
        Point {
            state: State::new(x, y, vx, vy),
            h,
            dh,
        }
    }

    fn bounds(&self, lo: f64, hi: f64) -> Bounds {
        self.reach.bounds(&BasisBound::on(&self.constants, lo, hi))
    }
}
