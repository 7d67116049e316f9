//! `rotor-rub orbit`: one periodic orbit by shooting (`docs/MODEL.md` §18): its state on the
//! section τ = 0 mod the forcing period, its period, Floquet multipliers and stability, Newton's
//! residuals, and optionally the orbit sampled over its period.

use std::fmt::Write as _;
use std::path::PathBuf;

use rotor_rub::orbit::{
    Extremum, MapObserver, PeriodicOrbit, ShootingSettings, Shot, shoot_observed,
};
use rotor_rub::{Event, EventKind, Options, Problem, State};

use super::evaluate::orbit_error;
use super::start::{Guess, Orbits, StartSpec, map_settings, parse_start, start_state};
use crate::error::{CliError, Result, num};
use crate::limits::{Budget, LimitArgs};
use crate::options::{MethodArgs, at_least, describe, parse_positive};
use crate::output::{CsvOut, check_distinct, commit_all};
use crate::problem::ProblemArgs;
use crate::stdio;
use crate::trajectory::{self, uniform_times};

/// Two section points closer than this (relative to 1 + |s|∞) are the same: the orbit's own
/// period is the smallest j dividing k with P^j(s) = s to within it.
pub const PERIOD_TOLERANCE: f64 = 1e-6;

/// Find one periodic orbit: a fixed point of k forcing periods, by Newton's method from a start.
/// Each map runs --method (default hybrid) at --tol (default 1e-12 here).
#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    pub problem: ProblemArgs,

    #[command(flatten)]
    pub method: MethodArgs<Orbits>,

    #[command(flatten)]
    pub limits: LimitArgs,

    /// The orbit's period k in forcing periods (a fixed point of k periods of the
    /// stroboscopic map), an integer in [1, 32]
    #[arg(long, value_name = "K", default_value_t = 1, value_parser = parse_period)]
    pub period: u32,

    /// Where Newton starts: `simulate` (the state after --transient forcing periods from the
    /// problem's initial state), `free` (the steady response without contact, in closed form)
    /// or a state `x,y,vx,vy` on the section τ = 0
    #[arg(long, value_name = "SPEC", default_value = "simulate", value_parser = parse_start, allow_hyphen_values = true)]
    pub start: StartSpec,

    /// Forcing periods simulated before the start of `--start simulate`
    #[arg(long, value_name = "P", default_value_t = 200, value_parser = at_least(0))]
    pub transient: u64,

    /// Newton's residual |P^k(s) − s|∞ at which the orbit is found, relative to 1 + |s|∞, in
    /// [1e-14, 1e-3]
    #[arg(long, value_name = "TOL", default_value = "1e-10", value_parser = parse_positive)]
    pub newton_tol: f64,

    /// Write the orbit sampled over its k periods as CSV with header tau,x,y,vx,vy,regime
    #[arg(long, value_name = "FILE.csv")]
    pub samples: Option<PathBuf>,

    /// Number of samples written to --samples, an integer >= 2 [default: 1001]
    #[arg(long, value_name = "N", value_parser = at_least(2), requires = "samples")]
    pub sample_count: Option<u64>,
}

/// `--period`: an integer in [1, 32].
pub fn parse_period(text: &str) -> Result<u32, String> {
    let max = rotor_rub::orbit::MAX_PERIOD as u64;
    let n = at_least(1)(text)?;
    if n > max {
        return Err(format!(
            "{n} is out of range: it must be an integer in [1, {max}]"
        ));
    }
    Ok(n as u32)
}

/// What the map saw along the orbit found.
#[derive(Default)]
pub(crate) struct Collect {
    pub extrema: Vec<Extremum>,
    pub events: Vec<Event>,
}

impl MapObserver for Collect {
    fn extremum(&mut self, e: &Extremum) {
        self.extrema.push(*e);
    }
    fn event(&mut self, e: &Event) {
        self.events.push(*e);
    }
}

/// An orbit found, with where the search started.
pub struct Found {
    /// The shot: the orbit and Newton's residuals.
    pub shot: Shot,
    /// The state Newton started from.
    pub start: State,
    /// The orbit's own period (the response class period-j of a Poincaré section on it).
    pub minimal_period: u32,
    /// The local extrema of z along the orbit.
    pub extrema: Vec<Extremum>,
    /// The switches along the orbit, over its k periods.
    pub events: Vec<Event>,
}

impl Found {
    /// The orbit.
    pub fn orbit(&self) -> &PeriodicOrbit {
        &self.shot.orbit
    }
}

/// The period-k orbit of `problem` from `guess` (simulated over `transient` periods, the free
/// response or given), Newton to `tolerance`, the trajectory by `options` (tol unset: the
/// orbits' default).
///
/// # Errors
/// Invalid input (exit 2), or no orbit found (exit 1).
pub fn find(
    problem: &Problem,
    options: &Options,
    guess: Guess,
    transient: u64,
    periods: u32,
    tolerance: f64,
    budget: &Budget,
) -> Result<Found> {
    let start = start_state(problem, options, guess, transient, budget)?;
    let mut map = map_settings(options);
    map.extrema = true;
    let settings = ShootingSettings {
        map,
        tolerance,
        ..ShootingSettings::default()
    };
    let mut seen = Collect::default();
    let shot = shoot_observed(&problem.params, start, periods, &settings, &mut seen)
        .map_err(|e| orbit_error("", e))?;
    let minimal_period = shot.orbit.minimal_period(PERIOD_TOLERANCE);
    Ok(Found {
        shot,
        start,
        minimal_period,
        extrema: seen.extrema,
        events: seen.events,
    })
}

/// A multiplier as `re ± im i (|λ| m)`.
pub fn multiplier_text(z: &rotor_rub::linalg::Complex) -> String {
    let sign = if z.im < 0.0 { '-' } else { '+' };
    format!("{:.6} {sign} {:.6}i (|λ| {:.6})", z.re, z.im.abs(), z.abs())
}

/// Run the command.
pub fn run(args: &Args) -> Result<()> {
    if args.start.value.is_some() {
        return Err(CliError::input(
            "--start: @VALUE belongs to `continue`; set the parameter with --set",
        ));
    }
    let problem = args.problem.build()?;
    let options = args.method.options()?;
    if let Some(p) = &args.samples {
        check_distinct(&[("--samples", p.as_path())], &args.problem.input_files())?;
    }
    let count = match &args.samples {
        Some(_) => args.sample_count.unwrap_or(1001),
        None => 0,
    };
    let budget = args.limits.budget();
    budget.plan("--sample-count", count)?;
    budget.plan("--transient", args.transient)?;
    let started = std::time::Instant::now();
    let found = find(
        &problem,
        &options,
        args.start.guess,
        args.transient,
        args.period,
        args.newton_tol,
        &budget,
    )?;
    let elapsed = started.elapsed();
    let orbit = found.orbit();
    let mut files = Vec::new();
    if let Some(path) = &args.samples {
        let end = f64::from(orbit.periods) * problem.params.forcing_period();
        let at = Problem {
            initial: orbit.state,
            start_time: 0.0,
            ..problem
        };
        let propagator = rotor_rub::Propagator::resume(&at, &map_options(&options))
            .map_err(|e| CliError::propagation("", e))?;
        let mut out = CsvOut::create(path, &["tau", "x", "y", "vx", "vy", "regime"])?;
        let count = usize::try_from(count).unwrap_or(usize::MAX);
        let mut tracker = budget.run(0.0, end);
        trajectory::run(
            propagator,
            end,
            uniform_times(0.0, end, count),
            &mut tracker,
            false,
            |_| Ok(()),
            |s| {
                let x = s.state;
                out.row((s.time, x.x, x.y, x.vx, x.vy, s.regime.name()))
            },
        )?;
        files.push(out.finish()?);
    }
    commit_all(files)?;
    stdio::out(&report(args, &problem, &options, &found, elapsed))
}

/// The options the maps ran with (the orbits' default tolerance where none was given).
fn map_options(options: &Options) -> Options {
    map_settings(options).options
}

fn report(
    args: &Args,
    problem: &Problem,
    options: &Options,
    found: &Found,
    elapsed: std::time::Duration,
) -> String {
    let orbit = found.orbit();
    let s = &orbit.summary;
    let mut r = String::new();
    let _ = writeln!(
        r,
        "method: {}; monodromy: closed-form free flight, variational equations in contact (DOP853, tol {:e}), saltation at switches",
        describe(&map_options(options)),
        rotor_rub::orbit::DEFAULT_VARIATIONAL_TOL
    );
    let start = match args.start.guess {
        Guess::Simulate => format!(
            "the state after {} forcing periods from the initial state",
            args.transient
        ),
        Guess::Free => "the steady free response (closed form)".to_owned(),
        Guess::Given(_) => "the state given".to_owned(),
    };
    let _ = writeln!(r, "start: {start}");
    let residuals: Vec<String> = found
        .shot
        .residuals()
        .iter()
        .map(|x| format!("{x:.2e}"))
        .collect();
    let _ = writeln!(
        r,
        "Newton: residual |P^k(s) - s| {} ({} map evaluations, {:.3} s)",
        residuals.join(", "),
        found.shot.evaluations,
        elapsed.as_secs_f64()
    );
    let st = orbit.state;
    let _ = writeln!(
        r,
        "orbit: period-{} (k = {}) at speed_ratio = {}, on the section tau = 0 mod 2*pi/eta: x = {}, y = {}, x' = {}, y' = {}",
        found.minimal_period,
        orbit.periods,
        num(problem.params.speed_ratio),
        num(st.x),
        num(st.y),
        num(st.vx),
        num(st.vy)
    );
    let _ = writeln!(r, "multipliers:");
    for z in &orbit.multipliers {
        let _ = writeln!(r, "  {}", multiplier_text(z));
    }
    let _ = writeln!(
        r,
        "stable: {} (largest |λ| {:.6})",
        if orbit.stable() { "yes" } else { "no" },
        orbit.spectral_radius()
    );
    let _ = writeln!(
        r,
        "contact: {} entries over the orbit, contact fraction {:.4}; radius |q| {:.4} to {:.4}, distance z from the stator centre {:.4} to {:.4}",
        s.count(EventKind::Enter),
        s.contact_fraction(),
        s.min_radius,
        s.max_radius,
        s.min_distance,
        s.max_distance
    );
    if let Some(p) = &args.samples {
        let _ = writeln!(r, "wrote {}", p.display());
    }
    r
}
