//! `rotor-rub simulate`: one run, its switches and uniform samples as CSV, a summary on stdout.

use std::path::PathBuf;

use rotor_rub::Regime;

use crate::error::Result;
use crate::options::{MethodArgs, SingleRun, TimeArgs, describe};
use crate::output::CsvOut;
use crate::problem::ProblemArgs;
use crate::trajectory::{self, contact_fraction, uniform_times};

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
    let count = if samples_out.is_some() {
        args.sample_count.unwrap_or(1001) as usize
    } else {
        0
    };
    let pass = trajectory::run(
        propagator,
        end,
        uniform_times(problem.start_time, end, count),
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
                let contact = u8::from(sample.regime == Regime::Contact);
                out.row((sample.time, s.x, s.y, s.vx, s.vy, contact))
            }
            None => Ok(()),
        },
    )?;
    if let Some(out) = events_out {
        out.commit()?;
    }
    if let Some(out) = samples_out {
        out.commit()?;
    }

    let enters = pass
        .events
        .iter()
        .filter(|e| e.kind.regime_after() == Regime::Contact)
        .count();
    let s = pass.last.state;
    println!(
        "method: {}; τ from {} to {end} ({} forcing periods)",
        describe(&options),
        problem.start_time,
        (end - problem.start_time) / problem.params.forcing_period()
    );
    println!(
        "switches: {} ({enters} contact starts, {} contact ends)",
        pass.events.len(),
        pass.events.len() - enters
    );
    println!(
        "contact fraction: {}",
        contact_fraction(pass.initial_regime, &pass.events, problem.start_time, end)
    );
    println!(
        "final state: x = {}, y = {}, vx = {}, vy = {} ({})",
        s.x,
        s.y,
        s.vx,
        s.vy,
        match pass.last.regime {
            Regime::Contact => "in contact",
            Regime::Free => "free flight",
        }
    );
    println!("run time: {:.3} ms", pass.elapsed.as_secs_f64() * 1e3);
    for (path, what) in [(&args.events, "events"), (&args.samples, "samples")] {
        if let Some(p) = path {
            println!("wrote {what}: {}", p.display());
        }
    }
    Ok(())
}
