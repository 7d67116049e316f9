//! `rotor-rub simulate`: one run, its switches and uniform samples as CSV, a summary on stdout.

use std::cell::Cell;
use std::fmt::Write as _;
use std::path::PathBuf;

use rotor_rub::{EventKind, Params, Regime, State};

use crate::error::{CliError, Result, num};
use crate::limits::LimitArgs;
use crate::options::{MethodArgs, SingleRun, TimeArgs, describe};
use crate::output::{CsvOut, check_distinct, commit_all};
use crate::problem::ProblemArgs;
use crate::stdio;
use crate::trajectory::{self, uniform_times};

/// Header of the events file.
pub const EVENTS_HEADER: [&str; 6] = ["tau", "kind", "x", "y", "vx", "vy"];
/// Header of the samples file (`regime`: free, contact or rolling, after the original columns).
pub const SAMPLES_HEADER: [&str; 7] = ["tau", "x", "y", "vx", "vy", "contact", "regime"];

/// Simulate one parameter set from τ = 0 (the stable contract for scripts).
#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    pub problem: ProblemArgs,

    /// A rotor from matrices (TOML or .npz, SI units: docs/MODEL_FILES.md) instead of the
    /// paper's model: --t-end in seconds, --periods of 2π/Ω, CSV columns named after its DOFs
    #[arg(long, value_name = "FILE", conflicts_with_all = ["preset", "config", "set"])]
    pub model: Option<PathBuf>,

    #[command(flatten)]
    pub time: TimeArgs,

    #[command(flatten)]
    pub method: MethodArgs<SingleRun>,

    #[command(flatten)]
    pub limits: LimitArgs,

    /// Write every switch, in order, as CSV with header tau,kind,x,y,vx,vy (kind is `enter` or
    /// `exit`; with friction also `reverse`, `roll` or `slip`)
    #[arg(long, value_name = "FILE.csv")]
    pub events: Option<PathBuf>,

    /// Write uniform samples as CSV with header tau,x,y,vx,vy,contact,regime (contact 0 or 1;
    /// regime free, contact or rolling) at the times t_i = t_end·i/(N−1), i = 0..N−1
    #[arg(long, value_name = "FILE.csv")]
    pub samples: Option<PathBuf>,

    /// Number N of samples written to --samples, an integer >= 2 [default: 1001]
    #[arg(long, value_name = "N", value_parser = crate::options::at_least(2), requires = "samples")]
    pub sample_count: Option<u64>,
}

/// Run the command.
pub fn run(args: &Args) -> Result<()> {
    if let Some(path) = &args.model {
        return crate::model_file::simulate(&crate::model_file::SimulateModel {
            path,
            options: args.method.options()?,
            t_end: args.time.t_end,
            periods: args.time.periods,
            events: args.events.as_deref(),
            samples: args.samples.as_deref(),
            sample_count: args
                .samples
                .as_ref()
                .map_or(0, |_| args.sample_count.unwrap_or(1001) as usize),
        });
    }
    let problem = args.problem.build()?;
    let options = args.method.options()?;
    let end = args.time.end_time(&problem.params);
    let mut outputs = Vec::new();
    if let Some(p) = &args.events {
        outputs.push(("--events", p.as_path()));
    }
    if let Some(p) = &args.samples {
        outputs.push(("--samples", p.as_path()));
    }
    check_distinct(&outputs, &args.problem.input_files())?;
    let count = if args.samples.is_some() {
        args.sample_count.unwrap_or(1001)
    } else {
        0
    };
    let budget = args.limits.budget();
    budget.plan("--sample-count", count)?;
    if problem.params.stator_mass_ratio > 0.0 {
        // A stator ring with mass: the n = 4 matrix model (issue 28).
        return crate::model_file::simulate_ring_command(
            &problem,
            &options,
            end,
            usize::try_from(count).map_err(|_| CliError::input("--sample-count is too large"))?,
            args.events.as_deref(),
            args.samples.as_deref(),
        );
    }
    let propagator = trajectory::start(&problem, &options)?;
    let mut events_out = args
        .events
        .as_deref()
        .map(|p| CsvOut::create(p, &EVENTS_HEADER))
        .transpose()?;
    let mut samples_out = args
        .samples
        .as_deref()
        .map(|p| CsvOut::create(p, &SAMPLES_HEADER))
        .transpose()?;
    let count =
        usize::try_from(count).map_err(|_| CliError::input("--sample-count is too large"))?;
    let mut tracker = budget.run(problem.start_time, end);
    // Under friction the whirl rate is measured on a grid of its own (64 points per forcing
    // period and per natural period), merged with the requested samples: sampling never changes
    // a run, and only the requested ones are written. Both are streamed: no count needs memory.
    let friction = problem.params.friction_coefficient > 0.0;
    let grid_step = problem.params.forcing_period().min(std::f64::consts::TAU) / 64.0;
    let grid_count = if friction {
        let n = ((end - problem.start_time) / grid_step).floor() as u64;
        budget.plan("whirl samples", n)?;
        n
    } else {
        0
    };
    let grid = (1..=grid_count).map(|k| problem.start_time + k as f64 * grid_step);
    let times = merged(uniform_times(problem.start_time, end, count), grid);
    // Whether the sample being handed over was requested (set as its time is drawn, which
    // `trajectory::run` does just before it hands over that sample).
    let requested = Cell::new(false);
    let mut whirl = Whirl::new(&problem.params, problem.start_time, &problem.initial, end);
    let pass = trajectory::run(
        propagator,
        end,
        times.map(|(t, user)| {
            requested.set(user);
            t
        }),
        &mut tracker,
        false,
        |e| match &mut events_out {
            Some(out) => {
                let s = e.state;
                out.row((e.time, e.kind.name(), s.x, s.y, s.vx, s.vy))
            }
            None => Ok(()),
        },
        |sample| {
            whirl.add(sample.time, &sample.state);
            match &mut samples_out {
                Some(out) if requested.get() => {
                    let s = sample.state;
                    let contact = u8::from(sample.regime.in_contact());
                    let regime = sample.regime.name();
                    out.row((sample.time, s.x, s.y, s.vx, s.vy, contact, regime))
                }
                _ => Ok(()),
            }
        },
    )?;
    whirl.add(end, &pass.last.state);
    let files = [events_out, samples_out]
        .into_iter()
        .flatten()
        .map(CsvOut::finish)
        .collect::<Result<Vec<_>>>()?;
    commit_all(files)?;

    let mut report = String::new();
    let s = pass.last.state;
    let _ = writeln!(
        report,
        "method: {}; τ from {} to {} ({} forcing periods)",
        describe(&options),
        num(problem.start_time),
        num(end),
        num((end - problem.start_time) / problem.params.forcing_period())
    );
    let _ = writeln!(
        report,
        "switches: {} ({} contact starts, {} contact ends)",
        pass.switches,
        pass.count(EventKind::Enter),
        pass.count(EventKind::Exit)
    );
    let _ = writeln!(report, "contact fraction: {}", pass.contact_fraction);
    if friction {
        let _ = writeln!(
            report,
            "friction: {} slip reversals, {} rolling starts, {} rolling ends",
            pass.count(EventKind::Reverse),
            pass.count(EventKind::Roll),
            pass.count(EventKind::Slip)
        );
        let span = end - problem.start_time;
        let [free, slipping, rolling] = pass.time_in;
        let _ = writeln!(
            report,
            "time free {} ({:.1}%), slipping {} ({:.1}%), rolling {} ({:.1}%)",
            num(free),
            100.0 * free / span,
            num(slipping),
            100.0 * slipping / span,
            num(rolling),
            100.0 * rolling / span
        );
        let eta = problem.params.speed_ratio;
        for (label, rate) in [
            ("whole run", whirl.rate()),
            ("second half", whirl.second_half_rate()),
        ] {
            let sense = if rate < 0.0 { "backward" } else { "forward" };
            let _ = writeln!(
                report,
                "mean whirl rate ({label}): {} ({sense}, {} of the running speed)",
                num(rate),
                num(rate / eta)
            );
        }
    }
    let _ = writeln!(
        report,
        "final state: x = {}, y = {}, vx = {}, vy = {} ({})",
        s.x,
        s.y,
        s.vx,
        s.vy,
        match pass.last.regime {
            Regime::Contact => "in contact",
            Regime::Free => "free flight",
            Regime::Rolling => "rolling",
        }
    );
    let _ = writeln!(
        report,
        "run time: {:.3} ms",
        pass.elapsed.as_secs_f64() * 1e3
    );
    for (path, what) in [(&args.events, "events"), (&args.samples, "samples")] {
        if let Some(p) = path {
            let _ = writeln!(report, "wrote {what}: {}", p.display());
        }
    }
    stdio::out(&report)
}

/// The requested sample times (`true`) and the whirl grid (`false`), both increasing, merged in
/// time order (a requested time first where both fall on one instant).
fn merged(
    user: impl Iterator<Item = f64>,
    grid: impl Iterator<Item = f64>,
) -> impl Iterator<Item = (f64, bool)> {
    let (mut user, mut grid) = (user.peekable(), grid.peekable());
    std::iter::from_fn(move || match (user.peek(), grid.peek()) {
        (Some(&u), Some(&g)) if g.total_cmp(&u).is_lt() => grid.next().map(|g| (g, false)),
        (Some(_), _) => user.next().map(|u| (u, true)),
        (None, _) => grid.next().map(|g| (g, false)),
    })
}

/// The mean whirl rate dφ/dτ of the rotor's angle φ about the stator centre, from states at
/// increasing times (each step of φ taken as the shortest turn, so the states must be closer
/// than half a turn apart: the grid of `run`).
struct Whirl {
    centre: (f64, f64),
    start: f64,
    half: f64,
    last: (f64, f64),
    total: f64,
    second_half: f64,
    second_half_from: Option<f64>,
    time: f64,
}

impl Whirl {
    fn new(params: &Params, start: f64, initial: &State, end: f64) -> Self {
        let centre = (params.offset_x, params.offset_y);
        let angle = (initial.y - centre.1).atan2(initial.x - centre.0);
        Whirl {
            centre,
            start,
            half: 0.5 * (start + end),
            last: (start, angle),
            total: 0.0,
            second_half: 0.0,
            second_half_from: None,
            time: start,
        }
    }

    fn add(&mut self, time: f64, state: &State) {
        if time <= self.last.0 {
            return;
        }
        let angle = (state.y - self.centre.1).atan2(state.x - self.centre.0);
        let mut d = angle - self.last.1;
        if d > std::f64::consts::PI {
            d -= std::f64::consts::TAU;
        } else if d < -std::f64::consts::PI {
            d += std::f64::consts::TAU;
        }
        self.total += d;
        if time > self.half {
            self.second_half_from.get_or_insert(self.last.0);
            self.second_half += d;
        }
        self.last = (time, angle);
        self.time = time;
    }

    fn rate(&self) -> f64 {
        self.total / (self.time - self.start)
    }

    fn second_half_rate(&self) -> f64 {
        let from = self.second_half_from.unwrap_or(self.half);
        self.second_half / (self.time - from)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sample_times_merge_with_the_whirl_grid_in_order() {
        let user = [0.0, 0.5, 1.0, 1.5];
        let grid = [0.25, 0.5, 0.75, 1.75, 2.0];
        let all: Vec<(f64, bool)> = merged(user.into_iter(), grid.into_iter()).collect();
        assert_eq!(
            all,
            [
                (0.0, true),
                (0.25, false),
                (0.5, true),
                (0.5, false),
                (0.75, false),
                (1.0, true),
                (1.5, true),
                (1.75, false),
                (2.0, false)
            ]
        );
    }
}
