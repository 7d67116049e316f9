//! The state machine itself: one [`Piecewise`] behind [`Propagate`] for every method.

use super::{Located, Solvers, StepBudget, System};
use crate::driver::SegmentStart;
use crate::params::{Params, Problem};
use crate::propagate::{Event, Propagate, PropagationError, Regime, check_target};

/// A piecewise propagation of a model `Y` (the paper's planar model by default): the current
/// regime's solver serves targets until it reports a switch; the next regime's solver starts
/// there. See the module documentation of [`crate::driver`].
#[derive(Clone, Copy, Debug)]
pub struct Piecewise<S, Y: System = Params> {
    solvers: S,
    system: Y,
    budget: Option<StepBudget>,
    time: f64,
    state: Y::State,
    regime: Regime,
    /// σ of the current slipping contact segment (0 when none is tracked).
    slip: f64,
    /// A step failure: the run stays at its last good time and reports it again.
    failure: Option<PropagationError>,
}

impl<S: Solvers> Piecewise<S> {
    /// Start at the problem's start, in the regime [`crate::field::regime_of`] decides there (on z = 1:
    /// the side the motion takes, see the module documentation): [`Piecewise::start`] for the
    /// paper's planar model.
    ///
    /// # Errors
    /// [`crate::ParamError::RingNeedsMatrixModel`] for a ring with mass (the planar model has
    /// none; see [`crate::matrix`]), else as [`Piecewise::start`].
    #[inline(always)]
    pub fn new(
        problem: &Problem,
        budget: Option<StepBudget>,
        build: impl FnOnce(SegmentStart) -> Result<S, PropagationError>,
    ) -> Result<Self, PropagationError> {
        problem.params.planar()?;
        Piecewise::start(
            problem.params,
            problem.start_time,
            problem.initial,
            budget,
            build,
        )
    }
}

impl<Y: System, S: Solvers<Y::State>> Piecewise<S, Y> {
    /// Start `system` at `(time, state)`, in the regime [`System::start_side`] decides there.
    /// `build(at)` makes the method's solvers with the solver of `at.regime` started at `at`
    /// ([`super::SegmentSolver::start`]): at `time`, in the initial state or, on the contact
    /// surface, the start moved onto its side, with the slip direction the friction rules give.
    ///
    /// # Errors
    /// [`PropagationError::Diverged`] for a start beyond the divergence radius, or what `build`
    /// reports.
    #[inline(always)]
    pub fn start(
        system: Y,
        time: f64,
        state: Y::State,
        budget: Option<StepBudget>,
        build: impl FnOnce(SegmentStart<Y::State>) -> Result<S, PropagationError>,
    ) -> Result<Self, PropagationError> {
        if !system.within_bounds(&state) {
            return Err(system.diverged(time, &state));
        }
        let (regime, start) = system.start_side(time, &state);
        let slip = match regime {
            Regime::Contact => system.slip_direction(time, &start, None),
            Regime::Free | Regime::Rolling => 0.0,
        };
        let solvers = build(SegmentStart {
            regime,
            slip,
            time,
            state: start,
        })?;
        Ok(Piecewise {
            solvers,
            system,
            budget,
            time,
            state,
            regime,
            slip,
            failure: None,
        })
    }

    /// Start `system` on a side already known: at `at.time` and `at.state` in `at.regime` with
    /// slip direction `at.slip` (a run continued from its saved position, where deciding the
    /// side afresh could read σ from a slip velocity that is 0 to rounding right after a
    /// `reverse`). `build` as for [`Piecewise::start`]; the side is the caller's to get right.
    ///
    /// # Errors
    /// As [`Piecewise::start`].
    #[inline(always)]
    pub fn start_on(
        system: Y,
        at: SegmentStart<Y::State>,
        budget: Option<StepBudget>,
        build: impl FnOnce(SegmentStart<Y::State>) -> Result<S, PropagationError>,
    ) -> Result<Self, PropagationError> {
        if !system.within_bounds(&at.state) {
            return Err(system.diverged(at.time, &at.state));
        }
        let solvers = build(at)?;
        Ok(Piecewise {
            solvers,
            system,
            budget,
            time: at.time,
            state: at.state,
            regime: at.regime,
            slip: at.slip,
            failure: None,
        })
    }

    /// A propagation already under way: at `(time, state)` in `regime` with slip direction
    /// `slip`, the solvers' solver of `regime` already started there (a fixed-step caller that
    /// keeps the position between its steps and runs the driver over each, `crate::stepper`).
    /// Nothing is validated: the caller's position is one the driver reached.
    #[inline]
    pub fn resume(
        system: Y,
        time: f64,
        state: Y::State,
        regime: Regime,
        slip: f64,
        solvers: S,
    ) -> Self {
        Piecewise {
            solvers,
            system,
            budget: None,
            time,
            state,
            regime,
            slip,
            failure: None,
        }
    }

    /// The slip direction σ of the current contact segment (±1 while slipping under friction, 0
    /// otherwise).
    pub fn slip(&self) -> f64 {
        self.slip
    }

    /// The method's solvers (for their work counters).
    pub fn solvers(&self) -> &S {
        &self.solvers
    }

    /// Move to `event` and start the next regime's solver there.
    fn switch(&mut self, event: Event<Y::State>) -> Result<(), PropagationError> {
        if !self.system.within_bounds(&event.state) {
            return Err(self.system.diverged(event.time, &event.state));
        }
        let regime = event.kind.regime_after();
        let slip = match regime {
            Regime::Contact => {
                self.system
                    .slip_direction(event.time, &event.state, Some(event.kind))
            }
            Regime::Free | Regime::Rolling => 0.0,
        };
        self.solvers.solver(regime).start(SegmentStart {
            regime,
            slip,
            time: event.time,
            state: event.state,
        })?;
        self.time = event.time;
        self.state = event.state;
        self.regime = regime;
        self.slip = slip;
        Ok(())
    }
}

impl<Y: System, S: Solvers<Y::State>> Propagate<Y::State> for Piecewise<S, Y> {
    fn time(&self) -> f64 {
        self.time
    }

    fn state(&self) -> Y::State {
        self.state
    }

    fn regime(&self) -> Regime {
        self.regime
    }

    fn advance(&mut self, target: f64) -> Result<Option<Event<Y::State>>, PropagationError> {
        if !check_target(target, self.time)? {
            return Ok(None);
        }
        let limit = self
            .budget
            .map(|b| b.base + b.per_time_unit * (target - self.time));
        let mut steps = 0.0;
        loop {
            match self.solvers.locate(self.regime, target) {
                Located::Reached(state) => {
                    self.time = target;
                    self.state = state;
                    return Ok(None);
                }
                Located::Switch(event) => {
                    self.switch(event)?;
                    return Ok(Some(event));
                }
                Located::NeedStep => {
                    if let Some(e) = self.failure {
                        return Err(e);
                    }
                    let solver = self.solvers.solver(self.regime);
                    if let Some(limit) = limit {
                        if steps >= limit {
                            return Err(PropagationError::StepSizeUnderflow {
                                time: solver.computed_to(),
                            });
                        }
                        steps += 1.0;
                    }
                    if let Err(e) = solver.step() {
                        self.failure = Some(e);
                        return Err(e);
                    }
                }
            }
        }
    }
}
