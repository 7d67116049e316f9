//! Property: the first contact found is never after a sampled point with z > 1. Random rotors
//! (n = 2 … 4: any mass, damping, gyroscopic and non-symmetric stiffness, a fixed or a moving
//! stator point, an offset), random starts; z sampled at 400 points of the run by nalgebra's
//! exponential of the augmented system (independent of the code under test).

use proptest::prelude::*;
use rotor_rub::matrix::Unbalance;

use super::common::*;

fn case_strategy() -> impl Strategy<Value = Case> {
    (2usize..=4).prop_flat_map(|n| {
        let entries = n * n;
        (
            prop::collection::vec(0.5f64..2.0, n),
            prop::collection::vec(-0.3f64..0.3, entries),
            prop::collection::vec(0.0f64..0.4, n),
            prop::collection::vec(-0.5f64..0.5, entries),
            prop::collection::vec(-1.0f64..1.0, 2 * n),
            (
                0.3f64..3.0,
                -0.3f64..0.3,
                -0.3f64..0.3,
                0.0f64..0.4,
                any::<bool>(),
            ),
        )
            .prop_map(
                move |(mass, k, c, g, y0, (speed, ox, oy, amount, moving))| {
                    let at = |i: usize, j: usize| i * n + j;
                    let mut m = vec![0.0; n * n];
                    let mut kk = vec![0.0; n * n];
                    let mut cc = vec![0.0; n * n];
                    let mut gg = vec![0.0; n * n];
                    for i in 0..n {
                        m[at(i, i)] = mass[i];
                        cc[at(i, i)] = c[i];
                        for j in 0..n {
                            // Diagonally dominant stiffness (positive, possibly non-symmetric),
                            // skew gyroscopic coupling.
                            kk[at(i, j)] = if i == j {
                                1.5 + k[at(i, j)].abs()
                            } else {
                                k[at(i, j)]
                            };
                            if i < j {
                                gg[at(i, j)] = g[at(i, j)];
                                gg[at(j, i)] = -g[at(i, j)];
                            }
                        }
                    }
                    let stator = (moving && n >= 4).then_some((2, 3));
                    Case {
                        name: "random".into(),
                        n,
                        speed,
                        phase: 0.3,
                        mass: m,
                        damping: cc,
                        gyroscopic: gg,
                        stiffness: kk,
                        unbalances: vec![Unbalance {
                            x: 0,
                            y: 1,
                            amount,
                            phase: 0.0,
                        }],
                        input: vec![],
                        rotor: (0, 1),
                        stator,
                        offset: (ox, oy),
                        t0: 0.2,
                        y0: y0.iter().map(|v| 0.6 * v).collect(),
                        expm_check: None,
                        states: vec![],
                        scipy: vec![],
                        contact: None,
                        no_contact_to: None,
                    }
                },
            )
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    #[test]
    fn the_first_contact_is_never_after_a_sampled_contact(case in case_strategy()) {
        let start = case.start();
        let model = case.model();
        // Only starts inside the clearance: free flight is this solver's regime.
        prop_assume!(station_h(&case, &case.y0) < -1e-3);
        let end = case.t0 + 8.0;
        let mut free = started(&model, case.t0, start);
        let found = contact(&mut free, end).map(|e| e.time);
        let horizon = found.unwrap_or(end);
        // nalgebra's exp is good to ~1e-12 here: a sampled h above 1e-9 is a contact.
        let samples = 400;
        for k in 1..=samples {
            let t = case.t0 + (end - case.t0) * k as f64 / samples as f64;
            if t >= horizon {
                break;
            }
            let y = augmented_state(&case, case.t0, &case.y0, t);
            let h = station_h(&case, &y);
            prop_assert!(
                h <= 1e-9,
                "z > 1 at t = {} (h = {:e}) before the contact found at {:?}",
                t, h, found
            );
        }
        if let Some(t) = found {
            // The contact found is a real one: h crosses 0 there (independent state).
            let y = augmented_state(&case, case.t0, &case.y0, t);
            prop_assert!(station_h(&case, &y).abs() < 1e-9);
        }
        prop_assert_eq!(free.work().unresolved, 0);
    }
}
