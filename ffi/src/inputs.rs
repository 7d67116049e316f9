//! The inputs a fixed-rate loop changes between steps: the external input force and the
//! running speed (`rotor_rub::Stepper::set_input_force`, `set_speed_ratio`).

use crate::raw::{guard, slot_mut};
use crate::types::*;

/// Apply the external input force (`fx`, `fy`) from the current time on, held constant until the
/// next call (what a magnetic bearing or a controller applies; `docs/MODEL.md` §15). Cheap: the
/// precomputed free-flight map is kept. On error nothing changes.
///
/// Returns `ROTOR_RUB_OK`; `ROTOR_RUB_ERR_NULL` if `stepper` is null;
/// `ROTOR_RUB_ERR_MISALIGNED`; `ROTOR_RUB_ERR_NOT_INITIALIZED`; `ROTOR_RUB_ERR_INVALID_VALUE` if
/// a component is not finite or outside [-1000, 1000] (`force_x`, `force_y` in the table).
///
/// # Safety
/// `stepper` as for `rotor_rub_stepper_step`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rotor_rub_stepper_set_input_force(
    stepper: *mut RotorRubStepper,
    fx: f64,
    fy: f64,
) -> i32 {
    guard(|| {
        // SAFETY: caller's contract.
        let slot = unsafe { slot_mut(stepper)? };
        slot.stepper
            .set_input_force(fx, fy)
            .map_err(|_| ROTOR_RUB_ERR_INVALID_VALUE)
    })
}

/// Change the running speed ratio η from the current time on with a continuous forcing phase
/// (the phase parameter is re-based); the unbalance amplitude follows η². Recomputes the
/// free-flight map when η changes. On error nothing changes.
///
/// Returns `ROTOR_RUB_OK`; `ROTOR_RUB_ERR_NULL` if `stepper` is null;
/// `ROTOR_RUB_ERR_MISALIGNED`; `ROTOR_RUB_ERR_NOT_INITIALIZED`; `ROTOR_RUB_ERR_INVALID_VALUE` if
/// `speed_ratio` is not finite or outside [0.001, 100].
///
/// # Safety
/// `stepper` as for `rotor_rub_stepper_step`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rotor_rub_stepper_set_speed_ratio(
    stepper: *mut RotorRubStepper,
    speed_ratio: f64,
) -> i32 {
    guard(|| {
        // SAFETY: caller's contract.
        let slot = unsafe { slot_mut(stepper)? };
        slot.stepper
            .set_speed_ratio(speed_ratio)
            .map_err(|_| ROTOR_RUB_ERR_INVALID_VALUE)
    })
}
