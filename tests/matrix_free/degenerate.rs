//! The cases a user meets that must not be refused, and the one that is: a forced undamped
//! mode exactly at the running speed (a clear error naming η); a constant force along a free
//! rigid-body mode (no static deflection). Checked against nalgebra's exponential of the
//! augmented system (independent of the particular solution).

use rotor_rub::driver::SegmentStart;
use rotor_rub::linalg::LinalgError;
use rotor_rub::matrix::{ExactFree, MatrixError};

use super::common::*;

fn jeffcott(damping: f64, speed: f64) -> Case {
    let mut case = Case::load("jeffcott");
    case.damping = vec![damping, 0.0, 0.0, damping];
    case.speed = speed;
    case
}

#[test]
fn a_forced_undamped_mode_at_the_running_speed_is_refused_naming_the_speed() {
    let case = jeffcott(0.0, 1.0);
    let model = case.model();
    let err = ExactFree::new(&model).unwrap_err();
    assert_eq!(
        err,
        Error::InvalidModel(MatrixError::Linalg(LinalgError::Resonance {
            speed_ratio: 1.0
        }))
    );
    let message = err.to_string();
    assert!(message.contains("η = 1"), "{message}");
    // Off resonance, or damped at resonance, it runs.
    assert!(ExactFree::new(&jeffcott(0.0, 1.0 + 1e-9).model()).is_ok());
    assert!(ExactFree::new(&jeffcott(1e-9, 1.0).model()).is_ok());
}

#[test]
fn an_undamped_ring_at_the_forcing_frequency_without_forcing_runs_exactly() {
    // The accuracy test covers it against scipy; here: the model is accepted and its ring
    // keeps ringing at η (bounded, no secular growth).
    let case = Case::load("ring_resonant_unforced");
    let model = case.model();
    let mut free = started(&model, case.t0, case.start());
    let far = case.t0 + 2000.0;
    let y = reached(&mut free, far);
    let reference = augmented_state(&case, case.t0, &case.y0, far);
    assert!(
        relative(&y, &reference) < 1e-10,
        "{:e}",
        relative(&y, &reference)
    );
    assert!(y[2].abs() < 1.0 && y[3].abs() < 1.0);
}

#[test]
fn a_free_rigid_body_mode_runs_and_a_force_along_it_is_refused() {
    let mut case = Case::load("rigid_body");
    // An internal force (equal and opposite on the two bodies) does not push the free
    // translation: consistent, a static deflection exists.
    case.input = vec![0.02, -0.01, -0.02, 0.01];
    let model = case.model();
    let mut free = started(&model, case.t0, case.start());
    for t in [0.5, 3.0, 17.0] {
        let y = reached(&mut free, t);
        let reference = augmented_state(&case, case.t0, &case.y0, t);
        let e = relative(&y, &reference);
        assert!(e < 1e-12, "t = {t}: {e:e}");
    }
    // A net force on the free body: it would accelerate for ever; no static deflection.
    case.input = vec![0.02, 0.0, 0.0, 0.0];
    let err = ExactFree::new(&case.model()).unwrap_err();
    assert!(
        matches!(
            err,
            Error::InvalidModel(MatrixError::Linalg(LinalgError::StaticSingular { .. }))
        ),
        "{err:?}"
    );
}

#[test]
fn a_state_of_the_wrong_size_is_a_typed_error() {
    use rotor_rub::driver::SegmentSolver;
    use rotor_rub::propagate::Regime;
    let case = Case::load("jeffcott");
    let model = case.model();
    let mut free = ExactFree::new(&model).unwrap();
    let wrong = State::new(&[0.0; 3], &[0.0; 3]).unwrap();
    let err = free
        .start(SegmentStart {
            regime: Regime::Free,
            slip: 0.0,
            time: 0.0,
            state: wrong,
        })
        .unwrap_err();
    assert!(
        matches!(err, Error::InvalidModel(MatrixError::Shape { .. })),
        "{err:?}"
    );
}

#[test]
fn the_solver_runs_behind_an_arc_and_a_reference_alike() {
    use std::sync::Arc;
    let case = Case::load("ring_undamped_contact");
    let shared = Arc::new(case.model());
    let mut by_arc: ExactFree<Arc<Model>, CAP> = ExactFree::new(shared.clone()).unwrap();
    let at = SegmentStart {
        regime: rotor_rub::propagate::Regime::Free,
        slip: 0.0,
        time: case.t0,
        state: case.start(),
    };
    rotor_rub::driver::SegmentSolver::start(&mut by_arc, at).unwrap();
    let mut by_ref = started(&shared, case.t0, case.start());
    let end = case.t0 + 10.0;
    assert_eq!(contact(&mut by_arc, end), contact(&mut by_ref, end));
}
