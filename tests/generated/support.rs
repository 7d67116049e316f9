//! Independent reference computations for the generated-formula tests: the contact function and
//! its finite-difference Jacobian, nalgebra solves, matrix exponentials of the equations of
//! motion written as first-order linear systems, and finite-difference ODE residuals.

#![allow(dead_code)]

use nalgebra::{Matrix2, SMatrix, SVector, Vector2};
use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed};
use rotor_rub::analytic::linear::Linearization;
use rotor_rub::analytic::segment::Segment;
use rotor_rub::coefficients::{
    self as coef, CubicForcing, LinearizedContact, ModelParams, Position, TaylorTerms,
};
use rotor_rub::{Params, State};

/// Proptest configuration: `cases` cases, no regression files written into the source tree.
/// The seed is fixed (reproducible runs) unless `PROPTEST_RNG_SEED` is set to explore others.
pub fn config(cases: u32) -> Config {
    let mut c = Config {
        cases,
        failure_persistence: None,
        ..Config::default()
    };
    if std::env::var_os("PROPTEST_RNG_SEED").is_none() {
        c.rng_seed = RngSeed::Fixed(0x5EED_0DDB);
    }
    c
}

/// One random physical situation: parameters, a linearization point and a segment start.
#[derive(Clone, Copy, Debug)]
pub struct Case {
    pub nu: f64,
    pub eta: f64,
    pub f: f64,
    /// K_s = [[kxx, kxy], [kyx, kyy]].
    pub k: [[f64; 2]; 2],
    pub offset: (f64, f64),
    pub phase: f64,
    /// Absolute time of the segment start.
    pub t0: f64,
    /// Linearization point.
    pub x0: f64,
    pub y0: f64,
}

impl Case {
    /// The runtime parameters. F = η_m ρ η² is produced with η_m = 1, ρ = F/η².
    pub fn params(&self) -> Params {
        Params {
            speed_ratio: self.eta,
            damping_ratio: self.nu,
            mass_ratio: 1.0,
            eccentricity_ratio: self.f / (self.eta * self.eta),
            phase: self.phase,
            k_xx: self.k[0][0],
            k_xy: self.k[0][1],
            k_yx: self.k[1][0],
            k_yy: self.k[1][1],
            offset_x: self.offset.0,
            offset_y: self.offset.1,
            ..Params::DEFAULT
        }
    }

    /// F exactly as the runtime computes it.
    pub fn forcing(&self) -> f64 {
        self.params().mass_ratio
            * self.params().eccentricity_ratio
            * self.params().speed_ratio
            * self.params().speed_ratio
    }

    pub fn ks(&self) -> Matrix2<f64> {
        Matrix2::new(self.k[0][0], self.k[0][1], self.k[1][0], self.k[1][1])
    }

    /// The generated code's parameter struct for this case.
    pub fn model(&self) -> ModelParams {
        ModelParams::of(&self.params())
    }

    pub fn taylor(&self) -> TaylorTerms {
        let at = Position {
            x: self.x0,
            y: self.y0,
        };
        coef::taylor_terms(&self.model(), &at)
    }

    pub fn linearized(&self) -> LinearizedContact {
        coef::linearized_stiffness(&self.model(), &self.taylor())
    }

    /// The linearization point at distance `z0` from the stator centre, direction `angle`.
    pub fn at(mut self, z0: f64, angle: f64) -> Self {
        self.x0 = self.offset.0 + z0 * angle.cos();
        self.y0 = self.offset.1 + z0 * angle.sin();
        self
    }

    /// The forcing phase θ at local time s.
    pub fn theta(&self, s: f64) -> f64 {
        self.eta * (self.t0 + s) + self.phase
    }
}

prop_compose! {
    /// Random parameters in the ranges of the brief; z0 ∈ [0.5, 3] and any direction.
    pub fn any_case()(
        nu in 0.05..1.5f64,
        eta in 0.2..5.0f64,
        f in 0.01..2.0f64,
        kxx in 0.0..60.0f64,
        kyy in 0.0..60.0f64,
        kxy in -30.0..30.0f64,
        kyx in -30.0..30.0f64,
        ex in -0.5..0.5f64,
        ey in -0.5..0.5f64,
        phase in 0.0..std::f64::consts::TAU,
        t0 in 0.0..20.0f64,
        z0 in 0.5..3.0f64,
        angle in 0.0..std::f64::consts::TAU,
    ) -> Case {
        Case { nu, eta, f, k: [[kxx, kxy], [kyx, kyy]], offset: (ex, ey), phase, t0, x0: 0.0, y0: 0.0 }
            .at(z0, angle)
    }
}

prop_compose! {
    /// A start state near the linearization point.
    pub fn start_near(x0: f64, y0: f64)(
        dx in -0.3..0.3f64, dy in -0.3..0.3f64, vx in -2.0..2.0f64, vy in -2.0..2.0f64,
    ) -> State {
        State::new(x0 + dx, y0 + dy, vx, vy)
    }
}

/// A random cubic forcing [a0x, a0y, a1x, a1y, a2x, a2y, a3x, a3y].
pub fn any_cubic() -> impl Strategy<Value = [f64; 8]> {
    proptest::array::uniform8(-3.0..3.0f64)
}

/// The contact function g(x, y) = (1 − 1/z)(x − εx, y − εy) (`docs/MODEL.md` §1).
pub fn g(x: f64, y: f64, ex: f64, ey: f64) -> Vector2<f64> {
    let (u, v) = (x - ex, y - ey);
    let z = (u * u + v * v).sqrt();
    Vector2::new((1.0 - 1.0 / z) * u, (1.0 - 1.0 / z) * v)
}

/// Central-difference Jacobian of a map R² → R² at (x, y) with step `h`.
pub fn jacobian(f: impl Fn(f64, f64) -> Vector2<f64>, x: f64, y: f64, h: f64) -> Matrix2<f64> {
    let dx = (f(x + h, y) - f(x - h, y)) / (2.0 * h);
    let dy = (f(x, y + h) - f(x, y - h)) / (2.0 * h);
    Matrix2::from_columns(&[dx, dy])
}

/// The real 4×4 system of the harmonic ansatz x = c11 cos θ + c22 sin θ (+ c55),
/// y = c33 cos θ + c44 sin θ (+ c66) in q'' + 2νq' + Kl q + Fd = F (cos θ, sin θ):
/// with θ' = η, x'' = −η² x_harm, x' = η(−c11 sin θ + c22 cos θ). Collecting cos θ and sin θ in
/// each equation, for the unknowns (c11, c22, c33, c44):
///
/// ```text
/// x, cos θ:  (Fa1 − η²) c11 + 2νη c22 + Fb1 c33                 = F
/// x, sin θ:  −2νη c11 + (Fa1 − η²) c22           + Fb1 c44       = 0
/// y, cos θ:  Fb2 c11              + (Fa2 − η²) c33 + 2νη c44     = 0
/// y, sin θ:            Fb2 c22    − 2νη c33 + (Fa2 − η²) c44     = F
/// ```
///
/// and the constants solve Kl (c55, c66) = −Fd.
pub fn harmonic_system(
    kl: &Matrix2<f64>,
    nu: f64,
    eta: f64,
    f: f64,
) -> (SMatrix<f64, 4, 4>, SVector<f64, 4>) {
    let (a11, a12, a21, a22) = (
        kl[(0, 0)] - eta * eta,
        kl[(0, 1)],
        kl[(1, 0)],
        kl[(1, 1)] - eta * eta,
    );
    let p = 2.0 * nu * eta;
    #[rustfmt::skip]
    let m = SMatrix::<f64, 4, 4>::new(
        a11,  p,   a12, 0.0,
        -p,   a11, 0.0, a12,
        a21,  0.0, a22, p,
        0.0,  a21, -p,  a22,
    );
    (m, SVector::<f64, 4>::new(f, 0.0, 0.0, f))
}

/// Kl as a matrix from the generated struct (corrected layout [[Fa1, Fb1], [Fb2, Fa2]]).
pub fn kl_matrix(k: &LinearizedContact) -> Matrix2<f64> {
    Matrix2::new(k.fa1, k.fb1, k.fb2, k.fa2)
}

/// 1-norm condition number of a square matrix (∞ when singular).
pub fn cond<const N: usize>(m: &SMatrix<f64, N, N>) -> f64 {
    match m.try_inverse() {
        Some(inv) => m.abs().column_sum().max() * inv.abs().column_sum().max(),
        None => f64::INFINITY,
    }
}

/// The linearized contact equations, with the cubic forcing, as a 10-dimensional linear system
/// w' = M w in w = (x, y, x', y', cos θ, sin θ, 1, s, s², s³): cos θ and sin θ rotate at η, the
/// monomials satisfy (sᵏ)' = k sᵏ⁻¹, and
///
/// ```text
/// x'' = −2νx' − Fa1 x − Fb1 y − Fd1 + F cos θ + a0x + a1x s + a2x s² + a3x s³
/// y'' = −2νy' − Fb2 x − Fa2 y − Fd2 + F sin θ + a0y + a1y s + a2y s² + a3y s³
/// ```
///
/// Its exponential gives the exact solution with no reference to the closed forms.
pub fn contact_system(
    k: &LinearizedContact,
    nu: f64,
    eta: f64,
    f: f64,
    a: &[f64; 8],
) -> SMatrix<f64, 10, 10> {
    let mut m = SMatrix::<f64, 10, 10>::zeros();
    m[(0, 2)] = 1.0;
    m[(1, 3)] = 1.0;
    m[(2, 0)] = -k.fa1;
    m[(2, 1)] = -k.fb1;
    m[(3, 0)] = -k.fb2;
    m[(3, 1)] = -k.fa2;
    m[(2, 2)] = -2.0 * nu;
    m[(3, 3)] = -2.0 * nu;
    m[(2, 4)] = f;
    m[(3, 5)] = f;
    m[(2, 6)] = a[0] - k.fd1;
    m[(3, 6)] = a[1] - k.fd2;
    for j in 1..4 {
        m[(2, 6 + j)] = a[2 * j];
        m[(3, 6 + j)] = a[2 * j + 1];
    }
    m[(4, 5)] = -eta;
    m[(5, 4)] = eta;
    m[(7, 6)] = 1.0;
    m[(8, 7)] = 2.0;
    m[(9, 8)] = 3.0;
    m
}

/// The free equations (Kl = I, Fd = 0, no cubic forcing) in the same form.
pub fn free_system(nu: f64, eta: f64, f: f64) -> SMatrix<f64, 10, 10> {
    let free = LinearizedContact {
        fa1: 1.0,
        fb1: 0.0,
        fb2: 0.0,
        fa2: 1.0,
        fd1: 0.0,
        fd2: 0.0,
    };
    contact_system(&free, nu, eta, f, &[0.0; 8])
}

/// The augmented start vector for a state at forcing phase θ0.
pub fn augmented(state: &State, theta0: f64) -> SVector<f64, 10> {
    let mut w = SVector::<f64, 10>::zeros();
    w[0] = state.x;
    w[1] = state.y;
    w[2] = state.vx;
    w[3] = state.vy;
    w[4] = theta0.cos();
    w[5] = theta0.sin();
    w[6] = 1.0;
    w
}

/// The exact state at local time s: exp(M s) w0 (Padé scaling and squaring, relative accuracy
/// ≈ 1e-14·‖exp(|M| s)‖).
pub fn propagate(m: &SMatrix<f64, 10, 10>, w0: &SVector<f64, 10>, s: f64) -> State {
    let w = (m * s).exp() * w0;
    State::new(w[0], w[1], w[2], w[3])
}

/// Eighth-order central difference d/ds of `f` at s with step h (truncation h⁸|f⁽⁹⁾|/630).
pub fn d_ds(f: impl Fn(f64) -> f64, s: f64, h: f64) -> f64 {
    const W: [f64; 4] = [4.0 / 5.0, -1.0 / 5.0, 4.0 / 105.0, -1.0 / 280.0];
    let mut acc = 0.0;
    for (k, w) in W.iter().enumerate() {
        let d = (k + 1) as f64 * h;
        acc += w * (f(s + d) - f(s - d));
    }
    acc / h
}

/// Eighth-order central difference d²/ds² of `f` at s with step h.
pub fn d2_ds2(f: impl Fn(f64) -> f64, s: f64, h: f64) -> f64 {
    const W: [f64; 4] = [8.0 / 5.0, -1.0 / 5.0, 8.0 / 315.0, -1.0 / 560.0];
    let mut acc = -205.0 / 72.0 * f(s);
    for (k, w) in W.iter().enumerate() {
        let d = (k + 1) as f64 * h;
        acc += w * (f(s + d) + f(s - d));
    }
    acc / (h * h)
}

/// A finite-difference step for a trajectory whose fastest rate is `rate` (frequency or
/// exponential rate): h·rate = 0.2 keeps the eighth-order truncation near (0.2)⁸/630 ≈ 4e-9 of
/// the acceleration while rounding stays ≈ 1e-15·|v|/h.
pub fn fd_step(rate: f64) -> f64 {
    (0.08 / rate.max(1.0)).min(0.02)
}

/// Local times (inside [0, 1]) at which residuals are evaluated: far enough from 0 that an
/// eighth-order stencil with h ≤ 0.02 stays at s ≥ 0.
pub const SAMPLE_TIMES: [f64; 5] = [0.1, 0.3, 0.5, 0.7, 0.9];

/// The largest rate present in the linearized contact motion: √|ω²| of Kl's eigenvalues, the
/// damping, the forcing frequency, and growth rates of over-damped modes.
pub fn contact_rate(k: &LinearizedContact, nu: f64, eta: f64) -> f64 {
    let kl = kl_matrix(k);
    let eig = kl.complex_eigenvalues();
    let mut r = eta.max(nu).max(1.0);
    for l in eig.iter() {
        // λ = −ν ± √(ν² − ω²): its modulus bounds the rate.
        let disc = nalgebra::Complex::new(nu * nu, 0.0) - l;
        r = r.max(nu + disc.norm().sqrt());
    }
    r
}

/// Result of checking a contact segment: the largest residuals seen, each relative to its scale.
#[derive(Clone, Copy, Debug, Default)]
pub struct SegmentCheck {
    /// |state(0) − start| / (1 + |start|).
    pub initial: f64,
    /// ODE residual / forcing scale (F + |Fd| + |a(s)|).
    pub residual_forcing: f64,
    /// ODE residual / magnitude of the equation's terms (|q''| + 2ν|q'| + ‖Kl‖|q| + forcing scale).
    pub residual_terms: f64,
    /// |x' − d x/ds| / (|x'| + rate·|x|): velocity consistent with position.
    pub velocity: f64,
    /// |state(s) − exp(M s) w0| / (1 + |exp(M s) w0|), against the augmented linear system.
    pub expm: f64,
    /// Cancellation factor 1 + (Σ|c_ij| + Σ|b_k|)/(1 + |start|): the particular solutions'
    /// size relative to the start state. The closed form is particular + homogeneous, the
    /// homogeneous part starts at (start − particular), so rounding errors scale with this. The
    /// polynomial particular coefficients b_k grow like det(Kl)^−(k+1) when Kl is nearly
    /// singular and dominate it there.
    pub cancellation: f64,
    /// Growth max_s (1 + |state(s)|)/(1 + |start|) (over-damped, flutter and z0 < 1 modes grow;
    /// finite-difference rounding grows with the state).
    pub growth: f64,
}

fn norm4(s: &State) -> f64 {
    (s.x * s.x + s.y * s.y + s.vx * s.vx + s.vy * s.vy).sqrt()
}

/// |got − exact| / (1 + |exact|) over the four state components.
pub fn relative_error(got: &State, exact: &State) -> f64 {
    let d = State::new(
        got.x - exact.x,
        got.y - exact.y,
        got.vx - exact.vx,
        got.vy - exact.vy,
    );
    norm4(&d) / (1.0 + norm4(exact))
}

/// Check `Linearization::new(case).segment(state, a, horizon)` at [`SAMPLE_TIMES`]·horizon (the
/// stencil step is ≤ 0.02·horizon so it stays inside [0, horizon]): initial state, ODE residual by finite differences of the
/// segment's own velocity, velocity against the position's derivative, and the exact solution
/// of the augmented linear system.
pub fn check_contact_segment(case: &Case, state: State, a: [f64; 8], horizon: f64) -> SegmentCheck {
    let p = case.params();
    let lin = Linearization::new(&p, case.t0, case.x0, case.y0).expect("regular linearization");
    let seg = lin.segment(state, a, horizon);
    let k = lin.kl;
    let (nu, eta, f) = (case.nu, case.eta, case.forcing());
    let mut out = SegmentCheck {
        growth: 1.0,
        ..SegmentCheck::default()
    };
    // Magnitudes that cancel in the closed form: the particular solution (harmonic and constant)
    // and, when the runtime uses it (`Linearization::segment`: non-zero forcing and
    // ‖Kl‖_F·horizon² > 1), the polynomial particular solution.
    let c = coef::contact_particular(&model(nu, eta, f), &k);
    let mut big = c.c11.abs() + c.c22.abs() + c.c33.abs() + c.c44.abs() + c.c55.abs() + c.c66.abs();
    if a.iter().any(|&v| v != 0.0) && kl_matrix(&k).norm() * horizon * horizon > 1.0 {
        let b = coef::polynomial_particular(&model(nu, eta, f), &k, &cubic(&a));
        big += [b.b0x, b.b0y, b.b1x, b.b1y, b.b2x, b.b2y, b.b3x, b.b3y]
            .iter()
            .map(|v| v.abs())
            .sum::<f64>();
    }
    out.cancellation = 1.0 + big / (1.0 + norm4(&state));
    let s0 = seg.point(0.0).state;
    let d = State::new(
        s0.x - state.x,
        s0.y - state.y,
        s0.vx - state.vx,
        s0.vy - state.vy,
    );
    out.initial = norm4(&d) / (1.0 + norm4(&state));
    let rate = contact_rate(&k, nu, eta);
    let h = fd_step(rate).min(0.02 * horizon);
    let sys = contact_system(&k, nu, eta, f, &a);
    let w0 = augmented(&state, case.theta(0.0));
    let poly = |s: f64, i: usize| a[i] + a[2 + i] * s + a[4 + i] * s * s + a[6 + i] * s * s * s;
    for &s in SAMPLE_TIMES
        .iter()
        .map(|t| t * horizon)
        .collect::<Vec<_>>()
        .iter()
    {
        let q = seg.point(s).state;
        out.growth = out.growth.max((1.0 + norm4(&q)) / (1.0 + norm4(&state)));
        let ax = d_ds(|t| seg.point(t).state.vx, s, h);
        let ay = d_ds(|t| seg.point(t).state.vy, s, h);
        let th = case.theta(s);
        let rx =
            ax + 2.0 * nu * q.vx + k.fa1 * q.x + k.fb1 * q.y + k.fd1 - f * th.cos() - poly(s, 0);
        let ry =
            ay + 2.0 * nu * q.vy + k.fb2 * q.x + k.fa2 * q.y + k.fd2 - f * th.sin() - poly(s, 1);
        let res = rx.hypot(ry);
        let forcing = f + k.fd1.hypot(k.fd2) + poly(s, 0).hypot(poly(s, 1));
        let norm_kl = kl_matrix(&k).norm();
        let terms = ax.hypot(ay) + 2.0 * nu * q.vx.hypot(q.vy) + norm_kl * q.x.hypot(q.y) + forcing;
        out.residual_forcing = out.residual_forcing.max(res / forcing);
        out.residual_terms = out.residual_terms.max(res / terms);
        let vx = d_ds(|t| seg.point(t).state.x, s, h);
        let vy = d_ds(|t| seg.point(t).state.y, s, h);
        let vscale = q.vx.hypot(q.vy) + rate * q.x.hypot(q.y);
        out.velocity = out.velocity.max((vx - q.vx).hypot(vy - q.vy) / vscale);
        let exact = propagate(&sys, &w0, s);
        out.expm = out.expm.max(relative_error(&q, &exact));
    }
    out
}

/// Same checks for a free-flight segment (`FreeSegment`), against x'' + 2νx' + x = F cos θ.
pub fn check_free_segment(case: &Case, state: State) -> SegmentCheck {
    use rotor_rub::analytic::free::{FreeConstants, FreeSegment};
    let p = case.params();
    let seg = FreeSegment::new(&p, &FreeConstants::new(&p), case.t0, state);
    let (nu, eta, f) = (case.nu, case.eta, case.forcing());
    let mut out = SegmentCheck {
        growth: 1.0,
        cancellation: 1.0,
        ..SegmentCheck::default()
    };
    let pt0 = seg.point(0.0);
    let s0 = pt0.state;
    let d = State::new(
        s0.x - state.x,
        s0.y - state.y,
        s0.vx - state.vx,
        s0.vy - state.vy,
    );
    out.initial = norm4(&d) / (1.0 + norm4(&state));
    let rate = 1.0 + 2.0 * nu + eta;
    let h = fd_step(rate);
    let sys = free_system(nu, eta, f);
    let w0 = augmented(&state, case.theta(0.0));
    for &s in &SAMPLE_TIMES {
        let pt = seg.point(s);
        let q = pt.state;
        // h = z² − 1 and h' = 2(u x' + v y') from the same evaluation.
        let (u, v) = (q.x - case.offset.0, q.y - case.offset.1);
        assert!((pt.h - (u * u + v * v - 1.0)).abs() <= 1e-12 * (1.0 + u * u + v * v));
        assert!(
            (pt.dh - 2.0 * (u * q.vx + v * q.vy)).abs()
                <= 1e-12 * (1.0 + (u.hypot(v) * q.vx.hypot(q.vy)))
        );
        let ax = d_ds(|t| seg.point(t).state.vx, s, h);
        let ay = d_ds(|t| seg.point(t).state.vy, s, h);
        let th = case.theta(s);
        let rx = ax + 2.0 * nu * q.vx + q.x - f * th.cos();
        let ry = ay + 2.0 * nu * q.vy + q.y - f * th.sin();
        let res = rx.hypot(ry);
        out.residual_forcing = out.residual_forcing.max(res / f);
        let terms = ax.hypot(ay) + 2.0 * nu * q.vx.hypot(q.vy) + q.x.hypot(q.y) + f;
        out.residual_terms = out.residual_terms.max(res / terms);
        let vx = d_ds(|t| seg.point(t).state.x, s, h);
        let vy = d_ds(|t| seg.point(t).state.y, s, h);
        let vscale = q.vx.hypot(q.vy) + rate * q.x.hypot(q.y);
        out.velocity = out.velocity.max((vx - q.vx).hypot(vy - q.vy) / vscale);
        let exact = propagate(&sys, &w0, s);
        let diff = State::new(
            q.x - exact.x,
            q.y - exact.y,
            q.vx - exact.vx,
            q.vy - exact.vy,
        );
        out.expm = out.expm.max(norm4(&diff) / (1.0 + norm4(&exact)));
    }
    out
}

/// The generated code's parameter struct with ν, η, F (the formulas using only these).
pub fn model(nu: f64, eta: f64, f: f64) -> ModelParams {
    ModelParams {
        damping_ratio: nu,
        speed_ratio: eta,
        unbalance_force: f,
        ..ModelParams::default()
    }
}

/// A cubic forcing `[a0x, a0y, a1x, a1y, a2x, a2y, a3x, a3y]` as the generated struct.
pub fn cubic(a: &[f64; 8]) -> CubicForcing {
    let [a0x, a0y, a1x, a1y, a2x, a2y, a3x, a3y] = *a;
    CubicForcing {
        a0x,
        a0y,
        a1x,
        a1y,
        a2x,
        a2y,
        a3x,
        a3y,
    }
}
