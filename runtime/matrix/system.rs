//! A rotor from matrices as a [`System`] of the piecewise driver: the side of a start on the
//! contact surface, the slip direction at a contact start, the divergence test.

use super::model::MatrixModel;
use super::state::MatrixState;
use crate::coefficients::{self as coef, Acceleration, Position, StatorOffset};
use crate::driver::{System, TOUCH_DEPTH, motion_side};
use crate::field::{self, Field};
use crate::math;
use crate::propagate::{DIVERGENCE_RADIUS, EventKind, PropagationError, Regime};

/// The model behind any pointer (`&MatrixModel`, `Box`, `Rc`, `Arc`): its solvers and the
/// driver share one statement, too large to copy.
impl<const CAP: usize, M> System for M
where
    M: core::ops::Deref<Target = MatrixModel<CAP>>,
{
    type State = MatrixState<CAP>;

    /// As the planar model's (`docs/MODEL.md` §6 case 14) on the station's relative motion: off
    /// the band the sign of h (rolling where w = 0 exactly inside the friction cone); within
    /// it the side of h0 + h0'·s + ½h0''·s² (h0'' along the free field), the rotor point moved
    /// along the normal to h = ±2·[`TOUCH_DEPTH`] on that side.
    fn start_side(&self, time: f64, state: &Self::State) -> (Regime, Self::State) {
        let model: &MatrixModel<CAP> = self;
        let y = state.as_slice();
        let p = model.switching(y);
        let phasor = field::phasor(model.running(), time);
        let side = if math::abs(p.h) > TOUCH_DEPTH || p.h.is_nan() {
            p.h
        } else {
            let n = model.dofs();
            let mut dy = [0.0; CAP];
            model.derivative(Field::Free, &phasor, y, &mut dy);
            let acceleration = dy.get(n..2 * n).unwrap_or(&[]);
            let motion = model.station_motion(y);
            let a = Acceleration {
                ax: model.station_component(acceleration, 0),
                ay: model.station_component(acceleration, 1),
            };
            let d2h = coef::switching_curvature(model.running(), &motion.at, &motion.rate, &a).d2h;
            match motion_side(p.h, p.dh, d2h) {
                0.0 => p.h,
                side => side,
            }
        };
        let regime = if side <= 0.0 {
            Regime::Free
        } else if model.has_friction() && model.friction(&phasor, y).rolls() {
            Regime::Rolling
        } else {
            Regime::Contact
        };
        if math::abs(p.h) > TOUCH_DEPTH || p.h.is_nan() {
            return (regime, *state);
        }
        let target = if regime == Regime::Free {
            -2.0 * TOUCH_DEPTH
        } else {
            2.0 * TOUCH_DEPTH
        };
        let (d, _) = model.station_offset(y);
        let scale = math::sqrt(1.0 + target) / math::hypot(d.u, d.v);
        let moved = coef::position_at_offset(
            model.running(),
            &StatorOffset {
                u: d.u * scale,
                v: d.v * scale,
            },
        );
        // Move the rotor point by the change of P = B q.
        let motion = model.station_motion(y);
        let mut start = *state;
        let (rx, ry) = model.station().rotor;
        let q = start.as_mut_slice();
        let shift = Position {
            x: moved.x - motion.at.x,
            y: moved.y - motion.at.y,
        };
        if let Some(x) = q.get_mut(rx) {
            *x += shift.x;
        }
        if let Some(y) = q.get_mut(ry) {
            *y += shift.y;
        }
        (regime, start)
    }

    fn slip_direction(&self, time: f64, state: &Self::State, cause: Option<EventKind>) -> f64 {
        let model: &MatrixModel<CAP> = self;
        if !model.has_friction() {
            return 0.0;
        }
        let phasor = field::phasor(model.running(), time);
        model
            .friction(&phasor, state.as_slice())
            .slip_direction(cause)
    }

    /// Every entry finite and every displacement within [`DIVERGENCE_RADIUS`] clearances.
    fn within_bounds(&self, state: &Self::State) -> bool {
        state.is_finite()
            && state
                .positions()
                .iter()
                .all(|q| math::abs(*q) <= DIVERGENCE_RADIUS)
    }

    fn diverged(&self, time: f64, state: &Self::State) -> PropagationError {
        let model: &MatrixModel<CAP> = self;
        PropagationError::Diverged {
            time,
            state: model.station_motion(state.as_slice()).to_state(),
        }
    }
}
