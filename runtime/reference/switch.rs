//! The switch inside one accepted step, shared by the numerical reference and the hybrid
//! method: located on the dense output, recomputed by an explicit step of exactly the needed
//! size, and polished onto the switching surface of the step solution (Newton steps along the
//! field, [`polish_switch`]).
//!
//! A regime has one or two switch functions ([`Switches`], `docs/MODEL.md` §10, §12): z = 1
//! always; while slipping under friction also σw (the slip velocity reaching 0); while rolling
//! also μN − |λ| (the friction limit). The earliest crossing of any of them ends the step's
//! search. Where σw reaches 0 the friction law decides ([`field::at_slip_zero`]): `roll`,
//! `reverse`, or a touch that changes nothing — then the search goes on after it in the same
//! step, so a touch is never found twice.

use core::cell::OnceCell;

use super::dop853::{Dop853, Dop853Dense, Dop853Step};
use super::events::{first_crossing_beyond, polish_switch};
use super::integrator::{AcceptedStep, Integrator};
use super::ode::OdeSystem;
use super::scheme::{After, Interpolant, Scheme};
use super::system::inside_measure;
use crate::coefficients::{ModelParams, Phasor};
use crate::field::{self, SlipZero};
use crate::params::{Params, State};
use crate::propagate::{EventKind, Regime};
use crate::{math, rounding};

/// Touches (w = 0 without a change) looked past in one step before the rest of the step is
/// taken as free of friction switches: each needs σw to turn back up, so more than a few in one
/// step means σw is flat at 0 to rounding (rolling would be the physics there, and the next
/// step's search starts afresh).
const MAX_TOUCHES: usize = 4;

/// A switch function of a regime.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Function {
    /// ±(z² − 1): contact starts or ends.
    Boundary,
    /// σw, slipping in direction σ: the slip velocity reaches 0.
    SlipVelocity,
    /// μN − |λ|, rolling: the friction needed to roll reaches its limit.
    SlipLimit,
}

/// The switch functions of one segment: its regime, slip direction, and the offsets that make
/// a friction function start at ≥ 0 (`docs/MODEL.md` §10, traps 1–2: after `slip` or `reverse`
/// the segment starts on w = 0 to rounding, after `roll` on |λ| ≈ μN; the offset, the start's
/// value when it is negative, keeps that start from being found again), and the size of the
/// terms each function is computed from, which sets its rounding band ([`Switches::band`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Switches {
    model: ModelParams,
    regime: Regime,
    slip: f64,
    offset: f64,
    /// The friction function's scale at the segment start (1 without one).
    scale: f64,
}

impl Switches {
    /// The switch functions of a segment of `regime` (slip direction `slip`) starting at
    /// `(t, y)`; `y`'s first four components are the rotor state (a phasor may follow).
    pub fn new<const N: usize>(
        params: &Params,
        regime: Regime,
        slip: f64,
        t: f64,
        y: &[f64; N],
    ) -> Self {
        let mut s = Switches {
            model: ModelParams::of(params),
            regime,
            slip,
            offset: 0.0,
            scale: 1.0,
        };
        if let Some(f) = s.friction_function() {
            s.offset = s.measure(f, t, y).0.min(0.0);
            s.scale = s.friction_scale(f, t, y);
        }
        s
    }

    /// The size of the terms `f`'s value at `(t, y)` is computed from (its rounding is relative
    /// to it), as the other methods measure it: 1 + ρ_R η + |q'| for σw (the analytic method's
    /// W, `analytic::switch::SlipVelocity::scale_at`), μN + |λ| for the cone's margin (the
    /// taylor method's).
    fn friction_scale<const N: usize>(&self, f: Function, t: f64, y: &[f64; N]) -> f64 {
        let state = rotor_state(y);
        let scale = match f {
            Function::SlipVelocity => {
                1.0 + math::abs(self.model.radius_ratio * self.model.speed_ratio)
                    + math::hypot(state.vx, state.vy)
            }
            Function::SlipLimit => {
                let friction =
                    field::friction_with_phasor(&self.model, &phasor(&self.model, t, y), &state);
                self.model.friction_coefficient * math::abs(friction.normal)
                    + math::abs(friction.lambda)
            }
            Function::Boundary => 1.0,
        };
        if scale.is_finite() {
            scale.max(1.0)
        } else {
            1.0
        }
    }

    /// The rounding band of `f` along a step's dense output ([`rounding::SOLUTION`] of its
    /// scale: 1 for z² − 1): a dip of the function that stays within it is rounding, not a
    /// switch ([`super::first_crossing_beyond`]; `docs/MODEL.md` §12).
    pub fn band(&self, f: Function) -> f64 {
        match f {
            Function::Boundary => rounding::SOLUTION,
            Function::SlipVelocity | Function::SlipLimit => rounding::SOLUTION * self.scale,
        }
    }

    /// The friction function's offset (≤ 0) from the segment start.
    pub fn offset(&self) -> f64 {
        self.offset
    }

    /// As [`Switches::new`] with the friction function's offset given (a segment continued).
    pub fn with_offset(params: &Params, regime: Regime, slip: f64, offset: f64) -> Self {
        Switches {
            model: ModelParams::of(params),
            regime,
            slip,
            offset,
            scale: 1.0,
        }
    }

    /// The regime's switch functions: z = 1, then friction's if any.
    pub fn functions(&self) -> [Option<Function>; 2] {
        [Some(Function::Boundary), self.friction_function()]
    }

    /// The friction switch function of the regime, if any.
    fn friction_function(&self) -> Option<Function> {
        match self.regime {
            Regime::Contact if self.slip != 0.0 => Some(Function::SlipVelocity),
            Regime::Rolling => Some(Function::SlipLimit),
            Regime::Free | Regime::Contact => None,
        }
    }

    /// The value (positive inside the regime) and its time derivative.
    ///
    /// Inlined so that the boundary function (a few multiplications, the only one without
    /// friction) is computed in place; the friction functions are a call.
    #[inline(always)]
    pub fn measure<const N: usize>(&self, f: Function, t: f64, y: &[f64; N]) -> (f64, f64) {
        if f == Function::Boundary {
            return inside_measure(&self.model, self.regime, y);
        }
        self.friction_measure(f, t, y)
    }

    /// [`Switches::measure`] of a friction function.
    #[inline(never)]
    fn friction_measure<const N: usize>(&self, f: Function, t: f64, y: &[f64; N]) -> (f64, f64) {
        let state = rotor_state(y);
        let phasor = phasor(&self.model, t, y);
        match f {
            Function::SlipVelocity => {
                let w = field::slip_velocity(&self.model, &state);
                let rate = field::slip_rate(&self.model, &phasor, &state, self.slip);
                (self.slip * w - self.offset, self.slip * rate)
            }
            _ => {
                let (margin, rate) = field::cone_margin(&self.model, &phasor, &state);
                (margin - self.offset, rate)
            }
        }
    }

    /// The event a crossing of `f` at `(t, y)` is, or `None` for a touch of w = 0.
    pub fn classify<const N: usize>(&self, f: Function, t: f64, y: &[f64; N]) -> Option<EventKind> {
        match f {
            Function::Boundary => Some(match self.regime {
                Regime::Free => EventKind::Enter,
                Regime::Contact | Regime::Rolling => EventKind::Exit,
            }),
            Function::SlipLimit => Some(EventKind::Slip),
            Function::SlipVelocity => {
                let phasor = phasor(&self.model, t, y);
                match field::at_slip_zero(&self.model, &phasor, &rotor_state(y), self.slip) {
                    SlipZero::Roll => Some(EventKind::Roll),
                    SlipZero::Reverse => Some(EventKind::Reverse),
                    SlipZero::Touch => None,
                }
            }
        }
    }
}

/// The rotor state of a state vector whose first four components are `[x, y, x', y']`.
fn rotor_state<const N: usize>(y: &[f64; N]) -> State {
    let c = |i: usize| y.get(i).copied().unwrap_or(0.0);
    State::new(c(0), c(1), c(2), c(3))
}

/// (cos θ, sin θ): carried in the state vector as components 4 and 5 when it has them (the
/// phasor system), else from the time ([`field::phasor`]).
fn phasor<const N: usize>(model: &ModelParams, t: f64, y: &[f64; N]) -> Phasor {
    match (y.get(4), y.get(5)) {
        (Some(&ct), Some(&st)) => Phasor { ct, st },
        _ => field::phasor(model, t),
    }
}

/// A switch found in a step: its time, the state there and what it is.
pub type Found<const N: usize> = (f64, [f64; N], EventKind);

/// The first switch of `switches` in the step `(t0, y0) → (t1, y1)` with dense output `dense`,
/// examined in `subdivisions` sub-intervals: the earliest crossing of any switch function,
/// put on the step solution (`redo` recomputes the state at a time by an explicit step from the
/// step start, `rhs` is the field), and classified; touches are looked past.
fn first_switch<const N: usize, D: Interpolant<N>>(
    switches: &Switches,
    subdivisions: usize,
    dense: &D,
    (y0, y1): (&[f64; N], &[f64; N]),
    mut redo: impl FnMut(f64) -> [f64; N],
    mut rhs: impl FnMut(f64, &[f64; N]) -> [f64; N],
) -> Option<Found<N>> {
    let (t0, t1) = (dense.start(), dense.end());
    if switches.friction_function().is_none() {
        // The boundary alone (no friction): the loop below with one function and no touch.
        let boundary = |t: f64, y: &[f64; N]| switches.measure(Function::Boundary, t, y);
        let band = switches.band(Function::Boundary);
        let t = first_crossing_beyond(subdivisions, dense, y0, y1, band, boundary)?;
        let (t, y) = on_step_solution(t, (t0, t1, *y1), &mut redo, &mut rhs, boundary);
        return switches
            .classify(Function::Boundary, t, &y)
            .map(|kind| (t, y, kind));
    }
    let functions = switches.functions();
    let (mut from, mut y_from) = (t0, *y0);
    for _ in 0..=MAX_TOUCHES {
        let window = After { dense, start: from };
        let mut first: Option<(f64, Function)> = None;
        for f in functions.iter().flatten() {
            let band = switches.band(*f);
            let found = first_crossing_beyond(subdivisions, &window, &y_from, y1, band, |t, y| {
                switches.measure(*f, t, y)
            });
            if let Some(t) = found
                && first.is_none_or(|(tf, _)| t < tf)
            {
                first = Some((t, *f));
            }
        }
        let (t, f) = first?;
        let (t, y) = on_step_solution(t, (t0, t1, *y1), &mut redo, &mut rhs, |t, y| {
            switches.measure(f, t, y)
        });
        match switches.classify(f, t, &y) {
            Some(kind) => return Some((t, y, kind)),
            // A touch: search on after it.
            None if t < t1 => (from, y_from) = (t, y),
            None => return None,
        }
    }
    None
}

/// The first switch out of the segment of `switches` inside `step`, if any.
pub fn switch_in_step<S, F, const N: usize>(
    integrator: &mut Integrator<S, N>,
    sys: &F,
    step: &AcceptedStep<N, S::Dense>,
    switches: &Switches,
) -> Option<Found<N>>
where
    S: Scheme<N>,
    F: OdeSystem<N> + ?Sized,
{
    first_switch(
        switches,
        super::events::SUBDIVISIONS,
        &step.dense,
        (&step.y0, &step.y1),
        |t| integrator.redo(sys, step, t),
        |t, y| sys.rhs(t, y),
    )
}

/// The switch found at `t` on the dense output of the step `(t0, t1, y1)`, put on the step
/// solution: the state by an explicit step of exactly the needed size (`redo`), polished onto
/// the switching surface of the step solution — the trajectory the integration continues
/// (dense output and step differ by about the tolerance).
fn on_step_solution<const N: usize>(
    t: f64,
    (t0, t1, y1): (f64, f64, [f64; N]),
    mut redo: impl FnMut(f64) -> [f64; N],
    rhs: impl FnMut(f64, &[f64; N]) -> [f64; N],
    measure: impl Fn(f64, &[f64; N]) -> (f64, f64),
) -> (f64, [f64; N]) {
    let t = t.max(t0).min(t1);
    let y = if t == t1 { y1 } else { redo(t) };
    let max_shift = 1e-3 * (t1 - t0);
    polish_switch(t0, t1, max_shift, (t, y), redo, rhs, measure)
}

/// The dense output of a [`Dop853Step`], built on first use (`into_inner` hands it on when it
/// was).
pub(crate) struct LazyDense<'a, F: ?Sized, const N: usize> {
    sys: &'a F,
    step: &'a Dop853Step<N>,
    dense: OnceCell<Dop853Dense<N>>,
}

impl<'a, F: ?Sized, const N: usize> LazyDense<'a, F, N> {
    /// The dense output of `step` (taken on `sys`), not built yet.
    pub(crate) fn new(sys: &'a F, step: &'a Dop853Step<N>) -> Self {
        LazyDense {
            sys,
            step,
            dense: OnceCell::new(),
        }
    }

    /// The dense output if it was built.
    pub(crate) fn into_inner(self) -> Option<Dop853Dense<N>> {
        self.dense.into_inner()
    }
}

impl<F: OdeSystem<N> + ?Sized, const N: usize> Interpolant<N> for LazyDense<'_, F, N> {
    fn start(&self) -> f64 {
        self.step.t0
    }

    fn end(&self) -> f64 {
        self.step.t0 + self.step.h()
    }

    fn eval(&self, t: f64) -> [f64; N] {
        self.dense.get_or_init(|| self.step.dense(self.sys)).eval(t)
    }
}

/// As [`switch_in_step`] for a step taken by [`Integrator::step_deferred`], examining the step
/// in `subdivisions` sub-intervals. The dense output is built only when the end states show a
/// crossing or a minimum; when it was built it is left in `dense` (for sampling inside the
/// step).
pub fn switch_in_deferred_step<F, const N: usize>(
    integrator: &mut Integrator<Dop853, N>,
    sys: &F,
    step: &Dop853Step<N>,
    switches: &Switches,
    subdivisions: usize,
    dense: &mut Option<Dop853Dense<N>>,
) -> Option<Found<N>>
where
    F: OdeSystem<N> + ?Sized,
{
    let lazy = LazyDense::new(sys, step);
    let f0 = step.f0();
    let found = first_switch(
        switches,
        subdivisions,
        &lazy,
        (&step.y0, &step.y1),
        |t| integrator.redo_from(sys, step.t0, &step.y0, &f0, t),
        |t, y| sys.rhs(t, y),
    );
    if let Some(d) = lazy.into_inner() {
        *dense = Some(d);
    }
    found
}
