//! Free flight against the matrix exponential of the augmented first-order system (the forcing
//! as three more states: no particular solution, no modal form), computed independently by
//! `scripts/matrix_expm.py` in 30 digits (mpmath) and by scipy's `expm`: within 1e-13 relative
//! (‖Δy‖₂/‖y‖₂) of the 30-digit states, and never further from scipy's than scipy is from them
//! plus 1e-13, at spans 0.01 … 25 on every case — the Jeffcott rotor, a
//! non-symmetric bearing, a gyroscopic disk on cross-coupled bearings with an input force, the
//! ring with non-symmetric K_s, with ĉ = 0 (never decays), with repeated modes, with its
//! undamped modes exactly at the forcing frequency (singular, consistent), a free rigid-body
//! mode, repeated isotropic modes and a 20-DOF shaft.

use super::common::*;

/// The free-flight cases (the files with reference states).
const CASES: [&str; 10] = [
    "jeffcott",
    "bearing",
    "gyroscopic",
    "ring_nonsymmetric",
    "ring_undamped",
    "ring_repeated",
    "ring_resonant_unforced",
    "rigid_body",
    "repeated",
    "chain20",
];

#[test]
fn free_flight_matches_an_independent_matrix_exponential_to_1e_13() {
    for name in CASES {
        let case = Case::load(name);
        assert!(!case.states.is_empty(), "{name}: no reference states");
        let model = case.model();
        let mut free = started(&model, case.t0, case.start());
        let mut worst = 0.0f64;
        let mut scipy_worst = 0.0f64;
        for ((t, reference), (ts, scipy)) in case.states.iter().zip(&case.scipy) {
            assert_eq!(t, ts);
            let y = reached(&mut free, *t);
            let e = relative(&y, reference);
            let scipy_error = relative(scipy, reference);
            assert!(e <= 1e-13, "{name} at t = {t}: relative error {e:e}");
            assert!(
                relative(&y, scipy) <= scipy_error + 1e-13,
                "{name} at t = {t}: {:e} from scipy",
                relative(&y, scipy)
            );
            worst = worst.max(e);
            scipy_worst = scipy_worst.max(scipy_error);
        }
        eprintln!(
            "{name:24} n = {:2}: worst relative error {worst:.1e} (scipy's: {scipy_worst:.1e})",
            case.n
        );
    }
}

#[test]
fn a_start_state_is_returned_exactly() {
    let case = Case::load("chain20");
    let model = case.model();
    let mut free = started(&model, case.t0, case.start());
    assert_eq!(reached(&mut free, case.t0), case.y0);
}
