//! Calibration (temporary).
#[path = "generated/support.rs"]
mod support;

use proptest::prelude::*;
use support::*;

proptest! {
    #![proptest_config(config(1024))]
    #[test]
    fn calib(case in any_case(), dx in -0.3..0.3f64, dy in -0.3..0.3f64, vx in -2.0..2.0f64, vy in -2.0..2.0f64, a in any_cubic()) {
        let p = case.params();
        let lin = rotor_rub::analytic::linear::Linearization::new(&p, case.t0, case.x0, case.y0);
        prop_assume!(lin.is_ok());
        let st = rotor_rub::State::new(case.x0+dx, case.y0+dy, vx, vy);
        let c0 = check_contact_segment(&case, st, [0.0;8], 1.0);
        let c1 = check_contact_segment(&case, st, a, 1.0);
        let f = check_free_segment(&case, st);
        if c1.initial > 1e-13*c1.cancellation || c1.expm > 1e-12*c1.cancellation || c1.residual_forcing > 1e-10*c1.cancellation || c0.residual_forcing > 1e-10 {
            let k = case.linearized();
            let m = rotor_rub::coefficients::contact_modes(k.fa1,k.fb1,k.fb2,k.fa2,case.nu);
            let b = rotor_rub::coefficients::polynomial_particular(k.fa1,k.fb1,k.fb2,k.fa2,case.nu,a[0],a[1],a[2],a[3],a[4],a[5],a[6],a[7]);
            eprintln!("BAD {c1:?}\n  {case:?}\n  {k:?}\n  {m:?}\n  {b:?}");
        }
        eprintln!("CAL {:e} {:e} {:e} {:e} {:e} | {:e} {:e} {:e} {:e} {:e} | {:e} {:e} {:e} {:e} {:e}",
          c0.initial, c0.residual_forcing, c0.residual_terms, c0.velocity, c0.expm,
          c1.initial/c1.cancellation, c1.residual_forcing/c1.cancellation, c1.residual_terms/c1.cancellation, c1.velocity/c1.cancellation, c1.expm/c1.cancellation,
          f.initial, f.residual_forcing, f.residual_terms, f.velocity, f.expm);
    }
}
