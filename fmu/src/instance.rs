//! One FMU instance, shared by the FMI 2.0 and 3.0 layers: the model, the FMI state machine's
//! phase, the importer's logger, and the checked, panic-free plumbing every exported function
//! goes through (null pointers, value references of the wrong type, phases, caught panics).

use core::ffi::{c_char, c_void};
use std::panic::{AssertUnwindSafe, catch_unwind};

use crate::message::Message;
use crate::model::Model;
use crate::msg;
use crate::variables::{self, Kind, Role};

/// FMI status codes (the same numbers in FMI 2.0 and 3.0).
pub mod status {
    /// OK.
    pub const OK: i32 = 0;
    /// Warning.
    pub const WARNING: i32 = 1;
    /// Discard.
    pub const DISCARD: i32 = 2;
    /// Error.
    pub const ERROR: i32 = 3;
    /// Fatal.
    pub const FATAL: i32 = 4;
}

/// The FMI 2.0 logger: variadic, its message is a printf format.
pub type Fmi2Logger =
    unsafe extern "C" fn(*mut c_void, *const c_char, i32, *const c_char, *const c_char, ...);
/// The FMI 3.0 logger.
pub type Fmi3Logger = unsafe extern "C" fn(*mut c_void, i32, *const c_char, *const c_char);

/// Where log messages go.
#[derive(Clone, Copy)]
pub enum Logger {
    /// FMI 2.0 callbacks.
    Fmi2(Option<Fmi2Logger>, *mut c_void),
    /// FMI 3.0 callback.
    Fmi3(Option<Fmi3Logger>, *mut c_void),
}

/// Where an instance is in the FMI state machine.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Phase {
    /// After instantiation: parameters and inputs may be set.
    Instantiated,
    /// In initialization mode.
    Initialization,
    /// Stepping.
    Step,
    /// After terminate.
    Terminated,
}

/// One instance.
pub struct Instance {
    /// The model.
    pub model: Model,
    /// The phase.
    pub phase: Phase,
    /// The logger.
    pub logger: Logger,
    /// Whether the importer wants log messages other than errors.
    pub logging_on: bool,
    /// FMI 3.0: fmi3DoStep may return early at a switch.
    pub early_return: bool,
    /// The experiment's start time.
    pub start_time: f64,
    /// The end of the last completed (or early-returned) step.
    pub last_time: f64,
    name: [u8; 64],
}

impl Instance {
    /// A new instance named `name` (truncated to 63 bytes).
    pub fn new(name: &[u8], logger: Logger, logging_on: bool) -> Instance {
        let mut n = [0u8; 64];
        for (d, s) in n.iter_mut().zip(name.iter().take(63)) {
            *d = *s;
        }
        Instance {
            model: Model::default(),
            phase: Phase::Instantiated,
            logger,
            logging_on,
            early_return: false,
            start_time: 0.0,
            last_time: 0.0,
            name: n,
        }
    }

    /// Log `message` with `status` (errors always, the rest when logging is on).
    pub fn log(&self, status: i32, message: &Message) {
        if status < status::WARNING && !self.logging_on {
            return;
        }
        let category = match status {
            status::OK => c"logAll",
            status::WARNING => c"logStatusWarning",
            status::DISCARD => c"logStatusDiscard",
            status::ERROR => c"logStatusError",
            _ => c"logStatusFatal",
        };
        match self.logger {
            Logger::Fmi2(Some(log), env) => {
                // SAFETY: the importer's logger, called as FMI 2.0 specifies; the message is
                // passed as the argument of a "%s" format, never as a format itself.
                unsafe {
                    log(
                        env,
                        self.name.as_ptr().cast(),
                        status,
                        category.as_ptr(),
                        c"%s".as_ptr(),
                        message.as_ptr(),
                    )
                }
            }
            Logger::Fmi3(Some(log), env) => {
                // SAFETY: the importer's logger, called as FMI 3.0 specifies.
                unsafe { log(env, status, category.as_ptr(), message.as_ptr()) }
            }
            Logger::Fmi2(None, _) | Logger::Fmi3(None, _) => {}
        }
    }

    /// Require one of `phases` for the function `what`.
    pub fn expect(&self, what: &str, phases: &[Phase]) -> Result<(), Message> {
        if phases.contains(&self.phase) {
            Ok(())
        } else {
            Err(msg!("{what} is not allowed in phase {:?}", self.phase))
        }
    }

    /// Check that `vr` is a variable of type `kind` (for a get or set of that type).
    pub fn check_kind(vr: u32, kind: Kind) -> Result<(), Message> {
        let var = variables::find(vr)
            .ok_or_else(|| msg!("unknown value reference {vr} (see modelDescription.xml)"))?;
        if var.kind == kind {
            Ok(())
        } else {
            Err(msg!(
                "value reference {vr} ({}) is of type {:?}, not {kind:?}",
                var.name,
                var.kind
            ))
        }
    }

    /// Set every value, in order, on a copy of the model that replaces it only when all were
    /// accepted: a refused value (named in the error) changes nothing.
    pub fn set_all(
        &mut self,
        vrs: &[u32],
        kind: Kind,
        values: impl Iterator<Item = f64>,
    ) -> Result<(), Message> {
        self.expect(
            "setting a variable",
            &[Phase::Instantiated, Phase::Initialization, Phase::Step],
        )?;
        let mut model = self.model;
        for (&vr, value) in vrs.iter().zip(values) {
            Self::check_kind(vr, kind)?;
            if self.phase == Phase::Step
                && variables::find(vr).is_some_and(|v| v.role == Role::Fixed)
            {
                let name = variables::find(vr).map_or("", |v| v.name);
                return Err(msg!(
                    "{name} is fixed: it cannot change after initialization (tried {value})"
                ));
            }
            model.set(vr, value)?;
        }
        self.model = model;
        Ok(())
    }

    /// Every value of `vrs` (of type `kind`) into `out` through `convert`.
    pub fn get_all<T>(
        &self,
        vrs: &[u32],
        kind: Kind,
        out: &mut [T],
        convert: impl Fn(f64) -> T,
    ) -> Result<(), Message> {
        for (&vr, slot) in vrs.iter().zip(out.iter_mut()) {
            Self::check_kind(vr, kind)?;
            *slot = convert(self.model.get(vr)?);
        }
        Ok(())
    }
}

/// Run an exported function's body on the instance behind `ptr`: null is an error, a panic
/// (a bug) is caught and reported as fatal, an error is logged and returned as `ERROR`.
///
/// # Safety
/// `ptr` is null or an instance created by this library's instantiate and not freed.
pub unsafe fn with_instance(
    ptr: *mut c_void,
    body: impl FnOnce(&mut Instance) -> Result<i32, Message>,
) -> i32 {
    if ptr.is_null() {
        return status::ERROR;
    }
    // SAFETY: caller's contract.
    let instance = unsafe { &mut *ptr.cast::<Instance>() };
    match catch_unwind(AssertUnwindSafe(|| body(instance))) {
        Ok(Ok(s)) => s,
        Ok(Err(m)) => {
            instance.log(status::ERROR, &m);
            status::ERROR
        }
        Err(_) => {
            instance.log(
                status::FATAL,
                &msg!("internal error (a bug): caught at the FMI boundary"),
            );
            status::FATAL
        }
    }
}

/// A slice from an FMI array argument (`n` = 0 allows null).
///
/// # Safety
/// `p` is null with `n` = 0, or valid for `n` reads.
pub unsafe fn slice<'a, T>(p: *const T, n: usize) -> Result<&'a [T], Message> {
    if n == 0 {
        return Ok(&[]);
    }
    if p.is_null() {
        return Err(msg!("a null array was passed with {n} elements"));
    }
    // SAFETY: caller's contract.
    Ok(unsafe { core::slice::from_raw_parts(p, n) })
}

/// A mutable slice from an FMI array argument.
///
/// # Safety
/// As [`slice`](fn@slice), for writes.
pub unsafe fn slice_mut<'a, T>(p: *mut T, n: usize) -> Result<&'a mut [T], Message> {
    if n == 0 {
        return Ok(&mut []);
    }
    if p.is_null() {
        return Err(msg!("a null array was passed with {n} elements"));
    }
    // SAFETY: caller's contract.
    Ok(unsafe { core::slice::from_raw_parts_mut(p, n) })
}
