//! Logging to the importer: its FMI 2.0 or 3.0 callback, the instance name, and the log
//! categories (`<LogCategories>`) the importer turned on with `SetDebugLogging`. Messages are
//! formatted into fixed buffers (`message.rs`): logging never allocates.

use core::ffi::{CStr, c_char, c_void};

use rotor_rub::Event;

use crate::instance::status;
use crate::message::Message;
use crate::msg;
use crate::units::{Dimension, Scales, Units};

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
    pub fn event(&self, model_units: (Units, Scales), e: &Event) {
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
