//! Runs the symbolic generator: derives every coefficient formula and writes the runtime's
//! `coefficients.rs` into `OUT_DIR` (only when its bytes change).

use std::path::PathBuf;

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rerun-if-changed=codegen/src");
    // The parameter table: the generator reads it too (`codegen/src/model/parameters.rs`).
    println!("cargo:rerun-if-changed=runtime/params/entries.rs");
    let out = PathBuf::from(std::env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    let generated = rotor_rub_codegen::generate();
    rotor_rub_codegen::write_if_changed(&out.join("coefficients.rs"), &generated.source)
        .expect("OUT_DIR is writable");
}
