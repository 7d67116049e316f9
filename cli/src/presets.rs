//! `rotor-rub presets`: every preset with every value.

use std::fmt::Write as _;

use rotor_rub::Preset;
use rotor_rub::params::Number;

use crate::error::Result;
use crate::problem::settable;
use crate::stdio;

/// The listing: each preset, its description and every value (also what `run` prints).
pub fn listing() -> String {
    let mut out = String::new();
    for (i, preset) in Preset::ALL.into_iter().enumerate() {
        if i > 0 {
            out.push('\n');
        }
        let _ = writeln!(out, "{}: {}", preset.name(), preset.description());
        let problem = preset.problem();
        for parameter in settable() {
            let info = parameter.info();
            let _ = writeln!(
                out,
                "  {:<20} = {:<8}  {} {}; valid range {}",
                info.name,
                Number(parameter.get(&problem)).to_string(),
                info.symbol,
                info.doc,
                info.range
            );
        }
    }
    out
}

/// Print the listing.
pub fn run() -> Result<()> {
    stdio::out(&listing())
}
