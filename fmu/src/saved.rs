//! FMU state get/set/free and serialization, the same six functions for FMI 2.0
//! (`fmi2GetFMUstate`, …) and FMI 3.0 (`fmi3GetFMUState`, …): a saved state is a boxed copy of
//! the [`Model`] (allocated by get, as both standards have it, never by `DoStep`); its bytes are
//! [`crate::state`]'s checked fixed-size form (format version and CRC-32 checksum: a corrupted
//! state is refused). A size argument other than the state's is refused before any byte is read.

use core::ffi::c_void;

use crate::instance::{Phase, slice, slice_mut, status, with_instance};
use crate::model::Model;
use crate::{msg, state};

/// The model-file FMU saves and restores its state in memory only (canSerializeFMUstate =
/// false in its model description): its bytes would be its whole stepper, not the planar
/// FMU's fixed-size form.
fn no_file_serialization(model: &Model) -> Result<(), crate::message::Message> {
    if model.file.is_some() {
        Err(msg!(
            "the FMU built for a model file does not serialize its state (canSerializeFMUstate = false): use get/set FMU state"
        ))
    } else {
        Ok(())
    }
}

macro_rules! saved_state {
    ($get:ident, $set:ident, $free:ident, $size:ident, $serialize:ident, $deserialize:ident) => {
        /// Save the model's state: a new state object, or the given one overwritten.
        ///
        /// # Safety
        /// `i` is null or an instance of this FMU; `saved` valid for a read and a write.
        #[unsafe(no_mangle)]
        pub unsafe extern "C" fn $get(i: *mut c_void, saved: *mut *mut c_void) -> i32 {
            // SAFETY: caller's contract.
            unsafe {
                with_instance(i, |i| {
                    let slot = saved.as_mut().ok_or_else(|| msg!("null state pointer"))?;
                    match (*slot).cast::<Model>().as_mut() {
                        Some(model) => model.clone_from(&i.model),
                        None => *slot = Box::into_raw(Box::new(i.model.clone())).cast(),
                    }
                    Ok(status::OK)
                })
            }
        }

        /// Restore a saved state (the time becomes the saved time).
        ///
        /// # Safety
        /// `i` is null or an instance of this FMU; `saved` null or a state of this FMU.
        #[unsafe(no_mangle)]
        pub unsafe extern "C" fn $set(i: *mut c_void, saved: *mut c_void) -> i32 {
            // SAFETY: caller's contract.
            unsafe {
                with_instance(i, |i| {
                    let model = saved
                        .cast::<Model>()
                        .as_ref()
                        .ok_or_else(|| msg!("null state"))?;
                    if model.units != i.model.units
                        || model.file.as_ref().map(|f| &f.file)
                            != i.model.file.as_ref().map(|f| &f.file)
                    {
                        return Err(msg!(
                            "a state of the {:?} FMU cannot be set on the {:?} one",
                            model.units,
                            i.model.units
                        ));
                    }
                    i.model.clone_from(model);
                    if i.model.stepper.is_some() {
                        i.last_time = i.model.time();
                        i.phase = Phase::Step;
                    }
                    Ok(status::OK)
                })
            }
        }

        /// Free a saved state and null the pointer.
        ///
        /// # Safety
        /// `i` is null or an instance of this FMU; `saved` valid for a read and a write.
        #[unsafe(no_mangle)]
        pub unsafe extern "C" fn $free(i: *mut c_void, saved: *mut *mut c_void) -> i32 {
            // SAFETY: caller's contract.
            unsafe {
                with_instance(i, |_| {
                    if let Some(slot) = saved.as_mut()
                        && !slot.is_null()
                    {
                        drop(Box::from_raw((*slot).cast::<Model>()));
                        *slot = core::ptr::null_mut();
                    }
                    Ok(status::OK)
                })
            }
        }

        /// The serialized size, [`state::BYTES`].
        ///
        /// # Safety
        /// `i` is null or an instance of this FMU; `size` valid for a write.
        #[unsafe(no_mangle)]
        pub unsafe extern "C" fn $size(
            i: *mut c_void,
            _saved: *mut c_void,
            size: *mut usize,
        ) -> i32 {
            // SAFETY: caller's contract.
            unsafe {
                with_instance(i, |i| {
                    no_file_serialization(&i.model)?;
                    *size.as_mut().ok_or_else(|| msg!("null size pointer"))? = state::BYTES;
                    Ok(status::OK)
                })
            }
        }

        /// Write a saved state's bytes.
        ///
        /// # Safety
        /// `i` is null or an instance of this FMU; `saved` a state of it; `bytes` valid for
        /// `size` writes.
        #[unsafe(no_mangle)]
        pub unsafe extern "C" fn $serialize(
            i: *mut c_void,
            saved: *mut c_void,
            bytes: *mut u8,
            size: usize,
        ) -> i32 {
            // SAFETY: caller's contract.
            unsafe {
                with_instance(i, |_| {
                    let model = saved
                        .cast::<Model>()
                        .as_ref()
                        .ok_or_else(|| msg!("null state"))?;
                    no_file_serialization(model)?;
                    if size < state::BYTES {
                        return Err(msg!(
                            "buffer of {size} bytes is too small: {} needed",
                            state::BYTES
                        ));
                    }
                    // Only the state's bytes are touched, whatever `size` says.
                    slice_mut(bytes, state::BYTES)?.copy_from_slice(&state::serialize(model));
                    Ok(status::OK)
                })
            }
        }

        /// A new saved state from bytes, every value checked.
        ///
        /// # Safety
        /// `i` is null or an instance of this FMU; `bytes` valid for `size` reads; `saved` for
        /// a write.
        #[unsafe(no_mangle)]
        pub unsafe extern "C" fn $deserialize(
            i: *mut c_void,
            bytes: *const u8,
            size: usize,
            saved: *mut *mut c_void,
        ) -> i32 {
            // SAFETY: caller's contract.
            unsafe {
                with_instance(i, |i| {
                    no_file_serialization(&i.model)?;
                    if size != state::BYTES {
                        return Err(msg!(
                            "serialized FMU state has {size} bytes, expected {}",
                            state::BYTES
                        ));
                    }
                    let model = state::deserialize(slice(bytes, size)?, i.model.units)?;
                    let slot = saved.as_mut().ok_or_else(|| msg!("null state pointer"))?;
                    *slot = Box::into_raw(Box::new(model)).cast();
                    Ok(status::OK)
                })
            }
        }
    };
}

saved_state!(
    fmi2GetFMUstate,
    fmi2SetFMUstate,
    fmi2FreeFMUstate,
    fmi2SerializedFMUstateSize,
    fmi2SerializeFMUstate,
    fmi2DeSerializeFMUstate
);
saved_state!(
    fmi3GetFMUState,
    fmi3SetFMUState,
    fmi3FreeFMUState,
    fmi3SerializedFMUStateSize,
    fmi3SerializeFMUState,
    fmi3DeserializeFMUState
);
