//! The assembled closed-form contact segment (`Linearization::segment`: taylor_terms,
//! linearized_stiffness, contact_modes, contact_particular(_eval), contact_homogeneous_start/eval,
//! polynomial_particular/eval) solves q'' + 2νq' + Kl q + Fd = F(cos θ, sin θ) + a(s), over a
//! random ensemble and in each degenerate case of `docs/MODEL.md` §6.
//!
//! Tolerances (see `support::SegmentCheck` for the measures):
//! - start state: 1e-14·cancellation (a handful of roundings of numbers of size ≤ cancellation;
//!   measured ≤ 2e-16 over 8000 random cases);
//! - ODE residual from eighth-order differences of the segment's velocity: ≤ 1e-9 of the forcing
//!   scale F + |Fd| + |a(s)| (the brief's bound) times cancellation·growth — the finite-difference
//!   rounding is ≈ 1e-13·rate²·|q|, and |q| grows by `growth` for growing modes and starts from
//!   the particular solutions' size; measured ≤ 7e-12 of that bound over 8000 random cases.
//!   In the named cases cancellation·growth is 1–5 without the cubic (the brief's 1e-9 of
//!   F + |Fd| + |a| up to that factor; measured ≤ 9e-12 of F + |Fd| + |a| itself), larger with it (up to
//!   5e4 at z0 = 0.9, ν = 1, where Kl has ω² = 0.15 and the cubic's polynomial particular
//!   solution is huge). Relative to the largest term of the equation the residual must be
//!   ≤ 1e-10·cancellation (measured ≤ 3e-12);
//! - velocity vs the position's derivative: 1e-9 (measured ≤ 6e-12);
//! - state vs exp(M s) of the augmented 10-dimensional linear system: 1e-11·cancellation
//!   (measured ≤ 2.3e-13).

use std::f64::consts::PI;

use nalgebra::Complex;
use proptest::prelude::*;
use rotor_rub::State;
use rotor_rub::analytic::linear::Linearization;
use rotor_rub::coefficients as coef;

use crate::support::*;

/// A fixed cubic forcing for the named cases.
const CUBIC: [f64; 8] = [0.7, -1.1, 2.0, 0.5, -1.5, 1.2, 0.8, -0.6];

fn assert_segment(what: &str, c: &SegmentCheck) {
    let k = c.cancellation;
    assert!(
        c.initial <= 1e-14 * k,
        "{what}: start not reproduced ({:e})",
        c.initial
    );
    assert!(
        c.residual_forcing <= 1e-9 * k * c.growth,
        "{what}: ODE residual {:e} of the forcing scale (cancellation {k:.3}, growth {:.3})",
        c.residual_forcing,
        c.growth
    );
    assert!(
        c.residual_terms <= 1e-10 * k,
        "{what}: ODE residual {:e} of the terms",
        c.residual_terms
    );
    assert!(
        c.velocity <= 1e-9 * k,
        "{what}: velocity inconsistent ({:e})",
        c.velocity
    );
    assert!(
        c.expm <= 1e-11 * k,
        "{what}: differs from exp(M s) by {:e}",
        c.expm
    );
}

/// Run the segment checks for a case with no extra forcing and with [`CUBIC`], at the unit
/// horizon (polynomial response) and at a short one (‖Kl‖h² ≤ 1: Taylor-series response).
fn check_case(what: &str, case: &Case, start: State) {
    let zero = check_contact_segment(case, start, [0.0; 8], 1.0);
    assert_segment(&format!("{what}, no cubic"), &zero);
    let cubic = check_contact_segment(case, start, CUBIC, 1.0);
    assert_segment(&format!("{what}, cubic"), &cubic);
    let norm = kl_matrix(&case.linearized()).norm();
    let short = (0.9 / norm).sqrt().min(1.0);
    let series = check_contact_segment(case, start, CUBIC, short);
    assert_segment(&format!("{what}, cubic, short horizon {short:.3}"), &series);
}

fn base() -> Case {
    Case {
        nu: 0.125,
        eta: 1.5,
        f: 0.35,
        k: [[20.0, 20.0], [20.0, 40.0]],
        offset: (0.3, -0.2),
        phase: 0.7,
        t0: 5.0,
        x0: 0.0,
        y0: 0.0,
    }
}

fn start_of(case: &Case) -> State {
    State::new(case.x0 + 0.05, case.y0 - 0.03, 0.8, -1.2)
}

fn eigenvalues(case: &Case) -> [Complex<f64>; 2] {
    let l = case.linearized();
    crate::modes::generated_eigenvalues(&coef::contact_modes(&case.model(), &l))
}

proptest! {
    #![proptest_config(config(256))]

    /// The random ensemble of the brief, with no extra forcing and with a random cubic.
    #[test]
    fn contact_segment_solves_linearized_ode(
        case in any_case(),
        d in proptest::array::uniform4(-1.0..1.0f64),
        a in any_cubic(),
    ) {
        prop_assume!(Linearization::new(&case.params(), case.t0, case.x0, case.y0).is_ok());
        let start = State::new(case.x0 + 0.3 * d[0], case.y0 + 0.3 * d[1], 2.0 * d[2], 2.0 * d[3]);
        for forcing in [[0.0; 8], a] {
            let c = check_contact_segment(&case, start, forcing, 1.0);
            let k = c.cancellation;
            prop_assert!(c.initial <= 1e-14 * k, "initial {:e}", c.initial);
            prop_assert!(c.residual_forcing <= 1e-9 * k * c.growth, "{c:?}");
            prop_assert!(c.residual_terms <= 1e-10 * k, "{c:?}");
            prop_assert!(c.velocity <= 1e-9 * k, "{c:?}");
            prop_assert!(c.expm <= 1e-11 * k, "{c:?}");
        }
    }

    /// Short horizons (‖Kl‖h² ≤ 1), where the runtime sums the cubic's response as a Taylor
    /// series instead of the polynomial particular solution.
    #[test]
    fn contact_segment_short_horizon(
        case in any_case(),
        d in proptest::array::uniform4(-1.0..1.0f64),
        a in any_cubic(),
    ) {
        prop_assume!(Linearization::new(&case.params(), case.t0, case.x0, case.y0).is_ok());
        let norm = kl_matrix(&case.linearized()).norm();
        let horizon = (0.9 / norm).sqrt().min(1.0);
        let start = State::new(case.x0 + 0.3 * d[0], case.y0 + 0.3 * d[1], 2.0 * d[2], 2.0 * d[3]);
        let c = check_contact_segment(&case, start, a, horizon);
        let k = c.cancellation;
        prop_assert!(c.initial <= 1e-14 * k, "initial {:e}", c.initial);
        prop_assert!(c.residual_forcing <= 1e-9 * k * c.growth, "{c:?}");
        prop_assert!(c.residual_terms <= 1e-10 * k, "{c:?}");
        prop_assert!(c.expm <= 1e-11 * k, "{c:?}");
    }
}

/// §6 case 1, Fb1 = 0: linearized at z0 = 1 on the horizontal line through the stator centre
/// (v0 = 0, so B1 = 0 and A2 = 1 − 1/z0 = 0 exactly), and for the paper's Kxx = Kxy at the entry
/// angle 3π/4 (Fb1 = sinϑ (Kxx cosϑ + Kxy sinϑ) = 0 to rounding).
#[test]
fn case_fb1_zero() {
    let mut case = base();
    case.offset = (0.25, -0.5); // dyadic: x0 − εx = ±1 exactly
    for side in [1.0, -1.0] {
        case.x0 = case.offset.0 + side;
        case.y0 = case.offset.1;
        let l = case.linearized();
        assert_eq!(l.fb1, 0.0, "Fb1 = {}", l.fb1);
        assert!(l.fb2 != 0.0, "Fb2 = Kyx A1 should stay");
        check_case(&format!("Fb1 = 0, side {side}"), &case, start_of(&case));
    }
    let case = base().at(1.0, 0.75 * PI);
    let l = case.linearized();
    assert!(l.fb1.abs() <= 1e-13, "Fb1 = {}", l.fb1);
    check_case("Fb1 = 0 at 3π/4", &case, start_of(&case));
}

/// §6 case 2, complex ω² (Δ < 0, Fb1·Fb2 < 0) for a non-symmetric stator, Kxy = 20, Kyx = −10.
#[test]
fn case_complex_omega_sq() {
    let mut found = 0;
    for z0 in [1.05, 1.2, 1.5, 2.0] {
        for i in 0..36 {
            let mut case = base().at(z0, f64::from(i) * PI / 18.0);
            case.k = [[20.0, 20.0], [-10.0, 40.0]];
            let l = case.linearized();
            let m = coef::contact_modes(&case.model(), &l);
            if m.disc >= -1e-3 {
                continue;
            }
            found += 1;
            assert!(l.fb1 * l.fb2 < 0.0);
            check_case(
                &format!("complex ω², z0 = {z0}, angle #{i}"),
                &case,
                start_of(&case),
            );
        }
    }
    assert!(
        found >= 3,
        "only {found} linearization points with complex ω²"
    );
}

/// §6 case 3, flutter: complex ω² with Im γ > ν (Kxy = 15, Kyx = −10, ν = 0.125): one pair
/// grows; the closed form must still solve the linear equations.
#[test]
fn case_flutter_growth() {
    let mut found = 0;
    for i in 0..36 {
        let mut case = base().at(1.5, f64::from(i) * PI / 18.0);
        case.k = [[20.0, 15.0], [-10.0, 40.0]];
        let growing = eigenvalues(&case)
            .iter()
            .any(|w| (w - case.nu * case.nu).sqrt().im.abs() > case.nu);
        if !growing || Linearization::new(&case.params(), case.t0, case.x0, case.y0).is_err() {
            continue;
        }
        found += 1;
        check_case(&format!("flutter, angle #{i}"), &case, start_of(&case));
    }
    assert!(found >= 1, "no flutter point found");
}

/// §6 case 4, over-damped modes ν = 1.2 and ν = 1.5 with an SPD stator just inside contact:
/// the tangential mode has ω² slightly above 1 < ν² (γ imaginary).
#[test]
fn case_overdamped_nu_1_2_and_1_5() {
    for nu in [1.2, 1.5] {
        let mut case = base().at(1.02, 0.9);
        case.nu = nu;
        case.k = [[20.0, 5.0], [5.0, 40.0]];
        let w = eigenvalues(&case);
        assert!(
            w.iter().all(|w| w.im == 0.0) && w[0].re < nu * nu,
            "ω² = {w:?}"
        );
        check_case(&format!("over-damped ν = {nu}"), &case, start_of(&case));
    }
}

/// §6 case 5, critical damping: ν = 1 at contact entry z0 = 1, where the tangential mode has
/// ω² = 1 exactly (J = n nᵀ, so Kl = I + K_s n nᵀ keeps the eigenvalue 1): γ = 0.
#[test]
fn case_critical_nu_1_at_entry() {
    for angle in [0.4, 2.0, 4.0] {
        let mut case = base().at(1.0, angle);
        case.nu = 1.0;
        let w = eigenvalues(&case);
        assert!(
            (w[0].re - 1.0).abs() <= 1e-13 && w[0].im == 0.0,
            "ω²₁ = {}",
            w[0]
        );
        let g = coef::damped_frequency_sq(
            &crate::support::model(1.0, 0.0, 0.0),
            &crate::modes::eigen(w[0].re),
        )
        .gamma_sq;
        assert!(g.abs() <= 1e-13, "γ²₁ = {g}");
        check_case(
            &format!("critical ν = 1, angle {angle}"),
            &case,
            start_of(&case),
        );
    }
}

/// §6 cases 4 and 6 from z0 < 1: linearizing inside the clearance gives the negative
/// tangential stiffness 1 + k(1 − 1/z0), hence negative ω² (static divergence, growing
/// exponential) for a stiff stator.
#[test]
fn case_linearized_inside_clearance() {
    let mut divergent = 0;
    for z0 in [0.5, 0.7, 0.9, 0.99] {
        for nu in [0.125, 1.0] {
            let mut case = base().at(z0, 1.1);
            case.nu = nu;
            // J's tangential eigenvalue 1 − 1/z0 is negative: J = [[A1, B1], [B2, A2]] has
            // det = 1 − 1/z0 (times the normal eigenvalue 1).
            let t = case.taylor();
            assert!(
                t.a1 * t.a2 - t.b1 * t.b2 < 0.0,
                "z0 = {z0}: J not indefinite"
            );
            let w = eigenvalues(&case);
            if w[0].re < 0.0 {
                divergent += 1;
            }
            check_case(&format!("z0 = {z0}, ν = {nu}"), &case, start_of(&case));
        }
    }
    assert!(divergent >= 4, "only {divergent} cases with a negative ω²");
}

/// §6 case 7, repeated ω² (diagonalizable): K_s = 0 gives Kl = I, Fd = 0, Δ = 0 exactly; the
/// paper's s1 = s2 would divide by zero.
#[test]
fn case_repeated_omega_sq() {
    for nu in [0.125, 1.0, 1.3] {
        let mut case = base().at(1.3, 2.2);
        case.nu = nu;
        case.k = [[0.0; 2]; 2];
        let l = case.linearized();
        assert_eq!(
            (l.fa1, l.fb1, l.fb2, l.fa2, l.fd1, l.fd2),
            (1.0, 0.0, 0.0, 1.0, 0.0, 0.0)
        );
        assert_eq!(
            coef::contact_modes(&crate::support::model(nu, 0.0, 0.0), &l).disc,
            0.0
        );
        check_case(&format!("Kl = I, ν = {nu}"), &case, start_of(&case));
    }
}

/// §6 case 8, defective and near-defective repeated ω²: K_s chosen so that
/// Kl = [[3, 1], [ε, 3]] at the linearization point (K_s = (Kl − I) J⁻¹). ε = 0 is a Jordan
/// block (confluent branch of `matrix_function`), ε = 1e-11 stays in that branch, ε = 1e-7
/// uses the divided differences across a close pair.
#[test]
fn case_defective_repeated_omega_sq() {
    for eps in [0.0, 1e-11, 1e-7] {
        let mut case = base().at(2.0, 0.6);
        let t = case.taylor();
        let j = nalgebra::Matrix2::new(t.a1, t.b1, t.b2, t.a2);
        let target = nalgebra::Matrix2::new(3.0, 1.0, eps, 3.0);
        let ks = (target - nalgebra::Matrix2::identity())
            * j.try_inverse().expect("J regular at z0 = 2");
        case.k = [[ks[(0, 0)], ks[(0, 1)]], [ks[(1, 0)], ks[(1, 1)]]];
        let l = case.linearized();
        assert!(
            (kl_matrix(&l) - target).abs().max() <= 1e-13,
            "Kl = {:?}",
            l
        );
        let m = coef::contact_modes(&case.model(), &l);
        assert!(m.disc.abs() <= 2e-7, "Δ = {}", m.disc);
        check_case(&format!("near-defective ε = {eps}"), &case, start_of(&case));
    }
}
