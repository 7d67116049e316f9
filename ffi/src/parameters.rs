//! Parameter access by table index (`rotor_rub::Parameter`): count, look-up by name, range and
//! default, get and set on the caller's structs. The header's `ROTOR_RUB_PARAMETER_*` index
//! constants are generated from the same table (`tests/header.rs`).

use core::ffi::{CStr, c_char};

use rotor_rub::{Parameter, Problem};

use crate::raw::{guard, read, write, write_text};
use crate::types::*;

/// Number of table entries: model parameters, initial state and start time.
pub const ROTOR_RUB_PARAMETER_COUNT: usize = 27;
const _: () = assert!(ROTOR_RUB_PARAMETER_COUNT == Parameter::COUNT);

fn parameter(index: i32) -> Result<Parameter, i32> {
    usize::try_from(index)
        .ok()
        .and_then(|i| Parameter::ALL.get(i).copied())
        .ok_or(ROTOR_RUB_ERR_INVALID_ARGUMENT)
}

/// The table index of the parameter named `name` (e.g. "speed_ratio"), written to `index`.
///
/// Returns `ROTOR_RUB_OK`; `ROTOR_RUB_ERR_NULL` if `name` or `index` is null;
/// `ROTOR_RUB_ERR_INVALID_ARGUMENT` if no parameter has that name.
///
/// # Safety
/// `name` is null or a NUL-terminated string; `index` is null or valid for writes.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rotor_rub_parameter_index(name: *const c_char, index: *mut i32) -> i32 {
    guard(|| {
        if name.is_null() || index.is_null() {
            return Err(ROTOR_RUB_ERR_NULL);
        }
        // SAFETY: non-null and NUL-terminated by the caller's contract.
        let name = unsafe { CStr::from_ptr(name) };
        let found = name
            .to_str()
            .ok()
            .and_then(Parameter::from_name)
            .ok_or(ROTOR_RUB_ERR_INVALID_ARGUMENT)?;
        let found = i32::try_from(found as usize).map_err(|_| ROTOR_RUB_ERR_INTERNAL)?;
        // SAFETY: caller's contract.
        unsafe { write(index, found) };
        Ok(())
    })
}

/// What the table says about parameter `index`: its name (NUL-terminated, truncated to
/// `capacity` bytes), default and valid range `[min, max]` (`min_open` 1 when `min` itself is
/// excluded). Every output is optional (null skips it).
///
/// Returns `ROTOR_RUB_OK`; `ROTOR_RUB_ERR_INVALID_ARGUMENT` if `index` is not in
/// `[0, ROTOR_RUB_PARAMETER_COUNT)` or `capacity` is larger than any buffer can be (nothing is
/// written then).
///
/// # Safety
/// `name` is null or valid for writes of `capacity` bytes; the other outputs null or valid for
/// writes.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rotor_rub_parameter_info(
    index: i32,
    name: *mut c_char,
    capacity: usize,
    default_value: *mut f64,
    min: *mut f64,
    max: *mut f64,
    min_open: *mut i32,
) -> i32 {
    guard(|| {
        let info = parameter(index)?.info();
        // SAFETY: caller's contract: `capacity` writable bytes at `name` (or null).
        unsafe { write_text(name, capacity, format_args!("{}", info.name))? };
        // SAFETY: caller's contract.
        unsafe {
            write(default_value, info.default);
            write(min, info.range.min);
            write(max, info.range.max);
            write(min_open, i32::from(info.range.min_open));
        }
        Ok(())
    })
}

/// Read the structs the parameter lives in (defaults where a pointer is null).
///
/// # Safety
/// Each pointer is null or valid for reads.
unsafe fn problem_of(
    params: *const RotorRubParams,
    initial: *const RotorRubState,
    start_time: *const f64,
) -> Problem {
    let mut problem = Problem::DEFAULT;
    // SAFETY: caller's contract; null pointers are skipped.
    unsafe {
        if let Ok(p) = read(params) {
            problem.params = p.into();
        }
        if let Ok(s) = read(initial) {
            problem.initial = s.into();
        }
        if let Ok(t) = read(start_time) {
            problem.start_time = t;
        }
    }
    problem
}

/// Whether the struct holding parameter `p` was given.
fn holder_given(
    p: Parameter,
    params: *const RotorRubParams,
    initial: *const RotorRubState,
    start_time: *const f64,
) -> Result<(), i32> {
    let given = if p.is_model() {
        !params.is_null()
    } else if p == Parameter::StartTime {
        !start_time.is_null()
    } else {
        !initial.is_null()
    };
    if given {
        Ok(())
    } else {
        Err(ROTOR_RUB_ERR_NULL)
    }
}

/// Set parameter `index` to `value` in whichever of `params`, `initial` (x0, y0, vx0, vy0) or
/// `start_time` holds it; the other pointers may be null. The value is checked against the
/// parameter's range first (cross-parameter rules are checked by `rotor_rub_problem_validate`
/// and `rotor_rub_stepper_init`); on error nothing is written.
///
/// Returns `ROTOR_RUB_OK`; `ROTOR_RUB_ERR_INVALID_ARGUMENT` for an unknown `index`;
/// `ROTOR_RUB_ERR_NULL` if the struct holding the parameter is null;
/// `ROTOR_RUB_ERR_INVALID_PARAMS` if `value` is not finite or outside the parameter's range.
///
/// # Safety
/// Each pointer is null or valid for reads and writes of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rotor_rub_parameter_set(
    params: *mut RotorRubParams,
    initial: *mut RotorRubState,
    start_time: *mut f64,
    index: i32,
    value: f64,
) -> i32 {
    guard(|| {
        let p = parameter(index)?;
        holder_given(p, params, initial, start_time)?;
        p.check(value).map_err(|_| ROTOR_RUB_ERR_INVALID_PARAMS)?;
        // SAFETY: caller's contract.
        let mut problem = unsafe { problem_of(params, initial, start_time) };
        p.set(&mut problem, value);
        // SAFETY: caller's contract; only the holder of `p` is written.
        unsafe {
            if p.is_model() {
                write(params, problem.params.into());
            } else if p == Parameter::StartTime {
                write(start_time, problem.start_time);
            } else {
                write(initial, problem.initial.into());
            }
        }
        Ok(())
    })
}

/// Read parameter `index` from whichever of `params`, `initial` or `start_time` holds it (the
/// other pointers may be null) into `value`.
///
/// Returns `ROTOR_RUB_OK`; `ROTOR_RUB_ERR_INVALID_ARGUMENT` for an unknown `index`;
/// `ROTOR_RUB_ERR_NULL` if `value` or the struct holding the parameter is null.
///
/// # Safety
/// Each input pointer is null or valid for reads; `value` is null or valid for writes.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rotor_rub_parameter_get(
    params: *const RotorRubParams,
    initial: *const RotorRubState,
    start_time: *const f64,
    index: i32,
    value: *mut f64,
) -> i32 {
    guard(|| {
        let p = parameter(index)?;
        holder_given(p, params, initial, start_time)?;
        if value.is_null() {
            return Err(ROTOR_RUB_ERR_NULL);
        }
        // SAFETY: caller's contract.
        let problem = unsafe { problem_of(params, initial, start_time) };
        // SAFETY: caller's contract.
        unsafe { write(value, p.get(&problem)) };
        Ok(())
    })
}
