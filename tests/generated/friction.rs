//! The generated friction formulas (`docs/MODEL.md` §10) against a friction law written out by
//! hand here with nalgebra: the slipping contact force, N, w, λ and the rolling field; the
//! slipping linearization against central finite differences of the hand field; the remainder
//! against hand field minus linearization; and λ's derivation checked by differentiating w along
//! the fields numerically (w' = λ − μσN while slipping, w' = 0 while rolling).

use nalgebra::{Matrix2, Vector2};
use proptest::prelude::*;
use rotor_rub::coefficients::{
    self as coef, LinearizedContact, ModelParams, Phasor, Position, Slip, Velocity,
};
use rotor_rub::field::{self, Field};
use rotor_rub::propagate::Regime;
use rotor_rub::{Params, State};

use crate::support::*;

/// One friction situation: a random case with a positive definite symmetric K_s part, μ, ρ_R,
/// σ, a contact position (z ∈ [1, 2.5]), a velocity and a forcing phase.
#[derive(Clone, Copy, Debug)]
struct Situation {
    case: Case,
    mu: f64,
    rho: f64,
    sigma: f64,
    q: Vector2<f64>,
    v: Vector2<f64>,
    theta: f64,
}

impl Situation {
    fn params(&self) -> Params {
        Params {
            friction_coefficient: self.mu,
            radius_ratio: self.rho,
            ..self.case.params()
        }
    }

    fn model(&self) -> ModelParams {
        ModelParams::of(&self.params())
    }

    fn r(&self, q: Vector2<f64>) -> Vector2<f64> {
        q - Vector2::new(self.case.offset.0, self.case.offset.1)
    }

    /// n, t, z at q.
    fn frame(&self, q: Vector2<f64>) -> (Vector2<f64>, Vector2<f64>, f64) {
        let r = self.r(q);
        let z = r.norm();
        (r / z, Vector2::new(-r.y, r.x) / z, z)
    }

    /// K_s g(q).
    fn elastic(&self, q: Vector2<f64>) -> Vector2<f64> {
        let r = self.r(q);
        self.case.ks() * (r * (1.0 - 1.0 / r.norm()))
    }

    fn normal(&self, q: Vector2<f64>) -> f64 {
        self.frame(q).0.dot(&self.elastic(q))
    }

    /// q + K_s g + μσN t: the slipping stiffness term.
    fn slipping_term(&self, q: Vector2<f64>) -> Vector2<f64> {
        let (_, t, _) = self.frame(q);
        q + self.elastic(q) + t * (self.mu * self.sigma * self.normal(q))
    }

    /// G: every force but friction.
    fn g_force(&self, q: Vector2<f64>, v: Vector2<f64>) -> Vector2<f64> {
        let f = self.params().mass_ratio
            * self.params().eccentricity_ratio
            * self.params().speed_ratio
            * self.params().speed_ratio;
        Vector2::new(self.theta.cos(), self.theta.sin()) * f
            - v * (2.0 * self.case.nu)
            - q
            - self.elastic(q)
    }

    fn slip_velocity(&self, q: Vector2<f64>, v: Vector2<f64>) -> f64 {
        v.dot(&self.frame(q).1) + self.rho * self.case.eta
    }

    fn lambda(&self, q: Vector2<f64>, v: Vector2<f64>) -> f64 {
        let (n, t, z) = self.frame(q);
        t.dot(&self.g_force(q, v)) - v.dot(&t) * v.dot(&n) / z
    }
}

prop_compose! {
    fn any_situation()(
        case in any_case(),
        kxx in 1.0..80.0f64,
        kyy in 1.0..80.0f64,
        cross in -0.9..0.9f64,
        skew in -20.0..20.0f64,
        mu in 0.01..1.0f64,
        rho in 0.1..200.0f64,
        forward in any::<bool>(),
        z in 1.0..2.5f64,
        angle in 0.0..std::f64::consts::TAU,
        v in proptest::array::uniform2(-3.0..3.0f64),
        theta in 0.0..std::f64::consts::TAU,
    ) -> Situation {
        // Symmetric part [[kxx, c], [c, kyy]] with |c| < √(kxx kyy): positive definite.
        let c = cross * (kxx * kyy).sqrt();
        let mut case = case;
        case.k = [[kxx, c + skew], [c - skew, kyy]];
        let q = Vector2::new(case.offset.0 + z * angle.cos(), case.offset.1 + z * angle.sin());
        Situation {
            case, mu, rho, sigma: if forward { 1.0 } else { -1.0 },
            q, v: Vector2::from(v), theta,
        }
    }
}

fn close(a: f64, b: f64, scale: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * (1.0 + scale)
}

proptest! {
    #![proptest_config(config(256))]

    /// N, w, λ and the slipping and rolling fields are the hand ones.
    #[test]
    fn friction_formulas_match_hand_law(s in any_situation()) {
        let (q, v) = (s.q, s.v);
        let model = s.model();
        let at = Position { x: q.x, y: q.y };
        let rate = Velocity { vx: v.x, vy: v.y };
        let phasor = Phasor { ct: s.theta.cos(), st: s.theta.sin() };
        let (_, t, _) = s.frame(q);
        let scale = s.case.ks().norm() * q.norm() + v.norm();
        let fs = coef::friction_state(&model, &at, &rate, &phasor);
        prop_assert!(close(fs.normal, s.normal(q), scale, 1e-13));
        prop_assert!(close(fs.slip_velocity, s.slip_velocity(q, v), s.rho * s.case.eta + scale, 1e-13));
        prop_assert!(close(fs.lambda, s.lambda(q, v), scale * (1.0 + v.norm()), 1e-13));
        let state = State::new(q.x, q.y, v.x, v.y);
        let rolling = s.g_force(q, v) - t * s.lambda(q, v);
        let p = s.params();
        let (ax, ay) = field::acceleration(&ModelParams::of(&p), Field::of(Regime::Rolling, 0.0), &Phasor { ct: phasor.ct, st: phasor.st }, &state);
        prop_assert!(close(ax, rolling.x, scale * (1.0 + v.norm()), 1e-13));
        prop_assert!(close(ay, rolling.y, scale * (1.0 + v.norm()), 1e-13));
        let slipping = s.g_force(q, v) - t * (s.mu * s.sigma * s.normal(q));
        let (ax, ay) = field::acceleration(&ModelParams::of(&p), Field::of(Regime::Contact, s.sigma), &Phasor { ct: phasor.ct, st: phasor.st }, &state);
        prop_assert!(close(ax, slipping.x, scale, 1e-13) && close(ay, slipping.y, scale, 1e-13));
    }

    /// Kl and Fd of the slipping linearization: Kl against central differences of the hand
    /// slipping term (step 1e-6: truncation ~1e-12·|term'''|, rounding ~1e-10·|term|), Fd from
    /// term(r0) − Kl r0; the generated remainder equals hand term minus linearization at nearby
    /// points and vanishes at r0.
    #[test]
    fn slipping_linearization_matches_finite_differences(
        s in any_situation(),
        dq in proptest::array::uniform2(-0.3..0.3f64),
    ) {
        let model = s.model();
        let slip = Slip { sigma: s.sigma };
        let r0 = s.q;
        let lin = coef::slipping_linearized_stiffness(&model, &Position { x: r0.x, y: r0.y }, &slip);
        let kl = Matrix2::new(lin.fa1, lin.fb1, lin.fb2, lin.fa2);
        let h = 1e-6;
        let mut fd_kl = Matrix2::zeros();
        for j in 0..2 {
            let mut e = Vector2::zeros();
            e[j] = h;
            let col = (s.slipping_term(r0 + e) - s.slipping_term(r0 - e)) / (2.0 * h);
            fd_kl.set_column(j, &col);
        }
        let scale = 1.0 + s.case.ks().norm() * (1.0 + s.mu);
        prop_assert!((kl - fd_kl).norm() <= 1e-7 * scale, "{kl} vs {fd_kl}");
        let fd = Vector2::new(lin.fd1, lin.fd2);
        let want_fd = s.slipping_term(r0) - kl * r0;
        prop_assert!((fd - want_fd).norm() <= 1e-12 * scale * (1.0 + r0.norm()));
        let q = r0 + Vector2::from(dq);
        let n = coef::slipping_remainder(&model, &Position { x: q.x, y: q.y }, &lin, &slip);
        let want = kl * q + fd - s.slipping_term(q);
        let scale_q = scale * (1.0 + q.norm());
        prop_assert!((Vector2::new(n.fx, n.fy) - want).norm() <= 1e-12 * scale_q);
        let n0 = coef::slipping_remainder(&model, &Position { x: r0.x, y: r0.y }, &lin, &slip);
        prop_assert!(Vector2::new(n0.fx, n0.fy).norm() <= 1e-12 * scale_q);
        let _: LinearizedContact = lin;
    }

    /// `max_contact_stiffness` bounds ‖Kl‖₂ of the slipping linearization too (the analytic
    /// method's step cap): at random contact points, both slip directions.
    #[test]
    fn slipping_stiffness_stays_within_the_cap(s in any_situation()) {
        let p = s.params();
        let cap = rotor_rub::analytic::linear::max_contact_stiffness(&p);
        let lin = coef::slipping_linearized_stiffness(
            &s.model(),
            &Position { x: s.q.x, y: s.q.y },
            &Slip { sigma: s.sigma },
        );
        let norm = Matrix2::new(lin.fa1, lin.fb1, lin.fb2, lin.fa2).singular_values().max();
        prop_assert!(norm <= cap * (1.0 + 1e-12), "‖Kl‖ = {norm} > cap {cap}");
    }

    /// λ's derivation: w differentiated numerically along the slipping field is λ − μσN, and
    /// along the rolling field 0 (central difference in time, step 1e-5 along the tangent of the
    /// trajectory: error ~1e-10 relative).
    #[test]
    fn slip_velocity_rate_is_lambda_minus_friction(s in any_situation()) {
        let p = s.params();
        let (q, v) = (s.q, s.v);
        let state = State::new(q.x, q.y, v.x, v.y);
        let (ct, st) = (s.theta.cos(), s.theta.sin());
        let rate = |regime: Regime, sigma: f64| {
            let (ax, ay) = field::acceleration(&ModelParams::of(&p), Field::of(regime, sigma), &Phasor { ct, st }, &state);
            let a = Vector2::new(ax, ay);
            let h = 1e-5;
            (s.slip_velocity(q + v * h, v + a * h) - s.slip_velocity(q - v * h, v - a * h)) / (2.0 * h)
        };
        let f = field::friction_with_phasor(&ModelParams::of(&p), &Phasor { ct, st }, &state);
        let scale = (1.0 + s.case.ks().norm()) * (1.0 + v.norm()).powi(2);
        let slip_rate = field::slip_rate(&ModelParams::of(&p), &Phasor { ct, st }, &state, s.sigma);
        prop_assert!(close(rate(Regime::Contact, s.sigma), slip_rate, scale, 1e-8));
        prop_assert!(close(slip_rate, f.lambda - s.mu * s.sigma * f.normal, scale, 1e-12));
        prop_assert!(close(rate(Regime::Rolling, 0.0), 0.0, scale, 1e-8));
    }

    /// The friction cone's rates (μN ∓ λ)' (`friction_cone`) against central differences of the
    /// margins along the rolling
    /// field, the forcing phase advancing at η (step 1e-5: error ~1e-10 relative).
    #[test]
    fn rolling_rates_match_finite_differences(s in any_situation()) {
        let p = s.params();
        let (q, v) = (s.q, s.v);
        let state = State::new(q.x, q.y, v.x, v.y);
        let (ct, st) = (s.theta.cos(), s.theta.sin());
        let (ax, ay) = field::acceleration(&ModelParams::of(&p), Field::of(Regime::Rolling, 0.0), &Phasor { ct, st }, &state);
        let a = Vector2::new(ax, ay);
        let h = 1e-5;
        let at = |sign: f64| {
            let qq = q + v * (sign * h);
            let vv = v + a * (sign * h);
            let th = s.theta + sign * h * s.case.eta;
            let st2 = State::new(qq.x, qq.y, vv.x, vv.y);
            field::friction_with_phasor(&ModelParams::of(&p), &Phasor { ct: th.cos(), st: th.sin() }, &st2)
        };
        let (plus, minus) = (at(1.0), at(-1.0));
        let cone = coef::friction_cone_rates(
            &ModelParams::of(&p),
            &Position { x: q.x, y: q.y },
            &Velocity { vx: v.x, vy: v.y },
            &Phasor { ct, st },
        );
        let scale = (1.0 + s.case.ks().norm()) * (1.0 + v.norm()).powi(3) * (1.0 + s.mu);
        prop_assert!(close(cone.upper_rate, (plus.cone.0 - minus.cone.0) / (2.0 * h), scale, 1e-7));
        prop_assert!(close(cone.lower_rate, (plus.cone.1 - minus.cone.1) / (2.0 * h), scale, 1e-7));
    }
}
