//! How finely the stepper resolves contact: what a rig needs to size `dt` and `max_substeps`
//! before running on a stiff stator.

use crate::raw::{guard, slot_ref, write};
use crate::types::*;

/// The contact sub-steps the stepper takes per step of its `dt` for the parameters in force
/// (the configured `contact_substeps`, or more where the stator's contact mode needs them: each
/// sub-step at most 0.5/ρ_c, ρ_c the contact mode's rate bound), and the longest step whose
/// sub-steps fit `max_substeps` (a longer step through contact is flagged `capped`, or refused
/// under `on_cap` = FAIL). For the ring with mass (`stator_mass_ratio` > 0), whose methods
/// choose their own steps: `substeps` = 0 and `largest_resolved_dt` = +infinity.
///
/// Returns `ROTOR_RUB_OK`; `ROTOR_RUB_ERR_NULL` if `stepper` is null;
/// `ROTOR_RUB_ERR_MISALIGNED`; `ROTOR_RUB_ERR_NOT_INITIALIZED`.
///
/// # Safety
/// `stepper` is null or valid initialised stepper memory; `substeps` and
/// `largest_resolved_dt` null (skipped) or valid for writes.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rotor_rub_stepper_contact_resolution(
    stepper: *const RotorRubStepper,
    substeps: *mut u32,
    largest_resolved_dt: *mut f64,
) -> i32 {
    guard(|| {
        // SAFETY: caller's contract.
        let slot = unsafe { slot_ref(stepper)? };
        let (n, dt) = slot
            .stepper
            .contact_resolution()
            .unwrap_or((0, f64::INFINITY));
        // SAFETY: caller's contract.
        unsafe {
            write(substeps, n);
            write(largest_resolved_dt, dt);
        }
        Ok(())
    })
}
