//! Contact schemes of the paper's family (`docs/MODEL.md` §8): the contact field is re-linearized at
//! every sub-step start and the linearized system is solved in closed form.
//!
//! * exprb2: the paper's closed-form step repeated from each sub-step start (exponential
//!   Rosenbrock–Euler, order 2). Its continuous extension is the linearized closed form itself.
//! * exprb43 (Hochbruck–Ostermann–Schweitzer): stages U2 = e^{hA/2}w, U3 = e^{hA}w + hφ1 D2, and
//!   w1 = e^{hA}w + h[(16φ3 − 48φ4)D2 + (12φ4 − 2φ3)D3] with D_k the Taylor remainder at U_k; the
//!   embedded third-order solution drops the φ4 terms. Every φ-term is the exact response to a
//!   polynomial forcing, so each stage is a [`LinearSegment`] with a cubic forcing
//!   (`polynomial_particular`, derived by the generator), and w1's segment evaluated at 0 < s < h
//!   is the scheme's continuous extension used for exit location and sampling.

use super::linear::{ContactConstants, LinearSegment, Linearization, Part, Singular};
use crate::math;
use crate::params::{Params, State};

/// One contact sub-step: the continuous extension on [0, h] and its end state.
#[derive(Clone, Copy, Debug)]
pub struct SubStep {
    /// The closed-form continuous extension.
    pub segment: LinearSegment,
    /// The step length.
    pub length: f64,
    /// The state at s = h.
    pub end: State,
    /// Error estimate in units of the tolerance (exprb43; 0 for exprb2).
    pub error: f64,
}

/// n(q) = Kl q + Fd − q − (contact force): the nonlinear contact force minus its
/// linearization, as a forcing on the acceleration (zero at the linearization point;
/// generated from the model, with friction when the linearization slips).
fn remainder(lin: &Linearization, s: &State) -> (f64, f64) {
    lin.remainder(s)
}

impl SubStep {
    /// A sub-step with every coefficient zero: a slot for [`exprb2_with`] and [`exprb43_with`].
    pub fn zeroed() -> SubStep {
        SubStep {
            segment: LinearSegment::zeroed(),
            length: 0.0,
            end: State::default(),
            error: 0.0,
        }
    }
}

/// exprb2: the linearized closed form from `state` at time `t` over `h`.
pub fn exprb2(params: &Params, t: f64, state: State, h: f64) -> Result<SubStep, Singular> {
    let mut out = SubStep::zeroed();
    exprb2_with(&ContactConstants::new(params), 0.0, t, state, h, &mut out)?;
    Ok(out)
}

/// A sub-step's start, shared by both schemes: the linearization at `state` written in place
/// into the output slot's segment, and the slot's part to build the scheme's segment in;
/// [`Singular`] when the linearization cannot take a step of `h`.
#[inline(always)]
fn linearize<'a>(
    constants: &ContactConstants,
    slip: f64,
    t: f64,
    state: State,
    h: f64,
    segment: &'a mut LinearSegment,
) -> Result<(&'a Linearization, &'a mut Part), Singular> {
    let (lin, part) = segment.split_mut();
    Linearization::slipping_with(constants, slip, t, state.x, state.y, lin)?;
    let lin = &*lin;
    if !lin.supports(h) {
        return Err(Singular);
    }
    Ok((lin, part))
}

/// [`exprb2`] written into `out` (no copy of the large segment) with the parameter set's
/// [`ContactConstants`], slipping in direction `slip` under friction (0: frictionless); `out` is
/// unspecified on error.
pub fn exprb2_with(
    constants: &ContactConstants,
    slip: f64,
    t: f64,
    state: State,
    h: f64,
    out: &mut SubStep,
) -> Result<(), Singular> {
    let (lin, part) = linearize(constants, slip, t, state, h, &mut out.segment)?;
    lin.fill(state, [0.0; 8], h, || lin.cubic_terms(h), part);
    out.end = lin.state_of(part, h, &lin.scalars(h));
    out.length = h;
    out.error = 0.0;
    Ok(())
}

/// exprb43 from `state` at time `t` over `h`, with the embedded error in units of `tol`
/// (max norm, each component scaled by tol·(1 + |w|)).
pub fn exprb43(
    params: &Params,
    t: f64,
    state: State,
    h: f64,
    tol: f64,
) -> Result<SubStep, Singular> {
    let mut out = SubStep::zeroed();
    exprb43_with(
        &ContactConstants::new(params),
        0.0,
        t,
        state,
        h,
        tol,
        &mut out,
    )?;
    Ok(out)
}

/// [`exprb43`] written into `out` (no copy of the large segment) with the parameter set's
/// [`ContactConstants`], slipping in direction `slip` under friction (0: frictionless); `out` is
/// unspecified on error. The linearization is written
/// in place into the output slot and the stages are parts evaluated with it (no copy of it).
pub fn exprb43_with(
    constants: &ContactConstants,
    slip: f64,
    t: f64,
    state: State,
    h: f64,
    tol: f64,
    out: &mut SubStep,
) -> Result<(), Singular> {
    let (lin, part) = linearize(constants, slip, t, state, h, &mut out.segment)?;
    // The unforced segment's part (the slot's part receives the scheme's own segment).
    let mut free = Part::empty();
    lin.fill(state, [0.0; 8], h, || lin.cubic_terms(h), &mut free);
    let u2 = lin.state_of(&free, 0.5 * h, &lin.scalars(0.5 * h));
    let (n2x, n2y) = remainder(lin, &u2);
    let at_h = lin.scalars(h);
    // The unforced segment at h: the stages share its homogeneous and harmonic parts whenever
    // their response to the extra forcing is a series (short steps), so only that response is
    // evaluated for them (bit for bit what evaluating each stage's own segment gives).
    let unforced = lin.state_of(&free, h, &at_h);
    // The series length of the stages' cubic responses, computed once.
    let terms = lin.cubic_terms(h);
    let stage_state = |forcing: [f64; 8]| {
        lin.forced_state_with(&unforced, &forcing, terms, h)
            .unwrap_or_else(|| {
                let mut stage = Part::empty();
                lin.fill(state, forcing, h, || lin.cubic_terms(h), &mut stage);
                lin.state_of(&stage, h, &at_h)
            })
    };
    let u3 = stage_state([n2x, n2y, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]);
    let (n3x, n3y) = remainder(lin, &u3);
    let (h2, h3) = (h * h, h * h * h);
    let a2 = ((8.0 * n2x - n3x) / h2, (8.0 * n2y - n3y) / h2);
    let a3 = ((-8.0 * n2x + 2.0 * n3x) / h3, (-8.0 * n2y + 2.0 * n3y) / h3);
    let embedded = stage_state([0.0, 0.0, 0.0, 0.0, a2.0, a2.1, 0.0, 0.0]);
    let forcing = [0.0, 0.0, 0.0, 0.0, a2.0, a2.1, a3.0, a3.1];
    lin.fill(state, forcing, h, || terms, part);
    let part = &*part;
    let end = lin
        .state_from_unforced(part, h, &unforced)
        .unwrap_or_else(|| lin.state_of(part, h, &at_h));
    let (e, y0, y1) = (embedded.to_array(), state.to_array(), end.to_array());
    let mut error: f64 = 0.0;
    for ((a, b), c) in y0.iter().zip(&y1).zip(&e) {
        let scale = tol * (1.0 + math::abs(*a).max(math::abs(*b)));
        error = error.max(math::abs(b - c) / scale);
    }
    if !error.is_finite() {
        error = f64::INFINITY;
    }
    out.length = h;
    out.end = end;
    out.error = error;
    Ok(())
}
