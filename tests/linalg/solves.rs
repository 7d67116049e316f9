//! The dense kit against nalgebra: eigenvalues, LU (real and complex), the first-order matrix,
//! the harmonic response; every typed error.

use super::common::*;
use nalgebra::Complex as NaComplex;
use nalgebra::{DMatrix, DVector};
type Complex64 = NaComplex<f64>;
use rotor_rub::linalg::{
    Complex, ComplexMatrix, HarmonicResponse, LinalgError, Lu, ModalExponential, RealMatrix,
    SecondOrder, eigenvalues,
};

#[test]
fn eigenvalues_match_nalgebra_sorted_by_modulus() {
    let mut rng = Rng(777);
    for m in [1, 2, 3, 5, 8, 13, 16] {
        for _ in 0..5 {
            let a = rng.matrix(m);
            let mut ours = [Complex::ZERO; CAP];
            assert_eq!(eigenvalues(&a, &mut ours).unwrap(), m);
            let mut theirs: Vec<Complex64> =
                to_na(&a).complex_eigenvalues().iter().copied().collect();
            // Each of ours matches a distinct one of theirs.
            for z in &ours[..m] {
                let (k, d) = theirs
                    .iter()
                    .enumerate()
                    .map(|(k, w)| (k, (w - Complex64::new(z.re, z.im)).norm()))
                    .min_by(|a, b| a.1.total_cmp(&b.1))
                    .unwrap();
                assert!(d < 1e-12 * (1.0 + z.abs()), "m = {m}: {z:?} off by {d:e}");
                theirs.remove(k);
            }
            assert!(ours[..m].windows(2).all(|w| w[0].abs() >= w[1].abs()));
        }
    }
    // The modal form's eigenvalues are the same set.
    let a = two_disk_rotor().first_order(0.7);
    let e = ModalExponential::new(&a).unwrap();
    let mut sorted = [Complex::ZERO; CAP];
    eigenvalues(&a, &mut sorted).unwrap();
    for z in e.eigenvalues() {
        assert!(sorted[..16].iter().any(|w| (*w - z).abs() < 1e-12));
    }
}

#[test]
fn real_and_complex_lu_match_nalgebra() {
    let mut rng = Rng(4242);
    for n in [1, 2, 4, 9, 16] {
        let a = rng.matrix(n);
        let b = rng.vector(n);
        let lu = Lu::factor(&a, "a").unwrap();
        let mut x = b.clone();
        lu.solve(&mut x);
        let want = to_na(&a).lu().solve(&DVector::from_vec(b)).unwrap();
        assert!(relative_error(&x, want.as_slice()) < 1e-12, "n = {n}");
        let det = to_na(&a).determinant();
        assert!((lu.determinant() - det).abs() <= 1e-12 * det.abs().max(1e-300));

        let ac =
            ComplexMatrix::<CAP>::from_fn(n, n, |_, _| Complex::new(rng.uniform(), rng.uniform()))
                .unwrap();
        let bc: Vec<Complex> = (0..n)
            .map(|_| Complex::new(rng.uniform(), rng.uniform()))
            .collect();
        let lu = Lu::factor(&ac, "ac").unwrap();
        let mut x = bc.clone();
        lu.solve(&mut x);
        let na = DMatrix::from_fn(n, n, |i, j| {
            Complex64::new(ac.get(i, j).re, ac.get(i, j).im)
        });
        let nb = DVector::from_iterator(n, bc.iter().map(|z| Complex64::new(z.re, z.im)));
        let want = na.lu().solve(&nb).unwrap();
        let err: f64 = x
            .iter()
            .zip(want.iter())
            .map(|(a, b)| (Complex64::new(a.re, a.im) - b).norm_sqr())
            .sum::<f64>()
            .sqrt();
        assert!(err < 1e-12 * want.norm(), "complex n = {n}");
    }
    let singular = RealMatrix::<CAP>::from_rows(&[&[1.0, 2.0], &[2.0, 4.0]]).unwrap();
    assert_eq!(
        Lu::factor(&singular, "k").unwrap_err(),
        LinalgError::Singular {
            what: "k",
            column: 1
        }
    );
}

#[test]
fn the_first_order_matrix_matches_nalgebra() {
    let rotor = two_disk_rotor();
    let eta = 1.7;
    let a = rotor.first_order(eta);
    let (m, c, g, k) = (
        to_na(&rotor.m),
        to_na(&rotor.c),
        to_na(&rotor.g),
        to_na(&rotor.k),
    );
    let minv = m.try_inverse().unwrap();
    let n = 8;
    let mut want = DMatrix::<f64>::zeros(16, 16);
    want.view_mut((0, n), (n, n))
        .copy_from(&DMatrix::identity(n, n));
    want.view_mut((n, 0), (n, n)).copy_from(&(-&minv * &k));
    want.view_mut((n, n), (n, n))
        .copy_from(&(-&minv * (&c + &g * eta)));
    assert!((to_na(&a) - &want).norm() < 1e-13 * want.norm());
}

#[test]
fn bad_mass_matrices_are_typed_errors() {
    let z = RealMatrix::<CAP>::zeros(2, 2).unwrap();
    let i = RealMatrix::<CAP>::identity(2).unwrap();
    let asym = RealMatrix::<CAP>::from_rows(&[&[1.0, 0.1], &[0.0, 1.0]]).unwrap();
    let indefinite = RealMatrix::<CAP>::from_rows(&[&[1.0, 2.0], &[2.0, 1.0]]).unwrap();
    let singular = RealMatrix::<CAP>::from_rows(&[&[1.0, 1.0], &[1.0, 1.0]]).unwrap();
    let rotor = |mass| SecondOrder {
        mass,
        damping: &z,
        gyroscopic: &z,
        stiffness: &i,
    };
    assert!(matches!(
        rotor(&asym).first_order(0.0),
        Err(LinalgError::MassNotSymmetric { row: 1, col: 0, .. })
    ));
    assert!(matches!(
        rotor(&indefinite).first_order(0.0),
        Err(LinalgError::MassNotPositiveDefinite { pivot: 1, .. })
    ));
    assert!(matches!(
        rotor(&singular).first_order(0.0),
        Err(LinalgError::MassNotPositiveDefinite { pivot: 1, .. })
    ));
    let mut nan = i.clone();
    nan.set(0, 1, f64::NAN);
    assert_eq!(
        SecondOrder {
            mass: &i,
            damping: &nan,
            gyroscopic: &z,
            stiffness: &i
        }
        .first_order(0.0)
        .unwrap_err(),
        LinalgError::NonFinite {
            what: "damping matrix",
            row: 0,
            col: 1
        }
    );
    let big = RealMatrix::<4>::identity(3).unwrap();
    let z4 = RealMatrix::<4>::zeros(3, 3).unwrap();
    assert!(matches!(
        SecondOrder {
            mass: &big,
            damping: &z4,
            gyroscopic: &z4,
            stiffness: &big
        }
        .first_order(0.0),
        Err(LinalgError::TooLarge {
            size: 6,
            capacity: 4,
            ..
        })
    ));
    let msg = rotor(&indefinite).first_order(0.0).unwrap_err().to_string();
    assert!(msg.contains("not positive definite"), "{msg}");
    let mut inf = RealMatrix::<CAP>::identity(3).unwrap();
    inf.set(2, 2, f64::INFINITY);
    assert!(matches!(
        ModalExponential::new(&inf),
        Err(LinalgError::NonFinite { row: 2, col: 2, .. })
    ));
}

/// The harmonic response solves the equation of motion: M q'' + (C + ηG) q' + K q =
/// Re(F e^{iηs}) + u at every s (q'' = −η² times the harmonic part), and its projection is B y_p.
#[test]
fn the_harmonic_response_solves_the_equation_of_motion() {
    let rotor = two_disk_rotor();
    let eta = 1.3;
    let n = 8;
    let force: Vec<Complex> = (0..n)
        .map(|i| Complex::new((i as f64).sin(), (i as f64).cos() * 0.5))
        .collect();
    let u: Vec<f64> = (0..n).map(|i| 0.1 * i as f64 - 0.3).collect();
    let h = HarmonicResponse::new(&rotor.second_order(), eta, &force, &u).unwrap();
    let (m, c, g, k) = (
        to_na(&rotor.m),
        to_na(&rotor.c),
        to_na(&rotor.g),
        to_na(&rotor.k),
    );
    let bx: Vec<f64> = (0..16).map(|i| if i == 2 { 1.0 } else { 0.0 }).collect();
    let by: Vec<f64> = (0..16).map(|i| if i == 3 { 1.0 } else { 0.0 }).collect();
    let proj = h.project(&bx, &by).unwrap();
    for s in [0.0, 0.7, 5.0] {
        let mut y = vec![0.0; 16];
        h.state(s, &mut y);
        let q = DVector::from_column_slice(&y[..n]);
        let v = DVector::from_column_slice(&y[n..]);
        // q'' of the harmonic part: −η² (q − q_u); q_u = K⁻¹u.
        let qu = k
            .clone()
            .lu()
            .solve(&DVector::from_column_slice(&u))
            .unwrap();
        let acc = (&q - &qu) * (-eta * eta);
        let lhs = &m * acc + (&c + &g * eta) * &v + &k * &q;
        let (sn, cs) = (eta * s).sin_cos();
        let rhs = DVector::from_iterator(
            n,
            force
                .iter()
                .zip(&u)
                .map(|(f, &ui)| f.re * cs - f.im * sn + ui),
        );
        assert!((&lhs - &rhs).norm() < 1e-13 * rhs.norm(), "s = {s}");
        let p = proj.at(s);
        assert!((p.value[0] - y[2]).abs() < 1e-15 && (p.value[1] - y[3]).abs() < 1e-15);
        assert!((p.rate[0] - y[n + 2]).abs() < 1e-14);
        let b = proj.bound();
        assert!(p.value[0].hypot(p.value[1]) <= b.value && p.rate[0].hypot(p.rate[1]) <= b.rate);
    }
}

#[test]
fn resonance_and_a_free_rigid_body_are_typed_errors() {
    let one = RealMatrix::<CAP>::identity(2).unwrap();
    let zero = RealMatrix::<CAP>::zeros(2, 2).unwrap();
    let k4 = RealMatrix::<CAP>::from_fn(2, 2, |i, j| if i == j { 4.0 } else { 0.0 }).unwrap();
    let undamped = SecondOrder {
        mass: &one,
        damping: &zero,
        gyroscopic: &zero,
        stiffness: &k4,
    };
    let f = [Complex::ONE, Complex::new(0.0, -1.0)];
    assert_eq!(
        HarmonicResponse::new(&undamped, 2.0, &f, &[]).unwrap_err(),
        LinalgError::Resonance { speed_ratio: 2.0 }
    );
    let msg = HarmonicResponse::new(&undamped, 2.0, &f, &[])
        .unwrap_err()
        .to_string();
    assert!(msg.contains("η = 2"), "{msg}");
    assert!(HarmonicResponse::new(&undamped, 1.5, &f, &[]).is_ok());
    let free = SecondOrder {
        mass: &one,
        damping: &one,
        gyroscopic: &zero,
        stiffness: &zero,
    };
    assert!(matches!(
        HarmonicResponse::new(&free, 1.0, &f, &[1.0, 0.0]),
        Err(LinalgError::StaticSingular { .. })
    ));
    // Without a constant force a free rigid body has a harmonic response.
    assert!(HarmonicResponse::new(&free, 1.0, &f, &[]).is_ok());
}
