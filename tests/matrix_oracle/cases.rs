//! The stator-ring cases of issue 28 item 5: each a problem of the parameter table (the
//! paper's rotor, ν = 0.125, with a ring of mass) and what it covers. Event counts are over
//! [`PERIODS`] forcing periods (DOP853 at tol 1e-13; the oracle agrees).

use rotor_rub::{Parameter, Preset, Problem};

/// Forcing periods each case runs.
pub const PERIODS: f64 = 10.0;

/// One case.
pub struct Case {
    /// Its name in messages.
    pub name: &'static str,
    /// What it covers.
    pub covers: &'static str,
    /// The parameters set on the `paper` preset.
    pub set: &'static [(Parameter, f64)],
    /// How many events the comparisons cover (all of them unless the motion amplifies
    /// differences: then up to where it does, said in `covers`).
    pub compared: usize,
}

impl Case {
    /// The case's problem.
    pub fn problem(&self) -> Problem {
        let mut problem = Preset::Paper.problem();
        for &(p, v) in self.set {
            p.set(&mut problem, v);
        }
        problem
    }
}

use Parameter::{
    ContactStiffness, FrictionCoefficient, KXx, KXy, KYx, KYy, OffsetX, OffsetY, RadiusRatio,
    SpeedRatio, StatorDamping, StatorMassRatio, X0, Y0,
};

/// The ring of the frictionless cases: m̂ = 1, k̂_c = 100, ĉ = 0.5.
const RING: [(Parameter, f64); 3] = [
    (StatorMassRatio, 1.0),
    (ContactStiffness, 100.0),
    (StatorDamping, 0.5),
];

/// Every case.
pub const CASES: &[Case] = &[
    Case {
        name: "sparse",
        covers: "frictionless sparse rub: ε̂ = 0, 6 switches in 10 periods, the ring barely moves (0.02)",
        set: &[(OffsetX, 0.0), (OffsetY, 0.0), RING[0], RING[1], RING[2]],
        compared: usize::MAX,
    },
    Case {
        name: "heavy",
        covers: "frictionless heavy rub: the paper's ε̂, 107 switches in 10 periods, the ring moves 0.62",
        set: &[RING[0], RING[1], RING[2]],
        compared: usize::MAX,
    },
    Case {
        name: "non-symmetric",
        covers: "non-symmetric support K_s = (20, 10, 30, 40), m̂ = 0.5, k̂_c = 200: 114 switches",
        set: &[
            (KXy, 10.0),
            (KYx, 30.0),
            (StatorMassRatio, 0.5),
            (ContactStiffness, 200.0),
            (StatorDamping, 0.3),
        ],
        compared: usize::MAX,
    },
    Case {
        name: "undamped ring",
        covers: "ĉ = 0: the ring rings down for ever between contacts and re-contacts (99 switches, ring amplitude 0.85)",
        set: &[RING[0], RING[1], (StatorDamping, 0.0)],
        compared: usize::MAX,
    },
    Case {
        name: "start inside",
        covers: "a start inside contact (x0 = 1.4, z0 = 1.10): the first switch is an exit",
        set: &[(X0, 1.4), (Y0, -0.3), RING[0], RING[1], RING[2]],
        compared: usize::MAX,
    },
    Case {
        name: "reversal",
        covers: "friction with reversal and rolling: K_s = 100 I, μ = 0.6, ρ_R = 1, m̂ = 0.2, k̂_c = 300: 8 reverse, 55 roll, 54 slip",
        set: &[
            (KXx, 100.0),
            (KXy, 0.0),
            (KYx, 0.0),
            (KYy, 100.0),
            (FrictionCoefficient, 0.6),
            (RadiusRatio, 1.0),
            (StatorMassRatio, 0.2),
            (ContactStiffness, 300.0),
            (StatorDamping, 0.5),
        ],
        compared: usize::MAX,
    },
    Case {
        name: "rolling ring",
        covers: "friction with rolling while the ring moves (ring amplitude 1.0): η = 2.5, μ = 0.4, ρ_R = 2, m̂ = 3, k̂_c = 300; a near-graze at τ ≈ 22 (event 84) amplifies differences 1e3-fold, so the first 80 events",
        set: &[
            (SpeedRatio, 2.5),
            (FrictionCoefficient, 0.4),
            (RadiusRatio, 2.0),
            (StatorMassRatio, 3.0),
            (ContactStiffness, 300.0),
            (StatorDamping, 1.0),
        ],
        compared: 80,
    },
];
