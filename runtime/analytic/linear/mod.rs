//! The linearized contact segment (`docs/MODEL.md` §3, §5): exact solution of
//! q'' + 2νq' + Kl q = −Fd + F(cos θ, sin θ) + a0 + a1 s + a2 s² + a3 s³
//! from a state, in local time, for every case of `docs/MODEL.md` §6 (matrix-function homogeneous part).

mod bounds;
mod segment;

pub use bounds::max_contact_stiffness;
use bounds::{frobenius, harmonic_condition, position_gain, velocity_gain};
pub use segment::{LinearSegment, Part, Response};

use super::basis::{MatrixFunction, matrix_function};
use super::free::harmonic_amplitude;
use super::series::{MAX_RATE_HORIZON, Recurrence, SERIES_TERMS, Series, len_for_rate, rate};
use crate::coefficients::{
    self as coef, ContactBasis, ContactModes, ContactParticular, CubicForcing, HomogeneousInitial,
    LinearizedContact, ModelParams, Phasor, PolynomialParticular, Position, Slip,
};

/// Gain of the harmonic particular solution (its amplitude over the forcing amplitude F) above
/// which the linearization counts as near-resonant: the particular solution and the homogeneous
/// part would cancel to the response's size, losing about log10(gain) digits, so the harmonic
/// forcing is carried in the series response instead (`docs/MODEL.md` §11). Below it the loss is
/// at most 1e3 ulps of the harmonic amplitude.
pub const RESONANT_GAIN: f64 = 1e3;
use crate::field;
use crate::geometry;
use crate::math;
use crate::params::{Params, State};

/// What every linearization of one parameter set shares, computed once per parameter set
/// (the contact solvers keep it): the model parameters in the generated code's form and the
/// velocity gain of the segment bounds (the linearized field's Jacobian in q' is the damping's,
/// whatever Kl: see [`Linearization::slipping_with`]).
#[derive(Clone, Copy, Debug)]
pub struct ContactConstants {
    model: ModelParams,
    velocity_gain: f64,
}

impl ContactConstants {
    /// The model's parameters in the generated code's form.
    #[inline]
    pub fn model(&self) -> &ModelParams {
        &self.model
    }

    /// The constants of `params`.
    pub fn new(params: &Params) -> Self {
        let model = ModelParams::of(params);
        ContactConstants {
            model,
            velocity_gain: velocity_gain(&model, &LinearizedContact::default()),
        }
    }
}

/// Everything fixed by the linearization point: Kl, Fd, modes, particular constants, phase.
#[derive(Clone, Copy, Debug)]
pub struct Linearization {
    /// Kl and Fd.
    pub kl: LinearizedContact,
    modes: ContactModes,
    particular: ContactParticular,
    model: ModelParams,
    nu: f64,
    eta: f64,
    phase0: (f64, f64),
    /// Frobenius norms of A = Kl − ν²I and of Kl (for bounds).
    norm_a: f64,
    norm_kl: f64,
    /// |q''| ≤ gains.0·|q'| + gains.1·|q| on the homogeneous linearized equations.
    gains: (f64, f64),
    /// Bounds of the harmonic particular part: its largest amplitude (singular value of the
    /// cos/sin coefficient matrix) and the distance of its centre from the stator's.
    harmonic_amplitude: f64,
    harmonic_shift: f64,
    /// Near resonance ([`RESONANT_GAIN`]): the harmonic particular part is zero and every
    /// segment carries the harmonic forcing in its series response.
    resonant: bool,
    /// The slip direction σ of the linearized contact field (0: frictionless, `docs/MODEL.md`
    /// §10).
    slip: f64,
}

/// Why a linearization cannot be used.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Singular;

/// One step of iterative refinement of the particular constants (`docs/MODEL.md` §5): their
/// residual in the linearized equations (generated `contact_particular_residual`, input force
/// included) and the correction that cancels it (`contact_particular_correction`, the same
/// Cramer solve). Cramer's rule leaves a residual force of about ε·cond(Kl)·‖Kl‖·|c|: at
/// K̂ = 1e5 near z = 1 (cond ≈ 1e5) up to 1e-7, which the closed form's velocity follows at
/// that rate whatever the sub-step (the analytic method's error floor of 1e-12 per contact on
/// stiff stators, issue 32); after the correction the residual is the rounding of its own
/// evaluation, ε·‖Kl‖·|c|.
fn refine_particular(model: &ModelParams, kl: &LinearizedContact, c: &mut ContactParticular) {
    let residual = coef::contact_particular_residual(model, kl, c);
    let d = coef::contact_particular_correction(model, kl, &residual);
    c.c11 += d.c11;
    c.c22 += d.c22;
    c.c33 += d.c33;
    c.c44 += d.c44;
    c.c55 += d.c55;
    c.c66 += d.c66;
}

impl Linearization {
    /// Linearize the contact force about position (x0, y0) for a segment starting at time `t0`
    /// (`docs/MODEL.md` §2–3, §5). Fails when Kl is singular or the forcing resonant (§6 cases 9–10).
    pub fn new(params: &Params, t0: f64, x0: f64, y0: f64) -> Result<Self, Singular> {
        Self::slipping(params, 0.0, t0, x0, y0)
    }

    /// As [`Linearization::new`] for contact slipping in direction `slip` (σ = ±1) under
    /// friction: the generated `slipping_linearized_stiffness`, Kl no longer symmetric
    /// (`docs/MODEL.md` §10). `slip` = 0 is frictionless contact, exactly [`Linearization::new`].
    pub fn slipping(
        params: &Params,
        slip: f64,
        t0: f64,
        x0: f64,
        y0: f64,
    ) -> Result<Self, Singular> {
        let mut out = LinearSegment::zeroed().lin;
        Self::slipping_with(&ContactConstants::new(params), slip, t0, x0, y0, &mut out)?;
        Ok(out)
    }

    /// [`Linearization::slipping`] with the parameter set's [`ContactConstants`], written into
    /// `out` (unspecified on error).
    ///
    /// The velocity gain comes from the constants: the generated `linear_field_jacobians` in q'
    /// do not depend on Kl (the damping's alone), so the gain is the same for every Kl.
    pub fn slipping_with(
        constants: &ContactConstants,
        slip: f64,
        t0: f64,
        x0: f64,
        y0: f64,
        out: &mut Linearization,
    ) -> Result<(), Singular> {
        let model = &constants.model;
        let at = Position { x: x0, y: y0 };
        let kl = if slip == 0.0 {
            let t = coef::taylor_terms(model, &at);
            coef::linearized_stiffness(model, &t)
        } else {
            coef::slipping_linearized_stiffness(model, &at, &Slip { sigma: slip })
        };
        let nu = model.damping_ratio;
        let modes = coef::contact_modes(model, &kl);
        let scale =
            1.0 + math::abs(kl.fa1) + math::abs(kl.fa2) + math::abs(kl.fb1) + math::abs(kl.fb2);
        if math::abs(modes.det) <= 1e-12 * scale * scale {
            return Err(Singular);
        }
        let mut particular = coef::contact_particular(model, &kl);
        if model.force_x != 0.0 || model.force_y != 0.0 {
            // A constant input force adds the constant response Kl⁻¹u (`docs/MODEL.md` §15).
            let q = coef::input_contact_constant(model, &kl);
            particular.c55 += q.x;
            particular.c66 += q.y;
        }
        refine_particular(model, &kl, &mut particular);
        let c = &particular;
        if [c.c55, c.c66, modes.disc, modes.omega_sq_mean]
            .iter()
            .any(|v| !v.is_finite())
        {
            return Err(Singular);
        }
        let mut amplitude = harmonic_amplitude(c.c11, c.c22, c.c33, c.c44);
        // (Exact resonance gives NaN or infinite constants.)
        let resonant = amplitude.is_nan()
            || amplitude > RESONANT_GAIN * math::abs(model.unbalance_force)
            || harmonic_condition(model, &kl) > RESONANT_GAIN;
        if resonant {
            (
                particular.c11,
                particular.c22,
                particular.c33,
                particular.c44,
            ) = (0.0, 0.0, 0.0, 0.0);
            amplitude = 0.0;
        }
        let c = &particular;
        let phasor = field::phasor(model, t0);
        let a = coef::shifted_stiffness(model, &kl);
        let norm_a = frobenius([[a.a11, a.a12], [a.a21, a.a22]]);
        let norm_kl = frobenius([[kl.fa1, kl.fb1], [kl.fb2, kl.fa2]]);
        let gains = (constants.velocity_gain, position_gain(model, &kl));
        *out = Linearization {
            kl,
            modes,
            particular,
            model: *model,
            nu,
            eta: model.speed_ratio,
            phase0: (phasor.ct, phasor.st),
            norm_a,
            norm_kl,
            gains,
            harmonic_amplitude: amplitude,
            harmonic_shift: geometry::distance(model, c.c55, c.c66),
            resonant,
            slip,
        };
        Ok(())
    }

    /// The forcing phasor (cos θ0, sin θ0) at the segment start.
    pub fn phase0(&self) -> (f64, f64) {
        self.phase0
    }

    /// The slip direction σ this linearization was made for (0: frictionless).
    pub fn slip(&self) -> f64 {
        self.slip
    }

    /// n(q) = Kl q + Fd − q − (contact force): the nonlinear contact field minus its
    /// linearization at `state`'s position, as a force on the acceleration (zero at the
    /// linearization point; generated: `contact_remainder`, or `slipping_remainder` under
    /// friction).
    pub fn remainder(&self, state: &State) -> (f64, f64) {
        let at = Position {
            x: state.x,
            y: state.y,
        };
        let n = if self.slip == 0.0 {
            coef::contact_remainder(&self.model, &at, &self.kl)
        } else {
            coef::slipping_remainder(&self.model, &at, &self.kl, &Slip { sigma: self.slip })
        };
        (n.fx, n.fy)
    }

    /// Whether segments of this linearization are exact over `horizon`: always, except near
    /// resonance, where the series that carries the harmonic forcing needs
    /// max(μ, η)·horizon ≤ [`MAX_RATE_HORIZON`] (μ of `series::rate`). The contact schemes'
    /// step caps keep it (their steps are at most 1/√‖Kl‖ and 1/η); a longer fixed step is
    /// reported as singular rather than answered inaccurately.
    pub fn supports(&self, horizon: f64) -> bool {
        !self.resonant || self.harmonic_rate() * horizon <= MAX_RATE_HORIZON
    }

    fn harmonic_rate(&self) -> f64 {
        rate(self.norm_kl, self.nu).max(self.eta)
    }

    /// The Taylor coefficients in s of the harmonic forcing F (cos θ, sin θ) from the segment
    /// start, `[a0x, a0y, a1x, a1y, …]`, added to `out`: a_m = F η^m/m! (cos, sin)(θ0 + mπ/2).
    /// The force itself comes from the model (the generated `unbalance_force_at`).
    fn add_harmonic_forcing(&self, out: &mut [f64; 2 * SERIES_TERMS]) {
        let (c0, s0) = self.phase0;
        let force = |ct: f64, st: f64| {
            let f = coef::unbalance_force_at(&self.model, &Phasor { ct, st });
            [f.fx, f.fy]
        };
        // d/ds turns (cos θ, sin θ) by a quarter turn: even orders use the force at θ0, odd
        // ones at θ0 + π/2, with the sign (−1)^⌊m/2⌋.
        let turns = [force(c0, s0), force(-s0, c0)];
        let mut scale = 1.0;
        for (m, a) in out.chunks_exact_mut(2).enumerate() {
            let sign = if (m / 2) % 2 == 0 { scale } else { -scale };
            let [fx, fy] = if m % 2 == 0 { turns[0] } else { turns[1] };
            if let [ax, ay] = a {
                *ax += sign * fx;
                *ay += sign * fy;
            }
            scale *= self.eta / (m + 1) as f64;
        }
    }

    /// The largest angular frequency present (for step-size caps): √‖A‖ and η.
    pub fn fastest_frequency(&self) -> f64 {
        math::sqrt(self.norm_a).max(self.eta).max(self.nu)
    }

    fn phasor(&self, s: f64) -> (f64, f64) {
        let (sd, cd) = math::sin_cos(self.eta * s);
        let (c0, s0) = self.phase0;
        (c0 * cd - s0 * sd, s0 * cd + c0 * sd)
    }

    fn particular_state(&self, s: f64) -> [f64; 4] {
        let (ct, st) = self.phasor(s);
        let p = coef::contact_particular_eval(&self.model, &Phasor { ct, st }, &self.particular);
        [p.x, p.y, p.vx, p.vy]
    }

    /// The segment from `state` at s = 0 with the extra cubic forcing `forcing`
    /// (`[a0x, a0y, a1x, a1y, a2x, a2y, a3x, a3y]`; zeros for none), to be evaluated on
    /// s ∈ [0, `horizon`].
    ///
    /// The response to the cubic forcing is taken from the generated polynomial particular
    /// solution when ‖Kl‖·horizon² > 1. For shorter horizons that form cancels badly (its
    /// coefficients grow like (‖Kl‖h²)⁻ᵏ while the response is O(h²)), so the zero-state response
    /// is summed as its Taylor series instead (see [`Response`]).
    pub fn segment(&self, state: State, forcing: [f64; 8], horizon: f64) -> LinearSegment {
        let mut out = LinearSegment {
            lin: *self,
            part: Part::empty(),
        };
        self.fill(
            state,
            forcing,
            horizon,
            || self.cubic_terms(horizon),
            &mut out.part,
        );
        out
    }

    /// [`Self::segment`] written into `out` (no copy of the large segment).
    pub fn segment_into(
        &self,
        state: State,
        forcing: [f64; 8],
        horizon: f64,
        out: &mut LinearSegment,
    ) {
        self.segment_with(state, forcing, horizon, || self.cubic_terms(horizon), out);
    }

    /// [`Self::segment_into`] with the cubic forcing's series length from `cubic_terms` (called
    /// only when that response is needed; [`Self::cubic_terms`] of `horizon`).
    pub fn segment_with(
        &self,
        state: State,
        forcing: [f64; 8],
        horizon: f64,
        cubic_terms: impl FnOnce() -> Option<usize>,
        out: &mut LinearSegment,
    ) {
        out.lin = *self;
        self.fill(state, forcing, horizon, cubic_terms, &mut out.part);
    }

    /// The [`Part`] of the segment of this linearization from `state` with the extra cubic
    /// `forcing` over `horizon` ([`Self::segment_with`] without copying the linearization: a
    /// segment whose linearization is already in place, or a part evaluated with
    /// [`Self::state_of`]).
    pub fn fill(
        &self,
        state: State,
        forcing: [f64; 8],
        horizon: f64,
        cubic_terms: impl FnOnce() -> Option<usize>,
        out: &mut Part,
    ) {
        let k = &self.kl;
        out.forcing = forcing;
        if self.resonant {
            // The harmonic forcing and the extra cubic, as one series (`docs/MODEL.md` §11).
            let mut all = [0.0; 2 * SERIES_TERMS];
            for (a, f) in all.iter_mut().zip(forcing) {
                *a = f;
            }
            self.add_harmonic_forcing(&mut all);
            let len = len_for_rate(self.harmonic_rate() * horizon);
            if !matches!(out.response, Response::Series(_)) {
                out.response = Response::Series(Series::ZERO);
            }
            if let Response::Series(c) = &mut out.response {
                Recurrence {
                    model: &self.model,
                    kl: &self.kl,
                    forcing: &all,
                }
                .refill(len, c);
            }
        } else if forcing.iter().all(|&a| a == 0.0) {
            out.response = Response::None;
        } else if let Some(len) = cubic_terms() {
            if !matches!(out.response, Response::Series(_)) {
                out.response = Response::Series(Series::ZERO);
            }
            if let Response::Series(c) = &mut out.response {
                self.recurrence(&forcing).refill(len, c);
            }
        } else {
            let [a0x, a0y, a1x, a1y, a2x, a2y, a3x, a3y] = forcing;
            let a = CubicForcing {
                a0x,
                a0y,
                a1x,
                a1y,
                a2x,
                a2y,
                a3x,
                a3y,
            };
            out.response = Response::Polynomial(coef::polynomial_particular(&self.model, k, &a));
        }
        let poly = match &out.response {
            Response::Polynomial(b) => *b,
            _ => PolynomialParticular::default(),
        };
        let p = self.particular_state(0.0);
        let initial = HomogeneousInitial {
            xh0: state.x - p[0] - poly.b0x,
            yh0: state.y - p[1] - poly.b0y,
            vxh0: state.vx - p[2] - poly.b1x,
            vyh0: state.vy - p[3] - poly.b1y,
        };
        let start = coef::contact_homogeneous_start(&self.model, &initial);
        out.start = start;
    }

    /// The model parameters in the generated code's form.
    pub fn model(&self) -> &ModelParams {
        &self.model
    }

    /// The series response's equation for the cubic `forcing`.
    pub(super) fn recurrence<'a>(&'a self, forcing: &'a [f64; 8]) -> Recurrence<'a> {
        Recurrence {
            model: &self.model,
            kl: &self.kl,
            forcing,
        }
    }

    /// The matrix-function scalars and decay at local time `s` (shared by every segment of this
    /// linearization evaluated at the same `s`).
    pub fn scalars(&self, s: f64) -> ContactBasis {
        let MatrixFunction { cc, cd, sc, sd } =
            matrix_function(self.modes.gamma_sq_mean, self.modes.disc, s);
        ContactBasis {
            decay: math::exp(-self.nu * s),
            cc,
            cd,
            sc,
            sd,
        }
    }
}
