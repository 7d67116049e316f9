//! The checks of a matrix model's statement ([`super::MatrixModel::new`] and its input force):
//! each value finite and in its range, the station's degrees of freedom in range and distinct,
//! the contact stiffness's symmetric part positive definite — the first value that is wrong
//! named in a [`MatrixError`] with what is valid.

use super::error::MatrixError;
use super::model::Station;
use crate::params::{Parameter, Range};

pub(super) fn check_finite(
    what: &'static str,
    index: usize,
    value: f64,
) -> Result<(), MatrixError> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(MatrixError::NonFinite { what, index, value })
    }
}

pub(super) fn check_scalar(
    what: &'static str,
    value: f64,
    valid: Range,
) -> Result<(), MatrixError> {
    check_finite(what, 0, value)?;
    if valid.contains(value) {
        Ok(())
    } else {
        Err(MatrixError::OutOfRange { what, value, valid })
    }
}

pub(super) fn check_dof(what: &'static str, index: usize, dofs: usize) -> Result<(), MatrixError> {
    if index < dofs {
        Ok(())
    } else {
        Err(MatrixError::Dof { what, index, dofs })
    }
}

/// The station's DOFs (in range, four different ones), its offset, stiffness, friction and
/// radius. With friction the symmetric part of K_c must be positive definite (else the normal
/// force N = (z − 1) nᵀK_c n can be negative, `docs/MODEL.md` §10).
pub(super) fn check_station(s: &Station, n: usize) -> Result<(), MatrixError> {
    let mut dofs = [
        (s.rotor.0, "station rotor x"),
        (s.rotor.1, "station rotor y"),
        (0, ""),
        (0, ""),
    ];
    let mut count = 2;
    if let Some((x, y)) = s.stator {
        dofs[2] = (x, "station stator x");
        dofs[3] = (y, "station stator y");
        count = 4;
    }
    for (i, &(dof, what)) in dofs.iter().take(count).enumerate() {
        check_dof(what, dof, n)?;
        if dofs.iter().take(i).any(|&(d, _)| d == dof) {
            return Err(MatrixError::StationOverlap { index: dof });
        }
    }
    check_scalar("offset x", s.offset.0, Parameter::OffsetX.range())?;
    check_scalar("offset y", s.offset.1, Parameter::OffsetY.range())?;
    for (i, &k) in s.contact_stiffness.iter().flatten().enumerate() {
        check_finite("contact stiffness", i, k)?;
    }
    let k = s.contact_stiffness;
    let cross = 0.5 * (k[0][1] + k[1][0]);
    let determinant = k[0][0] * k[1][1] - cross * cross;
    if !(k[0][0] > 0.0 && k[1][1] > 0.0 && determinant > 0.0) {
        return Err(MatrixError::OutOfRange {
            what: "contact stiffness (determinant of its symmetric part, with K_c[0][0] > 0 and K_c[1][1] > 0)",
            value: determinant,
            valid: Range::above(0.0, f64::MAX),
        });
    }
    check_scalar(
        "friction coefficient",
        s.friction_coefficient,
        Parameter::FrictionCoefficient.range(),
    )?;
    check_scalar(
        "radius ratio",
        s.radius_ratio,
        Parameter::RadiusRatio.range(),
    )?;
    Ok(())
}

/// The input force vector of an n-DOF model (`input` empty: none) in CAP storage.
pub(super) fn input_forces<const CAP: usize>(
    input: &[f64],
    n: usize,
) -> Result<[f64; CAP], MatrixError> {
    let mut forces = [0.0; CAP];
    if input.is_empty() {
        return Ok(forces);
    }
    if input.len() != n {
        return Err(MatrixError::Shape {
            what: "input force",
            got: input.len(),
            expected: n,
        });
    }
    for (i, (slot, &f)) in forces.iter_mut().zip(input).enumerate() {
        check_finite("input force", i, f)?;
        *slot = f;
    }
    Ok(forces)
}
