//! `runup` on a matrix model (a model file, SI, or the paper's rotor with a stator ring of
//! mass): a **stepped** run-up. The speed program is followed one step of `--hold` forcing
//! periods at a time; over a step the speed is held at the program's speed at the step's middle,
//! the model (the forcing m e Ω² e^{iθ}, the gyroscopic term Ω G and, when a model file lists
//! them, C and K) is stated at that speed and run exactly by the matrix methods, and the next
//! step starts from the state and the forcing angle θ where this one ended (both continuous).
//!
//! What it leaves out: the speed's change within a step (the unbalance's tangential term
//! −i m e Ω' e^{iθ} and the ramp of Ω inside a step). Its error is of the order of the speed
//! change per step relative to the speed; a slow ramp with `--hold 1` follows the continuous
//! run-up closely (the tests compare it with the planar model's exact variable-speed run on the
//! Jeffcott rotor written as matrices).

use std::path::Path;
use std::time::Instant;

use rotor_rub::EventKind;
use rotor_rub::variable_speed::{Revolution, SpeedDirection};

use super::analysis::Branch;
use super::matrix_report::{figure, summary};
pub use super::steps::{Program, model_program};
use super::{Args, report_files};
use crate::error::{CliError, Result};
use crate::limits::fits_memory;
use crate::model_file::{Segment, Subject, orbit_indices, orbit_state, planar_only};
use crate::output::{CsvOut, check_distinct, commit_all, ensure_parent};
use crate::plot;
use crate::stdio;

/// One forcing period's sums.
struct Period {
    index: u64,
    start: f64,
    end: f64,
    speed: f64,
    change: f64,
    radii: (f64, f64),
    contact: f64,
    whirl: f64,
    enters: u32,
    exits: u32,
}

/// The signed area of a closed polygon about its mean over π times its mean squared distance
/// from the mean (+1: one forward circle).
fn whirl(points: &[(f64, f64)]) -> f64 {
    let n = points.len() as f64;
    if points.len() < 3 {
        return 0.0;
    }
    let (mx, my) = points
        .iter()
        .fold((0.0, 0.0), |(a, b), p| (a + p.0 / n, b + p.1 / n));
    let spread: f64 = points
        .iter()
        .map(|p| (p.0 - mx).powi(2) + (p.1 - my).powi(2))
        .sum::<f64>()
        / n;
    let area: f64 = points
        .iter()
        .zip(points.iter().cycle().skip(1))
        .map(|(a, b)| 0.5 * ((a.0 - mx) * (b.1 - my) - (b.0 - mx) * (a.1 - my)))
        .sum();
    if spread > 0.0 {
        area / (std::f64::consts::PI * spread)
    } else {
        0.0
    }
}

/// Run the stepped run-up of `subject` along `program`.
pub fn run(args: &Args, subject: &Subject, program: &Program, model: Option<&Path>) -> Result<()> {
    if args.speed_holds.is_some() {
        return Err(planar_only("--speed-holds", subject));
    }
    let options = args.method.options()?;
    subject.check(&options)?;
    let hold = args.hold.unwrap_or(1);
    let per_period = args.samples_per_period;
    let (t_start, t_end) = program.span();
    // The number of forcing periods at the slowest speed bounds the rows.
    let slowest = program
        .points
        .iter()
        .map(|p| p.1)
        .fold(f64::INFINITY, f64::min);
    let most = ((t_end - t_start) * slowest / std::f64::consts::TAU).ceil() as u64 + 1;
    let biggest = most.max(
        ((t_end - t_start) * program.points.iter().map(|p| p.1).fold(0.0, f64::max)
            / std::f64::consts::TAU)
            .ceil() as u64
            + 1,
    );
    fits_memory("forcing periods", biggest, 200)?;
    let budget = args.limits.budget();
    budget.plan(
        "the forcing periods × --samples-per-period",
        biggest.saturating_mul(per_period),
    )?;
    let events_path = args
        .events
        .clone()
        .unwrap_or_else(|| super::files::events_beside(&args.out));
    let [svg, png] = plot::beside(&args.out);
    let mut outputs = vec![
        ("--out", args.out.as_path()),
        ("--events", events_path.as_path()),
    ];
    if !args.no_plot {
        outputs.extend([("the plot", svg.as_path()), ("the plot", png.as_path())]);
    }
    let mut inputs = args.problem.input_files();
    if let Some(m) = model {
        inputs.push(("--model", m));
    }
    check_distinct(&outputs, &inputs)?;

    let started = Instant::now();
    let orbit = orbit_indices(subject);
    let clearance = subject.clearance();
    let columns = subject.columns();
    // Every step on one large stack (a model file's statement needs it; one thread for all).
    let stepped = crate::model_file::on_large_stack(|| -> Result<_> {
        let mut tracker = budget.run(t_start, t_end);
        let mut periods: Vec<Period> = Vec::new();
        let mut events: Vec<(f64, f64, u64, EventKind, Vec<f64>)> = Vec::new();
        let mut state: Option<Vec<f64>> = None;
        // The forcing angle θ at t (the subject's θ = speed·t + φ0 at the start).
        let mut angle = subject.phase() + program.speed_at(t_start) * t_start;
        let mut t = t_start;
        let mut index = 0u64;
        let tau = std::f64::consts::TAU;
        let bar = stdio::progress(biggest, "{bar:40} {pos} forcing periods, {elapsed} elapsed");
        loop {
            let first = program.speed_at(t);
            let speed = program.speed_at(t + hold as f64 * 0.5 * tau / first);
            let period = tau / speed;
            let step_end = t + hold as f64 * period;
            if step_end > t_end + 1e-9 * period {
                break;
            }
            // θ = speed·t + φ continues the angle reached at t.
            let phase = (angle - speed * t).rem_euclid(tau);
            let held = subject.at_speed(speed, phase);
            let count = (hold * per_period) as usize;
            // The step's start, then `per_period` samples per forcing period (each period's
            // polygon closes on the next period's first sample).
            let times: Vec<f64> = (0..=count)
                .map(|j| t + period * j as f64 / per_period as f64)
                .collect();
            let base = index;
            let mut kinds: Vec<(f64, EventKind)> = Vec::new();
            let segment = Segment {
                start: state.as_deref().map(|y| (t, y)),
                times: &times,
            };
            let mut step_events = Vec::new();
            let (table, end_state) =
                held.run(&options, segment, &mut tracker, |time, kind, row| {
                    step_events.push((time, kind, row.to_vec()));
                    Ok(())
                })?;
            for (time, kind, row) in step_events {
                let k = base + ((time - t) / period).floor().clamp(0.0, hold as f64 - 1.0) as u64;
                kinds.push((time, kind));
                events.push((time, speed, k, kind, row));
            }
            let start_regime_in_contact = table.regimes.first().is_some_and(|r| r.in_contact());
            let rows: Vec<&[f64]> = table.rows().collect();
            let mut in_contact = start_regime_in_contact;
            for p in 0..hold {
                let (p0, p1) = (t + p as f64 * period, t + (p + 1) as f64 * period);
                let lo = (p * per_period) as usize;
                let hi = lo + per_period as usize;
                let pts: Vec<(f64, f64)> = rows
                    .get(lo..=hi)
                    .unwrap_or(&[])
                    .iter()
                    .map(|r| {
                        let s = orbit_state(r, &orbit, clearance);
                        (s.x * clearance, s.y * clearance)
                    })
                    .collect();
                let radius = |q: &(f64, f64)| q.0.hypot(q.1);
                let max_r = pts.iter().map(radius).fold(0.0, f64::max);
                let min_r = pts.iter().map(radius).fold(f64::INFINITY, f64::min);
                let mut contact = 0.0;
                let mut since = p0;
                let (mut enters, mut exits) = (0u32, 0u32);
                for &(time, kind) in kinds.iter().filter(|(tt, _)| *tt >= p0 && *tt < p1) {
                    match kind {
                        EventKind::Enter => {
                            enters += 1;
                            in_contact = true;
                            since = time;
                        }
                        EventKind::Exit => {
                            exits += 1;
                            if in_contact {
                                contact += time - since;
                            }
                            in_contact = false;
                        }
                        _ => {}
                    }
                }
                if in_contact {
                    contact += p1 - since.max(p0);
                }
                let closed: Vec<(f64, f64)> = pts
                    .iter()
                    .take(pts.len().saturating_sub(1))
                    .copied()
                    .collect();
                periods.push(Period {
                    index: base + p,
                    start: p0,
                    end: p1,
                    speed,
                    change: program.speed_at(p1) - program.speed_at(p0),
                    radii: (max_r, if min_r.is_finite() { min_r } else { 0.0 }),
                    contact: (contact / (p1 - p0)).clamp(0.0, 1.0),
                    whirl: whirl(&closed),
                    enters,
                    exits,
                });
                bar.inc(1);
            }
            angle = phase + speed * step_end;
            state = Some(end_state);
            t = step_end;
            index += hold;
        }
        bar.finish_and_clear();
        Ok((periods, events))
    });
    let (periods, events) = stepped?;
    if periods.is_empty() {
        return Err(CliError::input(
            "the speed program is shorter than one step of --hold forcing periods: nothing to tabulate",
        ));
    }
    let elapsed = started.elapsed();
    let rows: Vec<Revolution> = periods
        .iter()
        .map(|p| Revolution {
            index: p.index,
            start: p.start,
            end: p.end,
            speed_ratio: p.speed,
            speed_change: p.change,
            max_radius: p.radii.0,
            min_radius: p.radii.1,
            contact_fraction: p.contact,
            whirl: p.whirl,
            enters: p.enters,
            exits: p.exits,
        })
        .collect();
    let up = Branch::of(&rows, SpeedDirection::Up);
    let down = Branch::of(&rows, SpeedDirection::Down);
    let file = matches!(subject, Subject::File { .. });
    ensure_parent(&args.out)?;
    ensure_parent(&events_path)?;
    let speed_name = if file { "speed" } else { "speed_ratio" };
    let mut header = super::files::ROWS_HEADER.to_vec();
    if let Some(h) = header.get_mut(4) {
        *h = speed_name;
    }
    let rows_out = super::files::rows_file_with(&args.out, &header, &rows)?;
    let time_name = if file { "t" } else { "tau" };
    let ev_header: Vec<&str> = [time_name, speed_name, "period", "direction", "kind"]
        .into_iter()
        .chain(columns.iter().map(String::as_str))
        .collect();
    let mut ev = CsvOut::create(&events_path, &ev_header)?;
    for (time, speed, k, kind, row) in &events {
        let direction = rows
            .iter()
            .find(|r| r.index == *k)
            .map_or("hold", |r| r.direction().name());
        ev.record(
            [
                format!("{time:?}"),
                format!("{speed:?}"),
                k.to_string(),
                direction.to_string(),
                kind.name().to_string(),
            ]
            .into_iter()
            .chain(row.iter().map(|x| format!("{x:?}"))),
        )?;
    }
    let mut files = vec![rows_out, ev.finish()?];
    if !args.no_plot {
        let figure = figure(subject, program, &options, [&up, &down]);
        files.extend(plot::render(&figure, &svg, &png)?);
    }
    commit_all(files)?;
    let report = summary(subject, program, &options, [&up, &down]);
    report_files(
        report,
        args,
        (rows.len(), events.len(), elapsed),
        &events_path,
        [&svg, &png],
    )
}
