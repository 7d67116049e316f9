//! The linearized contact segment (`model.md` §3, §5): exact solution of
//! q'' + 2νq' + Kl q = −Fd + F(cos θ, sin θ) + a0 + a1 s + a2 s² + a3 s³
//! from a state, in local time, for every case of `model.md` §6 (matrix-function homogeneous part).

use super::basis::{MatrixFunction, matrix_function};
use super::segment::{Bounds, Point, Segment, point_of};
use crate::coefficients::{self as coef, ContactModes, ContactParticular, LinearizedContact};
use crate::math;
use crate::params::{Params, State};

/// Everything fixed by the linearization point: Kl, Fd, modes, particular constants, phase.
#[derive(Clone, Copy, Debug)]
pub struct Linearization {
    /// Kl and Fd.
    pub kl: LinearizedContact,
    modes: ContactModes,
    particular: ContactParticular,
    nu: f64,
    eta: f64,
    phase0: (f64, f64),
    offset: (f64, f64),
    /// Frobenius norms of A = Kl − ν²I and of Kl (for bounds).
    norm_a: f64,
    norm_kl: f64,
}

/// Why a linearization cannot be used.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Singular;

impl Linearization {
    /// Linearize the contact force about position (x0, y0) for a segment starting at time `t0`
    /// (`model.md` §2–3, §5). Fails when Kl is singular or the forcing resonant (§6 cases 9–10).
    pub fn new(params: &Params, t0: f64, x0: f64, y0: f64) -> Result<Self, Singular> {
        let p = params;
        let t = coef::taylor_terms(x0, y0, p.offset_x, p.offset_y);
        let kl = coef::linearized_stiffness(
            p.k_xx, p.k_xy, p.k_yx, p.k_yy, t.a1, t.b1, t.b2, t.a2, t.d1, t.d2,
        );
        let nu = p.damping_ratio;
        let modes = coef::contact_modes(kl.fa1, kl.fb1, kl.fb2, kl.fa2, nu);
        let scale =
            1.0 + math::abs(kl.fa1) + math::abs(kl.fa2) + math::abs(kl.fb1) + math::abs(kl.fb2);
        if math::abs(modes.det) <= 1e-12 * scale * scale {
            return Err(Singular);
        }
        let particular = coef::contact_particular(
            kl.fa1,
            kl.fb1,
            kl.fb2,
            kl.fa2,
            kl.fd1,
            kl.fd2,
            nu,
            p.speed_ratio,
            p.forcing_amplitude(),
        );
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
            nu,
            eta: p.speed_ratio,
            phase0: (ct, st),
            offset: (p.offset_x, p.offset_y),
            norm_a,
            norm_kl,
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
        let c = &self.particular;
        let p = coef::contact_particular_eval(
            c.c11, c.c22, c.c33, c.c44, c.c55, c.c66, ct, st, self.eta,
        );
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
        let k = &self.kl;
        let response = if forcing.iter().all(|&a| a == 0.0) {
            Response::None
        } else if self.norm_kl * horizon * horizon <= 1.0 {
            Response::Series(series_response(k, self.nu, &forcing))
        } else {
            let [a0x, a0y, a1x, a1y, a2x, a2y, a3x, a3y] = forcing;
            let b = coef::polynomial_particular(
                k.fa1, k.fb1, k.fb2, k.fa2, self.nu, a0x, a0y, a1x, a1y, a2x, a2y, a3x, a3y,
            );
            Response::Polynomial([b.b0x, b.b0y, b.b1x, b.b1y, b.b2x, b.b2y, b.b3x, b.b3y])
        };
        let poly = match &response {
            Response::Polynomial(b) => *b,
            _ => [0.0; 8],
        };
        let p = self.particular_state(0.0);
        let start = coef::contact_homogeneous_start(
            state.x - p[0] - poly[0],
            state.y - p[1] - poly[1],
            state.vx - p[2] - poly[2],
            state.vy - p[3] - poly[3],
            self.nu,
        );
        LinearSegment {
            lin: *self,
            response,
            q0: [start.q0x, start.q0y],
            w0: [start.w0x, start.w0y],
        }
    }

    /// The matrix-function scalars and decay at local time `s` (shared by every segment of this
    /// linearization evaluated at the same `s`).
    pub fn scalars(&self, s: f64) -> (f64, MatrixFunction) {
        (
            math::exp(-self.nu * s),
            matrix_function(self.modes.gamma_sq_mean, self.modes.disc, s),
        )
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
    Polynomial([f64; 8]),
    /// The zero-state response as a Taylor polynomial Σ c_m s^m (x and y coefficients), from
    /// the equations of motion: c0 = c1 = 0 and
    /// (m + 2)(m + 1) c_{m+2} = a_m − 2ν(m + 1) c_{m+1} − Kl c_m (`model.md` §3).
    Series([[f64; 2]; SERIES_TERMS]),
}

fn series_response(k: &LinearizedContact, nu: f64, a: &[f64; 8]) -> [[f64; 2]; SERIES_TERMS] {
    let mut c = [[0.0; 2]; SERIES_TERMS];
    for m in 0..SERIES_TERMS - 2 {
        let (f0, f1) = if m < 4 {
            (a[2 * m], a[2 * m + 1])
        } else {
            (0.0, 0.0)
        };
        let d = ((m + 2) * (m + 1)) as f64;
        let damp = 2.0 * nu * (m + 1) as f64;
        let [cx, cy] = c[m];
        let [nx, ny] = c[m + 1];
        c[m + 2] = [
            (f0 - damp * nx - k.fa1 * cx - k.fb1 * cy) / d,
            (f1 - damp * ny - k.fb2 * cx - k.fa2 * cy) / d,
        ];
    }
    c
}

/// Position and velocity of a Taylor polynomial at s (Horner).
fn series_eval(c: &[[f64; 2]; SERIES_TERMS], s: f64) -> [f64; 4] {
    let (mut x, mut y, mut vx, mut vy) = (0.0, 0.0, 0.0, 0.0);
    for m in (0..SERIES_TERMS).rev() {
        x = x * s + c[m][0];
        y = y * s + c[m][1];
        if m > 0 {
            vx = vx * s + m as f64 * c[m][0];
            vy = vy * s + m as f64 * c[m][1];
        }
    }
    [x, y, vx, vy]
}

/// A linearized contact segment: [`Linearization`] plus initial state and cubic forcing.
#[derive(Clone, Copy, Debug)]
pub struct LinearSegment {
    lin: Linearization,
    response: Response,
    q0: [f64; 2],
    w0: [f64; 2],
}

impl LinearSegment {
    /// The state at `s` given precomputed scalars (see [`Linearization::scalars`]).
    pub fn state_with(&self, s: f64, scalars: &(f64, MatrixFunction)) -> State {
        let (decay, f) = scalars;
        let l = &self.lin;
        let k = &l.kl;
        let h = coef::contact_homogeneous_eval(
            k.fa1,
            k.fb1,
            k.fb2,
            k.fa2,
            l.modes.omega_sq_mean,
            l.nu,
            self.q0[0],
            self.q0[1],
            self.w0[0],
            self.w0[1],
            *decay,
            f.cc,
            f.cd,
            f.sc,
            f.sd,
        );
        let p = l.particular_state(s);
        let q = match &self.response {
            Response::None => [0.0; 4],
            Response::Polynomial(b) => {
                let q = coef::polynomial_eval(b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7], s);
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

    /// The linearization this segment belongs to.
    pub fn linearization(&self) -> &Linearization {
        &self.lin
    }
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
        let q0 = math::hypot(self.q0[0], self.q0[1]);
        let w0 = math::hypot(self.w0[0], self.w0[1]);
        let rh = decay * ch * (q0 + hi * w0);
        let vh = l.nu * rh + decay * ch * (l.norm_a * hi * q0 + w0);
        let ah = 2.0 * l.nu * vh + l.norm_kl * rh;
        let c = &l.particular;
        let amp = math::sqrt(c.c11 * c.c11 + c.c22 * c.c22 + c.c33 * c.c33 + c.c44 * c.c44);
        let shift = math::hypot(c.c55 - l.offset.0, c.c66 - l.offset.1);
        // |Σ c_m s^m| and its derivatives, bounded term by term at s = hi (1-norms bound the
        // Euclidean ones).
        let (mut pr, mut pv, mut pa) = (0.0, 0.0, 0.0);
        let mut add = |coefficients: &mut dyn Iterator<Item = f64>| {
            // p2 = hi^(m−2), p1 = hi^(m−1), p0 = hi^m.
            let (mut p2, mut p1, mut p0) = (0.0, 0.0, 1.0);
            for (m, norm) in coefficients.enumerate() {
                let mf = m as f64;
                pr += norm * p0;
                pv += mf * norm * p1;
                pa += mf * (mf - 1.0) * norm * p2;
                (p2, p1, p0) = (if m == 0 { 1.0 } else { p1 }, p0, p0 * hi);
            }
        };
        match &self.response {
            Response::None => {}
            Response::Polynomial(b) => {
                add(&mut b.chunks_exact(2).map(|c| math::abs(c[0]) + math::abs(c[1])));
            }
            Response::Series(c) => {
                add(&mut c.iter().map(|c| math::abs(c[0]) + math::abs(c[1])));
            }
        }
        Bounds {
            radius: rh + amp + shift + pr,
            speed: vh + l.eta * amp + pv,
            accel: ah + l.eta * l.eta * amp + pa,
        }
    }
}
