//! What the matrix-model tests share: runs of the planar and the matrix propagators reduced to
//! (kind, time, state) lists, and their comparison.

#![allow(dead_code, reason = "each test file uses a part")]

use rotor_rub::linalg::{RealMatrix, SecondOrder};
use rotor_rub::matrix::{MatrixModel, MatrixPropagator, MatrixState, Running, Station, Unbalance};
use rotor_rub::method::{Method, Options};
use rotor_rub::{Params, Problem, Propagator, events};

/// One switch: kind, time, state (positions then velocities).
#[derive(Clone, Debug)]
pub struct Switch {
    pub kind: &'static str,
    pub time: f64,
    pub state: Vec<f64>,
}

/// Options of `method` at `tol` (`None`: its default).
pub fn options(method: Method, tol: Option<f64>) -> Options {
    Options {
        tol,
        ..Options::with_method(method)
    }
}

/// The planar model's switches on `problem` up to `end`.
pub fn planar(problem: &Problem, method: Method, tol: Option<f64>, end: f64) -> Vec<Switch> {
    let mut p = Propagator::new(problem, &options(method, tol)).expect("the planar run starts");
    events(&mut p, end)
        .map(|e| {
            let e = e.expect("the planar run goes on");
            Switch {
                kind: e.kind.name(),
                time: e.time,
                state: vec![e.state.x, e.state.y, e.state.vx, e.state.vy],
            }
        })
        .collect()
}

/// A matrix model's switches from `(0, start)` up to `end`.
pub fn matrix<const CAP: usize>(
    model: &MatrixModel<CAP>,
    start: MatrixState<CAP>,
    method: Method,
    tol: Option<f64>,
    end: f64,
) -> Vec<Switch> {
    let mut p = MatrixPropagator::new(model, 0.0, start, &options(method, tol))
        .unwrap_or_else(|e| panic!("{method:?} starts: {e}"));
    events(&mut p, end)
        .map(|e| {
            let e = e.unwrap_or_else(|e| panic!("{method:?} goes on: {e}"));
            Switch {
                kind: e.kind.name(),
                time: e.time,
                state: e.state.as_slice().to_vec(),
            }
        })
        .collect()
}

/// The largest differences (time, state over the entries `entries` maps) of two switch lists,
/// after checking they have the same kinds in the same order (the first `count` of each).
pub fn difference(
    what: &str,
    got: &[Switch],
    want: &[Switch],
    count: usize,
    entries: &dyn Fn(&[f64]) -> Vec<f64>,
) -> (f64, f64) {
    if count == usize::MAX {
        assert_eq!(
            got.len(),
            want.len(),
            "{what}: {} switches against {}",
            got.len(),
            want.len()
        );
    }
    let mut worst = (0.0f64, 0.0f64);
    for (k, (a, b)) in got.iter().zip(want).take(count).enumerate() {
        assert_eq!(
            a.kind, b.kind,
            "{what}: switch {k} is {} at {}, expected {} at {}",
            a.kind, a.time, b.kind, b.time
        );
        let (ea, eb) = (entries(&a.state), entries(&b.state));
        let dy = ea
            .iter()
            .zip(&eb)
            .map(|(x, y)| (x - y).abs())
            .fold(0.0, f64::max);
        worst = (worst.0.max((a.time - b.time).abs()), worst.1.max(dy));
    }
    worst
}

/// The paper's Jeffcott rotor of `params` written as matrices (n = 2): M = I, C = 2ν I,
/// K = I, the stator fixed, K_c = K_s, the same offset, unbalance, input force and friction.
pub fn jeffcott(params: &Params) -> MatrixModel<4> {
    let identity = RealMatrix::<4>::identity(2).expect("2 × 2");
    let damping = RealMatrix::<4>::from_fn(2, 2, |i, j| {
        if i == j {
            2.0 * params.damping_ratio
        } else {
            0.0
        }
    })
    .expect("2 × 2");
    let zero = RealMatrix::<4>::zeros(2, 2).expect("2 × 2");
    let rotor = SecondOrder {
        mass: &identity,
        damping: &damping,
        gyroscopic: &zero,
        stiffness: &identity,
    };
    MatrixModel::new(
        &rotor,
        Running {
            speed_ratio: params.speed_ratio,
            phase: params.phase,
        },
        &[Unbalance {
            x: 0,
            y: 1,
            amount: params.mass_ratio * params.eccentricity_ratio,
            phase: 0.0,
        }],
        &[params.force_x, params.force_y],
        Station {
            rotor: (0, 1),
            stator: None,
            offset: (params.offset_x, params.offset_y),
            contact_stiffness: [[params.k_xx, params.k_xy], [params.k_yx, params.k_yy]],
            friction_coefficient: params.friction_coefficient,
            radius_ratio: params.radius_ratio,
        },
    )
    .expect("the Jeffcott rotor states")
}

/// The planar start of `problem` as a matrix state of the Jeffcott rotor.
pub fn jeffcott_start(problem: &Problem) -> MatrixState<4> {
    let s = problem.initial;
    MatrixState::new(&[s.x, s.y], &[s.vx, s.vy]).expect("two DOFs")
}

/// The state of a run at each of `times` (increasing), through events.
pub fn sampled<S, P: rotor_rub::Propagate<S>>(p: &mut P, times: &[f64]) -> Vec<S> {
    times
        .iter()
        .map(|&t| {
            while p.advance(t).expect("the run goes on").is_some() {}
            p.state()
        })
        .collect()
}

/// `count` times evenly spaced over (0, end].
pub fn grid(end: f64, count: usize) -> Vec<f64> {
    (1..=count).map(|k| end * k as f64 / count as f64).collect()
}

/// The planar model's rotor states (x, y, x', y') at `times`.
pub fn planar_samples(problem: &Problem, times: &[f64]) -> Vec<Vec<f64>> {
    let mut p = Propagator::new(problem, &options(Method::Taylor, Some(1e-13)))
        .expect("the planar run starts");
    sampled(&mut p, times)
        .into_iter()
        .map(|s| vec![s.x, s.y, s.vx, s.vy])
        .collect()
}

/// A matrix model's states at `times` (taylor at 1e-13).
pub fn matrix_samples<const CAP: usize>(
    model: &MatrixModel<CAP>,
    start: MatrixState<CAP>,
    times: &[f64],
) -> Vec<Vec<f64>> {
    let mut p = MatrixPropagator::new(model, 0.0, start, &options(Method::Taylor, Some(1e-13)))
        .expect("the run starts");
    sampled(&mut p, times)
        .into_iter()
        .map(|s| s.as_slice().to_vec())
        .collect()
}

/// The largest entry difference of two sample lists.
pub fn sample_distance(a: &[Vec<f64>], b: &[Vec<f64>]) -> f64 {
    a.iter()
        .zip(b)
        .flat_map(|(x, y)| x.iter().zip(y).map(|(u, v)| (u - v).abs()))
        .fold(0.0, f64::max)
}
