//! `rotor-rub simulate`: one run, its switches and uniform samples as CSV, a summary on stdout.

use std::fmt::Write as _;
use std::path::PathBuf;

use rotor_rub::Regime;

use crate::error::{CliError, Result, num};
use crate::limits::LimitArgs;
use crate::options::{MethodArgs, SingleRun, TimeArgs, describe};
use crate::output::{CsvOut, check_distinct, commit_all, print};
use crate::problem::ProblemArgs;
use crate::trajectory::{self, uniform_times};

/// Header of the events file.
pub const EVENTS_HEADER: [&str; 6] = ["tau", "kind", "x", "y", "vx", "vy"];
/// Header of the samples file.
pub const SAMPLES_HEADER: [&str; 6] = ["tau", "x", "y", "vx", "vy", "contact"];

/// Simulate one parameter set from τ = 0 (the stable contract for scripts).
#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    pub problem: ProblemArgs,

    #[command(flatten)]
    pub time: TimeArgs,

    #[command(flatten)]
    pub method: MethodArgs<SingleRun>,

    #[command(flatten)]
    pub limits: LimitArgs,

    /// Write every contact switch, in order, as CSV with header tau,kind,x,y,vx,vy (kind is
    /// `enter` or `exit`)
    #[arg(long, value_name = "FILE.csv")]
    pub events: Option<PathBuf>,

    /// Write uniform samples as CSV with header tau,x,y,vx,vy,contact (contact 0 or 1) at the
    /// times t_i = t_end·i/(N−1), i = 0..N−1
    #[arg(long, value_name = "FILE.csv")]
    pub samples: Option<PathBuf>,

    /// Number N of samples written to --samples, an integer >= 2 [default: 1001]
    #[arg(long, value_name = "N", value_parser = crate::options::at_least(2), requires = "samples")]
    pub sample_count: Option<u64>,
}

/// Run the command.
pub fn run(args: &Args) -> Result<()> {
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
    check_distinct(&outputs, &[])?;
    let count = if args.samples.is_some() {
        args.sample_count.unwrap_or(1001)
    } else {
        0
    };
    let budget = args.limits.budget();
    budget.plan("--sample-count", count)?;
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
    let pass = trajectory::run(
        propagator,
        end,
        uniform_times(problem.start_time, end, count),
        &mut tracker,
        false,
        |e| match &mut events_out {
            Some(out) => {
                let s = e.state;
                out.row((e.time, e.kind.name(), s.x, s.y, s.vx, s.vy))
            }
            None => Ok(()),
        },
        |sample| match &mut samples_out {
            Some(out) => {
                let s = sample.state;
                let contact = u8::from(sample.regime.in_contact());
                out.row((sample.time, s.x, s.y, s.vx, s.vy, contact))
            }
            None => Ok(()),
        },
    )?;
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
        pass.enters,
        pass.switches - pass.enters
    );
    let _ = writeln!(report, "contact fraction: {}", pass.contact_fraction);
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
    print(&report)
}
