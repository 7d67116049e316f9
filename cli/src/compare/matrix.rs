//! `compare` on a model file or the ring with mass: the analytic method (the matrix model's
//! exact free flight with Taylor contact) against a numerical reference on the whole system,
//! switch by switch; the plot draws the rub station's relative orbit (the ring: the rotor's) in
//! clearances with the clearance circle.
//!
//! Switches are matched as the paper model's are (same kind, less than `MATCH_GAP` apart), on
//! the clock of the forcing angle Ωt for a model file (so the gap is 0.1 rad of the forcing at
//! any speed) and on τ for the ring; the table gives times in s (τ) and |Δstate| over the
//! station's (the rotor's) planar state in clearances.

use std::fmt::Write as _;

use rotor_rub::{Event, Method, State};

use super::{Args, legend, orbit};
use crate::analysis::switches::{MATCH_GAP, Matching};
use crate::error::{CliError, Result, num};
use crate::model_file::{Segment, Subject, orbit_indices, orbit_state};
use crate::options::reference_options;
use crate::output::{CsvOut, check_distinct, commit_all, ensure_dir};
use crate::plot::orbit::{OrbitFigure, Panel};
use crate::plot::{self, ANALYTIC, REFERENCE};
use crate::stdio;
use crate::trajectory::{dense_count, dense_times};

fn fmt_opt(x: Option<f64>) -> String {
    x.map_or_else(|| "-".to_string(), |v| format!("{v:.3e}"))
}

/// Compare on a matrix model (`model`: the file's path, an input the outputs must not be).
pub fn run(args: &Args, subject: &Subject, model: Option<&std::path::Path>) -> Result<()> {
    let period = subject.period();
    let start = subject.start_time();
    let end = match (args.time.t_end, args.time.periods) {
        (Some(t), _) => t,
        (None, n) => start + n.unwrap_or(20.0) * period,
    };
    if end <= start {
        return Err(CliError::input(format!(
            "--t-end {} is not after the start {}",
            num(end),
            num(start)
        )));
    }
    let analytic = args.scheme.cli_options(Method::Analytic)?;
    let reference = reference_options(args.reference, args.reference_tol)?;
    subject.check(&analytic)?;
    subject.check(&reference)?;
    let periods = (end - start) / period;
    if !(0.0..periods).contains(&args.plot_from) {
        return Err(CliError::input(format!(
            "--plot-from {} is outside the run: it must be in [0, {}) (forcing periods)",
            num(args.plot_from),
            num(periods)
        )));
    }
    let from = start + args.plot_from * period;
    let count = dense_count(from, end, period, 100);
    crate::limits::fits_memory(
        "orbit samples (100 per plotted forcing period, two runs)",
        count,
        16 * subject.columns().len(),
    )?;
    let budget = args.limits.budget();
    budget.plan("orbit samples (two runs)", count.saturating_mul(2))?;
    let csv_path = args.out_dir.join("compare.csv");
    let [svg_path, png_path] = plot::beside(&csv_path);
    let mut inputs = args.problem.input_files();
    if let Some(m) = model {
        inputs.push(("--model", m));
    }
    check_distinct(
        &[
            ("--out-dir", csv_path.as_path()),
            ("--out-dir", svg_path.as_path()),
            ("--out-dir", png_path.as_path()),
        ],
        &inputs,
    )?;
    let times: Vec<f64> = dense_times(from, end, period, 100).collect();
    let orbit_at = orbit_indices(subject);
    let clearance = subject.clearance();
    // The matching's clock: the forcing angle Ωt for a model file, τ for the ring.
    let clock = match subject {
        Subject::File { spec, .. } => spec.speed,
        Subject::Ring(_) => 1.0,
    };
    let pass = |options: &rotor_rub::Options| -> Result<_> {
        let clocked = std::time::Instant::now();
        let mut events = Vec::new();
        let mut tracker = budget.run(start, end);
        let (table, _) = subject.run(
            options,
            Segment {
                start: None,
                times: &times,
            },
            &mut tracker,
            |time, kind, row| {
                events.push(Event {
                    time: time * clock,
                    kind,
                    state: orbit_state(row, &orbit_at, clearance),
                });
                Ok(())
            },
        )?;
        let samples: Vec<rotor_rub::Sample> = table
            .rows()
            .zip(&table.times)
            .zip(&table.regimes)
            .map(|((row, &time), &regime)| rotor_rub::Sample {
                time,
                state: orbit_state(row, &orbit_at, clearance),
                regime,
            })
            .collect();
        Ok((events, samples, clocked.elapsed()))
    };
    let (events_a, samples_a, time_a) = pass(&analytic)?;
    let (events_r, samples_r, time_r) = pass(&reference)?;
    let matching = Matching::new(&events_a, &events_r, end * clock);
    let (name_a, name_r) = ("analytic", args.reference.name());
    let unit = if clock == 1.0 { "τ" } else { "s" };
    let mut report = String::new();
    let _ = writeln!(
        report,
        "{:>5}  {:<5}  {:>22}  {:>22}  {:>10}  {:>10}",
        "#",
        "kind",
        name_a,
        name_r,
        format!("Δt ({unit})"),
        "|Δstate|"
    );
    let dt = |p: &crate::analysis::switches::Pair| p.dt().map(|d| d / clock);
    for (i, pair) in matching.pairs.iter().enumerate() {
        let kind = pair.a.or(pair.b).map_or("", |e| e.kind.name());
        let at =
            |e: Option<Event>| e.map_or_else(|| "-".to_string(), |e| (e.time / clock).to_string());
        let _ = writeln!(
            report,
            "{:>5}  {:<5}  {:>22}  {:>22}  {:>10}  {:>10}",
            i + 1,
            kind,
            at(pair.a),
            at(pair.b),
            fmt_opt(dt(pair)),
            fmt_opt(pair.dstate())
        );
    }
    let _ = writeln!(
        report,
        "switches: {name_a} {}, {name_r} {}; matched {} (same kind, less than {MATCH_GAP} {} apart), unmatched {}",
        events_a.len(),
        events_r.len(),
        matching.matched(),
        if clock == 1.0 { "τ" } else { "rad of Ωt" },
        matching.unmatched()
    );
    let _ = writeln!(
        report,
        "largest differences: switch time {} {unit}, station state at a switch {} clearances",
        fmt_opt(matching.max_dt().map(|d| d / clock)),
        fmt_opt(matching.max_dstate())
    );
    let _ = writeln!(
        report,
        "run time: {name_a} {:.3} ms, {name_r} {:.3} ms",
        time_a.as_secs_f64() * 1e3,
        time_r.as_secs_f64() * 1e3
    );
    ensure_dir(&args.out_dir)?;
    let time_name = if clock == 1.0 { "tau" } else { "t" };
    let header = [
        "kind".to_string(),
        format!("{time_name}_analytic"),
        format!("{time_name}_reference"),
        format!("d{time_name}"),
        "dstate".to_string(),
    ];
    let header: Vec<&str> = header.iter().map(String::as_str).collect();
    let mut csv = CsvOut::create(&csv_path, &header)?;
    for pair in &matching.pairs {
        let kind = pair.a.or(pair.b).map_or("", |e| e.kind.name());
        csv.row((
            kind,
            pair.a.map(|e| e.time / clock),
            pair.b.map(|e| e.time / clock),
            dt(pair),
            pair.dstate(),
        ))?;
    }
    // The orbit plot's events on the run's own clock.
    let unclocked = |events: &[Event<State>]| -> Vec<Event<State>> {
        events
            .iter()
            .map(|e| Event {
                time: e.time / clock,
                ..*e
            })
            .collect()
    };
    let figure = OrbitFigure {
        title: format!(
            "{name_a} vs {name_r} ({}): {}, {time_name} from {} to {}",
            match subject {
                Subject::File { .. } => "the rub station, clearances",
                Subject::Ring(_) => "the rotor, ring with mass",
            },
            subject.speed_label(),
            num(from),
            num(end)
        ),
        legend: legend(&analytic, &reference),
        panels: vec![Panel {
            title: String::new(),
            offset: subject.offset(),
            orbits: vec![
                orbit(
                    &samples_a,
                    &unclocked(&events_a),
                    from..=end,
                    ANALYTIC,
                    false,
                ),
                orbit(
                    &samples_r,
                    &unclocked(&events_r),
                    from..=end,
                    REFERENCE,
                    true,
                ),
            ],
        }],
        columns: 1,
        panel: (1100, 1000),
    };
    let [svg_file, png_file] = plot::render(&figure, &svg_path, &png_path)?;
    commit_all([csv.finish()?, svg_file, png_file])?;
    let _ = writeln!(
        report,
        "wrote {}, {}, {}",
        csv_path.display(),
        svg_path.display(),
        png_path.display()
    );
    stdio::out(&report)
}
