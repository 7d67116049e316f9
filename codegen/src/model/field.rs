//! The nonlinear field itself and what the runtime's contact schemes need from it
//! (`docs/MODEL.md` §1, §3, §8): the contact force, the free acceleration, the
//! nonlinear remainder of the Taylor linearization, the linear contact acceleration the series
//! response recurs on, and the shifted stiffness A = Kl − ν²I of the closed form's bounds. Each
//! is assembled from the named pieces of the model statement ([`Model::acceleration`] and its
//! parts), so a new piece there reaches every one of them.

use super::{Model, Rates, Vec2};

pub(super) fn derive(m: &mut Model) {
    contact_remainder(m);
    linear_acceleration(m);
    shifted_stiffness(m);
}

fn position(m: &mut Model) -> Vec2 {
    [m.var("lx"), m.var("ly")]
}

/// n(q) = Kl q + Fd − q − K_s g(q).
fn contact_remainder(m: &mut Model) {
    let q = position(m);
    let (kl, fd) = m.linearized_inputs();
    let linear = m.linear_stiffness_term(kl, fd, q);
    let full = m.stiffness(q, Some(None));
    let g = &mut m.graph;
    let n = [0, 1].map(|i| g.sub(linear[i], full[i]));
    m.add_formula(
        "contact_remainder",
        "The nonlinear remainder n(q) = Kl q + Fd − q − K_s·g(q) of the Taylor-linearized contact field, as a force on the acceleration (zero at the linearization point).",
        "docs/MODEL.md §3, §8",
        "the linearized stiffness term minus the model's contact stiffness term.",
        "Force",
        vec![("fx", "n_x", n[0]), ("fy", "n_y", n[1])],
    );
}

/// q'' = a − 2ν q' − Kl q: the linearized contact equations without Fd and unbalance, under an
/// extra force a (the series response's recurrence).
fn linear_acceleration(m: &mut Model) {
    let q = position(m);
    let v = [m.var("vx"), m.var("vy")];
    let load = [m.var("fx"), m.var("fy")];
    let (kl, _) = m.linearized_inputs();
    let zero = m.graph.constant(0.0);
    let stiffness = m.linear_stiffness_term(kl, [zero, zero], q);
    let a = m.acceleration(v, stiffness, load);
    m.add_formula(
        "linear_acceleration",
        "Acceleration of the linearized contact equations under an extra force only: q'' = a − 2ν q' − Kl q (Fd and the unbalance are carried by the particular solution).",
        "docs/MODEL.md §3, §8",
        "the model's acceleration with the linearized stiffness term Kl q and the force a.",
        "Acceleration",
        vec![("ax", "x''", a[0]), ("ay", "y''", a[1])],
    );
}

/// A = Kl − ν²I: with q = e^{−νs} p the homogeneous linearized equations become p'' + A p = 0.
fn shifted_stiffness(m: &mut Model) {
    let [px, py, vpx, vpy, apx, apy, decay] =
        ["x", "y", "vx", "vy", "ax", "ay", "decay"].map(|n| m.var(n));
    let nu = m.var("damping_ratio");
    let (kl, _) = m.linearized_inputs();
    let mut rates = Rates::new();
    let g = &mut m.graph;
    let r_decay = {
        let t = g.mul(nu, decay);
        g.neg(t)
    };
    for (name, r) in [
        ("decay", r_decay),
        ("x", vpx),
        ("y", vpy),
        ("vx", apx),
        ("vy", apy),
    ] {
        let s = g.symbol(name);
        rates.insert(s, r);
    }
    let q = [g.mul(decay, px), g.mul(decay, py)];
    let zero = g.constant(0.0);
    let stiffness = m.linear_stiffness_term(kl, [zero, zero], q);
    let r = m.equations_of_motion(q, &rates, stiffness, [zero, zero]);
    // r = e^{−νs}(p'' + A p): at decay = 1, p' = p'' = 0 its coefficients of p are A.
    let one = m.graph.constant(1.0);
    let at = [
        ("decay", one),
        ("vx", zero),
        ("vy", zero),
        ("ax", zero),
        ("ay", zero),
    ];
    let r = r.map(|ri| m.subst(ri, &at));
    let a = [
        m.coefficients(r[0], &[px, py]),
        m.coefficients(r[1], &[px, py]),
    ];
    m.add_formula(
        "shifted_stiffness",
        "A = Kl − ν²I, the stiffness of the homogeneous contact equations after the substitution q = e^{−νs} p (p'' + A p = 0): its norm bounds the closed form's growth.",
        "docs/MODEL.md §5",
        "q = e^{−νs} p substituted into the homogeneous linearized equations; the coefficients of p at p' = p'' = 0.",
        "ShiftedStiffness",
        vec![
            ("a11", "A[0][0]", a[0][0]),
            ("a12", "A[0][1]", a[0][1]),
            ("a21", "A[1][0]", a[1][0]),
            ("a22", "A[1][1]", a[1][1]),
        ],
    );
}
