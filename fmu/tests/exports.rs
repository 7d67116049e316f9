//! The exported FMI functions called from Rust as an importer would: no allocation in DoStep,
//! get/set or error paths after instantiation (a counting allocator), early return at the
//! library stepper's switch, serialization round trip, the model description generated from the
//! parameter table.

mod common;

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::ffi::c_void;

use common::{instantiate, step};
use rotor_rub::{Parameter, Preset, Stepper, StepperConfig};
use rotor_rub_fmu::description::{Version, guid, model_description};
use rotor_rub_fmu::fmi3::*;
use rotor_rub_fmu::instance::status;
use rotor_rub_fmu::saved::*;
use rotor_rub_fmu::units::Units;

struct Counting;

thread_local! {
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

fn allocations() -> usize {
    ALLOCATIONS.with(Cell::get)
}

// SAFETY: forwards to the system allocator.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let _ = ALLOCATIONS.try_with(|n| n.set(n.get() + 1));
        // SAFETY: same contract.
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: same contract.
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

fn logged() -> usize {
    common::COUNT.with(Cell::get)
}

#[test]
fn do_step_set_get_and_errors_allocate_nothing() {
    let i = instantiate(true);
    let before = allocations();
    common::RECORD.with(|r| r.set(false));
    let logged_before = logged();
    let mut t = 0.0;
    let (fx, x) = (10u32, [1u32, 2, 3, 4]);
    let mut out = [0.0; 4];
    // SAFETY: a live instance, valid arrays.
    unsafe {
        for k in 0..20_000 {
            let f = [0.1 * (k as f64 * 1e-3).sin()];
            assert_eq!(fmi3SetFloat64(i, &fx, 1, f.as_ptr(), 1), status::OK);
            let (s, _, last) = step(i, t, 1e-3);
            assert_eq!(s, status::OK);
            t = last;
            assert_eq!(
                fmi3GetFloat64(i, x.as_ptr(), 4, out.as_mut_ptr(), 4),
                status::OK
            );
        }
        // Error paths log into a fixed buffer: no allocation either.
        let nan = [f64::NAN];
        assert_eq!(fmi3SetFloat64(i, &fx, 1, nan.as_ptr(), 1), status::ERROR);
        assert_eq!(step(i, t, -1.0).0, status::ERROR);
        assert_eq!(step(i, t + 1.0, 1e-3).0, status::ERROR);
    }
    let after = allocations();
    assert_eq!(after, before, "an FMI call allocated after instantiation");
    assert_eq!(logged(), logged_before + 3, "each error logged once");
    common::RECORD.with(|r| r.set(true));
    // SAFETY: a live instance, freed once.
    unsafe { fmi3FreeInstance(i) };
}

#[test]
fn early_return_reports_the_stepper_switch_time() {
    let i = instantiate(true);
    let problem = Preset::Paper.problem();
    let mut reference = Stepper::new(&problem, StepperConfig::with_dt(1e-3)).unwrap();
    let mut first = None;
    while first.is_none() {
        first = reference
            .step(1e-3)
            .unwrap()
            .events
            .iter()
            .next()
            .map(|e| e.time);
    }
    let (s, early, last) = step(i, 0.0, 10.0);
    assert_eq!((s, early), (status::OK, true));
    // The FMU's internal steps are the same 1e-3 grid: the same switch, bit for bit.
    assert_eq!(Some(last), first);
    // SAFETY: as above.
    unsafe { fmi3FreeInstance(i) };
}

#[test]
fn a_serialized_state_restores_the_run() {
    let i = instantiate(false);
    // SAFETY: a live instance, valid pointers.
    unsafe {
        let mut t = 0.0;
        for _ in 0..1000 {
            t = step(i, t, 1e-3).2;
        }
        let mut saved: *mut c_void = std::ptr::null_mut();
        assert_eq!(fmi3GetFMUState(i, &mut saved), status::OK);
        let mut size = 0;
        assert_eq!(fmi3SerializedFMUStateSize(i, saved, &mut size), status::OK);
        let mut bytes = vec![0u8; size];
        assert_eq!(
            fmi3SerializeFMUState(i, saved, bytes.as_mut_ptr(), size),
            status::OK
        );
        let vr = [1u32, 2, 3, 4, 6];
        let run = |t0: f64| {
            let mut t = t0;
            for _ in 0..3000 {
                t = step(i, t, 1e-3).2;
            }
            let mut out = [0.0; 5];
            assert_eq!(
                fmi3GetFloat64(i, vr.as_ptr(), 5, out.as_mut_ptr(), 5),
                status::OK
            );
            out
        };
        let a = run(t);
        let mut restored: *mut c_void = std::ptr::null_mut();
        assert_eq!(
            fmi3DeserializeFMUState(i, bytes.as_ptr(), size, &mut restored),
            status::OK
        );
        assert_eq!(fmi3SetFMUState(i, restored), status::OK);
        assert_eq!(run(t), a);
        bytes[3] ^= 0xff;
        let mut bad: *mut c_void = std::ptr::null_mut();
        assert_eq!(
            fmi3DeserializeFMUState(i, bytes.as_ptr(), size, &mut bad),
            status::ERROR
        );
        assert!(bad.is_null());
        assert_eq!(fmi3FreeFMUState(i, &mut saved), status::OK);
        assert_eq!(fmi3FreeFMUState(i, &mut restored), status::OK);
        fmi3FreeInstance(i);
    }
}

#[test]
fn the_descriptions_list_every_table_entry_with_its_range() {
    use Parameter as P;
    for version in [Version::Fmi2, Version::Fmi3] {
        let xml = model_description(version, Units::Dimensionless);
        assert!(xml.contains(&guid(Units::Dimensionless)));
        for p in Parameter::ALL {
            let info = p.info();
            let name = match p {
                P::ForceX => "fx",
                P::ForceY => "fy",
                P::StartTime => continue,
                // The ring's entries included: `stator_mass_ratio` > 0 runs the ring with mass.
                _ => info.name,
            };
            let lines: Vec<&str> = xml.lines().collect();
            let at = lines
                .iter()
                .position(|l| l.contains(&format!("name=\"{name}\"")))
                .unwrap_or_else(|| panic!("{name} missing"));
            // FMI 2.0 puts the bounds on the <Real> element of the next line.
            let line = format!("{} {}", lines[at], lines[at + 1]);
            assert!(
                line.contains(&format!("min=\"{:?}\"", info.range.min)),
                "{line}"
            );
            assert!(
                line.contains(&format!("max=\"{:?}\"", info.range.max)),
                "{line}"
            );
        }
    }
}
