//! `rotor-rub spectrum`: amplitude spectra of x and y, or of the complex whirl x + i y, against
//! frequency in multiples of the running speed.

use std::fmt::Write as _;
use std::path::PathBuf;

use rotor_rub::{Options, Problem};

use crate::analysis::spectrum::{peaks, real_amplitudes, whirl_amplitudes};
use crate::error::{CliError, Result, num};
use crate::limits::{Budget, LimitArgs, add_counts, fits_memory, reserve};
use crate::model_file::{Target, target};
use crate::options::{MethodArgs, Survey, describe, parse_positive};
use crate::output::{CsvOut, check_distinct, commit_all, ensure_parent};
use crate::plot::spectrum::{Curve, SECOND, SpectrumFigure};

mod matrix;
use crate::plot::{self, ANALYTIC};
use crate::problem::ProblemArgs;
use crate::stdio;
use crate::trajectory;
use matrix::run_matrix;

/// Amplitude spectrum from uniform samples over an integer number of forcing periods after a
/// transient, Hann window. Frequencies are orders: multiples of the running speed η, so the ½×
/// and ⅓× rub sub-harmonics fall on 0.5 and 0.333.
#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    pub problem: ProblemArgs,

    /// A rotor from matrices (TOML or .npz, SI units: docs/MODEL_FILES.md) instead of the
    /// paper's model: the spectrum of the rub station's relative displacement (rub_x, rub_y, m)
    /// in orders of Ω, or of the --columns named
    #[arg(long, value_name = "FILE", conflicts_with_all = ["preset", "config", "set"])]
    pub model: Option<PathBuf>,

    /// The signals analysed for a model file or the ring with mass (comma-separated): a model
    /// file's DOF names, `v` + a DOF name, rub_x, rub_y, rub_vx, rub_vy [default: rub_x,rub_y];
    /// the ring's x, y, vx, vy, xs, ys, vxs, vys [default: x,y]. With --whirl exactly two, the
    /// whirl's real and imaginary parts
    #[arg(long, value_name = "NAMES")]
    pub columns: Option<String>,

    #[command(flatten)]
    pub method: MethodArgs<Survey>,

    #[command(flatten)]
    pub limits: LimitArgs,

    /// Forcing periods skipped as transient
    #[arg(long, value_name = "P", default_value_t = 100, value_parser = crate::options::at_least(0))]
    pub transient: u64,

    /// Forcing periods analysed (the resolution is 1/P orders; a multiple of 6 puts ½× and ⅓×
    /// on bins), >= 1
    #[arg(long, value_name = "P", default_value_t = 60, value_parser = crate::options::at_least(1))]
    pub periods: u64,

    /// Samples per forcing period (the highest order shown is half of it), >= 2
    #[arg(long, value_name = "M", default_value_t = 64, value_parser = crate::options::at_least(2))]
    pub samples_per_period: u64,

    /// Spectrum of the complex whirl x + i y: positive orders are forward whirl, negative
    /// orders backward whirl
    #[arg(long)]
    pub whirl: bool,

    /// Highest order drawn in the plot (the CSV has every bin)
    #[arg(long, value_name = "ORDER", default_value_t = 4.0, value_parser = parse_positive, allow_hyphen_values = true)]
    pub max_order: f64,

    /// Output CSV: header order,x,y (or order,whirl with --whirl), amplitudes in clearances (a
    /// model file: order then --columns, in SI units); the plot goes next to it (.svg and .png)
    #[arg(long, value_name = "FILE.csv", default_value = "out/spectrum.csv")]
    pub out: PathBuf,
}

/// Run the command.
pub fn run(args: &Args) -> Result<()> {
    let problem = match target(args.model.as_deref(), &args.problem)? {
        Target::Planar(problem) => problem,
        Target::Matrix(subject) => return run_matrix(args, &subject),
    };
    if args.columns.is_some() {
        return Err(CliError::input(
            "--columns applies only to a model file (--model) or the stator ring with mass (stator_mass_ratio > 0)",
        ));
    }
    let options = args.method.options()?;
    let end_period = add_counts(("--transient", args.transient), ("--periods", args.periods))?;
    let n = sample_count(args.periods, args.samples_per_period)?;
    let budget = args.limits.budget();
    budget.plan("--periods × --samples-per-period", n as u64)?;
    let [svg, png] = plot::beside(&args.out);
    check_distinct(
        &[
            ("--out", args.out.as_path()),
            ("the plot", svg.as_path()),
            ("the plot", png.as_path()),
        ],
        &args.problem.input_files(),
    )?;
    ensure_parent(&args.out)?;
    let header: &[&str] = if args.whirl {
        &["order", "whirl"]
    } else {
        &["order", "x", "y"]
    };
    let mut out = CsvOut::create(&args.out, header)?;
    let (x, y) = signal(
        &problem,
        &options,
        args.transient,
        args.periods,
        args.samples_per_period,
        &budget,
    )?;
    let order = |bin: f64| bin / args.periods as f64;
    let (curves, lines) = if args.whirl {
        let w = whirl_amplitudes(&x, &y);
        for &(k, a) in &w {
            out.row((order(k as f64), a))?;
        }
        let amps: Vec<f64> = w.iter().map(|p| p.1).collect();
        let lines: Vec<String> = peaks(&amps, 6)
            .into_iter()
            .map(|i| format!("{:+.4}× {:.4e}", order(w[i].0 as f64), w[i].1))
            .collect();
        let points = w.iter().map(|&(k, a)| (order(k as f64), a)).collect();
        let curve = Curve {
            label: "whirl x + i y".into(),
            color: ANALYTIC,
            points,
        };
        (vec![curve], lines)
    } else {
        let (ax, ay) = (real_amplitudes(&x), real_amplitudes(&y));
        for (k, (a, b)) in ax.iter().zip(&ay).enumerate() {
            out.row((order(k as f64), a, b))?;
        }
        let mut lines = Vec::new();
        for (name, amps) in [("x", &ax), ("y", &ay)] {
            let top: Vec<String> = peaks(amps, 6)
                .into_iter()
                .map(|i| format!("{:.4}× {:.4e}", order(i as f64), amps[i]))
                .collect();
            lines.push(format!("{name}: {}", top.join(", ")));
        }
        let curve = |label: &str, color, a: &[f64]| Curve {
            label: label.into(),
            color,
            points: a
                .iter()
                .enumerate()
                .map(|(k, &v)| (order(k as f64), v))
                .collect(),
        };
        (
            vec![curve("x", ANALYTIC, &ax), curve("y", SECOND, &ay)],
            lines,
        )
    };
    let written = Written {
        out,
        plot: [svg, png],
        samples: n,
        end_period,
    };
    let subject = format!("η = {}", num(problem.params.speed_ratio));
    finish(
        args,
        &options,
        written,
        (&subject, "clearances"),
        curves,
        &lines,
    )
}

/// What a spectrum run has written before its figure and report: the CSV (not yet committed),
/// the plot's paths, the sample count and the last period.
pub(crate) struct Written {
    pub out: CsvOut,
    pub plot: [PathBuf; 2],
    pub samples: usize,
    pub end_period: u64,
}

/// The figure, the files committed together, and the report of a spectrum run (the planar
/// model's and a matrix model's): `subject` names the run in the title (its speed), `unit` the
/// amplitudes'.
pub(crate) fn finish(
    args: &Args,
    options: &Options,
    written: Written,
    (subject, unit): (&str, &str),
    curves: Vec<Curve>,
    lines: &[String],
) -> Result<()> {
    let Written {
        out,
        plot: [svg, png],
        samples,
        end_period,
    } = written;
    let lowest = if args.whirl { -args.max_order } else { 0.0 };
    let figure = SpectrumFigure {
        title: format!(
            "{} spectrum, {subject}, periods {}-{end_period}, Hann window",
            if args.whirl { "Whirl" } else { "Amplitude" },
            args.transient,
        ),
        curves,
        orders: lowest..args.max_order,
    };
    let [svg_file, png_file] = plot::render(&figure, &svg, &png)?;
    commit_all([out.finish()?, svg_file, png_file])?;
    let mut report = String::new();
    let _ = writeln!(report, "method: {}", describe(options));
    let _ = writeln!(
        report,
        "{samples} samples over forcing periods {}-{end_period}, resolution {} orders",
        args.transient,
        num(1.0 / args.periods as f64)
    );
    let _ = writeln!(report, "largest peaks (order, amplitude in {unit}):");
    for line in lines {
        let _ = writeln!(report, "  {line}");
    }
    let _ = writeln!(
        report,
        "wrote {}, {}, {}",
        args.out.display(),
        svg.display(),
        png.display()
    );
    stdio::out(&report)
}

/// The number of samples of `periods` forcing periods at `per_period` samples each, refused when
/// it overflows or does not fit in memory.
pub fn sample_count(periods: u64, per_period: u64) -> Result<usize> {
    let n = periods.checked_mul(per_period).ok_or_else(|| {
        CliError::input(format!(
            "--periods {periods} × --samples-per-period {per_period} is more than {} samples: use fewer",
            u64::MAX
        ))
    })?;
    // x and y, their transforms and the FFT's buffers: about 64 bytes per sample.
    fits_memory("--periods × --samples-per-period (samples)", n, 64)
}

/// x and y at `per_period` uniform samples per forcing period over `periods` forcing periods after
/// `transient` ones (the window the spectrum analyses), the work charged to `budget`.
pub fn signal(
    problem: &Problem,
    options: &Options,
    transient: u64,
    periods: u64,
    per_period: u64,
    budget: &Budget,
) -> Result<(Vec<f64>, Vec<f64>)> {
    let n = sample_count(periods, per_period)?;
    let end_period = add_counts(("--transient", transient), ("--periods", periods))?;
    let mut propagator = trajectory::start(problem, options)?;
    let period = problem.params.forcing_period();
    let start = transient as f64 * period;
    let dt = period / per_period as f64;
    let mut tracker = budget.run(problem.start_time, end_period as f64 * period);
    let (mut x, mut y) = (Vec::new(), Vec::new());
    reserve(&mut x, n, "--periods × --samples-per-period (samples)")?;
    reserve(&mut y, n, "--periods × --samples-per-period (samples)")?;
    for i in 0..n {
        let t = start + i as f64 * dt;
        let s = trajectory::advance_to(&mut propagator, t, &mut tracker, |_| Ok(()))?.state;
        x.push(s.x);
        y.push(s.y);
    }
    Ok((x, y))
}
