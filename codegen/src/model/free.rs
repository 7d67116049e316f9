//! Free flight (`docs/MODEL.md` §4): steady-state harmonic response, damped frequency, and the robust
//! closed form x_h = X·EC + P·ES, with EC = e^{−νs} cos βs and ES = e^{−νs} sin(βs)/β.

use super::{Model, Rates};
use crate::derive::derivative;

pub(super) fn derive(m: &mut Model) {
    free_particular(m);
    damped_frequency(m);
    free_homogeneous(m);
    free_eval(m);
    super::free_step::derive(m);
    free_forcing(m);
    free_start(m);
    free_forced_eval(m);
    input_static_deflection(m);
}

/// The constant response of free flight to the input force u (`docs/MODEL.md` §15): a constant
/// ansatz in the free equations with u as the only forcing. Free flight under a constant u is
/// free flight about this point, so the runtime moves the origin there and keeps every free
/// closed form (superposition: the equations are linear).
fn input_static_deflection(m: &mut Model) {
    let q = [m.var("qsx"), m.var("qsy")];
    let stiffness = m.stiffness(q, None);
    let forcing = m.input_force();
    let r = m.equations_of_motion(q, &Rates::new(), stiffness, forcing);
    let c = m.solve(&r, &["qsx", "qsy"]);
    m.add_formula(
        "input_static_deflection",
        "The static deflection of free flight under a constant input force u: the constant solution of q'' + 2νq' + q = u.",
        "docs/MODEL.md §15",
        "constant ansatz substituted into the free equations of motion with the input force as the only forcing, solved for the constants.",
        "Position",
        vec![("x", "x of the static deflection", c[0]), ("y", "y of the static deflection", c[1])],
    );
}

/// c11 … c44: the harmonic ansatz substituted into the free equations; coefficients of cos θ and
/// sin θ set to zero.
fn free_particular(m: &mut Model) {
    let mut rates = Rates::new();
    let ph = m.forcing_phasor(&mut rates);
    let [c11, c22, c33, c44] = ["c11", "c22", "c33", "c44"].map(|n| m.var(n));
    let q = harmonic(m, ph, [c11, c22, c33, c44]);
    let forcing = m.unbalance(ph);
    let r = m.equations_of_motion(q, &rates, q, forcing);
    let mut eqs = m.coefficients(r[0], &ph);
    eqs.extend(m.coefficients(r[1], &ph));
    let c = m.solve(&eqs, &["c11", "c22", "c33", "c44"]);
    m.add_formula(
        "free_particular",
        "Steady-state harmonic response of free flight: xp = c11 cos θ + c22 sin θ, yp = c33 cos θ + c44 sin θ.",
        "docs/MODEL.md §4, eqs. (5)–(6)",
        "harmonic ansatz substituted into the free equations of motion; the 4×4 system for the coefficients of cos θ and sin θ solved by Cramer's rule.",
        "FreeParticular",
        vec![
            ("c11", "c11, cos θ coefficient of x", c[0]),
            ("c22", "c22, sin θ coefficient of x", c[1]),
            ("c33", "c33, cos θ coefficient of y", c[2]),
            ("c44", "c44, sin θ coefficient of y", c[3]),
        ],
    );
}

/// The harmonic ansatz (c11 cos θ + c22 sin θ, c33 cos θ + c44 sin θ).
pub(super) fn harmonic(
    m: &mut Model,
    ph: [crate::expr::ExprId; 2],
    c: [crate::expr::ExprId; 4],
) -> [crate::expr::ExprId; 2] {
    let g = &mut m.graph;
    let a = g.mul(c[0], ph[0]);
    let b = g.mul(c[1], ph[1]);
    let x = g.add(a, b);
    let a = g.mul(c[2], ph[0]);
    let b = g.mul(c[3], ph[1]);
    let y = g.add(a, b);
    [x, y]
}

/// β² and γ²: the ansatz e^{−ντ} cos(√(b) τ) in a mode of stiffness ω² leaves the residual
/// ω² − ν² − b at τ = 0, so b = ω² − ν² (free flight: ω² = 1).
fn damped_frequency(m: &mut Model) {
    let tau = m.var("tau");
    let nu = m.var("damping_ratio");
    let bsq = m.var("bsq");
    let omega_sq = m.var("omega_sq");
    let g = &mut m.graph;
    let t_sym = g.symbol("tau");
    let one = g.constant(1.0);
    let rates = Rates::from([(t_sym, one)]);
    let decay = {
        let a = g.mul(nu, tau);
        let a = g.neg(a);
        g.exp(a)
    };
    let osc = {
        let b = g.sqrt(bsq);
        let a = g.mul(b, tau);
        g.cos(a)
    };
    let x = g.mul(decay, osc);
    let zero = g.constant(0.0);
    let stiff = g.mul(omega_sq, x);
    let r = m.equations_of_motion([x, zero], &rates, [stiff, zero], [zero, zero]);
    let at0 = m.subst(r[0], &[("tau", zero)]);
    let b = m.solve(&[at0], &["bsq"])[0];
    m.add_test_formula(
        "damped_frequency_sq",
        "Squared damped frequency γ² = ω² − ν² of a mode of undamped frequency² ω² (β² for free flight, ω² = 1); negative when over-damped.",
        "docs/MODEL.md §4 (β), §5 (γ_i), §6 cases 4–6, 11",
        "ansatz e^{−ντ} cos(√b τ) substituted into the homogeneous equation x'' + 2νx' + ω²x = 0, residual at τ = 0 solved for b.",
        "DampedFrequency",
        vec![("gamma_sq", "γ² = ω² − ν²", b)],
    );
    let one = m.graph.constant(1.0);
    let beta = m.subst(b, &[("omega_sq", one)]);
    m.add_formula(
        "free_damped_frequency_sq",
        "Squared damped frequency β² = 1 − ν² of free flight (negative for ν > 1, zero at critical damping).",
        "docs/MODEL.md §4",
        "`damped_frequency_sq` at ω² = 1.",
        "FreeDampedFrequency",
        vec![("beta_sq", "β² = 1 − ν²", beta)],
    );
}

/// The robust basis: EC(0) = 1, ES(0) = 0, EC' = −ν EC − β² ES, ES' = EC − ν ES.
pub(super) fn damped_basis(
    m: &mut Model,
    rates: &mut Rates,
    ec: &str,
    es: &str,
    bsq: &str,
) -> [crate::expr::ExprId; 2] {
    let (c, s) = (m.var(ec), m.var(es));
    let nu = m.var("damping_ratio");
    let b = m.var(bsq);
    let g = &mut m.graph;
    let rc = {
        let a = g.mul(nu, c);
        let bb = g.mul(b, s);
        let t = g.add(a, bb);
        g.neg(t)
    };
    let rs = {
        let a = g.mul(nu, s);
        g.sub(c, a)
    };
    rates.insert(g.symbol(ec), rc);
    rates.insert(g.symbol(es), rs);
    [c, s]
}

/// Free trajectory x = X·EC + P·ES + xp (and y alike) as an expression of the basis values.
pub(super) fn free_trajectory(m: &mut Model, rates: &mut Rates) -> [crate::expr::ExprId; 2] {
    let ph = m.forcing_phasor(rates);
    let [ec, es] = damped_basis(m, rates, "ec", "es", "beta_sq");
    let c = ["c11", "c22", "c33", "c44"].map(|n| m.var(n));
    let p = harmonic(m, ph, c);
    let [xh, yh, px, py] = ["xh", "yh", "px", "py"].map(|n| m.var(n));
    let g = &mut m.graph;
    let hx = {
        let a = g.mul(xh, ec);
        let b = g.mul(px, es);
        g.add(a, b)
    };
    let hy = {
        let a = g.mul(yh, ec);
        let b = g.mul(py, es);
        g.add(a, b)
    };
    [g.add(hx, p[0]), g.add(hy, p[1])]
}

/// X, P, Y, Q of the steady form from the state (x0, y0, vx0, vy0) and the forcing phasor
/// (ct, st) at the segment start: the initial conditions of the trajectory at s = 0.
pub(super) fn homogeneous_constants(m: &mut Model) -> Vec<crate::expr::ExprId> {
    let mut rates = Rates::new();
    let q = free_trajectory(m, &mut rates);
    let (one, zero) = (m.graph.constant(1.0), m.graph.constant(0.0));
    let eqs = m.initial_conditions(
        q,
        &rates,
        &[("ec", one), ("es", zero)],
        [("x0", "vx0"), ("y0", "vy0")],
    );
    m.solve(&eqs, &["xh", "px", "yh", "py"])
}

/// X, P (and Y, Q) from the state at the segment start.
fn free_homogeneous(m: &mut Model) {
    let c = homogeneous_constants(m);
    m.add_formula(
        "free_homogeneous",
        "Constants X, P, Y, Q of the free homogeneous solution x_h = X·EC(s) + P·ES(s) from the state (x0, y0, vx0, vy0) and forcing phase (cos θ0, sin θ0) at the segment start (P = c2·β of the paper; no division by β).",
        "docs/MODEL.md §4 (robust form), §6 cases 11–12",
        "initial conditions of the trajectory X·EC + P·ES + xp at s = 0 (EC = 1, ES = 0) solved for X, P, Y, Q.",
        "FreeHomogeneous",
        vec![
            ("xh", "X = x0 − xp(τ0)", c[0]),
            ("px", "P = x0' − xp'(τ0) + ν X", c[1]),
            ("yh", "Y = y0 − yp(τ0)", c[2]),
            ("py", "Q = y0' − yp'(τ0) + ν Y", c[3]),
        ],
    );
}

/// State and switching function at local time s of a free segment.
fn free_eval(m: &mut Model) {
    let mut rates = Rates::new();
    let q = free_trajectory(m, &mut rates);
    let outputs = state_and_event(m, q, &rates);
    m.add_formula(
        "free_eval",
        "State (x, y, x', y') and switching function h = z² − 1 with h' on a free segment, from the basis values EC(s), ES(s) and the forcing phasor (cos θ, sin θ).",
        "docs/MODEL.md §4, eq. (10)",
        "the trajectory X·EC + P·ES + xp and its total derivative using EC' = −νEC − β²ES, ES' = EC − νES, (cos θ)' = −η sin θ, (sin θ)' = η cos θ.",
        "FreeState",
        outputs,
    );
}

/// The forcing over a free segment as a_x cos ηs + b_x sin ηs (and y alike): the model's forcing
/// at θ = θ0 + ηs, the phasor rotated by angle addition, coefficients of cos ηs and sin ηs.
fn free_forcing(m: &mut Model) {
    let [ct, st, ce, se] = ["ct", "st", "ce", "se"].map(|n| m.var(n));
    let g = &mut m.graph;
    let c = {
        let a = g.mul(ct, ce);
        let b = g.mul(st, se);
        g.sub(a, b)
    };
    let s = {
        let a = g.mul(st, ce);
        let b = g.mul(ct, se);
        g.add(a, b)
    };
    let forcing = m.unbalance([c, s]);
    let x = m.coefficients(forcing[0], &[ce, se]);
    let y = m.coefficients(forcing[1], &[ce, se]);
    m.add_formula(
        "free_forcing",
        "Coefficients of cos ηs and sin ηs in the forcing over a free segment that starts at forcing phase (cos θ0, sin θ0): fx = fxc cos ηs + fxs sin ηs, fy = fyc cos ηs + fys sin ηs.",
        "docs/MODEL.md §1, §11",
        "the forcing at θ = θ0 + ηs with the phasor rotated by angle addition; coefficients of cos ηs and sin ηs by partial differentiation.",
        "FreeForcing",
        vec![
            ("fxc", "cos ηs coefficient of the x forcing", x[0]),
            ("fxs", "sin ηs coefficient of the x forcing", x[1]),
            ("fyc", "cos ηs coefficient of the y forcing", y[0]),
            ("fys", "sin ηs coefficient of the y forcing", y[1]),
        ],
    );
}

/// The resonance-stable free trajectory: homogeneous part from the start state plus the
/// zero-state forced response, x = X·EC + P·ES + fxc·FC + fxs·FS (and y alike), where FC, FS
/// (derivatives FC', FS', both zero at s = 0) answer cos ηs and sin ηs.
fn forced_trajectory(m: &mut Model, rates: &mut Rates) -> [crate::expr::ExprId; 2] {
    let [ec, es] = damped_basis(m, rates, "ec", "es", "beta_sq");
    let [fc, fs, dfc, dfs] = ["fc", "fs", "dfc", "dfs"].map(|n| m.var(n));
    let (fc_sym, fs_sym) = (m.sym("fc"), m.sym("fs"));
    rates.insert(fc_sym, dfc);
    rates.insert(fs_sym, dfs);
    let [xh, yh, px, py] = ["xh", "yh", "px", "py"].map(|n| m.var(n));
    let [ax, bx, ay, by] = ["fxc", "fxs", "fyc", "fys"].map(|n| m.var(n));
    let g = &mut m.graph;
    let mut component = |h: [crate::expr::ExprId; 2], f: [crate::expr::ExprId; 2]| {
        let terms = [
            g.mul(h[0], ec),
            g.mul(h[1], es),
            g.mul(f[0], fc),
            g.mul(f[1], fs),
        ];
        g.sum(&terms)
    };
    [component([xh, px], [ax, bx]), component([yh, py], [ay, by])]
}

/// X, P, Y, Q of the resonance-stable form from the start state (the forced part starts at rest).
fn free_start(m: &mut Model) {
    let mut rates = Rates::new();
    let q = forced_trajectory(m, &mut rates);
    let (one, zero) = (m.graph.constant(1.0), m.graph.constant(0.0));
    let at_start: Vec<(&str, crate::expr::ExprId)> = vec![
        ("ec", one),
        ("es", zero),
        ("fc", zero),
        ("fs", zero),
        ("dfc", zero),
        ("dfs", zero),
    ];
    let eqs = m.initial_conditions(q, &rates, &at_start, [("x0", "vx0"), ("y0", "vy0")]);
    let c = m.solve(&eqs, &["xh", "px", "yh", "py"]);
    m.add_formula(
        "free_start",
        "Constants X, P, Y, Q of the resonance-stable free form x = X·EC + P·ES + fxc·FC + fxs·FS from the start state (the forced part FC, FS starts at rest).",
        "docs/MODEL.md §4, §11",
        "initial conditions of the trajectory at s = 0 (EC = 1, ES = FC = FS = FC' = FS' = 0) solved for X, P, Y, Q.",
        "FreeHomogeneous",
        vec![
            ("xh", "X = x0", c[0]),
            ("px", "P = x0' + ν x0", c[1]),
            ("yh", "Y = y0", c[2]),
            ("py", "Q = y0' + ν y0", c[3]),
        ],
    );
}

/// State and switching function of the resonance-stable free form.
fn free_forced_eval(m: &mut Model) {
    let mut rates = Rates::new();
    let q = forced_trajectory(m, &mut rates);
    let outputs = state_and_event(m, q, &rates);
    m.add_formula(
        "free_forced_eval",
        "State (x, y, x', y') and switching function h = z² − 1 with h' of the resonance-stable free form, from the basis values EC, ES and the forced basis FC, FS, FC', FS' at s.",
        "docs/MODEL.md §4, §11, eq. (10)",
        "the trajectory X·EC + P·ES + fxc·FC + fxs·FS and its total derivative using EC' = −νEC − β²ES, ES' = EC − νES, FC' and FS' as given.",
        "ForcedFreeState",
        outputs,
    );
}

/// The outputs of a segment evaluation: the state of trajectory `q` (velocities by total
/// derivative with `rates`) and the switching function h = z² − 1 with h'.
fn state_and_event(
    m: &mut Model,
    q: [crate::expr::ExprId; 2],
    rates: &Rates,
) -> Vec<(&'static str, &'static str, crate::expr::ExprId)> {
    let (ex, ey) = (m.var("offset_x"), m.var("offset_y"));
    let g = &mut m.graph;
    let vx = derivative(g, q[0], rates);
    let vy = derivative(g, q[1], rates);
    let u = g.sub(q[0], ex);
    let v = g.sub(q[1], ey);
    let uu = g.mul(u, u);
    let vv = g.mul(v, v);
    let m1 = g.constant(-1.0);
    let h = g.sum(&[uu, vv, m1]);
    let dh = derivative(g, h, rates);
    vec![
        ("x", "x", q[0]),
        ("y", "y", q[1]),
        ("vx", "x'", vx),
        ("vy", "y'", vy),
        ("h", "h = z² − 1", h),
        ("dh", "h' = dh/dτ", dh),
    ]
}
