//! The unsafe plumbing behind the entry points: the stepper slot in caller memory, pointer
//! reads and writes, the panic guard and the error-code mapping.

use core::fmt::Write;
use std::panic::{AssertUnwindSafe, catch_unwind};

use rotor_rub::PropagationError;
use rotor_rub::stepper::{AnyStepper, StepperError};

use crate::types::*;

/// Marks initialised stepper memory ("rotorrub").
pub(crate) const MAGIC: u64 = 0x726f_746f_7272_7562;

/// What lives in a [`RotorRubStepper`].
#[repr(C)]
pub(crate) struct Slot {
    pub(crate) magic: u64,
    /// The planar stepper (m̂ = 0) or the ring's (m̂ > 0): the problem decides.
    pub(crate) stepper: AnyStepper,
}

const _: () = assert!(size_of::<Slot>() <= size_of::<RotorRubStepper>());
const _: () = assert!(align_of::<Slot>() <= align_of::<RotorRubStepper>());

/// Run an entry point's body; a panic (a bug) becomes `ROTOR_RUB_ERR_INTERNAL`.
pub(crate) fn guard(body: impl FnOnce() -> Result<(), i32>) -> i32 {
    match catch_unwind(AssertUnwindSafe(body)) {
        Ok(Ok(())) => ROTOR_RUB_OK,
        Ok(Err(code)) => code,
        Err(_) => ROTOR_RUB_ERR_INTERNAL,
    }
}

pub(crate) fn error_code(e: &StepperError) -> i32 {
    match e {
        StepperError::Propagation(
            PropagationError::InvalidProblem(_) | PropagationError::InvalidModel(_),
        ) => ROTOR_RUB_ERR_INVALID_PARAMS,
        // The ring's stepper: a stretch between switches beyond its integration-step budget.
        StepperError::Propagation(PropagationError::StepSizeUnderflow { .. }) => {
            ROTOR_RUB_ERR_BUDGET_EXCEEDED
        }
        StepperError::InvalidConfig { .. }
        | StepperError::Propagation(PropagationError::InvalidOption { .. }) => {
            ROTOR_RUB_ERR_INVALID_CONFIG
        }
        StepperError::InvalidStep { .. } => ROTOR_RUB_ERR_INVALID_STEP,
        StepperError::BudgetExceeded { .. } => ROTOR_RUB_ERR_BUDGET_EXCEEDED,
        StepperError::Propagation(PropagationError::Diverged { .. }) => ROTOR_RUB_ERR_DIVERGED,
        StepperError::Propagation(PropagationError::SingularContact { .. }) => {
            ROTOR_RUB_ERR_SINGULAR_CONTACT
        }
        // The stepper reports no other propagation error (targets, step control, options).
        StepperError::Propagation(_) => ROTOR_RUB_ERR_INTERNAL,
    }
}

/// Read a required input.
///
/// # Safety
/// `p` is null or valid for reads of a `T` (any alignment).
pub(crate) unsafe fn read<T: Copy>(p: *const T) -> Result<T, i32> {
    if p.is_null() {
        return Err(ROTOR_RUB_ERR_NULL);
    }
    // SAFETY: non-null and, by the caller's contract, valid for reads.
    Ok(unsafe { p.read_unaligned() })
}

/// Write an optional output (null: skipped).
///
/// # Safety
/// `p` is null or valid for writes of a `T` (any alignment).
pub(crate) unsafe fn write<T>(p: *mut T, value: T) {
    if !p.is_null() {
        // SAFETY: non-null and, by the caller's contract, valid for writes.
        unsafe { p.write_unaligned(value) }
    }
}

/// The slot behind a stepper pointer, checked for null, alignment and initialisation.
///
/// # Safety
/// `p` is null or valid for reads of a [`RotorRubStepper`], not written during the call.
pub(crate) unsafe fn slot_ref<'a>(p: *const RotorRubStepper) -> Result<&'a Slot, i32> {
    if p.is_null() {
        return Err(ROTOR_RUB_ERR_NULL);
    }
    if !(p as usize).is_multiple_of(align_of::<Slot>()) {
        return Err(ROTOR_RUB_ERR_MISALIGNED);
    }
    let slot = p.cast::<Slot>();
    // SAFETY: aligned and valid for reads; the magic word is a plain u64.
    let magic = unsafe { (&raw const (*slot).magic).read() };
    if magic != MAGIC {
        return Err(ROTOR_RUB_ERR_NOT_INITIALIZED);
    }
    // SAFETY: the magic word says `rotor_rub_stepper_init` wrote a valid `Slot` here.
    Ok(unsafe { &*slot })
}

/// As [`slot_ref`], for mutation.
///
/// # Safety
/// `p` is null or valid for reads and writes of a [`RotorRubStepper`], not aliased during the
/// call.
pub(crate) unsafe fn slot_mut<'a>(p: *mut RotorRubStepper) -> Result<&'a mut Slot, i32> {
    // SAFETY: caller's contract; the checks are those of `slot_ref`.
    unsafe { slot_ref(p)? };
    // SAFETY: checked above: aligned, initialised, and writable by the caller's contract.
    Ok(unsafe { &mut *p.cast::<Slot>() })
}

/// A `core::fmt::Write` into a caller buffer, truncating, keeping room for the NUL.
pub(crate) struct Buffer<'a> {
    pub(crate) bytes: &'a mut [u8],
    pub(crate) len: usize,
}

impl Write for Buffer<'_> {
    fn write_str(&mut self, s: &str) -> core::fmt::Result {
        let room = self.bytes.len().saturating_sub(1 + self.len);
        let n = s.len().min(room);
        let end = self.len.saturating_add(n);
        if let (Some(dst), Some(src)) = (self.bytes.get_mut(self.len..end), s.as_bytes().get(..n)) {
            dst.copy_from_slice(src);
            self.len = end;
        }
        Ok(())
    }
}

/// Longest text a call writes (messages and names are far shorter).
const TEXT_MAX: usize = 1024;

/// Write `text` NUL-terminated into the caller's buffer of `capacity` bytes at `dst`
/// (truncated to fit; null or 0 skips it). Only the bytes of the text and its NUL are touched.
/// A capacity that no buffer can have (more than `isize::MAX` bytes, or past the end of the
/// address space) is a wrong count: `ROTOR_RUB_ERR_INVALID_ARGUMENT`, nothing written.
///
/// # Safety
/// `dst` is null or valid for writes of `capacity` bytes.
pub(crate) unsafe fn write_text(
    dst: *mut core::ffi::c_char,
    capacity: usize,
    text: core::fmt::Arguments<'_>,
) -> Result<(), i32> {
    if dst.is_null() || capacity == 0 {
        return Ok(());
    }
    if capacity > isize::MAX as usize || (dst as usize).checked_add(capacity).is_none() {
        return Err(ROTOR_RUB_ERR_INVALID_ARGUMENT);
    }
    let mut staged = [0u8; TEXT_MAX];
    let mut buffer = Buffer {
        bytes: &mut staged,
        len: 0,
    };
    let _ = buffer.write_fmt(text);
    let len = buffer.len.min(capacity - 1);
    // SAFETY: the caller's contract: `capacity` > `len` writable bytes at `dst`.
    let out = unsafe { core::slice::from_raw_parts_mut(dst.cast::<u8>(), len + 1) };
    if let (Some((nul, body)), Some(src)) = (out.split_last_mut(), staged.get(..len)) {
        body.copy_from_slice(src);
        *nul = 0;
    }
    Ok(())
}
