//! Compile one of `examples/*.c` with the system C compiler (`$CC`, default `cc`; C99, all
//! warnings as errors) against the static library and run it.

use std::path::{Path, PathBuf};
use std::process::Command;

/// The static library cargo built next to the test binary.
fn staticlib() -> PathBuf {
    let exe = std::env::current_exe().expect("test binary path");
    let deps = exe.parent().expect("deps folder");
    let name = "librotor_rub_ffi.a";
    [
        deps.join(name),
        deps.parent().map(|p| p.join(name)).unwrap_or_default(),
    ]
    .into_iter()
    .find(|p| p.is_file())
    .unwrap_or_else(|| panic!("{name} not found next to {}", exe.display()))
}

/// Build `examples/<example>.c` as the executable `binary` (in the test's temporary folder)
/// and run it with `args`: its standard output.
pub fn compile_and_run(example: &str, binary: &str, args: &[&str]) -> String {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join(binary);
    let cc = std::env::var("CC").unwrap_or_else(|_| "cc".into());
    let mut cmd = Command::new(&cc);
    cmd.args(["-O2", "-std=c99", "-Wall", "-Werror", "-I"])
        .arg(dir.join("include"))
        .arg(dir.join(format!("examples/{example}.c")))
        .arg(staticlib())
        .arg("-o")
        .arg(&out);
    // The native libraries Rust's std needs in a static link.
    if cfg!(target_os = "macos") {
        cmd.args(["-lSystem", "-lc", "-lm"]);
    } else {
        cmd.args([
            "-lgcc_s",
            "-lutil",
            "-lrt",
            "-lpthread",
            "-lm",
            "-ldl",
            "-lc",
        ]);
    }
    let built = cmd
        .output()
        .unwrap_or_else(|e| panic!("cannot run `{cc}`: {e}"));
    assert!(
        built.status.success(),
        "compiling {example}.c failed:\n{}",
        String::from_utf8_lossy(&built.stderr)
    );
    let ran = Command::new(&out)
        .args(args)
        .output()
        .unwrap_or_else(|e| panic!("cannot run {example}: {e}"));
    assert!(
        ran.status.success(),
        "{example} failed:\n{}",
        String::from_utf8_lossy(&ran.stderr)
    );
    String::from_utf8(ran.stdout).expect("utf-8 output")
}
