//! `rotor-rub presets`: every preset with every value.

use rotor_rub::Preset;

use crate::problem::{meaning, settable_fields};

/// List the presets.
pub fn run() {
    for (i, preset) in Preset::ALL.into_iter().enumerate() {
        if i > 0 {
            println!();
        }
        println!("{}: {}", preset.name(), preset.description());
        let problem = preset.problem();
        for field in settable_fields() {
            println!(
                "  {:<20} = {:<8}  {}; {}",
                field.name(),
                field.get(&problem),
                meaning(field),
                field.rule()
            );
        }
    }
}
