//! Invalid options give typed errors; awkward finite inputs never panic or produce NaN.

use proptest::prelude::*;
use rotor_rub::reference::{DEFAULT_TOLERANCE, Dop853Propagator, Rk45Propagator};
use rotor_rub::{Params, Problem, Propagate, PropagationError, State, advance_to};

use crate::common::paper;

#[test]
fn invalid_tolerances_are_typed_errors() {
    let p = paper(1.5);
    for tol in [
        0.0,
        -1e-8,
        1e-15,
        9.9e-15,
        2e-3,
        10.0,
        f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
    ] {
        let same = |e: PropagationError| match e {
            PropagationError::InvalidOption {
                what: "tol",
                value: x,
                valid,
                ..
            } => (x == tol || (x.is_nan() && tol.is_nan())) && valid.min == 1e-14,
            _ => false,
        };
        assert!(same(Dop853Propagator::new(&p, tol).err().unwrap()), "{tol}");
        assert!(same(Rk45Propagator::new(&p, tol).err().unwrap()), "{tol}");
    }
    assert!(Dop853Propagator::new(&p, 1e-14).is_ok());
    assert!(Rk45Propagator::new(&p, DEFAULT_TOLERANCE).is_ok());
    let mut bad = p;
    bad.params.speed_ratio = -1.0;
    assert!(matches!(
        Dop853Propagator::new(&bad, 1e-8),
        Err(PropagationError::InvalidProblem(_))
    ));
}

#[test]
fn invalid_targets_are_typed_errors() {
    let mut prop = Dop853Propagator::new(&paper(1.5), 1e-8).unwrap();
    prop.advance(1.0).unwrap();
    for target in [0.5, f64::NAN, f64::INFINITY] {
        assert!(matches!(
            prop.advance(target),
            Err(PropagationError::InvalidTarget { .. })
        ));
    }
    assert_eq!(prop.time(), 1.0);
}

#[test]
fn flutter_is_reported_as_divergence() {
    // `docs/MODEL.md` §6 case 3: a strong circulatory stator grows without bound in contact.
    let mut p = paper(1.5);
    p.params.k_xy = 15.0;
    p.params.k_yx = -10.0;
    p.params.offset_x = 0.0;
    p.params.offset_y = 0.0;
    p.initial = State::new(1.2, 0.0, 0.0, 1.0);
    let mut prop = Dop853Propagator::new(&p, 1e-8).unwrap();
    let r = advance_to(&mut prop, 500.0, |_| {});
    match r {
        Err(e @ PropagationError::Diverged { time, state }) => {
            assert!(state.is_finite());
            // The error is sticky: the propagator stays before it and repeats it.
            assert!(prop.time() < time);
            assert_eq!(prop.advance(time + 1.0), Err(e));
        }
        other => panic!("expected divergence, got {other:?}"),
    }
}

fn params() -> impl Strategy<Value = Problem> {
    (
        (
            0.2..5.0f64,
            0.05..1.5f64,
            0.0..60.0f64,
            -30.0..60.0f64,
            -30.0..60.0f64,
            0.0..60.0f64,
        ),
        (-0.5..0.5f64, -0.5..0.5f64, 0.0..6.3f64),
        (-2.0..2.0f64, -2.0..2.0f64, -2.0..2.0f64, -2.0..2.0f64),
    )
        .prop_map(
            |((eta, nu, kxx, kxy, kyx, kyy), (ex, ey, phase), (x, y, vx, vy))| {
                let base = paper(eta).params;
                Problem {
                    params: Params {
                        speed_ratio: eta,
                        damping_ratio: nu,
                        phase,
                        k_xx: kxx,
                        k_xy: kxy,
                        k_yx: kyx,
                        k_yy: kyy,
                        offset_x: ex,
                        offset_y: ey,
                        ..base
                    },
                    initial: State::new(x, y, vx, vy),
                    start_time: 0.0,
                }
            },
        )
}

/// Run 50 forcing periods with samples every period: Ok with finite states, or a typed error.
fn run_checked<P: Propagate>(mut prop: P, p: &Problem) -> Result<(), TestCaseError> {
    let period = p.params.forcing_period();
    for k in 1..=50 {
        let r = advance_to(&mut prop, period * k as f64, |e| {
            assert!(e.state.is_finite() && e.time.is_finite(), "{e:?}");
        });
        match r {
            Ok(s) => prop_assert!(s.state.is_finite(), "{s:?}"),
            Err(PropagationError::Diverged { time, .. }) => {
                prop_assert!(time.is_finite());
                return Ok(());
            }
            Err(PropagationError::StepSizeUnderflow { time }) => {
                prop_assert!(time.is_finite());
                return Ok(());
            }
            Err(e) => return Err(TestCaseError::fail(format!("unexpected error {e:?}"))),
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn awkward_inputs_never_panic(p in params(), tol_exp in 6..=12i32) {
        let tol = 10f64.powi(-tol_exp);
        run_checked(Dop853Propagator::new(&p, tol).unwrap(), &p)?;
        run_checked(Rk45Propagator::new(&p, tol.max(1e-9)).unwrap(), &p)?;
    }
}
