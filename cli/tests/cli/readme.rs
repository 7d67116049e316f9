//! The README's `simulate` commands run as written (issue 28 item 7: "the presets run from the
//! README"): every line `cargo run --release -- simulate …` of README.md, with the binary in
//! place of `cargo run --release --`, from a scratch directory holding `out/`, exits 0; and each
//! ring preset is run by one of them.

use std::path::Path;

use rotor_rub::Preset;

use crate::common::bin;

/// The README's `simulate` command lines, as argument lists (after `cargo run --release --`,
/// a trailing `# comment` dropped).
fn simulate_commands() -> Vec<Vec<String>> {
    let readme = Path::new(env!("CARGO_MANIFEST_DIR")).join("../README.md");
    let text = std::fs::read_to_string(&readme).unwrap();
    text.lines()
        .filter_map(|line| line.trim().strip_prefix("cargo run --release -- "))
        .map(|rest| rest.split(" #").next().unwrap_or(rest))
        .map(|rest| {
            rest.split_whitespace()
                .map(str::to_owned)
                .collect::<Vec<_>>()
        })
        .filter(|args| args.first().is_some_and(|c| c == "simulate"))
        .collect()
}

#[test]
fn the_readme_simulate_commands_run() {
    let commands = simulate_commands();
    assert!(commands.len() >= 5, "{commands:?}");
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("out")).unwrap();
    for args in &commands {
        let out = bin().current_dir(dir.path()).args(args).output().unwrap();
        assert!(
            out.status.success(),
            "README: rotor-rub {}: {}",
            args.join(" "),
            String::from_utf8_lossy(&out.stderr)
        );
        let summary = String::from_utf8_lossy(&out.stdout);
        assert!(
            summary.contains("switches:"),
            "{}: {summary}",
            args.join(" ")
        );
    }
    // The ring presets' commands write what the README says they write.
    let header = std::fs::read_to_string(dir.path().join("out/ring-e.csv")).unwrap();
    assert!(
        header.starts_with("tau,kind,x,y,vx,vy,xs,ys,vxs,vys\n"),
        "{header}"
    );
    for preset in Preset::RING {
        assert!(
            commands.iter().any(|a| a
                .windows(2)
                .any(|w| w[0] == "--preset" && w[1] == preset.name())),
            "the README runs no `simulate --preset {}`",
            preset.name()
        );
    }
}
