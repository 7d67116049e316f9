//! Tests of the problem parsers, with a proptest fuzz of `--set` and the TOML config parser:
//! never a panic, always a value or a message.

use proptest::prelude::*;
use rotor_rub::Parameter;

use super::*;

#[test]
fn set_parses_and_rejects() {
    assert_eq!(parse_set("k_xx=2"), Ok((Parameter::KXx, 2.0)));
    assert!(parse_set("k_xx").unwrap_err().contains("NAME=VALUE"));
    assert!(
        parse_set("start_time=1")
            .unwrap_err()
            .contains("unknown parameter")
    );
    assert!(parse_set("phase=abc").unwrap_err().contains("phase"));
}

#[test]
fn config_errors_name_the_line_of_their_key() {
    let message = |text: &str| parse_config(text).unwrap_err();
    assert!(
        message("# c\nspeed_ratio = 2\n\nomega = 1\n").starts_with("line 4: unknown parameter")
    );
    assert!(message("k_xx = 1\n\"k_yy\" = 'x'\n").starts_with("line 2: k_yy must be a number"));
    assert!(message("preset = 'nope'\n").starts_with("line 1: unknown preset"));
    assert!(message("[table]\nx = 1\n").starts_with("unknown parameter 'table'"));
}

#[test]
fn parameter_indices_match_table_order() {
    for (i, p) in Parameter::ALL.into_iter().enumerate() {
        assert_eq!(p as usize, i);
    }
}

#[test]
fn config_parses_every_settable_parameter() {
    let text: String = settable()
        .enumerate()
        .map(|(i, p)| format!("{} = {}\n", p.name(), i as f64 * 0.5))
        .collect::<String>()
        + "preset = \"paper-text\"\n";
    let config = parse_config(&text).unwrap();
    assert_eq!(config.preset, Some(Preset::PaperText));
    let mut values = config.values;
    values.sort_by_key(|&(p, _)| p as usize);
    let expected: Vec<_> = settable()
        .enumerate()
        .map(|(i, p)| (p, i as f64 * 0.5))
        .collect();
    assert_eq!(values, expected);
}

/// A directory, a device and an oversized file are refused before being read.
#[test]
fn config_reads_only_small_regular_files() {
    let dir = tempfile::tempdir().unwrap();
    assert!(
        read_capped(dir.path(), "config", "TOML")
            .unwrap_err()
            .contains("regular file")
    );
    #[cfg(unix)]
    assert!(
        read_capped(Path::new("/dev/zero"), "config", "TOML")
            .unwrap_err()
            .contains("regular file")
    );
    // A FIFO is refused without opening it (opening would block until a writer appears).
    #[cfg(unix)]
    {
        let fifo = dir.path().join("fifo.toml");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status();
        if made.is_ok_and(|s| s.success()) {
            assert!(
                read_capped(&fifo, "config", "TOML")
                    .unwrap_err()
                    .contains("regular file")
            );
        }
    }
    let big = dir.path().join("big.toml");
    std::fs::write(&big, vec![b'#'; MAX_CONFIG_BYTES as usize + 1]).unwrap();
    assert!(
        read_capped(&big, "config", "TOML")
            .unwrap_err()
            .contains("more than")
    );
    let exact = dir.path().join("exact.toml");
    std::fs::write(&exact, vec![b'#'; MAX_CONFIG_BYTES as usize]).unwrap();
    assert_eq!(
        read_capped(&exact, "config", "TOML").unwrap().len(),
        MAX_CONFIG_BYTES as usize
    );
    let binary = dir.path().join("binary.toml");
    std::fs::write(&binary, [0xff, 0xfe, 0x00]).unwrap();
    assert!(
        read_capped(&binary, "config", "TOML")
            .unwrap_err()
            .contains("UTF-8")
    );
}

/// Near-valid `--set` arguments: a real or mangled name, a separator, a number-like value.
fn near_valid_set() -> impl Strategy<Value = String> {
    let names = prop::sample::select(
        Parameter::ALL
            .iter()
            .map(|p| p.name().to_string())
            .chain(["".into(), "preset".into(), "speed_ratio ".into()])
            .collect::<Vec<_>>(),
    );
    let values = prop_oneof![
        any::<f64>().prop_map(|x| x.to_string()),
        "[-+]?[0-9]{0,400}(\\.[0-9]*)?([eE][-+]?[0-9]{0,5})?",
        Just("nan".to_string()),
        Just("-inf".to_string()),
        ".*",
    ];
    (names, "[=:]{0,2}", values).prop_map(|(n, sep, v)| format!("{n}{sep}{v}"))
}

/// Near-valid config texts: lines of `key = value` with TOML values of every kind.
fn near_valid_config() -> impl Strategy<Value = String> {
    let key = prop_oneof![
        prop::sample::select(Parameter::ALL.iter().map(|p| p.name()).collect::<Vec<_>>())
            .prop_map(str::to_string),
        Just("preset".to_string()),
        "[a-z_\"\\[\\]. ]{0,12}",
    ];
    let value = prop_oneof![
        any::<f64>().prop_map(|x| format!("{x:?}")),
        any::<i64>().prop_map(|x| x.to_string()),
        Just("\"paper\"".to_string()),
        Just("nan".to_string()),
        Just("-inf".to_string()),
        Just("[1, 2]".to_string()),
        Just("{ a = 1 }".to_string()),
        Just("1979-05-27".to_string()),
        ".{0,20}",
    ];
    prop::collection::vec((key, "[ =]{0,3}", value), 0..8).prop_map(|lines| {
        lines
            .into_iter()
            .map(|(k, sep, v)| format!("{k}{sep}{v}\n"))
            .collect()
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    #[test]
    fn set_parser_never_panics(arg in prop_oneof![near_valid_set(), ".*"]) {
        match parse_set(&arg) {
            Ok((p, _)) => prop_assert!(p != Parameter::StartTime),
            Err(m) => prop_assert!(!m.is_empty() && !m.contains('\n')),
        }
    }

    #[test]
    fn config_parser_never_panics(text in prop_oneof![near_valid_config(), ".*"]) {
        if let Err(m) = parse_config(&text) {
            prop_assert!(!m.is_empty());
        }
    }

    /// Every accepted value round-trips through the problem and is then validated against the
    /// table: accepted exactly when finite and within the parameter's range.
    #[test]
    fn accepted_values_validate_against_the_table(arg in near_valid_set()) {
        if let Ok((p, v)) = parse_set(&arg) {
            let args = ProblemArgs { set: vec![(p, v)], ..ProblemArgs::default() };
            // The ring's own entries away from their defaults need a ring mass (the default
            // problem has none: `ParamError::RingWithoutMass`).
            let ring = [
                Parameter::ContactStiffness,
                Parameter::StatorDamping,
                Parameter::Xs0,
                Parameter::Ys0,
                Parameter::Vxs0,
                Parameter::Vys0,
            ];
            let ring_without_mass = ring.contains(&p) && v != p.info().default;
            let valid = v.is_finite() && p.info().range.contains(v) && !ring_without_mass;
            prop_assert_eq!(args.build().is_ok(), valid, "{} = {}", p, v);
        }
    }
}
