//! The stator ring with mass (issue 28 item 5) against an independent oracle
//! (`matrix_oracle/ring.rs`: the 8-state regime fields written by hand, DOP853 of another crate
//! at tol 1e-13, events bisected): every method, every case of `matrix_oracle/cases.rs`, event
//! by event — kind, time, state.
//!
//! Pass (the issue's): switch times within 1e-8 for dop853, hybrid, taylor at tol 1e-13, within
//! 1e-6 for analytic at its default tolerance; rk45 (fifth order) within 1e-8 at the tightest
//! tolerance of its range, 1e-14 (at 1e-13 it errs by 1.2e-8 on the non-symmetric case).

mod matrix_oracle {
    pub mod cases;
    pub mod ring;
}

use std::sync::OnceLock;

use matrix_oracle::cases::{CASES, Case, PERIODS};
use matrix_oracle::ring::{self, OracleRun};
use rotor_rub::Propagate;
use rotor_rub::events;
use rotor_rub::matrix::{
    MatrixPropagator, MatrixState, NumericalFree, NumericalSolver, RingModel, TaylorContact,
    ring_model, ring_start, split,
};
use rotor_rub::method::{Method, Options};

/// The oracle's run of each case, computed once for every test of this file.
fn oracle(index: usize) -> &'static OracleRun {
    static RUNS: OnceLock<Vec<OnceLock<OracleRun>>> = OnceLock::new();
    let runs = RUNS.get_or_init(|| CASES.iter().map(|_| OnceLock::new()).collect());
    runs[index].get_or_init(|| {
        let case = &CASES[index];
        let problem = case.problem();
        let y0: [f64; 8] = ring_start(&problem)
            .as_slice()
            .try_into()
            .expect("eight states");
        ring::run(
            &problem.params,
            y0,
            0.0,
            PERIODS * problem.params.forcing_period(),
        )
    })
}

fn model(case: &Case) -> RingModel {
    ring_model(&case.problem().params).expect("the ring model states")
}

/// Run `method` at `tol` on every case and compare with the oracle: same kinds, times within
/// `time_bound`, states within `state_bound`; the largest time difference is returned.
fn against_oracle(method: Method, tol: Option<f64>, time_bound: f64, state_bound: f64) -> f64 {
    let options = Options {
        tol,
        ..Options::with_method(method)
    };
    runs_against_oracle(
        &format!("{method:?}"),
        &|model, start| {
            Box::new(MatrixPropagator::new(model, 0.0, start, &options).expect("the method starts"))
        },
        time_bound,
        state_bound,
    )
}

/// A run of one method on a ring model from a start.
type Run<'r> =
    dyn for<'a> Fn(&'a RingModel, MatrixState<8>) -> Box<dyn Propagate<MatrixState<8>> + 'a> + 'r;

/// [`against_oracle`] for any way of running the ring (`method` names it in messages).
fn runs_against_oracle(method: &str, run: &Run<'_>, time_bound: f64, state_bound: f64) -> f64 {
    let mut worst_all = 0.0f64;
    for (index, case) in CASES.iter().enumerate() {
        let problem = case.problem();
        let model = model(case);
        let end = PERIODS * problem.params.forcing_period();
        let mut propagator = run(&model, ring_start(&problem));
        let got: Vec<_> = events(&mut *propagator, end)
            .collect::<Result<_, _>>()
            .unwrap_or_else(|e| panic!("{}: {method} failed: {e}", case.name));
        let want = &oracle(index).events;
        if case.compared == usize::MAX {
            assert_eq!(
                got.len(),
                want.len(),
                "{} ({}): {method} finds {} switches, the oracle {}",
                case.name,
                case.covers,
                got.len(),
                want.len()
            );
        }
        let mut worst = (0.0f64, 0.0f64);
        for (k, (a, b)) in got.iter().zip(want).take(case.compared).enumerate() {
            assert_eq!(
                a.kind.name(),
                b.kind,
                "{}: event {k} at {} is {:?} for {method}, {} at {} for the oracle",
                case.name,
                a.time,
                a.kind,
                b.kind,
                b.time
            );
            let dt = (a.time - b.time).abs();
            let dy = a
                .state
                .as_slice()
                .iter()
                .zip(&b.state)
                .map(|(x, y)| (x - y).abs())
                .fold(0.0, f64::max);
            assert!(
                dt <= time_bound && dy <= state_bound,
                "{}: event {k} ({}) at {}: {method} differs from the oracle by {dt:e} in time, {dy:e} in state",
                case.name,
                b.kind,
                b.time
            );
            worst = (worst.0.max(dt), worst.1.max(dy));
        }
        println!(
            "{method} {}: {} switches compared, worst time {:.1e}, state {:.1e}",
            case.name,
            got.len().min(case.compared),
            worst.0,
            worst.1
        );
        worst_all = worst_all.max(worst.0);
    }
    worst_all
}

#[test]
fn dop853_agrees_with_the_oracle() {
    against_oracle(Method::Dop853, Some(1e-13), 1e-8, 1e-6);
}

#[test]
fn rk45_agrees_with_the_oracle() {
    against_oracle(Method::Rk45, Some(1e-14), 1e-8, 1e-6);
}

#[test]
fn hybrid_agrees_with_the_oracle() {
    against_oracle(Method::Hybrid, Some(1e-13), 1e-8, 1e-6);
}

#[test]
fn taylor_agrees_with_the_oracle() {
    against_oracle(Method::Taylor, Some(1e-13), 1e-8, 1e-6);
}

#[test]
fn analytic_agrees_with_the_oracle_at_its_default_tolerance() {
    against_oracle(Method::Analytic, None, 1e-6, 1e-4);
}

/// The contact solvers alone: hybrid's DOP853 and taylor's Taylor contact behind a numerical
/// free flight (`NumericalFree`, DOP853 at 1e-14) instead of the exact one.
#[test]
fn the_contact_solvers_with_a_numerical_free_flight_agree_with_the_oracle() {
    runs_against_oracle(
        "hybrid (numerical free flight)",
        &|model, start| {
            let free = NumericalFree::new(model).expect("the free flight starts");
            let contact = NumericalSolver::<rotor_rub::reference::Dop853, _, _>::new(model, 1e-13);
            Box::new(split(model, free, contact, 0.0, start).expect("the method starts"))
        },
        1e-8,
        1e-6,
    );
    runs_against_oracle(
        "taylor (numerical free flight)",
        &|model, start| {
            let free = NumericalFree::new(model).expect("the free flight starts");
            let contact = TaylorContact::new(model, 1e-13);
            Box::new(split(model, free, contact, 0.0, start).expect("the method starts"))
        },
        1e-8,
        1e-6,
    );
}

#[test]
fn the_cases_cover_what_the_issue_lists() {
    // Each case shows what it is there for (on the oracle's own run).
    let kinds = |i: usize, kind: &str| oracle(i).events.iter().filter(|e| e.kind == kind).count();
    let find = |name: &str| CASES.iter().position(|c| c.name == name).expect("case");
    let sparse = find("sparse");
    assert!(oracle(sparse).events.len() <= 10);
    assert!(oracle(find("heavy")).events.len() >= 100);
    let inside = find("start inside");
    assert_eq!(oracle(inside).events.first().map(|e| e.kind), Some("exit"));
    let reversal = find("reversal");
    assert!(kinds(reversal, "reverse") >= 5 && kinds(reversal, "roll") >= 20);
    // Rolling while the ring moves: the ring's centre away from rest during rolling.
    let rolling = find("rolling ring");
    let moving = oracle(rolling)
        .samples
        .iter()
        .filter(|s| s.2 == ring::Phase::Rolling)
        .map(|s| s.1[2].hypot(s.1[3]))
        .fold(0.0, f64::max);
    assert!(kinds(rolling, "roll") >= 10 && moving > 0.3, "{moving}");
    // The undamped ring keeps moving between contacts: its speed in free flight stays up.
    let undamped = find("undamped ring");
    let late_free_speed = oracle(undamped)
        .samples
        .iter()
        .filter(|s| s.2 == ring::Phase::Free && s.0 > 30.0)
        .map(|s| s.1[6].hypot(s.1[7]))
        .fold(0.0, f64::max);
    assert!(late_free_speed > 0.5, "{late_free_speed}");
}
