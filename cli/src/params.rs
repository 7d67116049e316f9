//! `rotor-rub params`: every parameter of the table with its symbol, default, valid range and
//! meaning.

use rotor_rub::params::Number;

use crate::error::Result;
use crate::problem::settable;
use crate::stdio;

/// The listing, one line per parameter (also what `run` prints).
pub fn listing() -> String {
    let mut out = format!(
        "{:<20} {:<6} {:>9}  {:<18} meaning\n",
        "name", "symbol", "default", "valid range"
    );
    for parameter in settable() {
        let info = parameter.info();
        out.push_str(&format!(
            "{:<20} {:<6} {:>9}  {:<18} {}\n",
            info.name,
            info.symbol,
            Number(info.default).to_string(),
            info.range.to_string(),
            info.doc
        ));
    }
    out.push_str(
        "\nSet values with --set NAME=VALUE or a TOML --config; out-of-range values exit with code 2.\n",
    );
    out
}

/// Print the listing.
pub fn run() -> Result<()> {
    stdio::out(&listing())
}

#[cfg(test)]
mod tests {
    use rotor_rub::Parameter;

    use super::*;

    #[test]
    fn lists_every_settable_parameter_with_its_range() {
        let text = listing();
        for p in settable() {
            let info = p.info();
            let line = text
                .lines()
                .find(|l| l.starts_with(&format!("{} ", info.name)))
                .unwrap_or_else(|| panic!("{} missing from {text}", info.name));
            assert!(line.contains(&info.range.to_string()), "{line}");
            assert!(line.contains(info.doc), "{line}");
        }
        assert!(!text.contains(Parameter::StartTime.name()));
    }
}
