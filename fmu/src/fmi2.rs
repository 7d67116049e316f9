//! The FMI 2.0 co-simulation interface over [`crate::model::Model`]: the functions of
//! `fmi2Functions.h`, each checking its arguments and the instance's phase, none panicking
//! across the boundary, none allocating after `fmi2Instantiate` except `fmi2GetFMUstate` (`saved.rs`, which
//! returns a new state object, as FMI 2.0 has it). A communication step ended by the work cap
//! returns `fmi2Discard` with the time reached as `fmi2LastSuccessfulTime` (`step.rs`).

use core::ffi::{CStr, c_char, c_int, c_void};

use crate::description::units_of_token;
use crate::file::description::read_resource;
use crate::instance::{
    Fmi2Logger, Instance, Log, Logger, Phase, slice, slice_mut, status, with_instance,
};
use crate::model::Model;
use crate::msg;
use crate::step::Stepped;
use crate::units::Units;
use crate::variables::Kind;

type Component = *mut c_void;
type Status = c_int;

/// `fmi2CallbackFunctions`.
#[repr(C)]
pub struct Callbacks {
    logger: Option<Fmi2Logger>,
    allocate_memory: Option<unsafe extern "C" fn(usize, usize) -> *mut c_void>,
    free_memory: Option<unsafe extern "C" fn(*mut c_void)>,
    step_finished: Option<unsafe extern "C" fn(*mut c_void, c_int)>,
    component_environment: *mut c_void,
}

const CO_SIMULATION: c_int = 1;

#[unsafe(no_mangle)]
pub extern "C" fn fmi2GetTypesPlatform() -> *const c_char {
    c"default".as_ptr()
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi2GetVersion() -> *const c_char {
    c"2.0".as_ptr()
}

/// # Safety
/// FMI 2.0's contract for `fmi2Instantiate`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2Instantiate(
    name: *const c_char,
    kind: c_int,
    guid: *const c_char,
    resources: *const c_char,
    functions: *const Callbacks,
    _visible: c_int,
    logging_on: c_int,
) -> Component {
    let result = std::panic::catch_unwind(|| {
        // SAFETY: FMI's contract: null or valid.
        let callbacks = unsafe { functions.as_ref() };
        let logger = Logger::Fmi2(
            callbacks.and_then(|c| c.logger),
            callbacks.map_or(core::ptr::null_mut(), |c| c.component_environment),
        );
        // SAFETY: FMI's contract: a NUL-terminated string or null.
        let name_bytes = if name.is_null() {
            &b"rotor_rub"[..]
        } else {
            unsafe { CStr::from_ptr(name) }.to_bytes()
        };
        let log = Log::new(name_bytes, logger, logging_on != 0);
        // SAFETY: as above.
        let given = (!guid.is_null()).then(|| unsafe { CStr::from_ptr(guid) });
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
        } else if kind != CO_SIMULATION {
            Some(msg!(
                "this FMU supports co-simulation only (fmuType = {kind})"
            ))
        } else if units.is_none() {
            Some(msg!(
                "GUID {:?} is not this FMU's (the guid in its modelDescription.xml)",
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
/// `c` is null or an instance of this FMU, not used afterwards.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2FreeInstance(c: Component) {
    if !c.is_null() {
        // SAFETY: created by Box::into_raw in fmi2Instantiate.
        drop(unsafe { Box::from_raw(c.cast::<Instance>()) });
    }
}

/// # Safety
/// `c` is null or an instance of this FMU.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SetDebugLogging(
    c: Component,
    logging_on: c_int,
    n: usize,
    categories: *const *const c_char,
) -> Status {
    // SAFETY: caller's contract.
    unsafe {
        with_instance(c, |i| {
            i.log.set(logging_on != 0, slice(categories, n)?)?;
            Ok(status::OK)
        })
    }
}

/// # Safety
/// `c` is null or an instance of this FMU.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SetupExperiment(
    c: Component,
    tolerance_defined: c_int,
    tolerance: f64,
    start_time: f64,
    _stop_time_defined: c_int,
    _stop_time: f64,
) -> Status {
    // SAFETY: caller's contract.
    unsafe {
        with_instance(c, |i| {
            i.expect("fmi2SetupExperiment", &[Phase::Instantiated])?;
            if !start_time.is_finite() {
                return Err(msg!("start time {start_time} is not finite"));
            }
            if tolerance_defined != 0 && i.model.file.is_none() {
                i.model.set(201, tolerance)?;
            }
            i.model.start_time = start_time;
            Ok(status::OK)
        })
    }
}

/// # Safety
/// `c` is null or an instance of this FMU.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2EnterInitializationMode(c: Component) -> Status {
    // SAFETY: caller's contract.
    unsafe {
        with_instance(c, |i| {
            i.expect("fmi2EnterInitializationMode", &[Phase::Instantiated])?;
            i.phase = Phase::Initialization;
            Ok(status::OK)
        })
    }
}

/// # Safety
/// `c` is null or an instance of this FMU.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2ExitInitializationMode(c: Component) -> Status {
    // SAFETY: caller's contract.
    unsafe {
        with_instance(c, |i| {
            i.expect("fmi2ExitInitializationMode", &[Phase::Initialization])?;
            i.model.initialize()?;
            i.last_time = i.model.start_time;
            i.phase = Phase::Step;
            Ok(status::OK)
        })
    }
}

/// # Safety
/// `c` is null or an instance of this FMU.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2Terminate(c: Component) -> Status {
    // SAFETY: caller's contract.
    unsafe {
        with_instance(c, |i| {
            i.phase = Phase::Terminated;
            Ok(status::OK)
        })
    }
}

/// # Safety
/// `c` is null or an instance of this FMU.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2Reset(c: Component) -> Status {
    // SAFETY: caller's contract.
    unsafe {
        with_instance(c, |i| {
            i.model = i.model.reset();
            i.phase = Phase::Instantiated;
            Ok(status::OK)
        })
    }
}

macro_rules! getter {
    ($name:ident, $t:ty, $kind:expr, $conv:expr) => {
        /// # Safety
        /// FMI 2.0's contract: arrays of `n` elements.
        #[unsafe(no_mangle)]
        pub unsafe extern "C" fn $name(
            c: Component,
            vr: *const u32,
            n: usize,
            values: *mut $t,
        ) -> Status {
            // SAFETY: caller's contract.
            unsafe {
                with_instance(c, |i| {
                    let (vr, out) = (slice(vr, n)?, slice_mut(values, n)?);
                    i.get_all(vr, &[$kind], out, $conv)?;
                    Ok(status::OK)
                })
            }
        }
    };
}

macro_rules! setter {
    ($name:ident, $t:ty, $kind:expr, $conv:expr) => {
        /// # Safety
        /// FMI 2.0's contract: arrays of `n` elements.
        #[unsafe(no_mangle)]
        pub unsafe extern "C" fn $name(
            c: Component,
            vr: *const u32,
            n: usize,
            values: *const $t,
        ) -> Status {
            // SAFETY: caller's contract.
            unsafe {
                with_instance(c, |i| {
                    let (vr, v) = (slice(vr, n)?, slice(values, n)?);
                    i.set_all(vr, &[$kind], v.iter().map($conv))?;
                    Ok(status::OK)
                })
            }
        }
    };
}

getter!(fmi2GetReal, f64, Kind::Float, |v| v);
getter!(fmi2GetBoolean, c_int, Kind::Bool, |v| c_int::from(v != 0.0));
setter!(fmi2SetReal, f64, Kind::Float, |v: &f64| *v);
setter!(fmi2SetBoolean, c_int, Kind::Bool, |v: &c_int| f64::from(*v));

/// # Safety
/// FMI 2.0's contract: arrays of `n` elements.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetInteger(
    c: Component,
    vr: *const u32,
    n: usize,
    values: *mut c_int,
) -> Status {
    // SAFETY: caller's contract.
    unsafe {
        with_instance(c, |i| {
            let (vrs, out) = (slice(vr, n)?, slice_mut(values, n)?);
            // Int64 counts saturate at the largest FMI 2.0 Integer.
            i.get_all(vrs, &[Kind::Int32, Kind::Int64], out, |v| {
                v.min(f64::from(c_int::MAX)) as c_int
            })?;
            Ok(status::OK)
        })
    }
}

/// # Safety
/// FMI 2.0's contract: arrays of `n` elements.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SetInteger(
    c: Component,
    vr: *const u32,
    n: usize,
    values: *const c_int,
) -> Status {
    // SAFETY: caller's contract.
    unsafe {
        with_instance(c, |i| {
            let (vrs, v) = (slice(vr, n)?, slice(values, n)?);
            i.set_all(
                vrs,
                &[Kind::Int32, Kind::Int64],
                v.iter().map(|&x| f64::from(x)),
            )?;
            Ok(status::OK)
        })
    }
}

/// # Safety
/// FMI 2.0's contract: arrays of `n` elements.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetString(
    c: Component,
    vr: *const u32,
    n: usize,
    _v: *mut *const c_char,
) -> Status {
    // SAFETY: caller's contract.
    unsafe { no_variables(c, "fmi2GetString (the FMU has no String variable)", vr, n) }
}

/// # Safety
/// FMI 2.0's contract: arrays of `n` elements.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SetString(
    c: Component,
    vr: *const u32,
    n: usize,
    _v: *const *const c_char,
) -> Status {
    // SAFETY: caller's contract.
    unsafe { no_variables(c, "fmi2SetString (the FMU has no String variable)", vr, n) }
}

/// OK for an empty list, else an error naming the first value reference.
unsafe fn no_variables(c: Component, what: &str, vr: *const u32, n: usize) -> Status {
    // SAFETY: caller's contract.
    unsafe {
        with_instance(c, |_| match slice(vr, n)?.first() {
            None => Ok(status::OK),
            Some(r) => Err(msg!("{what}: value reference {r} cannot be used here")),
        })
    }
}

/// # Safety
/// `c` is null or an instance of this FMU.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2DoStep(c: Component, t: f64, h: f64, _no_set_prior: c_int) -> Status {
    // SAFETY: caller's contract.
    unsafe {
        with_instance(c, |i| {
            i.expect("fmi2DoStep", &[Phase::Step])?;
            let (log, units) = (i.log, (i.model.units, i.model.scales()));
            match i.model.do_step(t, h, false, &mut |e| log.event(units, e))? {
                Stepped::Completed | Stepped::Switch(_) => {
                    i.last_time = t + h;
                    Ok(status::OK)
                }
                Stepped::Capped(at) => {
                    // FMI 2.0: Discard, "computed successfully only a subinterval"; the time
                    // reached is fmi2LastSuccessfulTime, and stepping on from it is allowed.
                    i.last_time = at;
                    let outcome = "the FMU stays there (fmi2LastSuccessfulTime): step on from it, or restore a saved state";
                    log.log(status::DISCARD, &crate::fmi3::capped(&i.model, at, outcome));
                    Ok(status::DISCARD)
                }
            }
        })
    }
}

/// # Safety
/// `c` is null or an instance of this FMU.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2CancelStep(c: Component) -> Status {
    // SAFETY: caller's contract.
    unsafe {
        with_instance(c, |_| {
            Err(msg!("fmi2CancelStep: steps complete synchronously"))
        })
    }
}
