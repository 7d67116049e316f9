//! The generated field against a field written out by hand here (`docs/MODEL.md` §1–§3): the
//! runtime's field, remainder, linear acceleration, shifted stiffness and series response come
//! from the generator's model statement, so this file is where their independence lives.

use nalgebra::{Matrix2, Vector2};
use proptest::prelude::*;
use rotor_rub::State;
use rotor_rub::analytic::linear::{Linearization, max_contact_stiffness};
use rotor_rub::coefficients::{
    self as coef, LinearizedContact, ModelParams, Phasor, Position, Velocity,
};
use rotor_rub::field::{self, Field};
use rotor_rub::propagate::Regime;

use crate::support::*;

/// g(q) = (1 − 1/z)(u, v), written out.
fn g_hand(case: &Case, q: Vector2<f64>) -> Vector2<f64> {
    let r = q - Vector2::new(case.offset.0, case.offset.1);
    r * (1.0 - 1.0 / r.norm())
}

/// ∂g/∂q = (1 − 1/z) I + (1/z) n nᵀ, n = (q − ε̂)/z, written out.
fn j_hand(case: &Case, q: Vector2<f64>) -> Matrix2<f64> {
    let r = q - Vector2::new(case.offset.0, case.offset.1);
    let z = r.norm();
    let n = r / z;
    Matrix2::identity() * (1.0 - 1.0 / z) + n * n.transpose() / z
}

/// (Kl, Fd) of the hand linearization about r0: Kl = I + K_s J, Fd = K_s (g(r0) − J r0).
fn linearization_hand(case: &Case, r0: Vector2<f64>) -> (Matrix2<f64>, Vector2<f64>) {
    let j = j_hand(case, r0);
    (
        Matrix2::identity() + case.ks() * j,
        case.ks() * (g_hand(case, r0) - j * r0),
    )
}

fn as_generated(kl: &Matrix2<f64>, fd: &Vector2<f64>) -> LinearizedContact {
    LinearizedContact {
        fa1: kl[(0, 0)],
        fb1: kl[(0, 1)],
        fb2: kl[(1, 0)],
        fa2: kl[(1, 1)],
        fd1: fd.x,
        fd2: fd.y,
    }
}

fn close(a: Vector2<f64>, b: Vector2<f64>, scale: f64) -> bool {
    (a - b).norm() <= 1e-13 * (1.0 + scale)
}

proptest! {
    #![proptest_config(config(256))]

    /// The runtime field (the generated free and contact fields) is the hand field:
    /// q'' = F(cos θ, sin θ) − 2ν q' − q − [contact] K_s g(q), to rounding of its terms.
    #[test]
    fn field_matches_hand_field(
        case in any_case(),
        q in proptest::array::uniform2(-3.0..3.0f64),
        v in proptest::array::uniform2(-3.0..3.0f64),
        theta in 0.0..std::f64::consts::TAU,
    ) {
        let p = case.params();
        let (q, v) = (Vector2::from(q), Vector2::from(v));
        prop_assume!((q - Vector2::new(case.offset.0, case.offset.1)).norm() > 0.1);
        let f = p.mass_ratio * p.eccentricity_ratio * p.speed_ratio * p.speed_ratio;
        let forcing = f * Vector2::new(theta.cos(), theta.sin());
        let contact = case.ks() * g_hand(&case, q);
        let free = forcing - 2.0 * case.nu * v - q;
        let scale = forcing.norm() + 2.0 * case.nu * v.norm() + q.norm() + contact.norm();
        let s = State::new(q.x, q.y, v.x, v.y);
        let (ct, st) = (theta.cos(), theta.sin());
        let (ax, ay) = field::acceleration(&ModelParams::of(&p), Field::of(Regime::Free, 0.0), &Phasor { ct, st }, &s);
        prop_assert!(close(Vector2::new(ax, ay), free, scale));
        let (ax, ay) = field::acceleration(&ModelParams::of(&p), Field::of(Regime::Contact, 0.0), &Phasor { ct, st }, &s);
        prop_assert!(close(Vector2::new(ax, ay), free - contact, scale));
    }

    /// The generated remainder n(q) = Kl q + Fd − q − K_s g(q) equals the hand field minus the
    /// hand linearization (hand J, Kl, Fd) at random points, and vanishes at the linearization
    /// point; the generated Kl, Fd equal the hand ones.
    #[test]
    fn remainder_is_field_minus_linearization(
        case in any_case(),
        dq in proptest::array::uniform2(-0.5..0.5f64),
    ) {
        let r0 = Vector2::new(case.x0, case.y0);
        let (kl, fd) = linearization_hand(&case, r0);
        let generated = case.linearized();
        let scale = kl.norm() * (1.0 + r0.norm()) + fd.norm();
        prop_assert!(close(Vector2::new(generated.fa1, generated.fb1), kl.row(0).transpose(), scale));
        prop_assert!(close(Vector2::new(generated.fb2, generated.fa2), kl.row(1).transpose(), scale));
        prop_assert!(close(Vector2::new(generated.fd1, generated.fd2), fd, scale));
        let q = r0 + Vector2::from(dq);
        prop_assume!((q - Vector2::new(case.offset.0, case.offset.1)).norm() > 0.1);
        let field_stiffness = q + case.ks() * g_hand(&case, q);
        let want = kl * q + fd - field_stiffness;
        let n = coef::contact_remainder(
            &case.model(),
            &Position { x: q.x, y: q.y },
            &as_generated(&kl, &fd),
        );
        let scale = kl.norm() * q.norm() + fd.norm() + field_stiffness.norm();
        prop_assert!(close(Vector2::new(n.fx, n.fy), want, scale), "{n:?} vs {want}");
        let n0 = coef::contact_remainder(&case.model(), &Position { x: r0.x, y: r0.y }, &generated);
        prop_assert!(Vector2::new(n0.fx, n0.fy).norm() <= 1e-12 * (1.0 + scale));
    }

    /// The linear acceleration a − 2ν q' − Kl q and A = Kl − ν² I against their hand forms.
    #[test]
    fn linear_acceleration_and_shifted_stiffness_match_hand(
        case in any_case(),
        q in proptest::array::uniform2(-3.0..3.0f64),
        v in proptest::array::uniform2(-3.0..3.0f64),
        a in proptest::array::uniform2(-3.0..3.0f64),
    ) {
        let (q, v, a) = (Vector2::from(q), Vector2::from(v), Vector2::from(a));
        let l = case.linearized();
        let kl = kl_matrix(&l);
        let want = a - 2.0 * case.nu * v - kl * q;
        let got = coef::linear_acceleration(
            &case.model(),
            &Position { x: q.x, y: q.y },
            &Velocity { vx: v.x, vy: v.y },
            &coef::Force { fx: a.x, fy: a.y },
            &l,
        );
        let scale = a.norm() + 2.0 * case.nu * v.norm() + kl.norm() * q.norm();
        prop_assert!(close(Vector2::new(got.ax, got.ay), want, scale));
        let s = coef::shifted_stiffness(&case.model(), &l);
        let shifted = kl - Matrix2::identity() * case.nu * case.nu;
        let gm = Matrix2::new(s.a11, s.a12, s.a21, s.a22);
        prop_assert!((gm - shifted).norm() <= 1e-13 * (1.0 + kl.norm()));
    }

    /// The series response (`Linearization::forced_state` on a short horizon, where it is a
    /// Taylor series) against the recurrence written out here with the hand linear ODE
    /// q'' + 2νq' + Kl q = a0 + a1 s + a2 s² + a3 s³ and its own 30 terms.
    #[test]
    fn series_step_matches_hand_recurrence(
        case in any_case(),
        a in any_cubic(),
        frac in 0.1..1.0f64,
    ) {
        let p = case.params();
        let Ok(lin) = Linearization::new(&p, case.t0, case.x0, case.y0) else {
            return Err(TestCaseError::reject("singular"));
        };
        let kl = kl_matrix(&lin.kl);
        // ‖Kl‖_F h² ≤ 1: the runtime's series regime.
        let horizon = 0.5 / (1.0 + kl.norm()).sqrt();
        let s = frac * horizon;
        let zero = State::new(0.0, 0.0, 0.0, 0.0);
        let got = lin.forced_state(&zero, &a, horizon, s).expect("series regime");
        let mut c = vec![Vector2::zeros(); 32];
        for m in 0..30 {
            let am = if m < 4 { Vector2::new(a[2 * m], a[2 * m + 1]) } else { Vector2::zeros() };
            let mf = m as f64;
            c[m + 2] = (am - 2.0 * case.nu * (mf + 1.0) * c[m + 1] - kl * c[m])
                / ((mf + 2.0) * (mf + 1.0));
        }
        let (mut x, mut dx) = (Vector2::zeros(), Vector2::zeros());
        for (m, cm) in c.iter().enumerate() {
            x += cm * s.powi(m as i32);
            if m > 0 {
                dx += cm * (m as f64) * s.powi(m as i32 - 1);
            }
        }
        let scale = a.iter().map(|v| v.abs()).sum::<f64>() * (1.0 + s);
        prop_assert!((Vector2::new(got.x, got.y) - x).norm() <= 1e-13 * scale * s * s + 1e-300);
        prop_assert!((Vector2::new(got.vx, got.vy) - dx).norm() <= 1e-13 * scale * s + 1e-300);
    }

    /// `max_contact_stiffness` bounds ‖Kl‖₂ (nalgebra singular values) at every linearization
    /// point with z ≥ 1, and is the elastic law's 1 + ‖K_s‖_F up to its margin.
    #[test]
    fn contact_stiffness_bound_holds(
        case in any_case(),
        z in 1.0..50.0f64,
        angle in 0.0..std::f64::consts::TAU,
    ) {
        let p = case.params();
        let bound = max_contact_stiffness(&p);
        let r0 = Vector2::new(case.offset.0 + z * angle.cos(), case.offset.1 + z * angle.sin());
        let (kl, _) = linearization_hand(&case, r0);
        let sigma = kl.singular_values().max();
        prop_assert!(sigma <= bound * (1.0 + 1e-12), "‖Kl‖ = {sigma} > bound {bound}");
        let elastic = 1.0 + case.ks().norm();
        prop_assert!((bound - elastic).abs() <= 1e-10 * elastic, "{bound} vs {elastic}");
    }
}

/// The ‖J‖ bound's premise: the generated J along (1, 0) is affine in w = 1/z (J(w) at
/// w = ¼, ⅓ from the end values), for several offsets.
#[test]
fn jacobian_is_affine_in_inverse_radius() {
    for (ex, ey) in [(0.0, 0.0), (0.3, -0.2), (-0.4, 0.1)] {
        let model = coef::ModelParams {
            offset_x: ex,
            offset_y: ey,
            ..coef::ModelParams::default()
        };
        let j = |z: f64| {
            let t = coef::taylor_terms(&model, &Position { x: ex + z, y: ey });
            [t.a1, t.b1, t.b2, t.a2]
        };
        let (j1, j2) = (j(1.0), j(2.0));
        for z in [3.0, 4.0, 10.0] {
            let w = 1.0 / z;
            let want: Vec<f64> = (0..4)
                .map(|k| (2.0 * j2[k] - j1[k]) * (1.0 - w) + j1[k] * w)
                .collect();
            for (got, want) in j(z).iter().zip(&want) {
                assert!((got - want).abs() <= 1e-14, "z = {z}: {got} vs {want}");
            }
        }
    }
}
