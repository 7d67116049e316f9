// The parameter table: every model parameter and initial-state value, stated once with its name,
// paper symbol, default, valid range and meaning. Read by the runtime (`params/table.rs`: the
// `Params` struct, the `Parameter` enum, validation, the CLI, the C ABI) and by the generator
// (`codegen/src/model/parameters.rs`: the generated formulas' `ModelParams` and its constructor),
// each with its own `parameter_table!` macro. Adding a parameter is one entry here plus its use
// in the model statement (`codegen/src/model/mod.rs`).
//
// Why these ranges (the physics and the numerics; all values dimensionless):
// * η ∈ [1e-3, 1e2]: below, one forcing period (2π/η) exceeds 6e3 τ and the unbalance force
//   η_m ρ̂ η² vanishes, so no run is meaningful (η = 5e-324 overflowed the period); above, the
//   contact and forcing time scales differ by more than 1e2 K̂ and the phase η τ loses digits.
// * ν ∈ [0, 10]: 0 is the undamped rotor; ν = 10 already has a free decay rate ratio ≈ 4ν² = 400,
//   past which the free flight is a stiff relaxation no rub study uses.
// * η_m ∈ (0, 1]: the unbalance mass cannot exceed the disk's; ρ̂ ∈ (0, 1e3]: the unbalance
//   radius η_m ρ̂ (the supercritical orbit radius) stays a decade below the divergence radius
//   (1e4 clearances, `propagate::DIVERGENCE_RADIUS`), so a reported divergence is physical.
// * |K̂| ≤ 1e5 per entry: contact frequencies √(1 + K̂) ≤ 316; at this edge the analytic method
//   still meets 1e-6 against DOP853 even for a nearly singular K_s (`tests/degenerate.rs`), at
//   1e6 it errs by 1e-5; stiffer stators are rigid-wall limits outside this model.
// * |ε̂| ≤ 10 and |x0|, |y0| ≤ 1e2 clearances, |x0'|, |y0'| ≤ 1e2: the free amplitude
//   √(r0² + v0²) + η_m ρ̂ stays below the divergence radius, so a start inside the ranges is never
//   reported as diverged before it moves.
// * |φ0| ≤ 1e3 rad and |τ0| ≤ 1e6: the forcing phase η τ0 + φ0 keeps an absolute error ≤ 1e-8.
// * μ ∈ [0, 10]: dry friction coefficients of rubbing metals and seals are 0.1–0.6; 10 leaves
//   room for studies of the limit. ρ_R ∈ (0, 1e5]: real rotors have R/δ ≈ 1e2–1e4; the slip
//   velocity's spin term ρ_R η stays below 1e7. μ > 0 also needs a positive definite symmetric
//   part of K_s (`cross_checks`), else the normal force can turn negative (`docs/MODEL.md §10`).
// * |u| ≤ 1e3 per component (the external input force, `docs/MODEL.md §15`): its static
//   deflection u stays a decade below the divergence radius, like the unbalance orbit.
// * The stator ring (`docs/MODEL.md` §17): m̂ ∈ [0, 1e3] (0 is the paper's massless ring; at
//   1e3 the ring moves by 1e-3 of the rotor's contact impulse, the fixed-ring limit);
//   k̂_c ∈ (0, 1e6] (a contact frequency √(k̂_c (1 + 1/m̂)) ≤ 1e3·√2 keeps a contact resolved by
//   a few hundred steps per forcing period); ĉ ∈ [0, 1e3] (0: the ring rings down for ever).
//   Its start state has the rotor's ranges. Without mass (m̂ = 0) the ring has no state and no
//   contact spring of its own: a non-default k̂_c, ĉ or ring start is an error
//   (`ParamError::RingWithoutMass`), never silently ignored.


const STIFFNESS: f64 = 1.0e5;
const FORCE: f64 = 1.0e3;

parameter_table! {
    model {
        SpeedRatio speed_ratio "η" = 1.5, Range::closed(1.0e-3, 1.0e2),
            "running speed over the rotor's natural frequency, Ω/ω_n";
        DampingRatio damping_ratio "ν" = 0.125, Range::closed(0.0, 10.0),
            "viscous damping ratio of the rotor (ζ in the paper's Table 1; > 1 is over-damped)";
        MassRatio mass_ratio "η_m" = 0.005, Range::above(0.0, 1.0),
            "unbalance mass over disk mass";
        EccentricityRatio eccentricity_ratio "ρ̂" = 70.0, Range::above(0.0, 1.0e3),
            "unbalance eccentricity over the radial clearance";
        Phase phase "φ0" = 0.0, Range::closed(-1.0e3, 1.0e3),
            "phase of the unbalance at τ = 0, rad";
        KXx k_xx "K̂xx" = 20.0, Range::closed(0.0, STIFFNESS),
            "stator stiffness over rotor stiffness: x force per x displacement";
        KXy k_xy "K̂xy" = 20.0, Range::closed(-STIFFNESS, STIFFNESS),
            "stator stiffness over rotor stiffness: x force per y displacement (cross-coupling)";
        KYx k_yx "K̂yx" = 20.0, Range::closed(-STIFFNESS, STIFFNESS),
            "stator stiffness over rotor stiffness: y force per x displacement (cross-coupling)";
        KYy k_yy "K̂yy" = 40.0, Range::closed(0.0, STIFFNESS),
            "stator stiffness over rotor stiffness: y force per y displacement";
        OffsetX offset_x "ε̂x" = 0.3, Range::closed(-10.0, 10.0),
            "stator centre offset from the rotor's rest position, x, clearances";
        OffsetY offset_y "ε̂y" = -0.2, Range::closed(-10.0, 10.0),
            "stator centre offset from the rotor's rest position, y, clearances";
        FrictionCoefficient friction_coefficient "μ" = 0.0, Range::closed(0.0, 10.0),
            "Coulomb friction coefficient at contact (0: frictionless, the paper's model)";
        RadiusRatio radius_ratio "ρ_R" = 100.0, Range::above(0.0, 1.0e5),
            "rotor radius over radial clearance, R/δ (the rotor spins counter-clockwise at η)";
        ForceX force_x "u_x" = 0.0, Range::closed(-FORCE, FORCE),
            "external force on the rotor per unit mass, x, clearances·ω_n² (a bearing, a controller, a static load; the FMU's input fx)";
        ForceY force_y "u_y" = 0.0, Range::closed(-FORCE, FORCE),
            "external force on the rotor per unit mass, y, clearances·ω_n² (the FMU's input fy)";
        StatorMassRatio stator_mass_ratio "m̂" = 0.0, Range::closed(0.0, 1.0e3),
            "stator ring mass over disk mass (0: the paper's massless ring, whose support K_s is the contact spring)";
        ContactStiffness contact_stiffness "k̂_c" = 50.0, Range::above(0.0, 1.0e6),
            "rotor–ring contact stiffness over rotor stiffness (isotropic; with stator_mass_ratio > 0 only)";
        StatorDamping stator_damping "ĉ" = 0.0, Range::closed(0.0, 1.0e3),
            "ring support damping c_s/(M ω_n) (isotropic; with stator_mass_ratio > 0 only)";
        Xs0 xs0 "x̃s0" = 0.0, Range::closed(-1.0e2, 1.0e2),
            "initial ring position x from its rest position, clearances (with stator_mass_ratio > 0 only)";
        Ys0 ys0 "ỹs0" = 0.0, Range::closed(-1.0e2, 1.0e2),
            "initial ring position y from its rest position, clearances (with stator_mass_ratio > 0 only)";
        Vxs0 vxs0 "x̃s0'" = 0.0, Range::closed(-1.0e2, 1.0e2),
            "initial ring velocity x', clearances per unit τ (with stator_mass_ratio > 0 only)";
        Vys0 vys0 "ỹs0'" = 0.0, Range::closed(-1.0e2, 1.0e2),
            "initial ring velocity y', clearances per unit τ (with stator_mass_ratio > 0 only)";
    }
    start {
        X0 x0 "x̃0" = 0.1, Range::closed(-1.0e2, 1.0e2),
            "initial position x, clearances", initial.x;
        Y0 y0 "ỹ0" = 0.1, Range::closed(-1.0e2, 1.0e2),
            "initial position y, clearances", initial.y;
        Vx0 vx0 "x̃0'" = 0.0, Range::closed(-1.0e2, 1.0e2),
            "initial velocity x', clearances per unit τ", initial.vx;
        Vy0 vy0 "ỹ0'" = 0.0, Range::closed(-1.0e2, 1.0e2),
            "initial velocity y', clearances per unit τ", initial.vy;
        StartTime start_time "τ0" = 0.0, Range::closed(-1.0e6, 1.0e6),
            "time of the initial state", start_time;
    }
}
