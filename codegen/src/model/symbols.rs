//! Every symbol the model uses, declared once: its name, its meaning and the input struct of the
//! generated functions it belongs to (`None` for symbols that only live inside a derivation: an
//! unknown being solved for, a time variable that is substituted away).
//!
//! The model's parameters are the parameter table's entries (`parameters.rs`): each is a symbol
//! of the table's name in `ModelParams`, next to the quantities the model derives from them
//! ([`DERIVED`]); `ModelParams` is built from the runtime's `Params` by the generated
//! `model_params` (whose inputs are the table's fields, symbols `params.<name>`). The other
//! structs are declared in [`GROUPS`].
//!
//! The generated code takes and returns these structs instead of positional `f64`s. A formula
//! whose expression uses a symbol declared nowhere, or a symbol of no input struct, fails the
//! build with a message naming the symbol and the formula (see [`Symbols::lookup`] and
//! `emit::emit_formula`).

use std::collections::HashSet;
use std::sync::OnceLock;

use super::parameters;
use crate::ir::Group;

/// The struct of the model's parameters: the table's entries the formulas read, and the
/// quantities derived from them.
pub const MODEL_PARAMS: &str = "ModelParams";

/// The quantities the model derives from the table's parameters, with their meaning: fields of
/// `ModelParams` next to the table's own, defined once in the model statement
/// (`Model::derived_parameters`) and computed by the generated `model_params`.
pub const DERIVED: &[(&str, &str)] = &[
    (
        "unbalance",
        "η_m ρ̂, the unbalance's radius: mass ratio times eccentricity ratio",
    ),
    (
        "unbalance_force",
        "F = η_m ρ̂ η², the unbalance forcing amplitude at a constant speed",
    ),
];

/// The prefix of the symbols that stand for the runtime's `Params` fields (inputs of
/// `model_params` only): `params.speed_ratio` is the table entry `speed_ratio` as the caller holds it.
pub const TABLE_PREFIX: &str = "params.";

/// The declared input structs, in the order generated functions take them.
pub const GROUPS: &[Group] = &[
    Group {
        ty: "Position",
        arg: "at",
        doc: "A rotor position (x, y): the point a formula is evaluated or linearized at.",
        fields: &[("lx", "x", "x"), ("ly", "y", "y")],
        external: None,
    },
    Group {
        ty: "Time",
        arg: "time",
        doc: "An absolute time τ.",
        fields: &[("abs_time", "t", "τ")],
        external: None,
    },
    Group {
        ty: "SpeedRamp",
        arg: "ramp",
        doc: "A piece of a speed profile, η(τ) = η_k + η' (τ − τ_k), and its phase constant c (`docs/MODEL.md` §14).",
        fields: &[
            (
                "ramp_speed",
                "speed_ratio",
                "η_k, the speed at the piece's start",
            ),
            ("ramp_rate", "rate", "η' = dη/dτ on the piece"),
            ("ramp_start", "start", "τ_k, the piece's start"),
            (
                "ramp_constant",
                "phase_constant",
                "c in θ = η_k τ + c + ½η'(τ − τ_k)²",
            ),
        ],
        external: None,
    },
    Group {
        ty: "PhaseAdvance",
        arg: "advance",
        doc: "A forcing phase θ, or an advance Δθ of it, rad.",
        fields: &[("phase_value", "theta", "θ or Δθ")],
        external: None,
    },
    Group {
        ty: "StatorOffset",
        arg: "offset",
        doc: "A position relative to the stator centre, d = (u, v) = q − ε̂.",
        fields: &[("du", "u", "u = x − ε̂x"), ("dv", "v", "v = y − ε̂y")],
        external: None,
    },
    Group {
        ty: "SlipVelocityRate",
        arg: "slip_rate",
        doc: "The rate w' of the slip velocity (`docs/MODEL.md` §10).",
        fields: &[("w_rate", "rate", "w' = dw/dτ")],
        external: None,
    },
    Group {
        ty: "Velocity",
        arg: "rate",
        doc: "A rotor velocity (x', y').",
        fields: &[("vx", "vx", "x'"), ("vy", "vy", "y'")],
        external: None,
    },
    Group {
        ty: "Force",
        arg: "load",
        doc: "An extra force (per unit mass) on the rotor.",
        fields: &[("fx", "fx", "x component"), ("fy", "fy", "y component")],
        external: None,
    },
    Group {
        ty: "Acceleration",
        arg: "acceleration",
        doc: "A rotor acceleration (x'', y'').",
        fields: &[("ax", "ax", "x''"), ("ay", "ay", "y''")],
        external: None,
    },
    Group {
        ty: "StartState",
        arg: "start",
        doc: "The state at a segment start.",
        fields: &[
            ("x0", "x0", "x(τ0)"),
            ("y0", "y0", "y(τ0)"),
            ("vx0", "vx0", "x'(τ0)"),
            ("vy0", "vy0", "y'(τ0)"),
        ],
        external: None,
    },
    Group {
        ty: "Phasor",
        arg: "phasor",
        doc: "The forcing direction (cos θ, sin θ), θ = ητ + φ0.",
        fields: &[("ct", "ct", "cos θ"), ("st", "st", "sin θ")],
        external: None,
    },
    Group {
        ty: "LocalTime",
        arg: "time",
        doc: "Local time s = τ − τ0 in a segment.",
        fields: &[("s", "s", "s = τ − τ0")],
        external: None,
    },
    Group {
        ty: "TaylorTerms",
        arg: "taylor",
        doc: "Taylor terms of the contact function g ≈ J r + D, J = [[A1, B1], [B2, A2]] (`docs/MODEL.md` §2).",
        fields: &[
            ("a1", "a1", "A1 = ∂gx/∂x"),
            ("b1", "b1", "B1 = ∂gx/∂y"),
            ("b2", "b2", "B2 = ∂gy/∂x"),
            ("a2", "a2", "A2 = ∂gy/∂y"),
            ("d1", "d1", "D1 = gx(r0) − A1 x0 − B1 y0"),
            ("d2", "d2", "D2 = gy(r0) − B2 x0 − A2 y0"),
        ],
        external: None,
    },
    Group {
        ty: "LinearizedContact",
        arg: "kl",
        doc: "Linearized contact stiffness Kl = [[Fa1, Fb1], [Fb2, Fa2]] and constant Fd (`docs/MODEL.md` §3).",
        fields: &[
            (
                "fa1",
                "fa1",
                "Fa1 = Kl[0][0] (x equation, coefficient of x)",
            ),
            (
                "fb1",
                "fb1",
                "Fb1 = Kl[0][1] (x equation, coefficient of y)",
            ),
            (
                "fb2",
                "fb2",
                "Fb2 = Kl[1][0] (y equation, coefficient of x)",
            ),
            (
                "fa2",
                "fa2",
                "Fa2 = Kl[1][1] (y equation, coefficient of y)",
            ),
            ("fd1", "fd1", "Fd1 = (K_s D)_x, the x equation's constant"),
            ("fd2", "fd2", "Fd2 = (K_s D)_y, the y equation's constant"),
        ],
        external: None,
    },
    Group {
        ty: "ContactModes",
        arg: "modes",
        doc: "Eigenvalue data of Kl (`docs/MODEL.md` §5).",
        fields: &[
            (
                "omega_sq_mean",
                "omega_sq_mean",
                "(ω²₁ + ω²₂)/2 = (Fa1 + Fa2)/2",
            ),
            ("disc", "disc", "Δ = ((Fa1 − Fa2)/2)² + Fb1 Fb2"),
            ("det", "det", "det Kl = Fa1 Fa2 − Fb1 Fb2"),
            (
                "gamma_sq_mean",
                "gamma_sq_mean",
                "(γ²₁ + γ²₂)/2 = mean − ν²",
            ),
        ],
        external: None,
    },
    Group {
        ty: "Eigenvalue",
        arg: "mode",
        doc: "One eigenvalue ω² of Kl (undamped squared frequency of a mode).",
        fields: &[("omega_sq", "omega_sq", "ω²")],
        external: None,
    },
    Group {
        ty: "PaperModes",
        arg: "paper",
        doc: "The paper's mode ratios and damped frequencies (`docs/MODEL.md` §5).",
        fields: &[
            ("s1", "s1", "s1 = y/x of mode 1"),
            ("s2", "s2", "s2 = y/x of mode 2"),
            ("gamma1", "gamma1", "γ1, damped frequency of mode 1"),
            ("gamma2", "gamma2", "γ2, damped frequency of mode 2"),
        ],
        external: None,
    },
    Group {
        ty: "ContactParticular",
        arg: "particular",
        doc: "Particular solution of the linearized contact equations (`docs/MODEL.md` §5).",
        fields: &[
            ("cp11", "c11", "c11, cos θ coefficient of x"),
            ("cp22", "c22", "c22, sin θ coefficient of x"),
            ("cp33", "c33", "c33, cos θ coefficient of y"),
            ("cp44", "c44", "c44, sin θ coefficient of y"),
            ("cp55", "c55", "c55, constant of x: −(Kl⁻¹ Fd)_x"),
            ("cp66", "c66", "c66, constant of y: −(Kl⁻¹ Fd)_y"),
        ],
        external: None,
    },
    Group {
        ty: "ParticularResidual",
        arg: "residual",
        doc: "What the linearized contact equations leave at particular constants: their cos θ, sin θ and constant parts (`docs/MODEL.md` §5).",
        fields: &[
            ("pr_xc", "x_cos", "cos θ part of the x equation"),
            ("pr_xs", "x_sin", "sin θ part of the x equation"),
            ("pr_x0", "x_constant", "constant part of the x equation"),
            ("pr_yc", "y_cos", "cos θ part of the y equation"),
            ("pr_ys", "y_sin", "sin θ part of the y equation"),
            ("pr_y0", "y_constant", "constant part of the y equation"),
        ],
        external: None,
    },
    Group {
        ty: "HomogeneousInitial",
        arg: "initial",
        doc: "Initial state of the homogeneous part of a contact segment (state minus particular).",
        fields: &[
            ("xh0", "xh0", "x_h(0)"),
            ("yh0", "yh0", "y_h(0)"),
            ("vxh0", "vxh0", "x_h'(0)"),
            ("vyh0", "vyh0", "y_h'(0)"),
        ],
        external: None,
    },
    Group {
        ty: "HomogeneousStart",
        arg: "homogeneous",
        doc: "Start vectors q0, w0 of q_h = e^{−νs}[C(s) q0 + S(s) w0] (`docs/MODEL.md` §5).",
        fields: &[
            ("q0x", "q0x", "q0, x"),
            ("q0y", "q0y", "q0, y"),
            ("w0x", "w0x", "w0 = q_h'(0) + ν q0, x"),
            ("w0y", "w0y", "w0, y"),
        ],
        external: None,
    },
    Group {
        ty: "ContactBasis",
        arg: "basis",
        doc: "Scalars of the matrix functions at s: C = cc·I + cd·B, S = sc·I + sd·B (B = Kl − σI), decay = e^{−νs}.",
        fields: &[
            ("decay", "decay", "e^{−νs}"),
            (
                "cc",
                "cc",
                "even part of cos(√μ s) over the eigenvalue pair",
            ),
            ("cd", "cd", "odd part of cos(√μ s)"),
            ("sc", "sc", "even part of sin(√μ s)/√μ"),
            ("sd", "sd", "odd part of sin(√μ s)/√μ"),
        ],
        external: None,
    },
    Group {
        ty: "CubicForcing",
        arg: "forcing",
        doc: "An extra cubic forcing a0 + a1 s + a2 s² + a3 s³ (`docs/MODEL.md` §8).",
        fields: &[
            ("a0x", "a0x", "a0, x"),
            ("a0y", "a0y", "a0, y"),
            ("a1x", "a1x", "a1, x"),
            ("a1y", "a1y", "a1, y"),
            ("a2x", "a2x", "a2, x"),
            ("a2y", "a2y", "a2, y"),
            ("a3x", "a3x", "a3, x"),
            ("a3y", "a3y", "a3, y"),
        ],
        external: None,
    },
    Group {
        ty: "PolynomialParticular",
        arg: "poly",
        doc: "Cubic particular solution b0 + b1 s + b2 s² + b3 s³ (`docs/MODEL.md` §8).",
        fields: &[
            ("b0x", "b0x", "b0 (constant), x"),
            ("b0y", "b0y", "b0, y"),
            ("b1x", "b1x", "b1 (linear), x"),
            ("b1y", "b1y", "b1, y"),
            ("b2x", "b2x", "b2 (quadratic), x"),
            ("b2y", "b2y", "b2, y"),
            ("b3x", "b3x", "b3 (cubic), x"),
            ("b3y", "b3y", "b3, y"),
        ],
        external: None,
    },
    Group {
        ty: "FreeParticular",
        arg: "free",
        doc: "Steady-state harmonic response of free flight (`docs/MODEL.md` §4).",
        fields: &[
            ("c11", "c11", "c11, cos θ coefficient of x"),
            ("c22", "c22", "c22, sin θ coefficient of x"),
            ("c33", "c33", "c33, cos θ coefficient of y"),
            ("c44", "c44", "c44, sin θ coefficient of y"),
        ],
        external: None,
    },
    Group {
        ty: "FreeDampedFrequency",
        arg: "beta",
        doc: "Squared damped frequency of free flight (`docs/MODEL.md` §4).",
        fields: &[("beta_sq", "beta_sq", "β² = 1 − ν²")],
        external: None,
    },
    Group {
        ty: "FreeHomogeneous",
        arg: "homogeneous",
        doc: "Constants of the free homogeneous solution x_h = X·EC + P·ES (`docs/MODEL.md` §4).",
        fields: &[
            ("xh", "xh", "X = x0 − xp(τ0)"),
            ("px", "px", "P = x0' − xp'(τ0) + ν X"),
            ("yh", "yh", "Y = y0 − yp(τ0)"),
            ("py", "py", "Q = y0' − yp'(τ0) + ν Y"),
        ],
        external: None,
    },
    Group {
        ty: "FreeBasis",
        arg: "basis",
        doc: "The free-flight basis EC = e^{−νs} cos βs, ES = e^{−νs} sin(βs)/β at s.",
        fields: &[("ec", "ec", "EC(s)"), ("es", "es", "ES(s)")],
        external: None,
    },
    Group {
        ty: "FreeForcing",
        arg: "forcing",
        doc: "The forcing over a free segment as fxc cos ηs + fxs sin ηs, fyc cos ηs + fys sin ηs (`docs/MODEL.md` §11).",
        fields: &[
            ("fxc", "fxc", "cos ηs coefficient of the x forcing"),
            ("fxs", "fxs", "sin ηs coefficient of the x forcing"),
            ("fyc", "fyc", "cos ηs coefficient of the y forcing"),
            ("fys", "fys", "sin ηs coefficient of the y forcing"),
        ],
        external: None,
    },
    Group {
        ty: "ForcingRotation",
        arg: "rotation",
        doc: "The forcing phasor's rotation (cos ηs, sin ηs) over a local time s.",
        fields: &[("ce", "ce", "cos ηs"), ("se", "se", "sin ηs")],
        external: None,
    },
    Group {
        ty: "ForcedBasis",
        arg: "forced",
        doc: "The forced basis at s: zero-state responses FC, FS of the free oscillator to cos ηs, sin ηs and their derivatives (`docs/MODEL.md` §11).",
        fields: &[
            ("fc", "fc", "FC(s)"),
            ("fs", "fs", "FS(s)"),
            ("dfc", "dfc", "FC'(s)"),
            ("dfs", "dfs", "FS'(s)"),
        ],
        external: None,
    },
    Group {
        ty: "Slip",
        arg: "slip",
        doc: "The slip direction σ = sign w of slipping contact (`docs/MODEL.md` §10).",
        fields: &[("sigma", "sigma", "σ = ±1, the sign of the slip velocity w")],
        external: None,
    },
    Group {
        ty: "SpeedChange",
        arg: "speed",
        doc: "A running speed that changes in time (`docs/MODEL.md` §14): the speed's rate η' = dη/dτ.",
        fields: &[(
            "eta_rate",
            "speed_rate",
            "η' = dη/dτ, the rate of the speed ratio",
        )],
        external: None,
    },
    Group {
        ty: "OffsetRate",
        arg: "offset_rate",
        doc: "The rate d' = (u', v') of a rub station's offset from the stator centre (`docs/MODEL.md` §17).",
        fields: &[("du_rate", "ur", "u'"), ("dv_rate", "vr", "v'")],
        external: None,
    },
    Group {
        ty: "ContactLaw",
        arg: "law",
        doc: "A rub station's contact stiffness K_c (`docs/MODEL.md` §17; the planar model's is K_s).",
        fields: &[
            ("kc_xx", "kc_xx", "K_c[0][0]"),
            ("kc_xy", "kc_xy", "K_c[0][1]"),
            ("kc_yx", "kc_yx", "K_c[1][0]"),
            ("kc_yy", "kc_yy", "K_c[1][1]"),
        ],
        external: None,
    },
    Group {
        ty: "StationCompliance",
        arg: "compliance",
        doc: "How a force at a rub station accelerates its offset, W = B M⁻¹ Bᵀ with B = B_r − B_s (`docs/MODEL.md` §17).",
        fields: &[
            ("w_xx", "w_xx", "W[0][0]"),
            ("w_xy", "w_xy", "W[0][1]"),
            ("w_yx", "w_yx", "W[1][0]"),
            ("w_yy", "w_yy", "W[1][1]"),
        ],
        external: None,
    },
    Group {
        ty: "OffsetAcceleration",
        arg: "drive",
        doc: "The acceleration d'' of a rub station's offset from every force but the contact's (`docs/MODEL.md` §17).",
        fields: &[
            ("drive_u", "au", "u'' without contact forces"),
            ("drive_v", "av", "v'' without contact forces"),
        ],
        external: None,
    },
    Group {
        ty: "DriveRate",
        arg: "drive_rate",
        doc: "The rate a' of a rub station's offset acceleration from every force but the contact's (`docs/MODEL.md` §17).",
        fields: &[
            ("drive_rate_u", "au_rate", "(u'')' without contact forces"),
            ("drive_rate_v", "av_rate", "(v'')' without contact forces"),
        ],
        external: None,
    },
    Group {
        ty: "FieldJacobian",
        arg: "jacobian",
        doc: "The Jacobian of a regime's acceleration (x'', y'') with respect to the state (x, y, x', y'), row by row: the variational equations' matrix (`docs/MODEL.md` §18).",
        fields: &[
            ("jxx", "xx", "∂x''/∂x"),
            ("jxy", "xy", "∂x''/∂y"),
            ("jxvx", "xvx", "∂x''/∂x'"),
            ("jxvy", "xvy", "∂x''/∂y'"),
            ("jyx", "yx", "∂y''/∂x"),
            ("jyy", "yy", "∂y''/∂y"),
            ("jyvx", "yvx", "∂y''/∂x'"),
            ("jyvy", "yvy", "∂y''/∂y'"),
        ],
        external: None,
    },
    Group {
        ty: "StateGradient",
        arg: "gradient",
        doc: "The gradient of a scalar function of the state with respect to (x, y, x', y'): a switching surface's normal in the state space (`docs/MODEL.md` §18).",
        fields: &[
            ("gx", "x", "∂/∂x"),
            ("gy", "y", "∂/∂y"),
            ("gvx", "vx", "∂/∂x'"),
            ("gvy", "vy", "∂/∂y'"),
        ],
        external: None,
    },
];

/// Symbols that only live inside derivations (unknowns, variables substituted away).
pub const INTERNAL: &[(&str, &str)] = &[
    ("x", "x, the displacement variable of a derivation"),
    ("y", "y, the displacement variable of a derivation"),
    (
        "lam",
        "λ, the variable of the characteristic polynomial det(Kl − λI)",
    ),
    (
        "tau",
        "τ, time in a modal ansatz (substituted by 0 for initial conditions)",
    ),
    (
        "bsq",
        "b, the unknown squared frequency of the damped-frequency ansatz",
    ),
    ("s_ratio", "s, the unknown mode ratio y/x"),
    (
        "qsx",
        "x of the unknown constant response to the input force",
    ),
    (
        "qsy",
        "y of the unknown constant response to the input force",
    ),
    (
        "ring_q0",
        "x of the stator ring model's positions (q, p) = (x, y, x_s, y_s)",
    ),
    ("ring_q1", "y of the stator ring model's positions"),
    ("ring_q2", "x_s of the stator ring model's positions"),
    ("ring_q3", "y_s of the stator ring model's positions"),
    ("ring_v0", "x' of the stator ring model's velocities"),
    ("ring_v1", "y' of the stator ring model's velocities"),
    ("ring_v2", "x_s' of the stator ring model's velocities"),
    ("ring_v3", "y_s' of the stator ring model's velocities"),
    ("c1", "c1, unknown of the paper's modal constants"),
    ("c2", "c2, unknown of the paper's modal constants"),
    ("c3", "c3, unknown of the paper's modal constants"),
    ("c4", "c4, unknown of the paper's modal constants"),
];

/// A declared symbol: its group (if any) and its field name there.
#[derive(Clone, Copy)]
pub struct Declared {
    /// The input struct, `None` for derivation-internal symbols.
    pub group: Option<&'static Group>,
    /// The struct field (and local variable) name.
    pub field: &'static str,
}

/// The declaration table.
pub struct Symbols;

impl Symbols {
    /// The declaration of `name`, if declared.
    pub fn find(name: &str) -> Option<Declared> {
        for g in all_groups() {
            if let Some(&(_, field, _)) = g.fields.iter().find(|f| f.0 == name) {
                return Some(Declared {
                    group: Some(g),
                    field,
                });
            }
        }
        INTERNAL.iter().find(|f| f.0 == name).map(|_| Declared {
            group: None,
            field: "",
        })
    }

    /// Every place `name` is declared: the structs declaring it, and `"internal"`.
    pub fn declarations(name: &str) -> impl Iterator<Item = &'static str> + '_ {
        let groups = all_groups()
            .iter()
            .filter(move |g| g.fields.iter().any(|f| f.0 == name))
            .map(|g| g.ty);
        let internal = INTERNAL
            .iter()
            .filter(move |f| f.0 == name)
            .map(|_| "internal");
        groups.chain(internal)
    }

    /// The declaration of `name`; the build fails naming the symbol and `formula` when it is
    /// declared nowhere or more than once (two meanings of one name would silently merge).
    pub fn lookup(name: &str, formula: &str) -> Declared {
        let places: Vec<&str> = Self::declarations(name).collect();
        if places.len() > 1 {
            panic!(
                "formula `{formula}` uses the symbol `{name}`, declared more than once ({}): declare each symbol once in codegen/src/model/symbols.rs",
                places.join(", ")
            );
        }
        Self::find(name).unwrap_or_else(|| {
            panic!(
                "formula `{formula}` uses the undeclared symbol `{name}`: declare it once in codegen/src/model/symbols.rs (GROUPS or INTERNAL)"
            )
        })
    }

    /// The group whose struct is named `ty`.
    pub fn group(ty: &str) -> Option<&'static Group> {
        all_groups().iter().find(|g| g.ty == ty)
    }
}

/// The runtime's parameter struct as an input group: every model parameter of the table, as the
/// symbol `params.<name>` (not emitted: the generated code names `crate::params::Params`).
fn table_group() -> Group {
    let fields: Vec<(&'static str, &'static str, &'static str)> = parameters::MODEL
        .iter()
        .map(|e| {
            let symbol: &'static str =
                Box::leak(format!("{TABLE_PREFIX}{}", e.name).into_boxed_str());
            (symbol, e.name, e.doc)
        })
        .collect();
    Group {
        ty: "Params",
        arg: "params",
        doc: "The parameter table's values (the runtime's `Params`).",
        fields: fields.leak(),
        external: Some("crate::params::Params"),
    }
}

/// `ModelParams` with the fields `keep` says (table order, then [`DERIVED`]'s).
fn model_group(keep: impl Fn(&str) -> bool) -> Group {
    let table = parameters::MODEL.iter().map(|e| (e.name, e.name, e.doc));
    let derived = DERIVED.iter().map(|&(name, doc)| (name, name, doc));
    let fields: Vec<_> = table.chain(derived).filter(|f| keep(f.0)).collect();
    Group {
        ty: MODEL_PARAMS,
        arg: "model",
        doc: "The model's parameters: the parameter table's entries the formulas read and the quantities derived from them (`docs/MODEL.md` §0, §1).",
        fields: fields.leak(),
        external: None,
    }
}

/// Every declared struct: the table's, `ModelParams` with every table entry and derived
/// quantity, then [`GROUPS`] (what declarations are checked against).
pub fn all_groups() -> &'static [Group] {
    static ALL: OnceLock<Vec<Group>> = OnceLock::new();
    ALL.get_or_init(|| {
        let mut all = vec![table_group(), model_group(|_| true)];
        all.extend(GROUPS.iter().cloned());
        all
    })
}

/// The structs the generated code is emitted with: as [`all_groups`], with `ModelParams` holding
/// only the fields some formula reads (`used`: the symbols of every formula but `model_params`
/// itself), so that it carries nothing it does not need.
pub fn emission_groups(used: &HashSet<String>) -> &'static [Group] {
    let mut all = vec![table_group(), model_group(|name| used.contains(name))];
    all.extend(GROUPS.iter().cloned());
    all.leak()
}
