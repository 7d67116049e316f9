//! Modes of Kl and the paper's modal form: `contact_modes`, `mode_shape`, `paper_mode_ratio`,
//! `paper_modal_constants`, `damped_frequency_sq`, `free_damped_frequency_sq` (`docs/MODEL.md` §5).

use nalgebra::{Complex, Matrix2, Vector2};
use proptest::prelude::*;
use rotor_rub::coefficients as coef;

use crate::support::*;

type C = Complex<f64>;

/// The generated eigenvalues ω²₁,₂ = mean ∓ √Δ, complex when Δ < 0.
pub fn generated_eigenvalues(m: &coef::ContactModes) -> [C; 2] {
    let r = C::new(m.disc, 0.0).sqrt();
    [
        C::new(m.omega_sq_mean, 0.0) - r,
        C::new(m.omega_sq_mean, 0.0) + r,
    ]
}

fn sorted(mut v: [C; 2]) -> [C; 2] {
    v.sort_by(|a, b| a.re.total_cmp(&b.re).then(a.im.total_cmp(&b.im)));
    v
}

proptest! {
    #![proptest_config(config(256))]

    /// ω² = mean ∓ √Δ against nalgebra's (Schur) eigenvalues of Kl, complex included; the
    /// invariants det = ω²₁ω²₂, trace = 2·mean, γ̄² = mean − ν²; `damped_frequency_sq` is ω² − ν².
    ///
    /// Tolerance: a pair separated by `sep` moves by ≈ u‖Kl‖²/sep under rounding (any method), a
    /// nearly defective one by ≈ √u·‖Kl‖ ≈ 1.5e-8‖Kl‖; so 1e-12·(1 + ‖Kl‖)·max(1, (1 + ‖Kl‖)/sep),
    /// capped at 1e-7·(1 + ‖Kl‖) (measured ≤ 8e-16·(1 + ‖Kl‖) over 8000 cases). Invariants:
    /// 1e-12 relative.
    ///
    /// `mode_shape`: (Fb1, ω² − Fa1) and (ω² − Fa2, Fb2) are affine in ω², so the complex mode of
    /// a complex ω² = a + ib is v(a) + ib·(v(a + 1) − v(a)); the longer of the two satisfies
    /// (Kl − ω²I)v = 0 to 1e-11·(‖Kl‖ + |ω²|)‖v‖ (measured ≤ 8e-16; the error of ω² itself,
    /// ≲ 1e-8‖Kl‖ near a double root, enters times the distance √Δ to the other root).
    #[test]
    fn contact_modes_match_nalgebra_eigenvalues(case in any_case()) {
        let l = case.linearized();
        let kl = kl_matrix(&l);
        let m = coef::contact_modes(&case.model(), &l);
        let norm = kl.abs().max();
        let ours = sorted(generated_eigenvalues(&m));
        let ev = kl.complex_eigenvalues();
        let na = sorted([ev[0], ev[1]]);
        let sep = (na[1] - na[0]).norm();
        let tol = (1e-12 * ((1.0 + norm) / sep).max(1.0)).min(1e-7) * (1.0 + norm);
        for k in 0..2 {
            prop_assert!((ours[k] - na[k]).norm() <= tol, "ω² {:?} vs nalgebra {:?}", ours, na);
        }
        let det = kl.determinant();
        prop_assert!((m.det - det).abs() <= 1e-12 * (1.0 + norm * norm));
        prop_assert!((ours[0] * ours[1] - det).norm() <= 1e-12 * (1.0 + norm * norm));
        prop_assert!((2.0 * m.omega_sq_mean - kl.trace()).abs() <= 1e-12 * (1.0 + norm));
        let half = (l.fa1 - l.fa2) / 2.0;
        prop_assert!((m.disc - (half * half + l.fb1 * l.fb2)).abs() <= 1e-12 * (1.0 + norm * norm));
        prop_assert!((m.gamma_sq_mean - (m.omega_sq_mean - case.nu * case.nu)).abs() <= 1e-12 * (1.0 + norm));
        for w in ours {
            let d = coef::damped_frequency_sq(&case.model(), &eigen(w.re)).gamma_sq;
            prop_assert!((d - (w.re - case.nu * case.nu)).abs() <= 1e-12 * (1.0 + norm));

            let v0 = coef::mode_shape(&l, &eigen(w.re));
            let v1 = coef::mode_shape(&l, &eigen(w.re + 1.0));
            let lift = |a: f64, b: f64| C::new(a, w.im * (b - a));
            let rows = [
                Vector2::new(lift(v0.row1_x, v1.row1_x), lift(v0.row1_y, v1.row1_y)),
                Vector2::new(lift(v0.row2_x, v1.row2_x), lift(v0.row2_y, v1.row2_y)),
            ];
            let v = if rows[0].norm() >= rows[1].norm() { rows[0] } else { rows[1] };
            if v.norm() <= 1e-8 * (1.0 + norm) {
                continue; // Kl = ω² I (to rounding): every vector is a mode.
            }
            let a = kl.map(|x| C::new(x, 0.0)) - Matrix2::identity() * w;
            let r = (a * v).norm();
            prop_assert!(r <= 1e-11 * (norm + w.norm()) * v.norm(), "(Kl − ω²)v = {r:e} for ω² = {w}, v = {v}");
        }
    }

    /// `free_damped_frequency_sq` is `damped_frequency_sq` at ω² = 1.
    #[test]
    fn free_damped_frequency_is_unit_mode(nu in 0.0..2.0f64) {
        let model = crate::support::model(nu, 0.0, 0.0);
        let b = coef::free_damped_frequency_sq(&model).beta_sq;
        prop_assert_eq!(b, coef::damped_frequency_sq(&model, &eigen(1.0)).gamma_sq);
        prop_assert!((b - (1.0 - nu * nu)).abs() <= 4.0 * f64::EPSILON);
    }
}

/// The paper's homogeneous solution (eqs. 8–9) in local time: mode shapes (1, s_i), constants
/// c1…c4, frequencies γ1 (first pair) and `gamma_s2` in the s2 terms of y (γ2 when corrected,
/// γ1 as printed, erratum 5). Returns (x, y).
#[allow(clippy::too_many_arguments)]
pub fn paper_solution(
    c: &coef::PaperModalConstants,
    s1: f64,
    s2: f64,
    g1: f64,
    g2: f64,
    gamma_s2: f64,
    nu: f64,
    t: f64,
) -> Vector2<f64> {
    let e = (-nu * t).exp();
    let m1 = c.c1 * (g1 * t).cos() + c.c2 * (g1 * t).sin();
    let m2x = c.c3 * (g2 * t).cos() + c.c4 * (g2 * t).sin();
    let m2y = c.c3 * (gamma_s2 * t).cos() + c.c4 * (gamma_s2 * t).sin();
    Vector2::new(e * (m1 + m2x), e * (s1 * m1 + s2 * m2y))
}

/// Largest residual of q'' + 2νq' + Kl q = 0 for `q`, at [`SAMPLE_TIMES`], relative to the
/// magnitude of the terms, with derivatives by eighth-order central differences (step from
/// `rate`: truncation ≈ 1e-11, rounding ≈ 1e-13 of the terms).
pub fn homogeneous_residual(
    q: impl Fn(f64) -> Vector2<f64>,
    kl: &Matrix2<f64>,
    nu: f64,
    rate: f64,
) -> f64 {
    let h = fd_step(rate);
    let mut worst: f64 = 0.0;
    for &t in &SAMPLE_TIMES {
        let acc = Vector2::new(d2_ds2(|s| q(s).x, t, h), d2_ds2(|s| q(s).y, t, h));
        let vel = Vector2::new(d_ds(|s| q(s).x, t, h), d_ds(|s| q(s).y, t, h));
        let pos = q(t);
        let r = acc + 2.0 * nu * vel + kl * pos;
        let scale = acc.norm() + 2.0 * nu * vel.norm() + kl.norm() * pos.norm();
        worst = worst.max(r.norm() / scale);
    }
    worst
}

/// A case with real, distinct, under-damped modes and Fb1 away from 0, where the paper's form
/// (8)–(9) is valid (erratum 7): symmetric SPD-ish stator, contact depth z0 > 1, ν < 0.9.
pub fn real_modes_case() -> impl Strategy<Value = Case> {
    (
        any_case(),
        0.05..0.9f64,
        1.1..3.0f64,
        0.0..std::f64::consts::TAU,
        0.0..60.0f64,
        -20.0..20.0f64,
    )
        .prop_map(|(mut c, nu, z0, ang, kxx, kc)| {
            c.nu = nu;
            c.k = [[kxx, kc], [kc, c.k[1][1]]];
            c.at(z0, ang)
        })
}

/// Whether the paper's form applies comfortably: Δ > 0 clearly, both γ² > 0.05, |Fb1| not
/// small, s1 and s2 well apart (its constants divide by s2 − s1, γ1, γ2).
pub fn paper_form_valid(l: &coef::LinearizedContact, nu: f64) -> Option<(f64, f64, f64, f64)> {
    let model = crate::support::model(nu, 0.0, 0.0);
    let m = coef::contact_modes(&model, l);
    let norm = kl_matrix(l).abs().max();
    if m.disc <= 1e-2 * (1.0 + norm) * (1.0 + norm) || l.fb1.abs() <= 0.05 * norm {
        return None;
    }
    let w = [
        m.omega_sq_mean - m.disc.sqrt(),
        m.omega_sq_mean + m.disc.sqrt(),
    ];
    let g2 = w.map(|w| coef::damped_frequency_sq(&model, &eigen(w)).gamma_sq);
    if g2[0] <= 0.05 || g2[1] <= 0.05 {
        return None;
    }
    let s = w.map(|w| coef::paper_mode_ratio(l, &eigen(w)).s);
    if (s[1] - s[0]).abs() <= 0.05 * (1.0 + s[0].abs() + s[1].abs()) {
        return None;
    }
    Some((s[0], s[1], g2[0].sqrt(), g2[1].sqrt()))
}

proptest! {
    #![proptest_config(config(256))]

    /// `paper_mode_ratio` gives the mode (1, s) of Kl; `paper_modal_constants` reproduce the
    /// homogeneous initial state at s = 0 (analytic derivative; 1e-12 of the terms' magnitude
    /// Σ|c|(1 + |s_i|)(1 + γ + ν), since the constants may be larger than the state and cancel),
    /// and the resulting form (with γ2 in the s2 terms) solves q'' + 2νq' + Kl q = 0 to 1e-9 of
    /// its terms (finite differences; see `homogeneous_residual`).
    #[test]
    fn paper_modal_constants_reproduce_start_and_solve_ode(
        case in real_modes_case(),
        init in proptest::array::uniform4(-2.0..2.0f64),
    ) {
        let l = case.linearized();
        let Some((s1, s2, g1, g2)) = paper_form_valid(&l, case.nu) else {
            return Err(TestCaseError::reject("paper form not applicable"));
        };
        let kl = kl_matrix(&l);
        let nu = case.nu;
        for (s, w) in [(s1, g1 * g1 + nu * nu), (s2, g2 * g2 + nu * nu)] {
            // (Kl − ω²)(1, s) = 0: the first row by construction, the second by the
            // characteristic equation.
            let r = (kl - Matrix2::identity() * w) * Vector2::new(1.0, s);
            prop_assert!(r.norm() <= 1e-9 * (kl.norm() + w) * (1.0 + s.abs()), "mode residual {r}");
        }
        let [xh0, yh0, vxh0, vyh0] = init;
        let c = paper_constants([s1, s2, g1, g2], nu, [xh0, yh0, vxh0, vyh0]);
        let q0 = paper_solution(&c, s1, s2, g1, g2, g2, nu, 0.0);
        // Velocity at 0 from the form's analytic derivative: −ν q(0) + (γ1 c2 + γ2 c4, s1γ1c2 + s2γ2c4).
        let v0 = -nu * q0 + Vector2::new(g1 * c.c2 + g2 * c.c4, s1 * g1 * c.c2 + s2 * g2 * c.c4);
        let mag = (c.c1.abs() + c.c2.abs() + c.c3.abs() + c.c4.abs()) * (1.0 + s1.abs() + s2.abs()) * (1.0 + g1 + g2 + nu);
        let tol = 1e-12 * (1.0 + mag);
        prop_assert!((q0.x - xh0).abs() <= tol && (q0.y - yh0).abs() <= tol, "q(0) = {q0}");
        prop_assert!((v0.x - vxh0).abs() <= tol && (v0.y - vyh0).abs() <= tol, "q'(0) = {v0}");
        let res = homogeneous_residual(|t| paper_solution(&c, s1, s2, g1, g2, g2, nu, t), &kl, nu, nu + g1.max(g2));
        prop_assert!(res <= 1e-9, "ODE residual {res:e}");
    }
}

/// The generated eigenvalue struct for ω².
pub fn eigen(omega_sq: f64) -> coef::Eigenvalue {
    coef::Eigenvalue { omega_sq }
}

/// `paper_modal_constants` for modes [s1, s2, γ1, γ2], damping ν and homogeneous start
/// [x_h0, y_h0, x_h0', y_h0'].
pub fn paper_constants(modes: [f64; 4], nu: f64, init: [f64; 4]) -> coef::PaperModalConstants {
    let [s1, s2, gamma1, gamma2] = modes;
    let [xh0, yh0, vxh0, vyh0] = init;
    coef::paper_modal_constants(
        &crate::support::model(nu, 0.0, 0.0),
        &coef::PaperModes {
            s1,
            s2,
            gamma1,
            gamma2,
        },
        &coef::HomogeneousInitial {
            xh0,
            yh0,
            vxh0,
            vyh0,
        },
    )
}
