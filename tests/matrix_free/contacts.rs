//! Every contact found: the first contact time against a 30-digit mpmath reference (a dense
//! scan of the augmented system with Hermite checks between samples, refined by mpmath's root
//! finder; `scripts/matrix_expm.py`) on the Jeffcott rotor, a gyroscopic disk, the ring ringing
//! down undamped and a 20-DOF shaft; grazing cases built to touch 1e-11 beyond z = 1 (found)
//! and to stay 1e-11 inside (not found), for the ring (both bodies moving) and the shaft.

use super::common::*;

const TRANSVERSAL: [&str; 4] = [
    "jeffcott_contact",
    "gyroscopic_contact",
    "ring_undamped_contact",
    "chain20_contact",
];

fn check_contact(name: &str, tolerance: f64) -> f64 {
    let case = Case::load(name);
    let model = case.model();
    let reference = case
        .contact
        .unwrap_or_else(|| panic!("{name}: no reference contact"));
    let mut free = started(&model, case.t0, case.start());
    let end = reference + 1.0;
    let event = contact(&mut free, end).unwrap_or_else(|| panic!("{name}: contact missed"));
    let error = event.time - reference;
    assert!(
        error.abs() <= tolerance,
        "{name}: contact at {} against {reference} ({error:e})",
        event.time
    );
    // The contact state is on z = 1 (h to rounding).
    let h = model.switching(event.state.as_slice()).h;
    assert!(h.abs() < 1e-13, "{name}: h = {h:e} at the contact");
    let w = free.work();
    assert_eq!((w.uncertain, w.unresolved), (0, 0), "{name}: {w:?}");
    eprintln!("{name:24}: |Δt| = {:.1e}, {w:?}", error.abs());
    error.abs()
}

#[test]
fn first_contacts_match_the_30_digit_reference_to_1e_12() {
    for name in TRANSVERSAL {
        check_contact(name, 1e-12);
    }
}

#[test]
fn a_graze_1e_11_beyond_the_clearance_is_found() {
    // The entry of a graze of depth δ is ill-conditioned: h' ~ √(8δ|h''|) ~ 1e-5 there, so
    // a rounding of h of 1e-16 moves it by ~1e-11.
    for name in ["ring_graze", "chain20_graze"] {
        check_contact(name, 1e-9);
    }
}

#[test]
fn a_near_miss_1e_11_inside_the_clearance_is_not_a_contact() {
    for name in ["ring_graze_miss", "chain20_graze_miss"] {
        let case = Case::load(name);
        let end = case.no_contact_to.unwrap();
        let model = case.model();
        let mut free = started(&model, case.t0, case.start());
        assert!(
            contact(&mut free, end).is_none(),
            "{name}: a contact reported where z stays 1e-11 inside"
        );
        assert_eq!(free.work().unresolved, 0);
    }
}

/// The paper preset at η = 3.5 written as matrices (M = I, C = 2νI, K = I): its first contact
/// is the 30-digit planar reference's first `enter` (`tests/data/switches_30digit.csv`).
#[test]
fn the_jeffcott_rotor_enters_where_the_planar_30_digit_reference_does() {
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/switches_30digit.csv");
    let text = std::fs::read_to_string(path).unwrap();
    let first = text
        .lines()
        .filter(|l| !l.starts_with('#'))
        .find(|l| l.starts_with("enter"))
        .unwrap();
    let planar: f64 = first.split(',').nth(1).unwrap().parse().unwrap();
    let case = Case::load("jeffcott_contact");
    let model = case.model();
    let mut free = started(&model, case.t0, case.start());
    let event = contact(&mut free, 20.0).unwrap();
    assert!(
        (event.time - planar).abs() < 1e-12,
        "{} against {planar}",
        event.time
    );
}

/// A segment's start counts as inside free flight: a start on z = 1 (to rounding, either side)
/// moving inward, as after a contact's exit, is not reported as a contact; the next contact is
/// the one an independent sampling sees.
#[test]
fn a_start_on_the_clearance_moving_inward_is_not_a_contact() {
    let case = Case::load("jeffcott_contact");
    let model = case.model();
    for dz in [0.0, 2e-16, -2e-16, 1e-15] {
        // P = ε̂ + (1 + dz)(cos a, sin a), velocity inward.
        let a: f64 = 0.4;
        let (c, s) = (a.cos(), a.sin());
        let q = [
            case.offset.0 + (1.0 + dz) * c,
            case.offset.1 + (1.0 + dz) * s,
        ];
        let v = [-0.8 * c + 0.3 * s, -0.8 * s - 0.3 * c];
        let y0 = State::new(&q, &v).unwrap();
        let mut free = started(&model, 0.0, y0);
        let first = contact(&mut free, 6.0).map(|e| e.time);
        let end = first.unwrap_or(6.0);
        assert!(end > 1e-3, "dz = {dz:e}: contact reported at {end}");
        let y: Vec<f64> = y0.as_slice().to_vec();
        for k in 1..200 {
            let t = end * k as f64 / 200.0;
            let h = station_h(&case, &augmented_state(&case, 0.0, &y, t));
            assert!(h <= 1e-9, "dz = {dz:e}: h = {h:e} at {t} before {first:?}");
        }
    }
}
