//! The C ABI from Rust: null pointers, uninitialised or misaligned memory, invalid values and
//! configurations give their error codes; every code has a message; no call allocates.

use std::ffi::CStr;

use rotor_rub_ffi::*;

#[path = "common/alloc.rs"]
mod alloc;
use alloc::allocations;

fn blank() -> RotorRubStepper {
    RotorRubStepper {
        _opaque: [0; ROTOR_RUB_STEPPER_WORDS],
    }
}

fn paper() -> (RotorRubParams, RotorRubState, f64) {
    let mut params = RotorRubParams::from(rotor_rub::Preset::PaperText.problem().params);
    let mut initial = RotorRubState::default();
    let mut t0 = f64::NAN;
    // SAFETY: valid pointers.
    let rc =
        unsafe { rotor_rub_preset(ROTOR_RUB_PRESET_PAPER, &mut params, &mut initial, &mut t0) };
    assert_eq!(rc, ROTOR_RUB_OK);
    (params, initial, t0)
}

#[test]
fn a_whole_session_allocates_nothing_and_matches_rust() {
    let (params, initial, t0) = paper();
    let mut config = RotorRubConfig {
        dt: 0.0,
        scheme: -1,
        contact_substeps: 0,
        max_substeps: 0,
        on_cap: 9,
        switch_start: 9,
    };
    let mut stepper = blank();
    let mut result = RotorRubStepResult::default();
    let probe = allocations();
    drop(std::hint::black_box(vec![0u8; 8]));
    assert!(allocations() > probe, "the counting allocator counts");
    let before = allocations();
    // SAFETY: every pointer is valid.
    unsafe {
        assert_eq!(rotor_rub_config_default(&mut config), ROTOR_RUB_OK);
        assert_eq!(
            rotor_rub_stepper_init(&mut stepper, &params, &initial, t0, &config),
            ROTOR_RUB_OK
        );
        let mut events = 0;
        for _ in 0..20_000 {
            assert_eq!(
                rotor_rub_stepper_step(&mut stepper, config.dt, &mut result),
                ROTOR_RUB_OK
            );
            events += result.event_count;
        }
        assert!(events > 10, "the paper preset rubs: {events} switches");
        let mut faster = params;
        faster.speed_ratio = 2.0;
        assert_eq!(
            rotor_rub_stepper_set_params(&mut stepper, &faster),
            ROTOR_RUB_OK
        );
        assert_eq!(
            rotor_rub_stepper_step(&mut stepper, 2e-3, &mut result),
            ROTOR_RUB_OK
        );
        let (mut time, mut state, mut regime) = (0.0, RotorRubState::default(), -1);
        assert_eq!(
            rotor_rub_stepper_state(&stepper, &mut time, &mut state, &mut regime),
            ROTOR_RUB_OK
        );
        assert_eq!(
            (time, state, regime),
            (result.time, result.state, result.regime)
        );
        let mut read = RotorRubParams::from(rotor_rub::Preset::PaperText.problem().params);
        assert_eq!(rotor_rub_stepper_params(&stepper, &mut read), ROTOR_RUB_OK);
        assert_eq!(read, faster);
    }
    assert_eq!(allocations(), before, "a C ABI call allocated");

    // The same steps through the Rust API.
    let problem = rotor_rub::Problem {
        params: params.into(),
        initial: initial.into(),
        start_time: t0,
    };
    let mut rust = rotor_rub::Stepper::new(&problem, rotor_rub::StepperConfig::default()).unwrap();
    for _ in 0..20_000 {
        rust.step(1e-3).unwrap();
    }
    let mut faster = problem.params;
    faster.speed_ratio = 2.0;
    rust.set_params(&faster).unwrap();
    let r = rust.step(2e-3).unwrap();
    assert_eq!(RotorRubStepResult::from(&r), result);
}

#[test]
fn misuse_gives_error_codes() {
    let (params, initial, t0) = paper();
    let null_stepper = std::ptr::null_mut::<RotorRubStepper>();
    let mut stepper = blank();
    let mut result = RotorRubStepResult::default();
    let mut message = [0 as std::ffi::c_char; 96];
    // SAFETY: pointers are valid or null, as each call allows.
    unsafe {
        assert_eq!(
            rotor_rub_stepper_step(null_stepper, 1e-3, &mut result),
            ROTOR_RUB_ERR_NULL
        );
        assert_eq!(
            rotor_rub_stepper_step(&mut stepper, 1e-3, &mut result),
            ROTOR_RUB_ERR_NOT_INITIALIZED
        );
        assert_eq!(
            rotor_rub_stepper_init(
                &mut stepper,
                std::ptr::null(),
                &initial,
                t0,
                std::ptr::null()
            ),
            ROTOR_RUB_ERR_NULL
        );
        assert_eq!(
            rotor_rub_preset(
                7,
                std::ptr::null_mut(),
                std::ptr::null_mut(),
                std::ptr::null_mut()
            ),
            ROTOR_RUB_ERR_INVALID_ARGUMENT
        );
        assert_eq!(
            rotor_rub_config_default(std::ptr::null_mut()),
            ROTOR_RUB_ERR_NULL
        );
        // Misaligned memory.
        let mut words = [0u64; ROTOR_RUB_STEPPER_WORDS + 1];
        let odd = words
            .as_mut_ptr()
            .cast::<u8>()
            .add(4)
            .cast::<RotorRubStepper>();
        assert_eq!(
            rotor_rub_stepper_init(odd, &params, &initial, t0, std::ptr::null()),
            ROTOR_RUB_ERR_MISALIGNED
        );
        // Invalid parameters, with the message.
        let mut bad = params;
        bad.speed_ratio = -1.0;
        let rc =
            rotor_rub_problem_validate(&bad, &initial, t0, message.as_mut_ptr(), message.len());
        assert_eq!(rc, ROTOR_RUB_ERR_INVALID_PARAMS);
        let text = CStr::from_ptr(message.as_ptr()).to_str().unwrap();
        assert!(
            text.starts_with("speed_ratio = -1 is out of range: it must be in [0.001, 100]"),
            "{text}"
        );
        let rc = rotor_rub_problem_validate(&bad, &initial, t0, message.as_mut_ptr(), 8);
        assert_eq!(rc, ROTOR_RUB_ERR_INVALID_PARAMS);
        assert_eq!(CStr::from_ptr(message.as_ptr()).to_bytes(), b"speed_r");
        assert_eq!(
            rotor_rub_stepper_init(&mut stepper, &bad, &initial, t0, std::ptr::null()),
            ROTOR_RUB_ERR_INVALID_PARAMS
        );
        assert_eq!(
            rotor_rub_stepper_step(&mut stepper, 1e-3, &mut result),
            ROTOR_RUB_ERR_NOT_INITIALIZED,
            "a failed init leaves the memory uninitialised"
        );
        let mut config = RotorRubConfig {
            dt: 1e-3,
            scheme: 5,
            contact_substeps: 1,
            max_substeps: 8,
            on_cap: ROTOR_RUB_ON_CAP_DEGRADE,
            switch_start: ROTOR_RUB_SWITCH_START_NEWTON,
        };
        assert_eq!(
            rotor_rub_stepper_init(&mut stepper, &params, &initial, t0, &config),
            ROTOR_RUB_ERR_INVALID_CONFIG
        );
        config.scheme = ROTOR_RUB_SCHEME_EXPRB2;
        config.max_substeps = 0;
        assert_eq!(
            rotor_rub_stepper_init(&mut stepper, &params, &initial, t0, &config),
            ROTOR_RUB_ERR_INVALID_CONFIG
        );
        config.max_substeps = 8;
        assert_eq!(
            rotor_rub_stepper_init(&mut stepper, &params, &initial, t0, &config),
            ROTOR_RUB_OK
        );
        for dt in [0.0, -1.0, f64::NAN, f64::INFINITY, 1.5] {
            assert_eq!(
                rotor_rub_stepper_step(&mut stepper, dt, &mut result),
                ROTOR_RUB_ERR_INVALID_STEP
            );
        }
        assert_eq!(
            rotor_rub_stepper_step(&mut stepper, 1e-3, std::ptr::null_mut()),
            ROTOR_RUB_OK
        );
        assert_eq!(
            rotor_rub_stepper_set_params(&mut stepper, &bad),
            ROTOR_RUB_ERR_INVALID_PARAMS
        );
        assert_eq!(
            rotor_rub_stepper_set_params(&mut stepper, std::ptr::null()),
            ROTOR_RUB_ERR_NULL
        );
        assert_eq!(
            rotor_rub_stepper_state(
                &stepper,
                std::ptr::null_mut(),
                std::ptr::null_mut(),
                std::ptr::null_mut()
            ),
            ROTOR_RUB_OK
        );
    }
}

#[test]
fn every_code_has_a_message_and_the_memory_fits() {
    for code in -1..=12 {
        let text = unsafe { CStr::from_ptr(rotor_rub_error_message(code)) };
        assert!(!text.to_bytes().is_empty());
    }
    let unknown = unsafe { CStr::from_ptr(rotor_rub_error_message(99)) };
    assert_eq!(unknown.to_str().unwrap(), "unknown error code");
    assert!(rotor_rub_stepper_size() <= size_of::<RotorRubStepper>());
    assert!(rotor_rub_stepper_align() <= align_of::<RotorRubStepper>());
    let version = unsafe { CStr::from_ptr(rotor_rub_version()) };
    assert_eq!(version.to_str().unwrap(), env!("CARGO_PKG_VERSION"));
}

/// The parameter functions reach every table entry by index and by name, write only the
/// struct holding the parameter, check the range, and agree with the Rust table (so the
/// `RotorRubParams` mirror and its conversions list the fields in the table's meaning).
#[test]
fn parameters_by_index_and_name() {
    use rotor_rub::{Parameter, Params, Problem};
    assert_eq!(ROTOR_RUB_PARAMETER_COUNT, Parameter::COUNT);
    let mut params = RotorRubParams::from(Params::DEFAULT);
    let mut initial = RotorRubState::default();
    let mut start_time = 0.0;
    let mut name = [0 as std::ffi::c_char; 32];
    let before = allocations();
    for (i, p) in Parameter::ALL.into_iter().enumerate() {
        let index = i32::try_from(i).unwrap();
        let info = p.info();
        let (mut default, mut min, mut max, mut open) = (0.0, 0.0, 0.0, 0);
        // SAFETY: valid pointers and buffer sizes.
        unsafe {
            let rc = rotor_rub_parameter_info(
                index,
                name.as_mut_ptr(),
                name.len(),
                &mut default,
                &mut min,
                &mut max,
                &mut open,
            );
            assert_eq!(rc, ROTOR_RUB_OK);
            assert_eq!(CStr::from_ptr(name.as_ptr()).to_str(), Ok(info.name));
            assert_eq!(
                (default, min, max, open == 1),
                (
                    info.default,
                    info.range.min,
                    info.range.max,
                    info.range.min_open
                )
            );
            let mut found = -1;
            assert_eq!(
                rotor_rub_parameter_index(name.as_ptr(), &mut found),
                ROTOR_RUB_OK
            );
            assert_eq!(found, index);
            // A distinct in-range value lands where the Rust table says, nowhere else.
            let value = if info.range.contains(0.5 + 0.125 * i as f64) {
                0.5 + 0.125 * i as f64
            } else {
                info.range.max
            };
            let untouched = (params, initial, start_time);
            let rc =
                rotor_rub_parameter_set(&mut params, &mut initial, &mut start_time, index, value);
            assert_eq!(rc, ROTOR_RUB_OK, "{p}");
            let problem = Problem {
                params: params.into(),
                initial: initial.into(),
                start_time,
            };
            assert_eq!(p.get(&problem), value, "{p}");
            let mut back = f64::NAN;
            let rc = rotor_rub_parameter_get(&params, &initial, &start_time, index, &mut back);
            assert_eq!((rc, back), (ROTOR_RUB_OK, value), "{p}");
            // Out of range or not finite: an error and nothing written.
            let changed = (params, initial, start_time);
            for bad in [info.range.max.next_up(), f64::NAN] {
                let rc =
                    rotor_rub_parameter_set(&mut params, &mut initial, &mut start_time, index, bad);
                assert_eq!(rc, ROTOR_RUB_ERR_INVALID_PARAMS, "{p} = {bad}");
            }
            assert_eq!((params, initial, start_time), changed);
            // Exactly one of the three holders changed.
            let moved = [
                params != untouched.0,
                initial != untouched.1,
                start_time != untouched.2,
            ];
            assert_eq!(moved.iter().filter(|&&m| m).count(), 1, "{p}");
        }
    }
    assert_eq!(allocations(), before, "parameter calls allocate");
    // SAFETY: valid or null pointers as each case says.
    unsafe {
        let mut found = 0;
        for bad in [-1, ROTOR_RUB_PARAMETER_COUNT as i32, i32::MAX] {
            assert_eq!(
                rotor_rub_parameter_set(&mut params, &mut initial, &mut start_time, bad, 1.0),
                ROTOR_RUB_ERR_INVALID_ARGUMENT
            );
            assert_eq!(
                rotor_rub_parameter_info(
                    bad,
                    name.as_mut_ptr(),
                    4,
                    std::ptr::null_mut(),
                    std::ptr::null_mut(),
                    std::ptr::null_mut(),
                    std::ptr::null_mut()
                ),
                ROTOR_RUB_ERR_INVALID_ARGUMENT
            );
        }
        assert_eq!(
            rotor_rub_parameter_index(c"omega".as_ptr(), &mut found),
            ROTOR_RUB_ERR_INVALID_ARGUMENT
        );
        assert_eq!(
            rotor_rub_parameter_index(c"\xff".as_ptr(), &mut found),
            ROTOR_RUB_ERR_INVALID_ARGUMENT
        );
        assert_eq!(
            rotor_rub_parameter_index(std::ptr::null(), &mut found),
            ROTOR_RUB_ERR_NULL
        );
        // The holder of the parameter is required, the others are not.
        assert_eq!(
            rotor_rub_parameter_set(std::ptr::null_mut(), &mut initial, &mut start_time, 0, 2.0),
            ROTOR_RUB_ERR_NULL
        );
        assert_eq!(
            rotor_rub_parameter_set(
                &mut params,
                std::ptr::null_mut(),
                std::ptr::null_mut(),
                0,
                2.0
            ),
            ROTOR_RUB_OK
        );
        assert_eq!(params.speed_ratio, 2.0);
        let mut value = 0.0;
        // The first start value (x0) needs the initial state.
        let x0 = Parameter::X0 as i32;
        assert_eq!(
            rotor_rub_parameter_get(&params, std::ptr::null(), std::ptr::null(), x0, &mut value),
            ROTOR_RUB_ERR_NULL
        );
        assert_eq!(
            rotor_rub_parameter_get(
                &params,
                std::ptr::null(),
                std::ptr::null(),
                0,
                std::ptr::null_mut()
            ),
            ROTOR_RUB_ERR_NULL
        );
        // Truncated names stay NUL-terminated.
        rotor_rub_parameter_info(
            3,
            name.as_mut_ptr(),
            4,
            std::ptr::null_mut(),
            std::ptr::null_mut(),
            std::ptr::null_mut(),
            std::ptr::null_mut(),
        );
        assert_eq!(CStr::from_ptr(name.as_ptr()).to_bytes(), b"ecc");
    }
}

/// Friction through the C ABI (issue 12): the dry-whip preset rolls (ROLL, SLIP codes, regime
/// ROLLING at the end) and the reversal case reverses (REVERSE), with no allocation.
#[test]
fn friction_through_the_c_abi() {
    let mut params = RotorRubParams::from(rotor_rub::Preset::Paper.problem().params);
    let (mut initial, mut t0) = (RotorRubState::default(), 0.0);
    let mut config = RotorRubConfig {
        dt: 0.0,
        scheme: -1,
        contact_substeps: 0,
        max_substeps: 0,
        on_cap: 9,
        switch_start: 9,
    };
    let mut reversal = RotorRubParams::from(rotor_rub::Preset::Paper.problem().params);
    reversal.speed_ratio = 2.0;
    reversal.friction_coefficient = 0.2;
    reversal.radius_ratio = 1.0;
    let before = allocations();
    // SAFETY: every pointer is valid.
    unsafe {
        assert_eq!(rotor_rub_config_default(&mut config), ROTOR_RUB_OK);
        assert_eq!(
            rotor_rub_preset(
                ROTOR_RUB_PRESET_DRY_WHIP,
                &mut params,
                &mut initial,
                &mut t0
            ),
            ROTOR_RUB_OK
        );
        for (p, steps, wanted) in [
            (params, 60_000, [ROTOR_RUB_EVENT_ROLL, ROTOR_RUB_EVENT_SLIP]),
            (
                reversal,
                30_000,
                [ROTOR_RUB_EVENT_REVERSE, ROTOR_RUB_EVENT_ENTER],
            ),
        ] {
            let mut stepper = blank();
            let mut result = RotorRubStepResult::default();
            assert_eq!(
                rotor_rub_stepper_init(&mut stepper, &p, &initial, t0, &config),
                ROTOR_RUB_OK
            );
            let mut seen = [0u32; 6];
            for _ in 0..steps {
                assert_eq!(
                    rotor_rub_stepper_step(&mut stepper, config.dt, &mut result),
                    ROTOR_RUB_OK
                );
                for e in result.events.iter().take(result.event_count as usize) {
                    seen[e.kind as usize] += 1;
                }
            }
            for kind in wanted {
                assert!(seen[kind as usize] > 0, "event code {kind} seen: {seen:?}");
            }
            if p.friction_coefficient == 0.6 {
                assert_eq!(result.regime, ROTOR_RUB_REGIME_ROLLING, "dry whip rolls on");
            }
        }
        // Friction with a stator whose symmetric part is not definite is refused.
        let mut bad = reversal;
        bad.k_xy = 30.0;
        bad.k_yx = 30.0;
        let mut stepper = blank();
        assert_eq!(
            rotor_rub_stepper_init(&mut stepper, &bad, &initial, t0, &config),
            ROTOR_RUB_ERR_INVALID_PARAMS
        );
    }
    assert_eq!(allocations(), before, "friction steps allocate");
}

#[test]
fn input_force_and_speed_setters_match_rust_and_refuse_bad_values() {
    let (params, initial, t0) = paper();
    let mut stepper = blank();
    let mut result = RotorRubStepResult::default();
    let problem = rotor_rub::Problem {
        params: params.into(),
        initial: initial.into(),
        start_time: t0,
    };
    let mut rust = rotor_rub::Stepper::new(&problem, rotor_rub::StepperConfig::default()).unwrap();
    // SAFETY: every pointer is valid.
    unsafe {
        assert_eq!(
            rotor_rub_stepper_init(&mut stepper, &params, &initial, t0, std::ptr::null()),
            ROTOR_RUB_OK
        );
        let before = allocations();
        for k in 0..5000 {
            let (fx, fy) = (0.3 * (k as f64 * 1e-3).sin(), -0.2);
            assert_eq!(
                rotor_rub_stepper_set_input_force(&mut stepper, fx, fy),
                ROTOR_RUB_OK
            );
            rust.set_input_force(fx, fy).unwrap();
            if k == 2500 {
                assert_eq!(
                    rotor_rub_stepper_set_speed_ratio(&mut stepper, 1.8),
                    ROTOR_RUB_OK
                );
                rust.set_speed_ratio(1.8).unwrap();
            }
            assert_eq!(
                rotor_rub_stepper_step(&mut stepper, 1e-3, &mut result),
                ROTOR_RUB_OK
            );
            assert_eq!(result, RotorRubStepResult::from(&rust.step(1e-3).unwrap()));
        }
        assert_eq!(allocations(), before, "the setters allocate nothing");
        for (fx, fy) in [(f64::NAN, 0.0), (0.0, 2e3)] {
            assert_eq!(
                rotor_rub_stepper_set_input_force(&mut stepper, fx, fy),
                ROTOR_RUB_ERR_INVALID_VALUE
            );
        }
        for eta in [f64::INFINITY, -1.0, 0.0] {
            assert_eq!(
                rotor_rub_stepper_set_speed_ratio(&mut stepper, eta),
                ROTOR_RUB_ERR_INVALID_VALUE
            );
        }
        assert_eq!(
            rotor_rub_stepper_set_input_force(std::ptr::null_mut(), 0.0, 0.0),
            ROTOR_RUB_ERR_NULL
        );
        let mut read = params;
        assert_eq!(rotor_rub_stepper_params(&stepper, &mut read), ROTOR_RUB_OK);
        assert_eq!((read.force_x, read.force_y), rust.input_force());
        assert_eq!(read.speed_ratio, 1.8);
    }
}

/// The C ABI's presets are the library's (`Preset::ALL`, numbered in order: the planar ones,
/// then `stator-mass` and `ring-whirl`, whose ring with mass the C stepper runs); other numbers
/// are refused as unknown presets.
#[test]
fn the_c_presets_are_the_library_presets() {
    use rotor_rub::Preset;
    for (number, preset) in (0..).zip(Preset::ALL) {
        let mut params = RotorRubParams::from(rotor_rub::Params::DEFAULT);
        let mut initial = RotorRubState::default();
        let mut t0 = f64::NAN;
        // SAFETY: valid pointers.
        let rc = unsafe { rotor_rub_preset(number, &mut params, &mut initial, &mut t0) };
        assert_eq!(rc, ROTOR_RUB_OK, "{}", preset.name());
        let problem = preset.problem();
        assert_eq!(
            params,
            RotorRubParams::from(problem.params),
            "{}",
            preset.name()
        );
        assert_eq!(
            params.stator_mass_ratio > 0.0,
            Preset::RING.contains(&preset),
            "{}",
            preset.name()
        );
        assert_eq!(t0, problem.start_time);
    }
    for number in [-1, 6] {
        let mut params = RotorRubParams::from(rotor_rub::Params::DEFAULT);
        // SAFETY: valid pointers (null skips the optional outputs).
        let rc = unsafe {
            rotor_rub_preset(
                number,
                &mut params,
                std::ptr::null_mut(),
                std::ptr::null_mut(),
            )
        };
        assert_eq!(rc, ROTOR_RUB_ERR_INVALID_ARGUMENT, "preset number {number}");
    }
}
