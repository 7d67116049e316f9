//! Friction's switch on a closed-form contact sub-step (`docs/MODEL.md` §10, §12): the slip
//! velocity w reaching 0 while slipping in direction σ, as an [`EventFunction`] for the same
//! kernel and with the same guarantee as z = 1.
//!
//! # The function
//! g = −(σw − m)/W with w = q′·t + ρ_R η (generated `friction_state`), W = 1 + ρ_R η + |q′(0)| a
//! fixed scale (so that the kernel's touch threshold is relative to the size of w), and m ≤ 0
//! the segment start's σw when it is negative by rounding (after `slip` or `reverse` the start is
//! on w = 0: trap 1 of §10; the offset keeps it from being found again). On the closed form,
//! g′ = −σw′/W with w′ = q″·t + q′·t′ (generated `slip_velocity_rate`) along the closed form's
//! own acceleration a ([`LinearSegment::acceleration`]), so g′ is the exact derivative of the
//! closed form's g.
//!
//! # The bound (the proof the kernel rests on)
//! With t′ = −(q′·t/z) n and n′ = (q′·t/z) t: |t′| ≤ V/z, |t″| ≤ A/z + 3V²/z², and
//! w″ = q‴·t + 2 q″·t′ + q′·t″ gives |w″| ≤ J + 3AV/z + 3V³/z², where V, A, J bound |q′|, |q″|,
//! |q‴| on the interval (the segment's [`Segment::bounds`] and [`LinearSegment::jerk_bound`])
//! and z ≥ z(lo) − V·(hi − lo) (an interval that could come near the stator centre, z < ¼, gets
//! no finite bound and is split instead).

use super::{Budget, EventFunction, locate};
use crate::analytic::linear::LinearSegment;
use crate::analytic::segment::Segment;
use crate::coefficients::{self as coef, Acceleration};
use crate::field::{self, SlipZero};
use crate::geometry::{self, position, velocity};
use crate::math;
use crate::params::{Params, State};
use crate::propagate::EventKind;

/// A point of the sub-step: its local time and state.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SlipPoint {
    /// Local time.
    pub s: f64,
    /// The state there.
    pub state: State,
}

/// σw reaching 0 on a linearized contact sub-step that starts at absolute time `t0`.
#[derive(Clone, Copy, Debug)]
pub struct SlipVelocity<'a> {
    segment: &'a LinearSegment,
    t0: f64,
    slip: f64,
    offset: f64,
    scale: f64,
}

impl<'a> SlipVelocity<'a> {
    /// The slip switch of `segment` (starting at absolute time `t0`, slipping in direction
    /// `slip`), with `offset` = m ≤ 0 and `scale` = W of the module documentation (see
    /// [`SlipVelocity::start_offset`] and [`SlipVelocity::scale_at`]).
    pub fn new(segment: &'a LinearSegment, t0: f64, slip: f64, offset: f64, scale: f64) -> Self {
        SlipVelocity {
            segment,
            t0,
            slip,
            offset,
            scale,
        }
    }

    /// The slip direction σ.
    pub fn slip(&self) -> f64 {
        self.slip
    }

    /// W = 1 + ρ_R η + |q′| at the start of a slipping segment.
    pub fn scale_at(params: &Params, state: &State) -> f64 {
        1.0 + params.radius_ratio * params.speed_ratio + math::hypot(state.vx, state.vy)
    }

    /// m = min(σw, 0) at the start of a slipping segment.
    pub fn start_offset(params: &Params, t: f64, state: &State, slip: f64) -> f64 {
        (slip * field::friction_at(params, t, state).slip_velocity).min(0.0)
    }
}

impl EventFunction for SlipVelocity<'_> {
    type Point = SlipPoint;

    fn point(&self, s: f64) -> SlipPoint {
        SlipPoint {
            s,
            state: self.segment.point(s).state,
        }
    }

    fn value(&self, p: &SlipPoint) -> (f64, f64) {
        let model = self.segment.linearization().model();
        let st = &p.state;
        let w = field::slip_velocity(model, st);
        let (ax, ay) = self.segment.acceleration(p.s, st);
        let rate = coef::slip_velocity_rate(
            model,
            &position(st),
            &velocity(st),
            &Acceleration { ax, ay },
        )
        .rate;
        (
            -(self.slip * w - self.offset) / self.scale,
            -self.slip * rate / self.scale,
        )
    }

    fn curvature(&self, lo: f64, at_lo: &SlipPoint, hi: f64) -> f64 {
        let b = self.segment.bounds(lo, hi);
        let jerk = self.segment.jerk_bound(hi, &b);
        let st = &at_lo.state;
        let model = self.segment.linearization().model();
        let z0 = geometry::distance(model, st.x, st.y);
        let z = z0 - b.speed * (hi - lo);
        if z.is_nan() || z < 0.25 {
            return f64::INFINITY;
        }
        let (v, a) = (b.speed, b.accel);
        (jerk + 3.0 * a * v / z + 3.0 * v * v * v / (z * z)) / self.scale
    }
}

/// Where slipping changes before local time `limit` of the sub-step of `f`, which starts in
/// `state`: the first zero of the slip velocity that is a `roll` or a `reverse`
/// ([`field::at_slip_zero`]), searched by the kernel with `budget`, as (local time, state,
/// kind); a touch (w back to the old sign) is looked past, at most [`MAX_TOUCHES`] times.
pub fn first_slip_switch(
    f: &SlipVelocity<'_>,
    state: State,
    limit: f64,
    budget: &Budget,
) -> Option<(f64, State, EventKind)> {
    let mut from = SlipPoint { s: 0.0, state };
    for _ in 0..=MAX_TOUCHES {
        let (s, p) = locate(f, from.s, from, limit, None, f64::INFINITY, budget, None).found()?;
        let model = f.segment.linearization().model();
        let phasor = field::phasor(model, f.t0 + s);
        match field::at_slip_zero(model, &phasor, &p.state, f.slip) {
            SlipZero::Roll => return Some((s, p.state, EventKind::Roll)),
            SlipZero::Reverse => return Some((s, p.state, EventKind::Reverse)),
            SlipZero::Touch => from = p,
        }
    }
    None
}

/// Touches of w = 0 looked past in one sub-step (each needs σw to turn back up; more means w is
/// flat at 0 to rounding, and the next sub-step searches afresh).
pub const MAX_TOUCHES: usize = 4;
