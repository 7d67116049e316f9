//! Named run-up programs: a rotor (a parameter [`Preset`]) with a speed [`Ramp`].

use super::ramp::{Ramp, RampPace};
use crate::params::Preset;

/// The named run-up programs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RunupPreset {
    /// The paper's rotor with rub (the `paper` preset: K̂ = (20, 20, 20, 40), ε̂ = (0.3, −0.2))
    /// run up from η = 0.5 to 3.5 at dη/dτ = 1e-3 after 20 periods at 0.5, and run straight
    /// back down: the run-up rides the rub branch to η ≈ 2.5 and jumps off it; the coast-down
    /// stays on the lower branch, so the two curves form a hysteresis loop over η ≈ 1.4 … 2.5.
    PaperHysteresis,
}

impl RunupPreset {
    /// Every program, in the order help texts list them.
    pub const ALL: [RunupPreset; 1] = [RunupPreset::PaperHysteresis];

    /// The program's command-line name.
    pub const fn name(self) -> &'static str {
        match self {
            RunupPreset::PaperHysteresis => "paper-hysteresis",
        }
    }

    /// One line saying what it shows.
    pub const fn description(self) -> &'static str {
        match self {
            RunupPreset::PaperHysteresis => {
                "the paper's rotor with rub (preset paper), η 0.5 -> 3.5 -> 0.5 at dη/dτ = 1e-3: the run-up jumps off the rub branch near η = 2.5, the coast-down stays below (hysteresis)"
            }
        }
    }

    /// The rotor.
    pub const fn rotor(self) -> Preset {
        match self {
            RunupPreset::PaperHysteresis => Preset::Paper,
        }
    }

    /// The speed program (starting at τ = 0).
    pub const fn ramp(self) -> Ramp {
        match self {
            RunupPreset::PaperHysteresis => Ramp {
                start_time: 0.0,
                from: 0.5,
                to: 3.5,
                pace: RampPace::Rate(1e-3),
                settle_periods: 20.0,
                dwell_periods: 0.0,
                one_way: false,
            },
        }
    }

    /// The program with the given name.
    pub fn from_name(name: &str) -> Option<RunupPreset> {
        RunupPreset::ALL.into_iter().find(|p| p.name() == name)
    }
}
