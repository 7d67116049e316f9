//! The linearized contact segment (`docs/MODEL.md` §3, §5): exact solution of
//! q'' + 2νq' + Kl q = −Fd + F(cos θ, sin θ) + a0 + a1 s + a2 s² + a3 s³
//! from a state, in local time, for every case of `docs/MODEL.md` §6 (matrix-function homogeneous part).

use super::basis::{MatrixFunction, matrix_function};
use super::free::harmonic_amplitude;
use super::segment::{Bounds, Point, Segment, point_of};
use super::series::{
    self, Coefficients, MAX_RATE_HORIZON, Recurrence, SERIES_TERMS, len_for_rate, rate, series_len,
};
use crate::coefficients::{
    self as coef, ContactBasis, ContactModes, ContactParticular, CubicForcing, Force,
    HomogeneousInitial, HomogeneousStart, LinearizedContact, LocalTime, ModelParams, Phasor,
    PolynomialParticular, Position, Velocity,
};

/// Gain of the harmonic particular solution (its amplitude over the forcing amplitude F) above
/// which the linearization counts as near-resonant: the particular solution and the homogeneous
/// part would cancel to the response's size, losing about log10(gain) digits, so the harmonic
/// forcing is carried in the series response instead (`docs/MODEL.md` §11). Below it the loss is
/// at most 1e3 ulps of the harmonic amplitude.
pub const RESONANT_GAIN: f64 = 1e3;
use crate::math;
use crate::params::{Params, State};

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
    offset: (f64, f64),
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
}

/// The Frobenius norm of a 2×2 matrix (rows), diagonal first.
fn frobenius(m: [[f64; 2]; 2]) -> f64 {
    let [[a, b], [c, d]] = m;
    math::sqrt(a * a + d * d + b * b + c * c)
}

/// Gains of the homogeneous linearized contact acceleration q'' = −2ν q' − Kl q (the generated
/// `linear_acceleration` with no extra force): |q''| ≤ g_v |q'| + g_q |q| with g_v, g_q the
/// largest singular values of its Jacobians in q' and q, read off as its values at unit vectors
/// (the map is linear).
fn acceleration_gains(model: &ModelParams, kl: &LinearizedContact) -> (f64, f64) {
    let acc = |q: [f64; 2], v: [f64; 2]| {
        let a = coef::linear_acceleration(
            model,
            &Position { x: q[0], y: q[1] },
            &Velocity { vx: v[0], vy: v[1] },
            &Force::default(),
            kl,
        );
        [a.ax, a.ay]
    };
    let norm = |c1: [f64; 2], c2: [f64; 2]| harmonic_amplitude(c1[0], c2[0], c1[1], c2[1]);
    (
        norm(acc([0.0; 2], [1.0, 0.0]), acc([0.0; 2], [0.0, 1.0])),
        norm(acc([1.0, 0.0], [0.0; 2]), acc([0.0, 1.0], [0.0; 2])),
    )
}

/// An upper bound of ‖Kl‖₂ over every linearization point with z ≥ 1: the square of the fastest
/// contact frequency (the analytic propagator caps its contact step by its inverse root).
///
/// Argument, from the generated formulas only: Kl (`linearized_stiffness`) is affine in K_s,
/// Kl = Kl₀ + K_s J with Kl₀ its value at K_s = 0 (the restoring spring), so
/// ‖Kl‖₂ ≤ ‖Kl₀‖₂ + ‖K_s‖_F ‖J‖₂. The contact function g is rotation-equivariant about the stator
/// centre (g(Rq) = R g(q)), so J(Rq) = R J(q) Rᵀ and ‖J‖₂ depends on z only: J is evaluated along
/// (1, 0) (`taylor_terms`). J is affine in w = 1/z (checked in `tests/generated/field.rs`) and the
/// norm is convex, so its supremum over w ∈ (0, 1] is at an end: J(1) at z = 1 and
/// J(0) = 2 J(½) − J(1) from z = 2. (For the elastic law J = (1 − w) I + w n nᵀ: the bound is
/// 1 + ‖K_s‖_F up to the singular-value margin.)
pub fn max_contact_stiffness(params: &Params) -> f64 {
    let mut model = ModelParams::of(params);
    let ks = frobenius([[model.kxx, model.kxy], [model.kyx, model.kyy]]);
    let jacobian = |z: f64| {
        let at = Position {
            x: model.ex + z,
            y: model.ey,
        };
        let t = coef::taylor_terms(&model, &at);
        [[t.a1, t.b1], [t.b2, t.a2]]
    };
    let (j1, j2) = (jacobian(1.0), jacobian(2.0));
    let j0 = [[0, 1], [2, 3]].map(|row| {
        row.map(|k| {
            let (a, b) = (j2.as_flattened(), j1.as_flattened());
            2.0 * a.get(k).copied().unwrap_or(0.0) - b.get(k).copied().unwrap_or(0.0)
        })
    });
    let spectral = |m: [[f64; 2]; 2]| harmonic_amplitude(m[0][0], m[0][1], m[1][0], m[1][1]);
    let j_norm = spectral(j1).max(spectral(j0));
    (model.kxx, model.kxy, model.kyx, model.kyy) = (0.0, 0.0, 0.0, 0.0);
    let t = coef::taylor_terms(&model, &Position { x: 1.0, y: 0.0 });
    let k0 = coef::linearized_stiffness(&model, &t);
    spectral([[k0.fa1, k0.fb1], [k0.fb2, k0.fa2]]) + ks * j_norm
}

/// The condition of the harmonic system (Kl − η² I + 2iνη I) Z = F (1, −i)ᵀ that gives the
/// harmonic particular constants: the size of its determinant's terms over the determinant's
/// modulus. Rounding in the generated Cramer formulas is amplified by it; near resonance it can
/// leave finite but wrong constants whose amplitude looks harmless (at z0 = 1 with η = 1 the
/// tangential eigenvalue of Kl is 1 exactly and the computed determinant is rounding noise), so
/// the amplitude alone cannot detect resonance. The determinant comes from the generated
/// `contact_modes` of the shifted stiffness Kl − η² I: det(M + iP I) = det M − P² + iP tr M.
fn harmonic_condition(model: &ModelParams, kl: &LinearizedContact) -> f64 {
    let eta_sq = model.eta * model.eta;
    let shifted = LinearizedContact {
        fa1: kl.fa1 - eta_sq,
        fa2: kl.fa2 - eta_sq,
        ..*kl
    };
    let det = coef::contact_modes(model, &shifted).det;
    let p = 2.0 * model.nu * model.eta;
    let trace = shifted.fa1 + shifted.fa2;
    let modulus = math::hypot(det - p * p, p * trace);
    let terms = math::abs(shifted.fa1 * shifted.fa2)
        + math::abs(shifted.fb1 * shifted.fb2)
        + p * p
        + p * (math::abs(shifted.fa1) + math::abs(shifted.fa2));
    // (0/0 at a zero system is not resonant: there is no harmonic forcing to amplify.)
    if terms == 0.0 { 0.0 } else { terms / modulus }
}

/// Why a linearization cannot be used.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Singular;

impl Linearization {
    /// Linearize the contact force about position (x0, y0) for a segment starting at time `t0`
    /// (`docs/MODEL.md` §2–3, §5). Fails when Kl is singular or the forcing resonant (§6 cases 9–10).
    pub fn new(params: &Params, t0: f64, x0: f64, y0: f64) -> Result<Self, Singular> {
        let p = params;
        let model = ModelParams::of(p);
        let t = coef::taylor_terms(&model, &Position { x: x0, y: y0 });
        let kl = coef::linearized_stiffness(&model, &t);
        let nu = p.damping_ratio;
        let modes = coef::contact_modes(&model, &kl);
        let scale =
            1.0 + math::abs(kl.fa1) + math::abs(kl.fa2) + math::abs(kl.fb1) + math::abs(kl.fb2);
        if math::abs(modes.det) <= 1e-12 * scale * scale {
            return Err(Singular);
        }
        let mut particular = coef::contact_particular(&model, &kl);
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
            || amplitude > RESONANT_GAIN * math::abs(model.f)
            || harmonic_condition(&model, &kl) > RESONANT_GAIN;
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
        let (st, ct) = math::sin_cos(math::wrap_angle(p.speed_ratio * t0 + p.phase));
        let a = coef::shifted_stiffness(&model, &kl);
        let norm_a = frobenius([[a.a11, a.a12], [a.a21, a.a22]]);
        let norm_kl = frobenius([[kl.fa1, kl.fb1], [kl.fb2, kl.fa2]]);
        let gains = acceleration_gains(&model, &kl);
        Ok(Linearization {
            kl,
            modes,
            particular,
            model,
            nu,
            eta: p.speed_ratio,
            phase0: (ct, st),
            offset: (p.offset_x, p.offset_y),
            norm_a,
            norm_kl,
            gains,
            harmonic_amplitude: amplitude,
            harmonic_shift: math::hypot(c.c55 - p.offset_x, c.c66 - p.offset_y),
            resonant,
        })
    }

    /// Whether segments of this linearization are exact over `horizon`: always, except near
    /// resonance, where the series that carries the harmonic forcing needs
    /// max(μ, η)·horizon ≤ [`MAX_RATE_HORIZON`] (μ of [`series::rate`]). The contact schemes'
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
    /// The force itself comes from the model (the generated free acceleration at rest).
    fn add_harmonic_forcing(&self, out: &mut [f64; 2 * SERIES_TERMS]) {
        let (c0, s0) = self.phase0;
        let force = |ct: f64, st: f64| {
            let a = coef::free_acceleration(
                &self.model,
                &Position::default(),
                &Velocity::default(),
                &Phasor { ct, st },
            );
            [a.ax, a.ay]
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
            response: Response::None,
            start: HomogeneousStart::default(),
        };
        self.segment_into(state, forcing, horizon, &mut out);
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
        let k = &self.kl;
        out.lin = *self;
        if self.resonant {
            // The harmonic forcing and the extra cubic, as one series (`docs/MODEL.md` §11).
            let mut all = [0.0; 2 * SERIES_TERMS];
            for (a, f) in all.iter_mut().zip(forcing) {
                *a = f;
            }
            self.add_harmonic_forcing(&mut all);
            let len = len_for_rate(self.harmonic_rate() * horizon);
            if !matches!(out.response, Response::Series(_)) {
                out.response = Response::Series([[0.0; 2]; SERIES_TERMS]);
            }
            if let Response::Series(c) = &mut out.response {
                Recurrence {
                    model: &self.model,
                    kl: &self.kl,
                    forcing: &all,
                }
                .coefficients_into(len, c);
            }
        } else if forcing.iter().all(|&a| a == 0.0) {
            out.response = Response::None;
        } else if self.norm_kl * horizon * horizon <= 1.0 {
            let len = series_len(self.norm_kl, self.nu, horizon);
            if !matches!(out.response, Response::Series(_)) {
                out.response = Response::Series([[0.0; 2]; SERIES_TERMS]);
            }
            if let Response::Series(c) = &mut out.response {
                self.recurrence(&forcing).coefficients_into(len, c);
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

    /// The state at `s` of the segment from the same start with the extra cubic `forcing` over
    /// `horizon`, given `unforced`, the state at `s` of the segment without extra forcing — when
    /// that segment's response is a Taylor series or absent, so that both share their
    /// homogeneous and harmonic parts (`None` otherwise: build the segment). The same sums in
    /// the same order as [`LinearSegment::state_with`], so the same bits.
    pub fn forced_state(
        &self,
        unforced: &State,
        forcing: &[f64; 8],
        horizon: f64,
        s: f64,
    ) -> Option<State> {
        if self.resonant {
            // The unforced segment's series holds the harmonic forcing: build the segment.
            return None;
        }
        if forcing.iter().all(|&a| a == 0.0) {
            return Some(*unforced);
        }
        if self.norm_kl * horizon * horizon <= 1.0 {
            let len = series_len(self.norm_kl, self.nu, horizon);
            let q = self.recurrence(forcing).value(len, s);
            return Some(add_response(unforced, &q));
        }
        None
    }

    /// The model parameters in the generated code's form.
    pub fn model(&self) -> &ModelParams {
        &self.model
    }

    /// The series response's equation for the cubic `forcing`.
    fn recurrence<'a>(&'a self, forcing: &'a [f64; 8]) -> Recurrence<'a> {
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

/// How the response to the extra cubic forcing is represented.
#[derive(Clone, Copy, Debug)]
#[allow(
    clippy::large_enum_variant,
    reason = "the runtime has no heap to box into"
)]
pub enum Response {
    /// No extra forcing.
    None,
    /// The generated cubic particular solution (its homogeneous complement is in q0, w0).
    Polynomial(PolynomialParticular),
    /// The zero-state response as a Taylor polynomial Σ c_m s^m (x and y coefficients), from
    /// the equations of motion: c0 = c1 = 0 and
    /// (m + 2)(m + 1) c_{m+2} = a_m − 2ν(m + 1) c_{m+1} − Kl c_m (`docs/MODEL.md` §3).
    Series(Coefficients),
}

/// `unforced + q` componentwise (the last sum of [`LinearSegment::state_with`]).
#[inline]
fn add_response(unforced: &State, q: &[f64; 4]) -> State {
    State::new(
        unforced.x + q[0],
        unforced.y + q[1],
        unforced.vx + q[2],
        unforced.vy + q[3],
    )
}

/// A linearized contact segment: [`Linearization`] plus initial state and cubic forcing.
#[derive(Clone, Copy, Debug)]
pub struct LinearSegment {
    lin: Linearization,
    response: Response,
    start: HomogeneousStart,
}

impl LinearSegment {
    /// The state at `s` given precomputed scalars (see [`Linearization::scalars`]).
    pub fn state_with(&self, s: f64, scalars: &ContactBasis) -> State {
        let l = &self.lin;
        let h = coef::contact_homogeneous_eval(&l.model, &l.kl, &l.modes, &self.start, scalars);
        let p = l.particular_state(s);
        let q = match &self.response {
            Response::None => [0.0; 4],
            Response::Polynomial(b) => {
                let q = coef::polynomial_eval(&LocalTime { s }, b);
                [q.x, q.y, q.vx, q.vy]
            }
            Response::Series(c) => series::eval(c, s),
        };
        State::new(
            h.x + p[0] + q[0],
            h.y + p[1] + q[1],
            h.vx + p[2] + q[2],
            h.vy + p[3] + q[3],
        )
    }

    /// The state at `s` given `unforced`, the state at `s` of the segment without extra forcing
    /// from the same start (see [`Linearization::forced_state`]), when this segment's response
    /// shares its homogeneous part (a series or none); `None` for a polynomial response.
    pub fn state_from_unforced(&self, s: f64, unforced: &State) -> Option<State> {
        if self.lin.resonant {
            return None;
        }
        match &self.response {
            Response::None => Some(*unforced),
            Response::Series(c) => Some(add_response(unforced, &series::eval(c, s))),
            Response::Polynomial(_) => None,
        }
    }

    /// A segment with every coefficient zero (a slot to be filled by
    /// [`Linearization::segment_into`]).
    pub(crate) fn zeroed() -> LinearSegment {
        LinearSegment {
            lin: Linearization {
                kl: LinearizedContact::default(),
                modes: ContactModes::default(),
                particular: ContactParticular::default(),
                model: ModelParams::default(),
                nu: 0.0,
                eta: 0.0,
                phase0: (1.0, 0.0),
                offset: (0.0, 0.0),
                norm_a: 0.0,
                norm_kl: 0.0,
                gains: (0.0, 0.0),
                harmonic_amplitude: 0.0,
                harmonic_shift: 0.0,
                resonant: false,
            },
            response: Response::None,
            start: HomogeneousStart::default(),
        }
    }

    /// The linearization this segment belongs to.
    pub fn linearization(&self) -> &Linearization {
        &self.lin
    }
}

/// Σ‖c_m‖ s^m and the same bound for the first two derivatives at s = `hi`, from the norms
/// ‖c_m‖ in order of m.
#[inline]
fn polynomial_bounds(norms: impl Iterator<Item = f64>, hi: f64) -> (f64, f64, f64) {
    let (mut pr, mut pv, mut pa) = (0.0, 0.0, 0.0);
    // p2 = hi^(m−2), p1 = hi^(m−1), p0 = hi^m.
    let (mut p2, mut p1, mut p0) = (0.0, 0.0, 1.0);
    for (m, norm) in norms.enumerate() {
        let mf = m as f64;
        pr += norm * p0;
        pv += mf * norm * p1;
        pa += mf * (mf - 1.0) * norm * p2;
        (p2, p1, p0) = (if m == 0 { 1.0 } else { p1 }, p0, p0 * hi);
    }
    (pr, pv, pa)
}

impl Segment for LinearSegment {
    fn point(&self, s: f64) -> Point {
        let state = self.state_with(s, &self.lin.scalars(s));
        point_of(state, self.lin.offset.0, self.lin.offset.1)
    }

    fn bounds(&self, lo: f64, hi: f64) -> Bounds {
        let l = &self.lin;
        // ‖cos(√A s)‖ ≤ cosh(√‖A‖ s), ‖sin(√A s)/√A‖ ≤ s·cosh(√‖A‖ s) (power series).
        let ch = math::cosh(math::sqrt(l.norm_a) * hi);
        let decay = math::exp(-l.nu * lo);
        // |q0|, |w0| (no overflow: states are bounded by the divergence radius).
        let h = &self.start;
        let q0 = math::sqrt(h.q0x * h.q0x + h.q0y * h.q0y);
        let w0 = math::sqrt(h.w0x * h.w0x + h.w0y * h.w0y);
        let rh = decay * ch * (q0 + hi * w0);
        let vh = l.nu * rh + decay * ch * (l.norm_a * hi * q0 + w0);
        let ah = l.gains.0 * vh + l.gains.1 * rh;
        let (amp, shift) = (l.harmonic_amplitude, l.harmonic_shift);
        // |Σ c_m s^m| and its derivatives, bounded term by term at s = hi (1-norms bound the
        // Euclidean ones).
        let norm = |c: &[f64]| c.iter().take(2).map(|v| math::abs(*v)).sum::<f64>();
        let (pr, pv, pa) = match &self.response {
            Response::None => (0.0, 0.0, 0.0),
            Response::Polynomial(b) => {
                let c = [b.b0x, b.b0y, b.b1x, b.b1y, b.b2x, b.b2y, b.b3x, b.b3y];
                polynomial_bounds(c.chunks_exact(2).map(norm), hi)
            }
            Response::Series(c) => {
                polynomial_bounds(c.iter().take(series::used(c)).map(|c| norm(c)), hi)
            }
        };
        Bounds {
            radius: rh + amp + shift + pr,
            speed: vh + l.eta * amp + pv,
            accel: ah + l.eta * l.eta * amp + pa,
        }
    }
}
