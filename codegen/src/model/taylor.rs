//! The contact fields whose Taylor recurrences the `taylor` method integrates (`docs/MODEL.md`
//! §16): each regime's field as an autonomous system of six states (x, y, x', y' and the forcing
//! phasor cos θ, sin θ, with θ' = η), assembled from the model's pieces like every other
//! formula, and the switch functions the method needs as polynomials:
//!
//! * frictionless contact (`contact_taylor`): h = z² − 1;
//! * slipping in direction σ (`slipping_taylor`): h and the slip velocity w;
//! * rolling (`rolling_taylor`): h and the friction margins μN − λ and μN + λ (|λ| ≤ μN while
//!   both are ≥ 0).

use super::friction::{frictionless_contact_acceleration, rolling_force};
use super::{Model, Rates, Vec2};
use crate::expr::ExprId;
use crate::ir::System;

pub(super) fn derive(m: &mut Model) {
    let contact = contact(m);
    let slipping = slipping(m);
    let rolling = rolling(m);
    m.taylor = vec![contact, slipping, rolling];
}

/// The state symbols and their rates: q' = v, v' = `acceleration`, and the phasor's.
fn states(m: &mut Model, acceleration: Vec2) -> Vec<(crate::expr::Symbol, ExprId)> {
    let mut rates = Rates::new();
    m.forcing_phasor(&mut rates);
    let (vx, vy) = (m.var("vx"), m.var("vy"));
    let [sx, sy, svx, svy, sct, sst] = ["lx", "ly", "vx", "vy", "ct", "st"].map(|n| m.sym(n));
    vec![
        (sx, vx),
        (sy, vy),
        (svx, acceleration[0]),
        (svy, acceleration[1]),
        (sct, rates[&sct]),
        (sst, rates[&sst]),
    ]
}

/// h = z² − 1 ([`Model::boundary`]): positive in contact.
fn boundary(m: &mut Model) -> (String, String, ExprId) {
    let q = [m.var("lx"), m.var("ly")];
    let h = m.boundary(q);
    (
        "boundary".to_owned(),
        "h = z² − 1 (positive in contact)".to_owned(),
        h,
    )
}

fn contact(m: &mut Model) -> System {
    let (_, _, acc) = frictionless_contact_acceleration(m);
    let states = states(m, acc);
    let observed = vec![boundary(m)];
    System {
        name: "contact_taylor".to_owned(),
        summary: "Frictionless contact: q'' = F(cos θ, sin θ) + u − 2ν q' − q − K_s·g(q)."
            .to_owned(),
        source: "docs/MODEL.md §1, §16".to_owned(),
        states,
        observed,
    }
}

fn slipping(m: &mut Model) -> System {
    let q = [m.var("lx"), m.var("ly")];
    let v = [m.var("vx"), m.var("vy")];
    let phasor = [m.var("ct"), m.var("st")];
    let sigma = m.var("sigma");
    let forcing = m.forcing(phasor);
    let stiffness = m.stiffness(q, Some(Some(sigma)));
    let acc = m.acceleration(v, stiffness, forcing);
    let states = states(m, acc);
    let w = m.slip_velocity(q, v);
    let observed = vec![
        boundary(m),
        (
            "slip_velocity".to_owned(),
            "the slip velocity w = q'·t + ρ_R η".to_owned(),
            w,
        ),
    ];
    System {
        name: "slipping_taylor".to_owned(),
        summary: "Slipping contact in direction σ: the frictionless contact field minus μσN t."
            .to_owned(),
        source: "docs/MODEL.md §10, §16".to_owned(),
        states,
        observed,
    }
}

fn rolling(m: &mut Model) -> System {
    let (q, v, acc) = frictionless_contact_acceleration(m);
    let normal = m.normal_force(q);
    let (lambda, _, t) = rolling_force(m, q, v, acc);
    let mu = m.var("friction_coefficient");
    let g = &mut m.graph;
    let a = [0, 1].map(|i| {
        let f = g.mul(lambda, t[i]);
        g.sub(acc[i], f)
    });
    let limit = g.mul(mu, normal);
    let upper = g.sub(limit, lambda);
    let lower = g.add(limit, lambda);
    let states = states(m, a);
    let observed = vec![
        boundary(m),
        (
            "cone_upper".to_owned(),
            "μN − λ (rolling needs it ≥ 0)".to_owned(),
            upper,
        ),
        (
            "cone_lower".to_owned(),
            "μN + λ (rolling needs it ≥ 0)".to_owned(),
            lower,
        ),
    ];
    System {
        name: "rolling_taylor".to_owned(),
        summary: "Rolling contact: the frictionless contact field minus λ t, λ the tangential force that keeps w = 0."
            .to_owned(),
        source: "docs/MODEL.md §10, §16".to_owned(),
        states,
        observed,
    }
}
