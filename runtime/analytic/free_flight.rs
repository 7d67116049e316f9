//! Free flight between contacts, shared by the analytic and the hybrid methods: the exact free
//! segment (`model.md` §4) searched for the next contact as time advances, and dropped from the
//! search for good once no contact can ever happen again.

use super::free::{FreeConstants, FreeSegment};
use super::segment::{Point, Segment, point_of};
use super::switch::{Direction, first_crossing_to};
use crate::params::{Params, State};

/// Search chunks between two checks of whether the flight has settled.
const SETTLE_CHECK_CHUNKS: u32 = 8;

/// A free-flight phase from time `t0`.
#[derive(Clone, Copy, Debug)]
pub struct FreeFlight {
    t0: f64,
    segment: FreeSegment,
    searched: f64,
    last: Point,
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
            searched: 0.0,
            last: point_of(state, params.offset_x, params.offset_y),
            settled: false,
            chunk: 0.5 / omega,
        }
    }

    /// Whether the rest of this flight has been proven contact-free.
    pub fn settled(&self) -> bool {
        self.settled
    }

    /// Advance to `target` (not before the last target) or to the next contact entry.
    ///
    /// The search goes chunk by chunk; before the first chunk and every eighth one the orbit's
    /// reach from there on is bounded, so a flight that settles inside the clearance stops
    /// searching within a few chunks, however far the target lies (one closed-form evaluation at
    /// the target then).
    pub fn advance(&mut self, target: f64) -> FreeAdvance {
        let s_target = target - self.t0;
        let mut chunks = 0u32;
        while !self.settled && self.searched < s_target {
            // The reach is checked at the first chunk of every call and every eighth after.
            if chunks.is_multiple_of(SETTLE_CHECK_CHUNKS)
                && self.segment.reach_after(self.searched) < 1.0
            {
                // The orbit's reach stays inside the clearance from here on: no search needed.
                self.settled = true;
                break;
            }
            let b = (self.searched + self.chunk).min(s_target);
            let pb = self.segment.point(b);
            let found = first_crossing_to(
                &self.segment,
                self.searched,
                self.last,
                b,
                pb,
                Direction::Up,
            );
            if let Some((s, p)) = found {
                return FreeAdvance::Contact {
                    time: self.t0 + s,
                    state: p.state,
                };
            }
            self.searched = b;
            self.last = pb;
            chunks += 1;
        }
        if self.searched != s_target || self.settled {
            self.last = self.segment.point(s_target);
            self.searched = s_target;
        }
        FreeAdvance::Reached(self.last.state)
    }
}
