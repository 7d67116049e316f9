//! compare, poincare and spectrum: their files and headers.

use rotor_rub::Method;

use crate::common::{bin, num, read_csv};
use crate::require;

#[test]
fn compare_writes_table_and_plot() {
    require!(Method::Analytic, Method::Dop853);
    let dir = tempfile::tempdir().unwrap();
    let out = bin()
        .current_dir(dir.path())
        .args(["compare", "--periods", "4", "--out-dir", "cmp"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains("largest differences"), "{stdout}");
    let (header, rows) = read_csv(&dir.path().join("cmp/compare.csv"));
    assert_eq!(
        header,
        ["kind", "tau_analytic", "tau_reference", "dtau", "dstate"]
    );
    assert!(!rows.is_empty());
    for ext in ["svg", "png"] {
        assert!(dir.path().join(format!("cmp/compare.{ext}")).exists());
    }
}

#[test]
fn poincare_section_file() {
    require!(Method::Dop853);
    let dir = tempfile::tempdir().unwrap();
    bin()
        .current_dir(dir.path())
        .args([
            "poincare",
            "--method",
            "dop853",
            "--transient",
            "5",
            "--keep",
            "6",
        ])
        .args(["--out", "p.csv"])
        .assert()
        .success();
    let (header, rows) = read_csv(&dir.path().join("p.csv"));
    assert_eq!(header, ["period", "x", "y", "vx", "vy"]);
    let periods: Vec<&str> = rows.iter().map(|r| r[0].as_str()).collect();
    assert_eq!(periods, ["5", "6", "7", "8", "9", "10"]);
    assert!(dir.path().join("p.svg").exists() && dir.path().join("p.png").exists());
}

#[test]
fn spectrum_files_and_orders() {
    require!(Method::Dop853);
    let dir = tempfile::tempdir().unwrap();
    let run = |extra: &[&str], name: &str| {
        bin()
            .current_dir(dir.path())
            .args([
                "spectrum",
                "--method",
                "dop853",
                "--transient",
                "4",
                "--periods",
                "6",
            ])
            .args(["--samples-per-period", "16", "--out", name])
            .args(extra)
            .assert()
            .success();
        read_csv(&dir.path().join(name))
    };
    let (header, rows) = run(&[], "xy.csv");
    assert_eq!(header, ["order", "x", "y"]);
    assert_eq!(rows.len(), 6 * 16 / 2 + 1);
    assert_eq!(
        num(&rows[3][0]),
        0.5,
        "bin 3 of 6 periods is the ½× sub-harmonic"
    );
    let (header, rows) = run(&["--whirl"], "w.csv");
    assert_eq!(header, ["order", "whirl"]);
    assert_eq!(rows.len(), 6 * 16);
    assert!(num(&rows[0][0]) < 0.0, "backward whirl first");
    assert!(dir.path().join("w.svg").exists() && dir.path().join("xy.png").exists());
}
