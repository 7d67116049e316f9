//! Building the FMU's shared library. On Linux the default is a portable binary: built with
//! cargo-zigbuild against glibc 2.17 (zig links against that version's symbol set, so the
//! library loads on manylinux2014-era rig PCs as well as on new systems) and stripped (no
//! symbol table, no debug info: ~0.7 MB instead of 6.6 MB). cargo-zigbuild and zig come from
//! PyPI (`fmu/requirements-build.txt`); when they are not found this task installs them into
//! a virtual environment of its own under the target directory. `--host` builds with the host's
//! toolchain instead (the binary then needs the host's glibc or newer).

use std::path::{Path, PathBuf};
use std::process::Command;

/// The oldest glibc the portable Linux binary loads on.
pub const GLIBC: &str = "2.17";

/// Where the library was built, and how.
pub struct Built {
    /// The shared library.
    pub path: PathBuf,
    /// What the build guarantees, for the task's output.
    pub note: String,
}

/// Build the shared library `lib_name` (release unless `debug`; portable unless `host`).
pub fn build(
    root: &Path,
    target: &Path,
    lib_name: &str,
    debug: bool,
    host: bool,
) -> Result<Built, String> {
    let arch = std::env::consts::ARCH;
    let portable = !host && std::env::consts::OS == "linux" && matches!(arch, "x86_64" | "aarch64");
    let profile = if debug { "debug" } else { "release" };
    let mut args: Vec<String> = ["build", "-p", "rotor-rub-fmu", "--lib"]
        .map(String::from)
        .to_vec();
    if !debug {
        args.push("--release".into());
        // Stripped: no symbol table and no debug info (the workspace's release profile keeps
        // line tables for the benches; the FMU ships without them).
        args.extend(
            [
                "--config",
                "profile.release.debug=false",
                "--config",
                "profile.release.strip=\"symbols\"",
            ]
            .map(String::from),
        );
    }
    if !portable {
        let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
        run(Command::new(cargo).current_dir(root).args(&args))?;
        return Ok(Built {
            path: target.join(profile).join(lib_name),
            note: "host toolchain: needs the build machine's C library or newer".into(),
        });
    }
    let triple = format!("{arch}-unknown-linux-gnu");
    let (zigbuild, bin) = zigbuild(root, target)?;
    args[0] = "zigbuild".into();
    args.extend(["--target".into(), format!("{triple}.{GLIBC}")]);
    let path = std::env::var_os("PATH").unwrap_or_default();
    let mut paths = vec![bin];
    paths.extend(std::env::split_paths(&path));
    let path = std::env::join_paths(paths).map_err(|e| format!("PATH: {e}"))?;
    run(Command::new(&zigbuild)
        .current_dir(root)
        .env("PATH", path)
        .args(&args))?;
    Ok(Built {
        path: target.join(&triple).join(profile).join(lib_name),
        note: format!("portable: glibc >= {GLIBC}, built with cargo-zigbuild"),
    })
}

fn run(command: &mut Command) -> Result<(), String> {
    let status = command
        .status()
        .map_err(|e| format!("cannot run {:?}: {e}", command.get_program()))?;
    if status.success() {
        Ok(())
    } else {
        Err(format!("{:?} failed ({status})", command.get_program()))
    }
}

/// cargo-zigbuild and the folder whose `python3 -m ziglang` (or `zig`) it uses: from PATH, the
/// project's virtual environment, or one this task makes under the target directory.
fn zigbuild(root: &Path, target: &Path) -> Result<(PathBuf, PathBuf), String> {
    let tools = target.join("fmu-tools");
    let mut dirs: Vec<PathBuf> = std::env::var_os("PATH")
        .map(|p| std::env::split_paths(&p).collect())
        .unwrap_or_default();
    if let Some(venv) = std::env::var_os("ROTOR_RUB_VENV") {
        dirs.push(root.join(venv).join("bin"));
    }
    dirs.extend([root.join(".venv/bin"), tools.join("bin")]);
    if let Some(dir) = dirs.iter().find(|d| d.join("cargo-zigbuild").is_file()) {
        return Ok((dir.join("cargo-zigbuild"), dir.clone()));
    }
    eprintln!(
        "cargo xtask fmu: installing cargo-zigbuild and zig from PyPI into {} (fmu/requirements-build.txt)",
        tools.display()
    );
    let python = std::env::var("PYTHON").unwrap_or_else(|_| "python3".into());
    run(Command::new(python).args(["-m", "venv"]).arg(&tools))
        .map_err(|e| format!("{e}: a portable build needs python3 (or build with --host)"))?;
    run(Command::new(tools.join("bin/python"))
        .args([
            "-m",
            "pip",
            "install",
            "-q",
            "--disable-pip-version-check",
            "-r",
        ])
        .arg(root.join("fmu/requirements-build.txt")))
    .map_err(|e| format!("{e}: installing cargo-zigbuild failed (or build with --host)"))?;
    Ok((tools.join("bin/cargo-zigbuild"), tools.join("bin")))
}
