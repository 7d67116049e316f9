//! The stepper's segment solvers: how the shared driver ([`crate::driver::Piecewise`]) takes one
//! fixed step. The driver's state machine strings the pieces of a step together (switch to the
//! next regime's solver, slip direction, divergence), as for every method; what the stepper adds
//! lives here: the step's frame (its start, length and nominal sub-step, the sub-step budget,
//! the caps met) and three solvers that work in the step's local time s ∈ [0, dt]:
//!
//! * [`FreePieces`]: the exact free piece from s to the step end, searched for the next contact
//!   with the capped kernel (`search::locate_with`);
//! * [`Substeps`] of [`Contact`]: equal contact sub-steps of exprb43/exprb2 of at most dt /
//!   `Stepper::contact_substeps()` over the rest of the step, each searched for the exit and
//!   (slipping) the slip velocity's zero; the budget's last sub-step covers the rest without a
//!   search;
//! * [`Substeps`] of [`Rolling`]: rolling sub-steps, one explicit DOP853 step each
//!   (`friction.rs`).
//!
//! The solvers count in local time (the frame's cursor is the local time of the current
//! segment's start), so that every piece and sub-step has the lengths and times the step's grid
//! gives it, whatever the absolute time's rounding.

use crate::driver::SegmentStart;
use core::cell::Cell;

use super::friction::{Slip, SwitchIn, rolling_substep, slip_in};
use super::polynomial::SubstepPolynomial;
use super::report::StepReport;
use super::search::{TOUCH, curvature, locate_with, no_crossing};
use super::{FreeTransition, Stepper, StepperConfig};
use crate::analytic::free::FreeSegment;
use crate::analytic::linear::ContactConstants;
use crate::analytic::schemes::{SubStep, exprb2_with, exprb43_with};
use crate::analytic::segment::{Point, Segment};
use crate::analytic::switch::{Budget, Direction, Search};
use crate::coefficients::Phasor;
use crate::driver::{ByRegime, Located, SegmentSolver, within_bounds};
use crate::field;
use crate::geometry;
use crate::params::{Params, State};
use crate::propagate::{Event, EventKind, PropagationError, Regime};
use crate::registration::ContactScheme;

/// Relative slack when rounding the remaining span to a whole number of nominal sub-steps.
const SUBSTEP_SLACK: f64 = 1e-9;

/// One step's frame, shared by its solvers: where the step starts and how long it is, the
/// nominal contact sub-step, the local time of the current segment's start, the sub-step budget
/// left, and what the step's report accumulates.
pub(super) struct Frame<'a> {
    params: &'a Params,
    config: &'a StepperConfig,
    transition: &'a FreeTransition,
    t0: f64,
    dt: f64,
    /// The forcing phasor (cos θ, sin θ) at `t0` (the stepper's).
    phasor: (f64, f64),
    nominal: f64,
    /// The local time where the current segment starts (set by the solver that reports the
    /// switch ending the previous one).
    cursor: Cell<f64>,
    /// Contact and rolling sub-steps left.
    budget: Cell<u32>,
    substeps: Cell<u32>,
    capped: Cell<bool>,
    search_capped: Cell<bool>,
    error_estimate: Cell<f64>,
    /// The budget ran out before the step's end: its last sub-step went to the end without a
    /// search, and the regime at the end is to be read from the end state.
    exhausted: Cell<bool>,
}

impl<'a> Frame<'a> {
    /// The frame of a step of `dt` from `t0` (the stepper's time, phasor, parameters,
    /// configuration and free map).
    pub(super) fn new(stepper: &'a Stepper, t0: f64, dt: f64) -> Self {
        let config = &stepper.config;
        Frame {
            params: &stepper.params,
            config,
            transition: &stepper.transition,
            t0,
            dt,
            phasor: stepper.phasor,
            // The configured count, or more where the stator is too stiff for it (the
            // transition is the one of this step's dt).
            nominal: dt / f64::from(stepper.contact_substeps()),
            cursor: Cell::new(0.0),
            budget: Cell::new(config.max_substeps),
            substeps: Cell::new(0),
            capped: Cell::new(false),
            search_capped: Cell::new(false),
            error_estimate: Cell::new(0.0),
            exhausted: Cell::new(false),
        }
    }

    /// What the step's report accumulated: sub-steps, caps and error estimate.
    pub(super) fn report_into(&self, report: &mut StepReport) {
        report.substeps = self.substeps.get();
        report.capped = self.capped.get();
        report.search_capped = self.search_capped.get();
        report.error_estimate = self.error_estimate.get();
    }

    /// Whether the budget ran out before the step's end (see the field).
    pub(super) fn exhausted(&self) -> bool {
        self.exhausted.get()
    }

    /// A switch `sx` into the piece that starts at local time `s`: the event (at (t0 + s) + sx,
    /// the piece's own time plus its local time), with the cursor moved to s + sx.
    fn switch_at(&self, s: f64, sx: f64, state: State, kind: EventKind) -> Located {
        self.cursor.set(s + sx);
        Located::Switch(Event {
            time: (self.t0 + s) + sx,
            kind,
            state,
        })
    }

    /// The switch of a capped search, if any; a capped search is flagged.
    fn resolve(&self, found: Search<Point>) -> Option<(f64, Point)> {
        match found {
            Search::None => None,
            Search::Unresolved => {
                self.search_capped.set(true);
                None
            }
            Search::Found { s, point, certain } => {
                if !certain {
                    self.search_capped.set(true);
                }
                Some((s, point))
            }
        }
    }

    /// The next sub-step's length from local time `s` (whole nominal sub-steps over the rest,
    /// equal lengths, no slivers), counted against the budget; `None` when the budget is spent
    /// (the caller covers the rest at once, unsearched).
    fn next_substep(&self, s: f64) -> Option<f64> {
        let rem = self.dt - s;
        let budget = self.budget.get();
        if budget == 0 {
            self.capped.set(true);
            self.exhausted.set(true);
            return None;
        }
        let k = whole_substeps(rem / self.nominal);
        let h = if budget == 1 && k > 1 {
            self.capped.set(true);
            rem
        } else {
            rem / f64::from(k)
        };
        self.budget.set(budget - 1);
        Some(h)
    }

    fn counted(&self, error: f64) {
        self.substeps.set(self.substeps.get() + 1);
        self.error_estimate
            .set(self.error_estimate.get().max(error));
    }
}

/// ⌈q − slack⌉, at least 1 (q ≤ `MAX_SUBSTEPS` here; the cast saturates, never panics).
fn whole_substeps(q: f64) -> u32 {
    let q = q - SUBSTEP_SLACK;
    let k = q as u32;
    let k = if f64::from(k) < q {
        k.saturating_add(1)
    } else {
        k
    };
    k.max(1)
}

/// Free flight from the cursor to the step's end: one closed-form piece, searched once.
pub(super) struct FreePieces<'f, 'a> {
    frame: &'f Frame<'a>,
    /// The piece's start (local time) and state there.
    start: (f64, State),
}

impl SegmentSolver for FreePieces<'_, '_> {
    fn start(&mut self, at: SegmentStart) -> Result<(), PropagationError> {
        let state = at.state;
        self.start = (self.frame.cursor.get(), state);
        Ok(())
    }

    fn locate(&mut self, _target: f64) -> Located {
        let f = self.frame;
        let (s, state) = self.start;
        let (t, rem) = (f.t0 + s, f.dt - s);
        let tr = f.transition;
        let model = tr.constants().model();
        let start = geometry::point(model, state);
        // h holds frequencies up to 2·max(η, 1): chunks as in `FreeFlight`.
        let chunk = 0.5 / f.params.speed_ratio.max(1.0 + f.params.damping_ratio);
        // The forcing phasor at the piece's start: the stepper's at the step start, else
        // computed from the time.
        let phasor = if s == 0.0 {
            f.phasor
        } else {
            let (ct, st) = f.phasor;
            let turned = field::phasor_after(model, &Phasor { ct, st }, s);
            (turned.ct, turned.st)
        };
        // The piece as its Taylor polynomial (`polynomial.rs`: the free closed form to far
        // below rounding, cheaper to evaluate); a piece from the step start ends where the
        // free map takes it.
        let (found, end) = match SubstepPolynomial::free(model, &start, phasor, rem) {
            Some(poly) => {
                let end = if s == 0.0 && rem == tr.dt() {
                    geometry::point(model, tr.apply(&state, phasor))
                } else {
                    poly.point(rem)
                };
                (entry_on(&poly, start, (rem, end), chunk, f), end)
            }
            None => {
                let seg = FreeSegment::with_offset_distance(
                    f.params,
                    tr.constants(),
                    tr.offset_distance(),
                    t,
                    state,
                );
                let end = seg.point(rem);
                (entry_on(&seg, start, (rem, end), chunk, f), end)
            }
        };
        match f.resolve(found) {
            Some((se, p)) => f.switch_at(s, se, p.state, EventKind::Enter),
            None => Located::Reached(end.state),
        }
    }

    fn step(&mut self) -> Result<(), PropagationError> {
        Ok(())
    }

    fn computed_to(&self) -> f64 {
        self.frame.t0 + self.frame.dt
    }
}

/// Where a contact or rolling segment is within its sub-steps.
#[derive(Clone, Copy)]
struct Progress {
    /// The current sub-step's start (local time) and state there.
    s: f64,
    state: State,
    /// The current sub-step's length and whether it ends the step (`None` before the first).
    current: Option<(f64, bool)>,
    /// Its end state, and the switch in it (local time from its start, state, kind).
    end: State,
    found: Option<SwitchIn>,
}

impl Progress {
    fn at(s: f64, state: State) -> Self {
        Progress {
            s,
            state,
            current: None,
            end: state,
            found: None,
        }
    }

    /// What the current sub-step says of the step's end: its switch, its end when it ends the
    /// step, else the next sub-step is needed.
    fn locate(&self, frame: &Frame<'_>) -> Located {
        let Some((_, ends_step)) = self.current else {
            return Located::NeedStep;
        };
        match self.found {
            Some((sx, p, kind)) => frame.switch_at(self.s, sx, p, kind),
            None if ends_step => Located::Reached(self.end),
            None => Located::NeedStep,
        }
    }

    /// Move to the next sub-step's start (the end of the current one, which held no switch);
    /// its length from the budget, `None` when spent (then the rest of the step at once).
    fn advance(&mut self, frame: &Frame<'_>) -> Option<f64> {
        if let Some((h, _)) = self.current {
            self.s += h;
            self.state = self.end;
        }
        frame.next_substep(self.s)
    }

    fn computed_to(&self, frame: &Frame<'_>) -> f64 {
        frame.t0 + self.s + self.current.map_or(0.0, |(h, _)| h)
    }
}

/// A sub-step's start: local time `s`, `state` there, length `h`.
pub(super) type Substart = (f64, State, f64);

/// A sub-step taken: its end state and (when searched) the first switch in it.
pub(super) type Taken = Result<(State, Option<SwitchIn>), PropagationError>;

/// One kind of sub-step: how a sub-step of length `h` from `state` at local time `s` is taken,
/// with its end state and (when `search`) the first switch in it.
pub(super) trait SubstepKind {
    fn take(&mut self, frame: &Frame<'_>, slip: &Slip, from: Substart, search: bool) -> Taken;
}

/// Contact sub-steps of exprb43/exprb2, written into a slot on the step's stack (a sub-step is
/// too large to move around).
pub(super) struct Contact<'f>(&'f mut SubStep);

impl SubstepKind for Contact<'_> {
    fn take(&mut self, f: &Frame<'_>, slip: &Slip, (s, state, h): Substart, search: bool) -> Taken {
        let t = f.t0 + s;
        // The contact constants are built per sub-step rather than kept in the stepper: a copy
        // of the parameters and one generated gain (a few ns against a sub-step's hundreds),
        // where a kept copy made every stepper 112 bytes larger, two cache lines that each cold
        // step and parameter change pays (`benches/stepper.rs`).
        let contact = &ContactConstants::new(f.params);
        let sub = &mut *self.0;
        match f.config.scheme {
            ContactScheme::Exprb2 => exprb2_with(contact, slip.sigma, t, state, h, sub),
            ContactScheme::Exprb43 => exprb43_with(contact, slip.sigma, t, state, h, 1.0, sub),
        }
        .map_err(|_| PropagationError::SingularContact { time: t })?;
        if !within_bounds(&sub.end) {
            return Err(PropagationError::Diverged {
                time: t + h,
                state: sub.end,
            });
        }
        f.counted(sub.error);
        if !search {
            return Ok((sub.end, None));
        }
        // The exit on the sub-step's continuous extension, then the slip velocity's zero before it.
        let model = f.transition.constants().model();
        let (start, end) = (
            geometry::point(model, state),
            geometry::point(model, sub.end),
        );
        let exit = f
            .resolve(exit_search(sub, start, end, f.config.budget()))
            .map(|(sx, p)| (sx, p.state, EventKind::Exit));
        let limit = exit.map_or(sub.length, |(sx, _, _)| sx);
        let slipped = slip_in(sub, t, state, slip, limit, f.config.budget());
        Ok((sub.end, slipped.or(exit)))
    }
}

/// The exit (z = 1 downward) in the contact sub-step `sub` from `state`, with the points at its
/// ends: the sub-step proved exit-free by one bound test on its closed form (the common contact
/// step, as [`locate_with`]'s first test decides it), else located on the sub-step's Taylor
/// polynomial ([`SubstepPolynomial`]: the same function to far below rounding, a Horner sum per
/// evaluation instead of the closed form's transcendental functions), or on the closed form
/// when the sub-step is too long for the polynomial.
fn exit_search(sub: &SubStep, start: Point, end: Point, budget: &Budget) -> Search<Point> {
    let len = sub.length;
    // g = −h on the way out; the start counts as inside (g ≤ 0) whatever its rounding.
    let (ga, dga, gb, dgb) = (-start.h, -start.dh, -end.h, -end.dh);
    if gb <= TOUCH && len > budget.min_interval * (1.0 + len) {
        let m2 = curvature(&sub.segment, 0.0, &start, len);
        if no_crossing(ga.min(0.0), dga, gb, dgb, m2, len, TOUCH) {
            return Search::None;
        }
    }
    match SubstepPolynomial::contact(&sub.segment, &start, len) {
        Some(poly) => locate_with(
            &poly,
            (0.0, start),
            (len, end),
            Direction::Down,
            len,
            budget,
        ),
        None => locate_with(
            &sub.segment,
            (0.0, start),
            (len, end),
            Direction::Down,
            len,
            budget,
        ),
    }
}

/// Rolling sub-steps: one explicit DOP853 step each (`friction.rs`).
pub(super) struct Rolling;

impl SubstepKind for Rolling {
    fn take(&mut self, f: &Frame<'_>, slip: &Slip, (s, state, h): Substart, search: bool) -> Taken {
        let (end, found) = rolling_substep(f.params, f.t0 + s, state, h, slip)?;
        f.counted(0.0);
        Ok((end, if search { found } else { None }))
    }
}

/// Contact or rolling sub-steps from the cursor to the step's end: equal sub-steps of at most
/// the nominal one, the budget's last covering the rest unsearched.
pub(super) struct Substeps<'f, 'a, K> {
    frame: &'f Frame<'a>,
    slip: Slip,
    progress: Progress,
    kind: K,
}

impl<K: SubstepKind> SegmentSolver for Substeps<'_, '_, K> {
    fn start(&mut self, at: SegmentStart) -> Result<(), PropagationError> {
        let (regime, slip, time, state) = (at.regime, at.slip, at.time, at.state);
        let f = self.frame;
        self.slip = Slip::of(f.params, regime, time, &state, slip);
        self.progress = Progress::at(f.cursor.get(), state);
        Ok(())
    }

    fn locate(&mut self, _target: f64) -> Located {
        self.progress.locate(self.frame)
    }

    fn step(&mut self) -> Result<(), PropagationError> {
        let f = self.frame;
        let next = self.progress.advance(f);
        let (s, state) = (self.progress.s, self.progress.state);
        let rem = f.dt - s;
        // Budget spent: one last sub-step to the end, its switches not searched.
        let (h, search) = next.map_or((rem, false), |h| (h, true));
        let (end, found) = self.kind.take(f, &self.slip, (s, state, h), search)?;
        self.progress.current = Some((h, !search || h == rem));
        self.progress.end = end;
        self.progress.found = found;
        Ok(())
    }

    fn computed_to(&self) -> f64 {
        self.progress.computed_to(self.frame)
    }
}

/// The stepper's solvers of one step, by regime.
pub(super) type StepSolvers<'f, 'a> =
    ByRegime<FreePieces<'f, 'a>, Substeps<'f, 'a, Contact<'f>>, Substeps<'f, 'a, Rolling>>;

/// The solvers of the step framed by `frame`, the one of `regime` starting at its start in
/// `state` with the segment's carried `slip`; contact sub-steps are written into `sub`.
pub(super) fn step_solvers<'f, 'a>(
    frame: &'f Frame<'a>,
    sub: &'f mut SubStep,
    regime: Regime,
    state: State,
    slip: Slip,
) -> StepSolvers<'f, 'a> {
    let at = Progress::at(0.0, state);
    let carried = |r: Regime| if r == regime { slip } else { Slip::NONE };
    ByRegime {
        free: FreePieces {
            frame,
            start: (0.0, state),
        },
        contact: Substeps {
            frame,
            slip: carried(Regime::Contact),
            progress: at,
            kind: Contact(sub),
        },
        rolling: Substeps {
            frame,
            slip: carried(Regime::Rolling),
            progress: at,
            kind: Rolling,
        },
    }
}

/// The slip of the segment in progress in `regime` (carried to the next step).
pub(super) fn carried_slip(solvers: &StepSolvers<'_, '_>, regime: Regime) -> Slip {
    match regime {
        Regime::Contact => solvers.contact.slip,
        Regime::Rolling => solvers.rolling.slip,
        Regime::Free => Slip::NONE,
    }
}

/// The first contact entry on a free piece `seg` from `start` (local time 0) to `end` at
/// `rem`, with the step's capped budget.
fn entry_on<S: Segment>(
    seg: &S,
    start: Point,
    end: (f64, Point),
    chunk: f64,
    f: &Frame,
) -> Search<Point> {
    locate_with(
        seg,
        (0.0, start),
        end,
        Direction::Up,
        chunk,
        f.config.budget(),
    )
}
