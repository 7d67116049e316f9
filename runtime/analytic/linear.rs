//! The linearized contact segment (`model.md` §3, §5): exact solution of
//! q'' + 2νq' + Kl q = −Fd + F(cos θ, sin θ) + a0 + a1 s + a2 s² + a3 s³
//! from a state, in local time, for every case of `model.md` §6 (matrix-function homogeneous part).

use super::basis::{MatrixFunction, matrix_function};
use super::free::harmonic_amplitude;
use super::segment::{Bounds, Point, Segment, point_of};
use crate::coefficients::{
    self as coef, ContactBasis, ContactModes, ContactParticular, CubicForcing, HomogeneousInitial,
    HomogeneousStart, LinearizedContact, LocalTime, ModelParams, Phasor, PolynomialParticular,
    Position,
};
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
    /// Bounds of the harmonic particular part: its largest amplitude (singular value of the
    /// cos/sin coefficient matrix) and the distance of its centre from the stator's.
    harmonic_amplitude: f64,
    harmonic_shift: f64,
}

/// Why a linearization cannot be used.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Singular;

impl Linearization {
    /// Linearize the contact force about position (x0, y0) for a segment starting at time `t0`
    /// (`model.md` §2–3, §5). Fails when Kl is singular or the forcing resonant (§6 cases 9–10).
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
        let particular = coef::contact_particular(&model, &kl);
        let c = &particular;
        let all = [
            c.c11,
            c.c22,
            c.c33,
            c.c44,
            c.c55,
            c.c66,
            modes.disc,
            modes.omega_sq_mean,
        ];
        if all.iter().any(|v| !v.is_finite()) {
            return Err(Singular);
        }
        let (st, ct) = math::sin_cos(math::wrap_angle(p.speed_ratio * t0 + p.phase));
        let nn = nu * nu;
        let norm_a = math::sqrt(
            (kl.fa1 - nn) * (kl.fa1 - nn)
                + (kl.fa2 - nn) * (kl.fa2 - nn)
                + kl.fb1 * kl.fb1
                + kl.fb2 * kl.fb2,
        );
        let norm_kl =
            math::sqrt(kl.fa1 * kl.fa1 + kl.fa2 * kl.fa2 + kl.fb1 * kl.fb1 + kl.fb2 * kl.fb2);
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
            harmonic_amplitude: harmonic_amplitude(c.c11, c.c22, c.c33, c.c44),
            harmonic_shift: math::hypot(c.c55 - p.offset_x, c.c66 - p.offset_y),
        })
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
        if forcing.iter().all(|&a| a == 0.0) {
            out.response = Response::None;
        } else if self.norm_kl * horizon * horizon <= 1.0 {
            let len = series_len(self.norm_kl, self.nu, horizon);
            if !matches!(out.response, Response::Series(_)) {
                out.response = Response::Series([[0.0; 2]; SERIES_TERMS]);
            }
            if let Response::Series(c) = &mut out.response {
                series_response_into(k, self.nu, &forcing, len, c);
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
        if forcing.iter().all(|&a| a == 0.0) {
            return Some(*unforced);
        }
        if self.norm_kl * horizon * horizon <= 1.0 {
            let len = series_len(self.norm_kl, self.nu, horizon);
            let q = series_value(&self.kl, self.nu, forcing, len, s);
            return Some(add_response(unforced, &q));
        }
        None
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

/// Number of Taylor coefficients of the series response (degree `SERIES_TERMS − 1`); with
/// ‖Kl‖h² ≤ 1 the first neglected term is below 1e-16 of the forcing's response.
const SERIES_TERMS: usize = 20;

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
    /// (m + 2)(m + 1) c_{m+2} = a_m − 2ν(m + 1) c_{m+1} − Kl c_m (`model.md` §3).
    Series([[f64; 2]; SERIES_TERMS]),
}

/// 1/((m + 2)(m + 1)) for m = 0 … SERIES_TERMS − 3 (the recurrence's divisors).
const SERIES_DIVISORS: [f64; SERIES_TERMS - 2] = {
    let mut r = [0.0; SERIES_TERMS - 2];
    let mut m = 0;
    while m < SERIES_TERMS - 2 {
        r[m] = 1.0 / (((m + 2) * (m + 1)) as f64);
        m += 1;
    }
    r
};

/// How many Taylor coefficients the series response needs on s ∈ [0, horizon].
///
/// Beyond the forcing (m ≥ 4) the recurrence gives ‖c_m‖ ≤ B μ^m / m! with μ = ν + √(ν² + ‖Kl‖)
/// (μ² = 2νμ + ‖Kl‖ turns the bound into an equality), so the terms from n on add at most
/// (μh)^(n−5)·5!/n!·e^(μh) relative to the degree-5 term. The count is the smallest n ≥ 6 with
/// (μh)^(n−5)·5!/n! ≤ 1e-19, at most [`SERIES_TERMS`] (where ‖Kl‖h² ≤ 1 keeps the bound below
/// 1e-16, the fixed length's design).
fn series_len(norm_kl: f64, nu: f64, horizon: f64) -> usize {
    let mu_h = (nu + math::sqrt(nu * nu + norm_kl)) * horizon;
    // term = (μh)^(n−5)·5!/n!, from n = 6.
    let mut term = mu_h / 6.0;
    let mut n = 6;
    // (NaN runs to the full length.)
    while n < SERIES_TERMS && (term > 1e-19 || term.is_nan()) {
        n += 1;
        term *= mu_h / n as f64;
    }
    n
}

/// The first `len` (6 … [`SERIES_TERMS`]) coefficients of the series response into `c`, the
/// others zero.
fn series_response_into(
    k: &LinearizedContact,
    nu: f64,
    a: &[f64; 8],
    len: usize,
    c: &mut [[f64; 2]; SERIES_TERMS],
) {
    let len = len.clamp(6, SERIES_TERMS);
    c[0] = [0.0; 2];
    c[1] = [0.0; 2];
    for m in 0..len - 2 {
        let (f0, f1) = if m < 4 {
            (a[2 * m], a[2 * m + 1])
        } else {
            (0.0, 0.0)
        };
        let r = SERIES_DIVISORS[m];
        let damp = 2.0 * nu * (m + 1) as f64;
        let [cx, cy] = c[m];
        let [nx, ny] = c[m + 1];
        c[m + 2] = [
            (f0 - damp * nx - k.fa1 * cx - k.fb1 * cy) * r,
            (f1 - damp * ny - k.fb2 * cx - k.fa2 * cy) * r,
        ];
    }
    for t in &mut c[len..] {
        *t = [0.0; 2];
    }
}

/// The series response's position and velocity at `s` in one pass, without storing its
/// coefficients: the recurrence of [`series_response_into`] summed forwards (the same value as
/// [`series_eval`] of those coefficients up to rounding).
fn series_value(k: &LinearizedContact, nu: f64, a: &[f64; 8], len: usize, s: f64) -> [f64; 4] {
    let len = len.clamp(6, SERIES_TERMS);
    // (c_m, c_{m+1}) with c0 = c1 = 0; the terms m = 0, 1 contribute nothing.
    let (mut cm, mut cn) = ([0.0, 0.0], [0.0, 0.0]);
    let (mut x, mut y, mut vx, mut vy) = (0.0, 0.0, 0.0, 0.0);
    // s^(m+1) and (m+2)·s^(m+1) for the term c_{m+2} s^(m+2).
    let mut pow1 = s;
    for m in 0..len - 2 {
        let (f0, f1) = if m < 4 {
            (a[2 * m], a[2 * m + 1])
        } else {
            (0.0, 0.0)
        };
        let r = SERIES_DIVISORS[m];
        let damp = 2.0 * nu * (m + 1) as f64;
        let next = [
            (f0 - damp * cn[0] - k.fa1 * cm[0] - k.fb1 * cm[1]) * r,
            (f1 - damp * cn[1] - k.fb2 * cm[0] - k.fa2 * cm[1]) * r,
        ];
        let pow2 = pow1 * s;
        let d = (m + 2) as f64 * pow1;
        x += next[0] * pow2;
        y += next[1] * pow2;
        vx += next[0] * d;
        vy += next[1] * d;
        (cm, cn, pow1) = (cn, next, pow2);
    }
    [x, y, vx, vy]
}

/// The number of coefficients up to the last non-zero one.
#[inline]
fn series_used(c: &[[f64; 2]; SERIES_TERMS]) -> usize {
    c.iter()
        .rposition(|t| t[0] != 0.0 || t[1] != 0.0)
        .map_or(0, |i| i + 1)
}

/// Position and velocity of a Taylor polynomial at s (Horner).
fn series_eval(c: &[[f64; 2]; SERIES_TERMS], s: f64) -> [f64; 4] {
    series_eval_len(c, series_used(c), s)
}

/// [`series_eval`] of the first `len` coefficients.
#[inline]
fn series_eval_len(c: &[[f64; 2]; SERIES_TERMS], len: usize, s: f64) -> [f64; 4] {
    let (mut x, mut y, mut vx, mut vy) = (0.0, 0.0, 0.0, 0.0);
    for m in (0..len.min(SERIES_TERMS)).rev() {
        x = x * s + c[m][0];
        y = y * s + c[m][1];
        if m > 0 {
            vx = vx * s + m as f64 * c[m][0];
            vy = vy * s + m as f64 * c[m][1];
        }
    }
    [x, y, vx, vy]
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
            Response::Series(c) => series_eval(c, s),
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
        match &self.response {
            Response::None => Some(*unforced),
            Response::Series(c) => Some(add_response(unforced, &series_eval(c, s))),
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
                harmonic_amplitude: 0.0,
                harmonic_shift: 0.0,
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
        let ah = 2.0 * l.nu * vh + l.norm_kl * rh;
        let (amp, shift) = (l.harmonic_amplitude, l.harmonic_shift);
        // |Σ c_m s^m| and its derivatives, bounded term by term at s = hi (1-norms bound the
        // Euclidean ones).
        let norm = |c: &[f64]| math::abs(c[0]) + math::abs(c[1]);
        let (pr, pv, pa) = match &self.response {
            Response::None => (0.0, 0.0, 0.0),
            Response::Polynomial(b) => {
                let c = [b.b0x, b.b0y, b.b1x, b.b1y, b.b2x, b.b2y, b.b3x, b.b3y];
                polynomial_bounds(c.chunks_exact(2).map(norm), hi)
            }
            Response::Series(c) => {
                polynomial_bounds(c[..series_used(c)].iter().map(|c| norm(c)), hi)
            }
        };
        Bounds {
            radius: rh + amp + shift + pr,
            speed: vh + l.eta * amp + pv,
            accel: ah + l.eta * l.eta * amp + pa,
        }
    }
}
