//! What a run does in each turn of the unbalance (a forcing period at a changing speed): the
//! orbit's largest and smallest radius, the time in contact, the whirl and the switches —
//! the rows of a run-up diagram (`docs/MODEL.md` §14).
//!
//! Revolution k spans the forcing phase θ from θ_0 + 2πk to θ_0 + 2π(k + 1), θ_0 the phase where
//! the tracking starts; at a constant speed these are the forcing periods of the Poincaré
//! section. Each revolution is sampled at equal steps of phase, and every switch inside it is a
//! node too. The radius r = |q| (from the rotor's rest position) is interpolated between nodes
//! by the cubic Hermite polynomial of r² through their values and slopes 2 q·q' (r² is C¹ across
//! switches), so its extremes are found to fourth order in the node spacing rather than only at
//! the samples.

use core::f64::consts::TAU;

use super::period::Accumulator;
use super::period::Revolution;
use crate::propagate::{Event, EventKind, Propagate, PropagationError};
use crate::speed::{SpeedPiece, SpeedProfile};

/// The revolutions of a run on a speed profile, one at a time (see the module documentation).
pub struct Revolutions<'p, 'a, P: ?Sized> {
    propagator: &'p mut P,
    profile: SpeedProfile<'a>,
    cursor: SpeedPiece,
    phase_origin: f64,
    samples: u32,
    next_index: u64,
    count: u64,
}

impl<'p, 'a, P: Propagate + ?Sized> Revolutions<'p, 'a, P> {
    /// The revolutions of `propagator` (running on `profile`, forcing phase φ0 = `phase` as in
    /// [`SpeedProfile::first_piece`]) from its current time until the profile's end (whole
    /// revolutions only), each sampled at `samples` equal steps of phase (at least 8; the
    /// whirl needs less than half a whirl turn between samples).
    pub fn new(propagator: &'p mut P, profile: SpeedProfile<'a>, phase: f64, samples: u32) -> Self {
        let now = propagator.time();
        let cursor = profile.piece_holding(profile.first_piece(phase), now);
        let phase_origin = cursor.phase_at(now);
        let last = profile.piece_holding(cursor, profile.end());
        let turns = (last.phase_at(profile.end()) - phase_origin) / TAU;
        // A rounding below a whole number of turns still counts that turn.
        let count = libm::floor(turns + 1e-9).max(0.0) as u64;
        Revolutions {
            propagator,
            profile,
            cursor,
            phase_origin,
            samples: samples.max(8),
            next_index: 0,
            count,
        }
    }

    /// The number of revolutions the iteration yields in all (not `Iterator::count`, which
    /// would run them).
    pub fn total(&self) -> u64 {
        self.count
    }

    /// The time at which the phase reaches θ_0 + 2π·`turns`.
    fn time_of(&mut self, turns: f64) -> f64 {
        let phase = self.phase_origin + TAU * turns;
        loop {
            if let Some(t) = self.cursor.time_of_phase(phase) {
                return t;
            }
            match self.profile.next_piece(&self.cursor) {
                Some(next) => self.cursor = next,
                None => return self.cursor.end,
            }
        }
    }

    /// The next revolution, passing each switch inside it to `on_event`; `None` after the last.
    pub fn next_with(
        &mut self,
        mut on_event: impl FnMut(&Event),
    ) -> Option<Result<Revolution, PropagationError>> {
        if self.next_index >= self.count {
            return None;
        }
        let index = self.next_index;
        self.next_index += 1;
        let start = self.propagator.time();
        let speed_start = self
            .profile
            .piece_holding(self.cursor, start)
            .speed_at(start);
        let mut acc = Accumulator::new(start, self.propagator.state());
        let n = f64::from(self.samples);
        for j in 1..=self.samples {
            let t = self.time_of(index as f64 + f64::from(j) / n).max(start);
            let mut regime = self.propagator.regime();
            loop {
                match self.propagator.advance(t) {
                    Ok(Some(event)) => {
                        acc.node(event.time, event.state, regime);
                        match event.kind {
                            EventKind::Enter => acc.enters += 1,
                            EventKind::Exit => acc.exits += 1,
                            _ => {}
                        }
                        regime = event.kind.regime_after();
                        on_event(&event);
                    }
                    Ok(None) => break,
                    Err(e) => {
                        self.next_index = self.count;
                        return Some(Err(e));
                    }
                }
            }
            acc.node(t, self.propagator.state(), regime);
        }
        let end = self.propagator.time();
        let speed_end = self.profile.piece_holding(self.cursor, end).speed_at(end);
        Some(Ok(acc.finish(index, speed_end - speed_start)))
    }
}

impl<P: Propagate + ?Sized> Iterator for Revolutions<'_, '_, P> {
    type Item = Result<Revolution, PropagationError>;

    fn next(&mut self) -> Option<Self::Item> {
        self.next_with(|_| {})
    }
}
