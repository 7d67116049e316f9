//! The FMU built for a model file (`cargo xtask fmu --model FILE`, issue 29 item 5): the n = 4
//! rotor-in-a-ring model of `fmu/tests/data/ring_rotor.toml` read by the xtask, its resource
//! handed to the FMU's exported FMI 3.0 and 2.0 functions as an importer would, and every output
//! compared bit for bit with a `MatrixStepper` run on the CLI's own statement of the same file
//! (`ModelSpec::build`, capacity 128), an input force change included; its saved states restore
//! the same bits; a model of more than 4 DOFs and a wrong token are refused with clear messages.

use std::ffi::{CString, c_void};
use std::path::{Path, PathBuf};

use rotor_rub::stepper::matrix::MatrixStepperConfig;
use rotor_rub::stepper::{MatrixStepper, OwnedModel};
use rotor_rub::{EventKind, Regime};
use rotor_rub_cli::model_file::{CAPACITY, load, on_large_stack};
use rotor_rub_fmu::file::description::{file_model_description, file_token};
use rotor_rub_fmu::file::run::{FORCE_BASE, POSITION_BASE, VELOCITY_BASE};
use rotor_rub_fmu::file::{FileModel, RESOURCE};
use rotor_rub_fmu::fmi2::*;
use rotor_rub_fmu::fmi3::*;
use rotor_rub_fmu::instance::status;
use rotor_rub_fmu::saved::*;

fn model_path() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../fmu/tests/data/ring_rotor.toml")
}

/// The resource directory of one test (unique per test name), holding the model's resource.
fn resources(test: &str, text: &str) -> PathBuf {
    let dir =
        std::env::temp_dir().join(format!("rotor-rub-model-fmu-{}-{test}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join(RESOURCE), text).unwrap();
    dir
}

fn instantiate3(token: &str, dir: &Path) -> *mut c_void {
    let token = CString::new(token).unwrap();
    let location = CString::new(format!("{}/", dir.display())).unwrap();
    // SAFETY: valid strings; no logger.
    unsafe {
        fmi3InstantiateCoSimulation(
            c"model".as_ptr(),
            token.as_ptr(),
            location.as_ptr(),
            false,
            false,
            false,
            false,
            std::ptr::null(),
            0,
            std::ptr::null_mut(),
            None,
            std::ptr::null(),
        )
    }
}

fn get3(i: *mut c_void, vrs: &[u32]) -> Vec<f64> {
    let mut out = vec![f64::NAN; vrs.len()];
    // SAFETY: a live instance, matching counts.
    let s = unsafe { fmi3GetFloat64(i, vrs.as_ptr(), vrs.len(), out.as_mut_ptr(), out.len()) };
    assert_eq!(s, status::OK);
    out
}

fn set3(i: *mut c_void, vr: u32, value: f64) -> i32 {
    // SAFETY: a live instance, one value.
    unsafe { fmi3SetFloat64(i, &vr, 1, &value, 1) }
}

fn step3(i: *mut c_void, t: f64, h: f64) -> i32 {
    let (mut a, mut b, mut c, mut last) = (false, false, false, 0.0);
    // SAFETY: a live instance, valid outputs.
    unsafe { fmi3DoStep(i, t, h, true, &mut a, &mut b, &mut c, &mut last) }
}

/// The value references of every DOF's position and velocity, then rub_x, rub_y.
fn state_vrs(n: u32) -> Vec<u32> {
    let mut v: Vec<u32> = (0..n).map(|k| POSITION_BASE + k).collect();
    v.extend((0..n).map(|k| VELOCITY_BASE + k));
    v.extend([4, 5]);
    v
}

#[test]
fn the_fmu_steps_the_model_file_as_the_matrix_stepper_bit_for_bit() {
    let file = xtask::model::read(&model_path()).expect("the n = 4 model file reads");
    let text = file.to_text();
    assert_eq!(
        FileModel::parse(&text).unwrap(),
        file,
        "the resource round-trips exactly"
    );
    let dir = resources("bits", &text);
    let n = file.n();
    assert_eq!(n, 4);
    let delta = file.clearance;
    let spec = load(&model_path()).unwrap();
    let (h, steps, force_at, force) = (2e-4, 1500, 700, 40.0);

    // The reference: the CLI's statement (capacity 128), stepped by the matrix stepper.
    let (want, want_contacts, want_contact_flags) = on_large_stack(move || {
        let model = OwnedModel::<CAPACITY>(*spec.build().unwrap());
        let start = spec.start().unwrap();
        let mut s = MatrixStepper::new(model, 0.0, start, MatrixStepperConfig::with_dt(h)).unwrap();
        let (mut rows, mut entries, mut flags) = (Vec::new(), 0, Vec::new());
        for k in 1..=steps {
            if k == force_at + 1 {
                let mut u = vec![0.0; n];
                u[0] = force / delta;
                s.set_input(&u).unwrap();
            }
            let r = s.step(h).unwrap();
            entries += r
                .events
                .iter()
                .filter(|e| e.kind == EventKind::Enter)
                .count() as u64;
            let y = r.state.as_slice();
            let mut row: Vec<f64> = y.iter().map(|v| v * delta).collect();
            row.push((y[0] - y[2]) * delta);
            row.push((y[1] - y[3]) * delta);
            rows.push((r.time, row));
            flags.push((r.regime != Regime::Free, entries));
        }
        (rows, entries, flags)
    });
    assert!(
        want_contacts >= 3,
        "the rotor rubs ({want_contacts} contacts)"
    );

    let i = instantiate3(&file_token(&text), &dir);
    assert!(!i.is_null(), "the FMU instantiates from its resource");
    assert_eq!(set3(i, 1, h), status::OK, "internal_step");
    // SAFETY: a live instance.
    unsafe {
        assert_eq!(
            fmi3EnterInitializationMode(i, true, 1e-6, 0.0, false, 0.0),
            status::OK
        );
        assert_eq!(fmi3ExitInitializationMode(i), status::OK);
    }
    let start = get3(i, &state_vrs(4));
    assert_eq!(start[0], 5e-5, "x starts at the file's initial position");
    let vrs = state_vrs(n as u32);
    let mut t = 0.0;
    for (k, ((time, row), (contact, entries))) in want.iter().zip(&want_contact_flags).enumerate() {
        if k == force_at {
            assert_eq!(set3(i, FORCE_BASE, force), status::OK, "f_x");
        }
        assert_eq!(step3(i, t, h), status::OK, "step {k}");
        t = get3(i, &[0])[0];
        assert_eq!(t, *time, "time after step {k}");
        assert_eq!(&get3(i, &vrs), row, "outputs after step {}", k + 1);
        let mut flag = 0u8;
        let mut count = 0i64;
        // SAFETY: a live instance.
        unsafe {
            assert_eq!(fmi3GetBoolean(i, &2, 1, &mut flag, 1), status::OK);
            assert_eq!(fmi3GetInt64(i, &3, 1, &mut count, 1), status::OK);
        }
        assert_eq!((flag != 0, count as u64), (*contact, *entries), "step {k}");
    }
    println!(
        "ring rotor (n = 4), {steps} steps of {h} s: {want_contacts} contacts, every output bit-identical"
    );
    // SAFETY: created above.
    unsafe { fmi3FreeInstance(i) };
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn saved_states_restore_the_same_bits_and_fmi2_runs_the_same_model() {
    let file = xtask::model::read(&model_path()).unwrap();
    let text = file.to_text();
    let dir = resources("state", &text);
    let vrs = state_vrs(4);
    let h = 1e-3;
    let i = instantiate3(&file_token(&text), &dir);
    assert!(!i.is_null());
    // SAFETY: a live instance throughout; states created and freed here.
    unsafe {
        assert_eq!(
            fmi3EnterInitializationMode(i, false, 0.0, 0.0, false, 0.0),
            status::OK
        );
        assert_eq!(fmi3ExitInitializationMode(i), status::OK);
        let mut t = 0.0;
        for _ in 0..20 {
            assert_eq!(step3(i, t, h), status::OK);
            t = get3(i, &[0])[0];
        }
        let mut saved: *mut c_void = std::ptr::null_mut();
        assert_eq!(fmi3GetFMUState(i, &mut saved), status::OK);
        let t_saved = t;
        let mut first = Vec::new();
        for _ in 0..30 {
            assert_eq!(step3(i, t, h), status::OK);
            t = get3(i, &[0])[0];
            first.push(get3(i, &vrs));
        }
        assert_eq!(fmi3SetFMUState(i, saved), status::OK);
        assert_eq!(get3(i, &[0])[0], t_saved);
        let mut t = t_saved;
        for row in &first {
            assert_eq!(step3(i, t, h), status::OK);
            t = get3(i, &[0])[0];
            assert_eq!(&get3(i, &vrs), row, "after restoring the saved state");
        }
        let mut size = 0usize;
        assert_eq!(
            fmi3SerializedFMUStateSize(i, saved, &mut size),
            status::ERROR,
            "serialization is not offered (canSerializeFMUState = false)"
        );
        assert_eq!(fmi3FreeFMUState(i, &mut saved), status::OK);

        // FMI 2.0 from a file: URI, the same model, the same bits as FMI 3.0.
        let guid = CString::new(file_token(&text)).unwrap();
        let uri = CString::new(format!("file://{}", dir.display())).unwrap();
        let c = fmi2Instantiate(
            c"two".as_ptr(),
            1,
            guid.as_ptr(),
            uri.as_ptr(),
            std::ptr::null(),
            0,
            0,
        );
        assert!(!c.is_null(), "FMI 2.0 instantiates from the file: URI");
        let j = instantiate3(&file_token(&text), &dir);
        assert_eq!(fmi2SetupExperiment(c, 0, 0.0, 0.0, 0, 0.0), status::OK);
        assert_eq!(fmi2EnterInitializationMode(c), status::OK);
        assert_eq!(fmi2ExitInitializationMode(c), status::OK);
        assert_eq!(
            fmi3EnterInitializationMode(j, false, 0.0, 0.0, false, 0.0),
            status::OK
        );
        assert_eq!(fmi3ExitInitializationMode(j), status::OK);
        let mut t = 0.0;
        for k in 0..50 {
            assert_eq!(fmi2DoStep(c, t, h, 1), status::OK, "fmi2 step {k}");
            assert_eq!(step3(j, t, h), status::OK);
            let mut two = vec![0.0; vrs.len()];
            assert_eq!(
                fmi2GetReal(c, vrs.as_ptr(), vrs.len(), two.as_mut_ptr()),
                status::OK
            );
            assert_eq!(two, get3(j, &vrs), "FMI 2.0 and 3.0 at step {k}");
            t = get3(j, &[0])[0];
        }
        fmi2FreeInstance(c);
        fmi3FreeInstance(j);
        fmi3FreeInstance(i);
    }
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn a_wrong_token_a_bad_value_and_a_large_model_are_refused() {
    let file = xtask::model::read(&model_path()).unwrap();
    let text = file.to_text();
    let dir = resources("refusals", &text);
    // A token that is neither the planar FMUs' nor this resource's.
    assert!(instantiate3("{00000000-0000-5000-0000-000000000000}", &dir).is_null());
    let i = instantiate3(&file_token(&text), &dir);
    assert!(!i.is_null());
    assert_eq!(set3(i, 1, -1.0), status::OK, "set before initialization");
    // SAFETY: a live instance.
    unsafe {
        assert_eq!(
            fmi3EnterInitializationMode(i, false, 0.0, 0.0, false, 0.0),
            status::OK
        );
        assert_eq!(
            fmi3ExitInitializationMode(i),
            status::ERROR,
            "internal_step = -1"
        );
        assert_eq!(
            set3(i, FORCE_BASE + 1, f64::NAN),
            status::ERROR,
            "a NaN force"
        );
        assert_eq!(set3(i, POSITION_BASE, 1.0), status::ERROR, "an output");
        assert_eq!(set3(i, 999, 1.0), status::ERROR, "an unknown reference");
        fmi3FreeInstance(i);
    }
    std::fs::remove_dir_all(dir).unwrap();

    let two_disk = Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/models/two_disk.toml");
    let e = xtask::model::read(&two_disk).unwrap_err();
    assert!(
        e.contains("8 degrees of freedom") && e.contains("at most 4"),
        "{e}"
    );
}

#[test]
fn the_model_description_names_the_model_s_dofs() {
    use rotor_rub_fmu::description::Version;
    let file = xtask::model::read(&model_path()).unwrap();
    let text = file.to_text();
    let x3 = file_model_description(Version::Fmi3, &file, &text);
    let token = file_token(&text);
    assert!(x3.contains(&format!(r#"instantiationToken="{token}""#)));
    for name in [
        "x",
        "ys",
        "vxs",
        "f_y",
        "rub_x",
        "rub_y",
        "in_contact",
        "contact_count",
    ] {
        assert!(x3.contains(&format!(r#"name="{name}""#)), "{name} in\n{x3}");
    }
    assert!(
        x3.contains(r#"<Float64 name="f_x" valueReference="300""#),
        "{x3}"
    );
    let x2 = file_model_description(Version::Fmi2, &file, &text);
    assert!(x2.contains(&format!(r#"guid="{token}""#)));
    assert!(!x2.contains(r#"name="time""#));
}

#[test]
fn resource_locations_of_both_fmi_versions_are_read() {
    use rotor_rub_fmu::file::description::resource_dir;
    for (given, want) in [
        ("/tmp/a b/resources/", "/tmp/a b/resources/"),
        ("file:///tmp/a%20b/resources", "/tmp/a b/resources"),
        ("file://localhost/tmp/r", "/tmp/r"),
        ("file:/tmp/r/", "/tmp/r/"),
    ] {
        assert_eq!(resource_dir(given), PathBuf::from(want), "{given}");
    }
}
