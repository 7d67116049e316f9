//! Shooting (`docs/MODEL.md` §18): Newton's method on R(s) = P^k(s) − s,
//!
//! ```text
//! (M − I) δ = −R(s),     s ← s + δ,     M = ∂P^k/∂s (the monodromy from the segments),
//! ```
//!
//! until |R|∞ ≤ tol·(1 + |s|∞). With the exact Jacobian the residual falls quadratically
//! (each iteration squares it, up to a constant) until the trajectory's own accuracy; the
//! residual of every iteration is kept ([`Shot::residuals`]) to show it.

use super::floquet::PeriodicOrbit;
use super::map::{MapObserver, MapSettings, stroboscopic_map};
use super::matrix::{self, Mat4};
use super::{MAX_PERIOD, OrbitError};
use crate::math;
use crate::params::{Params, State, ValidRange};

/// Most Newton iterations of one shot.
pub const MAX_ITERATIONS: usize = 40;
/// The default residual tolerance, relative to 1 + |s|∞.
pub const DEFAULT_TOLERANCE: f64 = 1e-10;
/// The valid residual tolerances: above the trajectory's rounding, below a meaningful orbit.
pub const TOLERANCE_RANGE: ValidRange = ValidRange {
    min: 1e-14,
    max: 1e-3,
};

/// How a shot runs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShootingSettings {
    /// How the map and its monodromy are computed.
    pub map: MapSettings,
    /// Most Newton iterations (≤ [`MAX_ITERATIONS`]).
    pub max_iterations: u32,
    /// The residual |P^k(s) − s|∞ at which the orbit is found, relative to 1 + |s|∞.
    pub tolerance: f64,
}

impl Default for ShootingSettings {
    fn default() -> Self {
        ShootingSettings {
            map: MapSettings::default(),
            max_iterations: 30,
            tolerance: DEFAULT_TOLERANCE,
        }
    }
}

/// A shot: the orbit found and how Newton got there.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shot {
    /// The orbit.
    pub orbit: PeriodicOrbit,
    /// |P^k(s) − s|∞ at each iterate, the start first (the first `iterations` entries).
    pub residuals: [f64; MAX_ITERATIONS],
    /// The number of Newton iterates (whose residuals are recorded), the start included.
    pub iterations: usize,
    /// The number of map evaluations made (a damped step tries more than one).
    pub evaluations: usize,
}

impl Shot {
    /// The residual at each iterate, the start first.
    pub fn residuals(&self) -> &[f64] {
        self.residuals.get(..self.iterations).unwrap_or(&[])
    }
}

/// |v|∞.
fn norm(v: [f64; 4]) -> f64 {
    v.iter().fold(0.0, |acc: f64, x| acc.max(math::abs(*x)))
}

/// One Newton step for R(s) = P^k(s) − s: δ with (M − I) δ = −R.
///
/// # Errors
/// [`OrbitError::Linalg`] when M − I is singular (a multiplier at exactly 1).
pub fn newton_step(monodromy: &Mat4, residual: [f64; 4]) -> Result<[f64; 4], OrbitError> {
    let mut a = *monodromy;
    for (i, row) in a.iter_mut().enumerate() {
        if let Some(d) = row.get_mut(i) {
            *d -= 1.0;
        }
    }
    let delta = matrix::solve(&a, residual.map(|r| -r), "M - I")?;
    Ok(delta)
}

/// The period-k orbit (k = `periods`) of `params` near `guess`: Newton's method on
/// P^k(s) − s from `guess` (see the module documentation). The orbit's extrema are looked for
/// once at the end when `settings.map.extrema` asks (through `observer`).
///
/// # Errors
/// [`OrbitError::InvalidSetting`] for a tolerance or iteration count out of range;
/// [`OrbitError::NotConverged`] when the iterations run out; what the map reports.
pub fn shoot(
    params: &Params,
    guess: State,
    periods: u32,
    settings: &ShootingSettings,
) -> Result<Shot, OrbitError> {
    shoot_observed(params, guess, periods, settings, &mut ())
}

/// [`shoot`], with the converged orbit's extrema and switches passed to `observer`.
///
/// # Errors
/// As [`shoot`].
pub fn shoot_observed(
    params: &Params,
    guess: State,
    periods: u32,
    settings: &ShootingSettings,
    observer: &mut impl MapObserver,
) -> Result<Shot, OrbitError> {
    if !TOLERANCE_RANGE.contains(settings.tolerance) {
        return Err(OrbitError::InvalidSetting {
            what: "tolerance",
            value: settings.tolerance,
            valid: TOLERANCE_RANGE,
        });
    }
    let iterations = settings.max_iterations as usize;
    if !(1..=MAX_ITERATIONS).contains(&iterations) {
        return Err(OrbitError::InvalidSetting {
            what: "max_iterations",
            value: f64::from(settings.max_iterations),
            valid: ValidRange {
                min: 1.0,
                max: MAX_ITERATIONS as f64,
            },
        });
    }
    if periods == 0 || periods as usize > MAX_PERIOD {
        return Err(OrbitError::InvalidPeriod { periods });
    }
    let newton = MapSettings {
        jacobian: true,
        extrema: false,
        ..settings.map
    };
    let mut residuals = [0.0; MAX_ITERATIONS];
    let mut evaluations = 1;
    let mut s = guess.to_array();
    let mut point = stroboscopic_map(params, guess, periods, &newton, &mut ())?;
    let mut r = difference(&point.state, s);
    let mut last = norm(r);
    for (k, slot) in residuals.iter_mut().enumerate() {
        *slot = last;
        if last <= settings.tolerance * (1.0 + norm(s)) {
            let state = State::from_array(s);
            let point = if settings.map.extrema {
                let observed = MapSettings {
                    jacobian: false,
                    extrema: true,
                    ..settings.map
                };
                let extra = stroboscopic_map(params, state, periods, &observed, observer)?;
                super::map::MapPoint {
                    monodromy: point.monodromy,
                    ..extra
                }
            } else {
                point
            };
            let orbit = PeriodicOrbit::new(params, state, last, &point)?;
            return Ok(Shot {
                orbit,
                residuals,
                iterations: k + 1,
                evaluations,
            });
        }
        if k + 1 >= iterations {
            break;
        }
        let delta = newton_step(&point.monodromy, r)?;
        // The full step, or a fraction of it where the full one would raise the residual
        // (far from the orbit); near it the full step is taken and the convergence is
        // quadratic.
        let mut accepted = None;
        for fraction in DAMPING {
            let trial: [f64; 4] = core::array::from_fn(|i| {
                s.get(i).copied().unwrap_or(0.0) + fraction * delta.get(i).copied().unwrap_or(0.0)
            });
            if !trial.iter().all(|v| v.is_finite()) {
                continue;
            }
            evaluations += 1;
            let Ok(p) =
                stroboscopic_map(params, State::from_array(trial), periods, &newton, &mut ())
            else {
                continue;
            };
            let rt = difference(&p.state, trial);
            let size = norm(rt);
            if size < last || Some(&fraction) == DAMPING.last() {
                accepted = Some((trial, p, rt, size));
                break;
            }
        }
        let Some((trial, p, rt, size)) = accepted else {
            break;
        };
        (s, point, r, last) = (trial, p, rt, size);
    }
    Err(OrbitError::NotConverged {
        iterations: settings.max_iterations,
        residual: last,
    })
}

/// The fractions of the Newton step tried in turn.
const DAMPING: [f64; 5] = [1.0, 0.5, 0.25, 0.125, 0.0625];

/// P^k(s) − s.
fn difference(image: &State, s: [f64; 4]) -> [f64; 4] {
    let a = image.to_array();
    core::array::from_fn(|i| a.get(i).copied().unwrap_or(0.0) - s.get(i).copied().unwrap_or(0.0))
}
