//! Output requests never perturb propagation (`docs/MODEL.md` §13): the same run with and without
//! dense or Poincaré sampling gives bit-identical events and final states, for every method.

use rotor_rub::{
    ContactScheme, Event, Method, Options, Preset, Problem, Propagate, Propagator, State,
    advance_to, events, poincare_times,
};

/// A case with many short contacts: near resonance, heavy unbalance, soft anisotropic stator.
fn contact_heavy() -> Problem {
    let mut p = Preset::PaperText.problem();
    p.params.speed_ratio = 1.05;
    p.params.eccentricity_ratio = 140.0;
    p.params.k_xx = 5.0;
    p.params.k_yy = 12.0;
    p
}

fn problems() -> [(&'static str, Problem); 3] {
    [
        ("paper", Preset::Paper.problem()),
        ("paper-text", Preset::PaperText.problem()),
        ("contact-heavy", contact_heavy()),
    ]
}

fn option_sets() -> Vec<Options> {
    let mut all: Vec<Options> = Method::ALL
        .iter()
        .copied()
        .map(Options::with_method)
        .collect();
    all.push(Options {
        contact_scheme: ContactScheme::Exprb2,
        ..Options::default()
    });
    all
}

/// Events and final state of a run to `end`, advancing through `times` (sorted, inside
/// (start, end)) on the way.
fn run(problem: &Problem, options: &Options, times: &[f64], end: f64) -> (Vec<Event>, State) {
    let mut p = Propagator::new(problem, options).expect("valid problem");
    let mut found = Vec::new();
    for &t in times {
        advance_to(&mut p, t, |e| found.push(*e)).expect("sample");
    }
    for e in events(&mut p, end) {
        found.push(e.expect("event"));
    }
    (found, p.state())
}

#[test]
fn sampling_never_changes_events_or_final_state() {
    for (name, problem) in problems() {
        let end = 12.0 * problem.params.forcing_period();
        // Dense samples at an awkward spacing (not commensurate with any chunk or step), and the
        // stroboscopic times of a Poincaré section.
        let dense: Vec<f64> = (1..1500).map(|k| k as f64 * end / 1500.3).collect();
        let strobe: Vec<f64> = poincare_times(problem.start_time, problem.params.speed_ratio, 12)
            .filter(|&t| t > problem.start_time && t < end)
            .collect();
        for options in option_sets() {
            let (plain_events, plain_end) = run(&problem, &options, &[], end);
            assert!(!plain_events.is_empty(), "{name}: the case has contacts");
            for (label, times) in [("dense", &dense), ("poincare", &strobe)] {
                let (ev, fin) = run(&problem, &options, times, end);
                assert!(
                    ev == plain_events && fin == plain_end,
                    "{name}, {:?}/{:?}, {label} sampling changed the run: {} vs {} events, \
                     final {fin:?} vs {plain_end:?}",
                    options.method,
                    options.contact_scheme,
                    ev.len(),
                    plain_events.len(),
                );
            }
        }
    }
}
