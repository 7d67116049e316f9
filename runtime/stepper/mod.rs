//! A fixed-step stepper for embedding the model in a fixed-rate loop (a controller, a hardware in
//! the loop rig, a co-simulation): [`Stepper::step`] advances exactly `dt`, returns the state,
//! the regime and the switches inside the step, with bounded work per step.
//!
//! # How a step is taken
//! * **Free step** (the common case): one affine map w ↦ Φ(dt)·w + G(dt)·(cos θ, sin θ),
//!   precomputed from the generated free formulas ([`FreeTransition`]); the forcing phasor is
//!   rotated by (cos η·dt, sin η·dt) and re-anchored on the absolute time every
//!   [`PHASOR_RESYNC`] steps: 44 flops. With the switch test below about 150 flops and 4
//!   `sqrt`; measured 70–110 ns per step on the development machine.
//! * **Switch test on a free step**: h = z² − 1 and h' at both ends plus a rigorous bound
//!   M ≥ |h''| over the step (`FreeSegment::bounds`' bound with the step's basis bounds
//!   precomputed, radius and speed tightened around the start state, [`curvature`]); if the
//!   two-parabola bound ([`no_crossing_likely`]) proves h ≤ [`TOUCH`] on the step,
//!   the step is free. This is rigorous: no contact deeper than the rounding of h (z − 1 above
//!   ~1e-15) is missed, grazing ones included. The residual risk is rounding in M itself
//!   (relative 1e-15 of M·dt²/8, far below TOUCH for dt ≤ 1). Otherwise the step falls back to
//!   the exact machinery: the free piece and the switch search of [`locate`] — the analytic
//!   method's kernel (`analytic::switch`) with the stepper's hard caps — on the piece's Taylor
//!   polynomial ([`polynomial`]: the free closed form to below rounding, a Horner sum per
//!   evaluation); a piece from the step start ends at the free map's state.
//! * **Contact**: `contact_substeps` sub-steps of exprb43 (or exprb2) per `dt`, or more on a
//!   stiff stator: each at most `polynomial::MAX_RATE_STEP`/ρ_c = 0.5/ρ_c long, ρ_c the contact
//!   mode's rate bound from the generated `max_contact_stiffness` ([`Stepper::contact_substeps`];
//!   one sub-step per step on the presets up to dt = 1e-2; longer sub-steps gave wrong switches
//!   without a flag, `tests/stepper_coarse.rs`), each re-linearized at its start; a contact
//!   exit is proved absent by the same two-parabola test on the sub-step's closed form
//!   (`LinearSegment::bounds`, tightened by [`curvature`]), else
//!   located with [`locate`] on the sub-step's continuous extension taken as its Taylor
//!   polynomial ([`polynomial::SubstepPolynomial`], six to eight terms at dt = 1e-3; the closed
//!   form when ρ·h > [`polynomial::MAX_RATE_STEP`]). A step that enters
//!   contact mid-way fills the rest
//!   with equal sub-steps of that length at most; one that leaves contact continues
//!   in exact free flight.
//!
//! * **Friction** (`docs/MODEL.md` §10, [`friction`]): a slipping contact sub-step is the
//!   analytic method's slipping closed form, searched for the exit and for the slip velocity's
//!   zero (`reverse`, `roll`) with the same kernel under the capped budget; a rolling sub-step is
//!   one explicit DOP853 step of the rolling field with its exit and `slip` located on explicit
//!   steps from its start. The slip direction and the switch offsets are carried from step to
//!   step; μ = 0 runs the frictionless path, bit for bit.
//!
//! # Worst-case work per step
//! At most `max_substeps` contact sub-steps with exit search, one final sub-step without it,
//! and `max_substeps + 2` free pieces. Each exprb43 sub-step costs one linearization and eight
//! closed-form evaluations (four segments); each switch search at most
//! [`MAX_SEARCH_EVALUATIONS`] = 32 evaluations of a point and a bound, one point per search
//! chunk (a free piece of length ≤ dt has ≤ 2·max(η, 1 + ν)·dt + 1 chunks) and at most
//! [`MAX_REFINE_ITERATIONS`] = 40 Newton/bisection steps for each of at most two brackets
//! (a located switch typically costs 1–2 evaluations and 3–6 refinements; the exit and entry
//! searches evaluate the piece's Taylor polynomial of at most [`polynomial::TERMS`] terms, built
//! once per searched piece). Measured on the paper preset: a contact step
//! 0.6–0.8 µs, a step holding a switch 1–3.5 µs (the slowest of 10⁶ steps re-timed,
//! `cargo bench --bench stepper`). Caps are reported, never silent:
//! * [`StepReport::capped`] (sub-step cap): the last contact sub-step covers the rest of the
//!   step, so its local error grows like h⁵ for exprb43 (h³ for exprb2) with h up to dt
//!   instead of dt / [`Stepper::contact_substeps`]; if the cap was exhausted before the step
//!   end, a switch in the final piece is not located and the end regime is read from the end
//!   state, as with a plain fixed-step integrator (the error is then first order in the missed
//!   span).
//! * [`StepReport::search_capped`] (search cap): a grazing contact shallower than the search
//!   could resolve may be missing, or a switch time is known only to its last bracket.
//! * With [`OnCap::Fail`] either cap refuses the step instead: [`StepperError::BudgetExceeded`],
//!   the stepper unchanged, so a hard real-time caller never gets a degraded or overlong step
//!   without knowing (measured worst steps per kind: `BENCHMARKS.md`).
//!
//! # Inputs between steps
//! [`Stepper::set_input_force`] (the external force u, `docs/MODEL.md` §15: Φ is kept, the map
//! gains a constant), [`Stepper::set_speed_ratio`] (phase continuous), [`Stepper::snapshot`] /
//! [`Stepper::restore`] (roll back), and [`Stepper::step_to_switch`] (stop at the first switch:
//! an FMU's early return).
//!
//! # The stator ring with mass, and rotors from matrices
//! [`Stepper`] runs the paper's planar model (m̂ = 0) and refuses a ring with mass
//! (`ParamError::RingNeedsMatrixModel`); [`AnyStepper::new`] decides from the problem: the
//! planar [`Stepper`] for m̂ = 0 (its steps unchanged, one match per call), the ring's
//! [`RingStepper`] for m̂ > 0 (the C ABI and the FMU build it). A ring step is a
//! [`MatrixStepper`] step ([`matrix`]): the matrix propagator of the configured method
//! (default taylor: exact free flight of rotor and ring, Taylor-series contact, every switch
//! located as in a variable-step run) asked for anchor + k·dt; at most `max_switches` (64)
//! switches per step and the propagator's step budget between switches, else a typed error
//! with the stepper back at the step's start (its method restarted there: no copy of the
//! propagator per step). Measured 1.1–1.5 µs per step at dt = 1e-3. Its inputs re-state the
//! ring model and restart the method at the current state (a new free-flight decomposition).
//!
//! # Changing parameters or the step length
//! A `step` with a new `dt` recomputes Φ, G and the bound constants ([`FreeTransition::new`]:
//! the free basis at dt once (one `exp`, one `sin_cos`), the generated step formulas
//! `free_step_transition` and `free_step_forcing`). [`Stepper::set_params`] (a speed ramp, a
//! stiffness change) keeps Φ, the basis at dt and its bounds unless the damping changed
//! ([`FreeTransition::set_params`]): a new speed costs the validation, the free and contact
//! constants, G and one `sin_cos`.

mod any;
mod config;
mod exact;
pub mod friction;
mod inputs;
pub mod matrix;
pub mod polynomial;
mod report;
mod resolution;
pub mod ring;
mod ring_words;
pub mod search;
mod solvers;
mod transition;

pub use crate::analytic::switch::Search;
pub use any::{AnySnapshot, AnyStepper};
pub use config::{OnCap, StepperConfig, SwitchStart};
pub use inputs::Snapshot;
pub use matrix::{MatrixStepReport, MatrixStepper, MatrixStepperConfig, OwnedModel};
pub use report::{EVENT_CAPACITY, EventList, StepReport, StepperError};
pub use ring::{RingState, RingStepper};
pub use search::{
    MAX_REFINE_ITERATIONS, MAX_SEARCH_EVALUATIONS, TOUCH, curvature, locate, locate_with,
    no_crossing, no_crossing_likely,
};
pub use transition::FreeTransition;

use crate::analytic::free::FreeConstants;
use crate::coefficients::ModelParams;
use crate::driver::within_bounds;
use crate::field;
use crate::geometry;
use crate::math;
use crate::params::{Params, Problem, State};
use crate::propagate::{PropagationError, Regime};

/// Longest accepted step (time units). Longer spans: take several steps.
pub const MAX_STEP: f64 = 1.0;
/// Largest accepted `contact_substeps` and `max_substeps`.
pub const MAX_SUBSTEPS: u32 = 1024;
/// Number of steps of one length after which the forcing phasor is recomputed from the absolute
/// time (between, it is rotated: rounding drift ≤ ~1e-13 relative).
pub const PHASOR_RESYNC: u64 = 256;

/// The fixed-step propagator (see the module docs). Plain data, no heap: it can live in
/// caller-owned memory (the C ABI relies on that).
#[derive(Clone, Copy, Debug)]
pub struct Stepper {
    params: Params,
    config: StepperConfig,
    transition: FreeTransition,
    time: f64,
    /// Time at which the current step length (or parameter set) took effect.
    anchor_time: f64,
    /// Steps of the current length since `anchor_time`: time = anchor + steps·dt, no drift.
    anchor_steps: u64,
    state: State,
    regime: Regime,
    /// The slip direction of the current contact segment and its switch's constants.
    slip: friction::Slip,
    /// (cos θ, sin θ) of the forcing at `time`.
    phasor: (f64, f64),
}

impl Stepper {
    /// Validate `problem` and `config` and start at the problem's start time, with Φ precomputed
    /// for `config.dt`. The initial regime is decided as by every propagation method
    /// (`driver::start_side`): off z = 1 by the sign of z − 1; on it, by the side the motion takes,
    /// with the start moved radially by about 3e-14 onto that side so that no rounding-level
    /// switch is reported at the start (`docs/MODEL.md` §6 cases 14–15).
    pub fn new(problem: &Problem, config: StepperConfig) -> Result<Self, StepperError> {
        problem.validate()?;
        problem.params.planar()?;
        config.validate()?;
        check_dt(config.dt, problem.start_time)?;
        let params = problem.params;
        let free = FreeConstants::new(&params);
        let t0 = problem.start_time;
        check_bounded(t0, problem.initial)?;
        let (regime, state) = crate::driver::start_side(&params, t0, &problem.initial);
        let slip = friction::Slip::at(&params, regime, t0, &state, None);
        Ok(Stepper {
            params,
            config,
            transition: FreeTransition::new(&params, &free, config.dt),
            time: t0,
            anchor_time: t0,
            anchor_steps: 0,
            state,
            regime,
            slip,
            phasor: phasor_at(&params, t0),
        })
    }

    /// Advance exactly `dt` (finite, in (0, [`MAX_STEP`]]). Returns the end state and regime and
    /// the switches in (t, t + dt]. On error the stepper is left unchanged.
    pub fn step(&mut self, dt: f64) -> Result<StepReport, StepperError> {
        self.advance(dt, false)
    }

    /// As [`Stepper::step`], but the step ends at the first switch inside it, if any: the
    /// report's time is the switch time, its state the switch state and its one event the
    /// switch (an importer's early return: the event is seen where it happened). Without a
    /// switch it is exactly [`Stepper::step`].
    pub fn step_to_switch(&mut self, dt: f64) -> Result<StepReport, StepperError> {
        self.advance(dt, true)
    }

    fn advance(&mut self, dt: f64, stop_at_switch: bool) -> Result<StepReport, StepperError> {
        check_dt(dt, self.time)?;
        if dt != self.transition.dt() {
            self.transition = FreeTransition::new(&self.params, self.transition.constants(), dt);
            self.anchor_time = self.time;
            self.anchor_steps = 0;
        }
        if self.regime == Regime::Free
            && let Some(state) = self.free_step()
        {
            // The fast path: no cap can be hit, and the report is built once, in place.
            self.finish(dt, state, Regime::Free, friction::Slip::NONE, None);
            return Ok(StepReport::free(self.time, state));
        }
        let mut report = StepReport {
            time: self.time,
            state: self.state,
            regime: self.regime,
            events: EventList::default(),
            substeps: 0,
            capped: false,
            search_capped: false,
            error_estimate: 0.0,
        };
        let (state, regime, slip, stopped) = self.exact_step(dt, stop_at_switch, &mut report)?;
        if self.config.on_cap == OnCap::Fail && (report.capped || report.search_capped) {
            return Err(StepperError::BudgetExceeded {
                time: self.time,
                substeps: report.substeps,
            });
        }
        self.finish(dt, state, regime, slip, stopped);
        report.time = self.time;
        report.state = state;
        report.regime = regime;
        Ok(report)
    }

    /// Take the step's end: state, regime and slip, and the time and forcing phasor (re-anchored
    /// at the switch when the step `stopped` at one).
    #[inline]
    fn finish(
        &mut self,
        dt: f64,
        state: State,
        regime: Regime,
        slip: friction::Slip,
        stopped: Option<f64>,
    ) {
        self.state = state;
        self.regime = regime;
        self.slip = slip;
        if let Some(time) = stopped {
            // Stopped at a switch: re-anchor the time and the forcing phasor there.
            self.time = time;
            self.anchor_time = time;
            self.anchor_steps = 0;
            self.phasor = phasor_at(&self.params, time);
        } else {
            self.anchor_steps += 1;
            self.time = self.anchor_time + self.anchor_steps as f64 * dt;
            // Rotated on every step and overwritten out of line on a resync step: a store
            // shared by both paths would be two scalar stores, under the next step's vector
            // load of the phasor (a failed store forwarding, ≈ 20 % of a free step).
            self.phasor = self.transition.rotate(self.phasor);
            if self.anchor_steps.is_multiple_of(PHASOR_RESYNC) {
                self.resync_phasor();
            }
        }
    }

    /// The forcing phasor recomputed from the time (every [`PHASOR_RESYNC`] steps, so that
    /// the rotation's rounding does not accumulate).
    #[cold]
    #[inline(never)]
    fn resync_phasor(&mut self) {
        self.phasor = phasor_at(&self.params, self.time);
    }

    /// Replace the parameters from the current time on (e.g. one point of a speed ramp). Costs
    /// a recomputation of the free constants and of G for the current step length, and of Φ
    /// when the damping changed ([`FreeTransition::set_params`]). The regime is re-decided from
    /// the current state (a changed offset can move the boundary); no event is reported for
    /// that. On error nothing changes.
    pub fn set_params(&mut self, params: &Params) -> Result<(), StepperError> {
        params.validate()?;
        params.planar()?;
        self.params = *params;
        self.transition.set_params(params);
        self.anchor_time = self.time;
        self.anchor_steps = 0;
        self.phasor = phasor_at(params, self.time);
        self.regime = field::regime_of(params, self.time, &self.state);
        self.slip = friction::Slip::at(params, self.regime, self.time, &self.state, None);
        Ok(())
    }

    /// The current time τ.
    pub fn time(&self) -> f64 {
        self.time
    }

    /// The state at [`Stepper::time`].
    pub fn state(&self) -> State {
        self.state
    }

    /// The regime at [`Stepper::time`].
    pub fn regime(&self) -> Regime {
        self.regime
    }

    /// The slip direction σ of the current contact (±1 while slipping under friction, 0 when
    /// free, rolling or frictionless).
    pub fn slip_direction(&self) -> f64 {
        self.slip.sigma
    }

    /// The parameters in force.
    pub fn params(&self) -> &Params {
        &self.params
    }

    /// The configuration (its `dt` is the one given at construction).
    pub fn config(&self) -> &StepperConfig {
        &self.config
    }

    /// The step length Φ is currently precomputed for (the last `dt` stepped, or the config's).
    pub fn precomputed_dt(&self) -> f64 {
        self.transition.dt()
    }

    /// The contact sub-steps a step of [`Stepper::precomputed_dt`] takes in contact: the
    /// configured `contact_substeps`, or more on a stator too stiff for them, so that every
    /// contact and rolling sub-step is at most [`polynomial::MAX_RATE_STEP`]/ρ_c long (ρ_c the
    /// contact mode's rate bound, [`Stepper::contact_rate`]). When it exceeds `max_substeps`,
    /// steps in contact are capped ([`StepReport::capped`], or [`StepperError::BudgetExceeded`]
    /// with [`OnCap::Fail`]): take a shorter step, at most [`Stepper::largest_resolved_dt`].
    pub fn contact_substeps(&self) -> u32 {
        self.config
            .contact_substeps
            .max(self.transition.resolving_substeps())
    }

    /// ρ_c = ν + √(ν² + S), S the generated bound of the linearized contact stiffness ‖Kl‖₂
    /// over every contact position, friction included (`max_contact_stiffness`): the fastest
    /// rate of the contact mode (1/time), about √(1 + K̂) without friction.
    pub fn contact_rate(&self) -> f64 {
        self.transition.contact_rate()
    }

    /// The longest step whose contact sub-steps fit the configured `max_substeps`:
    /// `max_substeps`·[`polynomial::MAX_RATE_STEP`]/ρ_c, at most [`MAX_STEP`] (a step in
    /// contact of at most this length is never capped for the contact mode's sake; several
    /// switches in one step can still use up the cap).
    pub fn largest_resolved_dt(&self) -> f64 {
        let rate = self.transition.contact_rate();
        (f64::from(self.config.max_substeps) * polynomial::MAX_RATE_STEP / rate).min(MAX_STEP)
    }

    /// The fast path: one affine map and the switch bound; `None` when the bound cannot prove
    /// the step contact-free.
    #[inline]
    fn free_step(&self) -> Option<State> {
        let tr = &self.transition;
        let model = tr.constants().model();
        let end = tr.apply(&self.state, self.phasor);
        let b = geometry::point(model, end);
        if b.h >= 0.0 || b.h.is_nan() {
            return None;
        }
        let a = geometry::point(model, self.state);
        let m2 = tr.curvature_bound(&self.state, self.phasor, math::sqrt((a.h + 1.0).max(0.0)));
        no_crossing_likely(a.h.min(0.0), a.dh, b.h, b.dh, m2, tr.dt(), TOUCH).then_some(end)
    }
}

fn check_dt(dt: f64, time: f64) -> Result<(), StepperError> {
    // Finite, in (0, MAX_STEP]: the two comparisons also refuse NaN and ±∞ (no separate
    // finiteness test, which costs more than both on the free step's path).
    if dt > 0.0 && dt <= MAX_STEP && time + dt > time {
        Ok(())
    } else {
        Err(StepperError::InvalidStep { dt, time })
    }
}

fn check_bounded(time: f64, state: State) -> Result<(), StepperError> {
    if within_bounds(&state) {
        Ok(())
    } else {
        Err(PropagationError::Diverged { time, state }.into())
    }
}

/// (cos θ, sin θ) of the forcing at time `t` ([`field::phasor`]).
fn phasor_at(params: &Params, t: f64) -> (f64, f64) {
    let p = field::phasor(&ModelParams::of(params), t);
    (p.ct, p.st)
}
