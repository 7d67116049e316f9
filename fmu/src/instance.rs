//! One FMU instance, shared by the FMI 2.0 and 3.0 layers: the model, the FMI state machine's
//! phase, the importer's logger with its log categories (`log.rs`), and the checked, panic-free plumbing
//! every exported function goes through (null pointers, array counts, value references of the
//! wrong type, phases, caught panics).

use core::ffi::c_void;
use std::panic::{AssertUnwindSafe, catch_unwind};

pub use crate::log::{CATEGORIES, Fmi2Logger, Fmi3Logger, Log, Logger};
use crate::message::Message;
use crate::model::Model;
use crate::msg;
use crate::units::Units;
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
        if let Some(f) = &self.model.file {
            return f.check_kind(vr, &[kind]);
        }
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
        // All or nothing: the sets apply in place, and a refused one puts the model back (a
        // copy of the planar stepper's few words, or of the ring's model; never a heap copy).
        let backup = self.model.clone();
        if let Some(f) = &mut self.model.file {
            for (&vr, value) in vrs.iter().zip(values) {
                if let Err(e) = f
                    .check_kind(vr, kinds)
                    .and_then(|()| f.set(vr, value).map_err(|e| crate::msg!("{e}")))
                {
                    self.model = backup;
                    return Err(e);
                }
            }
            return Ok(());
        }
        for (&vr, value) in vrs.iter().zip(values) {
            let applied = self.model.variable(vr).and_then(|var| {
                if !kinds.contains(&var.kind) {
                    self.check_kind(vr, kinds.first().copied().unwrap_or(Kind::Float))?;
                }
                self.model.set(vr, value)
            });
            if let Err(e) = applied {
                self.model = backup;
                return Err(e);
            }
        }
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
        if let Some(f) = &self.model.file {
            for (&vr, slot) in vrs.iter().zip(out.iter_mut()) {
                f.check_kind(vr, kinds)?;
                *slot = convert(f.get(vr).map_err(|e| crate::msg!("{e}"))?);
            }
            return Ok(());
        }
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
