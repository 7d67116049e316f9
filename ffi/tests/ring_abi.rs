//! The stator ring with mass through the C ABI, from Rust: a problem with
//! `stator_mass_ratio` > 0 initialises the ring's stepper in the caller's memory, steps and
//! reads the ring's state without allocating; its inputs and bad values give the planar
//! stepper's error codes; the massless ring's state reads 0.

use rotor_rub::{Parameter, Preset};
use rotor_rub_ffi::*;

#[path = "common/alloc.rs"]
mod alloc;
use alloc::allocations;

fn ring_problem() -> rotor_rub::Problem {
    let mut problem = Preset::Paper.problem();
    for (p, v) in [
        (Parameter::StatorMassRatio, 1.0),
        (Parameter::ContactStiffness, 100.0),
        (Parameter::StatorDamping, 0.5),
    ] {
        p.set(&mut problem, v);
    }
    problem
}

/// The stepper memory on the heap (40 KiB: a test thread's stack is small).
fn memory() -> Box<RotorRubStepper> {
    Box::new(RotorRubStepper {
        _opaque: [0; ROTOR_RUB_STEPPER_WORDS],
    })
}

#[test]
fn a_ring_session_steps_reads_the_ring_and_allocates_nothing() {
    let problem = ring_problem();
    let params = RotorRubParams::from(problem.params);
    let initial = RotorRubState::from(problem.initial);
    let mut stepper = memory();
    let s: *mut RotorRubStepper = &mut *stepper;
    let before = allocations();
    // SAFETY: valid pointers; `s` is valid stepper memory.
    unsafe {
        assert_eq!(
            rotor_rub_stepper_init(s, &params, &initial, 0.0, std::ptr::null()),
            ROTOR_RUB_OK
        );
        let mut ring = RotorRubRingState::default();
        let mut is_ring = -1;
        assert_eq!(
            rotor_rub_stepper_ring_state(s, &mut ring, &mut is_ring),
            ROTOR_RUB_OK
        );
        assert_eq!(is_ring, 1);
        let mut largest = 0.0f64;
        let mut switches = 0;
        let mut result = std::mem::MaybeUninit::<RotorRubStepResult>::uninit();
        for k in 0..20_000 {
            if k == 10_000 {
                assert_eq!(
                    rotor_rub_stepper_set_input_force(s, 0.2, -0.1),
                    ROTOR_RUB_OK
                );
                assert_eq!(rotor_rub_stepper_set_speed_ratio(s, 1.4), ROTOR_RUB_OK);
            }
            assert_eq!(
                rotor_rub_stepper_step(s, 1e-3, result.as_mut_ptr()),
                ROTOR_RUB_OK
            );
            let r = result.assume_init_ref();
            switches += r.event_count + r.dropped_events;
            assert_eq!(
                rotor_rub_stepper_ring_state(s, &mut ring, std::ptr::null_mut()),
                0
            );
            largest = largest.max(ring.xs.hypot(ring.ys));
        }
        assert_eq!(allocations(), before, "no call allocates");
        assert!(switches > 20, "it rubs ({switches} switches)");
        assert!(largest > 0.3, "the ring moves ({largest})");
        let mut time = 0.0;
        assert_eq!(
            rotor_rub_stepper_state(s, &mut time, std::ptr::null_mut(), std::ptr::null_mut()),
            ROTOR_RUB_OK
        );
        assert!((time - 20.0).abs() < 1e-9, "{time}");
    }
}

#[test]
fn bad_values_give_error_codes_and_change_nothing() {
    let problem = ring_problem();
    let params = RotorRubParams::from(problem.params);
    let initial = RotorRubState::from(problem.initial);
    let mut stepper = memory();
    let s: *mut RotorRubStepper = &mut *stepper;
    // SAFETY: valid pointers; `s` is valid stepper memory.
    unsafe {
        assert_eq!(
            rotor_rub_stepper_init(s, &params, &initial, 0.0, std::ptr::null()),
            ROTOR_RUB_OK
        );
        for _ in 0..500 {
            assert_eq!(
                rotor_rub_stepper_step(s, 1e-2, std::ptr::null_mut()),
                ROTOR_RUB_OK
            );
        }
        let read = |s: *mut RotorRubStepper| {
            let (mut t, mut state, mut ring) =
                (0.0, RotorRubState::default(), RotorRubRingState::default());
            rotor_rub_stepper_state(s, &mut t, &mut state, std::ptr::null_mut());
            rotor_rub_stepper_ring_state(s, &mut ring, std::ptr::null_mut());
            (t, state, ring)
        };
        let saved = read(s);
        let mut massless = problem.params;
        massless.stator_mass_ratio = 0.0;
        massless.contact_stiffness = Parameter::ContactStiffness.info().default;
        massless.stator_damping = 0.0;
        let massless = RotorRubParams::from(massless);
        assert_eq!(
            rotor_rub_stepper_set_params(s, &massless),
            ROTOR_RUB_ERR_INVALID_PARAMS
        );
        assert_eq!(
            rotor_rub_stepper_set_input_force(s, f64::NAN, 0.0),
            ROTOR_RUB_ERR_INVALID_VALUE
        );
        assert_eq!(
            rotor_rub_stepper_set_speed_ratio(s, -1.0),
            ROTOR_RUB_ERR_INVALID_VALUE
        );
        for dt in [0.0, -1.0, 2.0, f64::NAN] {
            assert_eq!(
                rotor_rub_stepper_step(s, dt, std::ptr::null_mut()),
                ROTOR_RUB_ERR_INVALID_STEP
            );
        }
        assert_eq!(read(s), saved, "nothing changed");
        assert_eq!(
            rotor_rub_stepper_ring_state(s, std::ptr::null_mut(), std::ptr::null_mut()),
            ROTOR_RUB_ERR_NULL
        );
        // A bad ring value at initialisation: k̂_c out of range.
        let mut bad = problem.params;
        bad.contact_stiffness = -1.0;
        let bad = RotorRubParams::from(bad);
        assert_eq!(
            rotor_rub_stepper_init(s, &bad, &initial, 0.0, std::ptr::null()),
            ROTOR_RUB_ERR_INVALID_PARAMS
        );
        assert_eq!(
            rotor_rub_stepper_step(s, 1e-3, std::ptr::null_mut()),
            ROTOR_RUB_ERR_NOT_INITIALIZED
        );
        // The massless ring: the planar stepper, its ring at rest.
        let paper = RotorRubParams::from(Preset::Paper.problem().params);
        assert_eq!(
            rotor_rub_stepper_init(s, &paper, &initial, 0.0, std::ptr::null()),
            ROTOR_RUB_OK
        );
        let mut ring = RotorRubRingState {
            xs: 1.0,
            ..Default::default()
        };
        let mut is_ring = -1;
        assert_eq!(
            rotor_rub_stepper_ring_state(s, &mut ring, &mut is_ring),
            ROTOR_RUB_OK
        );
        assert_eq!((ring, is_ring), (RotorRubRingState::default(), 0));
    }
}

/// `rotor_rub_stepper_contact_resolution`: the planar stepper's contact sub-steps and longest
/// resolved step as the Rust stepper gives them (1 on the paper preset at dt = 1e-2; more on a
/// stator 30× dry whip's stiffness), 0 and +infinity for the ring; a null stepper is refused.
#[test]
fn the_contact_resolution_is_the_rust_steppers() {
    let mut stiff = Preset::DryWhip.problem();
    stiff.params.k_xx = 1e4;
    stiff.params.k_yy = 1e4;
    for (problem, expect_ring) in [
        (Preset::Paper.problem(), false),
        (stiff, false),
        (ring_problem(), true),
    ] {
        let params = RotorRubParams::from(problem.params);
        let initial = RotorRubState::from(problem.initial);
        let mut config = RotorRubConfig {
            dt: 0.0,
            scheme: -1,
            contact_substeps: 0,
            max_substeps: 0,
            on_cap: 9,
            switch_start: 9,
        };
        // SAFETY: valid pointer.
        assert_eq!(
            unsafe { rotor_rub_config_default(&mut config) },
            ROTOR_RUB_OK
        );
        config.dt = 1e-2;
        let mut stepper = memory();
        let s: *mut RotorRubStepper = &mut *stepper;
        let (mut substeps, mut largest) = (u32::MAX, f64::NAN);
        // SAFETY: valid pointers; `s` is valid stepper memory.
        unsafe {
            assert_eq!(
                rotor_rub_stepper_init(s, &params, &initial, 0.0, &config),
                ROTOR_RUB_OK
            );
            assert_eq!(
                rotor_rub_stepper_contact_resolution(s, &mut substeps, &mut largest),
                ROTOR_RUB_OK
            );
        }
        if expect_ring {
            assert_eq!((substeps, largest), (0, f64::INFINITY));
        } else {
            let rust = rotor_rub::Stepper::new(&problem, rotor_rub::StepperConfig::with_dt(1e-2))
                .expect("starts");
            assert_eq!(
                (substeps, largest),
                (rust.contact_substeps(), rust.largest_resolved_dt())
            );
            assert_eq!(substeps > 1, problem.params.k_xx > 1e3, "{substeps}");
        }
    }
    // SAFETY: null stepper: refused before any read; null outputs are skipped.
    let code = unsafe {
        rotor_rub_stepper_contact_resolution(
            std::ptr::null(),
            std::ptr::null_mut(),
            std::ptr::null_mut(),
        )
    };
    assert_eq!(code, ROTOR_RUB_ERR_NULL);
}
