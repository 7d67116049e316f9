//! Coulomb friction at contact (`docs/MODEL.md` §10): what the runtime needs of the model's
//! `friction` piece. Slipping (σ = ±1) adds μσN t to the contact pieces, a smooth function of
//! position for a fixed σ, so its contact field is linearized and solved in closed form like
//! frictionless contact; rolling replaces μσN by the tangential force λ that keeps the slip
//! velocity w at 0. The frictionless formulas of `field.rs` and `linearization.rs` are left
//! untouched: μ = 0 runs them, bit for bit.

use super::{Model, Vec2};
use crate::derive::partial;
use crate::expr::ExprId;

pub(super) fn derive(m: &mut Model) {
    slipping_linearized_stiffness(m);
    slipping_remainder(m);
    friction_state(m);
    rolling_acceleration(m);
}

fn position(m: &mut Model) -> Vec2 {
    [m.var("lx"), m.var("ly")]
}

/// Kl = I + ∂G_σ/∂q and Fd = G_σ(q0) − (∂G_σ/∂q) q0 at q0, G_σ = K_s g + μσN t: the Taylor
/// linearization of the slipping contact field (Kl is not symmetric even for an isotropic K_s:
/// friction is circulatory).
fn slipping_linearized_stiffness(m: &mut Model) {
    let q = [m.var("x"), m.var("y")];
    let sigma = m.var("sigma");
    let term = m.stiffness(q, Some(Some(sigma)));
    let g = &mut m.graph;
    let (sx, sy) = (g.symbol("x"), g.symbol("y"));
    let jac = [
        [partial(g, term[0], sx), partial(g, term[0], sy)],
        [partial(g, term[1], sx), partial(g, term[1], sy)],
    ];
    let (x0, y0) = (m.var("lx"), m.var("ly"));
    let at = [("x", x0), ("y", y0)];
    let kl = jac.map(|row| row.map(|e| m.subst(e, &at)));
    let value = term.map(|e| m.subst(e, &at));
    let g = &mut m.graph;
    let fd = [0, 1].map(|i| {
        let a = g.mul(kl[i][0], x0);
        let b = g.mul(kl[i][1], y0);
        let s = g.add(a, b);
        g.sub(value[i], s)
    });
    m.add_formula(
        "slipping_linearized_stiffness",
        "Linearized stiffness of slipping contact in direction σ: Kl = I + ∂(K_s g + μσN t)/∂q and Fd so that q + K_s g + μσN t ≈ Kl q + Fd about (x0, y0).",
        "docs/MODEL.md §10, §3",
        "partial derivatives of the model's stiffness term with the friction piece, at (x0, y0); Fd = term(r0) − Kl r0.",
        "LinearizedContact",
        vec![
            ("fa1", "Kl[0][0]", kl[0][0]),
            ("fb1", "Kl[0][1]", kl[0][1]),
            ("fb2", "Kl[1][0]", kl[1][0]),
            ("fa2", "Kl[1][1]", kl[1][1]),
            ("fd1", "Fd, x", fd[0]),
            ("fd2", "Fd, y", fd[1]),
        ],
    );
}

/// n(q) = Kl q + Fd − q − K_s g(q) − μσN t.
fn slipping_remainder(m: &mut Model) {
    let q = position(m);
    let sigma = m.var("sigma");
    let (kl, fd) = m.linearized_inputs();
    let linear = m.linear_stiffness_term(kl, fd, q);
    let full = m.stiffness(q, Some(Some(sigma)));
    let g = &mut m.graph;
    let n = [0, 1].map(|i| g.sub(linear[i], full[i]));
    m.add_formula(
        "slipping_remainder",
        "The nonlinear remainder n(q) = Kl q + Fd − q − K_s·g(q) − μσN t of the linearized slipping contact field, as a force on the acceleration.",
        "docs/MODEL.md §10, §8",
        "the linearized stiffness term minus the model's stiffness term with the friction piece.",
        "Force",
        vec![("fx", "n_x", n[0]), ("fy", "n_y", n[1])],
    );
}

/// Every force but friction, G = F(cos θ, sin θ) + u − 2ν q' − q − K_s g, at a state (the
/// input force u included: it changes λ and the rolling field, `docs/MODEL.md` §15).
pub(super) fn frictionless_contact_acceleration(m: &mut Model) -> (Vec2, Vec2, Vec2) {
    let q = position(m);
    let v = [m.var("vx"), m.var("vy")];
    let phasor = [m.var("ct"), m.var("st")];
    let forcing = m.forcing(phasor);
    let stiffness = m.stiffness(q, Some(None));
    (q, v, m.acceleration(v, stiffness, forcing))
}

/// λ = t·G − (q'·t)(q'·n)/z (with q'·t and t): from w' = t·q'' + q'·t' with t' = −(q'·t/z) n, the tangential
/// force that keeps w' = 0.
pub(super) fn rolling_force(m: &mut Model, q: Vec2, v: Vec2, acc: Vec2) -> (ExprId, ExprId, Vec2) {
    let (n, t, z) = m.contact_frame(q);
    let tg = m.dot(t, acc);
    let vt = m.dot(v, t);
    let vn = m.dot(v, n);
    let g = &mut m.graph;
    let inv_z = g.powi(z, -1);
    let centripetal = g.product(&[vt, vn, inv_z]);
    let lambda = g.sub(tg, centripetal);
    (lambda, vt, t)
}

/// N, w and λ at a contact state.
fn friction_state(m: &mut Model) {
    let (q, v, acc) = frictionless_contact_acceleration(m);
    let normal = m.normal_force(q);
    let (lambda, _, _) = rolling_force(m, q, v, acc);
    let w = m.slip_velocity(q, v);
    m.add_formula(
        "friction_state",
        "The friction quantities of a contact state: the normal force N = nᵀK_s g, the slip velocity w = q'·t + ρ_R η of the rotor surface at the contact point, and λ = t·G − (q'·t)(q'·n)/z (G: every force but friction), the tangential force that keeps w constant. While slipping w' = λ − μσN.",
        "docs/MODEL.md §10",
        "the model's `normal_force`, `contact_frame` and the frictionless contact field; w' = t·q'' + q'·t', t' = −(q'·t/z) n.",
        "FrictionState",
        vec![
            ("normal", "N, the normal elastic contact force", normal),
            ("slip_velocity", "w, the slip velocity", w),
            ("lambda", "λ, the tangential force of rolling", lambda),
        ],
    );
}

/// q'' = G − λ t while rolling (w ≡ 0 is a first integral of this field).
fn rolling_acceleration(m: &mut Model) {
    let (q, v, acc) = frictionless_contact_acceleration(m);
    let (lambda, _, t) = rolling_force(m, q, v, acc);
    let g = &mut m.graph;
    let a = [0, 1].map(|i| {
        let f = g.mul(lambda, t[i]);
        g.sub(acc[i], f)
    });
    m.add_formula(
        "rolling_acceleration",
        "Acceleration while rolling: q'' = G − λ t, the frictionless contact field minus the tangential force λ that keeps the slip velocity w at 0.",
        "docs/MODEL.md §10",
        "the frictionless contact field and λ of `friction_state`.",
        "Acceleration",
        vec![("ax", "x''", a[0]), ("ay", "y''", a[1])],
    );
}
