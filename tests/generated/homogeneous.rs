//! Homogeneous solutions: `contact_homogeneous_start` + `contact_homogeneous_eval` with the
//! runtime's `matrix_function`, and `free_homogeneous` + `free_eval` with `free_basis`
//! (`docs/MODEL.md` §4, §5), against the matrix exponential of the first-order system.

use proptest::prelude::*;
use rotor_rub::State;
use rotor_rub::analytic::basis::{free_basis, matrix_function};
use rotor_rub::coefficients::{self as coef, LinearizedContact};

use crate::support::*;

fn norm4(s: &State) -> f64 {
    (s.x * s.x + s.y * s.y + s.vx * s.vx + s.vy * s.vy).sqrt()
}

/// The homogeneous contact solution from the generated start and evaluation formulas at local
/// time `s` (σ = mean of Kl's eigenvalues, so B = Kl − σI is the trace-free part used by
/// `matrix_function`).
pub fn homogeneous_at(l: &LinearizedContact, nu: f64, init: [f64; 4], s: f64) -> State {
    let model = crate::support::model(nu, 0.0, 0.0);
    let m = coef::contact_modes(&model, l);
    let [xh0, yh0, vxh0, vyh0] = init;
    let initial = coef::HomogeneousInitial {
        xh0,
        yh0,
        vxh0,
        vyh0,
    };
    let st = coef::contact_homogeneous_start(&model, &initial);
    let f = matrix_function(m.gamma_sq_mean, m.disc, s);
    let basis = coef::ContactBasis {
        decay: (-nu * s).exp(),
        cc: f.cc,
        cd: f.cd,
        sc: f.sc,
        sd: f.sd,
    };
    let h = coef::contact_homogeneous_eval(&model, l, &m, &st, &basis);
    State::new(h.x, h.y, h.vx, h.vy)
}

/// Largest |closed form − exp(M s) q0| / (1 + |exp(M s) q0|) over [`SAMPLE_TIMES`], and the
/// error at s = 0 relative to 1 + |q0|.
pub fn homogeneous_errors(l: &LinearizedContact, nu: f64, init: [f64; 4]) -> (f64, f64) {
    let start = State::new(init[0], init[1], init[2], init[3]);
    let at0 = homogeneous_at(l, nu, init, 0.0);
    let d0 = State::new(
        at0.x - start.x,
        at0.y - start.y,
        at0.vx - start.vx,
        at0.vy - start.vy,
    );
    let initial = norm4(&d0) / (1.0 + norm4(&start));
    let free_of_forcing = LinearizedContact {
        fd1: 0.0,
        fd2: 0.0,
        ..*l
    };
    let sys = contact_system(&free_of_forcing, nu, 1.0, 0.0, &[0.0; 8]);
    let w0 = augmented(&start, 0.0);
    let mut worst: f64 = 0.0;
    for &s in &SAMPLE_TIMES {
        let got = homogeneous_at(l, nu, init, s);
        let want = propagate(&sys, &w0, s);
        let d = State::new(
            got.x - want.x,
            got.y - want.y,
            got.vx - want.vx,
            got.vy - want.vy,
        );
        worst = worst.max(norm4(&d) / (1.0 + norm4(&want)));
    }
    (initial, worst)
}

proptest! {
    #![proptest_config(config(256))]

    /// For any Kl of the random ensemble (real, complex, negative, near-repeated ω²): the start
    /// state is reproduced at s = 0 (rel. 1e-14: C = I, S = 0, only a few roundings), and the
    /// solution matches exp(M s) of the 4×4 first-order system to rel. 1e-10 (measured ≤ 1.4e-13
    /// over 8000 cases, but up to ≈ 1e-11 when Δ is slightly negative — see
    /// `bug_matrix_function_complex_pair_near_double_root`;
    /// expm's own error is ≈ 1e-14·‖exp(|M|s)‖, and `matrix_function`'s confluent branch, used
    /// when √|Δ| ≤ 1e-5(1 + |γ̄²|), truncates at O(Δ) ≲ 1e-10 relative).
    #[test]
    fn contact_homogeneous_matches_matrix_exponential(
        case in any_case(),
        init in proptest::array::uniform4(-2.0..2.0f64),
    ) {
        let l = case.linearized();
        let (initial, worst) = homogeneous_errors(&l, case.nu, init);
        prop_assert!(initial <= 1e-14, "initial error {initial:e}");
        prop_assert!(worst <= 1e-10, "error vs expm {worst:e}");
    }

    /// Free flight from the generated formulas directly: free_particular, free_homogeneous,
    /// free_basis, free_eval. The start state is reproduced at s = 0, h = z² − 1 and
    /// h' = 2(u x' + v y') are consistent with the state, and the state matches exp(M s) of the
    /// forced free system (6 states with the forcing phasor; rel. 1e-11, measured ≲ 1e-15).
    #[test]
    fn free_homogeneous_and_eval_match_matrix_exponential(
        case in any_case(),
        state in proptest::array::uniform4(-2.0..2.0f64),
    ) {
        check_free_formulas(&case, State::new(state[0], state[1], state[2], state[3]))?;
    }

    /// The stepper's free map from the generated step formulas: Φ(s)·w0 + G(s)·(cos θ0,
    /// sin θ0) with `free_step_transition`, `free_step_forcing` (basis from `free_basis`,
    /// rotation (cos ηs, sin ηs)) matches exp(M s) of the forced free system (rel. 1e-11, as
    /// the closed form it is simplified from); Φ(0) = I exactly, G(0) = 0 to rounding.
    #[test]
    fn free_step_formulas_match_matrix_exponential(
        case in any_case(),
        state in proptest::array::uniform4(-2.0..2.0f64),
    ) {
        check_free_step(&case, State::new(state[0], state[1], state[2], state[3]))?;
    }
}

/// See [`free_step_formulas_match_matrix_exponential`].
pub fn check_free_step(case: &Case, start: State) -> Result<(), TestCaseError> {
    let model = case.model();
    let p = coef::free_particular(&model);
    let beta = coef::free_damped_frequency_sq(&model);
    let th0 = case.theta(0.0);
    let (c0, s0) = (th0.cos(), th0.sin());
    let map = |s: f64| {
        let (ec, es) = free_basis(case.nu, beta.beta_sq, s);
        let basis = coef::FreeBasis { ec, es };
        let rotation = coef::ForcingRotation {
            ce: (case.eta * s).cos(),
            se: (case.eta * s).sin(),
        };
        let phi = coef::free_step_transition(&model, &beta, &basis);
        let g = coef::free_step_forcing(&model, &p, &beta, &basis, &rotation);
        let phi = [
            [phi.p00, phi.p01, phi.p02, phi.p03],
            [phi.p10, phi.p11, phi.p12, phi.p13],
            [phi.p20, phi.p21, phi.p22, phi.p23],
            [phi.p30, phi.p31, phi.p32, phi.p33],
        ];
        let g = [
            [g.g00, g.g01],
            [g.g10, g.g11],
            [g.g20, g.g21],
            [g.g30, g.g31],
        ];
        (phi, g)
    };
    let (phi0, g0) = map(0.0);
    for (i, (row, grow)) in phi0.iter().zip(&g0).enumerate() {
        for (j, &v) in row.iter().enumerate() {
            prop_assert_eq!(v, if i == j { 1.0 } else { 0.0 }, "Φ(0)[{}][{}]", i, j);
        }
        // G(0) is zero up to the rounding of the particular solution's cancellation.
        let scale = (1.0 + case.eta) * (p.c11.abs() + p.c22.abs() + p.c33.abs() + p.c44.abs());
        prop_assert!(
            grow[0].abs().max(grow[1].abs()) <= 8.0 * f64::EPSILON * scale,
            "G(0) row {i}: {grow:?}"
        );
    }
    let sys = free_system(case.nu, case.eta, case.forcing());
    let w0 = augmented(&start, th0);
    let a = start.to_array();
    for &s in &SAMPLE_TIMES {
        let (phi, g) = map(s);
        let mut end = [0.0; 4];
        for (e, (row, grow)) in end.iter_mut().zip(phi.iter().zip(&g)) {
            *e = row.iter().zip(&a).map(|(m, w)| m * w).sum::<f64>() + grow[0] * c0 + grow[1] * s0;
        }
        let end = State::new(end[0], end[1], end[2], end[3]);
        let want = propagate(&sys, &w0, s);
        let err = relative_error(&end, &want);
        prop_assert!(err <= 1e-11, "s = {s}: {end:?} vs exact {want:?} ({err:e})");
    }
    Ok(())
}

/// See [`free_homogeneous_and_eval_match_matrix_exponential`].
pub fn check_free_formulas(case: &Case, start: State) -> Result<(), TestCaseError> {
    let (nu, eta, f) = (case.nu, case.eta, case.forcing());
    let model = case.model();
    let p = coef::free_particular(&model);
    let beta = coef::free_damped_frequency_sq(&model);
    let beta_sq = beta.beta_sq;
    let th0 = case.theta(0.0);
    let phasor0 = coef::Phasor {
        ct: th0.cos(),
        st: th0.sin(),
    };
    let h = coef::free_homogeneous(&model, &start.into(), &phasor0, &p);
    let _ = (nu, eta, f);
    let eval = |s: f64| {
        let (ec, es) = free_basis(nu, beta_sq, s);
        let th = case.theta(s);
        let phasor = coef::Phasor {
            ct: th.cos(),
            st: th.sin(),
        };
        coef::free_eval(&model, &phasor, &p, &beta, &h, &coef::FreeBasis { ec, es })
    };
    let scale0 = 1.0 + norm4(&start) + p.c11.abs() + p.c22.abs();
    let e0 = eval(0.0);
    let d0 = State::new(
        e0.x - start.x,
        e0.y - start.y,
        e0.vx - start.vx,
        e0.vy - start.vy,
    );
    prop_assert!(
        norm4(&d0) <= 1e-14 * scale0 * (1.0 + eta),
        "start not reproduced: {e0:?} vs {start:?}"
    );
    let sys = free_system(nu, eta, f);
    let w0 = augmented(&start, th0);
    for &s in &SAMPLE_TIMES {
        let e = eval(s);
        let (u, v) = (e.x - case.offset.0, e.y - case.offset.1);
        prop_assert!((e.h - (u * u + v * v - 1.0)).abs() <= 1e-13 * (1.0 + u * u + v * v));
        prop_assert!(
            (e.dh - 2.0 * (u * e.vx + v * e.vy)).abs()
                <= 1e-13 * (1.0 + u.hypot(v) * e.vx.hypot(e.vy))
        );
        let want = propagate(&sys, &w0, s);
        let d = State::new(e.x - want.x, e.y - want.y, e.vx - want.vx, e.vy - want.vy);
        let err = norm4(&d) / (1.0 + norm4(&want));
        prop_assert!(err <= 1e-11, "s = {s}: {e:?} vs exact {want:?} ({err:e})");
    }
    Ok(())
}

/// ν < 1, ν = 1 exactly (β = 0: the series branch of `free_basis` for every s), ν > 1
/// (β² < 0: cosh/sinh), through the generated formulas and through `FreeSegment`: start
/// reproduced, ODE residual by finite differences ≤ 1e-9 of the forcing F (no growth in free
/// flight, so the forcing scale bounds the terms), agreement with expm.
#[test]
fn free_flight_in_every_damping_regime() {
    for nu in [0.05, 0.3, 0.999, 1.0, 1.001, 1.3, 1.5, 3.0] {
        for (eta, f) in [(0.7, 0.4), (1.0, 0.02), (2.5, 1.7)] {
            let case = Case {
                nu,
                eta,
                f,
                k: [[0.0; 2]; 2],
                offset: (0.3, -0.2),
                phase: 0.4,
                t0: 3.0,
                x0: 0.0,
                y0: 0.0,
            };
            let start = State::new(0.2, -0.7, 1.3, 0.4);
            check_free_formulas(&case, start)
                .unwrap_or_else(|e| panic!("ν = {nu}, η = {eta}: {e}"));
            let c = check_free_segment(&case, start);
            assert!(c.initial <= 1e-14, "ν = {nu}: initial {:e}", c.initial);
            assert!(
                c.residual_forcing <= 1e-9,
                "ν = {nu}, η = {eta}: residual {:e} of F",
                c.residual_forcing
            );
            assert!(c.velocity <= 1e-10, "ν = {nu}: velocity {:e}", c.velocity);
            assert!(c.expm <= 1e-11, "ν = {nu}: expm {:e}", c.expm);
        }
    }
    // ν = 1 really is the degenerate case: β² = 0 exactly.
    let model = crate::support::model(1.0, 0.0, 0.0);
    assert_eq!(coef::free_damped_frequency_sq(&model).beta_sq, 0.0);
}

proptest! {
    #![proptest_config(config(128))]

    /// `FreeSegment` over the random ensemble: start reproduced, FD residual ≤ 1e-9·F (measured
    /// ≲ 1e-11), velocity consistent with position, and exp(M s) agreement.
    #[test]
    fn free_segment_solves_free_ode(case in any_case(), state in proptest::array::uniform4(-2.0..2.0f64)) {
        let c = check_free_segment(&case, State::new(state[0], state[1], state[2], state[3]));
        prop_assert!(c.initial <= 1e-14, "initial {:e}", c.initial);
        prop_assert!(c.residual_forcing <= 1e-9, "residual {:e} of F", c.residual_forcing);
        prop_assert!(c.velocity <= 1e-10, "velocity {:e}", c.velocity);
        prop_assert!(c.expm <= 1e-11, "expm {:e}", c.expm);
    }
}

/// Kl with a close eigenvalue pair ω̄² ± √Δ, ω̄² = 27: Kl = [[27, 1], [Δ, 27]].
fn close_pair(disc: f64) -> LinearizedContact {
    LinearizedContact {
        fa1: 27.0,
        fb1: 1.0,
        fb2: disc,
        fa2: 27.0,
        fd1: 0.0,
        fd2: 0.0,
    }
}

/// `docs/MODEL.md` §6 cases 7–8 at the switch-over of `matrix_function`: below
/// √|Δ| = 1e-5(1 + |γ̄²|) it uses the first-order expansion f(γ̄²)I + f'(γ̄²)B, whose truncation
/// error is O(Δ) (measured 1.6e-10 at the threshold, Δ ≈ 7e-8, γ̄² ≈ 27); just above it, real
/// pairs use divided differences (measured 1e-13). Tolerance 1e-9 (the runtime's default
/// accuracy target) for the confluent side, 1e-11 for the real divided differences.
#[test]
fn matrix_function_near_double_root() {
    for disc in [0.0, 1e-12, -1e-12, 1e-9, -1e-9, 5e-8, -5e-8, 7e-8, -7e-8] {
        let (initial, worst) = homogeneous_errors(&close_pair(disc), 0.125, [0.3, -0.2, 1.0, 0.5]);
        assert!(initial <= 1e-14, "Δ = {disc:e}: initial {initial:e}");
        assert!(
            worst <= 1e-9,
            "Δ = {disc:e} (confluent branch): error {worst:e}"
        );
    }
    for disc in [1e-7, 1e-6, 1e-4, 1e-2] {
        let (_, worst) = homogeneous_errors(&close_pair(disc), 0.125, [0.3, -0.2, 1.0, 0.5]);
        assert!(worst <= 1e-11, "Δ = {disc:e} (real pair): error {worst:e}");
    }
}

/// Bug reproducer (runtime, `analytic/basis.rs`): for a complex pair close to a double root
/// (Δ slightly negative, just outside the confluent threshold), `matrix_function` loses about
/// u·γ̄⁴/|Δ| of relative accuracy: the odd part `c.im / e` divides the imaginary part of
/// cos(√μ s) by e = √|Δ|, and `Complex::sqrt` computes Im √μ as √((|μ| − Re μ)/2), which cancels
/// catastrophically when Im μ ≪ Re μ (|μ| − Re μ ≈ e²/(2 Re μ)). Measured against exp(M s):
/// Δ = −1e-7 → 4.8e-9, Δ = −1e-6 → 4.3e-10, Δ = −1e-4 → 1.9e-12, while the real pair at
/// Δ = +1e-7 gives 1.3e-13. Fix: Im √μ = Im μ / (2 Re √μ) for Re μ > 0 (and the mirror form
/// for Re μ < 0).
#[test]
fn matrix_function_complex_pair_near_double_root() {
    for disc in [-1e-7, -1e-6, -1e-4] {
        let (_, worst) = homogeneous_errors(&close_pair(disc), 0.125, [0.3, -0.2, 1.0, 0.5]);
        assert!(
            worst <= 1e-11,
            "Δ = {disc:e} (complex pair): error {worst:e}"
        );
    }
}
