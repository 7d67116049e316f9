//! A 4-node rotor from matrices (issue 29 item 3): a lumped shaft of four stations — two
//! bearing journals and two disks — written as a textbook model: the shaft's bending stiffness
//! between neighbouring stations, bearings with non-symmetric stiffness and damping (cross
//! terms, as oil-film bearings have), light structural damping at the disks, the disks'
//! gyroscopic coupling as a skew-symmetric G (a reduced model's translational coupling, ηG in
//! the damping), an unbalance on one disk and the rub station at the other against a fixed
//! stator. Positions (x0, y0, x1, y1, x2, y2, x3, y3), n = 8, CAP = 16.
//!
//! Each method against DOP853 at tol 1e-13 on the full system, with and without friction:
//! the same switches, times within 1e-8.

mod matrix_common;

use matrix_common::{difference, matrix};
use rotor_rub::linalg::{RealMatrix, SecondOrder};
use rotor_rub::matrix::{MatrixModel, MatrixState, Running, Station, Unbalance};
use rotor_rub::method::Method;

const CAP: usize = 16;
const N: usize = 8;

/// The 4-node rotor at speed `eta` with friction `mu` at the station.
fn rotor(eta: f64, unbalance: f64, mu: f64) -> MatrixModel<CAP> {
    let mut m = [[0.0; N]; N];
    let mut c = [[0.0; N]; N];
    let mut g = [[0.0; N]; N];
    let mut k = [[0.0; N]; N];
    for (i, mass) in [0.2, 1.0, 1.0, 0.2].into_iter().enumerate() {
        m[2 * i][2 * i] = mass;
        m[2 * i + 1][2 * i + 1] = mass;
    }
    // Shaft segments 0-1, 1-2, 2-3 (bending stiffness per station pair, both planes).
    for (a, b, ks) in [(0, 1, 4.0), (1, 2, 6.0), (2, 3, 4.0)] {
        for d in 0..2 {
            let (i, j) = (2 * a + d, 2 * b + d);
            k[i][i] += ks;
            k[j][j] += ks;
            k[i][j] -= ks;
            k[j][i] -= ks;
        }
    }
    // Bearings at the journals: non-symmetric stiffness and damping.
    let bearings = [
        (0, [[3.0, 0.8], [-0.6, 4.0]], [[0.3, 0.05], [0.03, 0.4]]),
        (3, [[3.5, -0.5], [0.7, 3.0]], [[0.35, -0.04], [0.02, 0.3]]),
    ];
    for (node, kb, cb) in bearings {
        for r in 0..2 {
            for s in 0..2 {
                k[2 * node + r][2 * node + s] += kb[r][s];
                c[2 * node + r][2 * node + s] += cb[r][s];
            }
        }
    }
    // The disks: structural damping and gyroscopic coupling (polar inertia J_p).
    for (node, jp) in [(1, 0.3), (2, 0.25)] {
        c[2 * node][2 * node] += 0.02;
        c[2 * node + 1][2 * node + 1] += 0.02;
        g[2 * node][2 * node + 1] = jp;
        g[2 * node + 1][2 * node] = -jp;
    }
    let matrix =
        |a: &[[f64; N]; N]| RealMatrix::<CAP>::from_fn(N, N, |i, j| a[i][j]).expect("8 × 8");
    let (m, c, g, k) = (matrix(&m), matrix(&c), matrix(&g), matrix(&k));
    MatrixModel::new(
        &SecondOrder {
            mass: &m,
            damping: &c,
            gyroscopic: &g,
            stiffness: &k,
        },
        Running {
            speed_ratio: eta,
            phase: 0.0,
        },
        &[Unbalance {
            x: 4,
            y: 5,
            amount: unbalance,
            phase: 0.0,
        }],
        &[],
        Station {
            rotor: (2, 3),
            stator: None,
            offset: (0.1, -0.05),
            contact_stiffness: [[30.0, 0.0], [0.0, 30.0]],
            friction_coefficient: mu,
            radius_ratio: 10.0,
        },
    )
    .expect("the 4-node rotor states")
}

fn start() -> MatrixState<CAP> {
    MatrixState::rest(N).expect("8 DOFs")
}

/// Every method against DOP853 at 1e-13, 10 forcing periods at η = 1.3 (11 contacts
/// frictionless, 15 with μ = 0.2).
fn against_dop853(mu: f64) {
    let (eta, end) = (1.3, 10.0 * 2.0 * std::f64::consts::PI / 1.3);
    let model = rotor(eta, 1.0, mu);
    let want = matrix(&model, start(), Method::Dop853, Some(1e-13), end);
    assert!(want.len() >= 20, "{} switches", want.len());
    for (method, tol, bound) in [
        (Method::Rk45, Some(1e-14), 1e-8),
        (Method::Hybrid, Some(1e-13), 1e-8),
        (Method::Taylor, Some(1e-13), 1e-8),
        (Method::Analytic, None, 1e-6),
    ] {
        let got = matrix(&model, start(), method, tol, end);
        let (dt, dy) = difference(
            &format!("μ = {mu}, {method:?}"),
            &got,
            &want,
            usize::MAX,
            &|y| y.to_vec(),
        );
        println!(
            "4-node μ = {mu} {method:?}: {} switches, time {dt:.1e}, state {dy:.1e}",
            got.len()
        );
        assert!(dt <= bound, "μ = {mu}, {method:?}: {dt:e}");
    }
}

#[test]
fn every_method_agrees_with_dop853_without_friction() {
    against_dop853(0.0);
}

#[test]
fn every_method_agrees_with_dop853_with_friction() {
    against_dop853(0.2);
}
