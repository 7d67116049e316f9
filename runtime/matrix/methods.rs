//! Every method for a rotor from matrices (`docs/MODEL.md` §17), each a [`Piecewise`] driver
//! over the model (a [`System`] behind any pointer) and its segment solvers, and one type that
//! dispatches them by [`Method`] ([`MatrixPropagator`]):
//!
//! | method | free flight | contact, rolling |
//! |---|---|---|
//! | `dop853`, `rk45` | the same integrator on the whole system ([`NumericalSolver`]) | same |
//! | `hybrid` | exact ([`FreeFlight`]) | DOP853, dense output deferred ([`Dop853Contact`]) |
//! | `taylor` | exact | Taylor series of the generated station law ([`TaylorContact`]) |
//! | `analytic` | exact | the Taylor segment at the analytic method's tolerance |
//!
//! The paper's linearized closed forms for contact (exprb2, exprb43) are the n = 2 model's
//! only: a rotor from matrices takes the analytic method's contact as a Taylor segment, and
//! refuses the contact scheme `exprb2` and a fixed sub-step ([`MatrixError::MethodOption`]).
//!
//! The free flight of `hybrid`, `taylor` and `analytic` is a type parameter `F` (any
//! [`SegmentSolver`] of free segments ending in `enter` switches); [`FreeFlight`] is the one
//! [`MatrixPropagator`] builds.

use core::ops::Deref;

use super::contact::Dop853Contact;
use super::error::MatrixError;
use super::free::ExactFree;
use super::model::MatrixModel;
#[cfg(doc)]
use super::numerical::NumericalFree;
use super::numerical::NumericalSolver;
use super::state::MatrixState;
use super::taylor::TaylorContact;
use crate::driver::{Located, Piecewise, SegmentSolver, SegmentStart, Solvers, System};
use crate::method::{ContactScheme, Method, Options};
use crate::propagate::{Event, Propagate, PropagationError, Regime};
use crate::reference::{Dop853, REFERENCE_BUDGET, Rk45, Scheme};

/// The free flight of `hybrid`, `taylor` and `analytic`: exact ([`ExactFree`],
/// `runtime/matrix/free/`). [`NumericalFree`] (DOP853 at [`super::STAND_IN_TOLERANCE`]) has
/// the same constructor and stands in for it in tests of the contact solvers alone.
pub type FreeFlight<M, const CAP: usize> = ExactFree<M, CAP>;

/// A free-flight solver and a contact solver (which serves rolling too: a segment of either
/// starts it afresh).
#[derive(Clone)]
pub struct Split<F, C> {
    /// Free flight.
    pub free: F,
    /// Contact and rolling.
    pub contact: C,
}

impl<St, F: SegmentSolver<St>, C: SegmentSolver<St>> Solvers<St> for Split<F, C> {
    fn solver(&mut self, regime: Regime) -> &mut dyn SegmentSolver<St> {
        match regime {
            Regime::Free => &mut self.free,
            Regime::Contact | Regime::Rolling => &mut self.contact,
        }
    }

    #[inline]
    fn locate(&mut self, regime: Regime, target: f64) -> Located<St> {
        match regime {
            Regime::Free => self.free.locate(target),
            Regime::Contact | Regime::Rolling => self.contact.locate(target),
        }
    }
}

/// A whole-system numerical method (`dop853` with `S` = [`Dop853`], `rk45` with [`Rk45`]).
pub type NumericalPropagator<S, M, const CAP: usize> = Piecewise<NumericalSolver<S, M, CAP>, M>;

/// `hybrid`: free flight by `F`, contact and rolling by DOP853.
pub type HybridPropagator<F, M, const CAP: usize> = Piecewise<Split<F, Dop853Contact<M, CAP>>, M>;

/// `taylor` and `analytic`: free flight by `F`, contact and rolling by Taylor series.
pub type TaylorPropagator<F, M, const CAP: usize> = Piecewise<Split<F, TaylorContact<M, CAP>>, M>;

/// Where a method starts: at a time and state, on the side the friction rules decide there
/// ([`Piecewise::start`]), or on a side already known ([`Piecewise::start_on`]).
#[derive(Clone, Copy)]
enum Begin<const CAP: usize> {
    Decide(f64, MatrixState<CAP>),
    On(SegmentStart<MatrixState<CAP>>),
}

impl<const CAP: usize> Begin<CAP> {
    /// The driver started here with the solvers `build` makes.
    fn piecewise<S, M: System<State = MatrixState<CAP>>>(
        self,
        model: M,
        build: impl FnOnce(SegmentStart<MatrixState<CAP>>) -> Result<S, PropagationError>,
    ) -> Result<Piecewise<S, M>, PropagationError>
    where
        S: Solvers<MatrixState<CAP>>,
    {
        match self {
            Begin::Decide(time, start) => {
                Piecewise::start(model, time, start, Some(REFERENCE_BUDGET), build)
            }
            Begin::On(at) => Piecewise::start_on(model, at, Some(REFERENCE_BUDGET), build),
        }
    }
}

/// Start a whole-system numerical method on `model` at `(time, start)` with rtol = atol = `tol`
/// (unchecked: the registry's range is the caller's).
///
/// # Errors
/// As [`Piecewise::start`].
pub fn numerical<S, M, const CAP: usize>(
    model: M,
    time: f64,
    start: MatrixState<CAP>,
    tol: f64,
) -> Result<NumericalPropagator<S, M, CAP>, PropagationError>
where
    S: Scheme<CAP>,
    M: Deref<Target = MatrixModel<CAP>> + Clone,
{
    numerical_from(model, Begin::Decide(time, start), tol)
}

fn numerical_from<S, M, const CAP: usize>(
    model: M,
    begin: Begin<CAP>,
    tol: f64,
) -> Result<NumericalPropagator<S, M, CAP>, PropagationError>
where
    S: Scheme<CAP>,
    M: Deref<Target = MatrixModel<CAP>> + Clone,
{
    let solver_model = model.clone();
    begin.piecewise(model, |at| {
        let mut solver = NumericalSolver::new(solver_model, tol);
        solver.start(at)?;
        Ok(solver)
    })
}

/// Start `hybrid` (contact: [`Dop853Contact`]) or `taylor` / `analytic` (contact:
/// [`TaylorContact`]) on `model` with free-flight solver `free` and the contact solver
/// `contact` (neither started: the one of the start's regime is started here).
///
/// # Errors
/// As [`Piecewise::start`].
pub fn split<F, C, M, const CAP: usize>(
    model: M,
    free: F,
    contact: C,
    time: f64,
    start: MatrixState<CAP>,
) -> Result<Piecewise<Split<F, C>, M>, PropagationError>
where
    F: SegmentSolver<MatrixState<CAP>>,
    C: SegmentSolver<MatrixState<CAP>>,
    M: Deref<Target = MatrixModel<CAP>>,
{
    split_from(model, free, contact, Begin::Decide(time, start))
}

fn split_from<F, C, M, const CAP: usize>(
    model: M,
    mut free: F,
    mut contact: C,
    begin: Begin<CAP>,
) -> Result<Piecewise<Split<F, C>, M>, PropagationError>
where
    F: SegmentSolver<MatrixState<CAP>>,
    C: SegmentSolver<MatrixState<CAP>>,
    M: Deref<Target = MatrixModel<CAP>>,
{
    begin.piecewise(model, |at| {
        match at.regime {
            Regime::Free => free.start(at)?,
            Regime::Contact | Regime::Rolling => contact.start(at)?,
        }
        Ok(Split { free, contact })
    })
}

#[allow(
    clippy::large_enum_variant,
    reason = "the runtime has no heap to box into; the CLI and Python hold it in a Box"
)]
#[derive(Clone)]
enum Inner<M: System, const CAP: usize> {
    Dop853(NumericalPropagator<Dop853, M, CAP>),
    Rk45(NumericalPropagator<Rk45, M, CAP>),
    Hybrid(HybridPropagator<FreeFlight<M, CAP>, M, CAP>),
    Taylor(TaylorPropagator<FreeFlight<M, CAP>, M, CAP>),
}

/// Every [`Method`] on a rotor from matrices behind one type (no heap): built from the model
/// (`&MatrixModel`, `Arc<MatrixModel>`, …), a start and the same [`Options`] as the planar
/// [`crate::Propagator`].
// (The definitions bound `M` by `System` only, which every `Deref<Target = MatrixModel<CAP>>`
// is: rustdoc 1.95 panics canonicalizing a definition's bound that projects to a type with a
// const parameter.)
#[derive(Clone)]
pub struct MatrixPropagator<M: System, const CAP: usize> {
    inner: Inner<M, CAP>,
    method: Method,
}

impl<M, const CAP: usize> MatrixPropagator<M, CAP>
where
    M: Deref<Target = MatrixModel<CAP>> + Clone,
{
    /// Validate `options` (the tolerance in the method's range; for `analytic` no contact
    /// scheme but exprb43 and no fixed sub-step) and the start (2n finite entries of the
    /// model's n, a finite time), and start the method at `(time, start)`.
    ///
    /// # Errors
    /// [`PropagationError::InvalidOption`] for the tolerance or step,
    /// [`PropagationError::InvalidModel`] for a start of the wrong size, not finite, or an
    /// option the matrix model does not take ([`MatrixError::MethodOption`]),
    /// [`PropagationError::InvalidTarget`] for a time that is not finite,
    /// [`PropagationError::Diverged`] for a start beyond the divergence radius.
    pub fn new(
        model: M,
        time: f64,
        start: MatrixState<CAP>,
        options: &Options,
    ) -> Result<Self, PropagationError> {
        Self::begin(model, Begin::Decide(time, start), options)
    }

    /// As [`MatrixPropagator::new`], continuing a run at `at` on the side it was on: in
    /// `at.regime` with slip direction `at.slip` (what [`Propagate::regime`] and
    /// [`MatrixPropagator::slip`] reported there), not the side the start rules would decide
    /// afresh — right after a `reverse` the slip velocity is 0 to rounding and its sign says
    /// nothing. A side the state is not on is the caller's error.
    ///
    /// # Errors
    /// As [`MatrixPropagator::new`].
    pub fn resume(
        model: M,
        at: SegmentStart<MatrixState<CAP>>,
        options: &Options,
    ) -> Result<Self, PropagationError> {
        Self::begin(model, Begin::On(at), options)
    }

    fn begin(model: M, begin: Begin<CAP>, options: &Options) -> Result<Self, PropagationError> {
        options.validate()?;
        if options.method == Method::Analytic {
            if options.contact_scheme != ContactScheme::Exprb43 {
                return Err(MatrixError::MethodOption {
                    method: "analytic",
                    option: "contact scheme exprb2",
                }
                .into());
            }
            if options.step.is_some() {
                return Err(MatrixError::MethodOption {
                    method: "analytic",
                    option: "a fixed contact sub-step (step)",
                }
                .into());
            }
        }
        let (time, start) = match &begin {
            Begin::Decide(time, start) => (*time, start),
            Begin::On(at) => (at.time, &at.state),
        };
        check_start(&model, time, start)?;
        let tol = options.tolerance();
        let inner = match options.method {
            Method::Dop853 => Inner::Dop853(numerical_from(model, begin, tol)?),
            Method::Rk45 => Inner::Rk45(numerical_from(model, begin, tol)?),
            Method::Hybrid => {
                let free = FreeFlight::new(model.clone())?;
                let contact = Dop853Contact::new(model.clone(), tol);
                Inner::Hybrid(split_from(model, free, contact, begin)?)
            }
            Method::Taylor | Method::Analytic => {
                let free = FreeFlight::new(model.clone())?;
                let contact = TaylorContact::new(model.clone(), tol);
                Inner::Taylor(split_from(model, free, contact, begin)?)
            }
        };
        Ok(MatrixPropagator {
            inner,
            method: options.method,
        })
    }

    /// The method it runs.
    pub fn method(&self) -> Method {
        self.method
    }
}

/// The start of a run: the model's size, finite entries, a finite time.
fn check_start<const CAP: usize>(
    model: &MatrixModel<CAP>,
    time: f64,
    start: &MatrixState<CAP>,
) -> Result<(), PropagationError> {
    if start.dofs() != model.dofs() {
        return Err(MatrixError::Shape {
            what: "start state (positions then velocities)",
            got: 2 * start.dofs(),
            expected: 2 * model.dofs(),
        }
        .into());
    }
    if let Some((i, &x)) = start
        .as_slice()
        .iter()
        .enumerate()
        .find(|(_, x)| !x.is_finite())
    {
        return Err(MatrixError::NonFinite {
            what: "start state",
            index: i,
            value: x,
        }
        .into());
    }
    if !time.is_finite() {
        return Err(PropagationError::InvalidTarget {
            target: time,
            current: time,
        });
    }
    Ok(())
}

macro_rules! each {
    ($self:expr, $p:ident => $e:expr) => {
        match $self {
            Inner::Dop853($p) => $e,
            Inner::Rk45($p) => $e,
            Inner::Hybrid($p) => $e,
            Inner::Taylor($p) => $e,
        }
    };
}

impl<M, const CAP: usize> MatrixPropagator<M, CAP>
where
    M: Deref<Target = MatrixModel<CAP>> + Clone,
{
    /// The slip direction σ the current contact segment runs with (±1 slipping under friction,
    /// 0 otherwise), decided at the segment's start (after `reverse` from λ, not from w, whose
    /// sign at w = 0 is rounding).
    pub fn slip(&self) -> f64 {
        each!(&self.inner, p => p.slip())
    }
}

impl<M, const CAP: usize> Propagate<MatrixState<CAP>> for MatrixPropagator<M, CAP>
where
    M: Deref<Target = MatrixModel<CAP>> + Clone,
{
    fn time(&self) -> f64 {
        each!(&self.inner, p => p.time())
    }

    fn state(&self) -> MatrixState<CAP> {
        each!(&self.inner, p => p.state())
    }

    fn regime(&self) -> Regime {
        each!(&self.inner, p => p.regime())
    }

    fn advance(
        &mut self,
        target: f64,
    ) -> Result<Option<Event<MatrixState<CAP>>>, PropagationError> {
        each!(&mut self.inner, p => p.advance(target))
    }
}
