//! The communication step: [`Model::do_step`] covers (t, t + h] with stepper steps of at most
//! `internal_step`, so the accuracy does not depend on h. A step whose exprb43 error estimate
//! exceeds `tolerance` is undone (the stepper is plain data, copied) and retried at half the length (at most
//! [`MAX_HALVINGS`] times; the length grows back by doubling when the estimate is 64× below the
//! tolerance). Every contact switch inside is located exactly by the stepper; with early return
//! the step ends at the first one ([`AnyStepper::step_to_switch`]) and reports its time. The
//! stator ring with mass (`stator_mass_ratio` > 0) runs the ring's stepper: no error estimate
//! (its method meets its own tolerance), every switch located as in the planar model; each of
//! its internal steps ends at its first switch (the next starts there), so it needs no copy to
//! undo a step (the ring's stepper is 39 KiB: a copy per internal step would cost more than
//! the step).
//!
//! # Bounded work
//! One communication step makes at most `max_internal_steps` stepper calls (retries included),
//! each of bounded work (the stepper's caps), so no `doStep` blocks however long h is (a step
//! of 1e5 time units took 96 s before the cap). Reaching the cap ends the step at the last
//! completed internal step with [`Stepped::Capped`]: the FMI layers report it as an early return
//! (FMI 3 with early return allowed), as `fmi3Discard` with the state of the step's start (FMI 3
//! without), or as `fmi2Discard` with the time reached (FMI 2.0's "computed a subinterval").

use rotor_rub::stepper::{AnySnapshot, AnyStepper};
use rotor_rub::{Event, EventKind, EventList};

use crate::message::Message;
use crate::model::Model;
use crate::msg;
use crate::units::Dimension;

/// Most halvings of one internal step (2⁻¹² of `internal_step`).
pub const MAX_HALVINGS: u32 = 12;

/// How a communication step ended.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Stepped {
    /// At t + h.
    Completed,
    /// Early, at a switch at this time (importer units; early return only).
    Switch(f64),
    /// Early, at this time (importer units), the work cap reached.
    Capped(f64),
}

/// What a communication step changes in a [`Model`], as it was before the step: the stepper as
/// an [`AnySnapshot`] (planar: a quarter of the stepper's size, so taking one costs little on
/// every step; rebuilding from it is needed only to rewind; the ring's: a copy), the counters
/// and the pending flag.
#[derive(Clone)]
pub struct Checkpoint {
    stepper: Option<AnySnapshot>,
    contact_count: u64,
    next_step: f64,
    pending: bool,
}

impl Model {
    /// The state a communication step starts from, to [`Model::rewind`] to.
    pub fn checkpoint(&self) -> Checkpoint {
        Checkpoint {
            stepper: self.stepper.as_ref().map(AnyStepper::snapshot),
            contact_count: self.contact_count,
            next_step: self.next_step,
            pending: self.pending,
        }
    }

    /// Back to `checkpoint`: the model as it was (the stepper rebuilt from its snapshot steps on
    /// with the same bits, `AnyStepper::restore`).
    pub fn rewind(&mut self, checkpoint: &Checkpoint) -> Result<(), Message> {
        self.stepper = match &checkpoint.stepper {
            Some(s) => Some(AnyStepper::restore(s).map_err(|e| msg!("rewinding the step: {e}"))?),
            None => None,
        };
        self.contact_count = checkpoint.contact_count;
        self.next_step = checkpoint.next_step;
        self.pending = checkpoint.pending;
        Ok(())
    }

    /// Cover the communication step (`t`, `t` + `h`] (importer units; see the module docs);
    /// with `early_return` end at the first switch. `on_event` sees every switch (in model
    /// units). The tunable parameters set since the last step take effect first, as one set.
    /// On error the model is left at its last completed internal step (or unchanged, for a
    /// bad argument or a refused parameter set).
    pub fn do_step(
        &mut self,
        t: f64,
        h: f64,
        early_return: bool,
        on_event: &mut dyn FnMut(&Event),
    ) -> Result<Stepped, Message> {
        let now = self.time();
        if let Some(f) = &mut self.file {
            if !t.is_finite() || (t - now).abs() > 1e-9 * (1.0 + t.abs().max(now.abs())) {
                return Err(msg!(
                    "communication point t = {t} does not match the FMU's time {now} (set the FMU state, or step from {now})"
                ));
            }
            f.do_step(h).map_err(|e| msg!("{e}"))?;
            return Ok(Stepped::Completed);
        }
        if self.stepper.is_none() {
            return Err(msg!("doStep before the end of initialization"));
        }
        if !t.is_finite() || (t - now).abs() > 1e-9 * (1.0 + t.abs().max(now.abs())) {
            return Err(msg!(
                "communication point t = {t} does not match the FMU's time {now} (set the FMU state, or step from {now})"
            ));
        }
        let scales = self.scales();
        let end = scales.to_model(Dimension::Time, t + h);
        if !(h.is_finite() && h > 0.0 && end.is_finite()) {
            return Err(msg!(
                "communication step size h = {h} is invalid: it must be finite and > 0"
            ));
        }
        self.apply_pending()?;
        let (settings, cap) = (self.settings, self.settings.max_internal_steps);
        let internal_step = self.model_internal_step();
        let Some(stepper) = self.stepper.as_mut() else {
            return Err(msg!("doStep before the end of initialization"));
        };
        let scale = 1.0 + end.abs();
        let (mut halvings, mut work) = (0, 0u32);
        let reached = |s: &AnyStepper| scales.to_importer(Dimension::Time, s.time());
        loop {
            let remaining = end - stepper.time();
            if remaining <= 1e-12 * scale {
                return Ok(Stepped::Completed);
            }
            if work >= cap {
                return Ok(Stepped::Capped(reached(stepper)));
            }
            // A remainder within rounding of the step length takes the step length itself, so
            // that communication steps of whole internal steps keep one precomputed map.
            let dt = if remaining - self.next_step >= -1e-9 * self.next_step {
                self.next_step
            } else {
                remaining
            };
            // The planar stepper is copied to undo a step (a few hundred bytes); the ring's
            // (39 KiB) is not: it has no error estimate to retry on, and it steps to each
            // switch, so its report never overflows.
            let ring = matches!(stepper, AnyStepper::Ring(_));
            let mut before = (!ring).then(|| stepper.clone());
            let start = stepper.time();
            work += 1;
            let report = if early_return || ring {
                stepper.step_to_switch(dt)
            } else {
                stepper.step(dt)
            }
            .map_err(|e| msg!("step of {dt} from τ = {start}: {e}"))?;
            if report.error_estimate > settings.tolerance
                && halvings < MAX_HALVINGS
                && let Some(before) = before.take()
            {
                *stepper = before;
                self.next_step = dt * 0.5;
                halvings += 1;
                continue;
            }
            halvings = 0;
            if report.events.overflowed()
                && let Some(before) = before.take()
            {
                // More switches than a report holds: redo the step switch by switch.
                let stop = start + dt;
                *stepper = before;
                while stop - stepper.time() > 1e-12 * scale {
                    if work >= cap {
                        return Ok(Stepped::Capped(reached(stepper)));
                    }
                    work += 1;
                    let r = stepper
                        .step_to_switch(stop - stepper.time())
                        .map_err(|e| msg!("step from τ = {}: {e}", stepper.time()))?;
                    self.contact_count += entries(&r.events, on_event);
                }
            } else {
                self.contact_count += entries(&report.events, on_event);
            }
            if report.error_estimate * 64.0 < settings.tolerance {
                self.next_step = (self.next_step * 2.0).min(internal_step);
            }
            if early_return && !report.events.is_empty() {
                return Ok(Stepped::Switch(reached(stepper)));
            }
        }
    }
}

/// Contact entries among `events`, each event handed to `on_event`.
fn entries(events: &EventList, on_event: &mut dyn FnMut(&Event)) -> u64 {
    let mut n = 0;
    for e in events {
        on_event(e);
        n += u64::from(e.kind == EventKind::Enter);
    }
    n
}
