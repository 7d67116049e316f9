//! The checked-in C header `include/rotor_rub.h` is what cbindgen generates from the sources
//! now. `UPDATE_HEADER=1` rewrites it instead of comparing.

use std::path::Path;

#[test]
fn header_is_up_to_date() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let config = cbindgen::Config::from_file(dir.join("cbindgen.toml")).expect("ffi/cbindgen.toml");
    let bindings = cbindgen::Builder::new()
        .with_config(config)
        .with_src(dir.join("src/lib.rs"))
        .with_src(dir.join("src/types.rs"))
        .generate()
        .expect("cbindgen generates the header");
    let mut generated = Vec::new();
    bindings.write(&mut generated);
    let path = dir.join("include/rotor_rub.h");
    if std::env::var_os("UPDATE_HEADER").is_some_and(|v| v != "0") {
        std::fs::write(&path, &generated).expect("write ffi/include/rotor_rub.h");
        return;
    }
    let current = std::fs::read(&path).unwrap_or_default();
    assert!(
        current == generated,
        "ffi/include/rotor_rub.h is stale: refresh it with `UPDATE_HEADER=1 cargo test -p rotor-rub-ffi --test header`"
    );
}
