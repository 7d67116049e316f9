//! Shared by the benches: the two benchmark cases, one timed run (switches and the Poincaré
//! section over a span of forcing periods), the tol = 1e-13 DOP853 reference, the accuracy
//! check, the search for the loosest tolerance that meets it, and the peer integrator
//! (`differential-equations`' DOP853 on the same right-hand side).
//!
//! Not every bench uses every item.
#![allow(dead_code)]

use std::time::Duration;

use criterion::Criterion;
use rotor_rub::compare::{compare_events, state_difference};
use rotor_rub::{
    ContactScheme, Event, Method, Options, Preset, Problem, Propagate, Propagator, State,
    advance_to,
};

/// Forcing periods of one timed propagation.
pub const PERIODS: usize = 100;

/// Accuracy every method is held to, against the tol = 1e-13 DOP853 reference: the largest
/// switch-time error, and the largest state error (any component, at every switch and at every
/// Poincaré point).
pub const SWITCH_TIME_ERROR: f64 = 1e-8;
/// See [`SWITCH_TIME_ERROR`].
pub const STATE_ERROR: f64 = 1e-6;
/// Tolerance of the reference run.
pub const REFERENCE_TOL: f64 = 1e-13;

/// Criterion settings for a 2-core machine shared with others: short warm-up and measurement,
/// overridable on the command line (`-- --warm-up-time 1 --measurement-time 3`).
pub fn criterion() -> Criterion {
    Criterion::default()
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3))
        .sample_size(20)
        .configure_from_args()
}

/// The two benchmark cases.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Case {
    /// `paper` preset, offset (0, 0), η = 1.5: contact only in the start-up transient.
    Sparse,
    /// `paper` preset, η = 2.5: contact in every forcing period (quasi-periodic rub).
    Heavy,
}

impl Case {
    pub const ALL: [Case; 2] = [Case::Sparse, Case::Heavy];

    pub fn name(self) -> &'static str {
        match self {
            Case::Sparse => "contact-sparse",
            Case::Heavy => "contact-heavy",
        }
    }

    pub fn problem(self) -> Problem {
        let mut p = Preset::Paper.problem();
        match self {
            Case::Sparse => {
                p.params.speed_ratio = 1.5;
                p.params.offset_x = 0.0;
                p.params.offset_y = 0.0;
            }
            Case::Heavy => p.params.speed_ratio = 2.5,
        }
        p
    }
}

/// A method (and contact scheme, for a method that takes one) with its accuracy knob: `tol`, or
/// the fixed contact sub-step for exprb2.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Setting {
    pub method: Method,
    pub scheme: Option<ContactScheme>,
    pub knob: f64,
}

/// The methods compared, by name, from the registry: `method` or `method-scheme` for a method
/// with contact schemes. The knob is filled in by [`Setting::with`].
pub fn methods() -> Vec<String> {
    let mut names = Vec::new();
    for &m in Method::ALL {
        if m.info().contact_scheme {
            for s in ContactScheme::ALL {
                names.push(format!("{}-{}", m.name(), s.name()));
            }
        } else {
            names.push(m.name().to_string());
        }
    }
    names
}

impl Setting {
    /// `method` at tolerance `tol` (default contact scheme).
    pub fn tol(method: Method, tol: f64) -> Setting {
        let scheme = method
            .info()
            .contact_scheme
            .then_some(ContactScheme::Exprb43);
        Setting {
            method,
            scheme,
            knob: tol,
        }
    }

    /// The setting named as in [`methods`] with `knob`.
    pub fn with(name: &str, knob: f64) -> Setting {
        let (method, scheme) = match name.split_once('-') {
            Some((m, s)) => (Method::from_name(m), ContactScheme::from_name(s)),
            None => (Method::from_name(name), None),
        };
        let method = method.unwrap_or_else(|| panic!("unknown method {name}"));
        Setting {
            method,
            scheme: scheme.or(method
                .info()
                .contact_scheme
                .then_some(ContactScheme::Exprb43)),
            knob,
        }
    }

    /// Whether the knob is a fixed sub-step (exprb2) rather than a tolerance.
    pub fn fixed_step(self) -> bool {
        self.scheme == Some(ContactScheme::Exprb2)
    }

    pub fn name(self) -> String {
        match self.scheme {
            Some(s) => format!("{}-{}", self.method.name(), s.name()),
            None => self.method.name().to_string(),
        }
    }

    /// The knob's value.
    pub fn knob(self) -> f64 {
        self.knob
    }

    /// `tol=1e-10` or `step=2e-5`.
    pub fn knob_label(self) -> String {
        if self.fixed_step() {
            format!("step={:e}", self.knob)
        } else {
            format!("tol={:e}", self.knob)
        }
    }

    pub fn options(self) -> Options {
        let mut options = Options::with_method(self.method);
        if let Some(scheme) = self.scheme {
            options.contact_scheme = scheme;
        }
        if self.fixed_step() {
            options.step = Some(self.knob);
        } else {
            options.tol = Some(self.knob);
        }
        options
    }

    /// Knob values searched for the loosest accurate one, loosest first ({1, 5, 2}·10^k), within
    /// the valid range (the method's tolerances, or the fixed sub-steps).
    pub fn ladder(name: &str) -> Vec<f64> {
        let setting = Setting::with(name, 0.0);
        let (hi, lo, valid) = if setting.fixed_step() {
            (-2, -6, rotor_rub::method::STEP_RANGE)
        } else {
            (-5, -13, setting.method.tolerance_range())
        };
        let mut v = Vec::new();
        for e in (lo..=hi).rev() {
            // Parsed from text so that the values print as written (2e-10, not 2.0000000000000003e-10).
            for (m, shift) in [(1, 0), (5, -1), (2, -1)] {
                let knob: f64 = format!("{m}e{}", e + shift).parse().expect("a number");
                if valid.contains(knob) {
                    v.push(knob);
                }
            }
        }
        v
    }
}

/// What one run produces: every switch, and the state at every forcing-period boundary.
#[derive(Clone, Debug, Default)]
pub struct Run {
    pub events: Vec<Event>,
    pub section: Vec<State>,
}

impl Run {
    pub fn with_capacity(events: usize) -> Self {
        Run {
            events: Vec::with_capacity(events),
            section: Vec::with_capacity(PERIODS + 1),
        }
    }
}

/// Propagate `problem` over `periods` forcing periods with `options`, collecting the switches
/// and the Poincaré section (τ = k·2π/η) into `out` (cleared first). This is what the
/// propagation benches time.
pub fn run_into(problem: &Problem, options: &Options, periods: usize, out: &mut Run) {
    out.events.clear();
    out.section.clear();
    let mut p = Propagator::new(problem, options).expect("valid problem and options");
    let period = problem.params.forcing_period();
    let events = &mut out.events;
    for k in 1..=periods {
        let sample = advance_to(&mut p, k as f64 * period, |e| events.push(*e))
            .expect("the benchmark cases propagate without error");
        out.section.push(sample.state);
    }
    std::hint::black_box(p.time());
}

/// One run into a fresh [`Run`].
pub fn run(problem: &Problem, options: &Options, periods: usize) -> Run {
    let mut r = Run::with_capacity(1024);
    run_into(problem, options, periods, &mut r);
    r
}

/// The reference run: DOP853 at tol = 1e-13.
pub fn reference(case: Case) -> Run {
    run(
        &case.problem(),
        &Setting::tol(Method::Dop853, REFERENCE_TOL).options(),
        PERIODS,
    )
}

/// Errors of a run against the reference.
#[derive(Clone, Copy, Debug)]
pub struct Accuracy {
    /// Switches without a same-kind partner (count or kind differ).
    pub unmatched: usize,
    /// Largest switch-time difference.
    pub switch_time: f64,
    /// Largest state difference at switches and at Poincaré points.
    pub state: f64,
}

impl Accuracy {
    pub fn of(run: &Run, reference: &Run) -> Accuracy {
        let c = compare_events(&run.events, &reference.events, SWITCH_TIME_ERROR);
        let section = run
            .section
            .iter()
            .zip(&reference.section)
            .map(|(a, b)| state_difference(a, b))
            .fold(0.0, f64::max);
        let missing = run.section.len() != reference.section.len();
        Accuracy {
            unmatched: c.unmatched,
            switch_time: c.max_time_difference,
            state: if missing {
                f64::INFINITY
            } else {
                c.max_state_difference.max(section)
            },
        }
    }

    /// Whether the run meets the common accuracy.
    pub fn meets(&self) -> bool {
        self.unmatched == 0 && self.switch_time <= SWITCH_TIME_ERROR && self.state <= STATE_ERROR
    }
}

/// The loosest knob on `ladder` whose run (by `run`) meets the common accuracy against
/// `reference`, with its accuracy; `None` when none does.
pub fn loosest<R: FnMut(f64) -> Run>(
    ladder: &[f64],
    reference: &Run,
    mut run: R,
) -> Option<(f64, Accuracy)> {
    ladder.iter().find_map(|&knob| {
        let acc = Accuracy::of(&run(knob), reference);
        acc.meets().then_some((knob, acc))
    })
}

/// The loosest knob of method `name` on `case` that meets the common accuracy (see
/// [`loosest`]).
pub fn loosest_accurate(name: &str, case: Case, reference: &Run) -> Option<(Setting, Accuracy)> {
    let problem = case.problem();
    loosest(&Setting::ladder(name), reference, |knob| {
        run(&problem, &Setting::with(name, knob).options(), PERIODS)
    })
    .map(|(knob, acc)| (Setting::with(name, knob), acc))
}

/// The peer: the same nonlinear right-hand side (`rotor_rub::field`, the regime chosen by the
/// sign of h = z² − 1 at every evaluation) integrated by the `differential-equations` crate's
/// DOP853 with rtol = atol = tol and the same largest step as ours, its event detection (sign
/// change of h between steps, Brent on the dense output) recording the switches, and its
/// `t_eval` output giving the Poincaré section. It does not restart at switches: the contact
/// kink is stepped over and left to its step-size control.
pub mod peer {
    use super::switching;
    use differential_equations::prelude::{
        CrossingDirection, Event as PeerEvent, EventConfig, ExplicitRungeKutta, IVP, ODE,
    };
    use rotor_rub::{Event, EventKind, Params, Problem, Regime, State, field};

    use super::{PERIODS, Run};

    /// The rotor as the peer sees it.
    pub struct Rotor(pub Params);

    impl ODE<f64, [f64; 4]> for Rotor {
        fn diff(&self, t: f64, y: &[f64; 4], dydt: &mut [f64; 4]) {
            let s = State::from_array(*y);
            let (h, _) = switching(&self.0, &s);
            let regime = if h > 0.0 {
                Regime::Contact
            } else {
                Regime::Free
            };
            *dydt = field::derivative(&self.0, regime, 0.0, t, &s).to_array();
        }
    }

    impl PeerEvent<f64, [f64; 4]> for Rotor {
        fn config(&self) -> EventConfig {
            EventConfig::new(CrossingDirection::Both, None)
        }

        fn event(&self, _t: f64, y: &[f64; 4]) -> f64 {
            switching(&self.0, &State::from_array(*y)).0
        }
    }

    /// The peer's run of `problem` over `periods` forcing periods at rtol = atol = `tol`.
    pub fn run(problem: &Problem, tol: f64, periods: usize) -> Run {
        let params = problem.params;
        let period = params.forcing_period();
        let times: Vec<f64> = (1..=periods).map(|k| k as f64 * period).collect();
        let t0 = problem.start_time;
        let t_end = periods as f64 * period;
        let h_max = 0.25 * period.min(core::f64::consts::TAU);
        let rotor = Rotor(params);
        let method = ExplicitRungeKutta::dop853()
            .rtol(tol)
            .atol(tol)
            .h_max(h_max)
            .max_steps(100_000_000);
        let solution = IVP::ode(&rotor, t0, t_end, problem.initial.to_array())
            .t_eval(&times)
            .event(&rotor)
            .method(method)
            .solve()
            .expect("the peer integrates the benchmark cases");
        let mut out = Run::with_capacity(2 * PERIODS);
        let mut next_sample = 0;
        for (t, y) in solution.t.iter().zip(solution.y.iter()) {
            let state = State::from_array(*y);
            if times.get(next_sample) == Some(t) {
                out.section.push(state);
                next_sample += 1;
            } else {
                let (_, dh) = switching(&params, &state);
                let kind = if dh > 0.0 {
                    EventKind::Enter
                } else {
                    EventKind::Exit
                };
                out.events.push(Event {
                    time: *t,
                    kind,
                    state,
                });
            }
        }
        out
    }
}

/// h = z² − 1 and h' of a state, by hand.
fn switching(p: &rotor_rub::Params, s: &rotor_rub::State) -> (f64, f64) {
    let (u, v) = (s.x - p.offset_x, s.y - p.offset_y);
    (u * u + v * v - 1.0, 2.0 * (u * s.vx + v * s.vy))
}
