//! Free flight with no contact possible against the exact damped, harmonically forced
//! oscillator (derived here independently of the library, `docs/MODEL.md` §4).

use rotor_rub::reference::{Dop853Propagator, Rk45Propagator};
use std::f64::consts::PI;

use rotor_rub::{Params, Preset, Problem, Propagate, State, advance_to};

/// The exact free motion x'' + 2ν x' + x = F cos θ, y'' + 2ν y' + y = F sin θ, θ = ητ + φ0,
/// for ν < 1, from `s0` at `t0`.
///
/// Particular solution: xp = A cos θ + B sin θ with A = F(1 − η²)/D, B = 2νηF/D,
/// D = (1 − η²)² + (2νη)² (substitute and match the cos and sin terms); yp is xp with θ → θ − π/2,
/// i.e. yp = A sin θ − B cos θ. Homogeneous part e^{−νs}(C cos βs + S sin βs), β = √(1 − ν²),
/// s = τ − t0, with C = q0 − qp(t0) and S = (q0' − qp'(t0) + νC)/β.
fn exact(p: &Params, t0: f64, s0: &State, t: f64) -> State {
    let (nu, eta) = (p.damping_ratio, p.speed_ratio);
    let f = p.mass_ratio * p.eccentricity_ratio * eta * eta;
    let d = (1.0 - eta * eta).powi(2) + (2.0 * nu * eta).powi(2);
    let (a, b) = (f * (1.0 - eta * eta) / d, 2.0 * nu * eta * f / d);
    // (xp, xp', yp, yp') at time τ.
    let part = |tau: f64| {
        let th = eta * tau + p.phase;
        let (s, c) = th.sin_cos();
        (
            a * c + b * s,
            eta * (-a * s + b * c),
            a * s - b * c,
            eta * (a * c + b * s),
        )
    };
    let beta = (1.0 - nu * nu).sqrt();
    let hom = |q0: f64, v0: f64, s: f64| {
        let cc = q0;
        let ss = (v0 + nu * cc) / beta;
        let e = (-nu * s).exp();
        let (sn, cs) = (beta * s).sin_cos();
        (
            e * (cc * cs + ss * sn),
            e * ((-nu * cc + beta * ss) * cs + (-nu * ss - beta * cc) * sn),
        )
    };
    let (xp0, vxp0, yp0, vyp0) = part(t0);
    let (xp, vxp, yp, vyp) = part(t);
    let (xh, vxh) = hom(s0.x - xp0, s0.vx - vxp0, t - t0);
    let (yh, vyh) = hom(s0.y - yp0, s0.vy - vyp0, t - t0);
    State::new(xh + xp, yh + yp, vxh + vxp, vyh + vyp)
}

/// A problem that never reaches the clearance: no offset, η = 2 (steady radius F/√D ≈ 0.46),
/// starting near the steady orbit (a transient of amplitude ≈ 0.1 on top), τ0 = 0.7.
fn problem() -> Problem {
    let mut p = Preset::PaperText.problem();
    p.params.speed_ratio = 2.0;
    p.params.phase = 0.4;
    p.start_time = 0.7;
    // The steady orbit is the exact solution from any state after the transient has decayed;
    // e^{-ν·300} ≈ 5e-17.
    let steady = exact(
        &p.params,
        0.0,
        &State::default(),
        p.start_time + 300.0 * 2.0 * PI,
    );
    p.initial = State::new(
        steady.x + 0.05,
        steady.y - 0.03,
        steady.vx + 0.02,
        steady.vy + 0.04,
    );
    p
}

/// Largest component error over 20 samples per forcing period for 50 periods, and the largest
/// radius seen.
fn max_error<P: Propagate>(prop: &mut P, p: &Problem) -> (f64, f64) {
    let period = p.params.forcing_period();
    let mut worst: f64 = 0.0;
    let mut radius: f64 = 0.0;
    for k in 1..=1000 {
        let t = p.start_time + period * k as f64 / 20.0;
        let sample = advance_to(prop, t, |e| panic!("unexpected switch {e:?}")).unwrap();
        let want = exact(&p.params, p.start_time, &p.initial, t);
        let got = sample.state;
        let err = [
            got.x - want.x,
            got.y - want.y,
            got.vx - want.vx,
            got.vy - want.vy,
        ];
        worst = err.iter().fold(worst, |m, e| m.max(e.abs()));
        radius = radius.max(want.x.hypot(want.y));
    }
    (worst, radius)
}

#[test]
fn dop853_free_flight_matches_closed_form() {
    let p = problem();
    let mut prop = Dop853Propagator::new(&p, 1e-12).unwrap();
    let (err, radius) = max_error(&mut prop, &p);
    println!("DOP853 free flight, tol 1e-12, 50 periods: max error {err:.3e}, radius {radius:.3}");
    assert!(radius < 0.9, "the test case must stay clear of the stator");
    assert!(err <= 1e-10, "error {err:e}");
    assert_eq!(prop.event_count(), 0);
}

#[test]
fn rk45_free_flight_matches_closed_form() {
    let p = problem();
    let mut prop = Rk45Propagator::new(&p, 1e-12).unwrap();
    let (err, _) = max_error(&mut prop, &p);
    println!("RK45 free flight, tol 1e-12, 50 periods: max error {err:.3e}");
    // The 5(4) pair's global error over ~20 000 steps is a larger multiple of tol.
    assert!(err <= 1e-10, "error {err:e}");
}

/// The closed form above solves the ODE (checked against finite differences of itself), so the
/// comparison tests the integrators, not a typo.
#[test]
fn closed_form_satisfies_the_equations() {
    let p = problem();
    let (t0, s0) = (p.start_time, p.initial);
    let f = p.params.mass_ratio
        * p.params.eccentricity_ratio
        * p.params.speed_ratio
        * p.params.speed_ratio;
    let nu = p.params.damping_ratio;
    let at = |t: f64| exact(&p.params, t0, &s0, t);
    let s = at(t0);
    assert!((s.x - s0.x).abs() + (s.y - s0.y).abs() + (s.vx - s0.vx).abs() < 1e-15);
    for &t in &[1.0, 4.3, 17.9] {
        let dt = 1e-5;
        let (a, b) = (at(t - dt), at(t + dt));
        let ax = (b.vx - a.vx) / (2.0 * dt);
        let ay = (b.vy - a.vy) / (2.0 * dt);
        let vx = (b.x - a.x) / (2.0 * dt);
        let s = at(t);
        let th = p.params.speed_ratio * t + p.params.phase;
        assert!((vx - s.vx).abs() < 1e-8);
        assert!((ax + 2.0 * nu * s.vx + s.x - f * th.cos()).abs() < 1e-8);
        assert!((ay + 2.0 * nu * s.vy + s.y - f * th.sin()).abs() < 1e-8);
    }
}
