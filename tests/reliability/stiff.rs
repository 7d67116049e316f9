//! Item 2 of issue 32: the analytic method's tolerance on very stiff stators. Two error sources,
//! both independent of the tolerance before:
//!
//! 1. The particular constants of a linearized contact segment (Cramer's rule) leave a residual
//!    force of ε·cond(Kl)·‖Kl‖·|c| in the equations they solve: up to 5.6e-8 at K̂ = 1e5 near
//!    z = 1 (Kl's condition 1e5), which the closed form's velocity follows at that rate
//!    whatever the sub-step. Now refined once (generated `contact_particular_residual` and
//!    `contact_particular_correction`).
//! 2. Every sub-step starts a closed form from a state rounded to ulps of |q|, which the stiff
//!    mode turns into a velocity error ω·δ: below a truncation target of ~4ε·ω more sub-steps
//!    only add rounding (tol 1e-14 took 730 sub-steps per contact and ended further off than
//!    3e-13 with 310). exprb43's step control now never targets less.

use rotor_rub::analytic::linear::Linearization;
use rotor_rub::analytic::segment::Segment;
use rotor_rub::coefficients::ModelParams;
use rotor_rub::{Event, Method, Params, Preset, Problem, State, field};

use super::common::switches;

/// The paper preset with an isotropic (`cross` = 0) or nearly singular stiff stator.
fn stiff_paper(k: f64, cross: f64) -> Problem {
    let mut p = Preset::Paper.problem();
    (p.params.k_xx, p.params.k_yy) = (k, k);
    (p.params.k_xy, p.params.k_yx) = (cross, cross);
    p
}

/// The state at `h` of the linearized contact equations q'' + 2ν q' + Kl q + Fd =
/// F (cos θ, sin θ) + u from `start` at time `t0`, by their Taylor series (hand-written here:
/// the independent reference the closed form is held to; 24 terms, exact to rounding for
/// ‖Kl‖h² ≤ 1e-2).
fn linear_taylor(params: &Params, lin: &Linearization, t0: f64, start: State, h: f64) -> State {
    let model = ModelParams::of(params);
    let k = &lin.kl;
    let (nu, eta) = (params.damping_ratio, params.speed_ratio);
    let force = model.unbalance_force;
    let phasor = field::phasor(&model, t0);
    let (mut x, mut y) = (vec![start.x, start.vx], vec![start.y, start.vy]);
    let mut factorial = 1.0;
    for m in 0..24 {
        // The m-th derivative of the forcing at t0, over m!: F η^m (cos, sin)(θ0 + mπ/2)/m!.
        let (c, s) = match m % 4 {
            0 => (phasor.ct, phasor.st),
            1 => (-phasor.st, phasor.ct),
            2 => (-phasor.ct, -phasor.st),
            _ => (phasor.st, -phasor.ct),
        };
        let scale = force * eta.powi(m as i32) / factorial;
        let constant = if m == 0 { 1.0 } else { 0.0 };
        let mf = m as f64;
        let ax = scale * c + constant * (params.force_x - k.fd1)
            - 2.0 * nu * (mf + 1.0) * x[m + 1]
            - k.fa1 * x[m]
            - k.fb1 * y[m];
        let ay = scale * s + constant * (params.force_y - k.fd2)
            - 2.0 * nu * (mf + 1.0) * y[m + 1]
            - k.fb2 * x[m]
            - k.fa2 * y[m];
        x.push(ax / ((mf + 2.0) * (mf + 1.0)));
        y.push(ay / ((mf + 2.0) * (mf + 1.0)));
        factorial *= mf + 1.0;
    }
    let at = |c: &[f64]| c.iter().rev().fold(0.0, |acc, &a| acc * h + a);
    let rate = |c: &[f64]| {
        c.iter()
            .enumerate()
            .skip(1)
            .rev()
            .fold(0.0, |acc, (i, &a)| acc * h + i as f64 * a)
    };
    State::new(at(&x), at(&y), rate(&x), rate(&y))
}

/// The closed form of a linearized contact segment solves the equations it states to rounding
/// on stiff stators (K̂ = 1e3 … 1e5, isotropic, anisotropic, nearly singular, with friction and
/// an input force), linearized on and near z = 1 where Kl is most ill-conditioned: its state
/// after 1e-5 is within 2e-15·(1 + |state|) of the equations' Taylor series (before: velocity off
/// by up to 5.6e-13, the particular constants' residual times the step).
#[test]
fn stiff_contact_closed_form_solves_its_equations() {
    let mut worst: f64 = 0.0;
    for (k, cross, friction, input) in [
        (1e3, 0.0, 0.0, 0.0),
        (1e5, 0.0, 0.0, 0.0),
        (1e5, 0.99e5, 0.0, 0.0),
        (3e4, 1e4, 0.3, 0.0),
        (1e5, 0.0, 0.0, 5.0),
    ] {
        let mut problem = stiff_paper(k, cross);
        problem.params.k_yy = 0.7 * k;
        problem.params.friction_coefficient = friction;
        problem.params.radius_ratio = 1.0;
        problem.params.force_x = input;
        let params = problem.params;
        let (ex, ey) = (params.offset_x, params.offset_y);
        for depth in [0.0, 1e-7, 1e-4, 1e-2] {
            for angle in [0.3f64, 1.9, 2.6, 4.4, 5.8] {
                let z = 1.0 + depth;
                let (x, y) = (ex + z * angle.cos(), ey + z * angle.sin());
                let start = State::new(x, y, -1.3 * angle.sin(), 0.9 * angle.cos());
                let t0 = 2.0 + angle;
                for slip in [0.0, 1.0, -1.0] {
                    if (slip != 0.0) != (friction > 0.0) {
                        continue;
                    }
                    // (Slipping: the friction force is part of Kl and Fd, which the
                    // reference takes from the same linearization.)
                    let lin = Linearization::slipping(&params, slip, t0, x, y).unwrap();
                    let h = 1e-5;
                    let segment = lin.segment(start, [0.0; 8], h);
                    let got = segment.point(h).state;
                    let want = linear_taylor(&params, &lin, t0, start, h);
                    let scale = 1.0 + want.to_array().iter().fold(0.0f64, |m, v| m.max(v.abs()));
                    let error = rotor_rub::compare::state_difference(&got, &want) / scale;
                    worst = worst.max(error);
                    assert!(
                        error <= 2e-15,
                        "K {k} cross {cross} μ {friction} u {input} depth {depth} angle {angle} \
                         σ {slip}: closed form off by {error:e}"
                    );
                }
            }
        }
    }
    eprintln!("largest relative deviation {worst:e}");
}

/// The largest switch-time difference between `a` and `b` (same kinds required).
fn worst_switch_error(a: &[Event], b: &[Event]) -> f64 {
    assert_eq!(a.len(), b.len(), "switch counts");
    a.iter()
        .zip(b)
        .map(|(x, y)| {
            assert_eq!(x.kind, y.kind);
            (x.time - y.time).abs()
        })
        .fold(0.0, f64::max)
}

/// The analytic method's switch times follow its tolerance on the stiff stator
/// (K̂xx = K̂yy = 1e5, K̂xy = K̂yx = 0) and a nearly singular one (K̂xy = K̂yx = 0.99e5), over
/// two forcing periods (before the orbit's own sensitivity amplifies every method's error:
/// ×1e5 over 20 periods), against the taylor method at tol 1e-16: within 3·tol, and never
/// beyond 2e-11 however tight the tolerance (measured: about 1.2·tol down to 1e-11, then
/// 1.5e-12 … 1.2e-11; before: 3.9e-10 at tol 1e-11, 5.5e-11 at 1e-13 and 1e-14).
#[test]
fn analytic_switch_times_follow_the_tolerance_on_stiff_stators() {
    for cross in [0.0, 0.99e5] {
        let problem = stiff_paper(1e5, cross);
        let end = 2.0 * problem.params.forcing_period();
        let reference = switches(&problem, Method::Taylor, 1e-16, end);
        assert!(reference.len() >= 10, "{} switches", reference.len());
        for tol in [1e-6, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13, 1e-14] {
            let events = switches(&problem, Method::Analytic, tol, end);
            let error = worst_switch_error(&events, &reference);
            assert!(
                error <= (3.0 * tol).max(2e-11),
                "K̂xy {cross} tol {tol:e}: switch times off by {error:e}"
            );
        }
    }
}
