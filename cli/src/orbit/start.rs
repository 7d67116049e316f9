//! Where a search for an orbit starts (`--start`): a state after a simulated transient, the
//! steady free response in closed form, or a state given; and the command-line options shared by
//! `orbit` and `continue` (the method's default, the start, the shooting tolerance).

use rotor_rub::coefficients::{
    self as coef, FreeBasis, FreeDampedFrequency, FreeHomogeneous, ModelParams,
};
use rotor_rub::orbit::{DEFAULT_TRAJECTORY_TOL, MapSettings};
use rotor_rub::{Method, Options, Params, Problem, State};

use crate::error::{CliError, Result, num};
use crate::limits::Budget;
use crate::options::{DefaultMethod, parse_finite};

/// `orbit` and `continue`: the trajectory of every map by hybrid (exact free flight, DOP853 in
/// contact), at [`DEFAULT_TRAJECTORY_TOL`] unless `--tol` says otherwise.
#[derive(Clone, Debug, Default)]
pub struct Orbits;

impl DefaultMethod for Orbits {
    const METHOD: Method = Method::Hybrid;
}

/// The map settings for `options` as given (`tol` unset: [`DEFAULT_TRAJECTORY_TOL`]).
pub fn map_settings(options: &Options) -> MapSettings {
    let options = Options {
        tol: Some(options.tol.unwrap_or(DEFAULT_TRAJECTORY_TOL)),
        ..*options
    };
    MapSettings {
        options,
        ..MapSettings::default()
    }
}

/// How a start state is made.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Guess {
    /// Simulate `--transient` forcing periods from the problem's initial state.
    Simulate,
    /// The steady response of free flight (no contact), in closed form.
    Free,
    /// A state given (x, y, x', y').
    Given(State),
}

/// A start: how its state is made, and at which value of the continued parameter (`None`: the
/// start of the range, or the problem's own value for `orbit`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StartSpec {
    /// The guess.
    pub guess: Guess,
    /// The parameter value (`@VALUE`).
    pub value: Option<f64>,
}

/// `--start`: `simulate`, `free` or `x,y,vx,vy`, optionally followed by `@VALUE`.
pub fn parse_start(text: &str) -> Result<StartSpec, String> {
    let (spec, value) = match text.split_once('@') {
        Some((spec, value)) => (spec, Some(parse_finite(value)?)),
        None => (text, None),
    };
    let guess = match spec.trim() {
        "simulate" => Guess::Simulate,
        "free" => Guess::Free,
        list => {
            let values: Vec<f64> = list
                .split(',')
                .map(parse_finite)
                .collect::<Result<_, _>>()
                .map_err(|e| format!("'{text}': {e}; expected simulate, free or x,y,vx,vy"))?;
            match values[..] {
                [x, y, vx, vy] => Guess::Given(State::new(x, y, vx, vy)),
                _ => {
                    return Err(format!(
                        "'{text}' has {} numbers: expected simulate, free or four numbers x,y,vx,vy",
                        values.len()
                    ));
                }
            }
        }
    };
    Ok(StartSpec { guess, value })
}

/// The steady response of free flight at the section τ = 0 (θ = φ0), from the generated closed
/// form with no transient (`free_eval` with X = P = Y = Q = 0), moved by the static deflection
/// under the input force; `None` where it is not finite (ν = 0 at η = 1).
pub fn free_steady_state(params: &Params) -> Option<State> {
    let model = ModelParams::of(params);
    let particular = coef::free_particular(&model);
    let beta = FreeDampedFrequency {
        beta_sq: coef::free_damped_frequency_sq(&model).beta_sq,
    };
    let phasor = rotor_rub::field::phasor(&model, 0.0);
    let none = FreeHomogeneous {
        xh: 0.0,
        px: 0.0,
        yh: 0.0,
        py: 0.0,
    };
    let r = coef::free_eval(
        &model,
        &phasor,
        &particular,
        &beta,
        &none,
        &FreeBasis { ec: 1.0, es: 0.0 },
    );
    let (dx, dy) = if params.force_x == 0.0 && params.force_y == 0.0 {
        (0.0, 0.0)
    } else {
        let d = coef::input_static_deflection(&model);
        (d.x, d.y)
    };
    let s = State::new(r.x + dx, r.y + dy, r.vx, r.vy);
    s.is_finite().then_some(s)
}

/// The start state of `problem` by `guess`: simulated over `transient` forcing periods (work
/// charged to `budget`), the free steady response, or the state given.
///
/// # Errors
/// What the simulation reports; a free response that does not exist (undamped resonance).
pub fn start_state(
    problem: &Problem,
    options: &Options,
    guess: Guess,
    transient: u64,
    budget: &Budget,
) -> Result<State> {
    match guess {
        Guess::Given(s) if s.is_finite() => Ok(s),
        Guess::Given(_) => Err(CliError::input(
            "--start: the state must be four finite numbers",
        )),
        Guess::Free => free_steady_state(&problem.params).ok_or_else(|| {
            CliError::input(format!(
                "--start free: the steady free response does not exist at speed_ratio = {} with damping_ratio = {} (undamped resonance)",
                num(problem.params.speed_ratio),
                num(problem.params.damping_ratio)
            ))
        }),
        Guess::Simulate => super::simulated_start(problem, options, transient, budget),
    }
}
