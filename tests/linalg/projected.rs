//! The projected fast path d(s) = B e^{As} y0: equal to B times the full path, its derivatives
//! B A y, B A² y, and its bounds true upper bounds on dense samples and within 10× of the
//! sampled maximum on smooth cases.

use super::common::*;
use nalgebra::{DMatrix, DVector};
use proptest::prelude::*;
use rotor_rub::linalg::{ModalExponential, ProjectedMotion, RealMatrix};

/// B for the rub station at DOF pair (i, j) of an n-DOF rotor, relative to DOF pair (k, l)
/// when given (a moving stator point).
fn station(n: usize, pair: (usize, usize), stator: Option<(usize, usize)>) -> [Vec<f64>; 2] {
    let mut b = [vec![0.0; 2 * n], vec![0.0; 2 * n]];
    b[0][pair.0] = 1.0;
    b[1][pair.1] = 1.0;
    if let Some((k, l)) = stator {
        b[0][k] -= 1.0;
        b[1][l] -= 1.0;
    }
    b
}

fn cases() -> Vec<(&'static str, RealMatrix<CAP>, [Vec<f64>; 2])> {
    vec![
        (
            "isotropic ν = 0.1",
            Rotor::jeffcott(0.1).first_order(0.0),
            station(2, (0, 1), None),
        ),
        (
            "isotropic ν = 1",
            Rotor::jeffcott(1.0).first_order(0.0),
            station(2, (0, 1), None),
        ),
        (
            "isotropic ν = 0",
            Rotor::jeffcott(0.0).first_order(0.0),
            station(2, (0, 1), None),
        ),
        (
            "two-disk η = 0.7, disk 1 against bearing 3",
            two_disk_rotor().first_order(0.7),
            station(8, (2, 3), Some((6, 7))),
        ),
        (
            "two-disk η = 3, disk 2",
            two_disk_rotor().first_order(3.0),
            station(8, (4, 5), None),
        ),
    ]
}

#[test]
fn the_projection_is_b_times_the_full_path_with_its_derivatives() {
    for (name, a, b) in cases() {
        let m = a.rows();
        let e = ModalExponential::new(&a).unwrap();
        let mut motion = ProjectedMotion::new(&e, &b[0], &b[1]).unwrap();
        let y0: Vec<f64> = (0..m).map(|i| (1.3 * i as f64).cos()).collect();
        motion.set_state(&e, &y0).unwrap();
        let bm = DMatrix::from_fn(2, m, |r, c| b[r][c]);
        let an = to_na(&a);
        for s in [0.0, 1e-3, 0.4, 3.0, 25.0, 200.0] {
            let y = DVector::from_vec(ours(&e, s, &y0));
            let scale = bm.norm() * exp_norm(&a, s) * norm(&y0);
            let p = motion.at(&e, s);
            for (got, want, what) in [
                (p.value, &bm * &y, "d"),
                (p.rate, &bm * &an * &y, "d'"),
                (p.acceleration, &bm * &an * &an * &y, "d''"),
            ] {
                let err = ((got[0] - want[0]).powi(2) + (got[1] - want[1]).powi(2)).sqrt();
                let size = scale
                    * an.norm().powi(if what == "d" {
                        0
                    } else if what == "d'" {
                        1
                    } else {
                        2
                    });
                assert!(
                    err <= 1e-13 * size,
                    "{name}, s = {s}, {what}: {err:.2e} vs {size:.2e}"
                );
            }
        }
    }
}

/// The largest |d|, |d'|, |d''| on a dense grid of [lo, hi].
fn sampled_max(
    motion: &ProjectedMotion<CAP>,
    e: &ModalExponential<CAP>,
    lo: f64,
    hi: f64,
) -> [f64; 3] {
    let mut most = [0.0f64; 3];
    for k in 0..=400 {
        let s = lo + (hi - lo) * k as f64 / 400.0;
        let p = motion.at(e, s);
        for (m, v) in most.iter_mut().zip([p.value, p.rate, p.acceleration]) {
            *m = m.max(v[0].hypot(v[1]));
        }
    }
    most
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// The bounds hold at 401 points of random intervals for random states of every case,
    /// degenerate ones included.
    #[test]
    fn the_bounds_hold_on_dense_samples(
        case in 0usize..5,
        lo in 0.0f64..50.0,
        len in 1e-3f64..20.0,
        seed in 1u64..1_000_000,
    ) {
        let (name, a, b) = &cases()[case];
        let e = ModalExponential::new(a).unwrap();
        let mut motion = ProjectedMotion::new(&e, &b[0], &b[1]).unwrap();
        let y0 = Rng(seed).vector(a.rows());
        motion.set_state(&e, &y0).unwrap();
        let bound = motion.bound(&e, lo, lo + len);
        let most = sampled_max(&motion, &e, lo, lo + len);
        for (m, bd) in most.iter().zip([bound.value, bound.rate, bound.acceleration]) {
            prop_assert!(*m <= bd, "{}: sampled {} > bound {}", name, m, bd);
        }
    }
}

/// A defective block (critical damping, two Jordan blocks on −1) and the free mass (a
/// defective 0): the polynomial part of the bound, checked on dense samples.
#[test]
fn the_bounds_hold_for_defective_blocks() {
    for a in [
        Rotor::jeffcott(1.0).first_order(0.0),
        RealMatrix::<CAP>::from_rows(&[&[0.0, 1.0], &[0.0, 0.0]]).unwrap(),
    ] {
        let e = ModalExponential::new(&a).unwrap();
        let m = a.rows();
        let b = station(m / 2, (0, m / 2 - 1), None);
        let b = if m == 2 {
            [vec![1.0, 0.0], vec![0.0, 1.0]]
        } else {
            b
        };
        let mut motion = ProjectedMotion::new(&e, &b[0], &b[1]).unwrap();
        motion.set_state(&e, &vec![0.7; m]).unwrap();
        for (lo, hi) in [(0.0, 1.0), (0.0, 30.0), (5.0, 5.5), (100.0, 140.0)] {
            let bound = motion.bound(&e, lo, hi);
            let most = sampled_max(&motion, &e, lo, hi);
            for (mx, bd) in most
                .iter()
                .zip([bound.value, bound.rate, bound.acceleration])
            {
                assert!(*mx <= bd, "[{lo}, {hi}]: sampled {mx} > bound {bd}");
            }
        }
    }
}

/// On smooth cases (a whirling rotor, one or two dominant modes) over an interval of a period
/// the bounds are within 10× of the sampled maxima.
#[test]
fn the_bounds_are_tight_on_smooth_cases() {
    for (name, a, b) in cases() {
        let e = ModalExponential::new(&a).unwrap();
        let mut motion = ProjectedMotion::new(&e, &b[0], &b[1]).unwrap();
        let m = a.rows();
        let y0: Vec<f64> = (0..m).map(|i| if i % 3 == 0 { 1.0 } else { 0.2 }).collect();
        motion.set_state(&e, &y0).unwrap();
        for lo in [0.0, 3.0, 10.0] {
            let hi = lo + 2.0 * std::f64::consts::PI;
            let bound = motion.bound(&e, lo, hi);
            let most = sampled_max(&motion, &e, lo, hi);
            for (mx, bd) in most
                .iter()
                .zip([bound.value, bound.rate, bound.acceleration])
            {
                assert!(
                    *mx <= bd && bd <= 10.0 * mx,
                    "{name} on [{lo}, {hi}]: {mx} vs bound {bd}"
                );
            }
        }
    }
}

/// Invalid intervals give infinite bounds, never NaN.
#[test]
fn invalid_intervals_give_infinite_bounds() {
    let a = Rotor::jeffcott(0.1).first_order(0.0);
    let e = ModalExponential::new(&a).unwrap();
    let motion = ProjectedMotion::new(&e, &[1.0, 0.0, 0.0, 0.0], &[0.0, 1.0, 0.0, 0.0]).unwrap();
    for (lo, hi) in [
        (2.0, 1.0),
        (f64::NAN, 1.0),
        (0.0, f64::INFINITY),
        (-1.0, 1.0),
    ] {
        let b = motion.bound(&e, lo, hi);
        assert_eq!(b.value, f64::INFINITY);
    }
}
