//! proptest strategies for physically valid problems (feature `proptest`), so a user can fuzz a
//! rub detector or controller against this plant model. Our own property tests use them.
//!
//! Domains (all dimensionless):
//! * [`params`]: η ∈ [0.3, 4], ν ∈ [0.05, 1.5], η_m ∈ [0.002, 0.01], ρ̂ ∈ [20, 100],
//!   φ0 ∈ [0, 2π), K̂xx, K̂yy ∈ [0, 50], K̂xy, K̂yx ∈ [−20, 30] independently (non-symmetric and
//!   indefinite K_s included), ε̂ ∈ [−0.5, 0.5]².
//! * [`initial_state`]: position within radius 2 of the origin, velocity components in [−2, 2].
//! * [`degenerate_problem`]: the corners of `docs/MODEL.md` §6 — ν = 1 exactly (critical free flight
//!   and critical contact entries), ν > 1, Kxy ≠ Kyx with Fb1·Fb2 < 0 (complex modes),
//!   Kxx = Kxy (Fb1 = 0 at entry angles 3π/4, −π/4), isotropic K_s (repeated modes), starts
//!   exactly on z = 1.

use proptest::prelude::*;

use crate::params::{Params, Problem, State};

/// Physically valid parameter sets (see the module docs for the domain).
pub fn params() -> impl Strategy<Value = Params> {
    (
        (
            0.3f64..4.0,
            0.05f64..1.5,
            0.002f64..0.01,
            20.0f64..100.0,
            0.0f64..core::f64::consts::TAU,
        ),
        (0.0f64..50.0, -20.0f64..30.0, -20.0f64..30.0, 0.0f64..50.0),
        (-0.5f64..0.5, -0.5f64..0.5),
    )
        .prop_map(
            |((eta, nu, m, rho, phase), (kxx, kxy, kyx, kyy), (ex, ey))| Params {
                speed_ratio: eta,
                damping_ratio: nu,
                mass_ratio: m,
                eccentricity_ratio: rho,
                phase,
                k_xx: kxx,
                k_xy: kxy,
                k_yx: kyx,
                k_yy: kyy,
                offset_x: ex,
                offset_y: ey,
                ..Params::DEFAULT
            },
        )
}

/// Initial states: position within radius 2, velocities in [−2, 2].
pub fn initial_state() -> impl Strategy<Value = State> {
    (
        0.0f64..2.0,
        0.0f64..core::f64::consts::TAU,
        -2.0f64..2.0,
        -2.0f64..2.0,
    )
        .prop_map(|(r, a, vx, vy)| State::new(r * libm::cos(a), r * libm::sin(a), vx, vy))
}

/// Problems from [`params`] and [`initial_state`] at τ0 = 0.
pub fn problem() -> impl Strategy<Value = Problem> {
    (params(), initial_state()).prop_map(|(params, initial)| Problem {
        params,
        initial,
        start_time: 0.0,
    })
}

/// Problems in the degenerate corners of `docs/MODEL.md` §6 (see the module docs).
pub fn degenerate_problem() -> impl Strategy<Value = Problem> {
    (
        problem(),
        0usize..6,
        0.0f64..core::f64::consts::TAU,
        -1.0f64..1.0,
    )
        .prop_map(|(mut p, corner, angle, radial)| {
            let q = &mut p.params;
            match corner {
                0 => q.damping_ratio = 1.0,
                1 => q.damping_ratio = 1.0 + q.damping_ratio / 3.0,
                2 => {
                    q.k_xy = 15.0;
                    q.k_yx = -10.0;
                }
                3 => {
                    q.k_xx = 20.0;
                    q.k_xy = 20.0;
                    q.k_yx = 20.0;
                    q.k_yy = 40.0;
                }
                4 => {
                    q.k_xx = 30.0;
                    q.k_yy = 30.0;
                    q.k_xy = 0.0;
                    q.k_yx = 0.0;
                }
                _ => {
                    let (s, c) = (libm::sin(angle), libm::cos(angle));
                    p.initial.x = q.offset_x + c;
                    p.initial.y = q.offset_y + s;
                    p.initial.vx = radial * c - 0.5 * s;
                    p.initial.vy = radial * s + 0.5 * c;
                }
            }
            p
        })
}
