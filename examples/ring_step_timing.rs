use rotor_rub::stepper::matrix::MatrixStepperConfig;
use rotor_rub::stepper::RingStepper;
use rotor_rub::{Parameter, Preset};
use rotor_rub::method::Method;
use std::time::Instant;
fn main() {
    for (name, eta_off) in [("heavy", false), ("sparse", true)] {
        for method in [Method::Taylor, Method::Hybrid] {
            let mut p = Preset::Paper.problem();
            for (q, v) in [(Parameter::StatorMassRatio, 1.0), (Parameter::ContactStiffness, 100.0), (Parameter::StatorDamping, 0.5)] { q.set(&mut p, v); }
            if eta_off { Parameter::OffsetX.set(&mut p, 0.0); Parameter::OffsetY.set(&mut p, 0.0); }
            let cfg = MatrixStepperConfig { method, ..MatrixStepperConfig::with_dt(1e-3) };
            let mut s = RingStepper::new(&p, cfg).unwrap();
            let n = 50_000;
            let mut worst = 0.0f64; let mut sw = 0;
            let t0 = Instant::now();
            for _ in 0..n { let a = Instant::now(); let r = s.step(1e-3).unwrap(); sw += r.events.total(); worst = worst.max(a.elapsed().as_secs_f64()); }
            let mean = t0.elapsed().as_secs_f64() / n as f64;
            println!("{name} {method:?}: mean {:.2} us/step, worst {:.1} us, {sw} switches, size {} B", mean*1e6, worst*1e6, std::mem::size_of::<RingStepper>());
        }
    }
}
