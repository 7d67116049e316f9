//! The switch inside one accepted step, shared by the numerical reference and the hybrid
//! method: located on the dense output, recomputed by an explicit step of exactly the needed
//! size, and polished onto z = 1 of the step solution (Newton steps along the field,
//! [`polish_switch`]).

use core::cell::OnceCell;

use super::dop853::{Dop853, Dop853Dense, Dop853Step};
use super::events::{first_crossing, first_crossing_subdivided, polish_switch};
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
    Some(on_step_solution(
        t,
        (step.t0, step.t1, step.y1),
        |t| integrator.redo(sys, step, t),
        |t, y| sys.rhs(t, y),
        inside,
    ))
}

/// The switch found at `t` on the dense output of the step `(t0, t1, y1)`, put on the step
/// solution: the state by an explicit step of exactly the needed size (`redo`), polished onto
/// z = 1 of the step solution — the trajectory the integration continues (dense output and step
/// differ by about the tolerance).
fn on_step_solution<const N: usize>(
    t: f64,
    (t0, t1, y1): (f64, f64, [f64; N]),
    mut redo: impl FnMut(f64) -> [f64; N],
    rhs: impl FnMut(f64, &[f64; N]) -> [f64; N],
    inside: impl Fn(&[f64; N]) -> (f64, f64),
) -> (f64, [f64; N]) {
    let t = t.max(t0).min(t1);
    let y = if t == t1 { y1 } else { redo(t) };
    let max_shift = 1e-3 * (t1 - t0);
    polish_switch(t0, t1, max_shift, (t, y), redo, rhs, inside)
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
    let f0 = step.f0();
    Some(on_step_solution(
        t,
        (step.t0, step.t1, step.y1),
        |t| integrator.redo_from(sys, step.t0, &step.y0, &f0, t),
        |t, y| sys.rhs(t, y),
        inside,
    ))
}
