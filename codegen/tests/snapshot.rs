//! The checked-in snapshot of the generated code must equal what the generator emits now, so
//! every formula change shows in review.

use std::path::Path;

#[test]
fn snapshot_matches_generator() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("snapshot/coefficients.rs");
    let fresh = rotor_rub_codegen::generate().source;
    if std::env::var_os("UPDATE_SNAPSHOT").is_some() {
        std::fs::write(&path, &fresh).expect("snapshot is writable");
        return;
    }
    let stored = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        stored == fresh,
        "codegen/snapshot/coefficients.rs is stale; refresh it with: UPDATE_SNAPSHOT=1 cargo test -p rotor-rub-codegen --test snapshot"
    );
}
