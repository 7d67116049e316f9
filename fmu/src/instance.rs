//! One FMU instance, shared by the FMI 2.0 and 3.0 layers: the model, the FMI state machine's
//! phase, the importer's logger with its log categories, and the checked, panic-free plumbing
//! every exported function goes through (null pointers, array counts, value references of the
//! wrong type, phases, caught panics).

use core::ffi::{CStr, c_char, c_void};
use std::panic::{AssertUnwindSafe, catch_unwind};

use rotor_rub::Event;

use crate::message::Message;
use crate::model::Model;
use crate::msg;
use crate::units::{Dimension, Units};
use crate::variables::Kind;

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

/// The log categories (`<LogCategories>`): name, bit, description.
pub const CATEGORIES: [(&str, u8, &str); 4] = [
    (
        "logEvents",
        1,
        "each contact switch inside a communication step (kind, time, position) and each early return",
    ),
    (
        "logStatusDiscard",
        2,
        "a communication step ended by the work cap (max_internal_steps) and returned Discard",
    ),
    (
        "logStatusError",
        4,
        "every refused call: the value, its valid range and what to do (on from instantiation, as are Discard and Fatal)",
    ),
    (
        "logStatusFatal",
        8,
        "an internal error caught at the FMI boundary (a bug)",
    ),
];
const EVENTS: u8 = 1;
const DISCARD: u8 = 2;
const ERRORS: u8 = 4;
const FATAL: u8 = 8;
const ALL: u8 = EVENTS | DISCARD | ERRORS | FATAL;

/// The importer's logger, the instance name and the categories turned on.
#[derive(Clone, Copy)]
pub struct Log {
    logger: Logger,
    name: [u8; 64],
    on: u8,
}

impl Log {
    /// Every category when `logging_on`, else the failure statuses only (Discard, Error,
    /// Fatal: a failure is never silent unless the importer turns its category off with
    /// `SetDebugLogging`).
    pub fn new(name: &[u8], logger: Logger, logging_on: bool) -> Log {
        let mut n = [0u8; 64];
        for (d, s) in n.iter_mut().zip(name.iter().take(63)) {
            *d = *s;
        }
        Log {
            logger,
            name: n,
            on: if logging_on {
                ALL
            } else {
                DISCARD | ERRORS | FATAL
            },
        }
    }

    /// `SetDebugLogging`: turn `categories` on or off (all of them for an empty list); an
    /// unknown name is refused and changes nothing.
    pub fn set(&mut self, on: bool, categories: &[*const c_char]) -> Result<(), Message> {
        let mut bits = if categories.is_empty() { ALL } else { 0 };
        for &c in categories {
            if c.is_null() {
                return Err(msg!("SetDebugLogging: a null category name"));
            }
            // SAFETY: FMI's contract: NUL-terminated category names.
            let name = unsafe { CStr::from_ptr(c) };
            let found = CATEGORIES
                .iter()
                .find(|(n, _, _)| n.as_bytes() == name.to_bytes());
            match found {
                Some((_, bit, _)) => bits |= bit,
                None => {
                    return Err(msg!(
                        "SetDebugLogging: unknown log category {name:?} (the FMU has logEvents, logStatusDiscard, logStatusError, logStatusFatal)"
                    ));
                }
            }
        }
        self.on = if on { self.on | bits } else { self.on & !bits };
        Ok(())
    }

    /// Log `message` with `status` under the category of `status` (OK: logEvents), if on.
    pub fn log(&self, status: i32, message: &Message) {
        let (bit, category) = match status {
            status::OK | status::WARNING => (EVENTS, c"logEvents"),
            status::DISCARD => (DISCARD, c"logStatusDiscard"),
            status::ERROR => (ERRORS, c"logStatusError"),
            _ => (FATAL, c"logStatusFatal"),
        };
        if self.on & bit == 0 {
            return;
        }
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

    /// Whether logEvents is on.
    pub fn events_on(&self) -> bool {
        self.on & EVENTS != 0
    }

    /// Log a switch under logEvents, in the importer's units.
    pub fn event(&self, model_units: (Units, crate::units::Scales), e: &Event) {
        if !self.events_on() {
            return;
        }
        let (units, scales) = model_units;
        let time = scales.to_importer(Dimension::Time, e.time);
        let (x, y) = (
            scales.to_importer(Dimension::Length, e.state.x),
            scales.to_importer(Dimension::Length, e.state.y),
        );
        let unit = Dimension::Length.unit(units);
        self.log(
            status::OK,
            &msg!(
                "{} at t = {time} (x = {x}, y = {y}{})",
                e.kind.name(),
                if unit == "1" { "" } else { " m" }
            ),
        );
    }
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
    /// The logger and its categories.
    pub log: Log,
    /// FMI 3.0: fmi3DoStep may return early (at a switch, or at the work cap).
    pub early_return: bool,
    /// The end of the last completed (or early-returned) step, in the importer's units.
    pub last_time: f64,
}

impl Instance {
    /// A new instance of `units` logging to `log`.
    pub fn new(log: Log, units: Units) -> Instance {
        Instance {
            model: Model::new(units),
            phase: Phase::Instantiated,
            log,
            early_return: false,
            last_time: 0.0,
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
    pub fn check_kind(&self, vr: u32, kind: Kind) -> Result<(), Message> {
        let var = self.model.variable(vr)?;
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
        kinds: &[Kind],
        values: impl Iterator<Item = f64>,
    ) -> Result<(), Message> {
        self.expect(
            "setting a variable",
            &[Phase::Instantiated, Phase::Initialization, Phase::Step],
        )?;
        let mut model = self.model;
        for (&vr, value) in vrs.iter().zip(values) {
            let var = model.variable(vr)?;
            if !kinds.contains(&var.kind) {
                self.check_kind(vr, kinds.first().copied().unwrap_or(Kind::Float))?;
            }
            model.set(vr, value)?;
        }
        self.model = model;
        Ok(())
    }

    /// Every value of `vrs` (of one of `kinds`) into `out` through `convert`.
    pub fn get_all<T>(
        &self,
        vrs: &[u32],
        kinds: &[Kind],
        out: &mut [T],
        convert: impl Fn(f64) -> T,
    ) -> Result<(), Message> {
        for (&vr, slot) in vrs.iter().zip(out.iter_mut()) {
            let var = self.model.variable(vr)?;
            if !kinds.contains(&var.kind) {
                self.check_kind(vr, kinds.first().copied().unwrap_or(Kind::Float))?;
            }
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
            instance.log.log(status::ERROR, &m);
            status::ERROR
        }
        Err(_) => {
            instance.log.log(
                status::FATAL,
                &msg!("internal error (a bug): caught at the FMI boundary"),
            );
            status::FATAL
        }
    }
}

/// Check that an array of `n` elements of `T` at `p` can exist: at most `isize::MAX` bytes,
/// not wrapping around the address space. A count beyond that is a bad argument, refused
/// before any memory is touched (forming the slice would be undefined behaviour).
fn check_count<T>(p: *const T, n: usize) -> Result<(), Message> {
    let bytes = n.checked_mul(size_of::<T>().max(1));
    let fits =
        bytes.is_some_and(|b| b <= isize::MAX as usize && (p as usize).checked_add(b).is_some());
    if fits {
        Ok(())
    } else {
        Err(msg!(
            "an array of {n} elements of {} bytes cannot exist in memory: the count is wrong",
            size_of::<T>()
        ))
    }
}

/// A slice from an FMI array argument (`n` = 0 allows null), its count checked first.
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
    check_count(p, n)?;
    // SAFETY: caller's contract; the count fits the address space (checked).
    Ok(unsafe { core::slice::from_raw_parts(p, n) })
}

/// A mutable slice from an FMI array argument, its count checked first.
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
    check_count(p, n)?;
    // SAFETY: caller's contract; the count fits the address space (checked).
    Ok(unsafe { core::slice::from_raw_parts_mut(p, n) })
}
