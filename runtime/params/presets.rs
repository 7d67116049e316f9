//! The named presets (`docs/MODEL.md §9`): the table's defaults with a few values overridden.

use super::{Parameter, Problem};

/// The named presets.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Preset {
    /// The Fig. 2 caption's stiffnesses (K̂xx = K̂xy = K̂yx = 20, K̂yy = 40) with the offset
    /// ε̂ = (0.3, −0.2) that the paper's Table 1 leaves blank: our reading, which shows the mix of
    /// periodic, quasi-periodic and chaotic responses the paper reports. These are the table's
    /// defaults.
    Paper,
    /// The text's stiffnesses (K̂xx = K̂xy = K̂yx = 2, K̂yy = 40) with ε̂ = (0, 0), as printed.
    /// Every η ≥ 1.5 of Fig. 2 ends on the non-contact synchronous orbit.
    PaperText,
    /// Coulomb friction turning a forward full rub into backward whirl while slipping: isotropic
    /// K̂ = 100, ε̂ = (0.3, −0.2), η = 1.5, μ = 0.2, ρ_R = 100 (`docs/MODEL.md §10`).
    Friction,
    /// Sustained dry whip (rolling without slip): isotropic K̂ = 300, ε̂ = (0, 0), η = 1.5,
    /// μ = 0.6, ρ_R = 2 (`docs/MODEL.md §10`).
    DryWhip,
    /// The `paper` rotor and stator support (K̂ = (20, 20, 20, 40), ε̂ = (0.3, −0.2), η = 1.5)
    /// holding a stator ring of the disk's mass (`docs/MODEL.md §17`): m̂ = 1, contact
    /// stiffness k̂_c = 100, support damping ĉ = 0.5 (damping ratios 0.090 and 0.035 of the
    /// ring's two support modes, 2.76 and 7.24 per unit τ). The rub is sustained and the ring
    /// moves with it: over forcing periods 50–100 (hybrid, 20 001 samples over 100 periods) the
    /// rotor enters contact 321 times and is in contact 46 % of the time, the ring's centre
    /// moves up to 0.58 clearances and the rotor up to 1.72. With ĉ = 1 the rub is as heavy
    /// (67 % in contact); with k̂_c = 50 and ĉ = 0.5 it dies out after the start (no contact
    /// after period 50). `tests/ring_presets.rs` checks the numbers.
    StatorMass,
    /// Dry whip of the rotor and the ring together (`docs/MODEL.md §17`): the `friction` rotor
    /// and stator (isotropic K̂ = 100, ε̂ = (0.3, −0.2), η = 1.5, ρ_R = 100) with μ = 0.5 and a
    /// ring of m̂ = 1, k̂_c = 300, ĉ = 0.5. At τ = 28.8, after a rub from the start, the rotor
    /// starts rolling on the ring without slip (one `roll` event, rolling ever after): full annular backward
    /// whirl, the ring whirling opposite the rotor. Over forcing periods 90–100 the relative
    /// position whirls at −23.68 per unit τ (15.8 times the running speed, backward) at the mean
    /// relative radius z̄ = 6.34, the rotor reaches 3.23 clearances and the ring 3.49, as over
    /// periods 40–50. Rolling fixes the product z̄ω = ρ_R η = 150 (no slip) and the coupled modes
    /// fix ω: 23.68 is the frequency of the rotor–ring out-of-phase mode (rotor and ring moving
    /// against each other) with the contact's secant stiffness k̂_c (1 − 1/z̄) at that radius. A
    /// massless ring on the same springs (their series stiffness, below K̂ = 100) cannot whirl
    /// faster than √101 = 10.05 (8.52 at z̄ = 6.34). From the same start μ = 0.4 or ĉ = 1 gives no
    /// whip (the synchronous orbit with light rub); k̂_c = 1000 the same whip at −39.12, z̄ = 3.83.
    RingWhirl,
}

impl Preset {
    /// Every preset, in the order `presets` lists them.
    pub const ALL: [Preset; 6] = [
        Preset::Paper,
        Preset::PaperText,
        Preset::Friction,
        Preset::DryWhip,
        Preset::StatorMass,
        Preset::RingWhirl,
    ];

    /// The presets of the planar model (`stator_mass_ratio` = 0): what the planar driver, the
    /// stepper, the C ABI and the FMU run.
    pub const PLANAR: [Preset; 4] = [
        Preset::Paper,
        Preset::PaperText,
        Preset::Friction,
        Preset::DryWhip,
    ];

    /// The presets with a stator ring of mass (`stator_mass_ratio` > 0): the n = 4 matrix model
    /// (`matrix::ring_model`), which the CLI's and Python's `simulate` choose for them.
    pub const RING: [Preset; 2] = [Preset::StatorMass, Preset::RingWhirl];

    /// Whether the preset states a stator ring with mass (`stator_mass_ratio` > 0), which the
    /// planar entry points refuse ([`crate::ParamError::RingNeedsMatrixModel`]).
    pub const fn has_ring_mass(self) -> bool {
        self.problem().params.stator_mass_ratio > 0.0
    }

    /// The preset's command-line name.
    pub const fn name(self) -> &'static str {
        match self {
            Preset::Paper => "paper",
            Preset::PaperText => "paper-text",
            Preset::Friction => "friction",
            Preset::DryWhip => "dry-whip",
            Preset::StatorMass => "stator-mass",
            Preset::RingWhirl => "ring-whirl",
        }
    }

    /// One line saying where the preset comes from.
    pub const fn description(self) -> &'static str {
        match self {
            Preset::Paper => {
                "Fig. 2 caption: Kxx = Kxy = Kyx = 20, Kyy = 40, offset (0.3, -0.2) (our reading of the blank Table 1 offsets)"
            }
            Preset::PaperText => {
                "paper text: Kxx = Kxy = Kyx = 2, Kyy = 40, offset (0, 0) as printed"
            }
            Preset::Friction => {
                "backward whirl from friction: isotropic K = 100, offset (0.3, -0.2), mu = 0.2, R/clearance = 100"
            }
            Preset::DryWhip => {
                "sustained dry whip (rolling): isotropic K = 300, offset (0, 0), mu = 0.6, R/clearance = 2"
            }
            Preset::StatorMass => {
                "paper rotor and stator with a ring of mass: mass ratio 1, contact stiffness 100, ring damping 0.5 (sustained rub, the ring moving up to 0.6 clearances)"
            }
            Preset::RingWhirl => {
                "dry whip of rotor and ring: friction preset with mu = 0.5 and a ring of mass ratio 1, contact stiffness 300, damping 0.5 (rolling, backward whirl at -15.8 times the running speed at the coupled mode)"
            }
        }
    }

    /// The values that differ from the table's defaults.
    pub const fn overrides(self) -> &'static [(Parameter, f64)] {
        match self {
            Preset::Paper => &[],
            Preset::PaperText => &[
                (Parameter::KXx, 2.0),
                (Parameter::KXy, 2.0),
                (Parameter::KYx, 2.0),
                (Parameter::OffsetX, 0.0),
                (Parameter::OffsetY, 0.0),
            ],
            Preset::Friction => &[
                (Parameter::KXx, 100.0),
                (Parameter::KXy, 0.0),
                (Parameter::KYx, 0.0),
                (Parameter::KYy, 100.0),
                (Parameter::FrictionCoefficient, 0.2),
            ],
            Preset::DryWhip => &[
                (Parameter::KXx, 300.0),
                (Parameter::KXy, 0.0),
                (Parameter::KYx, 0.0),
                (Parameter::KYy, 300.0),
                (Parameter::OffsetX, 0.0),
                (Parameter::OffsetY, 0.0),
                (Parameter::FrictionCoefficient, 0.6),
                (Parameter::RadiusRatio, 2.0),
            ],
            Preset::StatorMass => &[
                (Parameter::StatorMassRatio, 1.0),
                (Parameter::ContactStiffness, 100.0),
                (Parameter::StatorDamping, 0.5),
            ],
            Preset::RingWhirl => &[
                (Parameter::KXx, 100.0),
                (Parameter::KXy, 0.0),
                (Parameter::KYx, 0.0),
                (Parameter::KYy, 100.0),
                (Parameter::FrictionCoefficient, 0.5),
                (Parameter::StatorMassRatio, 1.0),
                (Parameter::ContactStiffness, 300.0),
                (Parameter::StatorDamping, 0.5),
            ],
        }
    }

    /// The preset with the given name, if any.
    pub fn from_name(name: &str) -> Option<Preset> {
        Preset::ALL.into_iter().find(|p| p.name() == name)
    }

    /// The preset's problem: the table's defaults (η = 1.5, start (0.1, 0.1, 0, 0) at τ0 = 0)
    /// with [`Preset::overrides`] applied.
    pub const fn problem(self) -> Problem {
        let mut problem = Problem::DEFAULT;
        let mut rest = self.overrides();
        while let [(parameter, value), tail @ ..] = rest {
            parameter.set(&mut problem, *value);
            rest = tail;
        }
        problem
    }
}
