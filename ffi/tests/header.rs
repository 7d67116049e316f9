//! The checked-in C header `include/rotor_rub.h` is what cbindgen generates from the sources
//! now, with the `ROTOR_RUB_PARAMETER_*` indices generated from the parameter table.
//! `UPDATE_HEADER=1` rewrites it instead of comparing.

use std::path::Path;

use rotor_rub::Parameter;

/// `#define ROTOR_RUB_PARAMETER_<NAME> <index>` for every table entry, with its doc line.
fn parameter_indices() -> String {
    let mut text = String::from(
        "\n/* Parameter indices for rotor_rub_parameter_{info,get,set}, from the Rust parameter table. */\n",
    );
    for (i, p) in Parameter::ALL.into_iter().enumerate() {
        let info = p.info();
        text.push_str(&format!(
            "/* {} ({}): {}; valid range {}. */\n#define ROTOR_RUB_PARAMETER_{} {i}\n",
            info.name,
            info.symbol,
            info.doc,
            info.range,
            info.name.to_uppercase()
        ));
    }
    text
}

fn generated() -> Vec<u8> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let config = cbindgen::Config::from_file(dir.join("cbindgen.toml")).expect("ffi/cbindgen.toml");
    let bindings = cbindgen::Builder::new()
        .with_config(config)
        .with_src(dir.join("src/lib.rs"))
        .with_src(dir.join("src/types.rs"))
        .with_after_include(parameter_indices())
        .generate()
        .expect("cbindgen generates the header");
    let mut out = Vec::new();
    bindings.write(&mut out);
    out
}

#[test]
fn header_is_up_to_date() {
    let generated = generated();
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("include/rotor_rub.h");
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

/// Every function returning an error code documents, in the header, the codes it can return,
/// and each code it names exists.
#[test]
fn every_function_documents_its_error_codes() {
    let text = String::from_utf8(generated()).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    let defined: Vec<&str> = lines
        .iter()
        .filter_map(|l| l.strip_prefix("#define "))
        .filter_map(|l| l.split_whitespace().next())
        .collect();
    let mut checked = 0;
    for (i, line) in lines.iter().enumerate() {
        if !(line.starts_with("int32_t rotor_rub_")) {
            continue;
        }
        let doc: Vec<&str> = lines[..i]
            .iter()
            .rev()
            .take_while(|l| l.starts_with("//"))
            .copied()
            .collect();
        let doc = doc.join(" ");
        assert!(doc.contains("Returns `ROTOR_RUB_OK`"), "{line}: {doc}");
        for code in doc
            .split(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
            .filter(|w| w.starts_with("ROTOR_RUB_ERR_"))
        {
            assert!(defined.contains(&code), "{line}: unknown code {code}");
        }
        checked += 1;
    }
    assert_eq!(checked, 16, "functions returning an error code");
}

/// The C struct `RotorRubParams` has one `double` per model parameter of the table, named as the
/// table names it and in the table's order (the conversions go through the table's order): a
/// missing, extra or reordered field fails here.
#[test]
fn the_c_parameter_struct_follows_the_table() {
    let header =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("include/rotor_rub.h"))
            .unwrap();
    let start = header.find("typedef struct RotorRubParams {").unwrap();
    let end = start + header[start..].find("} RotorRubParams;").unwrap();
    let fields: Vec<&str> = header[start..end]
        .lines()
        .filter_map(|l| l.trim().strip_prefix("double "))
        .map(|f| f.trim_end_matches(';'))
        .collect();
    let table: Vec<&str> = Parameter::ALL[..Parameter::MODEL_COUNT]
        .iter()
        .map(|p| p.info().name)
        .collect();
    assert_eq!(fields, table);
}
