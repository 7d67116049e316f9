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
