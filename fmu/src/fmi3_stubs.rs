//! The FMI 3.0 functions this co-simulation FMU does not provide: present in the binary (FMI 3.0
//! requires every function, and importers bind them all), each logging why and returning
//! `fmi3Error`. Model exchange and scheduled execution instantiate nothing (null).

use core::ffi::{c_char, c_void};

use crate::instance::{Fmi3Logger, Log, Logger, slice, status, with_instance};
use crate::message::Message;

type Inst = *mut c_void;
type Status = i32;

macro_rules! unsupported {
    ($( $name:ident ( $($arg:ident : $t:ty),* ) $why:literal; )*) => {$(
        /// Not provided: logs why and returns `fmi3Error`.
        ///
        /// # Safety
        /// `i` is null or an instance of this FMU.
        #[unsafe(no_mangle)]
        pub unsafe extern "C" fn $name(i: Inst, $($arg: $t),*) -> Status {
            $(let _ = $arg;)*
            // SAFETY: caller's contract.
            unsafe {
                with_instance(i, |_| {
                    Err(Message::new(format_args!(concat!(stringify!($name), ": ", $why))))
                })
            }
        }
    )*};
}

type P = *const c_void;
type M = *mut c_void;

unsupported! {
    fmi3EnterEventMode() "event mode is not provided (hasEventMode = false)";
    fmi3EnterConfigurationMode() "no structural parameters";
    fmi3ExitConfigurationMode() "no structural parameters";
    fmi3EvaluateDiscreteStates() "no discrete states to evaluate in co-simulation";
    fmi3UpdateDiscreteStates(a: M, b: M, c: M, d: M, e: M, f: M) "event mode is not provided";
    fmi3EnterContinuousTimeMode() "model exchange is not provided";
    fmi3CompletedIntegratorStep(a: bool, b: M, c: M) "model exchange is not provided";
    fmi3SetTime(t: f64) "model exchange is not provided";
    fmi3SetContinuousStates(a: P, n: usize) "model exchange is not provided";
    fmi3GetContinuousStateDerivatives(a: M, n: usize) "model exchange is not provided";
    fmi3GetEventIndicators(a: M, n: usize) "model exchange is not provided";
    fmi3GetContinuousStates(a: M, n: usize) "model exchange is not provided";
    fmi3GetNominalsOfContinuousStates(a: M, n: usize) "model exchange is not provided";
    fmi3GetNumberOfEventIndicators(a: M) "model exchange is not provided";
    fmi3GetNumberOfContinuousStates(a: M) "model exchange is not provided";
    fmi3GetOutputDerivatives(a: P, b: usize, c: P, d: M, e: usize) "not provided (maxOutputDerivativeOrder = 0)";
    fmi3ActivateModelPartition(a: u32, t: f64) "scheduled execution is not provided";
    fmi3GetNumberOfVariableDependencies(a: u32, n: M) "dependencies are stated in modelDescription.xml only";
    fmi3GetVariableDependencies(a: u32, b: M, c: M, d: M, e: M, n: usize) "dependencies are stated in modelDescription.xml only";
    fmi3GetDirectionalDerivative(a: P, b: usize, c: P, d: usize, e: P, f: usize, g: M, h: usize) "not provided (providesDirectionalDerivative = false)";
    fmi3GetAdjointDerivative(a: P, b: usize, c: P, d: usize, e: P, f: usize, g: M, h: usize) "not provided (providesAdjointDerivatives = false)";
    fmi3GetIntervalDecimal(a: P, n: usize, b: M, c: M) "no clocks";
    fmi3GetIntervalFraction(a: P, n: usize, b: M, c: M, d: M) "no clocks";
    fmi3GetShiftDecimal(a: P, n: usize, b: M) "no clocks";
    fmi3GetShiftFraction(a: P, n: usize, b: M, c: M) "no clocks";
    fmi3SetIntervalDecimal(a: P, n: usize, b: P) "no clocks";
    fmi3SetIntervalFraction(a: P, n: usize, b: P, c: P) "no clocks";
    fmi3SetShiftDecimal(a: P, n: usize, b: P) "no clocks";
    fmi3SetShiftFraction(a: P, n: usize, b: P, c: P) "no clocks";
}

/// Get/set of a type the FMU has no variable of: OK for an empty list, else an error naming
/// the first value reference.
macro_rules! no_variables {
    ($( $name:ident ( $($arg:ident : $t:ty),* ); )*) => {$(
        /// No variable of this type: an empty list is OK, any value reference an error.
        ///
        /// # Safety
        /// `i` is null or an instance of this FMU; `vr` valid for `nvr` reads.
        #[unsafe(no_mangle)]
        pub unsafe extern "C" fn $name(i: Inst, vr: *const u32, nvr: usize, $($arg: $t),*) -> Status {
            $(let _ = $arg;)*
            // SAFETY: caller's contract.
            unsafe {
                with_instance(i, |_| match slice(vr, nvr)?.first() {
                    None => Ok(status::OK),
                    Some(r) => Err(Message::new(format_args!(
                        "{}: value reference {} is not of this type",
                        stringify!($name),
                        r
                    ))),
                })
            }
        }
    )*};
}

no_variables! {
    fmi3GetFloat32(v: M, n: usize);
    fmi3SetFloat32(v: P, n: usize);
    fmi3GetInt8(v: M, n: usize);
    fmi3SetInt8(v: P, n: usize);
    fmi3GetUInt8(v: M, n: usize);
    fmi3SetUInt8(v: P, n: usize);
    fmi3GetInt16(v: M, n: usize);
    fmi3SetInt16(v: P, n: usize);
    fmi3GetUInt16(v: M, n: usize);
    fmi3SetUInt16(v: P, n: usize);
    fmi3GetUInt32(v: M, n: usize);
    fmi3SetUInt32(v: P, n: usize);
    fmi3GetUInt64(v: M, n: usize);
    fmi3SetUInt64(v: P, n: usize);
    fmi3GetString(v: M, n: usize);
    fmi3SetString(v: P, n: usize);
    fmi3GetBinary(s: M, v: M, n: usize);
    fmi3SetBinary(s: P, v: P, n: usize);
    fmi3GetClock(v: M);
    fmi3SetClock(v: P);
}

/// Model exchange is not provided: logs why, returns null.
///
/// # Safety
/// FMI 3.0's contract.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3InstantiateModelExchange(
    _name: *const c_char,
    _token: *const c_char,
    _resources: *const c_char,
    _visible: bool,
    _logging_on: bool,
    environment: *mut c_void,
    log: Option<Fmi3Logger>,
) -> Inst {
    refuse(environment, log, "model exchange")
}

/// Scheduled execution is not provided: logs why, returns null.
///
/// # Safety
/// FMI 3.0's contract.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3InstantiateScheduledExecution(
    _name: *const c_char,
    _token: *const c_char,
    _resources: *const c_char,
    _visible: bool,
    _logging_on: bool,
    environment: *mut c_void,
    log: Option<Fmi3Logger>,
    _clock_update: *const c_void,
    _lock: *const c_void,
    _unlock: *const c_void,
) -> Inst {
    refuse(environment, log, "scheduled execution")
}

fn refuse(environment: *mut c_void, log: Option<Fmi3Logger>, what: &str) -> Inst {
    let log = Log::new(b"rotor_rub", Logger::Fmi3(log, environment), true);
    log.log(
        status::ERROR,
        &Message::new(format_args!(
            "{what} is not provided: this FMU is co-simulation only"
        )),
    );
    core::ptr::null_mut()
}
