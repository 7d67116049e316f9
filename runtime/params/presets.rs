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
}

impl Preset {
    /// Every preset, in the order `presets` lists them.
    pub const ALL: [Preset; 4] = [
        Preset::Paper,
        Preset::PaperText,
        Preset::Friction,
        Preset::DryWhip,
    ];

    /// The preset's command-line name.
    pub const fn name(self) -> &'static str {
        match self {
            Preset::Paper => "paper",
            Preset::PaperText => "paper-text",
            Preset::Friction => "friction",
            Preset::DryWhip => "dry-whip",
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
