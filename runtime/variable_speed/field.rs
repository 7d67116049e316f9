//! The equations of motion on one piece of a speed profile (`docs/MODEL.md` §14), as the
//! systems the numerical integrators take: the constant-speed field at the speed η(τ) and phase
//! θ(τ) of the piece, plus the force of the speed's change (generated, `speed_change_force`).
//! On a piece that holds its speed this is the constant-speed field, bit for bit.

use crate::coefficients::{ModelParams, Phasor};
use crate::field::{self, Field};
use crate::math;
use crate::params::{Params, State};
use crate::propagate::Regime;
use crate::reference::{FieldFamily, OdeSystem};
use crate::speed::SpeedPiece;

/// The fields of one profile piece, by regime ([`FieldFamily`] of the reference solver).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RampField {
    /// The model's parameters (their speed ratio and phase are not used by the field).
    model: Params,
    /// `model` at the piece's highest speed and with its phase constant: what the switch
    /// functions and the step limit see (a quarter of the shortest forcing period on the piece
    /// bounds the step; on a piece that holds its speed these are its exact speed and phase,
    /// which friction's switch functions use).
    params: Params,
    piece: SpeedPiece,
}

impl RampField {
    /// The fields of `piece` for the model `params`.
    pub fn new(params: &Params, piece: SpeedPiece) -> Self {
        let end_speed = if piece.end.is_finite() {
            piece.speed_at(piece.end)
        } else {
            piece.speed_ratio
        };
        RampField {
            model: *params,
            params: Params {
                speed_ratio: piece.speed_ratio.max(end_speed),
                phase: piece.phase_constant,
                ..*params
            },
            piece,
        }
    }

    /// The piece.
    pub fn piece(&self) -> &SpeedPiece {
        &self.piece
    }
}

impl FieldFamily for RampField {
    type System = RampSystem;

    #[inline]
    fn system(&self, regime: Regime, slip: f64) -> RampSystem {
        RampSystem {
            params: self.model,
            regime,
            slip,
            piece: self.piece,
        }
    }

    fn params(&self) -> &Params {
        &self.params
    }
}

/// One regime's field on a profile piece, on `[x, y, x', y']`. (Friction is taken only on a
/// profile that holds its speed — a changing speed with friction is refused before a run
/// starts — where this is the constant-speed field with friction, bit for bit.)
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RampSystem {
    /// The model's parameters.
    pub params: Params,
    /// Which field.
    pub regime: Regime,
    /// The slip direction σ of slipping contact (±1), 0 when none is tracked.
    pub slip: f64,
    /// The speed profile's piece.
    pub piece: SpeedPiece,
}

impl OdeSystem<4> for RampSystem {
    #[inline]
    fn rhs(&self, t: f64, y: &[f64; 4]) -> [f64; 4] {
        let state = State::from_array(*y);
        let params = Params {
            speed_ratio: self.piece.speed_at(t),
            ..self.params
        };
        let (st, ct) = math::sin_cos(self.piece.phase_at(t));
        let (model, phasor) = (ModelParams::of(&params), Phasor { ct, st });
        let field = Field::of(self.regime, self.slip);
        let (mut ax, mut ay) = field::acceleration(&model, field, &phasor, &state);
        if self.piece.rate != 0.0 {
            let (fx, fy) = field::speed_change_force(&model, self.piece.rate, &phasor);
            ax += fx;
            ay += fy;
        }
        [state.vx, state.vy, ax, ay]
    }
}
