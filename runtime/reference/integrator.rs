//! The adaptive driver shared by every [`Scheme`]: Hairer's initial step guess (`HINIT`), his
//! step-size controller with optional PI stabilisation, step rejection, and step-size underflow
//! detection. It owns no memory beyond fixed-size arrays.

use core::marker::PhantomData;

use super::dop853::{Dop853, Dop853Step};
use super::ode::{OdeSystem, all_finite};
use super::scheme::{Attempt, Controller, Scheme, StepStart, Tolerance};
use crate::math;
use crate::propagate::PropagationError;

/// Consecutive rejections after which a step is declared impossible
/// ([`PropagationError::StepSizeUnderflow`]); the controller shrinks h by at least 10 % per
/// rejection, so this is only reached when the right-hand side is non-finite or the tolerance
/// cannot be met.
pub const MAX_REJECTIONS: u32 = 1000;

/// Work counters of an integrator.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Stats {
    /// Right-hand-side evaluations.
    pub evaluations: u64,
    /// Accepted steps.
    pub accepted: u64,
    /// Rejected steps.
    pub rejected: u64,
}

/// One accepted step: its ends, the data needed to redo it with a shorter size, and its dense
/// output.
#[derive(Clone, Copy, Debug)]
pub struct AcceptedStep<const N: usize, D> {
    /// Start time.
    pub t0: f64,
    /// State at `t0`.
    pub y0: [f64; N],
    /// f(t0, y0).
    pub f0: [f64; N],
    /// End time `t0 + h`.
    pub t1: f64,
    /// State at `t1`.
    pub y1: [f64; N],
    /// The dense output on `[t0, t1]`.
    pub dense: D,
}

/// An adaptive explicit Runge–Kutta integrator for an `N`-state system with scheme `S`.
///
/// Steps go forward only. The integrator does not hold the system: every call takes it, so one
/// integrator can be restarted on another vector field (a regime switch) with [`Self::restart`].
#[derive(Clone, Copy, Debug)]
pub struct Integrator<S: Scheme<N>, const N: usize> {
    t: f64,
    y: [f64; N],
    f: [f64; N],
    h: f64,
    h_max: f64,
    tol: Tolerance,
    controller: Controller,
    err_old: f64,
    rejected_last: bool,
    stats: Stats,
    scheme: PhantomData<S>,
}

impl<S: Scheme<N>, const N: usize> Integrator<S, N> {
    /// Start at `(t, y)` with tolerances `tol` and largest step `h_max` (> 0; use
    /// `f64::INFINITY` for none). The first step size comes from Hairer's `HINIT`.
    pub fn new<F: OdeSystem<N> + ?Sized>(
        sys: &F,
        t: f64,
        y: [f64; N],
        tol: Tolerance,
        h_max: f64,
    ) -> Self {
        let mut me = Self::unstarted(t, y, tol, h_max);
        me.restart(sys, t, y);
        me
    }

    /// An integrator at `(t, y)` not yet started on a field: [`Self::restart`] it before the
    /// first step (a step before that fails with [`PropagationError::StepSizeUnderflow`]: its
    /// step size is 0). For a solver built ahead of the segment it will be started at, so that
    /// building it evaluates nothing.
    pub(crate) fn unstarted(t: f64, y: [f64; N], tol: Tolerance, h_max: f64) -> Self {
        Integrator {
            t,
            y,
            f: [0.0; N],
            h: 0.0,
            h_max: if h_max > 0.0 { h_max } else { f64::INFINITY },
            tol,
            controller: S::CONTROLLER,
            err_old: 1e-4,
            rejected_last: false,
            stats: Stats::default(),
            scheme: PhantomData,
        }
    }

    /// Restart at `(t, y)` on the field `sys` (for example after a regime switch): fresh first
    /// stage, fresh initial step guess, controller memory cleared. Counters are kept.
    pub fn restart<F: OdeSystem<N> + ?Sized>(&mut self, sys: &F, t: f64, y: [f64; N]) {
        self.reset(sys, t, y);
        self.h = self.initial_step(sys);
    }

    /// Move to `(t, y)` on `sys` with a fresh first stage and the controller's memory cleared;
    /// the step size is the caller's to set.
    fn reset<F: OdeSystem<N> + ?Sized>(&mut self, sys: &F, t: f64, y: [f64; N]) {
        self.t = t;
        self.y = y;
        self.f = sys.rhs(t, &y);
        self.stats.evaluations = self.stats.evaluations.saturating_add(1);
        self.err_old = 1e-4;
        self.rejected_last = false;
    }

    /// As [`Self::restart`], but with `h` (> 0, clamped to the largest step) as the first step
    /// size instead of Hairer's initial guess (one evaluation fewer): for a restart on a field
    /// whose step size is already known, as at the next contact of a periodic rub.
    pub fn restart_with_step<F: OdeSystem<N> + ?Sized>(
        &mut self,
        sys: &F,
        t: f64,
        y: [f64; N],
        h: f64,
    ) {
        if !(h > 0.0 && h.is_finite()) {
            self.restart(sys, t, y);
            return;
        }
        self.reset(sys, t, y);
        self.h = h.min(self.h_max);
    }

    /// Replace the step-size controller (the default is the scheme's
    /// [`Scheme::CONTROLLER`]; for example set `beta = 0.04` and `alpha = 1/8 − 0.2·beta` for
    /// DOP853 with PI stabilisation, as its `BETA` option does).
    #[must_use]
    pub fn with_controller(mut self, controller: Controller) -> Self {
        self.controller = controller;
        self
    }

    /// The current time.
    pub fn time(&self) -> f64 {
        self.t
    }

    /// The current state.
    pub fn state(&self) -> [f64; N] {
        self.y
    }

    /// The step size the next [`Self::step`] will try first.
    pub fn proposed_step(&self) -> f64 {
        self.h
    }

    /// The tolerances.
    pub fn tolerance(&self) -> Tolerance {
        self.tol
    }

    /// Work counters.
    pub fn stats(&self) -> Stats {
        self.stats
    }

    /// Hairer's `HINIT`: a step whose explicit Euler error is about 1 % of the tolerance, from
    /// ‖f0‖ and a finite-difference estimate of ‖f'‖, capped by `h_max`.
    fn initial_step<F: OdeSystem<N> + ?Sized>(&mut self, sys: &F) -> f64 {
        let tol = self.tol;
        let (mut dnf, mut dny) = (0.0, 0.0);
        for (y, f) in self.y.iter().zip(self.f.iter()) {
            let sk = tol.scale(*y, *y);
            dnf += (f / sk) * (f / sk);
            dny += (y / sk) * (y / sk);
        }
        let mut h = if dnf <= 1e-10 || dny <= 1e-10 {
            1e-6
        } else {
            math::sqrt(dny / dnf) * 0.01
        };
        if !(h > 0.0 && h.is_finite()) {
            h = 1e-6;
        }
        h = h.min(self.h_max);
        let mut y1 = self.y;
        for (a, f) in y1.iter_mut().zip(self.f.iter()) {
            *a += h * f;
        }
        let f1 = sys.rhs(self.t + h, &y1);
        self.stats.evaluations = self.stats.evaluations.saturating_add(1);
        let mut der2 = 0.0;
        for ((a, b), y) in f1.iter().zip(self.f.iter()).zip(self.y.iter()) {
            let d = (a - b) / tol.scale(*y, *y);
            der2 += d * d;
        }
        let der2 = math::sqrt(der2) / h;
        let der12 = der2.max(math::sqrt(dnf));
        let h1 = if der12 <= 1e-15 || !der12.is_finite() {
            (h * 1e-3).max(1e-6)
        } else {
            math::pow(0.01 / der12, 1.0 / f64::from(S::ORDER))
        };
        let h = (100.0 * h).min(h1).min(self.h_max);
        if h > 0.0 && h.is_finite() { h } else { 1e-6 }
    }

    /// One accepted step, not past `t_limit` (> the current time; `f64::INFINITY` for none).
    /// Rejected trials are retried with a smaller step.
    ///
    /// # Errors
    /// [`PropagationError::StepSizeUnderflow`] when the step falls below the resolution of the
    /// time (h ≤ 10·ε·|t|) or [`MAX_REJECTIONS`] trials in a row fail;
    /// [`PropagationError::InvalidTarget`] when `t_limit` is not after the current time.
    #[inline(always)]
    pub fn step<F: OdeSystem<N> + ?Sized>(
        &mut self,
        sys: &F,
        t_limit: f64,
    ) -> Result<AcceptedStep<N, S::Dense>, PropagationError> {
        self.accepted_trial(sys, t_limit, |me, h, t1, trial| {
            let from = StepStart {
                t: me.t,
                y: &me.y,
                f0: &me.f,
                h,
                tol: &me.tol,
            };
            let (f1, dense) = S::accept(sys, from, trial);
            me.stats.evaluations = me.stats.evaluations.saturating_add(S::ACCEPT_EVALUATIONS);
            let step = AcceptedStep {
                t0: me.t,
                y0: me.y,
                f0: me.f,
                t1,
                y1: trial.y1,
                dense,
            };
            me.t = t1;
            me.y = trial.y1;
            me.f = f1;
            step
        })
    }

    /// The trial loop of [`Self::step`]: retries until a trial is accepted and updates the
    /// controller (the next proposed step), but leaves the current time, state and derivative
    /// for `accept` to move to the step end; it gets the step size, the step end time and the
    /// accepted trial (by reference: the trial with its stages is not moved out of the loop).
    #[inline(always)]
    fn accepted_trial<F: OdeSystem<N> + ?Sized, R>(
        &mut self,
        sys: &F,
        t_limit: f64,
        accept: impl FnOnce(&mut Self, f64, f64, &Attempt<N, S::Stages>) -> R,
    ) -> Result<R, PropagationError> {
        if t_limit.is_nan() || t_limit <= self.t {
            return Err(PropagationError::InvalidTarget {
                target: t_limit,
                current: self.t,
            });
        }
        let ctl = self.controller;
        let (fac_lo, fac_hi) = (1.0 / ctl.fac_max, 1.0 / ctl.fac_min);
        let mut rejections = 0u32;
        loop {
            let mut h = self.h.min(self.h_max);
            // Hairer's rule: take the remainder at once when it is within 1 % of a step.
            if self.t + 1.01 * h >= t_limit {
                h = t_limit - self.t;
            }
            if h.is_nan() || h <= 10.0 * f64::EPSILON * math::abs(self.t) || h < f64::MIN_POSITIVE {
                return Err(PropagationError::StepSizeUnderflow { time: self.t });
            }
            let from = StepStart {
                t: self.t,
                y: &self.y,
                f0: &self.f,
                h,
                tol: &self.tol,
            };
            let trial = S::attempt(sys, from);
            self.stats.evaluations = self.stats.evaluations.saturating_add(S::STAGE_EVALUATIONS);
            let err = if trial.err.is_nan() || !all_finite(&trial.y1) {
                f64::INFINITY
            } else {
                trial.err
            };
            // err^alpha; DOP853's alpha = 1/8 by three square roots (a power costs ten times
            // more).
            let fac11 = if ctl.alpha == 0.125 {
                math::sqrt(math::sqrt(math::sqrt(err)))
            } else {
                math::pow(err, ctl.alpha)
            };
            if err <= 1.0 {
                // Lund stabilisation: fac = err^alpha / err_old^beta (no stabilisation when
                // beta = 0, DOP853's default).
                let fac = if ctl.beta == 0.0 {
                    fac11
                } else {
                    fac11 / math::pow(self.err_old, ctl.beta)
                };
                let fac = (fac / ctl.safety).min(fac_hi).max(fac_lo);
                let mut h_new = h / fac;
                if self.rejected_last {
                    h_new = h_new.min(h);
                }
                self.err_old = err.max(1e-4);
                self.rejected_last = false;
                self.stats.accepted = self.stats.accepted.saturating_add(1);
                let t1 = if h == t_limit - self.t {
                    t_limit
                } else {
                    self.t + h
                };
                self.h = h_new.min(self.h_max);
                return Ok(accept(self, h, t1, &trial));
            }
            self.stats.rejected = self.stats.rejected.saturating_add(1);
            self.rejected_last = true;
            self.h = h / (fac11 / ctl.safety).min(fac_hi);
            rejections += 1;
            if rejections >= MAX_REJECTIONS {
                return Err(PropagationError::StepSizeUnderflow { time: self.t });
            }
        }
    }

    /// The state at `t` in `[step.t0, step.t1]` by one explicit step of exactly `t − step.t0`
    /// from the step's start (not interpolated): as accurate as a step of the method.
    pub fn redo<F: OdeSystem<N> + ?Sized>(
        &mut self,
        sys: &F,
        step: &AcceptedStep<N, S::Dense>,
        t: f64,
    ) -> [f64; N] {
        self.redo_from(sys, step.t0, &step.y0, &step.f0, t)
    }

    /// The state at `t` by one explicit step of exactly `t − t0` from `(t0, y0)` with
    /// `f0 = f(t0, y0)` (see [`Self::redo`]).
    pub fn redo_from<F: OdeSystem<N> + ?Sized>(
        &mut self,
        sys: &F,
        t0: f64,
        y0: &[f64; N],
        f0: &[f64; N],
        t: f64,
    ) -> [f64; N] {
        self.stats.evaluations = self.stats.evaluations.saturating_add(S::STAGE_EVALUATIONS);
        let from = StepStart {
            t: t0,
            y: y0,
            f0,
            h: t - t0,
            tol: &self.tol,
        };
        S::attempt(sys, from).y1
    }
}

impl<const N: usize> Integrator<Dop853, N> {
    /// As [`Self::step`], but the dense output is not built: the accepted step keeps its stages
    /// and builds the dense output on demand ([`Dop853Step::dense`], three more evaluations).
    /// The step sequence and the states are those of [`Self::step`].
    ///
    /// # Errors
    /// As [`Self::step`].
    pub fn step_deferred<F: OdeSystem<N> + ?Sized>(
        &mut self,
        sys: &F,
        t_limit: f64,
        out: &mut Dop853Step<N>,
    ) -> Result<(), PropagationError> {
        self.accepted_trial(sys, t_limit, |me, h, t1, trial| {
            out.set(sys, me.t, &me.y, h, t1, trial);
            me.stats.evaluations = me.stats.evaluations.saturating_add(1);
            me.t = t1;
            me.y = trial.y1;
            me.f = out.f1();
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// y' = −y: enough to step.
    struct Decay;

    impl OdeSystem<1> for Decay {
        fn rhs(&self, _t: f64, y: &[f64; 1]) -> [f64; 1] {
            [-y[0]]
        }
    }

    #[test]
    fn an_unstarted_integrator_refuses_to_step_until_restarted() {
        let tol = Tolerance::uniform(1e-10);
        let mut idle = Integrator::<Dop853, 1>::unstarted(0.0, [1.0], tol, 1.0);
        assert_eq!(
            idle.step(&Decay, 10.0).map(|s| s.t1),
            Err(PropagationError::StepSizeUnderflow { time: 0.0 })
        );
        // Restarted, it steps exactly as one built started there.
        idle.restart(&Decay, 0.0, [1.0]);
        let mut started = Integrator::<Dop853, 1>::new(&Decay, 0.0, [1.0], tol, 1.0);
        let (a, b) = (idle.step(&Decay, 10.0), started.step(&Decay, 10.0));
        assert_eq!(a.map(|s| (s.t1, s.y1)), b.map(|s| (s.t1, s.y1)));
        assert!(idle.time() > 0.0);
    }
}
