//! Free flight between contacts, shared by the analytic, hybrid and taylor methods: the exact
//! free segment (`docs/MODEL.md` §4, §11) searched for the next contact as time advances, and
//! dropped from the search for good once no contact can ever happen again ([`FreeFlight`]), as
//! the driver's free-flight [`SegmentSolver`] ([`FreeFlightSolver`]).
//!
//! The search runs on a fixed grid of chunks k·Δ in local time, independent of the targets it is
//! asked for: a target inside a chunk searches the whole chunk and keeps a crossing found beyond
//! the target for later. So sampling (any sequence of targets) never moves a switch, and the state
//! at a target is always the closed form evaluated from the segment start (`docs/MODEL.md` §13).

use super::free::{FreeConstants, FreeSegment};
use super::segment::{Point, Segment};
use super::switch::{Direction, first_crossing_to};
use crate::driver::SegmentStart;
use crate::driver::{Located, SegmentSolver, switch_time};
use crate::geometry;
use crate::params::{Params, State};
use crate::propagate::{Event, EventKind, PropagationError};

/// Search chunks between two checks of whether the flight has settled.
const SETTLE_CHECK_CHUNKS: u64 = 8;

/// A free-flight phase from time `t0`.
#[derive(Clone, Copy, Debug)]
pub struct FreeFlight {
    t0: f64,
    segment: FreeSegment,
    /// Chunks searched so far: (0, chunks·Δ] is proven contact-free unless `found` is set.
    chunks: u64,
    /// The point at the end of the searched range.
    last: Point,
    /// The first contact entry, once a chunk found it (possibly beyond the last target).
    found: Option<(f64, Point)>,
    settled: bool,
    chunk: f64,
}

/// What advancing a free flight found.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FreeAdvance {
    /// The target time was reached in free flight, at this state.
    Reached(State),
    /// Contact starts at `time` in `state` (on z = 1), before the target.
    Contact {
        /// Entry time.
        time: f64,
        /// State at entry.
        state: State,
    },
}

impl FreeFlight {
    /// Free flight through `state` at time `t0`.
    pub fn new(params: &Params, constants: &FreeConstants, t0: f64, state: State) -> Self {
        // h = z² − 1 holds frequencies up to 2·max(η, 1): search chunks of a twelfth of the
        // fastest period keep the interval bounds tight.
        let omega = params.speed_ratio.max(1.0 + params.damping_ratio);
        FreeFlight {
            t0,
            segment: FreeSegment::new(params, constants, t0, state),
            chunks: 0,
            last: geometry::point(constants.model(), state),
            found: None,
            settled: false,
            chunk: 0.5 / omega,
        }
    }

    /// Whether the rest of this flight has been proven contact-free.
    pub fn settled(&self) -> bool {
        self.settled
    }

    /// The local time of the end of the searched range.
    fn searched(&self) -> f64 {
        self.chunks as f64 * self.chunk
    }

    /// Advance to `target` (not before the last target) or to the next contact entry.
    ///
    /// The search goes chunk by chunk on the fixed grid; before every eighth chunk (counted from
    /// the segment start) the orbit's reach from there on is bounded, so a flight that settles
    /// inside the clearance stops searching within a few chunks, however far the target lies
    /// (one closed-form evaluation at the target then).
    pub fn advance(&mut self, target: f64) -> FreeAdvance {
        let s_target = target - self.t0;
        while self.found.is_none() && !self.settled && self.searched() < s_target {
            if self.chunks.is_multiple_of(SETTLE_CHECK_CHUNKS)
                && self.segment.reach_after(self.searched()) < 1.0
            {
                // The orbit's reach stays inside the clearance from here on: no search needed.
                self.settled = true;
                break;
            }
            let (a, b) = (self.searched(), (self.chunks + 1) as f64 * self.chunk);
            let pb = self.segment.point(b);
            self.found = first_crossing_to(&self.segment, a, self.last, b, pb, Direction::Up);
            self.chunks += 1;
            self.last = pb;
        }
        match self.found {
            Some((s, p)) if s <= s_target => {
                let (time, at) = switch_time(self.t0, s);
                let state = if at == s {
                    p.state
                } else {
                    self.segment.point(at).state
                };
                FreeAdvance::Contact { time, state }
            }
            _ => FreeAdvance::Reached(self.segment.point(s_target).state),
        }
    }
}

/// Free flight in closed form, searched for the next contact (`docs/MODEL.md` §4): serves every
/// target in [`SegmentSolver::locate`], never asks for a step.
pub struct FreeFlightSolver {
    params: Params,
    constants: FreeConstants,
    flight: FreeFlight,
    located: f64,
}

impl FreeFlightSolver {
    /// A solver for `params`, with a flight started at `(time, state)`.
    #[inline]
    pub fn new(params: &Params, time: f64, state: State) -> Self {
        let constants = FreeConstants::new(params);
        FreeFlightSolver {
            params: *params,
            constants,
            flight: FreeFlight::new(params, &constants, time, state),
            located: time,
        }
    }
}

impl SegmentSolver for FreeFlightSolver {
    fn start(&mut self, at: SegmentStart) -> Result<(), PropagationError> {
        let (time, state) = (at.time, at.state);
        self.flight = FreeFlight::new(&self.params, &self.constants, time, state);
        self.located = time;
        Ok(())
    }

    fn locate(&mut self, target: f64) -> Located {
        match self.flight.advance(target) {
            FreeAdvance::Reached(state) => {
                self.located = target;
                Located::Reached(state)
            }
            FreeAdvance::Contact { time, state } => Located::Switch(Event {
                time,
                kind: EventKind::Enter,
                state,
            }),
        }
    }

    fn step(&mut self) -> Result<(), PropagationError> {
        Ok(())
    }

    fn computed_to(&self) -> f64 {
        self.located
    }
}
