//! The `simulate` contract: headers, sample times and counts, full round-trip precision (checked
//! against the library run directly), event order, summary, precedence of the problem layers.

use std::fs;
use std::path::Path;

use rotor_rub::{
    Event, EventKind, Method, Options, Parameter, Preset, Propagate, Propagator, Regime, advance_to,
};

use crate::common::{bin, num, read_csv};
use crate::require;

const PERIODS: f64 = 6.0;
const COUNT: usize = 257;

/// The sample times of the contract: t_i = t_end·i/(N−1), the last exactly t_end.
fn contract_times(end: f64, count: usize) -> Vec<f64> {
    (0..count)
        .map(|i| {
            if i + 1 == count {
                end
            } else {
                end * i as f64 / (count - 1) as f64
            }
        })
        .collect()
}

fn run_simulate(dir: &Path, method: Method) -> String {
    let out = bin()
        .current_dir(dir)
        .args(["simulate", "--method", method.name(), "--periods", "6"])
        .args([
            "--events",
            "e.csv",
            "--samples",
            "s.csv",
            "--sample-count",
            "257",
        ])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

fn contract(method: Method) {
    let dir = tempfile::tempdir().unwrap();
    let stdout = run_simulate(dir.path(), method);

    let (eh, events) = read_csv(&dir.path().join("e.csv"));
    let (sh, samples) = read_csv(&dir.path().join("s.csv"));
    assert_eq!(eh, ["tau", "kind", "x", "y", "vx", "vy"]);
    // The original columns, in order, then `regime` (added with friction).
    assert_eq!(sh, ["tau", "x", "y", "vx", "vy", "contact", "regime"]);
    assert_eq!(samples.len(), COUNT);

    // The same run through the library, with the same sequence of calls.
    let problem = Preset::Paper.problem();
    let end = PERIODS * problem.params.forcing_period();
    let times = contract_times(end, COUNT);
    let mut propagator = Propagator::new(&problem, &Options::with_method(method)).unwrap();
    let initial = propagator.regime();
    let mut lib_events: Vec<Event> = Vec::new();
    for (row, &t) in samples.iter().zip(&times) {
        let s = advance_to(&mut propagator, t, |e| lib_events.push(*e)).unwrap();
        assert_eq!(num(&row[0]).to_bits(), t.to_bits(), "sample time");
        let parsed = [num(&row[1]), num(&row[2]), num(&row[3]), num(&row[4])];
        assert_eq!(
            parsed,
            s.state.to_array(),
            "sample at τ = {t} (bit for bit)"
        );
        assert_eq!(
            row[5],
            if s.regime == Regime::Contact {
                "1"
            } else {
                "0"
            }
        );
        assert_eq!(row[6], s.regime.name());
    }
    advance_to(&mut propagator, end, |e| lib_events.push(*e)).unwrap();
    assert_eq!(num(&samples[COUNT - 1][0]), end);

    assert_eq!(events.len(), lib_events.len(), "event count");
    assert!(
        !events.is_empty(),
        "the paper preset rubs within {PERIODS} periods"
    );
    let mut expected = if initial == Regime::Free {
        "enter"
    } else {
        "exit"
    };
    let mut last = 0.0;
    for (row, e) in events.iter().zip(&lib_events) {
        assert_eq!(row[1], expected, "kinds alternate");
        assert_eq!(row[1], e.kind.name());
        let tau = num(&row[0]);
        assert!(tau >= last, "events in time order");
        last = tau;
        assert_eq!(tau.to_bits(), e.time.to_bits());
        let parsed = [num(&row[2]), num(&row[3]), num(&row[4]), num(&row[5])];
        assert_eq!(parsed, e.state.to_array());
        expected = if e.kind == EventKind::Enter {
            "exit"
        } else {
            "enter"
        };
    }

    assert!(
        stdout.contains(&format!("switches: {}", events.len())),
        "{stdout}"
    );
    assert!(stdout.contains("contact fraction: "), "{stdout}");
    assert!(stdout.contains("final state: "), "{stdout}");
    assert!(stdout.contains("run time: "), "{stdout}");
}

#[test]
fn contract_dop853() {
    require!(Method::Dop853);
    contract(Method::Dop853);
}

#[test]
fn contract_analytic() {
    require!(Method::Analytic);
    contract(Method::Analytic);
}

#[test]
fn contract_rk45() {
    require!(Method::Rk45);
    contract(Method::Rk45);
}

#[test]
fn contract_hybrid() {
    require!(Method::Hybrid);
    contract(Method::Hybrid);
}

#[test]
fn t_end_and_defaults() {
    require!(Method::Dop853);
    let dir = tempfile::tempdir().unwrap();
    bin()
        .current_dir(dir.path())
        .args([
            "simulate",
            "--method",
            "dop853",
            "--t-end",
            "10",
            "--samples",
            "s.csv",
        ])
        .assert()
        .success();
    let (_, rows) = read_csv(&dir.path().join("s.csv"));
    assert_eq!(rows.len(), 1001, "default sample count");
    assert_eq!(rows[0][0], "0.0");
    assert_eq!(num(&rows[1000][0]), 10.0);
}

#[test]
fn precedence_preset_config_set() {
    require!(Method::Dop853);
    let dir = tempfile::tempdir().unwrap();
    fs::write(
        dir.path().join("c.toml"),
        "preset = \"paper-text\"\nspeed_ratio = 2\ndamping_ratio = 0.15\n",
    )
    .unwrap();
    let events = |name: &str, args: &[&str]| {
        bin()
            .current_dir(dir.path())
            .args([
                "simulate",
                "--method",
                "dop853",
                "--periods",
                "4",
                "--events",
                name,
            ])
            .args(args)
            .assert()
            .success();
        fs::read_to_string(dir.path().join(name)).unwrap()
    };
    let layered = events(
        "a.csv",
        &["--config", "c.toml", "--set", "speed_ratio=1.25"],
    );
    let direct = events(
        "b.csv",
        &[
            "--preset",
            "paper-text",
            "--set",
            "damping_ratio=0.15",
            "--set",
            "speed_ratio=1.25",
        ],
    );
    assert_eq!(layered, direct, "config over preset, --set over config");
    let flag = events("c.csv", &["--config", "c.toml", "--preset", "paper"]);
    let plain = events(
        "d.csv",
        &["--set", "speed_ratio=2", "--set", "damping_ratio=0.15"],
    );
    assert_eq!(flag, plain, "--preset over the config's preset");
}

#[test]
fn presets_list_every_value() {
    let out = bin().arg("presets").output().unwrap();
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    for preset in Preset::ALL {
        assert!(text.contains(preset.name()), "{text}");
        assert!(text.contains(preset.description()), "{text}");
    }
    for field in Parameter::ALL
        .iter()
        .filter(|f| **f != Parameter::StartTime)
    {
        assert_eq!(
            text.matches(&format!("  {} ", field.name())).count(),
            Preset::ALL.len()
        );
    }
}

/// `simulate --preset NAME` runs every preset: the planar ones with the rotor's columns, the
/// ring presets (`stator_mass_ratio` > 0) through the ring's matrix model with the ring's columns
/// after the rotor's and the ring's largest displacement in the summary; each rubs.
#[test]
fn simulate_runs_every_preset() {
    let dir = tempfile::tempdir().unwrap();
    for preset in Preset::ALL {
        let out = bin()
            .current_dir(dir.path())
            .args(["simulate", "--preset", preset.name(), "--periods", "10"])
            .args(["--method", "hybrid", "--events", "e.csv"])
            .output()
            .unwrap();
        let text = String::from_utf8_lossy(&out.stdout);
        assert!(
            out.status.success(),
            "{}: {}",
            preset.name(),
            String::from_utf8_lossy(&out.stderr)
        );
        let (header, rows) = read_csv(&dir.path().join("e.csv"));
        let rotor = ["tau", "kind", "x", "y", "vx", "vy"];
        assert_eq!(&header[..6], rotor, "{}", preset.name());
        assert!(
            rows.iter().any(|r| r[1] == "enter"),
            "{}: no contact",
            preset.name()
        );
        if preset.has_ring_mass() {
            assert_eq!(
                &header[6..],
                ["xs", "ys", "vxs", "vys"],
                "{}",
                preset.name()
            );
            let line = text
                .lines()
                .find(|l| l.starts_with("ring: largest displacement"))
                .unwrap_or_else(|| panic!("{}: {text}", preset.name()));
            let moved = num(line.split(" = ").nth(1).unwrap().split(' ').next().unwrap());
            assert!(moved > 0.1, "{}: {line}", preset.name());
        } else {
            assert_eq!(header.len(), 6, "{}", preset.name());
        }
    }
}

#[test]
fn help_explains_units_and_defaults() {
    let top = bin().arg("--help").output().unwrap();
    let top = String::from_utf8(top.stdout).unwrap();
    for piece in ["clearances", "τ = ω_n t", "η = Ω/ω_n", "fig2.svg"] {
        assert!(top.contains(piece), "{piece}: {top}");
    }
    for cmd in [
        "simulate", "compare", "sweep", "merge", "poincare", "spectrum", "presets",
    ] {
        let help = bin().args([cmd, "--help"]).output().unwrap();
        assert!(help.status.success(), "{cmd}");
        let help = String::from_utf8(help.stdout).unwrap();
        assert!(
            help.contains("τ = ω_n t") && help.contains("clearances"),
            "{cmd}: {help}"
        );
    }
    let sim = bin().args(["simulate", "--help"]).output().unwrap();
    let sim = String::from_utf8(sim.stdout).unwrap();
    for piece in [
        "[default: 20]",
        "[default: analytic]",
        "tau,kind,x,y,vx,vy",
        "clearances",
    ] {
        assert!(sim.contains(piece), "{piece}: {sim}");
    }
}
