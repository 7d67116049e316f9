//! `rotor-rub poincare`: the Poincaré section (the state once per forcing period) as CSV and a
//! scatter plot, with the response class.

use std::path::PathBuf;

use rotor_rub::{Problem, State, poincare};

use crate::analysis::classify::{POINT_TOLERANCE, classify, distinct_points};
use crate::analysis::lyapunov::largest_exponent;
use crate::error::Result;
use crate::options::{MethodArgs, Survey, describe};
use crate::output::{CsvOut, ensure_dir};
use crate::plot::{self, scatter::SectionFigure};
use crate::problem::ProblemArgs;
use crate::trajectory;

/// Poincaré section: the state at τ = k·2π/η for the kept forcing periods k.
#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    pub problem: ProblemArgs,

    #[command(flatten)]
    pub method: MethodArgs<Survey>,

    /// Forcing periods skipped as transient
    #[arg(long, value_name = "P", default_value_t = 200)]
    pub transient: u64,

    /// Forcing periods kept (section points), >= 1
    #[arg(long, value_name = "P", default_value_t = 100, value_parser = crate::options::at_least(1))]
    pub keep: u64,

    /// Also estimate the largest Lyapunov exponent over the kept periods (Benettin), to tell
    /// quasi-periodic from chaotic motion
    #[arg(long)]
    pub lyapunov: bool,

    /// Output CSV, header period,x,y,vx,vy; the plot goes next to it (.svg and .png)
    #[arg(long, value_name = "FILE.csv", default_value = "out/poincare.csv")]
    pub out: PathBuf,
}

/// Run the command.
pub fn run(args: &Args) -> Result<()> {
    let problem = args.problem.build()?;
    let options = args.method.options()?;
    let mut propagator = trajectory::start(&problem, &options)?;
    if let Some(dir) = args.out.parent().filter(|d| !d.as_os_str().is_empty()) {
        ensure_dir(dir)?;
    }
    let mut out = CsvOut::create(&args.out, &["period", "x", "y", "vx", "vy"])?;
    let period = problem.params.forcing_period();
    let from = args.transient as f64 * period;
    rotor_rub::advance_to(&mut propagator, from, |_| {})?;
    let mut points: Vec<State> = Vec::new();
    for (sample, k) in poincare(
        &mut propagator,
        problem.params.speed_ratio,
        args.keep as usize,
    )
    .zip(args.transient..)
    {
        let s = sample?.state;
        out.row((k, s.x, s.y, s.vx, s.vy))?;
        points.push(s);
    }
    let lyapunov = if args.lyapunov {
        let start = Problem {
            initial: points[0],
            start_time: from,
            ..problem
        };
        Some(largest_exponent(
            &start,
            &options,
            period,
            args.keep as usize,
        )?)
    } else {
        None
    };
    let response = classify(&points, lyapunov);
    let figure = SectionFigure {
        title: format!(
            "Poincaré section, η = {}, periods {}-{}: {response}",
            problem.params.speed_ratio,
            args.transient,
            args.transient + args.keep
        ),
        offset: (problem.params.offset_x, problem.params.offset_y),
        points: points.iter().map(|s| (s.x, s.y)).collect(),
    };
    let [svg, png] = plot::save_beside(&figure, &args.out)?;
    out.commit()?;
    println!("method: {}", describe(&options));
    println!(
        "section: {} points over forcing periods {}-{}, {} distinct (tolerance {POINT_TOLERANCE:e})",
        points.len(),
        args.transient,
        args.transient + args.keep,
        distinct_points(&points)
    );
    if let Some(l) = lyapunov {
        println!("largest Lyapunov exponent: {l:.5} per unit τ");
    }
    println!("response: {response}");
    println!(
        "wrote {}, {}, {}",
        args.out.display(),
        svg.display(),
        png.display()
    );
    Ok(())
}
