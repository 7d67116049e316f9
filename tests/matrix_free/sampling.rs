//! Sampling never changes a trajectory: the contact and the states are the same bits whether a
//! run is asked for one target or a thousand on the way; and a free flight restarted from its
//! own state at a later time continues the same motion (to rounding).

use super::common::*;

fn dense_and_sparse(name: &str, end: f64) {
    let case = Case::load(name);
    let model = case.model();
    let mut sparse = started(&model, case.t0, case.start());
    let direct = run_to(&mut sparse, end);
    let mut dense = started(&model, case.t0, case.start());
    let mut last = None;
    for k in 1..=1000 {
        let t = case.t0 + (end - case.t0) * k as f64 / 1000.0;
        let r = run_to(&mut dense, t);
        if let rotor_rub::driver::Located::Switch(_) = r {
            last = Some(r);
            break;
        }
        last = Some(r);
    }
    let last = last.unwrap();
    match (direct, last) {
        (rotor_rub::driver::Located::Switch(a), rotor_rub::driver::Located::Switch(b)) => {
            assert_eq!(a, b, "{name}: the contact moved with sampling")
        }
        (rotor_rub::driver::Located::Reached(a), rotor_rub::driver::Located::Reached(b)) => {
            assert_eq!(a, b, "{name}: the end state moved with sampling")
        }
        (a, b) => panic!("{name}: {a:?} against {b:?}"),
    }
}

#[test]
fn sampling_never_moves_a_contact_or_a_state() {
    for name in [
        "jeffcott_contact",
        "gyroscopic_contact",
        "ring_undamped_contact",
        "chain20_contact",
        "ring_graze",
        "chain20_graze_miss",
    ] {
        dense_and_sparse(name, Case::load(name).t0 + 4.0);
    }
    for name in ["ring_undamped", "chain20"] {
        dense_and_sparse(name, Case::load(name).t0 + 30.0);
    }
}

#[test]
fn a_restarted_flight_continues_the_same_motion() {
    for name in [
        "gyroscopic",
        "ring_undamped",
        "ring_resonant_unforced",
        "rigid_body",
        "chain20",
    ] {
        let case = Case::load(name);
        let model = case.model();
        let (t1, t2) = (case.t0 + 3.3, case.t0 + 11.9);
        let mut direct = started(&model, case.t0, case.start());
        let y1 = reached(&mut direct, t1);
        let y2 = reached(&mut direct, t2);
        let n = case.n;
        let restart = State::new(&y1[..n], &y1[n..]).unwrap();
        let mut again = started(&model, t1, restart);
        let y2b = reached(&mut again, t2);
        let e = relative(&y2b, &y2);
        assert!(e < 1e-13, "{name}: restarted flight differs by {e:e}");
    }
}
