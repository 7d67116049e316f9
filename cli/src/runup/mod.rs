//! `rotor-rub runup`: the rotor run up through its critical speed and back down (or either, or
//! along any speed profile), one row per forcing period — speed, the orbit's largest and
//! smallest radius, contact fraction, whirl, switches — and the amplitude against the speed for
//! both directions on one chart with the rubbing speeds shaded and the jumps marked
//! (`docs/MODEL.md` §14).

pub mod analysis;
mod figure;
mod files;
mod matrix;
mod matrix_report;
pub mod profile_csv;
pub mod program;
mod report;
mod steps;

use std::fmt::Write as _;
use std::path::PathBuf;
use std::time::Instant;

use rotor_rub::speed::{RunupPreset, SpeedProfile};
use rotor_rub::variable_speed::{
    DEFAULT_SPEED_HOLDS, Revolution, Revolutions, SPEED_HOLDS_RANGE, SpeedDirection,
    VariableSpeedError, VariableSpeedOptions, VariableSpeedPropagator,
};
use rotor_rub::{Method, Propagate, PropagationError};

use self::analysis::Branch;
use self::files::{RunEvent, events_beside, events_file, rows_file};
use self::program::{SpeedArgs, parse_program, program_help};
use crate::error::{CliError, Result};
use crate::limits::{LimitArgs, fits_memory, reserve};
use crate::options::{MethodArgs, Survey, at_least, describe, flagged};
use crate::output::{check_distinct, commit_all, ensure_parent};
use crate::plot;
use crate::problem::ProblemArgs;
use crate::stdio;

/// Run-up and coast-down through resonance.
#[derive(clap::Args, Debug)]
pub struct Args {
    #[arg(long, value_name = "NAME", default_value = "paper-hysteresis", value_parser = parse_program, help = program_help())]
    pub program: RunupPreset,

    #[command(flatten)]
    pub problem: ProblemArgs,

    /// A rotor from matrices (TOML or .npz, SI units: docs/MODEL_FILES.md) instead of the
    /// paper's model: a stepped run-up (the speed held over each step of --hold forcing periods,
    /// the matrices re-evaluated at each step's speed; the speed's change within a step is left
    /// out), --from and --to in rad/s (required; --program's rotor and ramp do not apply),
    /// --rate in rad/s², radii of the rub station in m. The ring with mass (stator_mass_ratio >
    /// 0) runs the same stepped run-up in η
    #[arg(long, value_name = "FILE", conflicts_with_all = ["preset", "config", "set"])]
    pub model: Option<PathBuf>,

    /// Forcing periods per held speed of the stepped run-up of a model file or the ring with
    /// mass, >= 1 [default: 1]
    #[arg(long, value_name = "N", value_parser = at_least(1))]
    pub hold: Option<u64>,

    #[command(flatten)]
    pub speed: SpeedArgs,

    #[command(flatten)]
    pub method: MethodArgs<Survey>,

    /// Held-speed steps per forcing period of --method analytic where the speed changes (the
    /// closed forms hold η and dη/dτ over each; error second order in the step) [default: 32]
    #[arg(long, value_name = "N", value_parser = at_least(1))]
    pub speed_holds: Option<u64>,

    /// Samples per forcing period for the radii (refined between samples) and the whirl
    #[arg(long, value_name = "N", default_value_t = 64, value_parser = at_least(8))]
    pub samples_per_period: u64,

    #[command(flatten)]
    pub limits: LimitArgs,

    /// Output CSV, one row per forcing period: direction (up, down, hold), period, start, end,
    /// speed_ratio (mean over the period), speed_change, max_radius, min_radius (|q|,
    /// clearances), contact_fraction, whirl (signed orbit area over π times its mean squared
    /// radius: +1 one forward circle), whirl_direction, enters, exits. The plot goes next to it
    /// (.svg, .png)
    #[arg(long, value_name = "FILE.csv", default_value = "out/runup.csv")]
    pub out: PathBuf,

    /// Every switch of the run: time, speed_ratio, period, direction, kind, x, y, vx, vy (those
    /// after the last whole forcing period carry the next period's number, which --out has no
    /// row for) [default: <out's stem>-events.csv next to --out]
    #[arg(long, value_name = "FILE.csv")]
    pub events: Option<PathBuf>,

    /// Do not draw the plot
    #[arg(long)]
    pub no_plot: bool,
}

/// The error of a run that cannot start: the runtime's message, exit 2 (bad input) unless the
/// method failed at the start state.
fn cannot_start(e: VariableSpeedError) -> CliError {
    match e {
        VariableSpeedError::Invalid(e) => CliError::propagation("", e),
        e => CliError::input(e.to_string()),
    }
}

/// The held-speed steps per period (an input error for another method or out of range, naming
/// `--speed-holds`).
fn speed_holds(args: &Args) -> Result<u32> {
    match args.speed_holds {
        None => Ok(DEFAULT_SPEED_HOLDS),
        Some(_) if args.method.method != Method::Analytic => Err(CliError::input(format!(
            "--speed-holds applies only to --method analytic, not to --method {}",
            args.method.method.name()
        ))),
        Some(n) if SPEED_HOLDS_RANGE.contains(n as f64) => Ok(n as u32),
        Some(n) => Err(flagged(
            PropagationError::InvalidOption {
                method: Method::Analytic.name(),
                what: "speed_holds",
                value: n as f64,
                valid: SPEED_HOLDS_RANGE,
            },
            &[("speed_holds", "--speed-holds")],
        )),
    }
}

/// Run the command.
pub fn run(args: &Args) -> Result<()> {
    if let Some(path) = &args.model {
        let spec = crate::model_file::read(path)?;
        let subject = crate::model_file::Subject::file(spec, path);
        let program = matrix::model_program(args)?;
        return matrix::run(args, &subject, &program, Some(path));
    }
    let mut problem_args = args.problem.clone();
    if problem_args.preset.is_none() && problem_args.config.is_none() {
        problem_args.preset = Some(args.program.rotor());
    }
    let mut problem = problem_args.build()?;
    if problem.params.stator_mass_ratio > 0.0 {
        let speed = args.speed.program(args.program)?;
        let program = matrix::Program {
            points: speed
                .points
                .iter()
                .map(|p| (p.time, p.speed_ratio))
                .collect(),
            description: format!(
                "{}, stepped: {} forcing period(s) per held speed",
                speed.description,
                args.hold.unwrap_or(1)
            ),
        };
        problem.start_time = program.span().0;
        let subject = crate::model_file::Subject::Ring(problem);
        return matrix::run(args, &subject, &program, None);
    }
    if args.hold.is_some() {
        return Err(CliError::input(
            "--hold applies only to the stepped run-up of a model file (--model) or the stator ring with mass (stator_mass_ratio > 0)",
        ));
    }
    let options = VariableSpeedOptions {
        options: args.method.options()?,
        speed_holds: speed_holds(args)?,
    };
    let speed = args.speed.program(args.program)?;
    let profile = SpeedProfile::new(&speed.points).map_err(|e| CliError::input(e.to_string()))?;
    problem.start_time = profile.start();

    let events_path = args
        .events
        .clone()
        .unwrap_or_else(|| events_beside(&args.out));
    let [svg, png] = plot::beside(&args.out);
    let mut outputs = vec![
        ("--out", args.out.as_path()),
        ("--events", events_path.as_path()),
    ];
    if !args.no_plot {
        outputs.extend([("the plot", svg.as_path()), ("the plot", png.as_path())]);
    }
    let mut inputs = args.problem.input_files();
    if let Some(profile) = &args.speed.profile {
        inputs.push(("--profile", profile.as_path()));
    }
    check_distinct(&outputs, &inputs)?;

    let mut propagator =
        VariableSpeedPropagator::new(&problem, profile, &options).map_err(cannot_start)?;
    let samples = u32::try_from(args.samples_per_period).unwrap_or(u32::MAX);
    let mut revolutions = Revolutions::new(&mut propagator, profile, problem.params.phase, samples);
    let count = revolutions.total();
    if count == 0 {
        return Err(CliError::input(
            "the speed program is shorter than one forcing period: nothing to tabulate",
        ));
    }
    fits_memory(
        "forcing periods",
        count,
        std::mem::size_of::<Revolution>() + 200,
    )?;
    let budget = args.limits.budget();
    budget.plan(
        "the forcing periods × --samples-per-period",
        count.saturating_mul(args.samples_per_period),
    )?;
    let mut tracker = budget.run(profile.start(), profile.end());

    let started = Instant::now();
    let bar = stdio::progress(
        count,
        "{bar:40} {pos}/{len} forcing periods, η = {msg}, {elapsed} elapsed, ETA {eta}",
    );
    let mut rows = Vec::new();
    let mut events = Vec::new();
    let mut cursor = profile.first_piece(problem.params.phase);
    let mut pending = Vec::new();
    while let Some(row) = revolutions.next_with(|e| pending.push(*e)) {
        let row = row.map_err(|e| CliError::propagation("", e))?;
        for event in pending.drain(..) {
            tracker.switch(event.time)?;
            cursor = profile.piece_holding(cursor, event.time);
            reserve(&mut events, 1, "switches kept")?;
            events.push(RunEvent {
                event,
                speed_ratio: cursor.speed_at(event.time),
                period: row.index,
                direction: row.direction(),
            });
        }
        bar.set_message(format!("{:.3}", row.speed_ratio));
        bar.inc(1);
        reserve(&mut rows, 1, "forcing periods")?;
        rows.push(row);
    }
    bar.finish_and_clear();
    // The switches after the last whole forcing period, in the partial one the per-period file
    // has no row for: the events file holds every switch of the run. A remainder within
    // rounding of a whole turn (less than 1e-9 turns) was counted as that turn by `Revolutions`.
    let start = propagator.time();
    let phase_at = |t: f64| profile.piece_holding(cursor, t).phase_at(t);
    if phase_at(profile.end()) - phase_at(start) > 1e-9 * std::f64::consts::TAU {
        let speed_at = |t: f64| profile.piece_holding(cursor, t).speed_at(t);
        let change = speed_at(profile.end()) - speed_at(start);
        let direction = if change > 0.0 {
            SpeedDirection::Up
        } else if change < 0.0 {
            SpeedDirection::Down
        } else {
            SpeedDirection::Hold
        };
        while let Some(event) = propagator
            .advance(profile.end())
            .map_err(|e| CliError::propagation("", e))?
        {
            tracker.switch(event.time)?;
            cursor = profile.piece_holding(cursor, event.time);
            reserve(&mut events, 1, "switches kept")?;
            events.push(RunEvent {
                event,
                speed_ratio: cursor.speed_at(event.time),
                period: count,
                direction,
            });
        }
    }
    let elapsed = started.elapsed();

    let up = Branch::of(&rows, SpeedDirection::Up);
    let down = Branch::of(&rows, SpeedDirection::Down);
    // Directories are made only once the run has succeeded.
    ensure_parent(&args.out)?;
    ensure_parent(&events_path)?;
    let mut files = vec![
        rows_file(&args.out, &rows)?,
        events_file(&events_path, &events)?,
    ];
    if !args.no_plot {
        let figure = figure::figure(
            &problem,
            &speed.description,
            &describe(&options.options),
            [&up, &down],
        );
        files.extend(plot::render(&figure, &svg, &png)?);
    }
    commit_all(files)?;

    let report = report::summary(&speed.description, &options, [&up, &down]);
    report_files(
        report,
        args,
        (rows.len(), events.len(), elapsed),
        &events_path,
        [&svg, &png],
    )
}

/// The end of a run-up's report: its size and time, and the files written (the planar and the
/// matrix run-up alike); printed.
fn report_files(
    mut report: String,
    args: &Args,
    (periods, switches, elapsed): (usize, usize, std::time::Duration),
    events_path: &std::path::Path,
    [svg, png]: [&std::path::Path; 2],
) -> Result<()> {
    let _ = writeln!(
        report,
        "{periods} forcing periods, {switches} switches, run time {:.2} s",
        elapsed.as_secs_f64()
    );
    let _ = writeln!(
        report,
        "wrote {} and {}",
        args.out.display(),
        events_path.display()
    );
    if !args.no_plot {
        let _ = writeln!(
            report,
            "plot written to {} and {}",
            svg.display(),
            png.display()
        );
    }
    stdio::out(&report)
}
