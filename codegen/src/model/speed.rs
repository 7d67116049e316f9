//! A running speed that changes in time (`docs/MODEL.md` §14): what the runtime needs of the
//! model's [`Model::unbalance_at_varying_speed`] piece. The constant-speed formulas are left
//! untouched (a speed profile with η' = 0 runs them, bit for bit); a changing speed adds the
//! part of the unbalance forcing proportional to η' ([`speed_change_force`]), and a speed held
//! constant over a step with its rate frozen is one harmonic forcing ([`held_speed_forcing`]).
//!
//! The build checks that the piece's η' = 0 part is the constant-speed `unbalance` with
//! F = η_m ρ̂ η², and that its x and y components are one rotating forcing (so that a held
//! step is exactly the constant-speed closed form with another amplitude and phase).

use super::{Model, Vec2};
use crate::derive::partial;
use crate::expr::ExprId;

pub(super) fn derive(m: &mut Model) {
    let (forcing, _) = m.unbalance_at_varying_speed();
    check_constant_speed_case(m, forcing);
    speed_change_force(m, forcing);
    held_speed_forcing(m, forcing);
    varying_speed_unbalance(m, forcing);
}

/// Panics (fails the build) unless `a − b` simplifies to 0.
fn assert_same(m: &mut Model, a: ExprId, b: ExprId, what: &str) {
    let d = m.graph.sub(a, b);
    assert!(
        m.graph.is_const(d, 0.0),
        "codegen/src/model/speed.rs: {what} does not hold symbolically"
    );
}

/// At η' = 0 the varying-speed unbalance is the constant-speed `unbalance` with F = η_m ρ̂ η².
fn check_constant_speed_case(m: &mut Model, forcing: Vec2) {
    let zero = m.graph.constant(0.0);
    let at_rest = forcing.map(|f| m.subst(f, &[("eta_rate", zero)]));
    let phasor = [m.var("ct"), m.var("st")];
    let constant = m.unbalance(phasor);
    let amplitude = m.derived("unbalance_force");
    for i in 0..2 {
        let expected = m.subst(constant[i], &[("unbalance_force", amplitude)]);
        assert_same(
            m,
            at_rest[i],
            expected,
            "the η' = 0 case of unbalance_at_varying_speed = unbalance with F = η_m ρ̂ η²",
        );
    }
}

/// η' ∂F/∂η': the forcing that a changing speed adds to the constant-speed unbalance (the
/// forcing is linear in η').
fn speed_change_force(m: &mut Model, forcing: Vec2) {
    let rate = m.var("eta_rate");
    let s = m.sym("eta_rate");
    let g = &mut m.graph;
    let f = forcing.map(|fi| {
        let d = partial(g, fi, s);
        g.mul(rate, d)
    });
    m.add_formula(
        "speed_change_force",
        "The part of the unbalance forcing a changing speed adds to F (cos θ, sin θ): −η_m ρ̂ η' (−sin θ, cos θ), the unbalance lagging behind (or running ahead of) the rotor's rotation.",
        "docs/MODEL.md §14",
        "η' times the partial derivative by η' of the model's `unbalance_at_varying_speed` (linear in η').",
        "Force",
        vec![("fx", "x component", f[0]), ("fy", "y component", f[1])],
    );
}

/// With η and η' held constant the forcing is one harmonic of frequency η: its x component is
/// a_c cos θ + a_s sin θ and its y component a_c sin θ − a_s cos θ, i.e.
/// A (cos(θ − δ), sin(θ − δ)) with A = √(a_c² + a_s²), δ = atan2(a_s, a_c).
fn held_speed_forcing(m: &mut Model, forcing: Vec2) {
    let (ct, st) = (m.sym("ct"), m.sym("st"));
    let g = &mut m.graph;
    let in_phase = partial(g, forcing[0], ct);
    let quadrature = partial(g, forcing[0], st);
    let y_cos = partial(g, forcing[1], ct);
    let y_sin = partial(g, forcing[1], st);
    let minus_quadrature = g.neg(quadrature);
    assert_same(
        m,
        y_sin,
        in_phase,
        "the y forcing's sin θ part equals the x forcing's cos θ part",
    );
    assert_same(
        m,
        y_cos,
        minus_quadrature,
        "the y forcing's cos θ part is minus the x forcing's sin θ part",
    );
    let force = m.derived("unbalance_force");
    let g = &mut m.graph;
    let in_phase_ratio = g.div(in_phase, force);
    let quadrature_ratio = g.div(quadrature, force);
    m.add_formula(
        "held_speed_forcing",
        "The unbalance forcing with η and η' held constant as one rotating harmonic: x = a_c cos θ + a_s sin θ, y = a_c sin θ − a_s cos θ, i.e. A (cos(θ − δ), sin(θ − δ)), A = √(a_c² + a_s²), δ = atan2(a_s, a_c); and the same coefficients relative to the constant-speed amplitude F, so that the held forcing is the constant-speed one with the unbalance scaled by √(r_c² + r_s²) and the phase moved by δ.",
        "docs/MODEL.md §14",
        "the coefficients of cos θ and sin θ in the x component of the model's `unbalance_at_varying_speed`; the y component is checked to be the same harmonic a quarter turn on.",
        "HeldForcing",
        vec![
            ("in_phase", "a_c = η_m ρ̂ η², the cos θ coefficient of the x forcing", in_phase),
            ("quadrature", "a_s = η_m ρ̂ η', the sin θ coefficient of the x forcing", quadrature),
            ("in_phase_ratio", "r_c = a_c/F", in_phase_ratio),
            ("quadrature_ratio", "r_s = a_s/F", quadrature_ratio),
        ],
    );
}

/// The whole varying-speed unbalance, for the verification tests (`tests/generated`).
fn varying_speed_unbalance(m: &mut Model, forcing: Vec2) {
    m.add_test_formula(
        "varying_speed_unbalance",
        "The unbalance forcing η_m ρ̂ (η² (cos θ, sin θ) − η' (−sin θ, cos θ)) at a changing speed.",
        "docs/MODEL.md §14",
        "the model's `unbalance_at_varying_speed`.",
        "Force",
        vec![
            ("fx", "x component", forcing[0]),
            ("fy", "y component", forcing[1]),
        ],
    );
}
