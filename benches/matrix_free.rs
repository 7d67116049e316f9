//! Exact free flight of rotors from matrices and its contact search (`rotor_rub::matrix::
//! ExactFree`), on the ring with mass (n = 4, ĉ = 0: it rings for ever and is searched for
//! ever) and a 20-DOF shaft (`tests/data/matrix_free/`):
//!
//! * `matrix_free/decompose/{ring,chain20}`: `ExactFree::new` (modal form, harmonic and
//!   constant responses, projections on the station);
//! * `matrix_free/periods/{ring,chain20}`: start a flight and search it, period by period, over
//!   the whole forcing periods of the span its data file proves contact-free (the span of its
//!   reference states: 9 periods of the ring, whose non-symmetric undamped stator grows, 5 of
//!   the chain); the work counters per period are printed;
//! * `matrix_free/state/{ring,chain20}`: one state at a target in the proved-free horizon;
//! * `matrix_free/contact/{ring,chain20}`: start a flight and find its first contact, refined.

mod common;

#[allow(dead_code)]
#[path = "../tests/matrix_free/common.rs"]
mod cases;

use rotor_rub::driver::SegmentStart;
use std::hint::black_box;

use cases::{Case, Free, Model, run_to};
use rotor_rub::driver::{Located, SegmentSolver};
use rotor_rub::matrix::ExactFree;
use rotor_rub::propagate::Regime;

fn restart(free: &mut Free<'_>, case: &Case) {
    free.start(SegmentStart {
        regime: Regime::Free,
        slip: 0.0,
        time: case.t0,
        state: case.start(),
    })
    .unwrap();
}

fn flight(c: &mut criterion::Criterion, label: &str, file: &str) {
    let case = Case::load(file);
    let model: Box<Model> = Box::new(case.model());
    let period = 2.0 * std::f64::consts::PI / case.speed;
    // The span the data file's reference states cover contact-free (the script scales the
    // start so that |P - offset| <= 0.8 on it).
    let span = case.states.last().map_or(0.0, |s| s.0) - case.t0;
    let periods = (span / period).floor() as usize;
    assert!(periods > 0, "{label}: no whole period in the checked span");
    c.bench_function(&format!("matrix_free/decompose/{label}"), |b| {
        b.iter(|| ExactFree::new(black_box(&*model)).unwrap())
    });
    let mut free: Box<Free<'_>> = Box::new(ExactFree::new(&*model).unwrap());
    // The work of one run, per period.
    restart(&mut free, &case);
    let before = free.work();
    for k in 1..=periods {
        let r = run_to(&mut *free, case.t0 + k as f64 * period);
        assert!(
            matches!(r, Located::Reached(_)),
            "{label}: contact in the free case"
        );
    }
    let w = free.work();
    let per = |a: u64, b: u64| (a - b) as f64 / periods as f64;
    eprintln!(
        "{label}: {periods} periods; per forcing period {:.1} chunks, {:.1} evaluations, {:.1} bound tests; settled: {}",
        per(w.chunks, before.chunks),
        per(w.evaluations, before.evaluations),
        per(w.bound_tests, before.bound_tests),
        w.settled - before.settled,
    );
    c.bench_function(&format!("matrix_free/periods/{label}"), |b| {
        b.iter(|| {
            restart(&mut free, &case);
            for k in 1..=periods {
                black_box(run_to(&mut *free, case.t0 + k as f64 * period));
            }
        })
    });
    restart(&mut free, &case);
    let target = case.t0 + 0.9 * period;
    run_to(&mut *free, target);
    c.bench_function(&format!("matrix_free/state/{label}"), |b| {
        b.iter(|| free.locate(black_box(target)))
    });
}

fn contact(c: &mut criterion::Criterion, label: &str, file: &str) {
    let case = Case::load(file);
    let model: Box<Model> = Box::new(case.model());
    let mut free: Box<Free<'_>> = Box::new(ExactFree::new(&*model).unwrap());
    let end = case.contact.unwrap() + 1.0;
    restart(&mut free, &case);
    assert!(matches!(run_to(&mut *free, end), Located::Switch(_)));
    c.bench_function(&format!("matrix_free/contact/{label}"), |b| {
        b.iter(|| {
            restart(&mut free, &case);
            black_box(run_to(&mut *free, end))
        })
    });
}

fn main() {
    let mut c = common::criterion();
    flight(&mut c, "ring", "ring_undamped");
    flight(&mut c, "chain20", "chain20");
    contact(&mut c, "ring", "ring_undamped_contact");
    contact(&mut c, "chain20", "chain20_contact");
    c.final_summary();
}
