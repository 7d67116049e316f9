//! `hybrid`'s contact and rolling solver on a rotor from matrices: DOP853 on the regime's whole
//! field, as [`NumericalSolver`] integrates it, with the economies of the planar hybrid's
//! contact solver (`crate::hybrid`):
//!
//! - the dense output (three more evaluations and its coefficients) is built only for a step
//!   that holds a switch, a minimum of a switch function, or a requested time;
//! - the switch functions are examined on sub-intervals no longer than an eighth of the contact
//!   field's fastest period ([`CONTACT_PIECES`], [`longest_piece`]) and than the planar hybrid's
//!   (a 32nd of the forcing period); a contact step, which DOP853 keeps far shorter to resolve
//!   that mode, is one sub-interval given by its exact end states and their rates. Why an eighth
//!   suffices: the search reads each piece's end values and rates, so a crossing it misses needs
//!   the function to dip below 0 and back between two samples with rates that show no minimum,
//!   which takes two extrema inside the piece; a switching function's extrema driven by a mode
//!   are half its period apart, four pieces;
//! - the forcing direction at a stage is the step start's turned by η·s ([`StepField`]), the
//!   sine and cosine of a small angle by their polynomials instead of the phase's at the
//!   stage's time;
//! - each contact after the first starts with the step size the previous one ended with
//!   instead of a fresh initial guess (two evaluations and a trial).
//!
//! The steps and the switch search are otherwise [`NumericalSolver`]'s: the same field, the
//! same tolerance semantics, the same refinement and polish onto the step solution.

use core::ops::Deref;

use super::model::MatrixModel;
use super::numerical::{fastest_rate, first_switch, max_step};
use super::state::MatrixState;
use super::switches::SegmentSide;
use crate::coefficients::Phasor;
use crate::driver::{Located, SegmentSolver, SegmentStart, System};
use crate::field::{self, Field};
use crate::math;
use crate::propagate::{Event, PropagationError};
use crate::reference::{
    Dop853, Dop853Dense, Dop853Step, Integrator, Interpolant, LazyDense, OdeSystem, Tolerance,
};

#[cfg(doc)]
use super::numerical::{MatrixField, NumericalSolver};

/// Sub-intervals per period of the contact field's fastest mode in which the switch search
/// examines a step (see the module documentation).
pub const CONTACT_PIECES: f64 = 8.0;

/// The most sub-intervals one step is examined in (a step longer than that many pieces, which
/// the max step rules out, is examined in as many).
const MAX_PIECES: usize = 64;

/// The longest sub-interval of a contact step the switch search examines whole: the shorter of
/// an [`CONTACT_PIECES`]th of the contact field's fastest period — its frequency bounded as
/// [`max_step`]'s with the contact's stiffness added, ‖W K_c‖∞ (W = B M⁻¹ Bᵀ the station's
/// compliance, K_c the contact stiffness) — and a 32nd of the forcing period.
pub fn longest_piece<const CAP: usize>(model: &MatrixModel<CAP>) -> f64 {
    let w = model.compliance();
    let k = model.station().contact_stiffness;
    let rows = [[w.w_xx, w.w_xy], [w.w_yx, w.w_yy]];
    let norm = rows
        .iter()
        .map(|row| {
            (0..2)
                .map(|j| {
                    let column = k.iter().map(|kr| kr.get(j).copied().unwrap_or(0.0));
                    math::abs(row.iter().zip(column).map(|(a, b)| a * b).sum::<f64>())
                })
                .sum::<f64>()
        })
        .fold(0.0, f64::max);
    let forcing = core::f64::consts::TAU / model.speed_ratio() / 32.0;
    let fastest = fastest_rate(model, norm);
    let contact = if fastest > 0.0 {
        core::f64::consts::TAU / fastest / CONTACT_PIECES
    } else {
        f64::INFINITY
    };
    let piece = forcing.min(contact);
    if piece > 0.0 { piece } else { f64::INFINITY }
}

/// A regime's field on one step: [`MatrixField`]'s, with the forcing direction at `t` that at
/// the step's start `t0` turned by η·(t − t0) (`field::phasor_within_step`): every stage, the dense
/// output and a redone step of that step use the same base.
struct StepField<'a, const CAP: usize> {
    model: &'a MatrixModel<CAP>,
    field: Field,
    t0: f64,
    phasor: Phasor,
}

impl<'a, const CAP: usize> StepField<'a, CAP> {
    /// `field` of `model` on a step from `t0`.
    fn new(model: &'a MatrixModel<CAP>, field: Field, t0: f64) -> Self {
        StepField {
            model,
            field,
            t0,
            phasor: field::phasor(model.running(), t0),
        }
    }
}

impl<const CAP: usize> OdeSystem<CAP> for StepField<'_, CAP> {
    #[inline(always)]
    fn rhs(&self, t: f64, y: &[f64; CAP]) -> [f64; CAP] {
        // At t0 itself the angle is 0, its sine and cosine (0, 1) exactly: the start's phasor.
        let phasor = field::phasor_within_step(self.model.running(), &self.phasor, t - self.t0);
        self.model.stage(self.field, &phasor, y)
    }

    #[inline(always)]
    fn dimension(&self) -> usize {
        2 * self.model.dofs()
    }
}

/// DOP853 on a matrix model's contact and rolling segments with deferred dense output (see the
/// module documentation).
#[derive(Clone)]
pub struct Dop853Contact<M, const CAP: usize> {
    model: M,
    side: SegmentSide,
    integrator: Integrator<Dop853, CAP>,
    /// [`longest_piece`] of the model.
    piece: f64,
    /// The step size proposed when the last contact ended.
    carried_step: Option<f64>,
    /// Whether the current segment has taken a step (`step` holds it).
    stepped: bool,
    step: Dop853Step<CAP>,
    /// The dense output of `step`, once built.
    dense: Option<Dop853Dense<CAP>>,
    /// The switch ending the segment, once a step holds it.
    pending: Option<Event<MatrixState<CAP>>>,
}

impl<M, const CAP: usize> Dop853Contact<M, CAP>
where
    M: Deref<Target = MatrixModel<CAP>>,
{
    /// A solver of `model` at rtol = atol = `tol`, not yet started (the driver starts it).
    pub fn new(model: M, tol: f64) -> Self {
        let integrator =
            Integrator::unstarted(0.0, [0.0; CAP], Tolerance::uniform(tol), max_step(&model));
        let piece = longest_piece(&model);
        Dop853Contact {
            model,
            side: SegmentSide::NONE,
            integrator,
            piece,
            carried_step: None,
            stepped: false,
            step: Dop853Step::default(),
            dense: None,
            pending: None,
        }
    }

    /// Work counters of the integration so far.
    pub fn stats(&self) -> crate::reference::Stats {
        self.integrator.stats()
    }

    /// The state at `t` in the last step: its end exactly, else its dense output (built now if
    /// the switch search did not).
    fn state_at(&mut self, t: f64) -> MatrixState<CAP> {
        let model: &MatrixModel<CAP> = &self.model;
        let y = if t == self.step.t1 {
            self.step.y1
        } else {
            let step = &self.step;
            let field = StepField::new(model, self.side.field(), step.t0);
            self.dense.get_or_insert_with(|| step.dense(&field)).eval(t)
        };
        MatrixState::from_array(model.dofs(), y)
    }
}

impl<M, const CAP: usize> SegmentSolver<MatrixState<CAP>> for Dop853Contact<M, CAP>
where
    M: Deref<Target = MatrixModel<CAP>>,
{
    /// Take the regime's field and restart the integration at the switch, with the step size
    /// the last contact ended with.
    fn start(&mut self, at: SegmentStart<MatrixState<CAP>>) -> Result<(), PropagationError> {
        self.side = SegmentSide::at(&self.model, &at);
        self.stepped = false;
        self.dense = None;
        self.pending = None;
        let model: &MatrixModel<CAP> = &self.model;
        let (time, y) = (at.time, *at.state.array());
        let field = StepField::new(model, self.side.field(), time);
        match self.carried_step {
            Some(h) => self.integrator.restart_with_step(&field, time, y, h),
            None => self.integrator.restart(&field, time, y),
        }
        Ok(())
    }

    fn locate(&mut self, target: f64) -> Located<MatrixState<CAP>> {
        if let Some(event) = self.pending
            && target >= event.time
        {
            self.carried_step = Some(self.integrator.proposed_step());
            return Located::Switch(event);
        }
        if self.stepped && target <= self.step.t1 {
            Located::Reached(self.state_at(target))
        } else {
            Located::NeedStep
        }
    }

    /// Take one step and look for a switch in it.
    fn step(&mut self) -> Result<(), PropagationError> {
        let model: &MatrixModel<CAP> = &self.model;
        let sys = StepField::new(model, self.side.field(), self.integrator.time());
        self.dense = None;
        self.integrator
            .step_deferred(&sys, f64::INFINITY, &mut self.step)?;
        let step = &self.step;
        let end = MatrixState::from_array(model.dofs(), step.y1);
        if !System::within_bounds(&model, &end) {
            return Err(System::diverged(&model, step.t1, &end));
        }
        // Sub-intervals no longer than the longest piece.
        let ratio = (step.t1 - step.t0) / self.piece;
        let subdivisions = if ratio <= 1.0 {
            1
        } else {
            (libm::ceil(ratio) as usize).min(MAX_PIECES)
        };
        let switches = self.side.switches(model);
        let lazy = LazyDense::new(&sys, step);
        let integrator = &mut self.integrator;
        let f0 = step.f0();
        let found = first_switch(
            &switches,
            subdivisions,
            &lazy,
            (&step.y0, &step.y1),
            |t| integrator.redo_from(&sys, step.t0, &step.y0, &f0, t),
            |t, y| sys.rhs(t, y),
        );
        self.dense = lazy.into_inner();
        self.pending = found.map(|(time, y, kind)| Event {
            time,
            kind,
            state: MatrixState::from_array(model.dofs(), y),
        });
        self.stepped = true;
        Ok(())
    }

    fn computed_to(&self) -> f64 {
        self.integrator.time()
    }
}
