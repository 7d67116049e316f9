//! An importer's calls to the exported FMI 3.0 functions, shared by the Rust tests.
#![allow(dead_code)]

use std::cell::{Cell, RefCell};
use std::ffi::{CStr, CString, c_char, c_void};

use rotor_rub_fmu::description::guid;
use rotor_rub_fmu::fmi3::*;
use rotor_rub_fmu::instance::status;
use rotor_rub_fmu::saved::*;
use rotor_rub_fmu::units::Units;

thread_local! {
    /// Every message logged on this thread: (status, category, text).
    pub static MESSAGES: RefCell<Vec<(i32, String, String)>> = const { RefCell::new(Vec::new()) };
    /// How many messages were logged on this thread.
    pub static COUNT: Cell<usize> = const { Cell::new(0) };
    /// Whether the logger keeps the messages' text (off: it allocates nothing).
    pub static RECORD: Cell<bool> = const { Cell::new(true) };
}

/// The last message logged on this thread.
pub fn last_message() -> String {
    MESSAGES.with(|m| {
        m.borrow()
            .last()
            .map(|(_, _, t)| t.clone())
            .unwrap_or_default()
    })
}

pub unsafe extern "C" fn logger(
    _: *mut c_void,
    status: i32,
    category: *const c_char,
    message: *const c_char,
) {
    // SAFETY: the FMU passes NUL-terminated strings.
    let (category, text) = unsafe { (CStr::from_ptr(category), CStr::from_ptr(message)) };
    assert!(!text.to_bytes().is_empty());
    COUNT.with(|n| n.set(n.get() + 1));
    if !RECORD.with(Cell::get) {
        return;
    }
    let entry = (
        status,
        category.to_string_lossy().into_owned(),
        text.to_string_lossy().into_owned(),
    );
    MESSAGES.with(|m| m.borrow_mut().push(entry));
}

/// An instance of `units`, not yet initialized.
pub fn instantiate_only(units: Units, early_return: bool) -> *mut c_void {
    let token = CString::new(guid(units)).unwrap();
    // SAFETY: valid strings and callbacks.
    let i = unsafe {
        fmi3InstantiateCoSimulation(
            c"test".as_ptr(),
            token.as_ptr(),
            std::ptr::null(),
            false,
            false,
            false,
            early_return,
            std::ptr::null(),
            0,
            std::ptr::null_mut(),
            Some(logger),
            std::ptr::null(),
        )
    };
    assert!(!i.is_null());
    i
}

/// End initialization at start time 0.
pub fn initialize(i: *mut c_void) {
    // SAFETY: a live instance.
    unsafe {
        assert_eq!(
            fmi3EnterInitializationMode(i, false, 0.0, 0.0, false, 0.0),
            status::OK,
            "{}",
            last_message()
        );
        assert_eq!(
            fmi3ExitInitializationMode(i),
            status::OK,
            "{}",
            last_message()
        );
    }
}

/// A dimensionless instance, initialized at time 0.
pub fn instantiate(early_return: bool) -> *mut c_void {
    let i = instantiate_only(Units::Dimensionless, early_return);
    initialize(i);
    i
}

/// One fmi3DoStep: (status, earlyReturn, lastSuccessfulTime).
pub fn step(i: *mut c_void, t: f64, h: f64) -> (i32, bool, f64) {
    let (mut event, mut terminate, mut early, mut last) = (false, false, false, f64::NAN);
    // SAFETY: a live instance, valid outputs.
    let s = unsafe {
        fmi3DoStep(
            i,
            t,
            h,
            false,
            &mut event,
            &mut terminate,
            &mut early,
            &mut last,
        )
    };
    (s, early, last)
}

/// Set Float64 values.
pub fn set(i: *mut c_void, vr: &[u32], values: &[f64]) -> i32 {
    // SAFETY: a live instance, arrays of the given lengths.
    unsafe { fmi3SetFloat64(i, vr.as_ptr(), vr.len(), values.as_ptr(), values.len()) }
}

/// Get Float64 values.
pub fn get(i: *mut c_void, vr: &[u32]) -> Vec<f64> {
    let mut out = vec![0.0; vr.len()];
    // SAFETY: a live instance, arrays of the given lengths.
    let s = unsafe { fmi3GetFloat64(i, vr.as_ptr(), vr.len(), out.as_mut_ptr(), out.len()) };
    assert_eq!(s, status::OK, "{}", last_message());
    out
}

/// The serialized state of the instance.
pub fn serialized(i: *mut c_void) -> Vec<u8> {
    // SAFETY: a live instance, valid pointers.
    unsafe {
        let mut saved: *mut c_void = std::ptr::null_mut();
        assert_eq!(fmi3GetFMUState(i, &mut saved), status::OK);
        let mut size = 0;
        assert_eq!(fmi3SerializedFMUStateSize(i, saved, &mut size), status::OK);
        let mut bytes = vec![0u8; size];
        assert_eq!(
            fmi3SerializeFMUState(i, saved, bytes.as_mut_ptr(), size),
            status::OK
        );
        assert_eq!(fmi3FreeFMUState(i, &mut saved), status::OK);
        bytes
    }
}

/// Value references of the dimensionless FMU.
pub mod vr {
    pub const X: u32 = 1;
    pub const Y: u32 = 2;
    pub const VX: u32 = 3;
    pub const VY: u32 = 4;
    pub const NORMAL_FORCE: u32 = 6;
    pub const FX: u32 = 10;
    pub const FY: u32 = 11;
    pub const SPEED: u32 = 12;
    pub const K_XY: u32 = 106;
    pub const K_YX: u32 = 107;
    pub const FRICTION: u32 = 111;
    pub const MAX_INTERNAL_STEPS: u32 = 202;
}
