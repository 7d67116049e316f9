//! The model, stated once (`docs/MODEL.md` §1), and the derivations of every formula from it.
//!
//! The equations of motion are a sum of named pieces, each written once below:
//!
//! ```text
//! q'' = F (cos θ, sin θ) + u          − 2ν q'   − q          − K_s·g(q)        − μσN t
//!       [`unbalance`]        [`input_force`] [`damping`] [`restoring`] [`elastic_contact`] [`friction`]
//!                                                                  [contact only]    [slipping]
//! ```
//!
//! At a running speed that changes, the unbalance term is [`unbalance_at_varying_speed`],
//! η_m ρ̂ (η² (cos θ, sin θ) − η' (−sin θ, cos θ)) with θ' = η; [`unbalance`] is its η' = 0 case.
//!
//! with g(q) = (1 − 1/z)(u, v) ([`contact_function`]), (u, v) = q − ε̂, z = |(u, v)|, the
//! normal force N = nᵀK_s g ([`normal_force`]) and the frame n, t ([`contact_frame`]); rolling
//! replaces μσN by the tangential force λ that keeps the slip velocity at 0 (`friction.rs`). [`Model::contact_pieces`] sums
//! the forces that act only in contact, [`Model::acceleration`] assembles a regime's field and
//! [`Model::equations_of_motion`] is its residual, which every derivation substitutes an ansatz
//! into; the Taylor linearization replaces K_s·g(q) by K_s(J q + D). A new force is one more
//! piece here, added to `contact_pieces` (friction) or to the forcing (an external input):
//! every generated formula follows from it.
//!
//! The input force u (an active magnetic bearing, a controller, a static load such as gravity)
//! is held constant over a step by every caller, so each regime's equations stay linear with a
//! constant extra forcing and the closed forms stay exact: free flight moves its equilibrium to
//! the static deflection ([`input_static_deflection`](free.rs)), linearized contact adds the
//! constant response Kl⁻¹u (`input_contact_constant`), and the friction quantities and the
//! rolling field see it in G, the sum of every force but friction.
//!
//! [`unbalance`]: Model::unbalance
//! [`unbalance_at_varying_speed`]: Model::unbalance_at_varying_speed
//! [`input_force`]: Model::input_force
//! [`damping`]: Model::damping
//! [`restoring`]: Model::restoring
//! [`elastic_contact`]: Model::elastic_contact
//! [`contact_function`]: Model::contact_function
//! [`friction`]: Model::friction
//! [`normal_force`]: Model::normal_force
//! [`contact_frame`]: Model::contact_frame

mod contact;
mod field;
mod free;
mod free_step;
mod friction;
mod linearization;
pub mod parameters;
mod polynomial;
mod regimes;
mod speed;
mod station;
pub mod symbols;
mod taylor;
mod tools;
mod variational;

use std::collections::HashMap;

use crate::derive::derivative;
use crate::expr::{ExprId, Graph, Symbol};
use crate::ir::Formula;

/// The model's graph and the formulas derived from it, in emission order.
pub struct Model {
    /// The expression graph all formulas live in.
    pub graph: Graph,
    /// The derived formulas.
    pub formulas: Vec<Formula>,
    /// The systems whose Taylor recurrences are generated (`taylor.rs`).
    pub taylor: Vec<crate::ir::System>,
}

/// Build the model and derive every formula.
pub fn derive_all() -> Model {
    let mut m = Model {
        graph: Graph::new(),
        formulas: Vec::new(),
        taylor: Vec::new(),
    };
    linearization::derive(&mut m);
    free::derive(&mut m);
    contact::derive(&mut m);
    polynomial::derive(&mut m);
    field::derive(&mut m);
    friction::derive(&mut m);
    speed::derive(&mut m);
    taylor::derive(&mut m);
    regimes::derive(&mut m);
    station::derive(&mut m);
    variational::derive(&mut m);
    m
}

/// The time-dependent quantities of an ansatz: each symbol's rate d/dτ.
pub(crate) type Rates = HashMap<Symbol, ExprId>;

/// A 2-vector of expressions.
pub(crate) type Vec2 = [ExprId; 2];

impl Model {
    /// The context named in a build failure: the formula derived next.
    fn context(&self) -> String {
        match self.formulas.last() {
            Some(f) => format!("after {}", f.name),
            None => "first".to_owned(),
        }
    }

    /// The declared symbol `name` (the build fails naming it when it is not declared).
    pub(crate) fn sym(&mut self, name: &str) -> Symbol {
        symbols::Symbols::lookup(name, &self.context());
        self.graph.symbol(name)
    }

    /// The input expression of the declared symbol `name`.
    pub(crate) fn var(&mut self, name: &str) -> ExprId {
        let s = self.sym(name);
        self.graph.input_of(s)
    }

    /// The parameter table's entry `name` as the caller holds it (the runtime's `Params` field):
    /// what the derived parameters are stated in.
    fn table(&mut self, name: &str) -> ExprId {
        self.var(&format!("{}{name}", symbols::TABLE_PREFIX))
    }

    /// The quantities the model derives from the table's parameters ([`symbols::DERIVED`]), each
    /// with its definition, in the order they depend on each other: the unbalance's radius
    /// η_m ρ̂ (from the table's mass and eccentricity ratios, which the formulas do not read
    /// themselves) and the forcing amplitude at a constant speed F = η_m ρ̂ η². The generated
    /// `model_params` computes them once per parameter set ([`Model::model_params_formula`]);
    /// the formulas read them as fields of `ModelParams`.
    pub(crate) fn derived_parameters(&mut self) -> Vec<(&'static str, ExprId)> {
        let (mass, eccentricity) = (self.table("mass_ratio"), self.table("eccentricity_ratio"));
        let unbalance_radius = self.graph.mul(mass, eccentricity);
        let (unbalance, eta) = (self.var("unbalance"), self.var("speed_ratio"));
        let force = self.graph.product(&[unbalance, eta, eta]);
        vec![("unbalance", unbalance_radius), ("unbalance_force", force)]
    }

    /// The derived quantity `name`'s definition ([`Model::derived_parameters`]).
    pub(crate) fn derived(&mut self, name: &str) -> ExprId {
        let derived = self.derived_parameters();
        derived
            .into_iter()
            .find_map(|(n, e)| (n == name).then_some(e))
            .unwrap_or_else(|| panic!("`{name}` is not a derived parameter of the model"))
    }

    /// The generated `model_params`: `ModelParams` from the runtime's `Params`, each field of the
    /// table copied by name and each derived quantity computed ([`Model::derived_parameters`],
    /// its symbols replaced by the table's fields). `fields` are `ModelParams`' fields (the
    /// emission's: only those the formulas read).
    pub(crate) fn model_params_formula(&mut self, fields: &[(&str, &str, &str)]) -> Formula {
        // Each derived quantity in the table's terms: earlier ones substituted into later ones,
        // then every table entry by its `params.` field.
        let mut derived: Vec<(&str, ExprId)> = Vec::new();
        for (name, definition) in self.derived_parameters() {
            let mut pairs: Vec<(String, ExprId)> =
                derived.iter().map(|&(n, e)| (n.to_owned(), e)).collect();
            for entry in parameters::MODEL {
                let field = self.table(entry.name);
                pairs.push((entry.name.to_owned(), field));
            }
            let pairs: Vec<(&str, ExprId)> = pairs.iter().map(|(n, e)| (n.as_str(), *e)).collect();
            let expr = self.subst(definition, &pairs);
            derived.push((name, expr));
        }
        let outputs = fields
            .iter()
            .map(|&(name, _, doc)| {
                let expr = match derived.iter().find(|d| d.0 == name) {
                    Some(&(_, e)) => e,
                    None => self.table(name),
                };
                crate::ir::Output {
                    name: name.to_owned(),
                    doc: doc.to_owned(),
                    expr,
                }
            })
            .collect();
        Formula {
            name: "model_params".to_owned(),
            summary: "The model's parameters from the parameter table: each entry the formulas read, copied by name, and the quantities derived from them (F = η_m ρ̂ η², η_m ρ̂).".to_owned(),
            source: "docs/MODEL.md §0, §1".to_owned(),
            derivation: "the table's fields; the derived quantities as the model states them (`Model::derived_parameters`).".to_owned(),
            test_only: false,
            output_type: symbols::MODEL_PARAMS.to_owned(),
            outputs,
        }
    }

    /// The forcing phasor's symbols (cos θ, sin θ) and their rates, θ = ητ + φ0:
    /// d(cos θ)/dτ = −η sin θ, d(sin θ)/dτ = η cos θ.
    pub(crate) fn forcing_phasor(&mut self, rates: &mut Rates) -> Vec2 {
        let eta = self.var("speed_ratio");
        let ct = self.var("ct");
        let st = self.var("st");
        let g = &mut self.graph;
        let rate_c = {
            let p = g.mul(eta, st);
            g.neg(p)
        };
        let rate_s = g.mul(eta, ct);
        let (cs, ss) = (g.symbol("ct"), g.symbol("st"));
        rates.insert(cs, rate_c);
        rates.insert(ss, rate_s);
        [ct, st]
    }

    /// Viscous damping 2ν q' (per unit mass).
    pub(crate) fn damping(&mut self, v: Vec2) -> Vec2 {
        let nu = self.var("damping_ratio");
        let g = &mut self.graph;
        v.map(|vi| {
            let t = g.mul(nu, vi);
            g.scale(2.0, t)
        })
    }

    /// The restoring force of the shaft's spring, q (stiffness 1 in the model's units).
    pub(crate) fn restoring(&mut self, q: Vec2) -> Vec2 {
        q
    }

    /// The rotor's position relative to the stator centre, stated once (`docs/MODEL.md` §1):
    /// d = (u, v) = q − ε̂, with its squared length z² and length z ([`Model::offset_length`]).
    /// Every contact quantity of the planar model (the contact function, the frame, the
    /// switching function) is built on it.
    pub(crate) fn stator_offset(&mut self, q: Vec2) -> (Vec2, ExprId, ExprId) {
        let (ex, ey) = (self.var("offset_x"), self.var("offset_y"));
        let g = &mut self.graph;
        let u = g.sub(q[0], ex);
        let v = g.sub(q[1], ey);
        let (z2, z) = self.offset_length([u, v]);
        ([u, v], z2, z)
    }

    /// z² = u² + v² and z of an offset d = (u, v) from the stator centre: the one definition of
    /// the distance every contact law measures (the planar model's d = q − ε̂, a rub station's
    /// d = B_r q − B_s q − ε̂).
    pub(crate) fn offset_length(&mut self, d: Vec2) -> (ExprId, ExprId) {
        let g = &mut self.graph;
        let uu = g.mul(d[0], d[0]);
        let vv = g.mul(d[1], d[1]);
        let z2 = g.add(uu, vv);
        let z = g.sqrt(z2);
        (z2, z)
    }

    /// The switching function h = z² − 1 of a position: negative in free flight, positive in
    /// contact (squared so that it is smooth and cheap).
    pub(crate) fn boundary(&mut self, q: Vec2) -> ExprId {
        let (_, z2, _) = self.stator_offset(q);
        self.boundary_at(z2)
    }

    /// h = z² − 1 from z².
    pub(crate) fn boundary_at(&mut self, z2: ExprId) -> ExprId {
        let g = &mut self.graph;
        let one = g.constant(1.0);
        g.sub(z2, one)
    }

    /// The contact function g(q) = (1 − 1/z)(u, v) ([`Model::stator_offset`]): the stator's
    /// deflection, the rotor's penetration beyond the clearance along the radius.
    pub(crate) fn contact_function(&mut self, q: Vec2) -> Vec2 {
        let (d, _, z) = self.stator_offset(q);
        self.penetration(d, z)
    }

    /// The penetration (1 − 1/z) d of an offset d of length z.
    pub(crate) fn penetration(&mut self, d: Vec2, z: ExprId) -> Vec2 {
        let g = &mut self.graph;
        let one = g.constant(1.0);
        let inv_z = g.powi(z, -1);
        let scale = g.sub(one, inv_z);
        [g.mul(scale, d[0]), g.mul(scale, d[1])]
    }

    /// K_s·w: the stator stiffness applied to a deflection.
    pub(crate) fn stator_force(&mut self, w: Vec2) -> Vec2 {
        let ks = self.stator_stiffness();
        self.apply(ks, w)
    }

    /// K·w for a 2 × 2 matrix K.
    pub(crate) fn apply(&mut self, k: [[ExprId; 2]; 2], w: Vec2) -> Vec2 {
        let g = &mut self.graph;
        [0, 1].map(|i| {
            let a = g.mul(k[i][0], w[0]);
            let b = g.mul(k[i][1], w[1]);
            g.add(a, b)
        })
    }

    /// The elastic contact force K_s·g(q) (restoring sign: it enters the acceleration with −).
    pub(crate) fn elastic_contact(&mut self, q: Vec2) -> Vec2 {
        let w = self.contact_function(q);
        self.stator_force(w)
    }

    /// The outward normal n = (u, v)/z and the counter-clockwise tangent t = (−v, u)/z of the
    /// contact at q ([`Model::stator_offset`]), with z (`docs/MODEL.md` §10).
    pub(crate) fn contact_frame(&mut self, q: Vec2) -> (Vec2, Vec2, ExprId) {
        let (d, _, z) = self.stator_offset(q);
        self.frame(d, z)
    }

    /// The normal n = d/z and the counter-clockwise tangent t = (−d_y, d_x)/z of an offset d of
    /// length z, with z.
    pub(crate) fn frame(&mut self, [u, v]: Vec2, z: ExprId) -> (Vec2, Vec2, ExprId) {
        let g = &mut self.graph;
        let inv_z = g.powi(z, -1);
        let n = [g.mul(u, inv_z), g.mul(v, inv_z)];
        let mv = g.neg(v);
        let t = [g.mul(mv, inv_z), g.mul(u, inv_z)];
        (n, t, z)
    }

    /// The slip velocity w = q'·t + ρ_R η of the rotor's surface at the contact point
    /// (`docs/MODEL.md` §10): the rotor spins counter-clockwise at η.
    pub(crate) fn slip_velocity(&mut self, q: Vec2, v: Vec2) -> ExprId {
        let (_, t, _) = self.contact_frame(q);
        self.surface_slip(v, t)
    }

    /// w = d'·t + ρ_R η: the slip velocity of the rotor's surface, spinning counter-clockwise at
    /// η, whose contact point moves at d' relative to the stator's, along the tangent t.
    pub(crate) fn surface_slip(&mut self, v: Vec2, t: Vec2) -> ExprId {
        let vt = self.dot(v, t);
        let (rho, eta) = (self.var("radius_ratio"), self.var("speed_ratio"));
        let g = &mut self.graph;
        let spin = g.mul(rho, eta);
        g.add(vt, spin)
    }

    /// The normal elastic contact force N = nᵀ K_s g(q) (≥ 0 when the symmetric part of K_s
    /// is positive definite): what presses the rotor on the stator.
    pub(crate) fn normal_force(&mut self, q: Vec2) -> ExprId {
        let f = self.elastic_contact(q);
        let (n, _, _) = self.contact_frame(q);
        self.dot(n, f)
    }

    /// Coulomb friction while slipping, μ σ N t (restoring sign: it enters the acceleration with
    /// −, opposing the slip velocity w whose sign is σ).
    pub(crate) fn friction(&mut self, q: Vec2, sigma: ExprId) -> Vec2 {
        let normal = self.normal_force(q);
        let (_, t, _) = self.contact_frame(q);
        let mu = self.var("friction_coefficient");
        self.coulomb(mu, sigma, normal, t)
    }

    /// μ σ N t: Coulomb friction of magnitude μN along the tangent t, in the slip direction σ.
    pub(crate) fn coulomb(&mut self, mu: ExprId, sigma: ExprId, normal: ExprId, t: Vec2) -> Vec2 {
        let g = &mut self.graph;
        let magnitude = g.product(&[mu, sigma, normal]);
        t.map(|ti| g.mul(magnitude, ti))
    }

    /// a·b for 2-vectors.
    pub(crate) fn dot(&mut self, a: Vec2, b: Vec2) -> ExprId {
        let g = &mut self.graph;
        let p0 = g.mul(a[0], b[0]);
        let p1 = g.mul(a[1], b[1]);
        g.add(p0, p1)
    }

    /// Every force that acts only in contact, summed (restoring sign): the elastic K_s·g(q),
    /// and while slipping in direction `slip` (σ), Coulomb friction μσN t. `None` is the
    /// frictionless contact of the paper (μ = 0 runs it, bit for bit).
    pub(crate) fn contact_pieces(&mut self, q: Vec2, slip: Option<ExprId>) -> Vec2 {
        let elastic = self.elastic_contact(q);
        match slip {
            None => elastic,
            Some(sigma) => {
                let f = self.friction(q, sigma);
                [0, 1].map(|i| self.graph.add(elastic[i], f[i]))
            }
        }
    }

    /// The nonlinear stiffness term of a regime: q, plus the contact pieces in contact
    /// (`Some(slip)`: slipping in direction `slip`, see [`Model::contact_pieces`]).
    pub(crate) fn stiffness(&mut self, q: Vec2, contact: Option<Option<ExprId>>) -> Vec2 {
        let r = self.restoring(q);
        let Some(slip) = contact else {
            return r;
        };
        let c = self.contact_pieces(q, slip);
        [self.graph.add(r[0], c[0]), self.graph.add(r[1], c[1])]
    }

    /// The acceleration q'' = forcing − 2ν q' − stiffness of the equations of motion, for a
    /// stiffness term (`stiffness`, `linear_stiffness_term`) and the forces on the right-hand side.
    pub(crate) fn acceleration(&mut self, v: Vec2, stiffness: Vec2, forcing: Vec2) -> Vec2 {
        let d = self.damping(v);
        let g = &mut self.graph;
        [0, 1].map(|i| {
            let a = g.neg(d[i]);
            let b = g.neg(stiffness[i]);
            g.sum(&[forcing[i], a, b])
        })
    }

    /// The residual q'' + 2ν q' + stiffness − forcing of the equations of motion
    /// (`docs/MODEL.md` §1) for a trajectory `q(τ)` whose time dependence is given by `rates`.
    pub(crate) fn equations_of_motion(
        &mut self,
        q: Vec2,
        rates: &Rates,
        stiffness: Vec2,
        forcing: Vec2,
    ) -> Vec2 {
        let mut residual = [q[0]; 2];
        for i in 0..2 {
            let g = &mut self.graph;
            let v = derivative(g, q[i], rates);
            let a = derivative(g, v, rates);
            let damping = self.damping([v, v])[0];
            let g = &mut self.graph;
            let rhs = g.neg(forcing[i]);
            residual[i] = g.sum(&[a, damping, stiffness[i], rhs]);
        }
        residual
    }

    /// The unbalance forcing F (cos θ, sin θ) at a constant running speed: the case η' = 0 of
    /// [`Model::unbalance_at_varying_speed`], with F = η_m ρ̂ η² (`speed.rs` checks the two agree
    /// when the build runs).
    pub(crate) fn unbalance(&mut self, phasor: Vec2) -> Vec2 {
        let f = self.var("unbalance_force");
        [self.graph.mul(f, phasor[0]), self.graph.mul(f, phasor[1])]
    }

    /// The unbalance forcing at a running speed η(τ) that changes at the rate η' (`docs/MODEL.md`
    /// §14): the unbalance sits at η_m ρ̂ (cos θ, sin θ) from the rotor centre, θ' = η, and
    /// pulls on the rotor with minus its acceleration,
    ///
    /// ```text
    /// −η_m ρ̂ d²/dτ² (cos θ, sin θ) = η_m ρ̂ (η² (cos θ, sin θ) − η' (−sin θ, cos θ)).
    /// ```
    ///
    /// Speeding up (η' > 0) the unbalance lags and drags the rotor backwards along its whirl.
    /// Returned with the rates it was differentiated with (θ' = η, η' = `eta_rate`).
    pub(crate) fn unbalance_at_varying_speed(&mut self) -> (Vec2, Rates) {
        let mut rates = Rates::new();
        let phasor = self.forcing_phasor(&mut rates);
        let (eta, rate) = (self.sym("speed_ratio"), self.var("eta_rate"));
        rates.insert(eta, rate);
        let unbalance = self.var("unbalance");
        let g = &mut self.graph;
        let forcing = phasor.map(|c| {
            let position = g.mul(unbalance, c);
            let velocity = derivative(g, position, &rates);
            let acceleration = derivative(g, velocity, &rates);
            g.neg(acceleration)
        });
        (forcing, rates)
    }

    /// The external input force u = (u_x, u_y) (per unit mass): what a magnetic bearing or a
    /// controller applies, or a static load. Constant over a step (`docs/MODEL.md` §15).
    pub(crate) fn input_force(&mut self) -> Vec2 {
        [self.var("force_x"), self.var("force_y")]
    }

    /// Every force on the right-hand side of the equations of motion that acts in all regimes:
    /// the unbalance at phasor `phasor` plus the input force.
    pub(crate) fn forcing(&mut self, phasor: Vec2) -> Vec2 {
        let unbalance = self.unbalance(phasor);
        let input = self.input_force();
        [0, 1].map(|i| self.graph.add(unbalance[i], input[i]))
    }

    /// The stator stiffness matrix K_s.
    pub(crate) fn stator_stiffness(&mut self) -> [[ExprId; 2]; 2] {
        [
            [self.var("k_xx"), self.var("k_xy")],
            [self.var("k_yx"), self.var("k_yy")],
        ]
    }

    /// The linearized contact stiffness Kl and constant Fd as inputs (outputs of
    /// `linearized_stiffness`).
    pub(crate) fn linearized_inputs(&mut self) -> ([[ExprId; 2]; 2], Vec2) {
        (
            [
                [self.var("fa1"), self.var("fb1")],
                [self.var("fb2"), self.var("fa2")],
            ],
            [self.var("fd1"), self.var("fd2")],
        )
    }

    /// Kl·q + Fd for the linearized contact regime.
    pub(crate) fn linear_stiffness_term(
        &mut self,
        kl: [[ExprId; 2]; 2],
        fd: Vec2,
        q: Vec2,
    ) -> Vec2 {
        let g = &mut self.graph;
        let mut out = [q[0]; 2];
        for i in 0..2 {
            let a = g.mul(kl[i][0], q[0]);
            let b = g.mul(kl[i][1], q[1]);
            out[i] = g.sum(&[a, b, fd[i]]);
        }
        out
    }
}
