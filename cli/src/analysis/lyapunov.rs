//! The largest Lyapunov exponent by the two-nearby-trajectories method with renormalisation
//! (Benettin et al. 1976), using the propagator for both trajectories.

use rotor_rub::{Options, Problem, Propagate, PropagationError, Propagator, State, advance_to};

/// Initial and renormalised separation of the two trajectories (max norm over the state, in
/// clearances): far above the methods' default tolerances, far below the attractor's size.
pub const SEPARATION: f64 = 1e-6;
/// Renormalisation intervals skipped before averaging, so the separation turns into the most
/// unstable direction first.
pub const SKIPPED_INTERVALS: usize = 5;

fn norm(s: &[f64; 4]) -> f64 {
    s.iter().map(|v| v.abs()).fold(0.0, f64::max)
}

/// The largest Lyapunov exponent (per unit τ) over `intervals` renormalisation intervals of
/// length `interval`, starting from `problem`'s initial state and start time (put the start after
/// a transient). The perturbed trajectory restarts from the renormalised state at the end of
/// every interval; the reference trajectory runs on uninterrupted. Both continue states a run
/// reached (`Propagator::resume`: the parameters and options are validated, the state is not
/// held to the table's start ranges): a section state of a runaway dry whip moves faster than
/// the 100 clearances per unit τ a start may have (issue 32).
pub fn largest_exponent(
    problem: &Problem,
    options: &Options,
    interval: f64,
    intervals: usize,
) -> Result<f64, PropagationError> {
    largest_exponent_checked(problem, options, interval, intervals, |_| Ok(()))
}

/// [`largest_exponent`], calling `check` with the time before each interval: its error ends the
/// estimate (a caller's interrupt, [`crate::watch`]).
pub fn largest_exponent_checked<E: From<PropagationError>>(
    problem: &Problem,
    options: &Options,
    interval: f64,
    intervals: usize,
    mut check: impl FnMut(f64) -> Result<(), E>,
) -> Result<f64, E> {
    let mut reference = Propagator::resume(problem, options)?;
    let mut direction = [1.0, 1.0, 1.0, 1.0];
    let mut t = problem.start_time;
    let mut sum = 0.0;
    let mut averaged = 0;
    for k in 0..SKIPPED_INTERVALS.saturating_add(intervals) {
        check(t)?;
        let base = reference.state().to_array();
        let perturbed_start = State::from_array(core::array::from_fn(|i| {
            base[i] + SEPARATION * direction[i]
        }));
        let mut perturbed = Propagator::resume(
            &Problem {
                initial: perturbed_start,
                start_time: t,
                ..*problem
            },
            options,
        )?;
        t += interval;
        let a = advance_to(&mut reference, t, |_| {})?.state.to_array();
        let b = advance_to(&mut perturbed, t, |_| {})?.state.to_array();
        let delta: [f64; 4] = core::array::from_fn(|i| b[i] - a[i]);
        let d = norm(&delta);
        if d == 0.0 || !d.is_finite() {
            // Collapsed onto the same trajectory (strong contraction): restart the direction.
            direction = [1.0, 1.0, 1.0, 1.0];
            if k >= SKIPPED_INTERVALS {
                sum += (f64::MIN_POSITIVE / SEPARATION).ln();
                averaged += 1;
            }
            continue;
        }
        direction = core::array::from_fn(|i| delta[i] / d);
        if k >= SKIPPED_INTERVALS {
            sum += (d / SEPARATION).ln();
            averaged += 1;
        }
    }
    Ok(if averaged == 0 {
        0.0
    } else {
        sum / (averaged as f64 * interval)
    })
}
