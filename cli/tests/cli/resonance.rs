//! Issue 13's near-resonance example through the binary: hybrid free flight is exact and
//! resonance-stable, so its switches and final state match DOP853 at tol 1e-13.

use crate::common::bin;

/// The switch count and final state printed by `simulate` for `method` (and its tolerance).
fn simulate(method: &str, tol: Option<&str>) -> (usize, [f64; 4]) {
    let mut cmd = bin();
    cmd.args(["simulate", "--method", method, "--t-end", "30"])
        .args(["--set", "speed_ratio=1", "--set", "damping_ratio=1e-9"]);
    if let Some(tol) = tol {
        cmd.args(["--tol", tol]);
    }
    let out = cmd.output().unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let stdout = String::from_utf8(out.stdout).unwrap();
    let line = |prefix: &str| {
        stdout
            .lines()
            .find_map(|l| l.strip_prefix(prefix))
            .unwrap_or_else(|| panic!("no {prefix:?} in {stdout}"))
            .to_owned()
    };
    let switches = line("switches: ");
    let count = switches.split_whitespace().next().unwrap().parse().unwrap();
    let state = line("final state: ");
    let mut values = state
        .split(", ")
        .map(|kv| kv.split(" = ").nth(1).unwrap().split(' ').next().unwrap());
    let mut next = || values.next().unwrap().parse::<f64>().unwrap();
    (count, [next(), next(), next(), next()])
}

#[test]
fn hybrid_near_resonance_matches_dop853() {
    // Before: hybrid 6151 switches against 35.
    let (n_ref, s_ref) = simulate("dop853", Some("1e-13"));
    let (n, s) = simulate("hybrid", None);
    assert_eq!(n, n_ref, "switch count");
    for (a, b) in s.iter().zip(&s_ref) {
        assert!((a - b).abs() < 1e-7, "final state {s:?} vs {s_ref:?}");
    }
}

/// ν = 0 at η = 1 exactly is a valid problem (free flight grows secularly); the analytic
/// method's linearized contact at z = 1 is exactly resonant there and says so with a typed error.
#[test]
fn exact_resonance_is_accepted() {
    let args = ["simulate", "--t-end", "30", "--set", "damping_ratio=0"];
    let out = bin()
        .args(args)
        .args(["--set", "speed_ratio=1", "--method", "hybrid"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let out = bin()
        .args(args)
        .args(["--set", "speed_ratio=1", "--method", "analytic"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("singular or resonant"), "{stderr}");
}
