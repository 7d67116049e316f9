//! The stator ring with mass in the FMU (issue 28 item 3): its entries offered again in both
//! unit systems with their SI units and scales (every ring entry's default round-trips through
//! the SI FMU bit for bit), the outputs `xs`, `ys`, `vxs`, `vys` (0 for the massless ring), a
//! ring run equal to the Rust ring stepper's, and a serialized ring state that restores.

use rotor_rub::stepper::RingStepper;
use rotor_rub::stepper::matrix::MatrixStepperConfig;
use rotor_rub::{Parameter, Params, Preset};
use rotor_rub_fmu::model::Model;
use rotor_rub_fmu::state::{deserialize, serialize};
use rotor_rub_fmu::units::{Dimension, SI_DEFAULT, Units};
use rotor_rub_fmu::variables::{self, Target};

/// The ring's entries.
const RING: [Parameter; 7] = [
    Parameter::StatorMassRatio,
    Parameter::ContactStiffness,
    Parameter::StatorDamping,
    Parameter::Xs0,
    Parameter::Ys0,
    Parameter::Vxs0,
    Parameter::Vys0,
];

fn vr(name: &str, units: Units) -> u32 {
    variables::all(units)
        .into_iter()
        .find(|v| v.name == name)
        .unwrap_or_else(|| panic!("{name} is a variable"))
        .vr
}

#[test]
fn every_ring_entry_is_offered_with_its_si_unit_and_scale() {
    let dimension = |p| match p {
        Parameter::StatorMassRatio => Dimension::One,
        Parameter::ContactStiffness => Dimension::Stiffness,
        Parameter::StatorDamping => Dimension::Damping,
        Parameter::Xs0 | Parameter::Ys0 => Dimension::Length,
        _ => Dimension::Velocity,
    };
    for units in [Units::Dimensionless, Units::Si] {
        for p in RING {
            let v = variables::of_parameter(p, units).expect("offered");
            assert_eq!(v.name, p.info().name);
            assert_eq!(v.dimension, dimension(p), "{}", v.name);
            assert_eq!(v.target, Target::Table(p));
        }
    }
    assert_eq!(Dimension::Damping.unit(Units::Si), "N.s/m");
    assert_eq!(Dimension::Stiffness.unit(Units::Si), "N/m");
    let w = SI_DEFAULT.natural_frequency;
    assert_eq!(
        SI_DEFAULT.factor(Dimension::Damping),
        SI_DEFAULT.mass * w,
        "ĉ = c_s/(M ω_n)"
    );
}

/// Untouched, every ring entry's SI start value reads back as itself and reaches the model as
/// the table's default, bit for bit (k̂_c = 50 stays 50), at the default scales and at others
/// (the last failure: an untouched k̂_c converted with other scales became ≠ 50, and the
/// massless ring then refused its "non-default" k̂_c); with m̂ = 1 set the ring runs with the
/// default k̂_c exactly.
#[test]
fn every_ring_entrys_default_round_trips_through_the_si_fmu() {
    let scales = [
        None,
        Some([
            ("natural_frequency", 437.0),
            ("clearance", 2.5e-4),
            ("mass", 7.3),
        ]),
    ];
    for (mass, scales) in [None, Some(1.0)]
        .into_iter()
        .flat_map(|m| scales.iter().map(move |s| (m, s)))
    {
        let mut model = Model::new(Units::Si);
        for (name, value) in scales.iter().flatten() {
            model.set(vr(name, Units::Si), *value).expect("a scale");
        }
        let custom = scales.is_some();
        if let Some(m) = mass {
            model
                .set(vr("stator_mass_ratio", Units::Si), m)
                .expect("settable");
        }
        for p in RING {
            let v = variables::of_parameter(p, Units::Si).expect("offered");
            let start = v.start.expect("a start value");
            if !(mass.is_some() && p == Parameter::StatorMassRatio) {
                // At other scales an untouched entry reads as its default in those scales.
                let want = if custom {
                    model.scales().to_importer(v.dimension, p.info().default)
                } else {
                    start
                };
                assert_eq!(model.get(v.vr).expect("readable"), want, "{}", v.name);
            }
        }
        model.initialize().expect("initializes");
        let stepper = model.stepper.as_ref().expect("a stepper");
        let params: &Params = stepper.params();
        for p in RING {
            let want = if p == Parameter::StatorMassRatio {
                mass.unwrap_or(0.0)
            } else {
                p.info().default
            };
            let got = p.get(&rotor_rub::Problem {
                params: *params,
                ..rotor_rub::Problem::DEFAULT
            });
            assert_eq!(
                got.to_bits(),
                want.to_bits(),
                "{}: {got} != {want}",
                p.info().name
            );
        }
        assert_eq!(
            matches!(stepper, rotor_rub::stepper::AnyStepper::Ring(_)),
            mass.is_some()
        );
    }
}

fn ring_model(units: Units) -> Model {
    let mut model = Model::new(units);
    for (name, value) in [
        ("stator_mass_ratio", 1.0),
        ("contact_stiffness", 100.0),
        ("stator_damping", 0.5),
    ] {
        let v = variables::of_parameter(
            Parameter::ALL
                .into_iter()
                .find(|p| p.info().name == name)
                .expect("an entry"),
            units,
        )
        .expect("offered");
        let value = rotor_rub_fmu::units::Scales::to_importer(&model.scales(), v.dimension, value);
        model.set(v.vr, value).expect("settable");
    }
    model.initialize().expect("initializes");
    model
}

/// The FMU's ring outputs at its communication points are the Rust ring stepper's states at
/// the same internal steps (1e-3, each ending at its first switch), bit for bit; the massless
/// ring's outputs are 0 and its run is the planar stepper's.
#[test]
fn a_ring_run_is_the_ring_steppers() {
    let mut model = ring_model(Units::Dimensionless);
    let mut problem = Preset::Paper.problem();
    for (p, v) in [
        (Parameter::StatorMassRatio, 1.0),
        (Parameter::ContactStiffness, 100.0),
        (Parameter::StatorDamping, 0.5),
    ] {
        p.set(&mut problem, v);
    }
    let mut rust = RingStepper::new(&problem, MatrixStepperConfig::with_dt(1e-3)).expect("starts");
    let names = ["x", "y", "xs", "ys", "vxs", "vys"];
    let vrs = names.map(|n| vr(n, Units::Dimensionless));
    let mut switches = 0;
    let mut largest = 0.0f64;
    for k in 0..500 {
        let t = model.time();
        model
            .do_step(t, 0.05, false, &mut |_| switches += 1)
            .expect("a communication step");
        // The FMU's internal steps (`step.rs`): 1e-3, or the rest to the communication point,
        // each ending at the first switch inside it.
        let end = t + 0.05;
        while end - rust.time() > 1e-12 * (1.0 + end.abs()) {
            let remaining = end - rust.time();
            let dt = if remaining - 1e-3 >= -1e-9 * 1e-3 {
                1e-3
            } else {
                remaining
            };
            rust.step_to_switch(dt).expect("a step");
        }
        let y = rust.full_state();
        let want = [y[0], y[1], y[2], y[3], y[6], y[7]];
        let got = vrs.map(|v| model.get(v).expect("readable"));
        assert_eq!(got, want, "communication point {k}");
        largest = largest.max(got[2].hypot(got[3]));
    }
    assert!(switches > 20, "the ring run rubs ({switches} switches)");
    assert!(largest > 0.3, "the ring moves ({largest})");

    // The massless ring: the planar stepper, bit for bit, and the ring's outputs 0.
    let mut massless = Model::new(Units::Dimensionless);
    massless.initialize().expect("initializes");
    let mut planar = rotor_rub::Stepper::new(
        &Preset::Paper.problem(),
        rotor_rub::StepperConfig::with_dt(1e-3),
    )
    .expect("starts");
    for _ in 0..300 {
        let t = massless.time();
        massless
            .do_step(t, 0.1, false, &mut |_| ())
            .expect("a step");
        for _ in 0..100 {
            planar.step(1e-3).expect("a step");
        }
        assert_eq!(massless.get(vrs[0]).expect("x"), planar.state().x);
        assert_eq!(massless.get(vrs[1]).expect("y"), planar.state().y);
        for v in &vrs[2..] {
            assert_eq!(massless.get(*v).expect("readable"), 0.0);
        }
    }
}

/// A serialized ring state restores into a new instance and runs on within the method's
/// tolerance of the original (its method restarts at the saved state).
#[test]
fn a_serialized_ring_state_restores() {
    let mut model = ring_model(Units::Si);
    let h = 0.05 / SI_DEFAULT.natural_frequency;
    for _ in 0..200 {
        let t = model.time();
        model.do_step(t, h, false, &mut |_| ()).expect("a step");
    }
    let bytes = serialize(&model);
    let mut restored = deserialize(&bytes, Units::Si).expect("restores");
    assert!(matches!(
        restored.stepper,
        Some(rotor_rub::stepper::AnyStepper::Ring(_))
    ));
    let xs = vr("xs", Units::Si);
    assert_eq!(restored.get(xs).expect("xs"), model.get(xs).expect("xs"));
    let mut worst = 0.0f64;
    for _ in 0..200 {
        let (t, u) = (model.time(), restored.time());
        model.do_step(t, h, false, &mut |_| ()).expect("a step");
        restored.do_step(u, h, false, &mut |_| ()).expect("a step");
        for name in ["x", "y", "xs", "ys"] {
            let v = vr(name, Units::Si);
            let d = (model.get(v).expect("a") - restored.get(v).expect("b")).abs();
            worst = worst.max(d / SI_DEFAULT.clearance);
        }
    }
    assert!(worst < 1e-6, "restored run differs by {worst:e} clearances");
}
