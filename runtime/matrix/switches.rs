//! The switch functions of a rotor from matrices (`docs/MODEL.md` §10, §17), as the numerical
//! methods search them on a step's dense output: z = 1 always (h = z² − 1 of the station's
//! relative motion); while slipping σw (the slip velocity reaching 0); while rolling
//! μN − |λ| (the friction limit). Each comes with its rate along the regime's field, from the
//! generated station law (`station_slip_rate`, `station_cone_rates`): the offset's
//! accelerations they take (d'' of the whole field, the drive a of every force but the contact's
//! and its rate a') are B applied to the model's accelerations — linear algebra on the model,
//! not a formula. Where σw reaches 0 the friction rules decide ([`Friction::at_slip_zero`]).

use super::model::MatrixModel;
use super::state::MatrixState;
use crate::coefficients::{
    self as coef, Acceleration, DriveRate, OffsetAcceleration, Phasor, PhasorRate, Slip,
};
use crate::driver::SegmentStart;
use crate::field::{self, Field, Friction, SlipZero};
use crate::propagate::{EventKind, Regime};
pub use crate::reference::Function;

/// The accelerations a station's rates take, at one state.
struct Accelerations {
    /// d'' along the field (every force).
    offset: Acceleration,
    /// a = the offset's acceleration from every force but the contact's.
    drive: OffsetAcceleration,
}

impl<const CAP: usize> MatrixModel<CAP> {
    /// B applied to the acceleration part (entries n … 2n) of a first-order derivative `dy`.
    #[inline]
    fn offset_acceleration(&self, dy: &[f64]) -> Acceleration {
        let n = self.dofs();
        let acc = dy.get(n..2 * n).unwrap_or(&[]);
        Acceleration {
            ax: self.station_component(acc, 0),
            ay: self.station_component(acc, 1),
        }
    }

    /// d'' along `field` and the drive a (the free field's d'') at `y`, with `field`'s
    /// derivative left in `dy`.
    fn accelerations(
        &self,
        field: Field,
        phasor: &Phasor,
        y: &[f64],
        dy: &mut [f64; CAP],
    ) -> Accelerations {
        self.derivative(Field::Free, phasor, y, dy);
        let free = self.offset_acceleration(dy);
        self.derivative(field, phasor, y, dy);
        Accelerations {
            offset: self.offset_acceleration(dy),
            drive: OffsetAcceleration {
                au: free.ax,
                av: free.ay,
            },
        }
    }

    /// The slip velocity w and its rate w' along the field of slipping in direction `slip`
    /// (generated `station_slipping`, `station_slip_rate`).
    pub fn slip_velocity_and_rate(&self, phasor: &Phasor, y: &[f64], slip: f64) -> (f64, f64) {
        let (d, r) = self.station_offset(y);
        let w = coef::station_slipping(self.running(), &d, &Slip { sigma: slip }, &r, self.law())
            .slip_velocity;
        let mut dy = [0.0; CAP];
        self.derivative(Field::of(Regime::Contact, slip), phasor, y, &mut dy);
        let a = self.offset_acceleration(&dy);
        (w, coef::station_slip_rate(&d, &a, &r).rate)
    }

    /// The `slip` switch function of rolling, min(μN − λ, μN + λ) = μN − |λ|, and its rate
    /// along the rolling field (generated `station_cone_rates`; the drive's rate
    /// a' = B(A ẏ)'s acceleration part + the unbalance at the phasor's rate, generated
    /// `forcing_phasor_rate`).
    pub fn cone_margin(&self, phasor: &Phasor, y: &[f64]) -> (f64, f64) {
        let n = self.dofs();
        let (d, r) = self.station_offset(y);
        let mut dy = [0.0; CAP];
        let acc = self.accelerations(Field::Rolling, phasor, y, &mut dy);
        // The free part's acceleration changes at A ẏ (lower half) + η² Re(M⁻¹f̂ (cos θ, sin θ)').
        let turn: PhasorRate = coef::forcing_phasor_rate(self.running(), phasor);
        let force = self.running().unbalance_force;
        let unbalance = self.unbalance_acceleration();
        let a = self.linear();
        let mut jerk = [0.0; CAP];
        let mut linear = [0.0; CAP];
        a.times(&dy, linear.get_mut(..n).unwrap_or(&mut []));
        for (i, (j, &linear)) in jerk.iter_mut().zip(&linear).enumerate().take(n) {
            let u = unbalance.get(i).copied().unwrap_or_default();
            *j = linear + force * (u.re * turn.ct_rate - u.im * turn.st_rate);
        }
        let drive_rate = DriveRate {
            au_rate: self.station_component(&jerk, 0),
            av_rate: self.station_component(&jerk, 1),
        };
        let c = coef::station_cone_rates(
            self.running(),
            &d,
            &acc.offset,
            &r,
            self.law(),
            self.compliance(),
            &acc.drive,
            &drive_rate,
        );
        if c.upper <= c.lower {
            (c.upper, c.upper_rate)
        } else {
            (c.lower, c.lower_rate)
        }
    }
}

/// The switch functions of one segment of a matrix model: its regime, slip direction, and the
/// offset that makes its friction function start at ≥ 0 (`docs/MODEL.md` §10 traps 1–2: after
/// `slip` or `reverse` the segment starts on w = 0 to rounding, after `roll` on |λ| ≈ μN; the
/// start's value, when negative, is subtracted so that the start is not found again).
pub struct MatrixSwitches<'a, const CAP: usize> {
    model: &'a MatrixModel<CAP>,
    regime: Regime,
    slip: f64,
    offset: f64,
}

/// A segment's side as a numerical solver's switch search keeps it from the segment's start:
/// regime, slip direction σ and the slip-velocity function's offset there
/// ([`MatrixSwitches::start_offset`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct SegmentSide {
    regime: Regime,
    slip: f64,
    offset: f64,
}

impl SegmentSide {
    /// No segment yet (free flight, no slip).
    pub(crate) const NONE: SegmentSide = SegmentSide {
        regime: Regime::Free,
        slip: 0.0,
        offset: 0.0,
    };

    /// The side of a segment of `model` starting at `at`.
    pub(crate) fn at<const CAP: usize>(
        model: &MatrixModel<CAP>,
        at: &SegmentStart<MatrixState<CAP>>,
    ) -> Self {
        let (regime, slip) = (at.regime, at.slip);
        let offset = MatrixSwitches::start_offset(model, regime, slip, at.time, at.state.array());
        SegmentSide {
            regime,
            slip,
            offset,
        }
    }

    /// The segment's field.
    pub(crate) fn field(&self) -> Field {
        Field::of(self.regime, self.slip)
    }

    /// The segment's switch functions on `model`.
    pub(crate) fn switches<'a, const CAP: usize>(
        &self,
        model: &'a MatrixModel<CAP>,
    ) -> MatrixSwitches<'a, CAP> {
        MatrixSwitches::new(model, self.regime, self.slip, self.offset)
    }
}

impl<'a, const CAP: usize> MatrixSwitches<'a, CAP> {
    /// The switch functions of a segment of `regime` (slip direction `slip`) with friction
    /// offset `offset` (≤ 0; see [`MatrixSwitches::start_offset`]).
    pub fn new(model: &'a MatrixModel<CAP>, regime: Regime, slip: f64, offset: f64) -> Self {
        MatrixSwitches {
            model,
            regime,
            slip,
            offset,
        }
    }

    /// The friction offset of a segment of `regime` (slip `slip`) starting at `(t, y)`: the
    /// friction function's value there when negative, else 0.
    pub fn start_offset(
        model: &'a MatrixModel<CAP>,
        regime: Regime,
        slip: f64,
        t: f64,
        y: &[f64],
    ) -> f64 {
        let s = MatrixSwitches::new(model, regime, slip, 0.0);
        match s.friction_function() {
            Some(f) => s.measure(f, t, y).0.min(0.0),
            None => 0.0,
        }
    }

    /// The regime's switch functions: z = 1, then friction's if any.
    pub fn functions(&self) -> [Option<Function>; 2] {
        [Some(Function::Boundary), self.friction_function()]
    }

    /// The friction switch function of the regime, if any.
    pub fn friction_function(&self) -> Option<Function> {
        match self.regime {
            Regime::Contact if self.slip != 0.0 => Some(Function::SlipVelocity),
            Regime::Rolling => Some(Function::SlipLimit),
            Regime::Free | Regime::Contact => None,
        }
    }

    /// The value of `f` at `(t, y)` (positive inside the regime) and its time derivative.
    pub fn measure(&self, f: Function, t: f64, y: &[f64]) -> (f64, f64) {
        match f {
            Function::Boundary => {
                let p = self.model.switching(y);
                match self.regime {
                    Regime::Free => (-p.h, -p.dh),
                    Regime::Contact | Regime::Rolling => (p.h, p.dh),
                }
            }
            Function::SlipVelocity => {
                let phasor = field::phasor(self.model.running(), t);
                let (w, rate) = self.model.slip_velocity_and_rate(&phasor, y, self.slip);
                (self.slip * w - self.offset, self.slip * rate)
            }
            Function::SlipLimit => {
                let phasor = field::phasor(self.model.running(), t);
                let (margin, rate) = self.model.cone_margin(&phasor, y);
                (margin - self.offset, rate)
            }
        }
    }

    /// The friction quantities at `(t, y)`.
    pub fn friction(&self, t: f64, y: &[f64]) -> Friction {
        let phasor = field::phasor(self.model.running(), t);
        self.model.friction(&phasor, y)
    }

    /// The event a crossing of `f` at `(t, y)` is, or `None` for a touch of w = 0.
    pub fn classify(&self, f: Function, t: f64, y: &[f64]) -> Option<EventKind> {
        match f {
            Function::Boundary => Some(match self.regime {
                Regime::Free => EventKind::Enter,
                Regime::Contact | Regime::Rolling => EventKind::Exit,
            }),
            Function::SlipLimit => Some(EventKind::Slip),
            Function::SlipVelocity => match self.friction(t, y).at_slip_zero(self.slip) {
                SlipZero::Roll => Some(EventKind::Roll),
                SlipZero::Reverse => Some(EventKind::Reverse),
                SlipZero::Touch => None,
            },
        }
    }

    /// The scale a function's value is computed from (its rounding is relative to it): 1 for
    /// z² − 1 (z ≈ 1), |P'| + ρ_R η for w, μN + |λ| for the friction cone.
    pub fn rounding_scale(&self, f: Function, t: f64, y: &[f64]) -> f64 {
        match f {
            Function::Boundary => 1.0,
            Function::SlipVelocity => {
                let m = self.model.station_motion(y);
                let r = self.model.running();
                crate::math::hypot(m.rate.vx, m.rate.vy)
                    + crate::math::abs(r.radius_ratio * r.speed_ratio)
            }
            Function::SlipLimit => {
                let f = self.friction(t, y);
                f.cone.0.max(f.cone.1)
            }
        }
    }
}
