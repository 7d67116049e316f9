//! Self-convergence on the paper's Fig. 2 cases: DOP853 at tol 1e-12 against tol 1e-13.

use rotor_rub::EventKind;
use rotor_rub::compare::compare_events;
use rotor_rub::reference::{Dop853Propagator, Rk45Propagator};

use crate::common::{paper, run_events};

const SPEEDS: [f64; 6] = [1.0, 1.5, 2.0, 2.5, 3.0, 3.5];

#[test]
fn dop853_self_convergence_on_fig2_cases() {
    let mut worst: f64 = 0.0;
    for eta in SPEEDS {
        let p = paper(eta);
        let end = p.start_time + 20.0 * p.params.forcing_period();
        let a = run_events(&mut Dop853Propagator::new(&p, 1e-12).unwrap(), end).unwrap();
        let b = run_events(&mut Dop853Propagator::new(&p, 1e-13).unwrap(), end).unwrap();
        // The chaotic case (η = 1.5) separates exponentially: compare its first 20 switches.
        let (a, b) = if eta == 1.5 {
            (&a[..a.len().min(20)], &b[..b.len().min(20)])
        } else {
            (&a[..], &b[..])
        };
        assert!(a.len() >= 2, "η = {eta}: the case must rub");
        let c = compare_events(a, b, 1e-10);
        println!(
            "η = {eta}: {} switches, max |Δt| = {:.2e} (index {:?}), max |Δs| = {:.2e}",
            a.len(),
            c.max_time_difference,
            c.max_time_index,
            c.max_state_difference
        );
        assert_eq!(c.unmatched, 0, "η = {eta}: {c:?}");
        assert!(c.agrees(), "η = {eta}: {c:?}");
        worst = worst.max(c.max_time_difference);
        // Switches alternate, starting with an entry (the preset starts in free flight).
        for (i, e) in a.iter().enumerate() {
            let want = if i % 2 == 0 {
                EventKind::Enter
            } else {
                EventKind::Exit
            };
            assert_eq!(e.kind, want);
        }
    }
    println!("largest switch-time difference over the Fig. 2 cases: {worst:.2e}");
}

/// RK45 agrees with DOP853 on the first switches of a periodic case at a tight tolerance.
#[test]
fn rk45_agrees_with_dop853() {
    let p = paper(3.5);
    let end = p.start_time + 10.0 * p.params.forcing_period();
    let a = run_events(&mut Dop853Propagator::new(&p, 1e-12).unwrap(), end).unwrap();
    let b = run_events(&mut Rk45Propagator::new(&p, 1e-12).unwrap(), end).unwrap();
    let c = compare_events(&a, &b, 1e-8);
    println!(
        "RK45 vs DOP853 (η = 3.5, tol 1e-12): {} switches, max |Δt| = {:.2e}",
        a.len(),
        c.max_time_difference
    );
    assert!(c.agrees(), "{c:?}");
}
