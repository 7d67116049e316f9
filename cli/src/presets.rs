//! `rotor-rub presets`: every preset with every value.

use rotor_rub::Preset;
use rotor_rub::params::Number;

use crate::problem::settable;

/// List the presets.
pub fn run() {
    for (i, preset) in Preset::ALL.into_iter().enumerate() {
        if i > 0 {
            println!();
        }
        println!("{}: {}", preset.name(), preset.description());
        let problem = preset.problem();
        for parameter in settable() {
            let info = parameter.info();
            println!(
                "  {:<20} = {:<8}  {} {}; valid range {}",
                info.name,
                Number(parameter.get(&problem)).to_string(),
                info.symbol,
                info.doc,
                info.range
            );
        }
    }
}
