//! Model files (docs/MODEL_FILES.md, issue 29 item 1): the example files, units, every error
//! path naming its key (and its line in TOML), the `check-model` and `simulate --model`
//! commands' exits, and the parser never panicking on any input.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use proptest::prelude::*;
use rotor_rub::linalg::Complex;
use rotor_rub_cli::model_file::{
    Array, Key, ModelSpec, end_time, from_npz, from_toml, load, read_npz, state_columns,
};

fn example(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../examples/models")
        .join(name)
}

fn bin() -> assert_cmd::Command {
    assert_cmd::cargo::cargo_bin_cmd!("rotor-rub")
}

/// A small valid model: two DOFs (a Jeffcott rotor in SI), a fixed stator.
const JEFFCOTT: &str = r#"
format = 1
units = "SI"
dofs = ["x", "y"]
speed = 100.0
[matrices]
mass = [[2.0, 0.0], [0.0, 2.0]]
damping = [[4.0, 0.0], [0.0, 4.0]]
stiffness = [[20000.0, 0.0], [0.0, 20000.0]]
[[unbalance]]
dof_x = "x"
dof_y = "y"
m_e = 1e-4
phase = 0.0
[rub]
dof_x = "x"
dof_y = "y"
clearance = 1e-3
contact_stiffness = 1e6
"#;

fn jeffcott() -> ModelSpec {
    from_toml(JEFFCOTT, None).expect("the Jeffcott model reads")
}

/// `JEFFCOTT` with `line` (a whole `key = value` line of the document) replaced.
fn with(old: &str, new: &str) -> String {
    assert!(JEFFCOTT.contains(old), "{old} is not in the model");
    JEFFCOTT.replacen(old, new, 1)
}

fn error_of(text: &str) -> String {
    match from_toml(text, None).and_then(|s| s.build().map(|_| ()).map_err(|e| e.to_string())) {
        Ok(()) => panic!("the model was accepted:\n{text}"),
        Err(e) => e,
    }
}

#[test]
fn the_examples_read_check_and_agree() {
    let toml = load(&example("two_disk.toml")).expect("two_disk.toml");
    let npz = load(&example("two_disk.npz")).expect("two_disk.npz");
    assert_eq!(toml.dofs(), 8);
    assert_eq!(toml.dofs, npz.dofs);
    for (a, b) in [
        (&toml.mass, &npz.mass),
        (&toml.damping, &npz.damping),
        (&toml.gyroscopic, &npz.gyroscopic),
        (&toml.stiffness, &npz.stiffness),
    ] {
        assert_eq!((a.rows, a.cols), (b.rows, b.cols));
        for (x, y) in a.data.iter().zip(&b.data) {
            assert!((x - y).abs() <= 1e-9 * x.abs().max(1.0), "{x} vs {y}");
        }
    }
    assert_eq!(toml.rub, npz.rub);
    assert_eq!(toml.unbalances, npz.unbalances);
    assert_eq!(toml.speed, npz.speed);
    toml.build().expect("two_disk.toml states a model");
    let modes = toml.eigenvalues().expect("its modes");
    assert_eq!(modes.len(), 16);
    // The first critical speed the file's comment names: 303 rad/s.
    let first = modes.first().copied().unwrap_or(Complex::ZERO);
    assert!((first.im.abs() - 302.75).abs() < 0.01, "{first:?}");
}

#[test]
fn the_model_is_stated_in_clearances() {
    let spec = jeffcott();
    let model = spec.build().expect("builds");
    // Unbalance m·e (kg·m) becomes m·e/δ; the forcing acceleration η² F/M in clearances.
    let u = model.unbalance();
    let amount = u.iter().map(|c| c.re.hypot(c.im)).fold(0.0, f64::max);
    assert!((amount - 1e-4 / 1e-3).abs() < 1e-12, "{u:?}");
    // The speed and time stay as given: eigenvalues of x'' + 2x' + 1e4 x = 0.
    let modes = spec.eigenvalues().expect("modes");
    for m in &modes {
        assert!((m.re + 1.0).abs() < 1e-9 && (m.im.abs() - (1e4f64 - 1.0).sqrt()).abs() < 1e-9);
    }
    // The start: metres become clearances.
    let mut spec = spec;
    spec.initial = Some((vec![5e-4, -2e-4], vec![0.1, 0.0]));
    let start = spec.start().expect("start");
    assert_eq!(start.positions(), &[0.5, -0.2]);
    assert_eq!(start.velocities(), &[100.0, 0.0]);
    // The clearance scales the model, not the modes: doubling δ halves the unbalance.
    spec.rub.clearance = 2e-3;
    let model2 = spec.build().expect("builds");
    let u2 = model2.unbalance();
    let amount2 = u2.iter().map(|c| c.re.hypot(c.im)).fold(0.0, f64::max);
    assert!((2.0 * amount2 - amount).abs() < 1e-12);
    assert_eq!(spec.eigenvalues().expect("modes"), modes);
}

#[test]
fn columns_and_end_times() {
    let spec = jeffcott();
    assert_eq!(
        state_columns(&spec),
        ["x", "y", "vx", "vy", "rub_x", "rub_y"]
    );
    let tau = std::f64::consts::TAU;
    assert_eq!(end_time(&spec, None, Some(3.0)), Ok(3.0 * tau / 100.0));
    assert_eq!(end_time(&spec, None, None), Ok(20.0 * tau / 100.0));
    assert_eq!(end_time(&spec, Some(0.5), None), Ok(0.5));
    assert!(end_time(&spec, Some(1.0), Some(1.0)).is_err());
    let e = end_time(&spec, Some(-1.0), None).expect_err("negative");
    assert!(e.contains("t_end = -1") && e.contains("> 0"), "{e}");
}

#[test]
fn every_value_is_checked_and_named() {
    // (replace, by, what the message must say)
    let cases: &[(&str, &str, &[&str])] = &[
        ("format = 1", "format = 2", &["format = 2", "format = 1"]),
        ("units = \"SI\"", "units = \"mm\"", &["units", "SI"]),
        (
            "speed = 100.0",
            "speed = -5.0",
            &["speed = -5", "rad/s", "line 5"],
        ),
        (
            "speed = 100.0",
            "speed = \"fast\"",
            &["speed", "must be a number"],
        ),
        ("speed = 100.0", "", &["speed", "missing"]),
        (
            "mass = [[2.0, 0.0], [0.0, 2.0]]",
            "mass = [[2.0, 0.0], [0.0]]",
            &["matrices.mass", "line 7"],
        ),
        (
            "mass = [[2.0, 0.0], [0.0, 2.0]]",
            "mass = [[2.0, 1.0], [0.0, 2.0]]",
            &["matrices.mass", "symmetric"],
        ),
        (
            "mass = [[2.0, 0.0], [0.0, 2.0]]",
            "mass = [[2.0, 0.0], [0.0, -2.0]]",
            &["matrices.mass", "positive definite"],
        ),
        (
            "damping = [[4.0, 0.0], [0.0, 4.0]]",
            "damping = [[4.0, 0.0, 1.0], [0.0, 4.0, 1.0]]",
            &["matrices.damping", "2 × 3", "2 × 2"],
        ),
        (
            "stiffness = [[20000.0, 0.0], [0.0, 20000.0]]",
            "",
            &["matrices.stiffness", "missing"],
        ),
        (
            "dof_x = \"x\"\ndof_y = \"y\"\nm_e",
            "dof_x = \"z\"\ndof_y = \"y\"\nm_e",
            &["unbalance[0].dof_x", "\"z\""],
        ),
        ("m_e = 1e-4", "m_e = -1e-4", &["unbalance[0].m_e", "≥ 0"]),
        (
            "clearance = 1e-3",
            "clearance = 0.0",
            &["rub.clearance = 0", "> 0", "(m)"],
        ),
        ("clearance = 1e-3", "", &["rub.clearance", "missing"]),
        (
            "contact_stiffness = 1e6",
            "contact_stiffness = [[1e6, 0.0], [0.0, -1e6]]",
            &["rub.contact_stiffness", "positive definite"],
        ),
        (
            "contact_stiffness = 1e6",
            "contact_stiffness = [1e6, 1e6]",
            &["rub.contact_stiffness"],
        ),
        (
            "contact_stiffness = 1e6",
            "contact_stiffness = 1e6\nfriction_coefficient = 0.2",
            &["rub.radius", "missing", "friction_coefficient = 0.2"],
        ),
        (
            "contact_stiffness = 1e6",
            "contact_stiffness = 1e6\nfriction_coefficient = -0.2",
            &["rub.friction_coefficient = -0.2"],
        ),
        (
            "contact_stiffness = 1e6",
            "contact_stiffness = 1e6\nstator = [\"x\", \"y\"]",
            &["rub.stator", "four different"],
        ),
        (
            "contact_stiffness = 1e6",
            "contact_stiffness = 1e6\nstator = [\"x\"]",
            &["rub.stator", "1 entries", "pair"],
        ),
        (
            "contact_stiffness = 1e6",
            "contact_stiffness = 1e6\noffset = [1.0, 0.0]",
            &["rub.offset", "clearances"],
        ),
        (
            "contact_stiffness = 1e6",
            "contact_stiffness = 1e6\nstiffnes = 3",
            &["stiffnes"],
        ),
        ("[rub]", "[rubs]", &["rubs"]),
        (
            "speed = 100.0",
            "speed = 100.0\n[initial]\npositions = [0.0]",
            &["initial.positions", "1 entries", "n = 2"],
        ),
    ];
    for (old, new, needles) in cases {
        let e = error_of(&with(old, new));
        for needle in *needles {
            assert!(
                e.contains(needle),
                "replacing {old:?} by {new:?}: {e:?} lacks {needle:?}"
            );
        }
    }
}

#[test]
fn speed_dependent_matrices_interpolate_and_check_their_speeds() {
    let text = format!(
        "{JEFFCOTT}\n[[speed_dependent]]\nspeed = 50.0\nstiffness = [[10000.0, 0.0], [0.0, 10000.0]]\n\
         [[speed_dependent]]\nspeed = 150.0\nstiffness = [[30000.0, 0.0], [0.0, 30000.0]]\n"
    );
    let spec = from_toml(&text, None).expect("reads");
    let (_, k) = spec.matrices_at(Key::Speed, 100.0).expect("inside");
    assert_eq!(k.get(0, 0), 20000.0);
    let (_, k) = spec.matrices_at(Key::Speed, 75.0).expect("inside");
    assert_eq!(k.get(1, 1), 15000.0);
    let e = spec.build_at(200.0).expect_err("outside").to_string();
    assert!(e.contains("speed = 200") && e.contains("[50, 150]"), "{e}");
    let down = text.replacen("speed = 150.0", "speed = 40.0", 1);
    let e = error_of(&down);
    assert!(
        e.contains("speed_dependent[1].speed = 40") && e.contains("increas"),
        "{e}"
    );
}

#[test]
fn npz_errors_name_the_array() {
    let good = read_npz(&std::fs::read(example("two_disk.npz")).expect("file")).expect("npz");
    from_npz(&good).expect("the example");
    let mut extra: BTreeMap<String, Array> = good.clone();
    extra.insert("bogus".into(), good.get("speed").cloned().expect("speed"));
    let e = from_npz(&extra).expect_err("unknown array");
    assert!(e.contains("'bogus'"), "{e}");
    let mut missing = good.clone();
    missing.remove("M");
    let e = from_npz(&missing).expect_err("no M");
    assert!(e.contains("'M'"), "{e}");
    for bytes in [&b""[..], b"PK\x03\x04garbage", b"\x93NUMPY"] {
        assert!(read_npz(bytes).is_err());
    }
}

#[test]
fn check_model_prints_the_model_and_exits_2_on_bad_files() {
    let out = bin()
        .args(["check-model"])
        .arg(example("two_disk.toml"))
        .output()
        .expect("runs");
    assert!(out.status.success(), "{out:?}");
    let text = String::from_utf8_lossy(&out.stdout);
    for needle in ["n = 8", "clearance: δ = 0.0002 m", "rub station", "302.75"] {
        assert!(text.contains(needle), "{text} lacks {needle}");
    }
    let dir = tempfile::tempdir().expect("tempdir");
    let bad = dir.path().join("bad.toml");
    std::fs::write(&bad, with("clearance = 1e-3", "clearance = -1e-3")).expect("write");
    let out = bin().arg("check-model").arg(&bad).output().expect("runs");
    assert_eq!(out.status.code(), Some(2), "{out:?}");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("bad.toml") && err.contains("rub.clearance = -0.001"),
        "{err}"
    );
    let out = bin()
        .arg("check-model")
        .arg(dir.path().join("absent.toml"))
        .output()
        .expect("runs");
    assert_eq!(out.status.code(), Some(2), "{out:?}");
    let out = bin()
        .args(["simulate", "--model"])
        .arg(&bad)
        .output()
        .expect("runs");
    assert_eq!(out.status.code(), Some(2), "{out:?}");
    let out = bin()
        .args(["simulate", "--preset", "paper", "--model"])
        .arg(example("two_disk.toml"))
        .output()
        .expect("runs");
    assert_eq!(
        out.status.code(),
        Some(2),
        "--model conflicts with --preset: {out:?}"
    );
}

#[test]
fn simulate_runs_model_files_and_the_ring() {
    let dir = tempfile::tempdir().expect("tempdir");
    let events = dir.path().join("ev.csv");
    let samples = dir.path().join("s.csv");
    let out = bin()
        .args([
            "simulate",
            "--periods",
            "5",
            "--method",
            "hybrid",
            "--model",
        ])
        .arg(example("two_disk.toml"))
        .arg("--events")
        .arg(&events)
        .arg("--samples")
        .arg(&samples)
        .args(["--sample-count", "11"])
        .output()
        .expect("runs");
    assert!(out.status.success(), "{out:?}");
    let text = std::fs::read_to_string(&events).expect("events");
    let mut lines = text.lines();
    assert_eq!(
        lines.next(),
        Some("t,kind,x1,y1,a1,b1,x2,y2,a2,b2,vx1,vy1,va1,vb1,vx2,vy2,va2,vb2,rub_x,rub_y")
    );
    // Every switch on the clearance circle (0.2 mm), in SI.
    let mut count = 0;
    for line in lines {
        let f: Vec<f64> = line
            .split(',')
            .skip(2)
            .map(|x| x.parse().expect("number"))
            .collect();
        let r = f[16].hypot(f[17]);
        assert!((r - 2e-4).abs() < 1e-15, "{line}");
        count += 1;
    }
    assert!(count > 0);
    let s = std::fs::read_to_string(&samples).expect("samples");
    assert_eq!(s.lines().count(), 12);
    assert!(
        s.lines()
            .next()
            .is_some_and(|h| h.ends_with("rub_x,rub_y,contact,regime"))
    );

    // The ring with mass: the rotor's columns, then the ring's.
    let ring = dir.path().join("ring.csv");
    let out = bin()
        .args([
            "simulate",
            "--set",
            "stator_mass_ratio=1",
            "--periods",
            "5",
            "--events",
        ])
        .arg(&ring)
        .output()
        .expect("runs");
    assert!(out.status.success(), "{out:?}");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains("ring: largest displacement"), "{stdout}");
    let text = std::fs::read_to_string(&ring).expect("ring events");
    assert_eq!(
        text.lines().next(),
        Some("tau,kind,x,y,vx,vy,xs,ys,vxs,vys")
    );
    assert!(text.lines().count() > 1);

    // m̂ = 0 is the paper's model, byte for byte.
    let a = dir.path().join("a.csv");
    let b = dir.path().join("b.csv");
    for (path, extra) in [(&a, None), (&b, Some("stator_mass_ratio=0"))] {
        let mut cmd = bin();
        cmd.args(["simulate", "--periods", "5", "--events"])
            .arg(path);
        if let Some(set) = extra {
            cmd.args(["--set", set]);
        }
        assert!(cmd.output().expect("runs").status.success());
    }
    assert_eq!(std::fs::read(&a).expect("a"), std::fs::read(&b).expect("b"));
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    /// Any text: an error or a model, never a panic.
    #[test]
    fn toml_never_panics(text in ".{0,400}") {
        let _ = from_toml(&text, None).map(|s| s.build().map(|_| ()));
    }

    /// The example with one value replaced by anything: an error naming something, or a model.
    #[test]
    fn edited_models_never_panic(line in 1usize..45, value in prop_oneof![
        Just("-1.0".to_string()), Just("nan".to_string()), Just("inf".to_string()),
        Just("0".to_string()), Just("\"q\"".to_string()), Just("[]".to_string()),
        Just("[[1.0]]".to_string()), Just("1e308".to_string()), Just("99".to_string()),
        any::<f64>().prop_map(|x| format!("{x:e}")),
    ]) {
        let lines: Vec<String> = JEFFCOTT.lines().enumerate().map(|(i, l)| {
            match l.split_once(" = ") {
                Some((k, _)) if i == line => format!("{k} = {value}"),
                _ => l.to_string(),
            }
        }).collect();
        let text = lines.join("\n");
        if let Ok(spec) = from_toml(&text, None) {
            let _ = spec.build();
            let _ = spec.eigenvalues();
        }
    }

    /// Any bytes as an .npz: an error or arrays, never a panic.
    #[test]
    fn npz_never_panics(bytes in proptest::collection::vec(any::<u8>(), 0..600)) {
        if let Ok(arrays) = read_npz(&bytes) {
            let _ = from_npz(&arrays);
        }
    }

    /// The example .npz with bytes flipped: never a panic.
    #[test]
    fn corrupted_npz_never_panics(flips in proptest::collection::vec((any::<usize>(), any::<u8>()), 1..8)) {
        let mut bytes = std::fs::read(example("two_disk.npz")).expect("file");
        let len = bytes.len();
        for (at, b) in flips {
            if let Some(x) = bytes.get_mut(at % len) { *x ^= b | 1; }
        }
        if let Ok(arrays) = read_npz(&bytes) {
            let _ = from_npz(&arrays).map(|s| s.build().map(|_| ()));
        }
    }
}
