//! One segment of an orbit between two switches (or a switch and a section time): its
//! state-transition matrix and what it does on the way ([`super::extrema`]).
//!
//! - Free flight: the closed form's transition matrix Φ(s) = ∂s(τ0 + s)/∂s(τ0), the generated
//!   `free_step_transition` at the basis EC(s), ES(s) (`docs/MODEL.md` §4; the forcing and the
//!   input force add to the state, not to its derivative), and the closed form sampled for the
//!   extrema.
//! - Contact (frictionless, slipping, rolling): the variational equations with the state, by
//!   DOP853 ([`super::variational`]), from the switch state the propagation found to the time it
//!   found the segment's end; the extrema on the dense output of each step.

use super::extrema::{Extremum, Probe, Summary, scan};
use super::matrix::{IDENTITY, Mat4};
use super::variational::{AUGMENTED, Augmented, pack, unpack};
use crate::analytic::basis::free_basis;
use crate::analytic::free::{FreeConstants, FreeSegment};
use crate::analytic::segment::Segment;
use crate::coefficients::{self as coef, FreeBasis, FreeDampedFrequency, ModelParams};
use crate::field::{self, Field};
use crate::params::{Params, State};
use crate::propagate::{PropagationError, Regime};
use crate::reference::{Dop853, Integrator, Interpolant, Tolerance};

/// Samples of a free segment per unit time, at least (more at high speed: z² varies at up to
/// twice the forcing frequency).
const FREE_SAMPLES_PER_TIME: f64 = 16.0;
/// Probes per DOP853 step of a contact segment (both ends included).
const STEP_PROBES: usize = 5;
/// Most probes of one scan stretch.
const STRETCH: usize = 64;

/// What a segment needs to know about the run it belongs to.
pub(super) struct Context<'a> {
    pub params: &'a Params,
    pub model: &'a ModelParams,
    pub free: &'a FreeConstants,
    /// The variational equations' DOP853 tolerance (rtol = atol).
    pub tol: f64,
    /// Whether to compute the transition matrix.
    pub jacobian: bool,
    /// Whether to look for extrema (and integrate contact even without the matrix).
    pub extrema: bool,
}

/// The free segment from `(t0, s0)` to `t1`: its transition matrix (identity when not wanted),
/// its extrema passed to `found` and its samples to `summary`.
pub(super) fn free(
    ctx: &Context<'_>,
    t0: f64,
    s0: State,
    t1: f64,
    summary: &mut Summary,
    found: &mut impl FnMut(&Extremum),
) -> Mat4 {
    let length = t1 - t0;
    if ctx.extrema && length > 0.0 {
        let segment = FreeSegment::new(ctx.params, ctx.free, t0, s0);
        let eval = |t: f64| {
            let state = segment.point(t - t0).state;
            let phasor = field::phasor(ctx.model, t);
            let a = field::acceleration(ctx.model, Field::Free, &phasor, &state);
            Probe::new(ctx.model, t, state, a)
        };
        let per_time = FREE_SAMPLES_PER_TIME.max(8.0 * ctx.model.speed_ratio);
        let n = libm::ceil(length * per_time).clamp(2.0, 1.0e6) as usize;
        // Stretches of at most STRETCH probes, each sharing its first probe with the last of
        // the one before.
        let mut probes = [eval(t0); STRETCH];
        let mut len = 1;
        for k in 1..=n {
            let t = if k == n {
                t1
            } else {
                t0 + length * (k as f64 / n as f64)
            };
            if let Some(slot) = probes.get_mut(len) {
                *slot = eval(t);
                len += 1;
            }
            if len == STRETCH || k == n {
                let stretch = probes.get(..len).unwrap_or(&[]);
                scan(ctx.model, Regime::Free, stretch, eval, summary, &mut *found);
                let last = stretch.last().copied().unwrap_or(probes[0]);
                probes[0] = last;
                len = 1;
            }
        }
    }
    if !ctx.jacobian || length <= 0.0 {
        return IDENTITY;
    }
    let beta_sq = ctx.free.beta_sq();
    let (ec, es) = free_basis(ctx.model.damping_ratio, beta_sq, length);
    let p = coef::free_step_transition(
        ctx.model,
        &FreeDampedFrequency { beta_sq },
        &FreeBasis { ec, es },
    );
    [
        [p.p00, p.p01, p.p02, p.p03],
        [p.p10, p.p11, p.p12, p.p13],
        [p.p20, p.p21, p.p22, p.p23],
        [p.p30, p.p31, p.p32, p.p33],
    ]
}

/// The contact segment in `field` from `(t0, s0)` to `t1` (`span`; `regime`: contact or rolling): its
/// transition matrix by the variational equations (identity when not wanted), extrema and
/// samples as for [`free`].
///
/// # Errors
/// What DOP853 reports (a step size underflow where the tolerance cannot be met).
pub(super) fn contact(
    ctx: &Context<'_>,
    field: Field,
    regime: Regime,
    (t0, s0, t1): (f64, State, f64),
    summary: &mut Summary,
    found: &mut impl FnMut(&Extremum),
) -> Result<Mat4, PropagationError> {
    if !(ctx.jacobian || ctx.extrema) || t1 <= t0 {
        return Ok(IDENTITY);
    }
    let system = Augmented {
        model: ctx.model,
        field,
    };
    let mut integrator = Integrator::<Dop853, AUGMENTED>::new(
        &system,
        t0,
        pack(&s0, &IDENTITY),
        Tolerance::uniform(ctx.tol),
        f64::INFINITY,
    );
    let probe = |t: f64, y: &[f64; AUGMENTED]| {
        let (state, _) = unpack(y);
        Probe::new(ctx.model, t, state, system.acceleration(t, &state))
    };
    loop {
        let step = integrator.step(&system, t1)?;
        if ctx.extrema {
            let mut probes = [probe(step.t0, &step.y0); STEP_PROBES];
            let span = step.t1 - step.t0;
            for (k, slot) in probes.iter_mut().enumerate().skip(1) {
                let t = if k + 1 == STEP_PROBES {
                    step.t1
                } else {
                    step.t0 + span * (k as f64 / (STEP_PROBES - 1) as f64)
                };
                let y = if k + 1 == STEP_PROBES {
                    step.y1
                } else {
                    step.dense.eval(t)
                };
                *slot = probe(t, &y);
            }
            let eval = |t: f64| probe(t, &step.dense.eval(t));
            scan(ctx.model, regime, &probes, eval, summary, &mut *found);
        }
        if step.t1 >= t1 {
            let (_, phi) = unpack(&step.y1);
            return Ok(if ctx.jacobian { phi } else { IDENTITY });
        }
    }
}
