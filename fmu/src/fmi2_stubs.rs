//! The FMI 2.0 functions this co-simulation FMU does not provide (directional and input/output
//! derivatives, asynchronous step status), each logging why and returning `fmi2Error`, and
//! `fmi2GetRealStatus` for the last successful time and `fmi2GetBooleanStatus` for
//! `fmi2Terminated` (what a master asks after `fmi2Discard`).

use core::ffi::{c_char, c_int, c_void};

use crate::instance::{status, with_instance};
use crate::message::Message;
use crate::msg;

type Component = *mut c_void;
type Status = c_int;

macro_rules! unsupported {
    ($name:ident ( $($arg:ident : $t:ty),* ), $why:literal) => {
        /// # Safety
        /// `c` is null or an instance of this FMU.
        #[unsafe(no_mangle)]
        pub unsafe extern "C" fn $name(c: Component, $($arg: $t),*) -> Status {
            $(let _ = $arg;)*
            // SAFETY: caller's contract.
            unsafe { with_instance(c, |_| Err(Message::new(format_args!(concat!(stringify!($name), ": ", $why))))) }
        }
    };
}

unsupported!(fmi2GetDirectionalDerivative(a: *const u32, b: usize, d: *const u32, e: usize, f: *const f64, g: *mut f64), "not provided (providesDirectionalDerivative = false)");
unsupported!(fmi2SetRealInputDerivatives(a: *const u32, b: usize, d: *const c_int, e: *const f64), "inputs are held constant over a step (canInterpolateInputs = false)");
unsupported!(fmi2GetRealOutputDerivatives(a: *const u32, b: usize, d: *const c_int, e: *mut f64), "not provided (maxOutputDerivativeOrder = 0)");
unsupported!(fmi2GetStatus(a: c_int, b: *mut c_int), "steps complete synchronously: no status to ask for");
unsupported!(fmi2GetIntegerStatus(a: c_int, b: *mut c_int), "no Integer status");
unsupported!(fmi2GetStringStatus(a: c_int, b: *mut *const c_char), "no String status");

/// fmi2LastSuccessfulTime (kind 2) only.
///
/// # Safety
/// `c` is null or an instance of this FMU; `value` valid for a write.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetRealStatus(c: Component, kind: c_int, value: *mut f64) -> Status {
    // SAFETY: caller's contract.
    unsafe {
        with_instance(c, |i| {
            if kind != 2 {
                return Err(msg!(
                    "fmi2GetRealStatus: only fmi2LastSuccessfulTime (2) is provided, not {kind}"
                ));
            }
            *value.as_mut().ok_or_else(|| msg!("null value pointer"))? = i.last_time;
            Ok(status::OK)
        })
    }
}

/// fmi2Terminated (kind 3) only: always false (the FMU never asks to end the simulation; a
/// step ended by the work cap can be continued).
///
/// # Safety
/// `c` is null or an instance of this FMU; `value` valid for a write.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetBooleanStatus(
    c: Component,
    kind: c_int,
    value: *mut c_int,
) -> Status {
    // SAFETY: caller's contract.
    unsafe {
        with_instance(c, |_| {
            if kind != 3 {
                return Err(msg!(
                    "fmi2GetBooleanStatus: only fmi2Terminated (3) is provided, not {kind}"
                ));
            }
            *value.as_mut().ok_or_else(|| msg!("null value pointer"))? = 0;
            Ok(status::OK)
        })
    }
}
