//! The FMU's reliability classes (issue 32, items 5, 9 and 11), through the exported functions
//! as an importer calls them: the work per `doStep` is capped (the issue's 1e5-time-unit step),
//! every single-byte corruption of a serialized state is refused, a tunable parameter set takes
//! effect as a whole whatever the order of its sets, and every array count is checked before
//! memory is touched.

mod common;

use std::ffi::{CString, c_char, c_void};

use common::{
    get, initialize, instantiate, instantiate_only, last_message, serialized, set, step, vr,
};
use rotor_rub_fmu::description::guid;
use rotor_rub_fmu::fmi2::*;
use rotor_rub_fmu::fmi2_stubs::fmi2GetRealStatus;
use rotor_rub_fmu::fmi3::*;
use rotor_rub_fmu::instance::status;
use rotor_rub_fmu::saved::*;
use rotor_rub_fmu::state;
use rotor_rub_fmu::units::Units;

const STATE: [u32; 5] = [vr::X, vr::Y, vr::VX, vr::VY, vr::NORMAL_FORCE];

fn set_cap(i: *mut c_void, cap: i32) {
    let v = [cap];
    // SAFETY: a live instance, one value.
    let s = unsafe { fmi3SetInt32(i, &vr::MAX_INTERNAL_STEPS, 1, v.as_ptr(), 1) };
    assert_eq!(s, status::OK, "{}", last_message());
}

#[test]
fn the_issues_1e5_time_unit_step_is_cut_by_the_work_cap() {
    // Without early return (FMI 3.0): Discard, the FMU left at the step's start.
    let i = instantiate(false);
    let before = get(i, &STATE);
    let (s, early, last) = step(i, 0.0, 1e5);
    assert_eq!((s, early, last), (status::DISCARD, false, 0.0));
    assert!(
        last_message().contains("max_internal_steps"),
        "{}",
        last_message()
    );
    assert_eq!(get(i, &STATE), before, "a discarded step changed the state");
    // The run goes on as if the discarded step had never been asked for, bit for bit.
    let untouched = instantiate(false);
    let (mut t, mut u) = (0.0, 0.0);
    for _ in 0..3000 {
        let (s, _, last) = step(i, t, 1e-3);
        assert_eq!(s, status::OK, "usable after the Discard");
        t = last;
        u = step(untouched, u, 1e-3).2;
    }
    assert_eq!(get(i, &STATE), get(untouched, &STATE));

    // With early return: the step ends early where the cap stopped it, and goes on from there.
    let i = instantiate(true);
    set_cap(i, 100);
    let (s, early, last) = step(i, 0.0, 1e5);
    assert_eq!((s, early), (status::OK, true));
    assert!(
        (last - 0.1).abs() < 1e-12,
        "100 internal steps of 1e-3 end at 0.1, not {last}"
    );
    let (s, _, next) = step(i, last, 1e5);
    assert_eq!(s, status::OK);
    assert!(next > last);
    // SAFETY: live instances, freed once.
    unsafe { fmi3FreeInstance(i) };
}

#[test]
fn fmi2_reports_the_capped_step_as_discard_with_the_time_reached() {
    let token = CString::new(guid(Units::Dimensionless)).unwrap();
    // SAFETY: valid strings; null callbacks are accepted (no logger).
    unsafe {
        let c = fmi2Instantiate(
            c"fmi2".as_ptr(),
            1,
            token.as_ptr(),
            std::ptr::null(),
            std::ptr::null(),
            0,
            0,
        );
        assert!(!c.is_null());
        let cap = [1000];
        assert_eq!(
            fmi2SetInteger(c, &vr::MAX_INTERNAL_STEPS, 1, cap.as_ptr()),
            status::OK
        );
        assert_eq!(fmi2SetupExperiment(c, 0, 0.0, 0.0, 0, 0.0), status::OK);
        assert_eq!(fmi2EnterInitializationMode(c), status::OK);
        assert_eq!(fmi2ExitInitializationMode(c), status::OK);
        assert_eq!(fmi2DoStep(c, 0.0, 1e5, 1), status::DISCARD);
        let mut reached = f64::NAN;
        assert_eq!(fmi2GetRealStatus(c, 2, &mut reached), status::OK);
        assert!(reached > 0.0 && reached <= 1.0 + 1e-9, "{reached}");
        assert_eq!(
            fmi2DoStep(c, reached, 1e-3, 1),
            status::OK,
            "steps on from the time reached"
        );
        fmi2FreeInstance(c);
    }
}

#[test]
fn every_single_byte_corruption_of_a_saved_state_is_refused() {
    let i = instantiate(false);
    let mut t = 0.0;
    for _ in 0..3000 {
        t = step(i, t, 1e-3).2;
    }
    let bytes = serialized(i);
    assert_eq!(bytes.len(), state::BYTES);
    common::RECORD.with(|r| r.set(false));
    let mut accepted = Vec::new();
    let mut corrupt = bytes.clone();
    for k in 0..bytes.len() {
        for flip in 1..=255u8 {
            corrupt[k] = bytes[k] ^ flip;
            let mut restored: *mut c_void = std::ptr::null_mut();
            // SAFETY: a live instance, a buffer of the state's size.
            let s = unsafe {
                fmi3DeserializeFMUState(i, corrupt.as_ptr(), corrupt.len(), &mut restored)
            };
            if s != status::ERROR || !restored.is_null() {
                accepted.push((k, flip));
            }
        }
        corrupt[k] = bytes[k];
    }
    common::RECORD.with(|r| r.set(true));
    assert!(
        accepted.is_empty(),
        "{} of {} single-byte corruptions accepted, e.g. {:?}",
        accepted.len(),
        bytes.len() * 255,
        &accepted[..accepted.len().min(5)]
    );
    // The real state itself is accepted, and an older format is named as such.
    let mut restored: *mut c_void = std::ptr::null_mut();
    // SAFETY: as above.
    unsafe {
        assert_eq!(
            fmi3DeserializeFMUState(i, bytes.as_ptr(), bytes.len(), &mut restored),
            status::OK
        );
        assert_eq!(fmi3FreeFMUState(i, &mut restored), status::OK);
        let mut old = bytes.clone();
        old[0] = 1;
        assert_eq!(
            fmi3DeserializeFMUState(i, old.as_ptr(), old.len(), &mut restored),
            status::ERROR
        );
        assert!(
            last_message().contains("format version 1"),
            "{}",
            last_message()
        );
        fmi3FreeInstance(i);
    }
}

/// Run 3000 steps of 1e-3 after setting `sets` one call at a time right after initialization;
/// the statuses of the sets and of the first step, and the end state.
fn run_after_sets(sets: &[(u32, f64)]) -> (Vec<i32>, Vec<f64>) {
    let i = instantiate(false);
    let mut statuses: Vec<i32> = sets.iter().map(|&(r, v)| set(i, &[r], &[v])).collect();
    let mut t = 0.0;
    for k in 0..3000 {
        let (s, _, last) = step(i, t, 1e-3);
        if k == 0 {
            statuses.push(s);
        }
        assert_eq!(s, status::OK, "{}", last_message());
        t = last;
    }
    let out = get(i, &STATE);
    // SAFETY: a live instance, freed once.
    unsafe { fmi3FreeInstance(i) };
    (statuses, out)
}

#[test]
fn a_tunable_parameter_set_takes_effect_as_a_whole_whatever_the_order() {
    // The issue's sequence on the paper preset: μ on, then k_xy = 50 (alone, with k_yx = 20, it
    // breaks the friction rule), then k_yx = −50 (together they hold). Every order gives the
    // same run; before, k_xy = 50 was refused and k_yx = −50 kept: a mixed set.
    let forward = run_after_sets(&[(vr::FRICTION, 0.2), (vr::K_XY, 50.0), (vr::K_YX, -50.0)]);
    let backward = run_after_sets(&[(vr::K_YX, -50.0), (vr::K_XY, 50.0), (vr::FRICTION, 0.2)]);
    let middle = run_after_sets(&[(vr::K_XY, 50.0), (vr::FRICTION, 0.2), (vr::K_YX, -50.0)]);
    assert_eq!(forward.0, vec![status::OK; 4]);
    assert_eq!(forward, backward);
    assert_eq!(forward, middle);

    // A set that does not hold together is refused at the step, in any order, and changes
    // nothing: fixing it and stepping on gives the run that never had it.
    let i = instantiate(false);
    assert_eq!(set(i, &[vr::FRICTION], &[0.2]), status::OK);
    assert_eq!(set(i, &[vr::K_XY], &[50.0]), status::OK);
    let before = get(i, &STATE);
    assert_eq!(step(i, 0.0, 1e-3).0, status::ERROR);
    let message = last_message();
    assert!(
        message.contains("friction_coefficient = 0.2") && message.contains("k_xy = 50"),
        "{message}"
    );
    assert_eq!(get(i, &STATE), before);
    assert_eq!(
        get(i, &[106]),
        vec![50.0],
        "the refused value stays set, to be fixed"
    );
    assert_eq!(set(i, &[vr::K_XY], &[20.0]), status::OK);
    let mut t = 0.0;
    for _ in 0..3000 {
        let (s, _, last) = step(i, t, 1e-3);
        assert_eq!(s, status::OK);
        t = last;
    }
    let fixed = get(i, &STATE);
    let friction_only = run_after_sets(&[(vr::FRICTION, 0.2)]);
    assert_eq!(fixed, friction_only.1);
    // SAFETY: a live instance, freed once.
    unsafe { fmi3FreeInstance(i) };
}

#[test]
fn counts_beyond_memory_are_refused_before_memory_is_touched() {
    let i = instantiate(false);
    let huge = usize::MAX / 2;
    let vrs = [vr::X];
    let mut out = [0.0f64; 1];
    let mut ints = [0i32; 1];
    let names: [*const c_char; 1] = [c"logEvents".as_ptr()];
    // SAFETY: a live instance; the arrays hold one element, the counts lie (as a buggy
    // importer's would): the FMU must refuse them without reading past the first element.
    unsafe {
        assert_eq!(
            fmi3GetFloat64(i, vrs.as_ptr(), huge, out.as_mut_ptr(), huge),
            status::ERROR
        );
        assert!(
            last_message().contains("cannot exist in memory"),
            "{}",
            last_message()
        );
        assert_eq!(
            fmi3SetFloat64(i, vrs.as_ptr(), huge, out.as_ptr(), huge),
            status::ERROR
        );
        assert_eq!(
            fmi3GetInt32(i, vrs.as_ptr(), huge, ints.as_mut_ptr(), huge),
            status::ERROR
        );
        assert_eq!(
            fmi3SetDebugLogging(i, true, huge, names.as_ptr()),
            status::ERROR
        );
        let bytes = serialized(i);
        let mut restored: *mut c_void = std::ptr::null_mut();
        assert_eq!(
            fmi3DeserializeFMUState(i, bytes.as_ptr(), usize::MAX, &mut restored),
            status::ERROR
        );
        assert!(restored.is_null());
        // A buffer said to be larger than memory: only the state's bytes are written.
        let mut saved: *mut c_void = std::ptr::null_mut();
        assert_eq!(fmi3GetFMUState(i, &mut saved), status::OK);
        let mut buffer = vec![0xa5u8; state::BYTES + 16];
        assert_eq!(
            fmi3SerializeFMUState(i, saved, buffer.as_mut_ptr(), usize::MAX),
            status::OK
        );
        assert_eq!(&buffer[..state::BYTES], &bytes[..]);
        assert!(buffer[state::BYTES..].iter().all(|&b| b == 0xa5));
        assert_eq!(fmi3FreeFMUState(i, &mut saved), status::OK);
        // Still usable.
        assert_eq!(step(i, 0.0, 1e-3).0, status::OK);
        fmi3FreeInstance(i);
    }
}

#[test]
fn log_categories_filter_the_messages() {
    let i = instantiate_only(Units::Dimensionless, false);
    let events = [c"logEvents".as_ptr()];
    let unknown = [c"logEverything".as_ptr()];
    // SAFETY: a live instance, arrays of the given lengths.
    unsafe {
        assert_eq!(
            fmi3SetDebugLogging(i, true, 1, unknown.as_ptr()),
            status::ERROR
        );
        assert!(
            last_message().contains("logEverything"),
            "{}",
            last_message()
        );
        assert_eq!(fmi3SetDebugLogging(i, true, 1, events.as_ptr()), status::OK);
    }
    initialize(i);
    let count = || common::MESSAGES.with(|m| m.borrow().len());
    let n = count();
    let mut t = 0.0;
    while count() == n && t < 20.0 {
        t = step(i, t, 1e-3).2;
    }
    let (status_logged, category, text) = common::MESSAGES.with(|m| m.borrow()[n].clone());
    assert_eq!(
        (status_logged, category.as_str()),
        (status::OK, "logEvents")
    );
    assert!(text.starts_with("enter at t = "), "{text}");
    // Errors off: a refused value logs nothing.
    let errors = [c"logStatusError".as_ptr()];
    // SAFETY: as above.
    unsafe {
        assert_eq!(
            fmi3SetDebugLogging(i, false, 1, errors.as_ptr()),
            status::OK
        );
    }
    let n = count();
    assert_eq!(set(i, &[vr::SPEED], &[-1.0]), status::ERROR);
    assert_eq!(count(), n);
    // SAFETY: a live instance, freed once.
    unsafe { fmi3FreeInstance(i) };
}
