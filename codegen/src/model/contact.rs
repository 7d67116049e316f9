//! Contact regime, linearized (`docs/MODEL.md` §5): particular solution, modes, the paper's modal
//! constants, and the matrix-function form of the homogeneous solution that the runtime uses in
//! every case of §6.

use super::free::harmonic;
use super::{Model, Rates};
use crate::derive::{derivative, determinant};
use crate::expr::ExprId;

pub(super) fn derive(m: &mut Model) {
    contact_particular(m);
    contact_particular_residual(m);
    contact_particular_correction(m);
    contact_particular_eval(m);
    contact_modes(m);
    mode_shapes(m);
    paper_modal_constants(m);
    homogeneous_start(m);
    homogeneous_eval(m);
    input_contact_constant(m);
}

/// The constant response of the linearized contact equations to the input force u
/// (`docs/MODEL.md` §15): Kl q = u. Added to the particular solution's constants c55, c66
/// (superposition), it makes every contact closed form exact under a constant u; the remainder
/// n(q) does not depend on u.
fn input_contact_constant(m: &mut Model) {
    let q = [m.var("qsx"), m.var("qsy")];
    let (kl, _) = m.linearized_inputs();
    let zero = m.graph.constant(0.0);
    let stiffness = m.linear_stiffness_term(kl, [zero, zero], q);
    let forcing = m.input_force();
    let r = m.equations_of_motion(q, &Rates::new(), stiffness, forcing);
    let c = m.solve(&r, &["qsx", "qsy"]);
    m.add_formula(
        "input_contact_constant",
        "The constant response Kl⁻¹u of the linearized contact equations to a constant input force u, added to the particular constants c55, c66.",
        "docs/MODEL.md §15, §5",
        "constant ansatz substituted into q'' + 2νq' + Kl q = u, solved by Cramer's rule.",
        "Position",
        vec![("x", "x of Kl⁻¹u", c[0]), ("y", "y of Kl⁻¹u", c[1])],
    );
}

/// Harmonic + constant ansatz in Kl q + Fd: c11 … c44 from cos θ / sin θ, c55, c66 from the
/// constant part.
fn contact_particular(m: &mut Model) {
    let eqs = particular_equations(m, true, |m, ph| m.unbalance(ph));
    let s = m.solve(&eqs, &["cp11", "cp22", "cp33", "cp44", "cp55", "cp66"]);
    m.add_formula(
        "contact_particular",
        "Particular solution of the linearized contact equations: xp = c11 cos θ + c22 sin θ + c55, yp = c33 cos θ + c44 sin θ + c66.",
        "docs/MODEL.md §5 (particular part), eqs. (8)–(9)",
        "harmonic-plus-constant ansatz substituted into q'' + 2νq' + Kl q + Fd = F(cos θ, sin θ); the system splits into a 2×2 block (constants, Kl⁻¹) and a 4×4 block (harmonic), each solved by Cramer's rule.",
        "ContactParticular",
        vec![
            ("c11", "c11, cos θ coefficient of x", s[0]),
            ("c22", "c22, sin θ coefficient of x", s[1]),
            ("c33", "c33, cos θ coefficient of y", s[2]),
            ("c44", "c44, sin θ coefficient of y", s[3]),
            ("c55", "c55, constant of x: −(Kl⁻¹ Fd)_x", s[4]),
            ("c66", "c66, constant of y: −(Kl⁻¹ Fd)_y", s[5]),
        ],
    );
}

/// The six equations the particular constants c11 … c66 solve: the linearized contact
/// equations with the harmonic-plus-constant ansatz, split into their cos θ, sin θ and constant
/// parts (x equation, then y), with Fd in the stiffness term or not (`with_fd`) and the forces
/// `forcing` gives for the phasor.
fn particular_equations(
    m: &mut Model,
    with_fd: bool,
    forcing: fn(&mut Model, [ExprId; 2]) -> [ExprId; 2],
) -> Vec<ExprId> {
    let mut rates = Rates::new();
    let ph = m.forcing_phasor(&mut rates);
    let c = ["cp11", "cp22", "cp33", "cp44"].map(|n| m.var(n));
    let h = harmonic(m, ph, c);
    let (c55, c66) = (m.var("cp55"), m.var("cp66"));
    let q = [m.graph.add(h[0], c55), m.graph.add(h[1], c66)];
    let (kl, kl_fd) = m.linearized_inputs();
    let zero = m.graph.constant(0.0);
    let fd = if with_fd { kl_fd } else { [zero, zero] };
    let stiffness = m.linear_stiffness_term(kl, fd, q);
    let forcing = forcing(m, ph);
    let r = m.equations_of_motion(q, &rates, stiffness, forcing);
    let mut eqs = Vec::new();
    for ri in r {
        eqs.extend(m.coefficients(ri, &ph));
        eqs.push(m.subst(ri, &[("ct", zero), ("st", zero)]));
    }
    eqs
}

/// The residual of particular constants: what the six equations of [`contact_particular`] (with
/// the input force on the right-hand side, so that c55, c66 may hold Kl⁻¹u) leave when the
/// constants are put in. Cramer's rule solves them with an error of about ε·cond in the
/// constants, and the stiff mode of Kl turns that into a residual force of up to ε·cond·‖Kl‖
/// (1e-7 at K̂ = 1e5 near z = 1, where Kl's condition is 1e5): the closed form's velocity then
/// drifts from the linearized equations' solution at that rate, whatever the step. One
/// correction ([`contact_particular_correction`]) brings the residual to the rounding of its
/// own evaluation (`docs/MODEL.md` §5).
fn contact_particular_residual(m: &mut Model) {
    let eqs = particular_equations(m, true, |m, ph| m.forcing(ph));
    m.add_formula(
        "contact_particular_residual",
        "Residual of particular constants c11 … c66 in the linearized contact equations with the input force (cos θ, sin θ and constant parts of the x and y equations): zero for the exact constants.",
        "docs/MODEL.md §5 (particular part), §15",
        "the harmonic-plus-constant ansatz substituted into q'' + 2νq' + Kl q + Fd − F(cos θ, sin θ) − u, split by partial derivatives in cos θ, sin θ and the rest.",
        "ParticularResidual",
        vec![
            ("x_cos", "cos θ part of the x equation", eqs[0]),
            ("x_sin", "sin θ part of the x equation", eqs[1]),
            ("x_constant", "constant part of the x equation", eqs[2]),
            ("y_cos", "cos θ part of the y equation", eqs[3]),
            ("y_sin", "sin θ part of the y equation", eqs[4]),
            ("y_constant", "constant part of the y equation", eqs[5]),
        ],
    );
}

/// The correction of particular constants from their residual ([`contact_particular_residual`]):
/// δ with M δ + r = 0, M the equations' matrix (their part linear in the constants: Kl − η²I
/// with the damping's 2νη coupling for the harmonic constants, Kl for the constant ones), by
/// the same block-triangular Cramer solve as [`contact_particular`]. Added to the constants it
/// is one step of iterative refinement: the residual falls from ε·cond·‖Kl‖·|c| to the
/// rounding of its evaluation.
fn contact_particular_correction(m: &mut Model) {
    let eqs = particular_equations(m, false, |m, _| {
        let zero = m.graph.constant(0.0);
        [zero, zero]
    });
    let residual = ["pr_xc", "pr_xs", "pr_x0", "pr_yc", "pr_ys", "pr_y0"].map(|n| m.var(n));
    let eqs: Vec<ExprId> = eqs
        .iter()
        .zip(residual)
        .map(|(&e, r)| m.graph.add(e, r))
        .collect();
    let s = m.solve(&eqs, &["cp11", "cp22", "cp33", "cp44", "cp55", "cp66"]);
    m.add_formula(
        "contact_particular_correction",
        "Correction δ of particular constants from their residual r (`contact_particular_residual`): M δ + r = 0, the equations' matrix M without forcing; c + δ is one step of iterative refinement.",
        "docs/MODEL.md §5 (particular part)",
        "the ansatz substituted into q'' + 2νq' + Kl q with no forcing and no Fd, the residual added to each of the six equations, solved by Cramer's rule as for the particular constants.",
        "ContactParticular",
        vec![
            ("c11", "c11, cos θ coefficient of x", s[0]),
            ("c22", "c22, sin θ coefficient of x", s[1]),
            ("c33", "c33, cos θ coefficient of y", s[2]),
            ("c44", "c44, sin θ coefficient of y", s[3]),
            ("c55", "c55, constant of x: −(Kl⁻¹ Fd)_x", s[4]),
            ("c66", "c66, constant of y: −(Kl⁻¹ Fd)_y", s[5]),
        ],
    );
}

/// The particular trajectory and its velocity at a phase (cos θ, sin θ).
fn contact_particular_eval(m: &mut Model) {
    let mut rates = Rates::new();
    let ph = m.forcing_phasor(&mut rates);
    let c = ["cp11", "cp22", "cp33", "cp44"].map(|n| m.var(n));
    let h = harmonic(m, ph, c);
    let (c55, c66) = (m.var("cp55"), m.var("cp66"));
    let g = &mut m.graph;
    let q = [g.add(h[0], c55), g.add(h[1], c66)];
    let v = [derivative(g, q[0], &rates), derivative(g, q[1], &rates)];
    m.add_formula(
        "contact_particular_eval",
        "Position and velocity of the contact particular solution at forcing phase (cos θ, sin θ).",
        "docs/MODEL.md §5, eqs. (8)–(9)",
        "the harmonic-plus-constant trajectory and its total derivative ((cos θ)' = −η sin θ, (sin θ)' = η cos θ).",
        "ParticularState",
        vec![("x", "x_p", q[0]), ("y", "y_p", q[1]), ("vx", "x_p'", v[0]), ("vy", "y_p'", v[1])],
    );
}

/// The eigenvalues ω² of Kl: characteristic polynomial p(λ) = det(Kl − λI), shifted to its
/// mean so the discriminant is computed without cancellation.
fn contact_modes(m: &mut Model) {
    let (kl, _) = m.linearized_inputs();
    let lam = m.var("lam");
    let nu = m.var("damping_ratio");
    let g = &mut m.graph;
    let shifted = |g: &mut crate::expr::Graph, s: ExprId| {
        let d0 = g.sub(kl[0][0], s);
        let d1 = g.sub(kl[1][1], s);
        [[d0, kl[0][1]], [kl[1][0], d1]]
    };
    let a = shifted(g, lam);
    let p = determinant(g, &a);
    let l_sym = g.symbol("lam");
    let one = g.constant(1.0);
    let rates = Rates::from([(l_sym, one)]);
    let dp = derivative(g, p, &rates);
    let ddp = derivative(g, dp, &rates);
    let zero = g.constant(0.0);
    let map0 = std::collections::HashMap::from([(l_sym, zero)]);
    let c0 = g.substitute(p, &map0);
    let c1 = g.substitute(dp, &map0);
    let c2 = {
        let t = g.substitute(ddp, &map0);
        g.scale(0.5, t)
    };
    // p(λ) = c2 (λ − mean)² − c2 Δ, so mean = −c1/(2 c2) and Δ = −p(mean)/c2.
    let mean = {
        let t = g.div(c1, c2);
        g.scale(-0.5, t)
    };
    let at_mean = shifted(g, mean);
    let p_mean = determinant(g, &at_mean);
    let disc = {
        let t = g.div(p_mean, c2);
        g.neg(t)
    };
    let nn = g.mul(nu, nu);
    let gamma_mean = g.sub(mean, nn);
    let det = c0;
    m.add_formula(
        "contact_modes",
        "Eigenvalues of Kl: ω²₁,₂ = mean ∓ √Δ (complex when Δ < 0), det Kl = ω²₁ ω²₂, and the mean of γ² = ω² − ν².",
        "docs/MODEL.md §5 (modes), §6 cases 2, 7–9",
        "characteristic polynomial det(Kl − λI) = c2 λ² + c1 λ + c0 differentiated at λ = 0; mean = −c1/(2c2); Δ = −det(Kl − mean·I)/c2 (trace-free shift, no cancellation).",
        "ContactModes",
        vec![
            ("omega_sq_mean", "(ω²₁ + ω²₂)/2 = (Fa1 + Fa2)/2", mean),
            ("disc", "Δ = ((Fa1 − Fa2)/2)² + Fb1 Fb2", disc),
            ("det", "det Kl = Fa1 Fa2 − Fb1 Fb2", det),
            ("gamma_sq_mean", "(γ²₁ + γ²₂)/2 = mean − ν²", gamma_mean),
        ],
    );
}

/// Mode shapes: null vectors of each row of Kl − ω²I, and the paper's ratio s = y/x.
fn mode_shapes(m: &mut Model) {
    let (kl, _) = m.linearized_inputs();
    let w = m.var("omega_sq");
    let s = m.var("s_ratio");
    let g = &mut m.graph;
    let r1 = [g.sub(kl[0][0], w), kl[0][1]];
    let r2 = [kl[1][0], g.sub(kl[1][1], w)];
    // The null vector of a row (a, b) is (b, −a).
    let n1 = [r1[1], g.neg(r1[0])];
    let n2 = [g.neg(r2[1]), r2[0]];
    m.add_test_formula(
        "mode_shape",
        "Eigenvectors of Kl for eigenvalue ω², one from each row of (Kl − ω²I)v = 0; the runtime keeps the longer (`docs/MODEL.md` §6 case 1: Fb1 = 0).",
        "docs/MODEL.md §5 (s_i), §6 case 1",
        "null vector (b, −a) of each row (a, b) of Kl − ω²I.",
        "ModeShape",
        vec![
            ("row1_x", "x of (Fb1, ω² − Fa1)", n1[0]),
            ("row1_y", "y of (Fb1, ω² − Fa1)", n1[1]),
            ("row2_x", "x of (ω² − Fa2, Fb2)", n2[0]),
            ("row2_y", "y of (ω² − Fa2, Fb2)", n2[1]),
        ],
    );
    // The paper's s: the first eigen-equation (Fa1 − ω²)·1 + Fb1·s = 0 solved for s.
    let e = {
        let g = &mut m.graph;
        let t = g.mul(kl[0][1], s);
        g.add(r1[0], t)
    };
    let sol = m.solve(&[e], &["s_ratio"])[0];
    m.add_test_formula(
        "paper_mode_ratio",
        "The paper's mode ratio s = y/x = (ω² − Fa1)/Fb1 (valid only when Fb1 ≠ 0, erratum 7).",
        "docs/MODEL.md §5, erratum 7",
        "first row of (Kl − ω²I)(1, s) = 0 solved for s.",
        "PaperModeRatio",
        vec![("s", "s = (ω² − Fa1)/Fb1", sol)],
    );
}

/// c1 … c4 of eqs. (8)–(9) with γ2 in the s2 terms (erratum 5), from the homogeneous initial state.
fn paper_modal_constants(m: &mut Model) {
    let tau = m.var("tau");
    let [nu, g1, g2, s1, s2] = ["damping_ratio", "gamma1", "gamma2", "s1", "s2"].map(|n| m.var(n));
    let c = ["c1", "c2", "c3", "c4"].map(|n| m.var(n));
    let g = &mut m.graph;
    let t_sym = g.symbol("tau");
    let one = g.constant(1.0);
    let rates = Rates::from([(t_sym, one)]);
    let decay = {
        let a = g.mul(nu, tau);
        let a = g.neg(a);
        g.exp(a)
    };
    let mode = |g: &mut crate::expr::Graph, ca: ExprId, cb: ExprId, gam: ExprId| {
        let arg = g.mul(gam, tau);
        let co = g.cos(arg);
        let si = g.sin(arg);
        let a = g.mul(ca, co);
        let b = g.mul(cb, si);
        g.add(a, b)
    };
    let m1 = mode(g, c[0], c[1], g1);
    let m2 = mode(g, c[2], c[3], g2);
    let xs = g.add(m1, m2);
    let x = g.mul(decay, xs);
    let y = {
        let a = g.mul(s1, m1);
        let b = g.mul(s2, m2);
        let t = g.add(a, b);
        g.mul(decay, t)
    };
    let zero = m.graph.constant(0.0);
    let eqs = m.initial_conditions(
        [x, y],
        &rates,
        &[("tau", zero)],
        [("xh0", "vxh0"), ("yh0", "vyh0")],
    );
    let sol = m.solve(&eqs, &["c1", "c2", "c3", "c4"]);
    m.add_test_formula(
        "paper_modal_constants",
        "The paper's homogeneous constants c1 … c4 of eqs. (8)–(9), with γ2 in the s2 terms, from the homogeneous initial state (xh0, yh0, x'h0, y'h0) in local time.",
        "docs/MODEL.md §5 (homogeneous part), errata 5–7",
        "initial conditions of the modal ansatz e^{−ντ}[(1, s1)(c1 cos γ1τ + c2 sin γ1τ) + (1, s2)(c3 cos γ2τ + c4 sin γ2τ)] at τ = 0; positions then velocities, each a 2×2 Cramer solve.",
        "PaperModalConstants",
        vec![
            ("c1", "c1, cos γ1 s coefficient", sol[0]),
            ("c2", "c2, sin γ1 s coefficient", sol[1]),
            ("c3", "c3, cos γ2 s coefficient", sol[2]),
            ("c4", "c4, sin γ2 s coefficient", sol[3]),
        ],
    );
}

/// The matrix-function form q_h(s) = e^{−νs}[C(s) q0 + S(s) w0] with C = cos(√A s),
/// S = sin(√A s)/√A, A = Kl − ν²I, written as C = cc I + cd B, S = sc I + sd B for B = Kl − σI.
/// Returns (q_h, rates).
fn matrix_function_trajectory(m: &mut Model) -> ([ExprId; 2], Rates) {
    let (kl, _) = m.linearized_inputs();
    let [sigma, nu, decay, cc, cd, sc, sd] = [
        "omega_sq_mean",
        "damping_ratio",
        "decay",
        "cc",
        "cd",
        "sc",
        "sd",
    ]
    .map(|n| m.var(n));
    let [q0x, q0y, w0x, w0y] = ["q0x", "q0y", "w0x", "w0y"].map(|n| m.var(n));
    let g = &mut m.graph;
    let b = [
        [g.sub(kl[0][0], sigma), kl[0][1]],
        [kl[1][0], g.sub(kl[1][1], sigma)],
    ];
    let tr_b = g.add(b[0][0], b[1][1]);
    let det_b = determinant(g, &b);
    let nn = g.mul(nu, nu);
    let rho = g.sub(sigma, nn);
    // C' = −A S, S' = C, with A = B + ρI and B² = tr(B) B − det(B) I (Cayley–Hamilton).
    let mut rates = Rates::new();
    let r_cc = {
        let a = g.mul(rho, sc);
        let bb = g.mul(sd, det_b);
        g.sub(bb, a)
    };
    let r_cd = {
        let a = g.mul(rho, sd);
        let bb = g.mul(sd, tr_b);
        let t = g.sum(&[sc, a, bb]);
        g.neg(t)
    };
    let r_decay = {
        let t = g.mul(nu, decay);
        g.neg(t)
    };
    for (name, r) in [
        ("cc", r_cc),
        ("cd", r_cd),
        ("sc", cc),
        ("sd", cd),
        ("decay", r_decay),
    ] {
        let s = g.symbol(name);
        rates.insert(s, r);
    }
    let apply = |g: &mut crate::expr::Graph, a: ExprId, bcoef: ExprId, v: [ExprId; 2]| {
        let mut out = [v[0]; 2];
        for i in 0..2 {
            let bv0 = g.mul(b[i][0], v[0]);
            let bv1 = g.mul(b[i][1], v[1]);
            let bv = g.add(bv0, bv1);
            let t1 = g.mul(a, v[i]);
            let t2 = g.mul(bcoef, bv);
            out[i] = g.add(t1, t2);
        }
        out
    };
    let cq = apply(g, cc, cd, [q0x, q0y]);
    let sw = apply(g, sc, sd, [w0x, w0y]);
    let q = [0, 1].map(|i| {
        let t = g.add(cq[i], sw[i]);
        g.mul(decay, t)
    });
    (q, rates)
}

/// q0 and w0 from the homogeneous part of the start state: the ansatz at s = 0 has C = I, S = 0,
/// e^{−νs} = 1.
fn homogeneous_start(m: &mut Model) {
    let (q, rates) = matrix_function_trajectory(m);
    let (one, zero) = (m.graph.constant(1.0), m.graph.constant(0.0));
    let at0 = [
        ("decay", one),
        ("cc", one),
        ("cd", zero),
        ("sc", zero),
        ("sd", zero),
    ];
    let eqs = m.initial_conditions(q, &rates, &at0, [("xh0", "vxh0"), ("yh0", "vyh0")]);
    let sol = m.solve(&eqs, &["q0x", "w0x", "q0y", "w0y"]);
    m.add_formula(
        "contact_homogeneous_start",
        "Start vectors q0, w0 of the homogeneous contact solution q_h = e^{−νs}[C(s) q0 + S(s) w0] from its initial position and velocity.",
        "docs/MODEL.md §5 (alternative without eigenvectors)",
        "initial conditions of the matrix-function ansatz at s = 0 (C = I, S = 0, C' = 0, S' = I) solved for q0, w0.",
        "HomogeneousStart",
        vec![
            ("q0x", "q0, x", sol[0]),
            ("q0y", "q0, y", sol[2]),
            ("w0x", "w0 = q_h'(0) + ν q0, x", sol[1]),
            ("w0y", "w0, y", sol[3]),
        ],
    );
}

/// Position and velocity of the homogeneous contact solution from the scalar matrix-function
/// coefficients at s.
fn homogeneous_eval(m: &mut Model) {
    let (q, rates) = matrix_function_trajectory(m);
    let g = &mut m.graph;
    let v = [derivative(g, q[0], &rates), derivative(g, q[1], &rates)];
    m.add_formula(
        "contact_homogeneous_eval",
        "Homogeneous contact solution q_h = e^{−νs}[C q0 + S w0] and its velocity, from C = cc·I + cd·B, S = sc·I + sd·B (B = Kl − σI) and decay = e^{−νs}.",
        "docs/MODEL.md §5 (alternative without eigenvectors), §6 cases 1–8",
        "the matrix-function form and its total derivative using C' = −(B + (σ − ν²)I) S, S' = C reduced with Cayley–Hamilton B² = tr(B) B − det(B) I.",
        "HomogeneousState",
        vec![("x", "x_h", q[0]), ("y", "y_h", q[1]), ("vx", "x_h'", v[0]), ("vy", "y_h'", v[1])],
    );
}
