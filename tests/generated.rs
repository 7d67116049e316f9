//! Calibration (temporary).
#[path = "generated/support.rs"]
mod support;

use proptest::prelude::*;
use support::*;

proptest! {
    #![proptest_config(config(256))]
    #[test]
    fn calib(case in any_case(), dx in -0.3..0.3f64, dy in -0.3..0.3f64, vx in -2.0..2.0f64, vy in -2.0..2.0f64, a in any_cubic()) {
        let p = case.params();
        let lin = rotor_rub::analytic::linear::Linearization::new(&p, case.t0, case.x0, case.y0);
        prop_assume!(lin.is_ok());
        let st = rotor_rub::State::new(case.x0+dx, case.y0+dy, vx, vy);
        let c0 = check_contact_segment(&case, st, [0.0;8], 1.0);
        let c1 = check_contact_segment(&case, st, a, 1.0);
        let f = check_free_segment(&case, st);
        eprintln!("CAL {:e} {:e} {:e} {:e} {:e} | {:e} {:e} {:e} {:e} {:e} | {:e} {:e} {:e} {:e} {:e}",
          c0.initial, c0.residual_forcing, c0.residual_terms, c0.velocity, c0.expm,
          c1.initial, c1.residual_forcing, c1.residual_terms, c1.velocity, c1.expm,
          f.initial, f.residual_forcing, f.residual_terms, f.velocity, f.expm);
    }
}
