//! Friction in the stepper (`docs/MODEL.md` §10): the slip direction carried from step to step,
//! the slip velocity's zero searched on each slipping sub-step with the analytic method's kernel
//! (capped budget), and rolling sub-steps.
//!
//! # Rolling sub-steps and their work
//! Rolling has no closed form: each rolling sub-step (at most dt /
//! `Stepper::contact_substeps()`, counted against `max_substeps` like a contact sub-step) is one
//! explicit DOP853 step of the rolling field (12 evaluations). Its switches (z = 1 and μN − |λ|)
//! are looked for as the numerical methods do on a step ([`first_crossing_subdivided`] over one
//! interval: both ends, and an
//! interior minimum where the slope turns from − to +), the states inside the sub-step taken by
//! explicit steps of exactly the needed length from its start (no interpolation); the crossing is
//! refined by the safeguarded Illinois iteration of the reference methods (at most 400
//! evaluations of a step: in practice 40–60). Rolling's first integral w stays at 0 to the
//! explicit steps' accuracy (its drift is the local error, ~h⁹).

use crate::analytic::schemes::SubStep;
use crate::analytic::switch::{Budget, SlipVelocity, first_slip_switch};
use crate::driver::within_bounds;
use crate::field;
use crate::params::{Params, State};
use crate::propagate::{EventKind, PropagationError, Regime};
use crate::reference::{
    Dop853, Function, Interpolant, OdeSystem, RotorSystem, Scheme, StepStart, Switches, Tolerance,
    first_crossing_subdivided,
};

/// What a contact segment under friction carries from sub-step to sub-step: its slip direction
/// σ (0 when none is tracked), and the offset and scale of its friction switch.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Slip {
    /// σ = ±1 while slipping under friction, 0 otherwise.
    pub sigma: f64,
    /// The friction switch's offset from the segment start (≤ 0).
    pub offset: f64,
    /// The slip switch's scale (slipping only).
    pub scale: f64,
}

impl Slip {
    /// No slip tracked.
    pub const NONE: Slip = Slip {
        sigma: 0.0,
        offset: 0.0,
        scale: 1.0,
    };

    /// The slip of a segment of `regime` starting at `(t, state)` after `cause` (the event that
    /// starts it, `None` at a start): its direction as the driver decides it
    /// ([`field::slip_direction`]), then [`Slip::of`].
    pub fn at(
        params: &Params,
        regime: Regime,
        t: f64,
        state: &State,
        cause: Option<EventKind>,
    ) -> Slip {
        let sigma = match regime {
            Regime::Contact => field::slip_direction(params, t, state, cause),
            Regime::Free | Regime::Rolling => 0.0,
        };
        Slip::of(params, regime, t, state, sigma)
    }

    /// The slip of a segment of `regime` starting at `(t, state)` in direction `sigma` (the
    /// driver's, 0 when no slip is tracked): the friction switch's offset and scale there.
    pub fn of(params: &Params, regime: Regime, t: f64, state: &State, sigma: f64) -> Slip {
        if params.friction_coefficient <= 0.0 {
            return Slip::NONE;
        }
        match regime {
            Regime::Free => Slip::NONE,
            Regime::Contact => Slip {
                sigma,
                offset: SlipVelocity::start_offset(params, t, state, sigma),
                scale: SlipVelocity::scale_at(params, state),
            },
            Regime::Rolling => Slip {
                sigma: 0.0,
                offset: Switches::new(params, Regime::Rolling, 0.0, t, &state.to_array()).offset(),
                scale: 1.0,
            },
        }
    }
}

/// A switch inside a sub-step: local time, state, kind.
pub type SwitchIn = (f64, State, EventKind);

/// The states inside a rolling sub-step: explicit steps of exactly the needed length.
struct ExactSteps<'a> {
    sys: &'a RotorSystem,
    t0: f64,
    t1: f64,
    y0: [f64; 4],
    f0: [f64; 4],
    tol: Tolerance,
}

impl Interpolant<4> for ExactSteps<'_> {
    fn start(&self) -> f64 {
        self.t0
    }
    fn end(&self) -> f64 {
        self.t1
    }
    fn eval(&self, t: f64) -> [f64; 4] {
        let from = StepStart {
            t: self.t0,
            y: &self.y0,
            f0: &self.f0,
            h: t - self.t0,
            tol: &self.tol,
        };
        Dop853::attempt(self.sys, from).y1
    }
}

/// The first `reverse` or `roll` on a slipping sub-step `sub` from `state` at `t`, before local
/// time `limit` (the exit, or the sub-step's end), with the capped `budget`.
pub(super) fn slip_in(
    sub: &SubStep,
    t: f64,
    state: State,
    slip: &Slip,
    limit: f64,
    budget: &Budget,
) -> Option<SwitchIn> {
    if slip.sigma == 0.0 {
        return None;
    }
    let f = SlipVelocity::new(&sub.segment, t, slip.sigma, slip.offset, slip.scale);
    first_slip_switch(&f, state, limit, budget)
}

/// One rolling sub-step of length `h` from `state` at `t`: its end state, or the first switch
/// in it as (local time, state, kind).
pub(super) fn rolling_substep(
    params: &Params,
    t: f64,
    state: State,
    h: f64,
    slip: &Slip,
) -> Result<(State, Option<SwitchIn>), PropagationError> {
    let sys = RotorSystem {
        params: *params,
        regime: Regime::Rolling,
        slip: 0.0,
    };
    let y0 = state.to_array();
    let steps = ExactSteps {
        sys: &sys,
        t0: t,
        t1: t + h,
        y0,
        f0: sys.rhs(t, &y0),
        tol: Tolerance::uniform(1e-12),
    };
    let y1 = steps.eval(t + h);
    let end = State::from_array(y1);
    if !within_bounds(&end) {
        return Err(PropagationError::Diverged {
            time: t + h,
            state: end,
        });
    }
    let switches = Switches::with_offset(params, Regime::Rolling, 0.0, slip.offset);
    let mut first: Option<(f64, Function)> = None;
    for f in switches.functions().into_iter().flatten() {
        let found =
            first_crossing_subdivided(1, &steps, &y0, &y1, |tt, y| switches.measure(f, tt, y));
        if let Some(te) = found
            && first.is_none_or(|(tf, _)| te < tf)
        {
            first = Some((te, f));
        }
    }
    let Some((te, f)) = first else {
        return Ok((end, None));
    };
    let ye = if te >= t + h { y1 } else { steps.eval(te) };
    Ok((
        end,
        switches
            .classify(f, te, &ye)
            .map(|kind| (te - t, State::from_array(ye), kind)),
    ))
}
