//! Every count that sizes memory is checked before memory is touched (issue 32, item 5): a
//! text buffer's `capacity` larger than any buffer can be is refused with
//! `ROTOR_RUB_ERR_INVALID_ARGUMENT`, and a plausible one gets only the text's bytes written.

use std::ffi::{CStr, c_char};

use rotor_rub_ffi::*;

fn paper() -> (RotorRubParams, RotorRubState, f64) {
    let mut params = RotorRubParams::from(rotor_rub::Preset::Paper.problem().params);
    let mut initial = RotorRubState::default();
    let mut t0 = f64::NAN;
    // SAFETY: valid pointers.
    let rc =
        unsafe { rotor_rub_preset(ROTOR_RUB_PRESET_PAPER, &mut params, &mut initial, &mut t0) };
    assert_eq!(rc, ROTOR_RUB_OK);
    (params, initial, t0)
}

#[test]
fn a_capacity_beyond_memory_is_refused_and_nothing_is_written() {
    let (params, initial, t0) = paper();
    for capacity in [usize::MAX, isize::MAX as usize + 1] {
        let mut buffer = [0x5a_u8; 32];
        let out = buffer.as_mut_ptr().cast::<c_char>();
        // SAFETY: valid structs; the buffer holds 32 bytes, the capacity lies (a wrong count).
        let (validate, info) = unsafe {
            (
                rotor_rub_problem_validate(&params, &initial, t0, out, capacity),
                rotor_rub_parameter_info(
                    0,
                    out,
                    capacity,
                    std::ptr::null_mut(),
                    std::ptr::null_mut(),
                    std::ptr::null_mut(),
                    std::ptr::null_mut(),
                ),
            )
        };
        assert_eq!(
            (validate, info),
            (
                ROTOR_RUB_ERR_INVALID_ARGUMENT,
                ROTOR_RUB_ERR_INVALID_ARGUMENT
            )
        );
        assert!(buffer.iter().all(|&b| b == 0x5a), "nothing written");
    }
    // SAFETY: a static string.
    let message =
        unsafe { CStr::from_ptr(rotor_rub_error_message(ROTOR_RUB_ERR_INVALID_ARGUMENT)) };
    assert!(message.to_str().unwrap().contains("capacity"));
}

#[test]
fn a_large_but_possible_capacity_gets_only_the_texts_bytes() {
    let (mut params, initial, t0) = paper();
    params.speed_ratio = -1.0;
    // A buffer of 200 bytes said to be a megabyte (the caller's contract broken as far as it
    // can be without the count being impossible): only the message and its NUL are written.
    let mut buffer = vec![0x5a_u8; 200];
    // SAFETY: the message below is shorter than 200 bytes, and only it is written.
    let rc = unsafe {
        rotor_rub_problem_validate(&params, &initial, t0, buffer.as_mut_ptr().cast(), 1 << 20)
    };
    assert_eq!(rc, ROTOR_RUB_ERR_INVALID_PARAMS);
    let text = CStr::from_bytes_until_nul(&buffer)
        .unwrap()
        .to_str()
        .unwrap();
    assert_eq!(
        text,
        "speed_ratio = -1 is out of range: it must be in [0.001, 100]"
    );
    assert!(buffer[text.len() + 1..].iter().all(|&b| b == 0x5a));
    // Truncation still leaves a NUL inside the capacity.
    let mut small = [0x5a_u8; 8];
    // SAFETY: 5 writable bytes of 8.
    let rc =
        unsafe { rotor_rub_problem_validate(&params, &initial, t0, small.as_mut_ptr().cast(), 5) };
    assert_eq!(rc, ROTOR_RUB_ERR_INVALID_PARAMS);
    assert_eq!(&small, b"spee\0\x5a\x5a\x5a");
}
