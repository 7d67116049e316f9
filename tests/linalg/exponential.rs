//! e^{As} y0: every degenerate case against its closed form, rotors (gyroscopic, non-symmetric
//! bearings) and random matrices against nalgebra's `exp`, spans 1e-3 … 1e3.

use super::common::*;
use rotor_rub::linalg::{ModalExponential, RealMatrix};

const SPANS: [f64; 6] = [1e-3, 0.1, 1.0, 10.0, 100.0, 1e3];

/// x'' + 2νx' + x = 0 in closed form: (x(s), x'(s)) from (x0, v0), any ν (EC/ES of
/// `docs/MODEL.md` §4 with their power series near β = 0).
fn oscillator(nu: f64, s: f64, x0: f64, v0: f64) -> [f64; 2] {
    let b2 = (1.0 - nu) * (1.0 + nu);
    // EC = e^{−νs} cos βs, ES = e^{−νs} sin(βs)/β (cosh/sinh for β² < 0, as sums of the two
    // real exponentials so nothing overflows; series in β²s² near β = 0).
    let (ec, es) = if b2.abs() * s * s < 1e-6 {
        let z = b2 * s * s;
        let x = (-nu * s).exp();
        (
            x * (1.0 - z / 2.0 + z * z / 24.0),
            x * s * (1.0 - z / 6.0 + z * z / 120.0),
        )
    } else if b2 > 0.0 {
        let b = b2.sqrt();
        let x = (-nu * s).exp();
        (x * (b * s).cos(), x * (b * s).sin() / b)
    } else if (-b2).sqrt() * s < 20.0 {
        let b = (-b2).sqrt();
        let x = (-nu * s).exp();
        (x * (b * s).cosh(), x * (b * s).sinh() / b)
    } else {
        let b = (-b2).sqrt();
        let (up, down) = (((b - nu) * s).exp(), (-(b + nu) * s).exp());
        (0.5 * (up + down), 0.5 * (up - down) / b)
    };
    [ec * x0 + es * (v0 + nu * x0), ec * v0 - es * (x0 + nu * v0)]
}

/// The worst relative error over the spans and a few states, and whether each met `tol`.
fn check_against(a: &RealMatrix<CAP>, exact: impl Fn(f64, &[f64]) -> Vec<f64>, name: &str) -> f64 {
    let e = ModalExponential::new(a).unwrap();
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    let mut worst: f64 = 0.0;
    for s in SPANS {
        let size = exp_norm(a, s);
        if !(1e-280..1e280).contains(&size) {
            continue;
        }
        let tol = tolerance(a, s);
        for _ in 0..4 {
            let y0 = rng.vector(a.rows());
            let r = exact(s, &y0);
            let err = normwise_error(a, s, &y0, &ours(&e, s, &y0), &r);
            assert!(err <= tol, "{name}: s = {s:e}: error {err:.2e} > {tol:.1e}");
            worst = worst.max(err);
        }
        if std::env::var("LINALG_REPORT").is_ok() {
            eprintln!("{name:32} s = {s:7.0e}: worst {worst:.1e}, tolerance {tol:.1e}");
        }
    }
    worst
}

/// Each coordinate of an isotropic rotor M = I, C = 2νI, K = I (n = 2: every eigenvalue twice,
/// diagonalizable; ν = 1 two Jordan blocks of size 2 on one eigenvalue) follows the scalar
/// oscillator.
#[test]
fn isotropic_rotors_match_the_closed_form_for_every_damping() {
    for nu in [
        0.0,
        0.1,
        0.5,
        1.0 - 1e-4,
        1.0 - 1e-8,
        1.0,
        1.0 + 1e-6,
        2.0,
        -0.05,
    ] {
        let a = Rotor::jeffcott(nu).first_order(0.0);
        check_against(
            &a,
            |s, y| {
                let [x, vx] = oscillator(nu, s, y[0], y[2]);
                let [z, vz] = oscillator(nu, s, y[1], y[3]);
                vec![x, z, vx, vz]
            },
            &format!("isotropic ν = {nu}"),
        );
    }
}

/// The single oscillator, including critical damping (a defective eigenvalue −1) and the
/// near-defective ν = 1 ± 1e-8.
#[test]
fn one_oscillator_matches_the_closed_form() {
    for nu in [0.0, 0.01, 1.0 - 1e-8, 1.0, 1.0 + 1e-8, 3.0, -0.02] {
        let a = RealMatrix::<CAP>::from_rows(&[&[0.0, 1.0], &[-1.0, -2.0 * nu]]).unwrap();
        check_against(
            &a,
            |s, y| oscillator(nu, s, y[0], y[1]).to_vec(),
            &format!("oscillator ν = {nu}"),
        );
    }
}

/// Zero eigenvalues: a free mass (a defective 0: x = x0 + v0 s) and a damped rigid-body mode
/// (0 and −c: x = x0 + v0 (1 − e^{−cs})/c), exactly.
#[test]
fn rigid_body_modes_match_the_closed_form() {
    let free = RealMatrix::<CAP>::from_rows(&[&[0.0, 1.0], &[0.0, 0.0]]).unwrap();
    check_against(&free, |s, y| vec![y[0] + y[1] * s, y[1]], "free mass");
    let c = 0.1;
    let damped = RealMatrix::<CAP>::from_rows(&[&[0.0, 1.0], &[0.0, -c]]).unwrap();
    check_against(
        &damped,
        |s, y| vec![y[0] + y[1] * -(-c * s).exp_m1() / c, y[1] * (-c * s).exp()],
        "damped rigid body",
    );
}

/// A two-disk rotor with gyroscopic disks and cross-coupled (non-symmetric) bearing K and C,
/// at several speeds (G scaled by η splits the whirl pairs), against nalgebra's `exp`.
#[test]
fn gyroscopic_rotor_on_non_symmetric_bearings_matches_nalgebra() {
    let rotor = two_disk_rotor();
    for eta in [0.0, 0.7, 3.0] {
        let a = rotor.first_order(eta);
        check_against(
            &a,
            |s, y| reference(&a, s, y),
            &format!("two-disk η = {eta}"),
        );
    }
}

/// Random dense matrices (entries uniform in [−1, 1], m = 2 … 16: complex pairs, real
/// eigenvalues, growing and decaying modes, non-normal) against nalgebra's `exp`, spans up to
/// 10 (longer spans of random growing modes overflow).
#[test]
fn random_matrices_match_nalgebra() {
    let mut rng = Rng(12345);
    let mut worst: f64 = 0.0;
    for m in 2..=16 {
        for _ in 0..6 {
            let a = rng.matrix(m);
            let e = ModalExponential::new(&a).unwrap();
            for s in [1e-3, 0.1, 1.0, 10.0] {
                let y0 = rng.vector(m);
                let r = reference(&a, s, &y0);
                let err = normwise_error(&a, s, &y0, &ours(&e, s, &y0), &r);
                assert!(
                    err <= tolerance(&a, s),
                    "m = {m}, s = {s}: {err:.2e} (cond S {:.1e})",
                    e.condition()
                );
                worst = worst.max(err);
            }
        }
    }
    eprintln!("random matrices: worst relative error {worst:.2e}");
}

/// A repeated defective eigenvalue of multiplicity 3 (a Jordan block of size 3 plus rounding):
/// A = −I + N (N the shift) against its closed form e^{−s}(I + Ns + N²s²/2), after a similarity
/// by a non-orthogonal matrix so the Schur form is not given away.
#[test]
fn a_jordan_block_of_size_three_is_exact() {
    let jordan =
        RealMatrix::<CAP>::from_rows(&[&[-1.0, 1.0, 0.0], &[0.0, -1.0, 1.0], &[0.0, 0.0, -1.0]])
            .unwrap();
    let p =
        nalgebra::DMatrix::from_row_slice(3, 3, &[1.0, 0.5, 0.0, 0.0, 1.0, -0.25, 0.5, 0.0, 1.0]);
    let pinv = p.clone().try_inverse().unwrap();
    let a: RealMatrix<CAP> = from_na(&(&p * to_na(&jordan) * &pinv));
    check_against(
        &a,
        |s, y| {
            let j = to_na(&jordan);
            let n = &j + nalgebra::DMatrix::identity(3, 3);
            let ej =
                (nalgebra::DMatrix::identity(3, 3) + &n * s + &n * &n * (s * s / 2.0)) * (-s).exp();
            let v = &p * ej * &pinv * nalgebra::DVector::from_column_slice(y);
            v.iter().copied().collect()
        },
        "Jordan block of size 3",
    );
}

/// y' = A y at every s (the rate from the modal form against A times the state).
#[test]
fn the_rate_is_a_times_the_state() {
    let a = two_disk_rotor().first_order(0.7);
    let e = ModalExponential::new(&a).unwrap();
    let y0: Vec<f64> = (0..a.rows()).map(|i| (i as f64 * 0.37).sin()).collect();
    let c = e.modal_coordinates(&y0).unwrap();
    for s in [0.0, 0.5, 7.0, 60.0] {
        let (mut y, mut dy) = (vec![0.0; a.rows()], vec![0.0; a.rows()]);
        e.state_and_rate(&c, s, &mut y, &mut dy);
        let ay: Vec<f64> = (to_na(&a) * nalgebra::DVector::from_column_slice(&y))
            .iter()
            .copied()
            .collect();
        assert!(relative_error(&dy, &ay) < 1e-13, "s = {s}");
    }
}

/// Long spans do not overflow: a decaying rotor over s = 1e4 underflows to exactly 0, an
/// undamped one stays bounded, a growing mode grows as it should.
#[test]
fn long_spans_neither_overflow_nor_produce_nan() {
    for (nu, expect_zero) in [(0.1, true), (1.0, true), (0.0, false)] {
        let a = Rotor::jeffcott(nu).first_order(0.0);
        let e = ModalExponential::new(&a).unwrap();
        let y = ours(&e, 1e4, &[1.0, -0.5, 0.2, 0.3]);
        assert!(y.iter().all(|v| v.is_finite()));
        if expect_zero {
            assert!(y.iter().all(|&v| v == 0.0), "ν = {nu}: {y:?}");
        } else {
            let exact = oscillator(0.0, 1e4, 1.0, 0.2);
            assert!((y[0] - exact[0]).abs() < 4e-12, "{y:?} vs {exact:?}");
        }
    }
}

/// A larger random matrix (m = 40, its own capacity) against nalgebra's `exp`.
#[test]
fn a_forty_by_forty_matrix_matches_nalgebra() {
    let mut rng = Rng(99);
    let a = RealMatrix::<40>::from_fn(40, 40, |_, _| rng.uniform() / 3.0).unwrap();
    let e = Box::new(ModalExponential::new(&a).unwrap());
    for s in [0.01, 1.0, 5.0] {
        let y0 = rng.vector(40);
        let err = normwise_error(&a, s, &y0, &ours(&e, s, &y0), &reference(&a, s, &y0));
        assert!(err <= tolerance(&a, s), "s = {s}: {err:.2e}");
    }
}
