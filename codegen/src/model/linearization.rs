//! Taylor linearization of the contact function and the linearized stiffness (`docs/MODEL.md` §2–3).

use super::Model;
use crate::derive::partial;

pub(super) fn derive(m: &mut Model) {
    taylor_terms(m);
    linearized_stiffness(m);
}

/// A1 … D2: the model's contact function g (`Model::contact_function`) expanded to first order
/// about (x0, y0).
fn taylor_terms(m: &mut Model) {
    let (x, y) = (m.var("x"), m.var("y"));
    let [gx, gy] = m.contact_function([x, y]);
    let g = &mut m.graph;
    let (sx, sy) = (g.symbol("x"), g.symbol("y"));
    let a1 = partial(g, gx, sx);
    let b1 = partial(g, gx, sy);
    let b2 = partial(g, gy, sx);
    let a2 = partial(g, gy, sy);
    // D = g(r0) − J r0, so that g ≈ J r + D.
    let d1 = {
        let t1 = g.mul(a1, x);
        let t2 = g.mul(b1, y);
        let s = g.add(t1, t2);
        g.sub(gx, s)
    };
    let d2 = {
        let t1 = g.mul(b2, x);
        let t2 = g.mul(a2, y);
        let s = g.add(t1, t2);
        g.sub(gy, s)
    };
    let (x0, y0) = (m.var("lx"), m.var("ly"));
    let at = |m: &mut Model, e| m.subst(e, &[("x", x0), ("y", y0)]);
    let outs = [a1, b1, b2, a2, d1, d2].map(|e| at(m, e));
    m.add_formula(
        "taylor_terms",
        "Taylor terms A1, B1, B2, A2, D1, D2 of the contact function g about (x0, y0): g ≈ J r + D with J = [[A1, B1], [B2, A2]].",
        "docs/MODEL.md §2",
        "partial derivatives of g = (1 − 1/z)(x − εx, y − εy) at (x0, y0); D = g(r0) − J r0.",
        "TaylorTerms",
        vec![
            ("a1", "A1 = ∂gx/∂x", outs[0]),
            ("b1", "B1 = ∂gx/∂y", outs[1]),
            ("b2", "B2 = ∂gy/∂x", outs[2]),
            ("a2", "A2 = ∂gy/∂y", outs[3]),
            ("d1", "D1 = gx(r0) − A1 x0 − B1 y0", outs[4]),
            ("d2", "D2 = gy(r0) − B2 x0 − A2 y0", outs[5]),
        ],
    );
}

/// Kl = I + K_s J and Fd = K_s D, read off the linearized equations of motion: the model's
/// stiffness term with the contact function g replaced by its Taylor form J q + D.
fn linearized_stiffness(m: &mut Model) {
    let q = [m.var("x"), m.var("y")];
    // K_s's symbols first: the graph orders operands by creation, so this keeps the emitted
    // operation order (and the runtime's bits) of the hand-assembled form this replaced.
    m.stator_stiffness();
    let j = [[m.var("a1"), m.var("b1")], [m.var("b2"), m.var("a2")]];
    let d = [m.var("d1"), m.var("d2")];
    let mut lin = [q[0]; 2];
    for i in 0..2 {
        let g = &mut m.graph;
        let jq = g.mul(j[i][0], q[0]);
        let jq2 = g.mul(j[i][1], q[1]);
        lin[i] = g.sum(&[jq, jq2, d[i]]);
    }
    // The stiffness part of the contact equations: q + K_s (J q + D).
    let restoring = m.restoring(q);
    let contact = m.stator_force(lin);
    let g = &mut m.graph;
    let term = [0, 1].map(|i| g.add(restoring[i], contact[i]));
    let (sx, sy) = (g.symbol("x"), g.symbol("y"));
    let kl = [
        [partial(g, term[0], sx), partial(g, term[0], sy)],
        [partial(g, term[1], sx), partial(g, term[1], sy)],
    ];
    let zero = g.constant(0.0);
    let fd = [term[0], term[1]].map(|t| m.subst(t, &[("x", zero), ("y", zero)]));
    m.add_formula(
        "linearized_stiffness",
        "Linearized contact stiffness Kl = [[Fa1, Fb1], [Fb2, Fa2]] = I + K_s J and constant Fd = K_s D (erratum 2: Fb2 is the y–x entry, Fa2 the diagonal).",
        "docs/MODEL.md §3, errata 2–3",
        "coefficients of x and y, and the constant, of q + K_s (J q + D) in the equations of motion.",
        "LinearizedContact",
        vec![
            ("fa1", "Fa1 = Kl[0][0] (x equation, coefficient of x)", kl[0][0]),
            ("fb1", "Fb1 = Kl[0][1] (x equation, coefficient of y)", kl[0][1]),
            ("fb2", "Fb2 = Kl[1][0] (y equation, coefficient of x)", kl[1][0]),
            ("fa2", "Fa2 = Kl[1][1] (y equation, coefficient of y)", kl[1][1]),
            ("fd1", "Fd1 = (K_s D)_x, the x equation's constant", fd[0]),
            ("fd2", "Fd2 = (K_s D)_y, the y equation's constant", fd[1]),
        ],
    );
}
