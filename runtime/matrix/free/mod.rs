//! Exact free flight of a rotor from matrices, searched for every contact with a proof
//! (`docs/MODEL.md` §17; issue 29 item 2, issue 28 item 3): the free-flight segment solver
//! [`ExactFree`] of the matrix methods (hybrid and analytic run it between contacts).
//!
//! # Free flight, to rounding
//! Between contacts M q'' + (C + ηG) q' + K q = η² Re(f̂ e^{iθ}) + u is linear, so
//! y(t) = y_p(t) + e^{A(t − t0)} (y0 − y_p(t0)) exactly (`flight.rs`):
//! - e^{As} in the stable modal form A = S J S⁻¹ of [`crate::linalg::ModalExponential`]
//!   (defective and near-defective clusters stay triangular blocks, never diagonalized; purely
//!   imaginary modes, zero and repeated eigenvalues included), one evaluation for any span: the
//!   cost per forcing period does not depend on any tolerance;
//! - y_p = Re(Y e^{iθ}) + (K⁻¹u, 0) from [`crate::linalg::HarmonicResponse`] with the one
//!   forcing phase θ (`field::phasor`). A singular dynamic stiffness K − η²M + iη(C + ηG) (an
//!   undamped mode exactly at η) has a particular solution when the unbalance does not force
//!   that mode (the stator ring's modes in free flight): it is solved as such. A forced
//!   undamped mode at η has none: [`ExactFree::new`] refuses it with
//!   `MatrixError::Linalg(LinalgError::Resonance { speed_ratio })`, naming η (no secular
//!   particular solution). Likewise a constant force along a free rigid-body mode
//!   (`LinalgError::StaticSingular`); a rigid-body mode without one is exact.
//!
//! Near (not at) resonance of a lightly damped forced mode the particular and homogeneous
//! parts are both large and cancel: the error is then ε times the dynamic stiffness's
//! condition number relative to the response (`linalg/harmonic.rs`).
//!
//! # Every contact, with a proof
//! `search.rs`: h(s) = z² − 1 of the station's relative position, with rigorous bounds of the
//! station's motion over any interval, searched by the one switch kernel
//! (`analytic::switch`) whose interval certificate is the same proof as for n = 2; the proof
//! sketch is in `search.rs`. Every switch is refined by `runtime/refine.rs` (through the
//! kernel) with the bands of `runtime/rounding.rs`.
//!
//! # The solver
//! [`ExactFree::start`] begins a segment (O(m²): the start's modal coordinates);
//! [`ExactFree::locate`] serves a target inside the proved-free horizon in closed form
//! (O(m²), no steps), reports the first contact at or before it, or asks for a step;
//! [`ExactFree::step`] extends the horizon chunk by chunk (O(m) per evaluation and per bound)
//! up to the last target asked for. The chunk grid depends on the segment only.
//!
//! - `flight.rs`: the decomposition and one segment's closed form, points and bounds.
//! - `search.rs`: the event function, the grid and the proof sketch.

mod flight;
mod search;

use crate::driver::SegmentStart;
use core::cell::Cell;
use core::ops::Deref;

use self::flight::{Decomposition, Flight, StationPoint};
use self::search::{
    CHUNK_RANGE, ChunkResult, SETTLE_CHECK_CHUNKS, SPLIT_TESTS, StationSwitch, search_chunk,
};
use super::error::MatrixError;
use super::model::MatrixModel;
use super::state::MatrixState;
use crate::analytic::switch::EventFunction;
use crate::driver::{Located, SegmentSolver};
use crate::linalg::{Complex, LinalgError, ProjectedMotion};
use crate::propagate::{Event, EventKind, PropagationError};

/// Work counters of an [`ExactFree`] since it was made (benches and diagnostics).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FreeWork {
    /// Segments started.
    pub segments: u64,
    /// Chunks searched.
    pub chunks: u64,
    /// Evaluations of the station's motion (O(m) each): chunk ends, splits, refinements.
    pub evaluations: u64,
    /// Interval bound tests (O(m) each).
    pub bound_tests: u64,
    /// Contacts found (each refined to rounding by `runtime/refine.rs`).
    pub contacts: u64,
    /// Of those, contacts whose refinement or proof hit the kernel's cap.
    pub uncertain: u64,
    /// Chunk parts left unresolved after the retries: h within rounding of 0 along a stretch,
    /// taken as a touch (`search.rs`).
    pub unresolved: u64,
    /// Flights proved contact-free for all later times (searched no more).
    pub settled: u64,
    /// Full states evaluated (O(m²) each): targets and contact states.
    pub states: u64,
}

/// Exact free flight of a matrix model with its contact search (module docs): the
/// [`SegmentSolver`] of the free regime. `M` is any pointer to the model: `&MatrixModel` in
/// `no_std`, `Arc<MatrixModel>` in the CLI and Python.
///
/// Size: the modal form's five complex CAP × CAP matrices plus O(CAP) (5 KiB at CAP = 8,
/// 1.3 MiB at CAP = 128: box it there).
#[derive(Clone, Debug)]
pub struct ExactFree<M, const CAP: usize> {
    model: M,
    decomposition: Decomposition<CAP>,
    flight: Flight<CAP>,
    /// Local time up to which the flight is proved free, and the station there.
    horizon: f64,
    last: StationPoint,
    /// The next chunk's length, and its bounds.
    chunk: f64,
    longest: f64,
    /// Chunks searched in this segment.
    chunks: u64,
    /// The first contact (local time, event), once found.
    found: Option<(f64, Event<MatrixState<CAP>>)>,
    settled: bool,
    /// The last target asked for beyond the horizon (local time).
    wanted: f64,
    work: FreeWork,
}

impl<M: Deref<Target = MatrixModel<CAP>> + Clone, const CAP: usize> ExactFree<M, CAP> {
    /// Decompose the model once (modal exponential, harmonic and constant responses,
    /// projections on the station).
    ///
    /// # Errors
    /// [`PropagationError::InvalidModel`] with the [`LinalgError`] of a decomposition that
    /// fails, `Resonance { speed_ratio }` for a forced undamped mode at the running speed,
    /// `StaticSingular` for an input force along a free rigid-body mode.
    pub fn new(model: M) -> Result<Self, PropagationError> {
        let invalid = |e: LinalgError| PropagationError::InvalidModel(MatrixError::Linalg(e));
        let m = 2 * model.dofs();
        let (mut bx, mut by) = ([0.0; CAP], [0.0; CAP]);
        let station = *model.station();
        for (row, (r, s)) in [
            (&mut bx, (station.rotor.0, station.stator.map(|s| s.0))),
            (&mut by, (station.rotor.1, station.stator.map(|s| s.1))),
        ] {
            if let Some(x) = row.get_mut(r) {
                *x = 1.0;
            }
            if let Some(x) = s.and_then(|s| row.get_mut(s)) {
                *x = -1.0;
            }
        }
        let (bx, by) = (bx.get(..m).unwrap_or(&[]), by.get(..m).unwrap_or(&[]));
        let decomposition = Decomposition::new(&model, bx, by).map_err(invalid)?;
        let motion = ProjectedMotion::new(&decomposition.modal, bx, by).map_err(invalid)?;
        let y0 = MatrixState::rest(model.dofs())?;
        // A quarter of the forcing period: the longest chunk.
        let longest = 0.5 * core::f64::consts::PI / model.speed_ratio();
        let mut solver = ExactFree {
            decomposition,
            flight: Flight {
                t0: 0.0,
                y0,
                motion,
                phase0: Complex::ONE,
            },
            horizon: 0.0,
            last: StationPoint {
                h: -1.0,
                dh: 0.0,
                rate: [0.0; 2],
            },
            chunk: longest,
            longest,
            chunks: 0,
            found: None,
            settled: false,
            wanted: 0.0,
            work: FreeWork::default(),
            model,
        };
        solver.begin(0.0, y0).map_err(invalid)?;
        solver.work = FreeWork::default();
        Ok(solver)
    }

    /// The work counters since the solver was made.
    pub fn work(&self) -> FreeWork {
        self.work
    }

    /// The model.
    pub fn model(&self) -> &M {
        &self.model
    }

    /// Start a flight at `(time, state)`.
    fn begin(&mut self, time: f64, state: MatrixState<CAP>) -> Result<(), LinalgError> {
        self.flight
            .start(&self.model, &self.decomposition, time, state)?;
        self.horizon = 0.0;
        self.last = self.flight.start_point(&self.model, &self.decomposition);
        self.chunk = self.longest / 8.0;
        self.chunks = 0;
        self.found = None;
        self.settled = false;
        self.wanted = 0.0;
        self.work.segments += 1;
        self.work.evaluations += 1;
        Ok(())
    }

    /// The state at local time `s` (closed form from the segment start).
    fn state_at(&mut self, s: f64) -> MatrixState<CAP> {
        self.work.states += 1;
        self.flight.state(&self.model, &self.decomposition, s)
    }

    /// Search chunks until the horizon reaches `wanted` (local time), a contact is found or
    /// the flight has settled; at least one chunk.
    fn search_to(&mut self, wanted: f64) {
        let mut first = true;
        while self.found.is_none() && !self.settled && (first || self.horizon < wanted) {
            first = false;
            // The reach over all later times is at least the station's distance where the
            // search stands: on or outside the clearance (h ≥ 0, a start just after a contact)
            // it cannot settle, and is not bounded.
            if self.chunks.is_multiple_of(SETTLE_CHECK_CHUNKS)
                && self.last.h < 0.0
                && self
                    .flight
                    .reach_after(&self.decomposition, self.horizon)
                    .radius
                    < 1.0
            {
                self.settled = true;
                self.work.settled += 1;
                break;
            }
            let (a, b) = (self.horizon, self.horizon + self.chunk);
            let f = StationSwitch {
                model: &self.model,
                decomposition: &self.decomposition,
                flight: &self.flight,
                evaluations: Cell::new(0),
                tests: Cell::new(0),
            };
            let pb = f.point(b);
            let result = search_chunk(&f, a, self.last, b, pb);
            let (evaluations, tests) = (f.evaluations.get(), f.tests.get());
            self.work.evaluations += evaluations;
            self.work.bound_tests += tests;
            self.work.chunks += 1;
            self.chunks += 1;
            match result {
                ChunkResult::Free { unresolved } => {
                    self.work.unresolved += u64::from(unresolved);
                    self.horizon = b;
                    self.last = pb;
                    self.chunk = if tests <= 1 {
                        (2.0 * self.chunk).min(self.longest)
                    } else if tests > SPLIT_TESTS {
                        (0.5 * self.chunk).max(self.longest / CHUNK_RANGE)
                    } else {
                        self.chunk
                    };
                }
                ChunkResult::Contact { s, at, certain } => {
                    if at.dh < 0.0 {
                        // h falling through 0 is no contact: the closed form's rounding
                        // (≈ 1e-14) above TOUCH just after a start on z = 1 moving outward (an
                        // exit). Free up to s; the search goes on from there (g clamped to ≤ 0
                        // again).
                        self.horizon = s;
                        self.last = at;
                        continue;
                    }
                    self.work.contacts += 1;
                    self.work.uncertain += u64::from(!certain);
                    let state = self.state_at(s);
                    self.found = Some((
                        s,
                        Event {
                            time: self.flight.t0 + s,
                            kind: EventKind::Enter,
                            state,
                        },
                    ));
                }
            }
        }
    }
}

impl<M: Deref<Target = MatrixModel<CAP>> + Clone, const CAP: usize> SegmentSolver<MatrixState<CAP>>
    for ExactFree<M, CAP>
{
    /// A free segment from `(time, state)` (any regime is taken as free flight: this solver
    /// serves the free regime).
    fn start(&mut self, at: SegmentStart<MatrixState<CAP>>) -> Result<(), PropagationError> {
        let (time, state) = (at.time, at.state);
        if state.dofs() != self.model.dofs() {
            return Err(PropagationError::InvalidModel(MatrixError::Shape {
                what: "state",
                got: state.as_slice().len(),
                expected: 2 * self.model.dofs(),
            }));
        }
        self.begin(time, state)
            .map_err(|e| PropagationError::InvalidModel(MatrixError::Linalg(e)))
    }

    fn locate(&mut self, target: f64) -> Located<MatrixState<CAP>> {
        let s = target - self.flight.t0;
        if let Some((at, event)) = self.found {
            if at <= s {
                return Located::Switch(event);
            }
            return Located::Reached(self.state_at(s));
        }
        if s <= self.horizon || self.settled {
            return Located::Reached(self.state_at(s));
        }
        self.wanted = s;
        Located::NeedStep
    }

    fn step(&mut self) -> Result<(), PropagationError> {
        self.search_to(self.wanted);
        Ok(())
    }

    fn computed_to(&self) -> f64 {
        match self.found {
            Some((_, event)) => event.time,
            None if self.settled => self.flight.t0 + self.horizon.max(self.wanted),
            None => self.flight.t0 + self.horizon,
        }
    }
}
