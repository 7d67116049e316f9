//! A rub station (`docs/MODEL.md` §17): the contact law of §1 and §10 acting on the offset
//! d = B_r q − B_s q − ε̂ of two points of any linear rotor (a rotor from matrices, the stator
//! ring with mass). The linear part of such a model is data (its matrices), so the model's size
//! is the caller's; what the generator states is the law at the station, for every size: the
//! elastic force K_c g(d) and its normal N, Coulomb friction while slipping, the slip velocity
//! w, and the rolling force λ that keeps w at 0 with its friction cone. The station's geometry
//! is the planar model's own formulas at the relative position P = B_r q − B_s q (d = P − ε̂:
//! `stator_offset`, `switching_function`, `switching_curvature`).
//!
//! The pieces are the planar model's (`mod.rs`): [`Model::offset_length`],
//! [`Model::penetration`], [`Model::frame`], [`Model::coulomb`], [`Model::surface_slip`]; the
//! planar model is the station with d = q − ε̂, K_c = K_s and W = I.

use super::{Model, Rates, Vec2};
use crate::derive::{derivative, partial};
use crate::expr::ExprId;

pub(super) fn derive(m: &mut Model) {
    station_slipping(m);
    station_rolling(m);
    ring_matrices(m);
    station_slip_rate(m);
    station_cone_rates(m);
    forcing_phasor_rate(m);
    let systems = [
        station_taylor(m, Law::Frictionless),
        station_taylor(m, Law::Slipping),
        station_taylor(m, Law::Rolling),
    ];
    m.taylor.extend(systems);
}

/// The stator ring with mass (`docs/MODEL.md` §17) as a matrix model of n = 4: positions
/// (x, y, x_s, y_s), the rotor's equations of motion (`damping`, `restoring`) beside the ring's
/// m̂ p'' + ĉ p' + K_s p (`stator_force`), each matrix entry the partial derivative of the
/// linear part by a velocity (C) or a position (K), the masses those of the accelerations.
/// The contact is the station's law between (x, y) and (x_s, y_s) with K_c = k̂_c I.
fn ring_matrices(m: &mut Model) {
    let q: [ExprId; 4] = ["ring_q0", "ring_q1", "ring_q2", "ring_q3"].map(|n| m.var(n));
    let v: [ExprId; 4] = ["ring_v0", "ring_v1", "ring_v2", "ring_v3"].map(|n| m.var(n));
    let rotor_damping = m.damping([v[0], v[1]]);
    let rotor_restoring = m.restoring([q[0], q[1]]);
    let ring_support = m.stator_force([q[2], q[3]]);
    let (c, mass) = (m.var("stator_damping"), m.var("stator_mass_ratio"));
    let g = &mut m.graph;
    let ring_damping = [g.mul(c, v[2]), g.mul(c, v[3])];
    let linear: [ExprId; 4] = [0, 1, 2, 3].map(|i| {
        let (d, k) = if i < 2 {
            (rotor_damping[i], rotor_restoring[i])
        } else {
            (ring_damping[i - 2], ring_support[i - 2])
        };
        g.add(d, k)
    });
    let one = g.constant(1.0);
    let masses = [one, one, mass, mass];
    let mut outputs: Vec<(String, String, ExprId)> = Vec::new();
    for (i, &mi) in masses.iter().enumerate() {
        outputs.push((format!("m{i}"), format!("M[{i}][{i}]"), mi));
    }
    for (prefix, vars) in [("c", "ring_v"), ("k", "ring_q")] {
        for (i, &row) in linear.iter().enumerate() {
            for j in 0..4 {
                let s = m.graph.symbol(&format!("{vars}{j}"));
                let e = partial(&mut m.graph, row, s);
                let name = if prefix == "c" { "C" } else { "K" };
                outputs.push((format!("{prefix}{i}{j}"), format!("{name}[{i}][{j}]"), e));
            }
        }
    }
    let (kc, zero) = (m.var("contact_stiffness"), m.graph.constant(0.0));
    for (name, e) in [
        ("kc_xx", kc),
        ("kc_xy", zero),
        ("kc_yx", zero),
        ("kc_yy", kc),
    ] {
        outputs.push((name.to_owned(), format!("K_c entry {name}: k̂_c I"), e));
    }
    let outputs: Vec<(&str, &str, ExprId)> = outputs
        .iter()
        .map(|(n, d, e)| (n.as_str(), d.as_str(), *e))
        .collect();
    m.add_formula(
        "ring_matrices",
        "The stator ring with mass as a 4-DOF matrix model: M = diag(1, 1, m̂, m̂), C and K of the positions (x, y, x_s, y_s): the rotor's 2ν I and I, the ring's ĉ I and K_s; the contact stiffness K_c = k̂_c I between rotor and ring.",
        "docs/MODEL.md §17",
        "the partial derivatives of the rotor's `damping` + `restoring` and the ring's ĉ p' + `stator_force`(p) by each velocity and position.",
        "RingMatrices",
        outputs,
    );
}

fn offset(m: &mut Model) -> Vec2 {
    [m.var("du"), m.var("dv")]
}

fn offset_rate(m: &mut Model) -> Vec2 {
    [m.var("du_rate"), m.var("dv_rate")]
}

/// The station's elastic contact: e = K_c g(d) (restoring sign), N = n·e, the frame n, t and z.
struct Elastic {
    force: Vec2,
    normal: ExprId,
    n: Vec2,
    t: Vec2,
    z: ExprId,
}

fn elastic(m: &mut Model, d: Vec2) -> Elastic {
    let (_, z) = m.offset_length(d);
    let g = m.penetration(d, z);
    let k = [
        [m.var("kc_xx"), m.var("kc_xy")],
        [m.var("kc_yx"), m.var("kc_yy")],
    ];
    let force = m.apply(k, g);
    let (n, t, z) = m.frame(d, z);
    let normal = m.dot(n, force);
    Elastic {
        force,
        normal,
        n,
        t,
        z,
    }
}

/// The contact force on the rotor's point: −(e + f t) for a tangential force f.
fn force_on_rotor(m: &mut Model, e: &Elastic, tangential: ExprId) -> Vec2 {
    let g = &mut m.graph;
    [0, 1].map(|i| {
        let f = g.mul(tangential, e.t[i]);
        let s = g.add(e.force[i], f);
        g.neg(s)
    })
}

/// The slipping law at offset `d` with rate `r`: the elastic contact, the restoring contact
/// force K_c g(d) + μσN t (the force on the rotor's point is its negative, f_c) and the slip
/// velocity w = d'·t + ρ_R η.
fn slipping_law(m: &mut Model, d: Vec2, r: Vec2) -> (Elastic, Vec2, ExprId) {
    let e = elastic(m, d);
    let (mu, sigma) = (m.var("friction_coefficient"), m.var("sigma"));
    let friction = m.coulomb(mu, sigma, e.normal, e.t);
    let g = &mut m.graph;
    let restoring = [0, 1].map(|i| g.add(e.force[i], friction[i]));
    let w = m.surface_slip(r, e.t);
    (e, restoring, w)
}

/// The contact force on the rotor's point while slipping (or frictionless, μ = 0).
fn station_slipping(m: &mut Model) {
    let d = offset(m);
    let r = offset_rate(m);
    let (e, restoring, w) = slipping_law(m, d, r);
    let g = &mut m.graph;
    let force = restoring.map(|f| g.neg(f));
    m.add_formula(
        "station_slipping",
        "A rub station in slipping contact in direction σ (μ = 0: frictionless): the normal force N = nᵀK_c g(d), the force on the rotor's point f_c = −(K_c g(d) + μσN t) (the stator's point carries −f_c), and the slip velocity w = d'·t + ρ_R η.",
        "docs/MODEL.md §17, §10",
        "the model's `penetration`, `frame` and `coulomb` on the station's offset, K_c for K_s.",
        "StationForce",
        vec![
            ("normal", "N, the normal elastic contact force", e.normal),
            ("fx", "f_c, x component", force[0]),
            ("fy", "f_c, y component", force[1]),
            ("slip_velocity", "w, the slip velocity", w),
        ],
    );
}

/// The rolling law at offset `d` with rate `r` and drive `a` (the offset's acceleration from
/// every force but the contact's).
struct Rolling {
    elastic: Elastic,
    lambda: ExprId,
    /// f_c, the force on the rotor's point.
    force: Vec2,
    /// K_c g(d) + λ t, the restoring contact force (−f_c).
    restoring: Vec2,
    upper: ExprId,
    lower: ExprId,
}

fn rolling_law(m: &mut Model, d: Vec2, r: Vec2, a: Vec2) -> Rolling {
    let e = elastic(m, d);
    let w = [
        [m.var("w_xx"), m.var("w_xy")],
        [m.var("w_yx"), m.var("w_yy")],
    ];
    // t·d'' = t·a − tᵀW e − λ tᵀW t must equal −d'·t' = (d'·t)(d'·n)/z for w' = 0.
    let ta = m.dot(e.t, a);
    let we = m.apply(w, e.force);
    let twe = m.dot(e.t, we);
    let wt = m.apply(w, e.t);
    let twt = m.dot(e.t, wt);
    let rt = m.dot(r, e.t);
    let rn = m.dot(r, e.n);
    let g = &mut m.graph;
    let inv_z = g.powi(e.z, -1);
    let centripetal = g.product(&[rt, rn, inv_z]);
    let drive = g.sub(ta, twe);
    let numerator = g.sub(drive, centripetal);
    let inv_twt = g.powi(twt, -1);
    let lambda = g.mul(numerator, inv_twt);
    let force = force_on_rotor(m, &e, lambda);
    let mu = m.var("friction_coefficient");
    let g = &mut m.graph;
    let restoring = [0, 1].map(|i| {
        let f = g.mul(lambda, e.t[i]);
        g.add(e.force[i], f)
    });
    let limit = g.mul(mu, e.normal);
    let upper = g.sub(limit, lambda);
    let lower = g.add(limit, lambda);
    Rolling {
        elastic: e,
        lambda,
        force,
        restoring,
        upper,
        lower,
    }
}

/// The rolling force λ and the contact force on the rotor's point while rolling (w ≡ 0).
fn station_rolling(m: &mut Model) {
    let d = offset(m);
    let r = offset_rate(m);
    let a = drive(m);
    let law = rolling_law(m, d, r, a);
    m.add_formula(
        "station_rolling",
        "A rub station rolling without slip (w ≡ 0): the normal force N, the tangential force λ = (t·a − tᵀW K_c g − (d'·t)(d'·n)/z)/(tᵀW t) that keeps w' = 0 (a: the offset's acceleration from every force but the contact's, W = B M⁻¹ Bᵀ), and the force on the rotor's point f_c = −(K_c g(d) + λ t).",
        "docs/MODEL.md §17, §10",
        "w' = d''·t + d'·t' with d'' = a + W f_c and t' = −(d'·t/z) n, solved for λ.",
        "StationRolling",
        vec![
            ("normal", "N, the normal elastic contact force", law.elastic.normal),
            ("lambda", "λ, the tangential force of rolling", law.lambda),
            ("fx", "f_c, x component", law.force[0]),
            ("fy", "f_c, y component", law.force[1]),
            ("upper", "μN − λ: rolling holds while both margins are ≥ 0", law.upper),
            ("lower", "μN + λ", law.lower),
        ],
    );
}

fn drive(m: &mut Model) -> Vec2 {
    [m.var("drive_u"), m.var("drive_v")]
}

/// The time rates of the station's inputs for the chain rule: d' for d, d'' for d', and the
/// drive's rate a' for the drive a.
fn station_rates(m: &mut Model) -> Rates {
    let pairs = [
        ("du", "du_rate"),
        ("dv", "dv_rate"),
        ("du_rate", "ax"),
        ("dv_rate", "ay"),
        ("drive_u", "drive_rate_u"),
        ("drive_v", "drive_rate_v"),
    ];
    let mut rates = Rates::new();
    for (of, rate) in pairs {
        let s = m.sym(of);
        let r = m.var(rate);
        rates.insert(s, r);
    }
    rates
}

/// The slip velocity's rate w' along the motion (`docs/MODEL.md` §17): the slope of the
/// slipping segment's switch function σw, for the numerical methods' switch search.
fn station_slip_rate(m: &mut Model) {
    let d = offset(m);
    let r = offset_rate(m);
    let (_, _, w) = slipping_law(m, d, r);
    let rates = station_rates(m);
    let rate = derivative(&mut m.graph, w, &rates);
    m.add_formula(
        "station_slip_rate",
        "The rate w' = d''·t − (d'·t)(d'·n)/z of a rub station's slip velocity along a motion whose offset accelerates at d'' (every force included).",
        "docs/MODEL.md §17, §10",
        "the total time derivative of the station's slip velocity w = d'·t + ρ_R η (d' → d'').",
        "SlipVelocityRate",
        vec![("rate", "w' = dw/dτ", rate)],
    );
}

/// The friction cone's margins μN ∓ λ of a rolling station and their rates (`docs/MODEL.md`
/// §17): the `slip` switch functions of rolling and their slopes, for the numerical methods.
fn station_cone_rates(m: &mut Model) {
    let d = offset(m);
    let r = offset_rate(m);
    let a = drive(m);
    let law = rolling_law(m, d, r, a);
    let rates = station_rates(m);
    let upper_rate = derivative(&mut m.graph, law.upper, &rates);
    let lower_rate = derivative(&mut m.graph, law.lower, &rates);
    m.add_formula(
        "station_cone_rates",
        "The friction cone's margins μN − λ and μN + λ of a rolling station and their rates along a motion whose offset accelerates at d'' and whose drive a changes at a'.",
        "docs/MODEL.md §17, §10",
        "the total time derivatives of `station_rolling`'s margins (d → d', d' → d'', a → a').",
        "StationConeRates",
        vec![
            ("upper", "μN − λ", law.upper),
            ("lower", "μN + λ", law.lower),
            ("upper_rate", "(μN − λ)'", upper_rate),
            ("lower_rate", "(μN + λ)'", lower_rate),
        ],
    );
}

/// The forcing phasor's rate (cos θ, sin θ)' = η (−sin θ, cos θ): what a matrix model's drive
/// rate takes of the unbalance forcing.
fn forcing_phasor_rate(m: &mut Model) {
    let mut rates = Rates::new();
    m.forcing_phasor(&mut rates);
    let (ct, st) = (m.sym("ct"), m.sym("st"));
    let (dc, ds) = (rates[&ct], rates[&st]);
    m.add_formula(
        "forcing_phasor_rate",
        "The forcing phasor's rate: (cos θ)' = −η sin θ, (sin θ)' = η cos θ.",
        "docs/MODEL.md §16, §17",
        "the model's `forcing_phasor` (θ' = η).",
        "PhasorRate",
        vec![("ct_rate", "(cos θ)'", dc), ("st_rate", "(sin θ)'", ds)],
    );
}

/// The station's regimes for the Taylor recurrences.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Law {
    Frictionless,
    Slipping,
    Rolling,
}

/// A rub station's contact law as a Taylor system (`docs/MODEL.md` §16, §17): the linear part
/// of a matrix model is a matrix–series product the runtime does, so the system's states are
/// the law's inputs — the station's relative position P (rate P') and velocity P' (and while
/// rolling the drive a; rate 0 stated, as the law does not know them), whose coefficients the
/// runtime sets from the matrix series before each order — and the forcing phasor with its
/// true rates. Observed: the restoring contact force −f_c (what the runtime feeds back through
/// −M⁻¹Bᵀ) and the switch functions (h = z² − 1, σw, μN ∓ λ), with the inputs' own indices.
fn station_taylor(m: &mut Model, law: Law) -> crate::ir::System {
    let p = [m.var("lx"), m.var("ly")];
    let r = [m.var("vx"), m.var("vy")];
    let mut rates = Rates::new();
    let phasor = m.forcing_phasor(&mut rates);
    let (d, z2, _) = m.stator_offset(p);
    let h = m.boundary_at(z2);
    let zero = m.graph.constant(0.0);
    let mut states = Vec::new();
    let mut observed: Vec<(String, String, ExprId)> = Vec::new();
    let mut input = |m: &mut Model, name: &str, rate: ExprId, what: &str, observe: &str| {
        let s = m.sym(name);
        let e = m.var(name);
        states.push((s, rate));
        observed.push((observe.to_owned(), what.to_owned(), e));
    };
    input(
        m,
        "lx",
        r[0],
        "P_x, the station's relative position (input)",
        "relative_x",
    );
    input(m, "ly", r[1], "P_y (input)", "relative_y");
    input(m, "vx", zero, "P'_x, its rate (input)", "relative_vx");
    input(m, "vy", zero, "P'_y (input)", "relative_vy");
    for (name, c) in [("ct", phasor[0]), ("st", phasor[1])] {
        let s = m.sym(name);
        states.push((s, rates[&s]));
        let what = if name == "ct" { "cos θ" } else { "sin θ" };
        observed.push((format!("phasor_{name}"), what.to_owned(), c));
    }
    let (force, name, summary, extra) = match law {
        Law::Frictionless | Law::Slipping => {
            let (e, slipping, w) = slipping_law(m, d, r);
            if law == Law::Frictionless {
                (
                    e.force,
                    "station_contact_taylor",
                    "A rub station in frictionless contact: the restoring force K_c g(d) at d = P − ε̂ (f_c = −K_c g(d)).",
                    vec![],
                )
            } else {
                (
                    slipping,
                    "station_slipping_taylor",
                    "A rub station slipping in direction σ: the restoring force K_c g(d) + μσN t (= −f_c).",
                    vec![(
                        "slip_velocity".to_owned(),
                        "the slip velocity w = d'·t + ρ_R η".to_owned(),
                        w,
                    )],
                )
            }
        }
        Law::Rolling => {
            let a = drive(m);
            for (name, what, observe) in [
                (
                    "drive_u",
                    "a_x, the offset's acceleration but the contact's (input)",
                    "drive_x",
                ),
                ("drive_v", "a_y (input)", "drive_y"),
            ] {
                let s = m.sym(name);
                let e = m.var(name);
                states.push((s, zero));
                observed.push((observe.to_owned(), what.to_owned(), e));
            }
            let rolling = rolling_law(m, d, r, a);
            (
                rolling.restoring,
                "station_rolling_taylor",
                "A rub station rolling without slip: the restoring force K_c g(d) + λ t (= −f_c), λ the tangential force that keeps w = 0.",
                vec![
                    (
                        "cone_upper".to_owned(),
                        "μN − λ (rolling needs it ≥ 0)".to_owned(),
                        rolling.upper,
                    ),
                    (
                        "cone_lower".to_owned(),
                        "μN + λ (rolling needs it ≥ 0)".to_owned(),
                        rolling.lower,
                    ),
                ],
            )
        }
    };
    observed.push((
        "restoring_x".to_owned(),
        "−f_c, x component: the contact force the rotor's point feels, with a minus".to_owned(),
        force[0],
    ));
    observed.push((
        "restoring_y".to_owned(),
        "−f_c, y component".to_owned(),
        force[1],
    ));
    observed.push((
        "boundary".to_owned(),
        "h = z² − 1 (positive in contact)".to_owned(),
        h,
    ));
    observed.extend(extra);
    crate::ir::System {
        name: name.to_owned(),
        summary: format!(
            "{summary} The law's inputs (P, P' and while rolling a) are states of rate 0 that the caller sets from the matrix model's series before each order; the forcing phasor is carried with its rates."
        ),
        source: "docs/MODEL.md §16, §17".to_owned(),
        states,
        observed,
    }
}
