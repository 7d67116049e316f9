//! One Taylor expansion of a contact regime's field about a state (`docs/MODEL.md` §16): the
//! generated recurrences fill the series, the order comes from the tolerance and the step from
//! the last two orders' coefficients (Jorba–Zou), and the same polynomials give the state
//! anywhere in the step (dense output) and the switch functions as polynomials.

use super::kernels::orders;
use super::kernels::{self, CAPACITY, MAX_ORDER, Series};
use super::step::StepRule;
use crate::coefficients::{
    ModelParams, Slip, TAYLOR_SERIES_MAX, contact_taylor, rolling_taylor, slipping_taylor,
};
use crate::geometry;
use crate::math;
use crate::params::State;
use crate::propagate::Regime;
use crate::refine::Knot;

/// A regime's field: which generated recurrences, with their constants.
#[derive(Clone, Copy, Debug)]
enum Field {
    Contact(contact_taylor::Constants),
    Slipping(slipping_taylor::Constants),
    Rolling(rolling_taylor::Constants),
}

/// A switch function of a contact regime, positive inside it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Switch {
    /// z² − 1: the contact ends (`exit`).
    Boundary,
    /// σw while slipping: the slip velocity reaches 0 (`roll`, `reverse`, or a touch).
    SlipVelocity,
    /// μN − λ while rolling: λ reaches the friction limit from below (`slip`).
    ConeUpper,
    /// μN + λ while rolling: λ reaches the friction limit from above (`slip`).
    ConeLower,
}

/// The expansion order for a tolerance (Jorba–Zou): p = ⌈−ln(tol)/2 + 1⌉, within [2, MAX_ORDER].
pub fn order_for(tol: f64) -> usize {
    let p = libm::ceil(-math::ln(tol) / 2.0 + 1.0);
    if p.is_finite() && p >= 2.0 {
        (p as usize).min(MAX_ORDER)
    } else {
        2
    }
}

/// The series of one step's expansion.
pub struct Expansion {
    field: Field,
    /// σ while slipping (1 otherwise): the slip-velocity switch is σw.
    slip: f64,
    order: usize,
    rule: StepRule,
    series: Series,
}

impl Expansion {
    /// An expansion of order `order` (≤ [`MAX_ORDER`]) for the field of frictionless contact.
    pub fn new(model: &ModelParams, order: usize) -> Self {
        let order = order.clamp(2, MAX_ORDER);
        Expansion {
            field: Field::Contact(contact_taylor::constants(model)),
            slip: 1.0,
            order,
            rule: StepRule::new(order),
            series: [[0.0; CAPACITY]; TAYLOR_SERIES_MAX],
        }
    }

    /// Switch to the field of `regime` (contact slipping in direction `slip` when `slip` ≠ 0).
    pub fn set_regime(&mut self, model: &ModelParams, regime: Regime, slip: f64) {
        self.slip = if slip < 0.0 { -1.0 } else { 1.0 };
        self.field = match regime {
            Regime::Rolling => Field::Rolling(rolling_taylor::constants(model)),
            _ if slip != 0.0 => {
                Field::Slipping(slipping_taylor::constants(model, &Slip { sigma: slip }))
            }
            _ => Field::Contact(contact_taylor::constants(model)),
        };
    }

    /// The switch functions of the current field.
    pub fn switches(&self) -> &'static [Switch] {
        match self.field {
            Field::Contact(_) => &[Switch::Boundary],
            Field::Slipping(_) => &[Switch::Boundary, Switch::SlipVelocity],
            Field::Rolling(_) => &[Switch::Boundary, Switch::ConeUpper, Switch::ConeLower],
        }
    }

    /// Expand about `state` with the forcing phasor (cos θ, sin θ): every series to the order.
    pub fn expand(&mut self, state: &State, (cos_theta, sin_theta): (f64, f64)) {
        let s = &mut self.series;
        for (series, value) in s
            .iter_mut()
            .zip([state.x, state.y, state.vx, state.vy, cos_theta, sin_theta])
        {
            if let Some(c) = series.first_mut() {
                *c = value;
            }
        }
        let p = self.order;
        match &self.field {
            Field::Contact(k) => {
                contact_taylor::order0(k, s);
                orders!(
                    p,
                    |N| contact_taylor::order::<N>(k, s),
                    contact_taylor::last::<N>(k, s)
                );
            }
            Field::Slipping(k) => {
                slipping_taylor::order0(k, s);
                orders!(
                    p,
                    |N| slipping_taylor::order::<N>(k, s),
                    slipping_taylor::last::<N>(k, s)
                );
            }
            Field::Rolling(k) => {
                rolling_taylor::order0(k, s);
                orders!(
                    p,
                    |N| rolling_taylor::order::<N>(k, s),
                    rolling_taylor::last::<N>(k, s)
                );
            }
        }
    }

    /// The step the expansion is good for at `tol` (Jorba–Zou, with heyoka's safety factors):
    /// ρ = min over the last two orders n of (max(1, ‖x₀‖∞)/‖xₙ‖∞)^{1/n} over the six states,
    /// h = ρ/e² · e^{−0.7/(p−1)}.
    pub fn step_size(&self) -> f64 {
        self.rule.step(&self.series)
    }

    /// The forcing phasor (cos θ, sin θ) at local time `s`, from its series (exact to the
    /// truncation, like the states).
    pub fn phasor_at(&self, s: f64) -> (f64, f64) {
        (self.value(4, s), self.value(5, s))
    }

    /// The rotor state at local time `s` of the step.
    pub fn state_at(&self, s: f64) -> State {
        let v = |i| self.value(i, s);
        State::new(v(0), v(1), v(2), v(3))
    }

    /// The rotor state and the forcing phasor at local time `s`: the six state polynomials in
    /// one pass (where the next step starts). The same values as [`Expansion::state_at`] and
    /// [`Expansion::phasor_at`], bit for bit.
    pub fn point_at(&self, s: f64) -> (State, (f64, f64)) {
        const NONE: &[f64; CAPACITY] = &[0.0; CAPACITY];
        let series = [0, 1, 2, 3, 4, 5].map(|i| self.series.get(i).unwrap_or(NONE));
        let [x, y, vx, vy, ct, st] = kernels::evaluate_many(series, self.order, s);
        (State::new(x, y, vx, vy), (ct, st))
    }

    /// The switch function's polynomial coefficients (positive inside the regime).
    pub fn switch_polynomial(&self, switch: Switch) -> [f64; CAPACITY] {
        let (series, sign) = self.switch_series(switch);
        series.map(|c| c * sign)
    }

    /// The series of a switch function and the sign that makes it positive inside the regime
    /// (σ for the slip velocity, 1 otherwise): [`Expansion::switch_polynomial`] without a copy.
    pub fn switch_series(&self, switch: Switch) -> (&[f64; CAPACITY], f64) {
        const NONE: &[f64; CAPACITY] = &[0.0; CAPACITY];
        let (index, sign) = match (switch, &self.field) {
            (Switch::Boundary, Field::Contact(_)) => (contact_taylor::BOUNDARY, 1.0),
            (Switch::Boundary, Field::Slipping(_)) => (slipping_taylor::BOUNDARY, 1.0),
            (Switch::Boundary, Field::Rolling(_)) => (rolling_taylor::BOUNDARY, 1.0),
            (Switch::SlipVelocity, _) => (slipping_taylor::SLIP_VELOCITY, self.slip),
            (Switch::ConeUpper, _) => (rolling_taylor::CONE_UPPER, 1.0),
            (Switch::ConeLower, _) => (rolling_taylor::CONE_LOWER, 1.0),
        };
        (self.series.get(index).unwrap_or(NONE), sign)
    }

    /// The size of the terms a switch function's value at the expansion point is computed from
    /// (its rounding is relative to it): 1 for z² − 1 (z ≈ 1), |q'| + ρ_R η for w, μN + |λ|
    /// (the larger margin) for the friction cone.
    pub fn rounding_scale(&self, switch: Switch, model: &ModelParams) -> f64 {
        let at0 = |i: usize| {
            self.series
                .get(i)
                .map_or(0.0, |c| math::abs(kernels::at(c, 0)))
        };
        match switch {
            Switch::Boundary => 1.0,
            Switch::SlipVelocity => {
                at0(2).max(at0(3)) + math::abs(model.radius_ratio * model.speed_ratio)
            }
            Switch::ConeUpper | Switch::ConeLower => {
                at0(rolling_taylor::CONE_UPPER).max(at0(rolling_taylor::CONE_LOWER))
            }
        }
    }

    /// The order of the expansion (the degree of its polynomials).
    pub fn order(&self) -> usize {
        self.order
    }

    /// Put the exit through z = 1 near local time `s` (the switch polynomial's root, which
    /// differs from it by truncation only) onto the surface of the step's polynomial state: the
    /// switching function h = z² − 1 of the polynomial state ([`geometry::point`]) bracketed
    /// about `s` within [0, `h`] and refined by the one refinement ([`crate::refine`]); `s`
    /// itself when no bracket is found.
    pub fn polish_boundary(&self, model: &ModelParams, s: f64, h: f64) -> f64 {
        // The exit: g = −h rises through 0.
        let knot = |t: f64| {
            let (x, vx) = self.eval_d(0, t);
            let (y, vy) = self.eval_d(1, t);
            let p = geometry::point(model, State::new(x, y, vx, vy));
            Knot {
                s: t,
                g: -p.h,
                dg: -p.dh,
                point: (),
            }
        };
        crate::refine::polish_about(knot, s, h)
    }

    /// Series `i`'s polynomial at local time `s`.
    fn value(&self, i: usize, s: f64) -> f64 {
        self.series
            .get(i)
            .map_or(0.0, |c| kernels::evaluate(c, self.order, s))
    }

    /// Series `i`'s polynomial and its derivative at local time `s`.
    fn eval_d(&self, i: usize, s: f64) -> (f64, f64) {
        self.series.get(i).map_or((0.0, 0.0), |c| {
            kernels::evaluate_with_derivative(c, self.order, s)
        })
    }
}
