//! What the monodromy matrix of a periodic orbit needs of the model (`docs/MODEL.md` §18): the
//! Jacobian of each contact regime's field, for the variational equations Φ' = J(τ, s) Φ
//! integrated along a contact segment, and the gradients of the switching functions, for the
//! saltation matrices S = I + (f⁺ − f⁻) ∇hᵀ / (∇h·f⁻) at the switches where the field jumps.
//!
//! Free flight needs nothing new: its field is linear, so its state-transition matrix over any
//! local time s is the closed form's response to the unit start states, the generated
//! `free_step_transition` (`free_step.rs`), evaluated with the basis EC(s), ES(s) at that s.
//!
//! Each Jacobian is the partial derivative of the regime's whole field (the same assembly of the
//! model statement's pieces as `regimes.rs`'s `*_field`) with respect to the state (x, y, x', y');
//! the forcing phasor and the input force do not depend on the state, so they drop out.
//! Derived last, after `regimes.rs`, so that its nodes come last in the graph and every other
//! formula keeps its form.

use super::{Model, Vec2};
use crate::derive::partial;
use crate::expr::ExprId;

pub(super) fn derive(m: &mut Model) {
    field_jacobians(m);
    switching_gradient(m);
    slip_velocity_gradient(m);
}

/// The state's symbols, in the order x, y, x', y'.
const STATE: [&str; 4] = ["lx", "ly", "vx", "vy"];

/// The 2×4 Jacobian ∂(ax, ay)/∂(x, y, x', y') of an acceleration, row by row, as the outputs of
/// the declared `FieldJacobian`.
fn jacobian_outputs(m: &mut Model, a: Vec2) -> Vec<(&'static str, &'static str, ExprId)> {
    const NAMES: [[(&str, &str); 4]; 2] = [
        [
            ("xx", "∂x''/∂x"),
            ("xy", "∂x''/∂y"),
            ("xvx", "∂x''/∂x'"),
            ("xvy", "∂x''/∂y'"),
        ],
        [
            ("yx", "∂y''/∂x"),
            ("yy", "∂y''/∂y"),
            ("yvx", "∂y''/∂x'"),
            ("yvy", "∂y''/∂y'"),
        ],
    ];
    let symbols = STATE.map(|n| m.sym(n));
    let mut outputs = Vec::with_capacity(8);
    for (row, names) in a.iter().zip(NAMES) {
        for (&s, (name, doc)) in symbols.iter().zip(names) {
            let d = partial(&mut m.graph, *row, s);
            outputs.push((name, doc, d));
        }
    }
    outputs
}

/// ∂q''/∂(q, q') of frictionless contact, slipping contact (direction σ) and rolling.
fn field_jacobians(m: &mut Model) {
    let q = [m.var("lx"), m.var("ly")];
    let v = [m.var("vx"), m.var("vy")];
    let phasor = [m.var("ct"), m.var("st")];
    let sigma = m.var("sigma");
    let forcing = m.forcing(phasor);
    let contact = {
        let stiffness = m.stiffness(q, Some(None));
        m.acceleration(v, stiffness, forcing)
    };
    let slipping = {
        let stiffness = m.stiffness(q, Some(Some(sigma)));
        m.acceleration(v, stiffness, forcing)
    };
    let rolling = {
        let (q, v, acc) = super::friction::frictionless_contact_acceleration(m);
        let (lambda, _, t) = super::friction::rolling_force(m, q, v, acc);
        let g = &mut m.graph;
        [0, 1].map(|i| {
            let f = g.mul(lambda, t[i]);
            g.sub(acc[i], f)
        })
    };
    let fields = [
        (
            "contact_field_jacobian",
            "The Jacobian of frictionless contact's field q'' = F(cos θ, sin θ) + u − 2ν q' − q − K_s·g(q) with respect to the state (x, y, x', y'): the variational equations' matrix in contact.",
            contact,
        ),
        (
            "slipping_field_jacobian",
            "The Jacobian of the field of contact slipping in direction σ, q'' = … − K_s·g(q) − μσN t, with respect to the state (x, y, x', y').",
            slipping,
        ),
        (
            "rolling_field_jacobian",
            "The Jacobian of the rolling field q'' = G − λ t with respect to the state (x, y, x', y') (λ depends on the velocity too).",
            rolling,
        ),
    ];
    for (name, summary, a) in fields {
        let outputs = jacobian_outputs(m, a);
        m.add_formula(
            name,
            summary,
            "docs/MODEL.md §10, §18",
            "partial derivatives of the regime's field (the model's acceleration with the regime's stiffness term and the forcing) with respect to x, y, x', y'.",
            "FieldJacobian",
            outputs,
        );
    }
}

/// The gradient of a switching function of the state, as the outputs of the declared
/// `StateGradient`.
fn gradient_outputs(m: &mut Model, h: ExprId) -> Vec<(&'static str, &'static str, ExprId)> {
    const NAMES: [(&str, &str); 4] = [
        ("x", "∂/∂x"),
        ("y", "∂/∂y"),
        ("vx", "∂/∂x'"),
        ("vy", "∂/∂y'"),
    ];
    let symbols = STATE.map(|n| m.sym(n));
    symbols
        .iter()
        .zip(NAMES)
        .map(|(&s, (name, doc))| (name, doc, partial(&mut m.graph, h, s)))
        .collect()
}

/// ∇h of h = z² − 1: the saltation matrix's normal at `enter` and `exit`.
fn switching_gradient(m: &mut Model) {
    let q = [m.var("lx"), m.var("ly")];
    let h = m.boundary(q);
    let outputs = gradient_outputs(m, h);
    m.add_formula(
        "switching_gradient",
        "The gradient ∇h = ∂h/∂(x, y, x', y') of the switching function h = z² − 1: the normal of the contact surface in the state space, for the saltation matrix of a switch whose field jumps (rolling's exit).",
        "docs/MODEL.md §1, §18",
        "partial derivatives of the model's `boundary`.",
        "StateGradient",
        outputs,
    );
}

/// ∇w of the slip velocity w = q'·t + ρ_R η: the saltation matrix's normal at `reverse` and `roll`.
fn slip_velocity_gradient(m: &mut Model) {
    let q = [m.var("lx"), m.var("ly")];
    let v = [m.var("vx"), m.var("vy")];
    let w = m.slip_velocity(q, v);
    let outputs = gradient_outputs(m, w);
    m.add_formula(
        "slip_velocity_gradient",
        "The gradient ∇w = ∂w/∂(x, y, x', y') of the slip velocity w = q'·t + ρ_R η: the normal of friction's switching surface w = 0 in the state space, for the saltation matrices at `reverse` and `roll`.",
        "docs/MODEL.md §10, §18",
        "partial derivatives of the model's `slip_velocity`.",
        "StateGradient",
        outputs,
    );
}
