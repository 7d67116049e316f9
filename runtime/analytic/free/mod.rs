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

mod bound;
mod instant;
mod step;

use bound::Amplitudes;
pub(crate) use bound::{BasisBound, FreeReach, harmonic_amplitude, plain_norm};
pub(crate) use instant::FreeInstant;
use instant::evaluate;
pub(crate) use step::{forcing_matrix, transition_matrix};

use super::basis::FreeRates;
use super::forced::Resonance;
use super::segment::{Bounds, Point, Segment};
use crate::coefficients::{
    self as coef, FreeForcing, FreeHomogeneous, FreeParticular, ModelParams, Phasor,
};
use crate::math;
use crate::params::{Params, State};

/// Per-parameter-set constants of free flight (computed once per propagation).
#[derive(Clone, Copy, Debug)]
pub struct FreeConstants {
    /// Steady-state harmonic response (not finite at ν = 0, η = 1).
    pub particular: FreeParticular,
    /// σ of the steady-state response, when finite.
    steady_amplitude: Option<f64>,
    /// The forced basis, within [`super::forced::RESONANT_BAND`] of resonance.
    resonance: Option<Resonance>,
    /// ν, β² = 1 − ν² and what the basis and its bounds derive from them.
    rates: FreeRates,
    /// The static deflection under the input force u (generated `input_static_deflection`;
    /// exactly (0, 0) without one, and then never applied: the unforced path is unchanged).
    deflection: (f64, f64),
    /// ν, η, F (and ε̂, replaced per segment) for the generated formulas.
    model: ModelParams,
}

impl FreeConstants {
    /// Derived constants for `params`.
    #[inline(always)]
    pub fn new(params: &Params) -> Self {
        let model = ModelParams::of(params);
        let beta_sq = coef::free_damped_frequency_sq(&model).beta_sq;
        let p = coef::free_particular(&model);
        let amp = harmonic_amplitude(p.c11, p.c22, p.c33, p.c44);
        FreeConstants {
            deflection: deflection(&model),
            particular: p,
            steady_amplitude: amp.is_finite().then_some(amp),
            rates: FreeRates::new(model.damping_ratio, beta_sq),
            resonance: Resonance::near(model.damping_ratio, beta_sq, model.speed_ratio),
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

    /// `f` of these constants without input force: of `self` itself when it has none (then
    /// [`Self::with_input`] of (0, 0) would copy the same values).
    /// One call of `f`, so that it is inlined (the stepper's Φ and G stay in registers).
    #[inline(always)]
    pub(crate) fn unforced<R>(&self, f: impl FnOnce(&FreeConstants) -> R) -> R {
        let stripped;
        let unforced = if self.model.force_x.to_bits() == 0 && self.model.force_y.to_bits() == 0 {
            self
        } else {
            stripped = self.with_input((0.0, 0.0));
            &stripped
        };
        f(unforced)
    }

    /// The model's parameters these constants were made for (the generated formulas' inputs).
    #[inline]
    pub fn model(&self) -> &ModelParams {
        &self.model
    }

    /// β² = 1 − ν².
    #[inline]
    pub fn beta_sq(&self) -> f64 {
        self.rates.beta_sq
    }

    /// The static deflection under the input force ((0, 0) without one).
    pub fn deflection(&self) -> (f64, f64) {
        self.deflection
    }

    /// Whether free flight uses the resonance-stable form (`docs/MODEL.md` §11).
    pub fn resonant(&self) -> bool {
        self.resonance.is_some()
    }

    /// ν and β² = 1 − ν², bit for bit: what unforced free flight depends on. Two parameter
    /// sets with the same key have the same response to a start state without forcing (the
    /// generated `free_step_transition`), so what depends on it alone — the stepper's Φ(dt),
    /// the basis at dt and its bounds — can be kept.
    pub(crate) fn damping_key(&self) -> (u64, u64) {
        (
            self.model.damping_ratio.to_bits(),
            self.rates.beta_sq.to_bits(),
        )
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

/// Free flight from a state at time τ0, valid for all s = τ − τ0 ≥ 0 until contact. Under an
/// input force the closed form describes q − d about the static deflection d of its constants
/// (`docs/MODEL.md` §15), with the stator offset moved by −d.
#[derive(Clone, Copy, Debug)]
pub struct FreeSegment {
    constants: FreeConstants,
    /// The parameters with this segment's offset.
    model: ModelParams,
    phase0: (f64, f64),
    form: Form,
    reach: FreeReach,
}

impl FreeSegment {
    /// The free segment through `state` at absolute time `t0`.
    pub fn new(params: &Params, constants: &FreeConstants, t0: f64, state: State) -> Self {
        let offset = (params.offset_x, params.offset_y);
        let off = Self::offset_distance(constants, offset);
        Self::with_offset_distance(params, constants, off, t0, state)
    }

    /// [`Self::new`] given `off` = [`Self::offset_distance`] of `constants` and the parameters'
    /// offset, which is constant per parameter set (the stepper keeps it: one `hypot` fewer
    /// per segment).
    pub(crate) fn with_offset_distance(
        params: &Params,
        constants: &FreeConstants,
        off: f64,
        t0: f64,
        state: State,
    ) -> Self {
        let phasor = crate::field::phasor(&constants.model, t0);
        Self::build(
            constants,
            (params.offset_x, params.offset_y),
            off,
            (phasor.ct, phasor.st),
            state,
        )
    }

    /// The free segment through `state` with forcing phasor `phasor` = (cos θ0, sin θ0) at its
    /// start, stator offset `offset` and `off` = [`Self::offset_distance`]. Under an input
    /// force the closed form is written about the static deflection d: free flight of q − d,
    /// with the offset ε − d (`docs/MODEL.md` §15).
    #[inline]
    fn build(
        constants: &FreeConstants,
        offset: (f64, f64),
        off: f64,
        phasor: (f64, f64),
        state: State,
    ) -> Self {
        let (model, form, reach) = Self::parts(constants, offset, off, phasor, state, math::hypot);
        FreeSegment {
            constants: *constants,
            model,
            phase0: phasor,
            form,
            reach,
        }
    }

    /// Only the bound amplitudes of [`Self::build`]'s segment, without building the
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
    /// of the free segment through `state` (see [`Self::build`]), with `norm` the
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
            offset_x: offset.0,
            offset_y: offset.1,
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

    /// The state at `at` of the free segment through `state` with start phasor `phasor` and no
    /// stator offset, without building the segment (no copy of the constants, no bound
    /// amplitudes): the stepper's forcing columns in the resonance-stable form. The same
    /// arithmetic as [`Self::build`] followed by [`Segment::point`].
    pub(crate) fn state_at(
        constants: &FreeConstants,
        phasor: (f64, f64),
        state: State,
        at: &FreeInstant,
    ) -> State {
        let (model, form, _) = Self::parts(constants, (0.0, 0.0), 0.0, phasor, state, |_, _| 0.0);
        evaluate(constants, &model, phasor, &form, at).state
    }
}

impl Segment for FreeSegment {
    fn point(&self, s: f64) -> Point {
        let at = FreeInstant::at(&self.constants, s);
        evaluate(&self.constants, &self.model, self.phase0, &self.form, &at)
    }

    fn bounds(&self, lo: f64, hi: f64) -> Bounds {
        self.reach.bounds(&BasisBound::on(&self.constants, lo, hi))
    }
}
