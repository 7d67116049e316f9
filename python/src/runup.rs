//! Run-up and coast-down for Python (`rotor_rub.runup`): the CLI's speed programs (a run-up
//! program such as `paper-hysteresis`, a ramp from options, a profile file or an array of
//! (τ, η) points) on the variable-speed propagator, one row per forcing period and every switch,
//! the same numbers as `rotor-rub runup`'s files, and each branch's jumps.

use numpy::{IntoPyArray, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rotor_rub::speed::SpeedProfile;
use rotor_rub::variable_speed::{
    DEFAULT_SPEED_HOLDS, Revolution, Revolutions, SPEED_HOLDS_RANGE, SpeedDirection,
    VariableSpeedError, VariableSpeedOptions, VariableSpeedPropagator,
};
use rotor_rub::{Event, Method, Propagate, State};
use rotor_rub_cli::error::CliError;
use rotor_rub_cli::limits::fits_memory;
use rotor_rub_cli::options::{DefaultMethod, Survey};
use rotor_rub_cli::problem::ProblemArgs;
use rotor_rub_cli::runup::analysis::Branch;

use crate::args;
use crate::errors::{cli, input};
use crate::inputs::{self, KEYWORDS, MethodKeywords};
use crate::meta;
use crate::runs::{kind_code, states};
use crate::runup_speed::{Ramp, programs, speed_program};
use crate::watch::{self, Progress};

type Any<'a, 'py> = Option<&'a Bound<'py, PyAny>>;

/// The index of a speed direction in `rotor_rub.SPEED_DIRECTIONS` (up, down, hold).
fn direction_code(d: SpeedDirection) -> u8 {
    match d {
        SpeedDirection::Up => 0,
        SpeedDirection::Down => 1,
        SpeedDirection::Hold => 2,
    }
}

/// The error of a run that cannot start, as the CLI's `runup` reports it.
fn cannot_start(e: VariableSpeedError) -> CliError {
    match e {
        VariableSpeedError::Invalid(e) => CliError::propagation("", e),
        e => CliError::input(e.to_string()),
    }
}

/// What a run-up pass gathers.
struct Pass {
    rows: Vec<Revolution>,
    events: Vec<(Event, f64, u64, SpeedDirection)>,
    elapsed: f64,
}

/// Run-up and coast-down through resonance: rows per forcing period, every switch with the
/// speed it happened at, and each branch's jumps.
#[pyfunction]
#[pyo3(signature = (*, preset=None, config=None, from_speed=None, to_speed=None, rate=None,
    ramp_periods=None, settle=None, dwell=None, one_way=None, profile=None, profile_path=None,
    method=None, tol=None, contact_scheme=None, step=None, speed_holds=None,
    samples_per_period=None, max_work=None, progress=None, params=None))]
#[allow(clippy::too_many_arguments)]
pub fn runup<'py>(
    py: Python<'py>,
    preset: Option<&str>,
    config: Option<String>,
    from_speed: Any<'_, 'py>,
    to_speed: Any<'_, 'py>,
    rate: Any<'_, 'py>,
    ramp_periods: Any<'_, 'py>,
    settle: Any<'_, 'py>,
    dwell: Any<'_, 'py>,
    one_way: Any<'_, 'py>,
    profile: Option<PyReadonlyArray2<'py, f64>>,
    profile_path: Option<String>,
    method: Any<'_, 'py>,
    tol: Any<'_, 'py>,
    contact_scheme: Any<'_, 'py>,
    step: Any<'_, 'py>,
    speed_holds: Any<'_, 'py>,
    samples_per_period: Any<'_, 'py>,
    max_work: Any<'_, 'py>,
    progress: Any<'_, 'py>,
    params: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    let (program, rotor) = programs(preset)?;
    let config = inputs::path(config);
    let problem_args = ProblemArgs {
        preset: rotor.or((config.is_none()).then(|| program.rotor())),
        config,
        set: inputs::overrides(params)?,
    };
    let mut problem = problem_args.build_naming(&[], KEYWORDS).map_err(cli)?;
    let keywords = MethodKeywords {
        method,
        tol,
        contact_scheme,
        step,
    };
    let options = inputs::options(&keywords, Survey::METHOD)?;
    let speed_holds = match speed_holds.filter(|s| !s.is_none()) {
        None => DEFAULT_SPEED_HOLDS,
        Some(_) if options.method != Method::Analytic => {
            return Err(input(format!(
                "speed_holds applies only to method analytic, not to method {}",
                options.method.name()
            )));
        }
        Some(s) => {
            let n = args::count("speed_holds", s, 1)?;
            u32::try_from(n).map_err(|_| {
                input(format!(
                    "speed_holds: {n} is out of range: it must be in {SPEED_HOLDS_RANGE}"
                ))
            })?
        }
    };
    let options = VariableSpeedOptions {
        options,
        speed_holds,
    };
    let ramp = Ramp {
        from_speed,
        to_speed,
        rate,
        ramp_periods,
        settle,
        dwell,
        one_way,
    };
    let speed = speed_program(program, &ramp, profile.as_ref(), profile_path)?;
    let profile = SpeedProfile::new(&speed.points).map_err(|e| input(e.to_string()))?;
    problem.start_time = profile.start();
    let spp = samples_per_period.map_or(Ok(64), |s| args::count("samples_per_period", s, 8))?;
    let budget = inputs::budget(max_work)?;

    let mut propagator = VariableSpeedPropagator::new(&problem, profile, &options)
        .map_err(|e| cli(cannot_start(e)))?;
    let samples = u32::try_from(spp).unwrap_or(u32::MAX);
    let phase = problem.params.phase;
    let count = Revolutions::new(&mut propagator, profile, phase, samples).total();
    if count == 0 {
        return Err(input(
            "the speed program is shorter than one forcing period: nothing to tabulate",
        ));
    }
    let count_kept = fits_memory(
        "forcing periods",
        count,
        std::mem::size_of::<Revolution>() + 200,
    )
    .map_err(cli)?;
    budget
        .plan(
            "the forcing periods × samples_per_period",
            count.saturating_mul(spp),
        )
        .map_err(cli)?;
    let done = std::sync::Arc::new(std::sync::atomic::AtomicU64::new(0));
    let counted = std::sync::Arc::clone(&done);
    let progress_done: watch::Done =
        Box::new(move |_| counted.load(std::sync::atomic::Ordering::Relaxed) as f64);
    let progress = Progress::new(progress, count as f64);
    let pass = watch::on_this_thread(py, progress, progress_done, |watch| {
        let budget = budget.watched(watch);
        let mut tracker = budget.run(profile.start(), profile.end());
        let started = std::time::Instant::now();
        let mut rows = Vec::with_capacity(count_kept);
        let mut events = Vec::new();
        let mut cursor = profile.first_piece(phase);
        let mut pending = Vec::new();
        let mut revolutions = Revolutions::new(&mut propagator, profile, phase, samples);
        while let Some(row) = revolutions.next_with(|e| pending.push(*e)) {
            let row = row.map_err(|e| CliError::propagation("", e))?;
            for event in pending.drain(..) {
                tracker.switch(event.time)?;
                cursor = profile.piece_holding(cursor, event.time);
                events.push((
                    event,
                    cursor.speed_at(event.time),
                    row.index,
                    row.direction(),
                ));
            }
            done.store(row.index + 1, std::sync::atomic::Ordering::Relaxed);
            budget.check(row.end)?;
            rows.push(row);
        }
        // The switches after the last whole forcing period, in the partial one that has no row:
        // every switch of the run is in the events (a remainder within 1e-9 turns of a whole
        // turn was counted as that turn by `Revolutions`).
        let start = propagator.time();
        let phase_at = |t: f64| profile.piece_holding(cursor, t).phase_at(t);
        if phase_at(profile.end()) - phase_at(start) > 1e-9 * std::f64::consts::TAU {
            let speed_at = |t: f64| profile.piece_holding(cursor, t).speed_at(t);
            let direction = match speed_at(profile.end()) - speed_at(start) {
                c if c > 0.0 => SpeedDirection::Up,
                c if c < 0.0 => SpeedDirection::Down,
                _ => SpeedDirection::Hold,
            };
            while let Some(event) = propagator
                .advance(profile.end())
                .map_err(|e| CliError::propagation("", e))?
            {
                tracker.switch(event.time)?;
                cursor = profile.piece_holding(cursor, event.time);
                events.push((event, cursor.speed_at(event.time), count, direction));
            }
        }
        Ok(Pass {
            rows,
            events,
            elapsed: started.elapsed().as_secs_f64(),
        })
    })?;

    let out = PyDict::new(py);
    let r = &pass.rows;
    let column = |f: fn(&Revolution) -> f64| r.iter().map(f).collect::<Vec<f64>>();
    out.set_item(
        "direction",
        r.iter()
            .map(|x| direction_code(x.direction()))
            .collect::<Vec<u8>>()
            .into_pyarray(py),
    )?;
    out.set_item(
        "period",
        r.iter()
            .map(|x| x.index)
            .collect::<Vec<u64>>()
            .into_pyarray(py),
    )?;
    out.set_item("start", column(|x| x.start).into_pyarray(py))?;
    out.set_item("end", column(|x| x.end).into_pyarray(py))?;
    out.set_item("speed", column(|x| x.speed_ratio).into_pyarray(py))?;
    out.set_item("speed_change", column(|x| x.speed_change).into_pyarray(py))?;
    out.set_item("max_radius", column(|x| x.max_radius).into_pyarray(py))?;
    out.set_item("min_radius", column(|x| x.min_radius).into_pyarray(py))?;
    out.set_item(
        "contact_fraction",
        column(|x| x.contact_fraction).into_pyarray(py),
    )?;
    out.set_item("whirl", column(|x| x.whirl).into_pyarray(py))?;
    let whirl = |x: &Revolution| match x.whirl_direction() {
        rotor_rub::variable_speed::WhirlDirection::Forward => 0u8,
        rotor_rub::variable_speed::WhirlDirection::Backward => 1,
        rotor_rub::variable_speed::WhirlDirection::Mixed => 2,
    };
    out.set_item(
        "whirl_direction",
        r.iter().map(whirl).collect::<Vec<u8>>().into_pyarray(py),
    )?;
    out.set_item(
        "enters",
        r.iter()
            .map(|x| x.enters)
            .collect::<Vec<u32>>()
            .into_pyarray(py),
    )?;
    out.set_item(
        "exits",
        r.iter()
            .map(|x| x.exits)
            .collect::<Vec<u32>>()
            .into_pyarray(py),
    )?;
    let e = &pass.events;
    out.set_item(
        "event_time",
        e.iter()
            .map(|x| x.0.time)
            .collect::<Vec<f64>>()
            .into_pyarray(py),
    )?;
    out.set_item(
        "event_kind",
        e.iter()
            .map(|x| kind_code(x.0.kind))
            .collect::<Vec<u8>>()
            .into_pyarray(py),
    )?;
    out.set_item(
        "event_state",
        states(py, &e.iter().map(|x| x.0.state).collect::<Vec<State>>())?,
    )?;
    out.set_item(
        "event_speed",
        e.iter().map(|x| x.1).collect::<Vec<f64>>().into_pyarray(py),
    )?;
    out.set_item(
        "event_period",
        e.iter().map(|x| x.2).collect::<Vec<u64>>().into_pyarray(py),
    )?;
    out.set_item(
        "event_direction",
        e.iter()
            .map(|x| direction_code(x.3))
            .collect::<Vec<u8>>()
            .into_pyarray(py),
    )?;
    let jumps = Vec::new();
    let mut jumps: Vec<Bound<'py, PyDict>> = jumps;
    for direction in [SpeedDirection::Up, SpeedDirection::Down] {
        let branch = Branch::of(r, direction);
        for j in &branch.jumps {
            let d = PyDict::new(py);
            d.set_item("speed", j.speed_ratio)?;
            d.set_item("direction", direction.name())?;
            d.set_item("before", j.before)?;
            d.set_item("after", j.after)?;
            d.set_item("period", branch.rows.get(j.position).map(|x| x.index))?;
            jumps.push(d);
        }
    }
    out.set_item("jumps", jumps)?;
    out.set_item("program", speed.description)?;
    out.set_item("speed_holds", speed_holds)?;
    out.set_item("elapsed", pass.elapsed)?;
    let mut start = problem;
    start.params.speed_ratio = profile.first_piece(phase).speed_ratio;
    out.set_item("problem", meta::problem(py, &start, &options.options)?)?;
    Ok(out)
}
