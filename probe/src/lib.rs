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

/// Runs the paper preset up from η = 0.8 to 1.2 at dη/dτ = 1e-3 and back (a ramp's points held
/// on the stack, no heap) with `method_code` (0 analytic, 1 hybrid, 2 dop853), one row per
/// forcing period; returns the number of switches, or −1 on error.
#[unsafe(no_mangle)]
pub extern "C" fn rotor_rub_probe_runup(method_code: u32) -> i64 {
    use rotor_rub::Method;
    use rotor_rub::speed::{Ramp, RampPace};
    use rotor_rub::variable_speed::{Revolutions, VariableSpeedOptions, VariableSpeedPropagator};
    let method = match method_code {
        0 => Method::Analytic,
        1 => Method::Hybrid,
        _ => Method::Dop853,
    };
    let problem = Preset::Paper.problem();
    let ramp = Ramp {
        start_time: 0.0,
        from: 0.8,
        to: 1.2,
        pace: RampPace::Rate(1e-3),
        settle_periods: 0.0,
        dwell_periods: 0.0,
        one_way: false,
    };
    let Ok(points) = ramp.points() else {
        return -1;
    };
    let Ok(profile) = points.profile() else {
        return -1;
    };
    let options = VariableSpeedOptions::new(Options::with_method(method));
    let Ok(mut p) = VariableSpeedPropagator::new(&problem, profile, &options) else {
        return -1;
    };
    let mut switches = 0i64;
    for row in Revolutions::new(&mut p, profile, problem.params.phase, 64) {
        match row {
            Ok(r) => switches += i64::from(r.enters + r.exits),
            Err(_) => return -1,
        }
    }
    switches
}
