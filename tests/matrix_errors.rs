//! Bad input to `MatrixPropagator` is a typed error naming the value (never a panic, a NaN or a
//! silent wrong answer), and a motion that grows without bound ends a run of every method with
//! `Diverged`.

mod matrix_common;

use matrix_common::{jeffcott, options};
use rotor_rub::linalg::{RealMatrix, SecondOrder};
use rotor_rub::matrix::{
    MatrixError, MatrixModel, MatrixPropagator, MatrixState, Running, Station, Unbalance,
};
use rotor_rub::method::{ContactScheme, Method, Options};
use rotor_rub::propagate::PropagationError;
use rotor_rub::{Preset, events};

const METHODS: [Method; 5] = [
    Method::Dop853,
    Method::Rk45,
    Method::Hybrid,
    Method::Taylor,
    Method::Analytic,
];

fn start(q: &[f64], v: &[f64]) -> MatrixState<4> {
    MatrixState::new(q, v).expect("a state")
}

#[test]
fn a_start_of_the_wrong_size_or_not_finite_is_refused() {
    let model = jeffcott(&Preset::Paper.problem().params);
    for method in METHODS {
        let o = options(method, None);
        let three = MatrixState::<4>::new(&[0.1], &[0.0]).expect("one DOF");
        assert!(matches!(
            MatrixPropagator::new(&model, 0.0, three, &o).err(),
            Some(PropagationError::InvalidModel(MatrixError::Shape {
                got: 2,
                expected: 4,
                ..
            }))
        ));
        // (MatrixState::new refuses it too; from_array does not check.)
        let nan = MatrixState::<4>::from_array(2, [0.1, f64::NAN, 0.0, 0.0]);
        assert!(matches!(
            MatrixPropagator::new(&model, 0.0, nan, &o).err(),
            Some(PropagationError::InvalidModel(MatrixError::NonFinite {
                index: 1,
                ..
            }))
        ));
        let fine = start(&[0.1, 0.0], &[0.0, 0.0]);
        assert!(matches!(
            MatrixPropagator::new(&model, f64::INFINITY, fine, &o).err(),
            Some(PropagationError::InvalidTarget { .. })
        ));
    }
}

#[test]
fn options_out_of_range_or_not_taken_are_refused() {
    let model = jeffcott(&Preset::Paper.problem().params);
    let s = start(&[0.1, 0.0], &[0.0, 0.0]);
    for method in METHODS {
        let err = MatrixPropagator::new(&model, 0.0, s, &options(method, Some(1.0))).err();
        assert!(
            matches!(
                err,
                Some(PropagationError::InvalidOption {
                    what: "tol",
                    value: 1.0,
                    ..
                })
            ),
            "{method:?}: {err:?}"
        );
    }
    let exprb2 = Options {
        contact_scheme: ContactScheme::Exprb2,
        ..Options::with_method(Method::Analytic)
    };
    let err = MatrixPropagator::new(&model, 0.0, s, &exprb2).err();
    assert!(
        matches!(
            err,
            Some(PropagationError::InvalidModel(MatrixError::MethodOption {
                method: "analytic",
                ..
            }))
        ),
        "{err:?}"
    );
    let stepped = Options {
        step: Some(0.01),
        ..Options::with_method(Method::Analytic)
    };
    let err = MatrixPropagator::new(&model, 0.0, s, &stepped).err();
    assert!(
        matches!(
            err,
            Some(PropagationError::InvalidModel(
                MatrixError::MethodOption { .. }
            )) | Some(PropagationError::InvalidOption { .. })
        ),
        "{err:?}"
    );
}

/// A Jeffcott rotor with negative damping (a self-excited instability) and a soft contact
/// spring that cannot hold it.
fn unstable() -> MatrixModel<4> {
    let identity = RealMatrix::<4>::identity(2).expect("2 × 2");
    let damping =
        RealMatrix::<4>::from_fn(2, 2, |i, j| if i == j { -0.2 } else { 0.0 }).expect("2 × 2");
    let zero = RealMatrix::<4>::zeros(2, 2).expect("2 × 2");
    MatrixModel::new(
        &SecondOrder {
            mass: &identity,
            damping: &damping,
            gyroscopic: &zero,
            stiffness: &identity,
        },
        Running {
            speed_ratio: 1.3,
            phase: 0.0,
        },
        &[Unbalance {
            x: 0,
            y: 1,
            amount: 0.01,
            phase: 0.0,
        }],
        &[],
        Station {
            rotor: (0, 1),
            stator: None,
            offset: (0.0, 0.0),
            contact_stiffness: [[0.5, 0.0], [0.0, 0.5]],
            friction_coefficient: 0.0,
            radius_ratio: 1.0,
        },
    )
    .expect("the model states")
}

#[test]
fn a_growing_motion_ends_every_method_with_diverged() {
    let model = unstable();
    for method in METHODS {
        let mut p = MatrixPropagator::new(
            &model,
            0.0,
            start(&[0.1, 0.0], &[0.0, 0.0]),
            &options(method, None),
        )
        .expect("the run starts");
        let end = events(&mut p, 1e4).find_map(Result::err);
        assert!(
            matches!(end, Some(PropagationError::Diverged { time, .. }) if time > 10.0 && time < 1e4),
            "{method:?}: {end:?}"
        );
    }
}
