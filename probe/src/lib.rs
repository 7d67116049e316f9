//! no_std probe: propagates the paper preset through the public API without `std` or `alloc`.
#![no_std]

use core::panic::PanicInfo;

use rotor_rub::{Options, Preset, Propagate, Propagator};

#[panic_handler]
fn panic(_: &PanicInfo) -> ! {
    loop {}
}

/// Propagates the paper preset for `periods` forcing periods; returns the number of switches,
/// or −1 on error.
#[unsafe(no_mangle)]
pub extern "C" fn rotor_rub_probe(periods: f64) -> i64 {
    let problem = Preset::Paper.problem();
    let Ok(mut p) = Propagator::new(&problem, &Options::default()) else {
        return -1;
    };
    let end = periods * problem.params.forcing_period();
    let mut switches = 0;
    loop {
        match p.advance(end) {
            Ok(Some(_)) => switches += 1,
            Ok(None) => return switches,
            Err(_) => return -1,
        }
    }
}

/// Steps the paper preset through the fixed-step stepper for `steps` steps of 1e-3; returns the
/// number of switches, or −1 on error.
#[unsafe(no_mangle)]
pub extern "C" fn rotor_rub_probe_stepper(steps: u32) -> i64 {
    let problem = Preset::Paper.problem();
    let Ok(mut stepper) = rotor_rub::Stepper::new(&problem, rotor_rub::StepperConfig::default())
    else {
        return -1;
    };
    let mut switches = 0i64;
    for _ in 0..steps {
        match stepper.step(1e-3) {
            Ok(report) => switches += report.events.total() as i64,
            Err(_) => return -1,
        }
    }
    switches
}
