//! The switch inside one accepted step, shared by the numerical reference and the hybrid
//! method: located on the dense output, recomputed by an explicit step of exactly the needed
//! size, and polished onto z = 1 of the step solution (Newton steps along the field,
//! [`polish_switch_linear`]).

use core::cell::OnceCell;

use super::dop853::{Dop853, Dop853Dense, Dop853Step};
use super::events::{first_crossing, first_crossing_subdivided, polish_switch_linear};
use super::integrator::{AcceptedStep, Integrator};
use super::ode::OdeSystem;
use super::scheme::{Interpolant, Scheme};
use super::system::inside_measure;
use crate::params::Params;
use crate::propagate::Regime;

/// The first switch out of `regime` inside `step`, as (time, state), if any.
pub fn switch_in_step<S, F, const N: usize>(
    integrator: &mut Integrator<S, N>,
    sys: &F,
    step: &AcceptedStep<N, S::Dense>,
    params: &Params,
    regime: Regime,
) -> Option<(f64, [f64; N])>
where
    S: Scheme<N>,
    F: OdeSystem<N> + ?Sized,
{
    let inside = |y: &[f64; N]| inside_measure(params, regime, y);
    let t = first_crossing(&step.dense, &step.y0, &step.y1, inside)?;
    let t = t.max(step.t0).min(step.t1);
    let y = if t == step.t1 {
        step.y1
    } else {
        integrator.redo(sys, step, t)
    };
    // The dense output and the step solution differ by about the tolerance: put the switch on
    // z = 1 of the step solution (the trajectory the integration continues).
    let max_shift = 1e-3 * (step.t1 - step.t0);
    Some(polish_switch_linear(
        step.t0,
        step.t1,
        max_shift,
        (t, y),
        |t| integrator.redo(sys, step, t),
        |t, y| sys.rhs(t, y),
        inside,
    ))
}

/// The dense output of a [`Dop853Step`], built on first use.
struct LazyDense<'a, F: ?Sized, const N: usize> {
    sys: &'a F,
    step: &'a Dop853Step<N>,
    dense: OnceCell<Dop853Dense<N>>,
}

impl<F: OdeSystem<N> + ?Sized, const N: usize> Interpolant<N> for LazyDense<'_, F, N> {
    fn start(&self) -> f64 {
        self.step.t0
    }

    fn end(&self) -> f64 {
        self.step.t0 + self.step.h()
    }

    fn eval(&self, t: f64) -> [f64; N] {
        self.dense.get_or_init(|| self.step.dense(self.sys)).eval(t)
    }
}

/// As [`switch_in_step`] for a step taken by [`Integrator::step_deferred`], examining the step
/// in `subdivisions` sub-intervals ([`first_crossing_subdivided`]). The dense output is built
/// only when the end states show a crossing or a minimum; when it was built it is left in
/// `dense` (for sampling inside the step).
pub fn switch_in_deferred_step<F, const N: usize>(
    integrator: &mut Integrator<Dop853, N>,
    sys: &F,
    step: &Dop853Step<N>,
    params: &Params,
    regime: Regime,
    subdivisions: usize,
    dense: &mut Option<Dop853Dense<N>>,
) -> Option<(f64, [f64; N])>
where
    F: OdeSystem<N> + ?Sized,
{
    let inside = |y: &[f64; N]| inside_measure(params, regime, y);
    let lazy = LazyDense {
        sys,
        step,
        dense: OnceCell::new(),
    };
    let found = first_crossing_subdivided(subdivisions, &lazy, &step.y0, &step.y1, inside);
    if let Some(d) = lazy.dense.into_inner() {
        *dense = Some(d);
    }
    let t = found?;
    let t = t.max(step.t0).min(step.t1);
    let f0 = step.f0();
    let y = if t == step.t1 {
        step.y1
    } else {
        integrator.redo_from(sys, step.t0, &step.y0, &f0, t)
    };
    let max_shift = 1e-3 * (step.t1 - step.t0);
    Some(polish_switch_linear(
        step.t0,
        step.t1,
        max_shift,
        (t, y),
        |t| integrator.redo_from(sys, step.t0, &step.y0, &f0, t),
        |t, y| sys.rhs(t, y),
        inside,
    ))
}
