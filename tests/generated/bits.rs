//! Before/after check of trajectories (ignored: a measurement, not a test). Writes the bits of
//! every event and sample of dop853, hybrid and analytic on the presets at several speed ratios
//! to `$ROTOR_RUB_BITS_OUT`; with `$ROTOR_RUB_BITS_BASE` set, compares against that file and
//! prints the largest differences per method (in ulps of the value and absolute).
//!
//! ```text
//! ROTOR_RUB_BITS_OUT=/tmp/before.txt cargo test --test generated bits -- --ignored --nocapture
//! # change the code, then
//! ROTOR_RUB_BITS_OUT=/tmp/after.txt ROTOR_RUB_BITS_BASE=/tmp/before.txt cargo test ...
//! ```

use std::collections::BTreeMap;
use std::fmt::Write as _;

use rotor_rub::{Method, Options, Preset, Propagator, advance_to};

fn record(method: Method) -> Vec<(String, f64)> {
    let mut out = Vec::new();
    for preset in Preset::PLANAR {
        for eta in [1.0, 1.5, 2.0, 3.0] {
            let mut problem = preset.problem();
            problem.params.speed_ratio = eta;
            let Ok(mut p) = Propagator::new(&problem, &Options::with_method(method)) else {
                continue;
            };
            let key = format!("{}/{:?}/{eta}", preset.name(), method);
            let mut n_event = 0;
            for k in 1..=400 {
                let t = 0.5 * f64::from(k);
                let r = advance_to(&mut p, t, |e| {
                    n_event += 1;
                    out.push((format!("{key}/event{n_event}/t"), e.time));
                    for (i, v) in e.state.to_array().iter().enumerate() {
                        out.push((format!("{key}/event{n_event}/{i}"), *v));
                    }
                });
                let Ok(s) = r else { break };
                for (i, v) in s.state.to_array().iter().enumerate() {
                    out.push((format!("{key}/sample{k}/{i}"), *v));
                }
            }
        }
    }
    out
}

#[test]
#[ignore = "measurement: run by hand around a change that may move last bits"]
fn bits() {
    let Ok(path) = std::env::var("ROTOR_RUB_BITS_OUT") else {
        return;
    };
    let mut text = String::new();
    let mut now = BTreeMap::new();
    for method in [
        Method::Dop853,
        Method::Hybrid,
        Method::Analytic,
        Method::Rk45,
    ] {
        for (k, v) in record(method) {
            let _ = writeln!(text, "{k} {:016x}", v.to_bits());
            now.insert(k, v);
        }
    }
    std::fs::write(&path, text).expect("writable output");
    let Ok(base) = std::env::var("ROTOR_RUB_BITS_BASE") else {
        return;
    };
    let base = std::fs::read_to_string(base).expect("readable base");
    // Per method: (values compared, values differing, max |Δ|, max ulps, keys missing).
    let mut stats: BTreeMap<String, (usize, usize, f64, u64, usize)> = BTreeMap::new();
    for line in base.lines() {
        let (k, bits) = line.split_once(' ').expect("key bits");
        let old = f64::from_bits(u64::from_str_radix(bits, 16).expect("hex"));
        let method = k.split('/').nth(1).unwrap_or("?").to_owned();
        let e = stats.entry(method).or_default();
        let Some(&new) = now.get(k) else {
            e.4 += 1;
            continue;
        };
        e.0 += 1;
        if new.to_bits() != old.to_bits() {
            e.1 += 1;
            e.2 = e.2.max((new - old).abs());
            e.3 = e.3.max(new.to_bits().abs_diff(old.to_bits()));
        }
    }
    for (m, (n, diff, abs, ulps, missing)) in stats {
        println!(
            "{m}: {n} values, {diff} differ, max |Δ| = {abs:e}, max {ulps} ulps, {missing} missing"
        );
    }
}
