//! Starts on z = 1 (`docs/MODEL.md` §6 case 14): which side the motion takes, and a start that
//! no solver can misread.

use super::TOUCH_DEPTH;
use crate::coefficients::ModelParams;
use crate::field::{self, Field};
use crate::geometry::{self, Point};
use crate::math;
use crate::params::{Params, State};
use crate::propagate::Regime;

/// The regime of a start at `(time, state)` and the state the solvers start from: unchanged off
/// z = 1; within [`TOUCH_DEPTH`] of z = 1, the side the motion takes once |h| leaves that band
/// (from the Taylor expansion h0 + h0'·s + ½h0''·s², where both fields agree, the contact force
/// vanishing on z = 1, so h0'' is the free field's), and the position moved radially to h =
/// ±2·[`TOUCH_DEPTH`] on that side (z changes by about 3e-14, below every method's resolution),
/// so that no solver sees a sign of h that is only rounding.
pub(crate) fn start_side(params: &Params, time: f64, state: &State) -> (Regime, State) {
    let model = ModelParams::of(params);
    let Point { h, dh, .. } = geometry::point(&model, *state);
    if math::abs(h) > TOUCH_DEPTH || h.is_nan() {
        return (field::regime_of(params, time, state), *state);
    }
    let free = field::acceleration(&model, Field::Free, &field::phasor(&model, time), state);
    let side = motion_side(h, dh, geometry::curvature(&model, state, free));
    let regime = if side > 0.0 {
        Regime::Contact
    } else if side < 0.0 {
        Regime::Free
    } else {
        // The motion stays on z = 1 to rounding: as `regime_of` decides.
        field::regime_of(params, time, state)
    };
    let target = match regime {
        Regime::Contact | Regime::Rolling => 2.0 * TOUCH_DEPTH,
        Regime::Free => -2.0 * TOUCH_DEPTH,
    };
    let (u, v) = geometry::offset(&model, state.x, state.y);
    let scale = math::sqrt(1.0 + target) / math::hypot(u, v);
    let (x, y) = geometry::at_offset(&model, (u * scale, v * scale));
    (regime, State { x, y, ..*state })
}

/// The side of z = 1 the motion takes from a start within [`TOUCH_DEPTH`] of it: the sign of
/// the expansion h0 + h0'·s + ½h0''·s² where it first leaves the band, marching s out
/// geometrically (0 when it never does: the motion stays on z = 1 to rounding).
pub(crate) fn motion_side(h: f64, dh: f64, d2h: f64) -> f64 {
    let c = 0.5 * d2h;
    let mut s = 1e-20;
    while s < 1e3 {
        let hs = h + dh * s + c * s * s;
        if math::abs(hs) > TOUCH_DEPTH {
            return hs;
        }
        s *= 2.0;
    }
    0.0
}
