//! The regime fields of a rotor from matrices (`docs/MODEL.md` §17): y' = A y + the forces'
//! accelerations, the contact's through M⁻¹Bᵀ f_c with f_c the generated station law; and the
//! station's own quantities (its point, offset, switching function, friction).

use super::model::MatrixModel;
use crate::coefficients::{
    self as coef, OffsetAcceleration, OffsetRate, Phasor, Position, Slip, StatorOffset, Velocity,
};
use crate::field::{Field, Friction};
use crate::geometry::Point;
use crate::params::State;

/// The rub station's relative motion: P = B q (the rotor point minus the stator point) and its
/// rate, as the planar formulas take a rotor's position and velocity (d = P − ε̂).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StationMotion {
    /// P = B q.
    pub at: Position,
    /// P' = B q'.
    pub rate: Velocity,
}

impl StationMotion {
    /// As a planar state (x, y, x', y') = (P, P'): what reports and the planar geometry take.
    pub fn to_state(self) -> State {
        State::new(self.at.x, self.at.y, self.rate.vx, self.rate.vy)
    }
}

impl<const CAP: usize> MatrixModel<CAP> {
    /// The station's relative motion in state `y` = (q, q').
    #[inline]
    pub fn station_motion(&self, y: &[f64]) -> StationMotion {
        let n = self.dofs();
        let (q, v) = y.split_at(n.min(y.len()));
        StationMotion {
            at: Position {
                x: self.station_component(q, 0),
                y: self.station_component(q, 1),
            },
            rate: Velocity {
                vx: self.station_component(v, 0),
                vy: self.station_component(v, 1),
            },
        }
    }

    /// The switching function h = z² − 1 of state `y` and its rate (generated
    /// `switching_function` at the station's relative motion).
    #[inline]
    pub fn switching(&self, y: &[f64]) -> Point {
        let m = self.station_motion(y);
        let s = coef::switching_function(self.running(), &m.at, &m.rate);
        Point {
            state: m.to_state(),
            h: s.h,
            dh: s.dh,
        }
    }

    /// d = P − ε̂ and d' of state `y` (generated `stator_offset`).
    #[inline]
    pub fn station_offset(&self, y: &[f64]) -> (StatorOffset, OffsetRate) {
        let m = self.station_motion(y);
        let d = coef::stator_offset(self.running(), &m.at);
        (
            StatorOffset { u: d.u, v: d.v },
            OffsetRate {
                ur: m.rate.vx,
                vr: m.rate.vy,
            },
        )
    }

    /// y' = f(y) of `field` with the forcing direction `phasor`, into `dy` (2n entries each).
    /// Every force enters through M⁻¹: the unbalance η² Re(M⁻¹f̂ e^{iθ}), the input M⁻¹u and,
    /// in contact, M⁻¹Bᵀ f_c with the generated station law (`station_slipping`, or while
    /// rolling `station_rolling` with the offset's acceleration from every other force).
    pub fn derivative(&self, field: Field, phasor: &Phasor, y: &[f64], dy: &mut [f64]) {
        self.derivative_inline(field, phasor, y, dy);
    }

    /// [`Self::derivative`] of a whole state, returned: an integrator's stage (inlined).
    #[inline(always)]
    pub(crate) fn stage(&self, field: Field, phasor: &Phasor, y: &[f64; CAP]) -> [f64; CAP] {
        let mut dy = [0.0; CAP];
        self.derivative_inline(field, phasor, y, &mut dy);
        dy
    }

    /// [`Self::derivative`] inlined into its caller: an integrator's stage, where the call's
    /// own cost is a tenth of the field's.
    #[inline(always)]
    fn derivative_inline(&self, field: Field, phasor: &Phasor, y: &[f64], dy: &mut [f64]) {
        let n = self.dofs();
        // A model that fills its storage (n = CAP/2: the ring in CAP = 8) runs the same body
        // with every length a constant, which the compiler unrolls and checks once.
        if 2 * n == CAP
            && let (Some(y), Some(dy)) = (y.first_chunk::<CAP>(), dy.first_chunk_mut::<CAP>())
        {
            self.field_of_size(CAP / 2, field, phasor, y, dy);
        } else {
            self.field_of_size(n, field, phasor, y, dy);
        }
    }

    /// [`Self::derivative`] for `n` = the model's DOFs.
    #[inline(always)]
    fn field_of_size(&self, n: usize, field: Field, phasor: &Phasor, y: &[f64], dy: &mut [f64]) {
        let (Some(y), Some(dy)) = (y.get(..2 * n), dy.get_mut(..2 * n)) else {
            return;
        };
        let (unbalance, input, [cx, cy]) = self.force_accelerations();
        let (Some(unbalance), Some(input), Some(cx), Some(cy)) =
            (unbalance.get(..n), input.get(..n), cx.get(..n), cy.get(..n))
        else {
            return;
        };
        let a = self.linear();
        let force = self.running().unbalance_force;
        let (ct, st) = (phasor.ct, phasor.st);
        let (dq, dv) = dy.split_at_mut(n);
        for (d, &v) in dq.iter_mut().zip(y.iter().skip(n)) {
            *d = v;
        }
        a.times(y, dv);
        for (acc, (u, &f)) in dv.iter_mut().zip(unbalance.iter().zip(input)) {
            *acc = *acc + force * (u.re * ct - u.im * st) + f;
        }
        let (fx, fy) = match field {
            Field::Free => return,
            Field::Contact | Field::Slipping(_) => {
                let sigma = match field {
                    Field::Slipping(s) => s,
                    _ => 0.0,
                };
                let (d, r) = self.station_offset(y);
                let f = coef::station_slipping(self.running(), &d, &Slip { sigma }, &r, self.law());
                (f.fx, f.fy)
            }
            Field::Rolling => {
                let f = self.rolling_law(y, dv);
                (f.fx, f.fy)
            }
        };
        for ((acc, x), y) in dv.iter_mut().zip(cx).zip(cy) {
            *acc += x * fx + y * fy;
        }
    }

    /// The generated rolling law at `y` (`docs/MODEL.md` §17: λ with W = B M⁻¹ Bᵀ), the station
    /// driven by `acceleration`, the DOFs' accelerations from every force but the contact's.
    fn rolling_law(&self, y: &[f64], acceleration: &[f64]) -> coef::StationRolling {
        let (d, r) = self.station_offset(y);
        let drive = OffsetAcceleration {
            au: self.station_component(acceleration, 0),
            av: self.station_component(acceleration, 1),
        };
        coef::station_rolling(
            self.running(),
            &d,
            &r,
            self.law(),
            self.compliance(),
            &drive,
        )
    }

    /// The friction quantities of a contact state `y` (`docs/MODEL.md` §10, §17): N, w, the
    /// rolling force λ and the cone μN ∓ λ, from the generated station law.
    pub fn friction(&self, phasor: &Phasor, y: &[f64]) -> Friction {
        let n = self.dofs();
        let (d, r) = self.station_offset(y);
        let slipping =
            coef::station_slipping(self.running(), &d, &Slip { sigma: 0.0 }, &r, self.law());
        // The offset's acceleration from every force but the contact's: the free field's.
        let mut dy = [0.0; CAP];
        self.derivative(Field::Free, phasor, y, &mut dy);
        let acceleration = dy.get(n..2 * n).unwrap_or(&[]);
        let rolling = self.rolling_law(y, acceleration);
        Friction {
            normal: rolling.normal,
            slip_velocity: slipping.slip_velocity,
            lambda: rolling.lambda,
            cone: (rolling.upper, rolling.lower),
        }
    }
}
