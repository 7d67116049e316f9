//! Project tasks. `cargo xtask fmu` builds the FMI co-simulation FMUs of the model:
//!
//! ```text
//! cargo xtask fmu            # portable release build → target/fmu/rotor_rub_fmi3.fmu, rotor_rub_fmi2.fmu,
//!                            #   rotor_rub_si_fmi3.fmu, rotor_rub_si_fmi2.fmu
//! cargo xtask fmu --debug    # the same from a debug build (faster to build, slower to run)
//! cargo xtask fmu --host     # with the host's toolchain instead of cargo-zigbuild (not portable)
//! cargo xtask fmu --model examples/models/FILE.toml
//!                            # the FMU built for a model file (n ≤ 4 DOFs; TOML or .npz) →
//!                            #   target/fmu/rotor_rub_<name>_fmi3.fmu, rotor_rub_<name>_fmi2.fmu
//! ```
//!
//! With `--model FILE` the file is read by the CLI's reader (`rotor_rub_cli::model_file`),
//! checked as `rotor-rub check-model` checks it, stated at its running speed and written in SI
//! into the archive's `resources/rotor_rub_model.txt` (`rotor_rub_fmu::file`); the same binary
//! reads it at instantiation. A model of more than 4 degrees of freedom is refused.
//!
//! Each archive holds `modelDescription.xml` (written by `rotor_rub_fmu::description` from the
//! variable table, itself read off the parameter table), `documentation/index.html`
//! (`rotor_rub_fmu::documentation`) and the one binary that serves both FMI versions and both
//! unit systems (`rotor-rub-fmu`'s cdylib; `binary.rs` builds it portable and stripped), under
//! the host platform's FMI folder name (`binaries/x86_64-linux/` for FMI 3.0,
//! `binaries/linux64/` for FMI 2.0 on x86_64 Linux). Other hosts get their own folder names; a
//! host without an FMI 2.0 name gets the FMI 3.0 FMUs only. The archive is a plain (stored)
//! zip file written here, so the task needs no crate beyond the workspace.

mod binary;
mod zip;

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use rotor_rub_fmu::description::{MODEL_IDENTIFIER, Version, model_description, model_name};
use rotor_rub_fmu::documentation::index_html;
use rotor_rub_fmu::file::description::{file_model_description, file_model_name};
use rotor_rub_fmu::file::{FileModel, RESOURCE};
use rotor_rub_fmu::units::Units;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let flag = |f: &str| args.iter().any(|a| a == f);
    // `--model FILE`: the FMU built for a model file.
    let model_at = args.iter().position(|a| a == "--model");
    let model_path = model_at.and_then(|k| args.get(k + 1)).map(PathBuf::from);
    let known = args.iter().enumerate().skip(1).all(|(k, a)| {
        a == "--debug" || a == "--host" || a == "--model" || model_at.is_some_and(|m| k == m + 1)
    }) && (model_at.is_none() || model_path.is_some());
    let model = match model_path.as_deref().map(xtask::model::read) {
        Some(Err(e)) => {
            eprintln!("cargo xtask fmu --model: {e}");
            return ExitCode::from(2);
        }
        Some(Ok(m)) => Some(m),
        None => None,
    };
    match args.first().map(String::as_str) {
        Some("fmu") if known => match fmu(flag("--debug"), flag("--host"), model.as_ref()) {
            Ok(paths) => {
                for p in paths {
                    println!("{}", p.display());
                }
                ExitCode::SUCCESS
            }
            Err(e) => {
                eprintln!("cargo xtask fmu: {e}");
                ExitCode::FAILURE
            }
        },
        _ => {
            eprintln!(
                "usage: cargo xtask fmu [--debug] [--host] [--model FILE]   (builds target/fmu/rotor_rub{{,_si}}_fmi{{3,2}}.fmu, or with --model FILE (n <= 4 DOFs) target/fmu/rotor_rub_<name>_fmi{{3,2}}.fmu)"
            );
            ExitCode::from(2)
        }
    }
}

/// The host's FMI platform folder names (FMI 2.0, FMI 3.0) and the shared library's extension.
fn platform() -> Result<(Option<&'static str>, &'static str, &'static str), String> {
    let (os, arch) = (std::env::consts::OS, std::env::consts::ARCH);
    let ext = match os {
        "linux" => "so",
        "macos" => "dylib",
        "windows" => "dll",
        other => return Err(format!("no FMI platform name for the OS {other}")),
    };
    let fmi3 = match (arch, os) {
        ("x86_64", "linux") => "x86_64-linux",
        ("aarch64", "linux") => "aarch64-linux",
        ("x86_64", "macos") => "x86_64-darwin",
        ("aarch64", "macos") => "aarch64-darwin",
        ("x86_64", "windows") => "x86_64-windows",
        ("x86", "windows") => "x86-windows",
        (a, o) => return Err(format!("no FMI 3.0 platform name for {a}-{o}")),
    };
    let fmi2 = match (arch, os) {
        ("x86_64", "linux") => Some("linux64"),
        ("x86_64", "macos") => Some("darwin64"),
        ("x86_64", "windows") => Some("win64"),
        ("x86", "windows") => Some("win32"),
        _ => None,
    };
    Ok((fmi2, fmi3, ext))
}

fn fmu(debug: bool, host: bool, model: Option<&FileModel>) -> Result<Vec<PathBuf>, String> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .ok_or("no workspace root")?
        .to_path_buf();
    let target = std::env::var_os("CARGO_TARGET_DIR")
        .map(|t| root.join(t))
        .unwrap_or_else(|| root.join("target"));
    let (fmi2, fmi3, ext) = platform()?;
    let lib_name = match ext {
        "dll" => format!("{MODEL_IDENTIFIER}.dll"),
        _ => format!("lib{MODEL_IDENTIFIER}.{ext}"),
    };
    let built = binary::build(&root, &target, &lib_name, debug, host)?;
    let binary =
        std::fs::read(&built.path).map_err(|e| format!("{}: {e}", built.path.display()))?;
    let out_dir = target.join("fmu");
    std::fs::create_dir_all(&out_dir).map_err(|e| format!("{}: {e}", out_dir.display()))?;
    let mut written = Vec::new();
    if let Some(model) = model {
        let resource = model.to_text();
        let name = file_model_name(model);
        for (version, platform, suffix) in [
            (Version::Fmi3, Some(fmi3), "fmi3"),
            (Version::Fmi2, fmi2, "fmi2"),
        ] {
            let file = format!("{name}_{suffix}.fmu");
            let Some(platform) = platform else {
                eprintln!("no FMI 2.0 platform name for this host: {file} not built");
                continue;
            };
            let entries = [
                (
                    "modelDescription.xml".to_owned(),
                    file_model_description(version, model, &resource).into_bytes(),
                ),
                (
                    format!("binaries/{platform}/{MODEL_IDENTIFIER}.{ext}"),
                    binary.clone(),
                ),
                (
                    format!("resources/{RESOURCE}"),
                    resource.clone().into_bytes(),
                ),
            ];
            written.push(write_fmu(&out_dir, &file, &entries)?);
        }
        eprintln!("cargo xtask fmu: {} ({} bytes)", built.note, binary.len());
        return Ok(written);
    }
    for units in [Units::Dimensionless, Units::Si] {
        let versions = [
            (Version::Fmi3, Some(fmi3), "fmi3"),
            (Version::Fmi2, fmi2, "fmi2"),
        ];
        for (version, platform, suffix) in versions {
            let file = format!("{}_{suffix}.fmu", model_name(units));
            let Some(platform) = platform else {
                eprintln!("no FMI 2.0 platform name for this host: {file} not built");
                continue;
            };
            let entries = [
                (
                    "modelDescription.xml".to_owned(),
                    model_description(version, units).into_bytes(),
                ),
                (
                    format!("binaries/{platform}/{MODEL_IDENTIFIER}.{ext}"),
                    binary.clone(),
                ),
                (
                    "documentation/index.html".to_owned(),
                    index_html(units).into_bytes(),
                ),
            ];
            written.push(write_fmu(&out_dir, &file, &entries)?);
        }
    }
    eprintln!("cargo xtask fmu: {} ({} bytes)", built.note, binary.len());
    Ok(written)
}

/// Write the archive `file` of `entries` into `out_dir`, whole or not at all.
fn write_fmu(out_dir: &Path, file: &str, entries: &[(String, Vec<u8>)]) -> Result<PathBuf, String> {
    let path = out_dir.join(file);
    let tmp = out_dir.join(format!(".{file}.tmp"));
    std::fs::write(&tmp, zip::stored(entries)).map_err(|e| format!("{}: {e}", tmp.display()))?;
    std::fs::rename(&tmp, &path).map_err(|e| format!("{}: {e}", path.display()))?;
    Ok(path)
}
