//! The fixed-step stepper built for a model file (issue 29 item 5, its stepper half): the
//! two-disk rotor of `examples/models/two_disk.toml` (n = 8, SI), read by the CLI's model file
//! reader and stated as the CLI states it, stepped by `MatrixStepper` at dt = 1e-4 s: its states
//! at k·dt and its switches are those of the matrix propagator's continuous run.

use std::sync::Arc;

use rotor_rub::Propagate;
use rotor_rub::matrix::MatrixPropagator;
use rotor_rub::stepper::MatrixStepper;
use rotor_rub::stepper::matrix::MatrixStepperConfig;
use rotor_rub_cli::model_file::{Model, load, on_large_stack};

#[test]
fn the_stepper_runs_a_model_file() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../examples/models/two_disk.toml"
    );
    let spec = load(std::path::Path::new(path)).expect("the example model file reads");
    on_large_stack(|| {
        let model: Arc<Model> = Arc::from(spec.build().expect("the model states"));
        let start = spec.start().expect("a start");
        let dt = 1e-4;
        let config = MatrixStepperConfig {
            tol: Some(1e-12),
            ..MatrixStepperConfig::with_dt(dt)
        };
        let mut stepper =
            MatrixStepper::new(Arc::clone(&model), 0.0, start, config).expect("starts");
        let mut continuous =
            MatrixPropagator::new(Arc::clone(&model), 0.0, start, &config.options())
                .expect("starts");
        let (mut want, mut got) = (Vec::new(), Vec::new());
        for k in 1..=2000 {
            let t = k as f64 * dt;
            while let Some(e) = continuous.advance(t).expect("the continuous run") {
                want.push((e.time, e.kind));
            }
            let r = stepper.step(dt).expect("a step");
            got.extend(r.events.iter().map(|e| (e.time, e.kind)));
            assert_eq!(r.time, t);
            assert_eq!(
                r.state.as_slice(),
                continuous.state().as_slice(),
                "step {k}"
            );
        }
        assert_eq!(got, want);
        println!(
            "two-disk rotor, 0.2 s in steps of 1e-4 s: {} switches",
            got.len()
        );
        assert!(
            got.len() >= 2,
            "disk 1 rubs ({} switches in 0.2 s)",
            got.len()
        );
    });
}
