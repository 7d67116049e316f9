//! `examples/ring.c` (the stator ring with mass through the C ABI), compiled with the system C
//! compiler and linked against the static library as `tests/paper_c.rs` does: the C run is the
//! Rust [`RingStepper`]'s (same code, same arithmetic): the same switches, bit for bit, and the
//! same rotor and ring states at the checkpoints; the ring moves.

use rotor_rub::stepper::RingStepper;
use rotor_rub::stepper::matrix::MatrixStepperConfig;
use rotor_rub::{Parameter, Preset};

#[path = "common/c_example.rs"]
mod c_example;

fn numbers(words: &[&str]) -> Vec<f64> {
    words.iter().map(|w| w.parse().expect("a number")).collect()
}

#[test]
fn the_c_ring_run_is_the_rust_ring_stepper() {
    let output = c_example::compile_and_run("ring", "rotor_rub_ring_c", &[]);
    let mut problem = Preset::Paper.problem();
    for (p, v) in [
        (Parameter::StatorMassRatio, 1.0),
        (Parameter::ContactStiffness, 100.0),
        (Parameter::StatorDamping, 0.5),
    ] {
        p.set(&mut problem, v);
    }
    let dt = 1e-2;
    let mut rust = RingStepper::new(&problem, MatrixStepperConfig::with_dt(dt)).expect("starts");
    let steps = (10.0 * problem.params.forcing_period() / dt - 1e-9).ceil() as usize;
    let mut switches = Vec::new();
    let mut states = Vec::new();
    let mut largest = 0.0f64;
    for k in 1..=steps {
        let r = rust.step(dt).expect("a step");
        switches.extend(r.events.iter().map(|e| {
            let y = e.state.array();
            vec![e.time, y[0], y[1], y[4], y[5]]
        }));
        let ring = rust.ring_state();
        largest = largest.max(ring.xs.hypot(ring.ys));
        if k % 100 == 0 {
            let y = r.state.array();
            states.push(vec![r.time, y[0], y[1], y[4], y[5], y[2], y[3], y[6], y[7]]);
        }
    }
    let (mut c_switches, mut c_states, mut summary) = (Vec::new(), Vec::new(), None);
    for line in output.lines() {
        let words: Vec<&str> = line.split_whitespace().collect();
        match words.first() {
            Some(&"switch") => c_switches.push(numbers(&words[2..])),
            Some(&"state") => c_states.push(numbers(&words[2..11])),
            Some(&"summary") => summary = Some(numbers(&words[1..])),
            _ => panic!("unexpected line {line}"),
        }
    }
    assert_eq!(
        c_switches, switches,
        "the C run's switches are the Rust stepper's"
    );
    assert_eq!(
        c_states, states,
        "the C run's checkpoints are the Rust stepper's"
    );
    let summary = summary.expect("a summary line");
    assert_eq!(summary[1] as usize, switches.len());
    assert!(
        switches.len() > 50,
        "heavy rub ({} switches)",
        switches.len()
    );
    assert_eq!(summary[2], largest);
    assert!(largest > 0.3, "the ring moves ({largest})");
}
