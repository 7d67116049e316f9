//! Particular solutions: `contact_particular`, `contact_particular_eval`, `free_particular`,
//! `polynomial_particular`, `polynomial_eval` (`docs/MODEL.md` §4, §5, §8).

use nalgebra::{Matrix2, SVector, Vector2};
use proptest::prelude::*;
use rotor_rub::coefficients as coef;

use crate::support::*;

/// Compare generated harmonic constants with a pivoted LU solve of the same 4×4 system.
///
/// Tolerances: the generated formulas are Cramer's rule, LU is backward stable; both have
/// forward error ≲ cond·u·(small constant), so |c − c_LU| ≤ 1e-13·cond·‖c‖ (cond ≤ 1e8 here;
/// measured ≤ 6e-16·cond·‖c‖ over 8000 cases). The backward residual ‖M c − rhs‖ of the
/// generated answer must be ≤ 1e-12 of ‖M‖‖c‖ + F (measured ≤ 9e-15).
fn check_harmonic(
    kl: &Matrix2<f64>,
    nu: f64,
    eta: f64,
    f: f64,
    c: [f64; 4],
) -> Result<(), TestCaseError> {
    let (m, rhs) = harmonic_system(kl, nu, eta, f);
    let k = cond(&m);
    prop_assume!(k < 1e8);
    let lu = m.lu().solve(&rhs).expect("regular");
    let got = SVector::<f64, 4>::from(c);
    let norm = lu.abs().max().max(got.abs().max());
    prop_assert!(
        (got - lu).abs().max() <= 1e-13 * k * norm,
        "generated {got} vs LU {lu} (cond {k:e})"
    );
    let residual = (m * got - rhs).abs().max();
    prop_assert!(
        residual <= 1e-10 * (m.abs().max() * got.abs().max() + f),
        "residual {residual:e}"
    );
    Ok(())
}

proptest! {
    #![proptest_config(config(256))]

    /// c11…c44 solve the 4×4 harmonic system (see `support::harmonic_system`) and c55, c66 the
    /// constant system Kl (c55, c66) = −Fd, against nalgebra LU. `contact_particular_eval` then
    /// satisfies the ODE exactly: with x_p'' = −η² (x_p − c55) the residual of
    /// q'' + 2νq' + Kl q + Fd − F(cos θ, sin θ) is rounding only.
    #[test]
    fn contact_particular_matches_lu(case in any_case(), theta in 0.0..std::f64::consts::TAU) {
        let l = case.linearized();
        let kl = kl_matrix(&l);
        let (nu, eta, f) = (case.nu, case.eta, case.forcing());
        let c = coef::contact_particular(&model(nu, eta, f), &l);
        check_harmonic(&kl, nu, eta, f, [c.c11, c.c22, c.c33, c.c44])?;
        let k2 = cond(&kl);
        prop_assume!(k2 < 1e8);
        let fd = Vector2::new(l.fd1, l.fd2);
        let constant = kl.lu().solve(&(-fd)).expect("regular");
        let norm = constant.abs().max();
        prop_assert!((c.c55 - constant.x).abs() <= 1e-13 * k2 * norm, "c55 {} vs {}", c.c55, constant.x);
        prop_assert!((c.c66 - constant.y).abs() <= 1e-13 * k2 * norm, "c66 {} vs {}", c.c66, constant.y);

        let (st, ct) = theta.sin_cos();
        let p = coef::contact_particular_eval(&model(nu, eta, f), &coef::Phasor { ct, st }, &c);
        prop_assert!((p.x - (c.c11 * ct + c.c22 * st + c.c55)).abs() <= 1e-12 * (1.0 + p.x.abs()));
        prop_assert!((p.vx - eta * (-c.c11 * st + c.c22 * ct)).abs() <= 1e-12 * (1.0 + p.vx.abs()));
        let q = Vector2::new(p.x, p.y);
        let v = Vector2::new(p.vx, p.vy);
        let acc = -eta * eta * (q - Vector2::new(c.c55, c.c66));
        let r = acc + 2.0 * nu * v + kl * q + fd - f * Vector2::new(ct, st);
        let scale = acc.norm() + 2.0 * nu * v.norm() + kl.norm() * q.norm() + fd.norm() + f;
        // Rounding of the terms themselves (each ≤ scale) and of the constants (backward error
        // of the solves ≲ 1e-13 of their terms): 1e-10·scale.
        prop_assert!(r.norm() <= 1e-10 * scale, "residual {} (scale {scale})", r.norm());
    }

    /// free_particular is the same 4×4 system with Kl = I and Fd = 0 (`docs/MODEL.md` §4), and
    /// contact_particular reduces to it for Kl = I, Fd = 0.
    #[test]
    fn free_particular_matches_lu(nu in 0.05..1.5f64, eta in 0.2..5.0f64, f in 0.01..2.0f64) {
        let c = coef::free_particular(&model(nu, eta, f));
        check_harmonic(&Matrix2::identity(), nu, eta, f, [c.c11, c.c22, c.c33, c.c44])?;
        let unit = coef::LinearizedContact { fa1: 1.0, fa2: 1.0, ..Default::default() };
        let d = coef::contact_particular(&model(nu, eta, f), &unit);
        for (a, b) in [(c.c11, d.c11), (c.c22, d.c22), (c.c33, d.c33), (c.c44, d.c44)] {
            prop_assert!((a - b).abs() <= 1e-13 * (a.abs() + b.abs()));
        }
        prop_assert!(d.c55 == 0.0 && d.c66 == 0.0);
    }

    /// The cubic q = b0 + b1 s + b2 s² + b3 s³ satisfies q'' + 2νq' + Kl q = a0 + a1 s + a2 s² +
    /// a3 s³ coefficient by coefficient:
    ///   s³: Kl b3 = a3,   s²: Kl b2 + 6ν b3 = a2,   s¹: Kl b1 + 4ν b2 + 6 b3 = a1,
    ///   s⁰: Kl b0 + 2ν b1 + 2 b2 = a0.
    /// Each residual is compared with the magnitude of that equation's terms (rel. 1e-10; a 2×2
    /// Cramer solve with cond(Kl) ≤ 1e4 leaves ≲ 1e-12). `polynomial_eval` is the cubic and its
    /// derivative.
    #[test]
    fn polynomial_particular_solves_coefficientwise(
        case in any_case(), a in any_cubic(), s in 0.0..2.0f64,
    ) {
        let l = case.linearized();
        let kl = kl_matrix(&l);
        prop_assume!(cond(&kl) < 1e4);
        let nu = case.nu;
        let b = coef::polynomial_particular(&model(nu, 0.0, 0.0), &l, &cubic(&a));
        let bk = [
            Vector2::new(b.b0x, b.b0y),
            Vector2::new(b.b1x, b.b1y),
            Vector2::new(b.b2x, b.b2y),
            Vector2::new(b.b3x, b.b3y),
        ];
        let ak = [0, 1, 2, 3].map(|k| Vector2::new(a[2 * k], a[2 * k + 1]));
        let norm_kl = kl.abs().max() * 2.0;
        for k in 0..4 {
            // Coefficient of s^k: Kl b_k + 2ν(k+1) b_{k+1} + (k+2)(k+1) b_{k+2} = a_k.
            let mut lhs = kl * bk[k];
            let mut scale = norm_kl * bk[k].abs().max() + ak[k].abs().max();
            if k + 1 < 4 {
                let t = 2.0 * nu * (k + 1) as f64 * bk[k + 1];
                lhs += t;
                scale += t.abs().max();
            }
            if k + 2 < 4 {
                let t = ((k + 2) * (k + 1)) as f64 * bk[k + 2];
                lhs += t;
                scale += t.abs().max();
            }
            let r = (lhs - ak[k]).abs().max();
            prop_assert!(r <= 1e-10 * scale, "s^{k}: residual {r:e}, scale {scale:e}");
        }
        let e = coef::polynomial_eval(&coef::LocalTime { s }, &b);
        let want = bk[0] + bk[1] * s + bk[2] * s * s + bk[3] * s * s * s;
        let dwant = bk[1] + bk[2] * (2.0 * s) + bk[3] * (3.0 * s * s);
        let sc = 1e-13 * (1.0 + bk.iter().map(|v| v.abs().max()).sum::<f64>()) * 8.0;
        prop_assert!((e.x - want.x).abs() <= sc && (e.y - want.y).abs() <= sc);
        prop_assert!((e.vx - dwant.x).abs() <= sc && (e.vy - dwant.y).abs() <= sc);
    }
}
