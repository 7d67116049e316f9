//! Free flight between contacts, shared by the analytic and the hybrid methods: the exact free
//! segment (`model.md` §4) searched for the next contact as time advances, and dropped from the
//! search for good once no contact can ever happen again.

use super::free::{FreeConstants, FreeSegment};
use super::segment::{Point, Segment, point_of};
use super::switch::{Direction, first_crossing};
use crate::params::{Params, State};

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
    pub fn advance(&mut self, target: f64) -> FreeAdvance {
        let s_target = target - self.t0;
        if !self.settled && self.segment.reach_after(self.searched) < 1.0 {
            // The orbit's reach stays inside the clearance from here on: no search needed.
            self.settled = true;
        }
        if !self.settled {
            let found = first_crossing(
                &self.segment,
                self.searched,
                self.last,
                s_target,
                Direction::Up,
                self.chunk,
            );
            if let Some((s, p)) = found {
                return FreeAdvance::Contact {
                    time: self.t0 + s,
                    state: p.state,
                };
            }
        }
        let p = self.segment.point(s_target);
        self.searched = s_target;
        self.last = p;
        FreeAdvance::Reached(p.state)
    }
}
