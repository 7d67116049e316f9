//! The stator ring with mass (`docs/MODEL.md` §17) as the n = 4 instance of the matrix model:
//! positions (x, y, x_s, y_s), the matrices and the contact stiffness generated from the
//! table's entries (`ring_matrices`), the station between the rotor's pair and the ring's.

use super::error::MatrixError;
use super::model::{MatrixModel, Running, Station, Unbalance};
use super::state::MatrixState;
use crate::coefficients::{self as coef, RingMatrices};
use crate::linalg::{RealMatrix, SecondOrder};
use crate::params::{Params, Problem};

/// First-order capacity of the ring model: n = 4, y = (x, y, x_s, y_s, x', y', x_s', y_s').
pub const RING_CAPACITY: usize = 8;

/// The stator ring model's statement.
pub type RingModel = MatrixModel<RING_CAPACITY>;

/// The ring model of `params` (`stator_mass_ratio` > 0; validated by the caller).
///
/// # Errors
/// A [`MatrixError`] when the matrices cannot be decomposed (never for validated parameters
/// with m̂ > 0).
pub fn ring_model(params: &Params) -> Result<RingModel, MatrixError> {
    let model = coef::model_params(params);
    let m: RingMatrices = coef::ring_matrices(&model);
    let masses = [m.m0, m.m1, m.m2, m.m3];
    let mass = RealMatrix::from_fn(4, 4, |i, j| {
        if i == j {
            masses.get(i).copied().unwrap_or(0.0)
        } else {
            0.0
        }
    })?;
    let c = [
        [m.c00, m.c01, m.c02, m.c03],
        [m.c10, m.c11, m.c12, m.c13],
        [m.c20, m.c21, m.c22, m.c23],
        [m.c30, m.c31, m.c32, m.c33],
    ];
    let k = [
        [m.k00, m.k01, m.k02, m.k03],
        [m.k10, m.k11, m.k12, m.k13],
        [m.k20, m.k21, m.k22, m.k23],
        [m.k30, m.k31, m.k32, m.k33],
    ];
    let entry = |a: &[[f64; 4]; 4], i: usize, j: usize| {
        a.get(i).and_then(|r| r.get(j)).copied().unwrap_or(0.0)
    };
    let damping = RealMatrix::from_fn(4, 4, |i, j| entry(&c, i, j))?;
    let stiffness = RealMatrix::from_fn(4, 4, |i, j| entry(&k, i, j))?;
    let gyroscopic = RealMatrix::zeros(4, 4)?;
    let rotor = SecondOrder {
        mass: &mass,
        damping: &damping,
        gyroscopic: &gyroscopic,
        stiffness: &stiffness,
    };
    MatrixModel::new(
        &rotor,
        Running {
            speed_ratio: params.speed_ratio,
            phase: params.phase,
        },
        &[Unbalance {
            x: 0,
            y: 1,
            amount: model.unbalance,
            phase: 0.0,
        }],
        &[params.force_x, params.force_y, 0.0, 0.0],
        Station {
            rotor: (0, 1),
            stator: Some((2, 3)),
            offset: (params.offset_x, params.offset_y),
            contact_stiffness: [[m.kc_xx, m.kc_xy], [m.kc_yx, m.kc_yy]],
            friction_coefficient: params.friction_coefficient,
            radius_ratio: params.radius_ratio,
        },
    )
}

/// The ring model's start: the rotor's initial state and the ring's (`xs0` … `vys0`).
pub fn ring_start(problem: &Problem) -> MatrixState<RING_CAPACITY> {
    let (r, p) = (problem.initial, problem.params);
    MatrixState::full([r.x, r.y, p.xs0, p.ys0, r.vx, r.vy, p.vxs0, p.vys0])
}
