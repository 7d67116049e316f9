//! The stator ring with mass (issue 28): its state. A problem with `stator_mass_ratio` > 0
//! initialises a ring stepper (`rotor_rub::stepper::AnyStepper` decides); every other call is
//! the planar stepper's.

use crate::raw::{guard, slot_ref, write};
use crate::types::*;

/// The stator ring's state: its centre (x_s, y_s) and velocity, in clearances and clearances
/// per τ (all 0 for a massless ring, `stator_mass_ratio` = 0, which does not move).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RotorRubRingState {
    /// x_s.
    pub xs: f64,
    /// y_s.
    pub ys: f64,
    /// x_s'.
    pub vxs: f64,
    /// y_s'.
    pub vys: f64,
}

/// Read the stator ring's state at the current time (`rotor_rub_stepper_state` gives the
/// time, the rotor's state and the regime); all 0 when `stator_mass_ratio` = 0. `is_ring`
/// (optional: null skips it) receives 1 when the stepper runs the ring with mass, 0 for the
/// planar model.
///
/// Returns `ROTOR_RUB_OK`; `ROTOR_RUB_ERR_NULL` if `stepper` or `ring` is null;
/// `ROTOR_RUB_ERR_MISALIGNED`; `ROTOR_RUB_ERR_NOT_INITIALIZED`.
///
/// # Safety
/// `stepper` is null or valid initialised stepper memory; `ring` and `is_ring` null or valid
/// for writes.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rotor_rub_stepper_ring_state(
    stepper: *const RotorRubStepper,
    ring: *mut RotorRubRingState,
    is_ring: *mut i32,
) -> i32 {
    guard(|| {
        // SAFETY: caller's contract.
        let slot = unsafe { slot_ref(stepper)? };
        if ring.is_null() {
            return Err(ROTOR_RUB_ERR_NULL);
        }
        let r = slot.stepper.ring_state();
        let running = matches!(slot.stepper, rotor_rub::stepper::AnyStepper::Ring(_));
        // SAFETY: caller's contract.
        unsafe {
            write(
                ring,
                RotorRubRingState {
                    xs: r.xs,
                    ys: r.ys,
                    vxs: r.vxs,
                    vys: r.vys,
                },
            );
            write(is_ring, i32::from(running));
        }
        Ok(())
    })
}
