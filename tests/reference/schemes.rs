//! The Runge–Kutta cores on smooth problems with known solutions: order of the propagated
//! solution and of the dense output, the adaptive driver, and the 6-state phasor system.

use rotor_rub::reference::{
    Controller, Dop853, Integrator, Interpolant, OdeSystem, PhasorRotorSystem, Rk45, RotorSystem,
    Scheme, StepStart, Tolerance,
};
use rotor_rub::{Preset, Regime, State};

/// y'' = −y written as a system, exact solution (cos t, −sin t) from (1, 0).
fn oscillator(_t: f64, y: &[f64; 2]) -> [f64; 2] {
    [y[1], -y[0]]
}

fn exact(t: f64) -> [f64; 2] {
    [t.cos(), -t.sin()]
}

/// Error of the propagated solution after one step of size `h` and of the dense output at
/// θ = 0.37 of it.
fn one_step_errors<S: Scheme<2>>(h: f64) -> (f64, f64) {
    let y0 = [1.0, 0.0];
    let f0 = oscillator(0.0, &y0);
    let tol = Tolerance::uniform(1.0);
    let from = StepStart {
        t: 0.0,
        y: &y0,
        f0: &f0,
        h,
        tol: &tol,
    };
    let att = S::attempt(&oscillator, from);
    let (f1, dense) = S::accept(&oscillator, from, &att);
    let e1 = exact(h);
    let step_err = (att.y1[0] - e1[0]).abs().max((att.y1[1] - e1[1]).abs());
    assert_eq!(
        f1,
        oscillator(h, &att.y1),
        "f(t+h, y1) is the next first stage"
    );
    let tm = 0.37 * h;
    let ym = dense.eval(tm);
    let em = exact(tm);
    let dense_err = (ym[0] - em[0]).abs().max((ym[1] - em[1]).abs());
    // The dense output reproduces the step's ends.
    let y_end = dense.eval(h);
    assert!((y_end[0] - att.y1[0]).abs() < 1e-15 && (y_end[1] - att.y1[1]).abs() < 1e-15);
    (step_err, dense_err)
}

/// Observed local order: log2 of the error ratio when h is halved.
fn local_orders<S: Scheme<2>>(h: f64) -> (f64, f64) {
    let (s1, d1) = one_step_errors::<S>(h);
    let (s2, d2) = one_step_errors::<S>(h / 2.0);
    ((s1 / s2).log2(), (d1 / d2).log2())
}

#[test]
fn dopri5_local_orders() {
    // Local error of an order-p solution is O(h^{p+1}).
    let (step, dense) = local_orders::<Rk45>(0.2);
    assert!(
        (step - 6.0).abs() < 0.3,
        "5th-order solution: local order {step}"
    );
    assert!(
        (dense - 5.0).abs() < 0.3,
        "4th-order dense output: local order {dense}"
    );
}

#[test]
fn dop853_local_orders() {
    let (step, dense) = local_orders::<Dop853>(0.8);
    assert!(
        (step - 9.0).abs() < 0.4,
        "8th-order solution: local order {step}"
    );
    assert!(
        (dense - 8.0).abs() < 0.4,
        "7th-order dense output: local order {dense}"
    );
}

/// The adaptive driver on the oscillator over 10 periods: the global error follows the
/// tolerance and the steps are large.
fn adaptive_error<S: Scheme<2>>(tol: f64) -> (f64, u64) {
    let mut integ = Integrator::<S, 2>::new(
        &oscillator,
        0.0,
        [1.0, 0.0],
        Tolerance::uniform(tol),
        f64::INFINITY,
    );
    let end = 20.0 * std::f64::consts::PI;
    let mut worst: f64 = 0.0;
    while integ.time() < end {
        let step = integ.step(&oscillator, end).expect("smooth problem");
        let tm = 0.5 * (step.t0 + step.t1);
        let ym = step.dense.eval(tm);
        worst = worst.max((ym[0] - exact(tm)[0]).abs());
        worst = worst.max((step.y1[0] - exact(step.t1)[0]).abs());
    }
    assert_eq!(integ.time(), end, "the last step lands on the limit");
    (worst, integ.stats().accepted)
}

#[test]
fn adaptive_driver_meets_tolerance() {
    let (e8, n8) = adaptive_error::<Dop853>(1e-12);
    assert!(e8 < 2e-11, "DOP853 error {e8:e}");
    assert!(n8 < 400, "DOP853 took {n8} steps");
    let (e5, n5) = adaptive_error::<Rk45>(1e-10);
    assert!(e5 < 5e-9, "DOPRI5 error {e5:e}");
    assert!(n5 < 2000, "DOPRI5 took {n5} steps");
}

/// The optional PI stabilisation (DOP853's `BETA` option) keeps the accuracy.
#[test]
fn pi_controller_variant() {
    let beta = 0.04;
    let ctl = Controller {
        alpha: 1.0 / 8.0 - 0.2 * beta,
        beta,
        ..<Dop853 as Scheme<2>>::CONTROLLER
    };
    let mut integ = Integrator::<Dop853, 2>::new(
        &oscillator,
        0.0,
        [1.0, 0.0],
        Tolerance::uniform(1e-12),
        f64::INFINITY,
    )
    .with_controller(ctl);
    let end = 20.0 * std::f64::consts::PI;
    while integ.time() < end {
        integ.step(&oscillator, end).unwrap();
    }
    let y = integ.state();
    assert!((y[0] - exact(end)[0]).abs() < 2e-11);
}

/// DOP853 on the 6-state phasor system follows the 4-state system with explicit trigonometry.
#[test]
fn phasor_system_matches_trigonometric_forcing() {
    let p = Preset::Paper.problem();
    let s0 = State::new(0.4, -0.3, 0.2, 0.5);
    let tol = Tolerance::uniform(1e-12);
    for regime in [Regime::Free, Regime::Contact] {
        let sys4 = RotorSystem {
            params: p.params,
            regime,
            slip: 0.0,
        };
        let sys6 = PhasorRotorSystem {
            params: p.params,
            regime,
            slip: 0.0,
        };
        let t0 = 0.3;
        let mut a = Integrator::<Dop853, 4>::new(&sys4, t0, s0.to_array(), tol, 0.5);
        let y6 = PhasorRotorSystem::initial(&p.params, t0, &s0);
        let mut b = Integrator::<Dop853, 6>::new(&sys6, t0, y6, tol, 0.5);
        let end = 3.0;
        while a.time() < end {
            a.step(&sys4, end).unwrap();
        }
        while b.time() < end {
            b.step(&sys6, end).unwrap();
        }
        let ya = a.state();
        let yb = b.state();
        for i in 0..4 {
            assert!((ya[i] - yb[i]).abs() < 1e-10, "{regime:?} component {i}");
        }
        let theta = p.params.speed_ratio * end + p.params.phase;
        assert!((yb[4] - theta.cos()).abs() < 1e-11 && (yb[5] - theta.sin()).abs() < 1e-11);
        let _ = sys6.rhs(0.0, &yb);
    }
}

/// A right-hand side that turns non-finite is rejected until the step underflows: a typed error,
/// not a hang or a NaN state.
#[test]
fn non_finite_field_gives_step_size_underflow() {
    let blow_up = |t: f64, y: &[f64; 1]| [if t > 0.5 { f64::NAN } else { y[0] }];
    let mut integ =
        Integrator::<Dop853, 1>::new(&blow_up, 0.0, [1.0], Tolerance::uniform(1e-8), 0.1);
    let mut result = Ok(());
    while integ.time() < 2.0 {
        if let Err(e) = integ.step(&blow_up, 2.0) {
            result = Err(e);
            break;
        }
        assert!(integ.state()[0].is_finite());
    }
    assert!(matches!(
        result,
        Err(rotor_rub::PropagationError::StepSizeUnderflow { time }) if time <= 0.5
    ));
}
