//! The switch inside one accepted step, shared by the numerical reference and the hybrid
//! method: located on the dense output, recomputed by an explicit step of exactly the needed
//! size, and polished onto z = 1 of the step solution.

use super::events::{first_crossing, polish_switch};
use super::integrator::{AcceptedStep, Integrator};
use super::ode::OdeSystem;
use super::scheme::Scheme;
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
    Some(polish_switch(
        step.t0,
        step.t1,
        max_shift,
        (t, y),
        |t| integrator.redo(sys, step, t),
        inside,
    ))
}
