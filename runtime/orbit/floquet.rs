//! A periodic orbit and its Floquet multipliers (`docs/MODEL.md` §18): the eigenvalues of the
//! monodromy matrix of P^k at the orbit. The orbit is stable when all lie inside the unit circle.

use super::MAX_PERIOD;
use super::OrbitError;
use super::extrema::Summary;
use super::map::MapPoint;
use super::matrix::{Mat4, eigenvalues_of};
use crate::linalg::Complex;
use crate::math;
use crate::params::{Params, State};

/// A periodic orbit of the stroboscopic map: a fixed point of P^k.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PeriodicOrbit {
    /// The parameters.
    pub params: Params,
    /// The orbit's state on the section τ = 0 (mod the forcing period).
    pub state: State,
    /// k: the orbit is a fixed point of P^k (its minimal period divides k,
    /// [`Self::minimal_period`]).
    pub periods: u32,
    /// |P^k(s) − s|∞ at [`Self::state`].
    pub residual: f64,
    /// The monodromy matrix ∂P^k/∂s at the orbit.
    pub monodromy: Mat4,
    /// The Floquet multipliers (the monodromy's eigenvalues), largest modulus first.
    pub multipliers: [Complex; 4],
    /// The section states after 1 … k periods (the first `periods` entries).
    pub sections: [State; MAX_PERIOD],
    /// What the orbit does over its k periods.
    pub summary: Summary,
}

impl PeriodicOrbit {
    /// The orbit at `state` with the map's `point` there (its monodromy and sections) and the
    /// residual found.
    ///
    /// # Errors
    /// [`OrbitError::Linalg`] when the monodromy's eigenvalues cannot be computed.
    pub fn new(
        params: &Params,
        state: State,
        residual: f64,
        point: &MapPoint,
    ) -> Result<Self, OrbitError> {
        Ok(PeriodicOrbit {
            params: *params,
            state,
            periods: point.periods,
            residual,
            monodromy: point.monodromy,
            multipliers: eigenvalues_of(&point.monodromy)?,
            sections: point.sections,
            summary: point.summary,
        })
    }

    /// The largest multiplier's modulus.
    pub fn spectral_radius(&self) -> f64 {
        self.multipliers
            .iter()
            .fold(0.0, |acc: f64, m| acc.max(m.abs()))
    }

    /// Stable: every multiplier inside the unit circle.
    pub fn stable(&self) -> bool {
        self.spectral_radius() < 1.0
    }

    /// The section states after 1 … k periods.
    pub fn sections(&self) -> &[State] {
        self.sections
            .get(..self.periods as usize)
            .unwrap_or(&self.sections)
    }

    /// The smallest j dividing k with P^j(s) = s to within `tolerance` (max norm, relative to
    /// 1 + |s|∞): the orbit's own period in forcing periods (the response class period-j of a
    /// Poincaré section on it).
    pub fn minimal_period(&self, tolerance: f64) -> u32 {
        let s = self.state.to_array();
        let scale = 1.0 + s.iter().fold(0.0, |a: f64, v| a.max(math::abs(*v)));
        for (j, section) in (1..self.periods).zip(self.sections()) {
            if !self.periods.is_multiple_of(j) {
                continue;
            }
            let d = section
                .to_array()
                .iter()
                .zip(s)
                .fold(0.0, |a: f64, (p, q)| a.max(math::abs(p - q)));
            if d <= tolerance * scale {
                return j;
            }
        }
        self.periods
    }
}
