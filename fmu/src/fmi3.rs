//! The FMI 3.0 co-simulation interface over [`crate::model::Model`]: instantiation with early
//! return, initialization, Float64/Int64/Int32/Boolean access, `fmi3DoStep` (returning at a
//! contact switch with its time when early return is allowed); FMU state get/set/serialize is
//! in `saved.rs`.
//! The functions FMI 3.0 requires but this FMU does not provide (model exchange, scheduled
//! execution, clocks, other types) are in `fmi3_stubs.rs`: they log why and return an error.

use core::ffi::{CStr, c_char, c_void};

use crate::description::units_of_token;
use crate::file::description::read_resource;
use crate::instance::{
    Fmi3Logger, Instance, Log, Logger, Phase, slice, slice_mut, status, with_instance,
};
use crate::model::Model;
use crate::msg;
use crate::step::Stepped;
use crate::units::Units;
use crate::variables::Kind;

type Inst = *mut c_void;
type Status = i32;

#[unsafe(no_mangle)]
pub extern "C" fn fmi3GetVersion() -> *const c_char {
    c"3.0".as_ptr()
}

/// # Safety
/// `i` is null or an instance of this FMU.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3SetDebugLogging(
    i: Inst,
    on: bool,
    n: usize,
    categories: *const *const c_char,
) -> Status {
    // SAFETY: caller's contract.
    unsafe {
        with_instance(i, |i| {
            i.log.set(on, slice(categories, n)?)?;
            Ok(status::OK)
        })
    }
}

/// # Safety
/// FMI 3.0's contract for `fmi3InstantiateCoSimulation`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3InstantiateCoSimulation(
    name: *const c_char,
    token: *const c_char,
    resources: *const c_char,
    _visible: bool,
    logging_on: bool,
    event_mode_used: bool,
    early_return_allowed: bool,
    _required: *const u32,
    _n_required: usize,
    environment: *mut c_void,
    log: Option<Fmi3Logger>,
    _intermediate_update: *const c_void,
) -> Inst {
    let result = std::panic::catch_unwind(|| {
        // SAFETY: FMI's contract: NUL-terminated strings or null.
        let name_bytes = if name.is_null() {
            &b"rotor_rub"[..]
        } else {
            unsafe { CStr::from_ptr(name) }.to_bytes()
        };
        let log = Log::new(name_bytes, Logger::Fmi3(log, environment), logging_on);
        // SAFETY: as above.
        let given = (!token.is_null()).then(|| unsafe { CStr::from_ptr(token) });
        let units = given.and_then(|g| units_of_token(g.to_str().ok()?));
        // Not a planar FMU's token: the FMU built for a model file, if its resource says so.
        // SAFETY: as above.
        let location = (!resources.is_null()).then(|| unsafe { CStr::from_ptr(resources) });
        let file = match (units, given.and_then(|g| g.to_str().ok())) {
            (None, Some(token)) => read_resource(location.and_then(|l| l.to_str().ok()), token),
            _ => Ok(None),
        };
        let (units, file) = match file {
            Ok(Some(f)) => (Some(Units::Si), Ok(Some(f))),
            other => (units, other),
        };
        let refused = if let Err(e) = &file {
            Some(msg!("{e}"))
        } else if event_mode_used {
            Some(msg!(
                "event mode is not provided (hasEventMode = false): instantiate with eventModeUsed = false"
            ))
        } else if units.is_none() {
            Some(msg!(
                "instantiation token {:?} is not this FMU's (the token in its modelDescription.xml)",
                given
            ))
        } else {
            None
        };
        match (refused, units) {
            (None, Some(units)) => {
                let mut instance = Instance::new(log, units);
                if let Ok(Some(f)) = file {
                    instance.model = Model::for_file(f);
                }
                instance.early_return = early_return_allowed;
                Box::into_raw(Box::new(instance)).cast::<c_void>()
            }
            (m, _) => {
                log.log(
                    status::ERROR,
                    &m.unwrap_or_else(|| msg!("instantiation refused")),
                );
                core::ptr::null_mut()
            }
        }
    });
    result.unwrap_or(core::ptr::null_mut())
}

/// # Safety
/// `i` is null or an instance of this FMU, not used afterwards.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3FreeInstance(i: Inst) {
    if !i.is_null() {
        // SAFETY: created by Box::into_raw at instantiation.
        drop(unsafe { Box::from_raw(i.cast::<Instance>()) });
    }
}

/// # Safety
/// `i` is null or an instance of this FMU.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3EnterInitializationMode(
    i: Inst,
    tolerance_defined: bool,
    tolerance: f64,
    start_time: f64,
    _stop_time_defined: bool,
    _stop_time: f64,
) -> Status {
    // SAFETY: caller's contract.
    unsafe {
        with_instance(i, |i| {
            i.expect("fmi3EnterInitializationMode", &[Phase::Instantiated])?;
            if !start_time.is_finite() {
                return Err(msg!("start time {start_time} is not finite"));
            }
            // The model-file FMU's method runs at its own tolerance.
            if tolerance_defined && i.model.file.is_none() {
                i.model.set(201, tolerance)?;
            }
            i.model.start_time = start_time;
            i.phase = Phase::Initialization;
            Ok(status::OK)
        })
    }
}

/// # Safety
/// `i` is null or an instance of this FMU.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3ExitInitializationMode(i: Inst) -> Status {
    // SAFETY: caller's contract.
    unsafe {
        with_instance(i, |i| {
            i.expect("fmi3ExitInitializationMode", &[Phase::Initialization])?;
            i.model.initialize()?;
            i.last_time = i.model.start_time;
            i.phase = Phase::Step;
            Ok(status::OK)
        })
    }
}

/// # Safety
/// `i` is null or an instance of this FMU.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3EnterStepMode(i: Inst) -> Status {
    // SAFETY: caller's contract.
    unsafe {
        with_instance(i, |i| {
            i.expect("fmi3EnterStepMode", &[Phase::Step])?;
            Ok(status::OK)
        })
    }
}

/// # Safety
/// `i` is null or an instance of this FMU.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3Terminate(i: Inst) -> Status {
    // SAFETY: caller's contract.
    unsafe {
        with_instance(i, |i| {
            i.phase = Phase::Terminated;
            Ok(status::OK)
        })
    }
}

/// # Safety
/// `i` is null or an instance of this FMU.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3Reset(i: Inst) -> Status {
    // SAFETY: caller's contract.
    unsafe {
        with_instance(i, |i| {
            i.model = i.model.reset();
            i.phase = Phase::Instantiated;
            Ok(status::OK)
        })
    }
}

macro_rules! access {
    ($get:ident, $set:ident, $t:ty, $kind:expr, $to:expr, $from:expr) => {
        /// # Safety
        /// FMI 3.0's contract: `nvr` value references, `n` values.
        #[unsafe(no_mangle)]
        pub unsafe extern "C" fn $get(
            i: Inst,
            vr: *const u32,
            nvr: usize,
            values: *mut $t,
            n: usize,
        ) -> Status {
            // SAFETY: caller's contract.
            unsafe {
                with_instance(i, |i| {
                    if n != nvr {
                        return Err(msg!("{} values for {} scalar variables", n, nvr));
                    }
                    let (vr, out) = (slice(vr, nvr)?, slice_mut(values, n)?);
                    i.get_all(vr, &[$kind], out, $to)?;
                    Ok(status::OK)
                })
            }
        }

        /// # Safety
        /// FMI 3.0's contract: `nvr` value references, `n` values.
        #[unsafe(no_mangle)]
        pub unsafe extern "C" fn $set(
            i: Inst,
            vr: *const u32,
            nvr: usize,
            values: *const $t,
            n: usize,
        ) -> Status {
            // SAFETY: caller's contract.
            unsafe {
                with_instance(i, |i| {
                    if n != nvr {
                        return Err(msg!("{} values for {} scalar variables", n, nvr));
                    }
                    let (vr, v) = (slice(vr, nvr)?, slice(values, n)?);
                    i.set_all(vr, &[$kind], v.iter().map($from))?;
                    Ok(status::OK)
                })
            }
        }
    };
}

access!(
    fmi3GetFloat64,
    fmi3SetFloat64,
    f64,
    Kind::Float,
    |v| v,
    |v: &f64| *v
);
access!(
    fmi3GetInt64,
    fmi3SetInt64,
    i64,
    Kind::Int64,
    |v| v as i64,
    |v: &i64| *v as f64
);
access!(
    fmi3GetInt32,
    fmi3SetInt32,
    i32,
    Kind::Int32,
    |v| v as i32,
    |v: &i32| f64::from(*v)
);
// fmi3Boolean is C's bool; read as a byte so that any non-zero value is true.
access!(
    fmi3GetBoolean,
    fmi3SetBoolean,
    u8,
    Kind::Bool,
    |v| u8::from(v != 0.0),
    |v: &u8| f64::from(u8::from(*v != 0))
);

/// # Safety
/// `i` is null or an instance of this FMU; the outputs valid for writes.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3DoStep(
    i: Inst,
    t: f64,
    h: f64,
    _no_set_prior: bool,
    event_handling_needed: *mut bool,
    terminate: *mut bool,
    early_return: *mut bool,
    last_successful_time: *mut f64,
) -> Status {
    // SAFETY: caller's contract.
    unsafe {
        with_instance(i, |i| {
            i.expect("fmi3DoStep", &[Phase::Step])?;
            // Without early return a capped step rewinds: keep where it started.
            let before = (!i.early_return).then(|| i.model.checkpoint());
            let (log, units) = (i.log, (i.model.units, i.model.scales()));
            let stepped = i
                .model
                .do_step(t, h, i.early_return, &mut |e| log.event(units, e));
            write(event_handling_needed, false);
            write(terminate, false);
            let (early, time, code) = match stepped {
                Ok(Stepped::Completed) => (false, t + h, status::OK),
                Ok(Stepped::Switch(at)) => (true, at, status::OK),
                Ok(Stepped::Capped(at)) if i.early_return => {
                    log.log(status::OK, &capped(&i.model, at, "returned early"));
                    (true, at, status::OK)
                }
                Ok(Stepped::Capped(at)) => {
                    // Without early return a partial step is a Discard, with the FMU in the
                    // state it had before the call (FMI 3.0, fmi3DoStep).
                    let m = capped(&i.model, at, "discarded: the FMU stays at the step's start");
                    if let Some(before) = &before {
                        i.model.rewind(before)?;
                    }
                    log.log(status::DISCARD, &m);
                    (false, t, status::DISCARD)
                }
                Err(m) => {
                    write(last_successful_time, i.model.time());
                    write(early_return, false);
                    return Err(m);
                }
            };
            if code == status::OK {
                i.last_time = time;
            }
            write(early_return, early);
            write(last_successful_time, time);
            Ok(code)
        })
    }
}

/// The message of a step ended by the work cap at `at`.
pub fn capped(model: &Model, at: f64, outcome: &str) -> crate::message::Message {
    msg!(
        "work cap reached: {} internal steps (max_internal_steps) covered the step up to t = {at}; {outcome}. Take shorter communication steps or raise max_internal_steps",
        model.settings.max_internal_steps
    )
}

/// Write an output argument (null skipped).
unsafe fn write<T>(p: *mut T, v: T) {
    if !p.is_null() {
        // SAFETY: caller's contract.
        unsafe { p.write(v) }
    }
}
