//! What the runtime needs of the model in every regime, so that it types no formula itself
//! (`docs/MODEL.md` §1, §10, §15): each regime's whole field (forcing and input force included),
//! the geometry of the contact surface (the switching function and its rate, the offset from
//! the stator centre and back), the rates of the friction switches, and the coefficients the
//! closed forms' bounds are built from. Each is assembled from the model statement's pieces
//! (`mod.rs`), so a new piece there reaches every one of them.
//!
//! Derived after every other formula, so that the nodes it creates come last in the graph and
//! the others keep their form.

use super::{Model, Rates, Vec2};
use crate::derive::{derivative, partial};
use crate::expr::ExprId;

pub(super) fn derive(m: &mut Model) {
    forcing_phase(m);
    ramp_phase(m);
    ramp_quantities(m);
    switching_function(m);
    switching_curvature(m);
    stator_offset(m);
    position_at_offset(m);
    regime_fields(m);
    unbalance_force_at(m);
    slip_velocity(m);
    slip_velocity_rate(m);
    slip_rate(m);
    cone_rates(m);
    linearized_contact_field(m);
    linear_field_jacobians(m);
    forcing_rate(m);
    harmonic_system(m);
    stator_bounds(m);
}

fn position(m: &mut Model) -> Vec2 {
    [m.var("lx"), m.var("ly")]
}

fn velocity(m: &mut Model) -> Vec2 {
    [m.var("vx"), m.var("vy")]
}

fn phasor(m: &mut Model) -> Vec2 {
    [m.var("ct"), m.var("st")]
}

/// Rates of a state moving with velocity `v` and acceleration `a` (and the forcing phasor's
/// rates when `with_phasor`): what a total time derivative along a field substitutes.
fn state_rates(m: &mut Model, v: Vec2, a: Vec2, with_phasor: bool) -> Rates {
    let mut rates = Rates::new();
    if with_phasor {
        m.forcing_phasor(&mut rates);
    }
    for (name, r) in [("lx", v[0]), ("ly", v[1]), ("vx", a[0]), ("vy", a[1])] {
        let s = m.graph.symbol(name);
        rates.insert(s, r);
    }
    rates
}

/// h = z² − 1 and h' = dh/dτ of a state: the sign of h is the regime, h' the radial velocity
/// (times 2z).
fn switching_function(m: &mut Model) {
    let q = position(m);
    let v = velocity(m);
    let h = m.boundary(q);
    let mut rates = Rates::new();
    for (name, r) in [("lx", v[0]), ("ly", v[1])] {
        let s = m.graph.symbol(name);
        rates.insert(s, r);
    }
    let dh = derivative(&mut m.graph, h, &rates);
    m.add_formula(
        "switching_function",
        "The switching function h = z² − 1 of a state (negative in free flight, positive in contact) and its rate h' = 2 (u x' + v y').",
        "docs/MODEL.md §1, §6 (cases 13–15)",
        "the model's `boundary` and its total time derivative.",
        "Switching",
        vec![("h", "h = z² − 1", h), ("dh", "h' = dh/dτ", dh)],
    );
}

/// h'' along a motion with acceleration a: what decides a start on z = 1 where h' vanishes.
fn switching_curvature(m: &mut Model) {
    let q = position(m);
    let v = velocity(m);
    let a = [m.var("ax"), m.var("ay")];
    let h = m.boundary(q);
    let rates = state_rates(m, v, a, false);
    let dh = derivative(&mut m.graph, h, &rates);
    let d2h = derivative(&mut m.graph, dh, &rates);
    m.add_formula(
        "switching_curvature",
        "The second rate h'' = 2 (|q'|² + d·a) of the switching function along a motion with acceleration a.",
        "docs/MODEL.md §6 (case 14)",
        "the second total time derivative of the model's `boundary` with q'' = a.",
        "SwitchingCurvature",
        vec![("d2h", "h''", d2h)],
    );
}

/// θ(τ) = ητ + φ0.
fn forcing_phase(m: &mut Model) {
    let (eta, phase, t) = (m.var("speed_ratio"), m.var("phase"), m.var("abs_time"));
    let g = &mut m.graph;
    let e = g.mul(eta, t);
    let theta = g.add(e, phase);
    m.add_formula(
        "forcing_phase",
        "The forcing phase θ(τ) = ητ + φ0 at a constant speed: the unbalance's angle.",
        "docs/MODEL.md §1",
        "the model's forcing phasor's angle, θ' = η, θ(0) = φ0.",
        "ForcingPhase",
        vec![("theta", "θ", theta)],
    );
}

/// θ(τ) = η_k τ + c + ½η'(τ − τ_k)² on a piece of a speed profile.
fn ramp_phase(m: &mut Model) {
    let (eta, rate, start, c, t) = (
        m.var("ramp_speed"),
        m.var("ramp_rate"),
        m.var("ramp_start"),
        m.var("ramp_constant"),
        m.var("abs_time"),
    );
    let g = &mut m.graph;
    let e = g.mul(eta, t);
    let linear = g.add(e, c);
    let s = g.sub(t, start);
    let rs = g.mul(rate, s);
    let rss = g.mul(rs, s);
    let half = g.scale(0.5, rss);
    let theta = g.add(linear, half);
    m.add_formula(
        "ramp_phase",
        "The forcing phase θ(τ) = η_k τ + c + ½η'(τ − τ_k)² on a piece of a speed profile; with η' = 0 and c = φ0 the constant-speed `forcing_phase`.",
        "docs/MODEL.md §14",
        "θ' = η(τ) = η_k + η'(τ − τ_k), integrated; written with the absolute time τ like the constant-speed phase.",
        "RampPhase",
        vec![("theta", "θ", theta)],
    );
}

/// The rest of a speed ramp's statement: its speed, the phase constant that gives a phase at a
/// time, and the time a phase advance takes.
fn ramp_quantities(m: &mut Model) {
    let (eta, rate, start, t) = (
        m.var("ramp_speed"),
        m.var("ramp_rate"),
        m.var("ramp_start"),
        m.var("abs_time"),
    );
    let theta = m.var("phase_value");
    let g = &mut m.graph;
    let s = g.sub(t, start);
    let rs = g.mul(rate, s);
    let speed = g.add(eta, rs);
    m.add_formula(
        "ramp_speed",
        "The speed ratio η(τ) = η_k + η'(τ − τ_k) on a piece of a speed profile.",
        "docs/MODEL.md §14",
        "the piece's statement: η linear in τ.",
        "RampSpeed",
        vec![("eta", "η", speed)],
    );
    let g = &mut m.graph;
    let e = g.mul(eta, t);
    let constant = g.sub(theta, e);
    m.add_formula(
        "ramp_phase_constant",
        "The phase constant c = θ − η_k τ of a piece whose phase is θ at time τ (its start): `ramp_phase` solved for c at s = 0.",
        "docs/MODEL.md §14",
        "`ramp_phase` at τ = τ_k solved for c.",
        "RampPhaseConstant",
        vec![("c", "c", constant)],
    );
    let g = &mut m.graph;
    let eta_sq = g.mul(eta, eta);
    let rate2 = g.scale(2.0, rate);
    let r2d = g.mul(rate2, theta);
    let disc = g.add(eta_sq, r2d);
    let root = g.sqrt(disc);
    let denominator = g.add(eta, root);
    let twice = g.scale(2.0, theta);
    let s = g.div(twice, denominator);
    m.add_formula(
        "ramp_time_to_phase",
        "The time s = τ − τ_k at which a piece's phase has advanced by Δθ from its start: ½η' s² + η_k s = Δθ solved as s = 2Δθ / (η_k + √(η_k² + 2η'Δθ)), which does not cancel.",
        "docs/MODEL.md §14",
        "`ramp_phase` minus its value at τ_k, a quadratic in s; the root with s → Δθ/η_k as η' → 0.",
        "RampTimeToPhase",
        vec![("disc", "η_k² + 2η'Δθ", disc), ("s", "s", s)],
    );
}

/// d = (u, v) = q − ε̂ of a position.
fn stator_offset(m: &mut Model) {
    let q = position(m);
    let (d, _, _) = m.stator_offset(q);
    m.add_formula(
        "stator_offset",
        "A position relative to the stator centre, d = (u, v) = q − ε̂ (its length is z, its direction the contact normal).",
        "docs/MODEL.md §1",
        "the model's `stator_offset`.",
        "StatorOffset",
        vec![("u", "u = x − ε̂x", d[0]), ("v", "v = y − ε̂y", d[1])],
    );
}

/// The position at a given offset from the stator centre: `stator_offset` solved for q.
fn position_at_offset(m: &mut Model) {
    let unknowns = [m.var("x"), m.var("y")];
    let (d, _, _) = m.stator_offset(unknowns);
    let (u, v) = (m.var("du"), m.var("dv"));
    let g = &mut m.graph;
    let equations = [g.sub(d[0], u), g.sub(d[1], v)];
    let q = m.solve(&equations, &["x", "y"]);
    m.add_formula(
        "position_at_offset",
        "The position whose offset from the stator centre is d: q = ε̂ + d.",
        "docs/MODEL.md §1",
        "the model's `stator_offset` solved for the position.",
        "Position",
        vec![("x", "x", q[0]), ("y", "y", q[1])],
    );
}

/// Each regime's whole field q'' (the unbalance, the input force, damping, the restoring spring
/// and the regime's contact forces): what the numerical methods integrate.
fn regime_fields(m: &mut Model) {
    let q = position(m);
    let v = velocity(m);
    let ph = phasor(m);
    let sigma = m.var("sigma");
    let forcing = m.forcing(ph);
    let free = {
        let stiffness = m.stiffness(q, None);
        m.acceleration(v, stiffness, forcing)
    };
    let contact = {
        let stiffness = m.stiffness(q, Some(None));
        m.acceleration(v, stiffness, forcing)
    };
    let slipping = {
        let stiffness = m.stiffness(q, Some(Some(sigma)));
        m.acceleration(v, stiffness, forcing)
    };
    let fields = [
        (
            "free_field",
            "Free flight: q'' = F(cos θ, sin θ) + u − 2ν q' − q.",
            free,
        ),
        (
            "contact_field",
            "Frictionless contact: q'' = F(cos θ, sin θ) + u − 2ν q' − q − K_s·g(q).",
            contact,
        ),
        (
            "slipping_field",
            "Contact slipping in direction σ: q'' = F(cos θ, sin θ) + u − 2ν q' − q − K_s·g(q) − μσN t.",
            slipping,
        ),
    ];
    for (name, summary, a) in fields {
        m.add_formula(
            name,
            summary,
            "docs/MODEL.md §1, §10, §15",
            "the model's acceleration with the regime's stiffness term and the forcing (unbalance and input force).",
            "Acceleration",
            vec![("ax", "x''", a[0]), ("ay", "y''", a[1])],
        );
    }
}

/// The unbalance force F (cos θ, sin θ) at a phasor (the forcing of the closed forms' series).
fn unbalance_force_at(m: &mut Model) {
    let ph = phasor(m);
    let f = m.unbalance(ph);
    m.add_formula(
        "unbalance_force_at",
        "The unbalance force F (cos θ, sin θ) at the forcing phasor (cos θ, sin θ).",
        "docs/MODEL.md §1",
        "the model's `unbalance` piece.",
        "Force",
        vec![("fx", "x component", f[0]), ("fy", "y component", f[1])],
    );
}

/// w' along any motion with acceleration a: the slope of friction's switch on a closed form.
fn slip_velocity_rate(m: &mut Model) {
    let q = position(m);
    let v = velocity(m);
    let a = [m.var("ax"), m.var("ay")];
    let w = m.slip_velocity(q, v);
    let rates = state_rates(m, v, a, false);
    let rate = derivative(&mut m.graph, w, &rates);
    m.add_formula(
        "slip_velocity_rate",
        "The rate w' of the slip velocity w = q'·t + ρ_R η along a motion with acceleration a (a closed form's own): w' = t·a + q'·t', t' = −(q'·t/z) n.",
        "docs/MODEL.md §10",
        "the total time derivative of the model's `slip_velocity` with q'' = a.",
        "SlipVelocityRate",
        vec![("rate", "w' = dw/dτ", rate)],
    );
}

/// w' along the slipping field: the slope of the slip velocity's switch while slipping.
fn slip_rate(m: &mut Model) {
    let q = position(m);
    let v = velocity(m);
    let ph = phasor(m);
    let sigma = m.var("sigma");
    let forcing = m.forcing(ph);
    let stiffness = m.stiffness(q, Some(Some(sigma)));
    let a = m.acceleration(v, stiffness, forcing);
    let w = m.slip_velocity(q, v);
    let rates = state_rates(m, v, a, true);
    let rate = derivative(&mut m.graph, w, &rates);
    m.add_formula(
        "slip_rate",
        "The rate w' of the slip velocity along the field of slipping in direction σ (= λ − μσN).",
        "docs/MODEL.md §10",
        "the total time derivative of the model's `slip_velocity` along the slipping field.",
        "SlipVelocityRate",
        vec![("rate", "w' = dw/dτ", rate)],
    );
}

/// The friction cone's margins μN ∓ λ and their rates along the rolling field: the `slip`
/// switch functions of rolling (|λ| ≤ μN while both are ≥ 0).
fn cone_rates(m: &mut Model) {
    let (q, v, acc) = super::friction::frictionless_contact_acceleration(m);
    let normal = m.normal_force(q);
    let (lambda, _, t) = super::friction::rolling_force(m, q, v, acc);
    let mu = m.var("friction_coefficient");
    let g = &mut m.graph;
    let rolling = [0, 1].map(|i| {
        let f = g.mul(lambda, t[i]);
        g.sub(acc[i], f)
    });
    let limit = g.mul(mu, normal);
    let upper = g.sub(limit, lambda);
    let lower = g.add(limit, lambda);
    let rates = state_rates(m, v, rolling, true);
    let upper_rate = derivative(&mut m.graph, upper, &rates);
    let lower_rate = derivative(&mut m.graph, lower, &rates);
    m.add_formula(
        "friction_cone",
        "The friction cone's margins μN − λ and μN + λ of a contact state: rolling holds while both are ≥ 0.",
        "docs/MODEL.md §10",
        "the model's `normal_force` and the rolling force λ.",
        "FrictionCone",
        vec![("upper", "μN − λ", upper), ("lower", "μN + λ", lower)],
    );
    m.add_formula(
        "friction_cone_rates",
        "The friction cone's margins μN ∓ λ and their rates along the rolling field: the `slip` switch functions of rolling and their slopes.",
        "docs/MODEL.md §10",
        "the model's `normal_force`, the rolling force λ and their total time derivatives along q'' = G − λ t.",
        "FrictionConeRates",
        vec![
            ("upper", "μN − λ", upper),
            ("lower", "μN + λ", lower),
            ("upper_rate", "(μN − λ)'", upper_rate),
            ("lower_rate", "(μN + λ)'", lower_rate),
        ],
    );
}

/// The slip velocity w = q'·t + ρ_R η of a state.
fn slip_velocity(m: &mut Model) {
    let q = position(m);
    let v = velocity(m);
    let w = m.slip_velocity(q, v);
    m.add_formula(
        "slip_velocity",
        "The slip velocity w = q'·t + ρ_R η of the rotor's surface at the contact point.",
        "docs/MODEL.md §10",
        "the model's `slip_velocity`.",
        "SlipVelocity",
        vec![("w", "w", w)],
    );
}

/// The linearized contact field with an extra force: what a closed-form contact segment's
/// acceleration is.
fn linearized_contact_field(m: &mut Model) {
    let q = position(m);
    let v = velocity(m);
    let ph = phasor(m);
    let load = [m.var("fx"), m.var("fy")];
    let (kl, fd) = m.linearized_inputs();
    let forcing = m.forcing(ph);
    let g = &mut m.graph;
    let driven = [g.add(forcing[0], load[0]), g.add(forcing[1], load[1])];
    let stiffness = m.linear_stiffness_term(kl, fd, q);
    let a = m.acceleration(v, stiffness, driven);
    m.add_formula(
        "linearized_contact_field",
        "The linearized contact field under an extra force a: q'' = F(cos θ, sin θ) + u + a − 2ν q' − Kl q − Fd.",
        "docs/MODEL.md §3, §8",
        "the model's acceleration with the linearized stiffness term Kl q + Fd, the forcing and the force a.",
        "Acceleration",
        vec![("ax", "x''", a[0]), ("ay", "y''", a[1])],
    );
}

/// ∂q''/∂q and ∂q''/∂q' of the linearized contact field: the gains its bounds rest on.
fn linear_field_jacobians(m: &mut Model) {
    let q = position(m);
    let v = velocity(m);
    let (kl, fd) = m.linearized_inputs();
    let zero = m.graph.constant(0.0);
    let stiffness = m.linear_stiffness_term(kl, fd, q);
    let a = m.acceleration(v, stiffness, [zero, zero]);
    let names = ["lx", "ly", "vx", "vy"].map(|n| m.sym(n));
    let g = &mut m.graph;
    let d = |g: &mut crate::expr::Graph, i: usize, k: usize| partial(g, a[i], names[k]);
    let entries = [
        d(g, 0, 0),
        d(g, 0, 1),
        d(g, 1, 0),
        d(g, 1, 1),
        d(g, 0, 2),
        d(g, 0, 3),
        d(g, 1, 2),
        d(g, 1, 3),
    ];
    m.add_formula(
        "linear_field_jacobians",
        "The Jacobians of the linearized contact field's acceleration in position (−Kl) and in velocity (the damping), row by row.",
        "docs/MODEL.md §8, §12",
        "partial derivatives of the model's linearized acceleration.",
        "FieldJacobians",
        vec![
            ("q11", "∂x''/∂x", entries[0]),
            ("q12", "∂x''/∂y", entries[1]),
            ("q21", "∂y''/∂x", entries[2]),
            ("q22", "∂y''/∂y", entries[3]),
            ("v11", "∂x''/∂x'", entries[4]),
            ("v12", "∂x''/∂y'", entries[5]),
            ("v21", "∂y''/∂x'", entries[6]),
            ("v22", "∂y''/∂y'", entries[7]),
        ],
    );
}

/// d/dτ of the unbalance forcing at a constant speed: its size bounds the forcing's share of q‴.
fn forcing_rate(m: &mut Model) {
    let ph = phasor(m);
    let f = m.unbalance(ph);
    let mut rates = Rates::new();
    m.forcing_phasor(&mut rates);
    let g = &mut m.graph;
    let r = [derivative(g, f[0], &rates), derivative(g, f[1], &rates)];
    m.add_formula(
        "forcing_rate",
        "The rate of the unbalance forcing d/dτ F (cos θ, sin θ) = F η (−sin θ, cos θ) at a phasor (its length F η is the same at every phase).",
        "docs/MODEL.md §1",
        "the total time derivative of the model's `unbalance` piece with θ' = η.",
        "Force",
        vec![("fx", "x component", r[0]), ("fy", "y component", r[1])],
    );
}

/// The harmonic system of the linearized contact equations: with q = Re(Z e^{iθ}) the equations
/// become (Kl − η² I + iη C) Z = F (1, −i)ᵀ, C the damping matrix ∂(damping)/∂q'.
fn harmonic_system(m: &mut Model) {
    let v = velocity(m);
    let (kl, _) = m.linearized_inputs();
    let eta = m.var("speed_ratio");
    let damping = m.damping(v);
    let names = ["vx", "vy"].map(|n| m.sym(n));
    let g = &mut m.graph;
    let eta_sq = g.mul(eta, eta);
    let mut re = [[eta; 2]; 2];
    let mut im = [[eta; 2]; 2];
    for i in 0..2 {
        for k in 0..2 {
            let c = partial(g, damping[i], names[k]);
            im[i][k] = g.mul(eta, c);
            re[i][k] = if i == k {
                g.sub(kl[i][k], eta_sq)
            } else {
                kl[i][k]
            };
        }
    }
    // det(A + iB) for 2×2 A, B.
    let p = |g: &mut crate::expr::Graph, a: ExprId, b: ExprId| g.mul(a, b);
    let det_re = {
        let t = [
            p(g, re[0][0], re[1][1]),
            p(g, im[0][0], im[1][1]),
            p(g, re[0][1], re[1][0]),
            p(g, im[0][1], im[1][0]),
        ];
        let n = [g.neg(t[1]), g.neg(t[2])];
        g.sum(&[t[0], n[0], n[1], t[3]])
    };
    let det_im = {
        let t = [
            p(g, re[0][0], im[1][1]),
            p(g, im[0][0], re[1][1]),
            p(g, re[0][1], im[1][0]),
            p(g, im[0][1], re[1][0]),
        ];
        let n = [g.neg(t[2]), g.neg(t[3])];
        g.sum(&[t[0], t[1], n[0], n[1]])
    };
    m.add_formula(
        "harmonic_system",
        "The harmonic system (Kl − η² I + iη C) Z = F (1, −i)ᵀ of the linearized contact equations (C the damping matrix): its real and imaginary parts and its determinant, whose size against its terms is the system's condition.",
        "docs/MODEL.md §5, §11",
        "the linearized stiffness and the model's damping piece at the forcing frequency η.",
        "HarmonicSystem",
        vec![
            ("re11", "Re[0][0]", re[0][0]),
            ("re12", "Re[0][1]", re[0][1]),
            ("re21", "Re[1][0]", re[1][0]),
            ("re22", "Re[1][1]", re[1][1]),
            ("im11", "Im[0][0]", im[0][0]),
            ("im12", "Im[0][1]", im[0][1]),
            ("im21", "Im[1][0]", im[1][0]),
            ("im22", "Im[1][1]", im[1][1]),
            ("det_re", "Re det", det_re),
            ("det_im", "Im det", det_im),
        ],
    );
}

/// The stator's stiffness norm and the bound of friction's stiffness on z ≥ 1.
///
/// Slipping adds μσ ∂(N t)/∂q to Kl (`docs/MODEL.md` §10). With N = (z − 1) nᵀK_s n,
/// ∇N = (nᵀK_s n) n + ((z − 1)/z)(I − n nᵀ)(K_s + K_sᵀ) n, so |∇N| ≤ 3‖K_s‖₂, and
/// ∂t/∂q = R(I − n nᵀ)/z has norm ≤ 1/z ≤ 1: ‖∂(N t)/∂q‖ ≤ |∇N| + |N|/z ≤ 4‖K_s‖₂ on z ≥ 1,
/// bounded by 4μ‖K_s‖_F.
fn stator_bounds(m: &mut Model) {
    let ks = m.stator_stiffness();
    let mu = m.var("friction_coefficient");
    let g = &mut m.graph;
    let squares: Vec<ExprId> = ks.iter().flatten().map(|&k| g.mul(k, k)).collect();
    let sum = g.sum(&squares);
    let norm = g.sqrt(sum);
    let friction = g.product(&[mu, norm]);
    let friction = g.scale(4.0, friction);
    m.add_formula(
        "stator_bounds",
        "The stator stiffness's Frobenius norm ‖K_s‖_F and the bound 4μ‖K_s‖_F of friction's share of the linearized contact stiffness on z ≥ 1.",
        "docs/MODEL.md §10, §12",
        "the model's stator stiffness; the bound's proof is in this formula's source.",
        "StatorBounds",
        vec![
            ("stator_norm", "‖K_s‖_F", norm),
            ("friction_gradient", "4μ‖K_s‖_F", friction),
        ],
    );
}
