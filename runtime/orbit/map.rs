//! The stroboscopic map P^k (`docs/MODEL.md` §18): a state on the section τ = 0 (mod the forcing
//! period T = 2π/η) carried over k forcing periods by a propagation method, with its monodromy
//! matrix ∂P^k/∂s assembled from the segments the propagation found: the product, in time order,
//! of each segment's transition matrix ([`super::segments`]) and, at each switch, its saltation
//! matrix ([`super::saltation`]).

use super::extrema::{Extremum, Summary};
use super::matrix::{self, IDENTITY, Mat4};
use super::saltation::saltation;
use super::segments::{self, Context};
use super::{MAX_PERIOD, OrbitError};
use crate::analytic::free::FreeConstants;
use crate::coefficients::ModelParams;
use crate::field::{self, Field};
use crate::method::{Method, Options, Propagator};
use crate::params::{Params, Problem, State};
use crate::propagate::{Event, Propagate, Regime};

/// How the map is evaluated.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MapSettings {
    /// The propagation method and its tolerance for the trajectory (the states and the switches).
    pub options: Options,
    /// DOP853's tolerance (rtol = atol) for the variational equations in contact.
    pub variational_tol: f64,
    /// Whether to compute the monodromy matrix.
    pub jacobian: bool,
    /// Whether to look for the extrema of z and |q| along the orbit.
    pub extrema: bool,
}

/// The trajectory's default method: hybrid (exact free flight, DOP853 in contact).
pub const DEFAULT_METHOD: Method = Method::Hybrid;
/// The trajectory's default tolerance: the propagation's error stays ~100× below the shooting's
/// default residual ([`super::DEFAULT_TOLERANCE`]).
pub const DEFAULT_TRAJECTORY_TOL: f64 = 1e-12;
/// The variational equations' default tolerance: the monodromy to ~1e-9, enough for Newton's
/// quadratic convergence down to rounding and the multipliers to better than 1e-7.
pub const DEFAULT_VARIATIONAL_TOL: f64 = 1e-11;

impl Default for MapSettings {
    fn default() -> Self {
        MapSettings {
            options: Options {
                tol: Some(DEFAULT_TRAJECTORY_TOL),
                ..Options::with_method(DEFAULT_METHOD)
            },
            variational_tol: DEFAULT_VARIATIONAL_TOL,
            jacobian: true,
            extrema: false,
        }
    }
}

/// What the map did to a state.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MapPoint {
    /// P^k(s).
    pub state: State,
    /// ∂P^k/∂s (the identity when not computed).
    pub monodromy: Mat4,
    /// The states on the section after 1, 2, …, k periods (the first `periods` entries; the
    /// last is [`Self::state`]).
    pub sections: [State; MAX_PERIOD],
    /// k.
    pub periods: u32,
    /// What the orbit did over the k periods.
    pub summary: Summary,
}

impl MapPoint {
    /// The section states after 1 … k periods.
    pub fn sections(&self) -> &[State] {
        self.sections
            .get(..self.periods as usize)
            .unwrap_or(&self.sections)
    }
}

/// What a caller may watch while the map runs.
pub trait MapObserver {
    /// A local extremum of z (only with [`MapSettings::extrema`]).
    fn extremum(&mut self, _extremum: &Extremum) {}
    /// A switch.
    fn event(&mut self, _event: &Event) {}
}

impl MapObserver for () {}

/// The field of a segment in `regime` with slip direction `slip`.
fn field_of(regime: Regime, slip: f64) -> Field {
    Field::of(regime, slip)
}

/// P^k(`start`) for `params` from the section τ = 0 (k = `periods` forcing periods), with its
/// monodromy matrix and extrema as `settings` ask (see the module documentation).
///
/// # Errors
/// [`OrbitError::InvalidPeriod`] for k outside 1 ..= [`MAX_PERIOD`]; what the propagation
/// reports (invalid parameters or options, divergence, …); [`OrbitError::Tangential`] at a
/// switch of friction tangential to its field.
pub fn stroboscopic_map(
    params: &Params,
    start: State,
    periods: u32,
    settings: &MapSettings,
    observer: &mut impl MapObserver,
) -> Result<MapPoint, OrbitError> {
    if periods == 0 || periods as usize > MAX_PERIOD {
        return Err(OrbitError::InvalidPeriod { periods });
    }
    let problem = Problem {
        params: *params,
        initial: start,
        start_time: 0.0,
    };
    let mut propagator = Propagator::resume(&problem, &settings.options)?;
    let model = ModelParams::of(params);
    let free = FreeConstants::new(params);
    let ctx = Context {
        params,
        model: &model,
        free: &free,
        tol: settings.variational_tol,
        jacobian: settings.jacobian,
        extrema: settings.extrema,
    };
    let period = params.forcing_period();
    let mut summary = Summary::default();
    let mut sections = [start; MAX_PERIOD];
    let mut monodromy = IDENTITY;
    let (mut t, mut state) = (0.0, start);
    let mut regime = propagator.regime();
    let mut slip = match regime {
        Regime::Contact => field::slip_direction(params, t, &state, None),
        Regime::Free | Regime::Rolling => 0.0,
    };
    for (j, section) in (1..=periods).zip(sections.iter_mut()) {
        let target = f64::from(j) * period;
        loop {
            let next = propagator.advance(target)?;
            let (t1, s1) = match next {
                Some(e) => (e.time, e.state),
                None => (target, propagator.state()),
            };
            let field = field_of(regime, slip);
            let phi = match regime {
                Regime::Free => {
                    let mut found = |e: &Extremum| observer.extremum(e);
                    segments::free(&ctx, t, state, t1, &mut summary, &mut found)
                }
                Regime::Contact | Regime::Rolling => {
                    summary.contact_time += t1 - t;
                    let mut found = |e: &Extremum| observer.extremum(e);
                    segments::contact(
                        &ctx,
                        field,
                        regime,
                        (t, state, t1),
                        &mut summary,
                        &mut found,
                    )?
                }
            };
            if settings.jacobian {
                monodromy = matrix::mul(&phi, &monodromy);
            }
            (t, state) = (t1, s1);
            let Some(event) = next else { break };
            let after_regime = event.kind.regime_after();
            let after_slip = match after_regime {
                Regime::Contact => {
                    field::slip_direction(params, event.time, &event.state, Some(event.kind))
                }
                Regime::Free | Regime::Rolling => 0.0,
            };
            if settings.jacobian {
                let s = saltation(&model, &event, field, field_of(after_regime, after_slip))
                    .map_err(|e| OrbitError::Tangential {
                        time: e.time,
                        kind: e.kind,
                    })?;
                monodromy = matrix::mul(&s, &monodromy);
            }
            summary.switch(event.kind);
            observer.event(&event);
            (regime, slip) = (after_regime, after_slip);
        }
        *section = state;
    }
    summary.duration = t;
    summary.point(&model, &state);
    Ok(MapPoint {
        state,
        monodromy,
        sections,
        periods,
        summary,
    })
}
