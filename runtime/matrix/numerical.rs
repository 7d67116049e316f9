//! The numerical methods on a rotor from matrices (`docs/MODEL.md` §17): an adaptive
//! Runge–Kutta integration (DOP853 or Dormand–Prince 5(4), `crate::reference`) of the current
//! regime's whole field y' = f(y) over the state's 2n entries, with every switch located on the
//! step's dense output and refined by the one refinement (`crate::refine`, through
//! [`first_crossing_subdivided`]), then put on the step solution ([`polish_switch`]), as the
//! planar reference propagators do (`crate::reference`'s module documentation).
//!
//! One [`NumericalSolver`] serves every regime (a switch restarts it on the next regime's
//! field): it is the whole of the `dop853` and `rk45` methods, the contact and rolling solver
//! of `hybrid`, and — at a tight tolerance — a numerical free flight ([`NumericalFree`]) that
//! can stand in for the exact one ([`super::ExactFree`]) to test the contact solvers alone.
//!
//! Tolerance semantics: rtol = atol = tol per step in Hairer's mixed norm over the 2n entries
//! of y ([`OdeSystem::dimension`]), as for the planar model.

use crate::driver::SegmentStart;
use core::ops::Deref;

use super::model::MatrixModel;
use super::state::MatrixState;
use super::switches::{Function, MatrixSwitches, SegmentSide};
use crate::driver::{Located, SegmentSolver, Solvers, System};
use crate::field::{self, Field};
use crate::math;
use crate::propagate::{Event, EventKind, PropagationError, Regime};
use crate::reference::{
    AcceptedStep, After, Dop853, Integrator, Interpolant, OdeSystem, SUBDIVISIONS, Scheme,
    Tolerance, first_crossing_subdivided, polish_switch,
};

/// Touches (w = 0 without a change) looked past in one step before the rest of the step is
/// taken as free of friction switches (as the planar search, `reference::switch`).
const MAX_TOUCHES: usize = 4;

/// The tolerance of the stand-in free flight ([`NumericalFree`]): as tight as DOP853's range
/// allows to a margin, so that its switch times are within 1e-10 of exact ones over the tests'
/// runs.
pub const STAND_IN_TOLERANCE: f64 = 1e-13;

/// One regime's field of a matrix model as an [`OdeSystem`] on its storage: y' = f(y) over the
/// first 2n entries (the rest stay 0), the forcing phase from the time.
pub struct MatrixField<'a, const CAP: usize> {
    model: &'a MatrixModel<CAP>,
    field: Field,
}

impl<'a, const CAP: usize> MatrixField<'a, CAP> {
    /// The field `field` of `model`.
    pub fn new(model: &'a MatrixModel<CAP>, field: Field) -> Self {
        MatrixField { model, field }
    }
}

impl<const CAP: usize> OdeSystem<CAP> for MatrixField<'_, CAP> {
    #[inline]
    fn rhs(&self, t: f64, y: &[f64; CAP]) -> [f64; CAP] {
        let phasor = field::phasor(self.model.running(), t);
        self.model.stage(self.field, &phasor, y)
    }

    #[inline(always)]
    fn dimension(&self) -> usize {
        2 * self.model.dofs()
    }
}

/// The largest step: a quarter of the shorter of the forcing period and the period of the
/// model's fastest free mode (`fastest_rate` of the free field), so that the switching
/// function is sampled at least 4·[`SUBDIVISIONS`] times per period even at loose tolerances.
pub fn max_step<const CAP: usize>(model: &MatrixModel<CAP>) -> f64 {
    let mut period = core::f64::consts::TAU / model.speed_ratio();
    let fastest = fastest_rate(model, 0.0);
    if fastest > 0.0 {
        period = period.min(core::f64::consts::TAU / fastest);
    }
    if period > 0.0 && period.is_finite() {
        0.25 * period
    } else {
        f64::INFINITY
    }
}

/// A bound on the fastest mode's frequency of a field whose stiffness is the model's plus
/// `extra` (an ∞-norm added to the stiffness rows): from |λ|² ≤ c|λ| + k, c and k the ∞-norms
/// of M⁻¹(C + ηG) and M⁻¹K (+ `extra`), the lower blocks of A.
pub(crate) fn fastest_rate<const CAP: usize>(model: &MatrixModel<CAP>, extra: f64) -> f64 {
    let n = model.dofs();
    let a = model.first_order();
    let (mut c, mut k) = (0.0f64, 0.0f64);
    for i in 0..n {
        let row = a.row(n + i);
        let stiffness: f64 = row.iter().take(n).map(|x| math::abs(*x)).sum();
        let damping: f64 = row.iter().skip(n).take(n).map(|x| math::abs(*x)).sum();
        k = k.max(stiffness);
        c = c.max(damping);
    }
    let k = k + extra;
    0.5 * (c + math::sqrt(c * c + 4.0 * k))
}

/// A switch found in a step: time, state, kind.
type Found<const CAP: usize> = (f64, [f64; CAP], EventKind);

/// An adaptive Runge–Kutta solver of a matrix model's segments, every regime (see the module
/// documentation).
#[derive(Clone)]
pub struct NumericalSolver<S: Scheme<CAP>, M, const CAP: usize> {
    model: M,
    side: SegmentSide,
    integrator: Integrator<S, CAP>,
    step: Option<AcceptedStep<CAP, S::Dense>>,
    pending: Option<Event<MatrixState<CAP>>>,
}

impl<S, M, const CAP: usize> NumericalSolver<S, M, CAP>
where
    S: Scheme<CAP>,
    M: Deref<Target = MatrixModel<CAP>>,
{
    /// A solver of `model` at rtol = atol = `tol`, not yet started (the driver starts it).
    pub fn new(model: M, tol: f64) -> Self {
        let integrator =
            Integrator::unstarted(0.0, [0.0; CAP], Tolerance::uniform(tol), max_step(&model));
        NumericalSolver {
            model,
            side: SegmentSide::NONE,
            integrator,
            step: None,
            pending: None,
        }
    }

    /// Work counters of the integration so far.
    pub fn stats(&self) -> crate::reference::Stats {
        self.integrator.stats()
    }

    fn state(&self, y: [f64; CAP]) -> MatrixState<CAP> {
        MatrixState::from_array(self.model.dofs(), y)
    }
}

impl<S, M, const CAP: usize> SegmentSolver<MatrixState<CAP>> for NumericalSolver<S, M, CAP>
where
    S: Scheme<CAP>,
    M: Deref<Target = MatrixModel<CAP>>,
{
    /// Take the regime's field and restart the integration at the switch.
    fn start(&mut self, at: SegmentStart<MatrixState<CAP>>) -> Result<(), PropagationError> {
        self.side = SegmentSide::at(&self.model, &at);
        self.step = None;
        self.pending = None;
        let model: &MatrixModel<CAP> = &self.model;
        let field = MatrixField::new(model, self.side.field());
        self.integrator.restart(&field, at.time, *at.state.array());
        Ok(())
    }

    fn locate(&mut self, target: f64) -> Located<MatrixState<CAP>> {
        if let Some(event) = self.pending
            && target >= event.time
        {
            return Located::Switch(event);
        }
        match &self.step {
            Some(step) if target <= step.t1 => Located::Reached(self.state(if target == step.t1 {
                step.y1
            } else {
                step.dense.eval(target)
            })),
            _ => Located::NeedStep,
        }
    }

    /// Take one step and look for a switch in it.
    fn step(&mut self) -> Result<(), PropagationError> {
        let model: &MatrixModel<CAP> = &self.model;
        let sys = MatrixField::new(model, self.side.field());
        let step = self.integrator.step(&sys, f64::INFINITY)?;
        let end = MatrixState::from_array(model.dofs(), step.y1);
        if !System::within_bounds(&model, &end) {
            return Err(System::diverged(&model, step.t1, &end));
        }
        let switches = self.side.switches(model);
        let integrator = &mut self.integrator;
        let found = first_switch(
            &switches,
            SUBDIVISIONS,
            &step.dense,
            (&step.y0, &step.y1),
            |t| integrator.redo(&sys, &step, t),
            |t, y| sys.rhs(t, y),
        );
        self.pending = found.map(|(time, y, kind)| Event {
            time,
            kind,
            state: MatrixState::from_array(model.dofs(), y),
        });
        self.step = Some(step);
        Ok(())
    }

    fn computed_to(&self) -> f64 {
        self.integrator.time()
    }
}

/// One solver for every regime: the whole-system numerical methods.
impl<S, M, const CAP: usize> Solvers<MatrixState<CAP>> for NumericalSolver<S, M, CAP>
where
    S: Scheme<CAP>,
    M: Deref<Target = MatrixModel<CAP>>,
{
    fn solver(&mut self, _regime: Regime) -> &mut dyn SegmentSolver<MatrixState<CAP>> {
        self
    }

    #[inline]
    fn locate(&mut self, _regime: Regime, target: f64) -> Located<MatrixState<CAP>> {
        SegmentSolver::locate(self, target)
    }
}

/// The stand-in free flight: DOP853 at [`STAND_IN_TOLERANCE`] in free flight (the exact
/// free-flight solver's interface: `new(model)`, then [`SegmentSolver`] for free segments,
/// ending in `enter` switches).
pub struct NumericalFree<M, const CAP: usize>(NumericalSolver<Dop853, M, CAP>);

impl<M: Deref<Target = MatrixModel<CAP>>, const CAP: usize> NumericalFree<M, CAP> {
    /// The free flight of `model`.
    ///
    /// # Errors
    /// None (the exact solver's decomposition can fail; this one cannot).
    pub fn new(model: M) -> Result<Self, PropagationError> {
        Ok(NumericalFree(NumericalSolver::new(
            model,
            STAND_IN_TOLERANCE,
        )))
    }
}

impl<M: Deref<Target = MatrixModel<CAP>>, const CAP: usize> SegmentSolver<MatrixState<CAP>>
    for NumericalFree<M, CAP>
{
    fn start(&mut self, at: SegmentStart<MatrixState<CAP>>) -> Result<(), PropagationError> {
        self.0.start(at)
    }

    #[inline]
    fn locate(&mut self, target: f64) -> Located<MatrixState<CAP>> {
        SegmentSolver::locate(&mut self.0, target)
    }

    fn step(&mut self) -> Result<(), PropagationError> {
        self.0.step()
    }

    fn computed_to(&self) -> f64 {
        self.0.computed_to()
    }
}

/// The first switch of `switches` in the step `(t0, y0) → (t1, y1)` with dense output `dense`,
/// examined in `subdivisions` sub-intervals (with one, the dense output is evaluated only when
/// the end states show a crossing or a minimum): the earliest crossing of any switch function
/// on the dense output, put on the step solution
/// (`redo` recomputes the state at a time by an explicit step from the step start, `rhs` is the
/// field) and classified; touches of w = 0 are looked past.
pub(crate) fn first_switch<const CAP: usize, D: Interpolant<CAP>>(
    switches: &MatrixSwitches<'_, CAP>,
    subdivisions: usize,
    dense: &D,
    (y0, y1): (&[f64; CAP], &[f64; CAP]),
    mut redo: impl FnMut(f64) -> [f64; CAP],
    mut rhs: impl FnMut(f64, &[f64; CAP]) -> [f64; CAP],
) -> Option<Found<CAP>> {
    let (t0, t1) = (dense.start(), dense.end());
    let functions = switches.functions();
    let (mut from, mut y_from) = (t0, *y0);
    for _ in 0..=MAX_TOUCHES {
        let window = After { dense, start: from };
        let mut first: Option<(f64, Function)> = None;
        for f in functions.iter().flatten() {
            let found = first_crossing_subdivided(
                subdivisions,
                &window,
                &y_from,
                y1,
                |t, y: &[f64; CAP]| switches.measure(*f, t, y),
            );
            if let Some(t) = found
                && first.is_none_or(|(tf, _)| t < tf)
            {
                first = Some((t, *f));
            }
        }
        let (t, f) = first?;
        let t = t.max(t0).min(t1);
        let y = if t == t1 { *y1 } else { redo(t) };
        let max_shift = 1e-3 * (t1 - t0);
        let (t, y) = polish_switch(t0, t1, max_shift, (t, y), &mut redo, &mut rhs, |t, y| {
            switches.measure(f, t, y)
        });
        match switches.classify(f, t, &y) {
            Some(kind) => return Some((t, y, kind)),
            None if t < t1 => (from, y_from) = (t, y),
            None => return None,
        }
    }
    None
}
