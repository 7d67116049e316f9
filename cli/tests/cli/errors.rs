//! Bad input: exit code 2, one line on stderr naming the parameter and the rule, no output file
//! created or changed. Propagation failures: exit code 1, one line, no output file.

use std::fs;
use std::path::Path;

use rotor_rub::Method;

use crate::common::{bin, listing};
use crate::require;

/// Run `args` in `dir` and check the failure: exit `code`, one `error:` line on stderr holding
/// every `expected` piece, nothing on stdout, no new file in `dir`.
fn fails_in(dir: &Path, args: &[&str], code: i32, expected: &[&str]) {
    let before = listing(dir);
    let out = bin().current_dir(dir).args(args).output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(code), "{args:?}: stderr {stderr}");
    assert_eq!(
        stderr.lines().count(),
        1,
        "{args:?}: not one line: {stderr}"
    );
    assert!(stderr.starts_with("error: "), "{args:?}: {stderr}");
    for piece in expected {
        assert!(
            stderr.contains(piece),
            "{args:?}: '{piece}' missing from: {stderr}"
        );
    }
    assert!(
        out.stdout.is_empty(),
        "{args:?}: stdout {:?}",
        String::from_utf8_lossy(&out.stdout)
    );
    assert_eq!(listing(dir), before, "{args:?}: files changed");
}

fn fails(args: &[&str], expected: &[&str]) {
    let dir = tempfile::tempdir().unwrap();
    let mut all = args.to_vec();
    if args[0] == "simulate" && !args.contains(&"--samples") {
        all.extend(["--events", "e.csv", "--samples", "s.csv"]);
    }
    fails_in(dir.path(), &all, 2, expected);
}

#[test]
fn non_numeric_values() {
    fails(
        &["simulate", "--set", "speed_ratio=abc"],
        &["speed_ratio", "not a number"],
    );
    fails(&["simulate", "--tol", "small"], &["--tol", "not a number"]);
    fails(&["simulate", "--step", "x"], &["--step", "not a number"]);
    fails(
        &["simulate", "--periods", "many"],
        &["--periods", "not a number"],
    );
    fails(&["sweep", "--from", "one"], &["--from", "not a number"]);
}

#[test]
fn out_of_range_values_use_the_library_rule() {
    fails(
        &["simulate", "--set", "speed_ratio=-1"],
        &["speed_ratio", "must be in [0.001, 100]", "--set"],
    );
    fails(
        &["simulate", "--set", "damping_ratio=-0.5"],
        &["damping_ratio", "must be in [0, 10]"],
    );
    fails(
        &["simulate", "--set", "k_xx=1e7"],
        &["k_xx", "1e7", "must be in [0, 100000]"],
    );
    fails(
        &["simulate", "--set", "x0=nan"],
        &["x0", "not a finite number"],
    );
    fails(
        &[
            "sweep",
            "--param",
            "damping_ratio",
            "--from",
            "-1",
            "--to",
            "1",
            "--steps",
            "3",
        ],
        &["damping_ratio", "-1", "must be in [0, 10]"],
    );
}

/// Issue 13 point 8: values outside the physical ranges exit 2 naming value and range, where
/// they used to fail in propagation (exit 1) or report a false divergence.
#[test]
fn physical_ranges_are_enforced() {
    fails(
        &["simulate", "--set", "speed_ratio=5e-324"],
        &["speed_ratio", "5e-324", "must be in [0.001, 100]"],
    );
    for x0 in ["1e4", "-1e5", "1e6"] {
        fails(
            &["simulate", "--set", &format!("x0={x0}")],
            &["x0", "must be in [-100, 100]"],
        );
    }
    fails(
        &["simulate", "--set", "y0=1e300"],
        &["y0 = 1e300 is out of range"],
    );
    fails(
        &["simulate", "--set", "mass_ratio=0"],
        &["mass_ratio", "must be in (0, 1]"],
    );
}

/// `rotor-rub params` lists every parameter with its default, range and meaning.
#[test]
fn params_lists_the_table() {
    let out = bin().arg("params").output().unwrap();
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    for p in rotor_rub::Parameter::ALL {
        if p == rotor_rub::Parameter::StartTime {
            continue;
        }
        let info = p.info();
        let line = text
            .lines()
            .find(|l| l.starts_with(&format!("{} ", info.name)))
            .unwrap_or_else(|| panic!("{} missing: {text}", info.name));
        assert!(line.contains(&info.range.to_string()), "{line}");
        assert!(line.contains(info.doc), "{line}");
    }
    assert!(
        text.contains("out-of-range values exit with code 2"),
        "{text}"
    );
}

#[test]
fn unknown_names() {
    fails(
        &["simulate", "--set", "omega=2"],
        &["omega", "unknown parameter", "speed_ratio"],
    );
    fails(
        &["simulate", "--set", "start_time=2"],
        &["start_time", "unknown parameter"],
    );
    fails(
        &["simulate", "--set", "speed_ratio"],
        &["--set", "NAME=VALUE"],
    );
    fails(
        &["sweep", "--param", "omega"],
        &["--param", "omega", "unknown parameter"],
    );
    fails(
        &["simulate", "--preset", "nope"],
        &["--preset", "nope", "paper-text"],
    );
    fails(
        &["simulate", "--method", "euler"],
        &["--method", "euler", "dop853"],
    );
    fails(
        &["compare", "--reference", "analytic"],
        &["--reference", "dop853 or rk45"],
    );
    fails(
        &["simulate", "--contact-scheme", "rk4"],
        &["--contact-scheme", "exprb43"],
    );
}

#[test]
fn bad_method_settings() {
    fails(&["simulate", "--tol", "0"], &["--tol", "> 0"]);
    fails(&["simulate", "--tol", "-1e-3"], &["--tol", "> 0"]);
    fails(&["simulate", "--tol", "inf"], &["--tol", "finite"]);
    fails(&["simulate", "--step", "-0.01"], &["--step", "> 0"]);
    fails(
        &["simulate", "--samples", "s.csv", "--sample-count", "1"],
        &["--sample-count", ">= 2"],
    );
    fails(
        &["simulate", "--t-end", "5", "--periods", "2"],
        &["--t-end", "--periods"],
    );
    fails(
        &["fig2", "--plot-from", "10", "--plot-to", "5"],
        &["--plot-to", "--plot-from"],
    );
}

#[test]
fn bad_shard_specs() {
    for spec in ["2/2", "a/b", "1", "0/0", "-1/2"] {
        fails(&["sweep", "--shard", spec], &["--shard", "I/N"]);
    }
}

#[test]
fn bad_config_files() {
    let dir = tempfile::tempdir().unwrap();
    let write = |name: &str, text: &str| {
        let p = dir.path().join(name);
        fs::write(&p, text).unwrap();
        p.to_string_lossy().into_owned()
    };
    let missing = dir
        .path()
        .join("missing.toml")
        .to_string_lossy()
        .into_owned();
    fails(
        &["simulate", "--config", &missing],
        &["--config", "cannot read"],
    );
    let syntax = write("syntax.toml", "speed_ratio = = 2\n");
    fails(
        &["simulate", "--config", &syntax],
        &["--config", "not valid TOML", "line 1"],
    );
    let unknown = write("unknown.toml", "omega = 2\n");
    fails(
        &["simulate", "--config", &unknown],
        &["omega", "unknown parameter"],
    );
    let text = write("text.toml", "speed_ratio = \"fast\"\n");
    fails(
        &["simulate", "--config", &text],
        &["speed_ratio", "must be a number"],
    );
    let range = write("range.toml", "speed_ratio = -2\n");
    fails(
        &["simulate", "--config", &range],
        &["speed_ratio", "must be in [0.001, 100]", "--config"],
    );
    // Issue 13 point 7: devices, directories and oversized files are refused before reading.
    #[cfg(unix)]
    fails(
        &["simulate", "--config", "/dev/zero"],
        &["/dev/zero", "not a regular file"],
    );
    let folder = dir.path().to_string_lossy().into_owned();
    fails(&["simulate", "--config", &folder], &["not a regular file"]);
    let big = write("big.toml", &"#".repeat((1 << 20) + 1));
    fails(
        &["simulate", "--config", &big],
        &["big.toml", "1048577 bytes", "more than the 1048576"],
    );
    let preset = write("preset.toml", "preset = \"nope\"\n");
    fails(
        &["simulate", "--config", &preset],
        &["nope", "unknown preset"],
    );
}

#[test]
fn set_overrides_an_invalid_config_value() {
    let dir = tempfile::tempdir().unwrap();
    let config = dir.path().join("c.toml");
    fs::write(&config, "speed_ratio = -2\n").unwrap();
    let out = bin()
        .args(["simulate", "--periods", "1", "--config"])
        .arg(&config)
        .args(["--set", "speed_ratio=2"])
        .output()
        .unwrap();
    assert!(!String::from_utf8_lossy(&out.stderr).contains("speed_ratio"));
}

/// A shard file with a valid metadata line (FNV-1a 64 over `body`) around any body.
fn shard_file(body: &str) -> String {
    let sum = body.bytes().fold(0xcbf2_9ce4_8422_2325_u64, |h, b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    });
    let rows = body.lines().count() - 1;
    format!("# rotor-rub sweep shard 0/1; rows {rows}; fnv1a64 {sum:016x}; run test\n{body}")
}

#[test]
fn bad_merge_inputs() {
    let dir = tempfile::tempdir().unwrap();
    fs::write(dir.path().join("plain.csv"), "a,b\n1,2\n").unwrap();
    fs::write(dir.path().join("bad.csv"), shard_file("a,b\n1,2\n")).unwrap();
    fs::write(
        dir.path().join("text.csv"),
        shard_file("value,period,x,y,vx,vy\n1,2,3,four,5,6\n"),
    )
    .unwrap();
    fails_in(
        dir.path(),
        &["merge", "m.csv", "plain.csv"],
        2,
        &["plain.csv", "metadata"],
    );
    fails_in(
        dir.path(),
        &["merge", "m.csv", "bad.csv"],
        2,
        &["bad.csv", "header"],
    );
    fails_in(
        dir.path(),
        &["merge", "m.csv", "text.csv"],
        2,
        &["text.csv", "y", "four"],
    );
    fails_in(
        dir.path(),
        &["merge", "m.csv", "none.csv"],
        2,
        &["none.csv"],
    );
}

#[test]
fn existing_files_are_untouched_by_bad_input() {
    let dir = tempfile::tempdir().unwrap();
    for name in ["e.csv", "s.csv", "sweep.csv"] {
        fs::write(dir.path().join(name), "keep me\n").unwrap();
    }
    let args = [
        "simulate",
        "--set",
        "k_yy=-1",
        "--events",
        "e.csv",
        "--samples",
        "s.csv",
    ];
    fails_in(dir.path(), &args, 2, &["k_yy", "must be in [0, 100000]"]);
    fails_in(
        dir.path(),
        &["sweep", "--tol", "0", "--out", "sweep.csv"],
        2,
        &["--tol"],
    );
    for name in ["e.csv", "s.csv", "sweep.csv"] {
        assert_eq!(
            fs::read_to_string(dir.path().join(name)).unwrap(),
            "keep me\n"
        );
    }
}

#[test]
fn divergence_fails_without_partial_files() {
    require!(Method::Dop853);
    let dir = tempfile::tempdir().unwrap();
    fs::write(dir.path().join("e.csv"), "keep me\n").unwrap();
    // A strongly circulatory stator (docs/MODEL.md §6 case 3): the rotor stays in contact and the
    // motion grows without bound.
    let args = [
        "simulate",
        "--method",
        "dop853",
        "--set",
        "k_xy=15",
        "--set",
        "k_yx=-10",
        "--periods",
        "40",
        "--events",
        "e.csv",
        "--samples",
        "s.csv",
    ];
    fails_in(dir.path(), &args, 1, &["diverged"]);
    assert_eq!(
        fs::read_to_string(dir.path().join("e.csv")).unwrap(),
        "keep me\n"
    );
}

#[test]
fn analytic_only_flags_with_another_method() {
    fails(
        &[
            "simulate",
            "--method",
            "dop853",
            "--contact-scheme",
            "exprb2",
        ],
        &["--contact-scheme", "only to --method analytic", "dop853"],
    );
    fails(
        &["simulate", "--method", "hybrid", "--step", "0.01"],
        &["--step", "only to --method analytic", "hybrid"],
    );
}
