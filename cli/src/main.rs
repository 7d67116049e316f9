//! `rotor-rub`: command-line front end of the rotor-rub library. This file holds the command
//! definition and the dispatch; each subcommand lives in its own module.

use std::process::ExitCode;

use clap::error::ErrorKind;
use clap::{Parser, Subcommand};

use rotor_rub_cli::error::{CliError, EXIT_INPUT};
use rotor_rub_cli::{
    compare, fig2, friction_fig, merge, model_file, orbit, output, params, poincare, presets,
    runup, simulate, spectrum, stdio, sweep,
};

const ABOUT: &str = "Jeffcott rotor rubbing on an anisotropically supported stator: \
piecewise-analytical simulation and numerical comparison.";

const LONG_ABOUT: &str = "Jeffcott rotor rubbing on an anisotropically supported stator: \
piecewise-analytical simulation and numerical comparison.

All quantities are dimensionless, as in the paper: lengths in radial clearances, time \
τ = ω_n t (ω_n the rotor's natural frequency), speed ratio η = Ω/ω_n, forcing period 2π/η, \
stiffnesses relative to the rotor stiffness. Contact when the distance z from the stator centre \
exceeds 1.

With no subcommand, reproduces the paper's Fig. 2 (same as `rotor-rub fig2`): analytic and \
numerical orbits for η = 1 … 3.5 with the paper preset, out/fig2.svg and out/fig2.png, and a \
table of switches, response class, Lyapunov exponent and run time per η.

Invalid input exits with code 2, a failed propagation or I/O error with code 1; no output file \
is created or changed by a failed run. A closed pipe on stdout ends a command quietly with code \
141; SIGINT, SIGTERM and SIGHUP with 130, 143 and 129, unfinished output files removed.";

/// Shown under every subcommand's help.
const UNITS: &str = "Units (dimensionless, as in the paper): lengths in radial clearances, time τ = ω_n t, \
speed ratio η = Ω/ω_n, forcing period 2π/η, stiffnesses relative to the rotor stiffness. \
Exit codes: 2 invalid input, 1 failed run, 141 closed stdout pipe, 128 + N signal N; a failed or \
interrupted run leaves no output file.";

#[derive(Parser, Debug)]
#[command(name = "rotor-rub", version, about = ABOUT, long_about = LONG_ABOUT)]
#[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,

    #[command(flatten, next_help_heading = "Fig. 2 options (no subcommand)")]
    fig2: fig2::Args,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Reproduce the paper's Fig. 2 (the default when no subcommand is given)
    #[command(after_help = UNITS)]
    Fig2(fig2::Args),
    /// Simulate one parameter set: switches and samples as CSV, a summary on stdout
    #[command(after_help = UNITS)]
    Simulate(simulate::Args),
    /// Analytic method against a numerical reference: switch table, differences, orbit plot
    #[command(after_help = UNITS)]
    Compare(compare::Args),
    /// Bifurcation diagram: Poincaré points over a range of one parameter (parallel, shardable)
    #[command(after_help = UNITS)]
    Sweep(sweep::Args),
    /// Join the shards of a sharded sweep into what the unsharded sweep writes
    #[command(after_help = UNITS)]
    Merge(merge::Args),
    /// Poincaré section (state once per forcing period) as CSV and plot, with response class
    #[command(after_help = UNITS)]
    Poincare(poincare::Args),
    /// Amplitude spectrum of x and y, or of the whirl x + i y, in orders of the running speed
    #[command(after_help = UNITS)]
    Spectrum(spectrum::Args),
    /// Coulomb friction: orbits with friction beside μ = 0, reversals and rolling marked
    #[command(after_help = UNITS)]
    Friction(friction_fig::Args),
    /// Run-up and coast-down through resonance: per forcing period the speed, orbit radii,
    /// contact, whirl and switches; amplitude against speed for both directions (jumps,
    /// hysteresis)
    #[command(after_help = UNITS)]
    Runup(runup::Args),
    /// One periodic orbit by shooting: its state on the section, period, Floquet multipliers
    /// and stability (each map by --method, default hybrid, at --tol, default 1e-12 here)
    #[command(after_help = UNITS)]
    Orbit(orbit::command::Args),
    /// Continue periodic orbits over a range of one parameter: branches with their stability,
    /// folds, period doublings, Neimark-Sacker and grazing points (CSV and plot; each map by
    /// --method, default hybrid, at --tol, default 1e-12 here)
    #[command(after_help = UNITS)]
    Continue(orbit::continue_command::Args),
    /// Read and check a model file (TOML or .npz, SI units: docs/MODEL_FILES.md); print its
    /// degrees of freedom, station, clearance and modes
    CheckModel(model_file::CheckArgs),
    /// List the presets with every value
    #[command(after_help = UNITS)]
    Presets,
    /// List every parameter: name, symbol, default, valid range and meaning
    #[command(after_help = UNITS)]
    Params,
}

/// A clap usage error as one line: its first line plus any value list or tip.
fn one_line(e: &clap::Error) -> String {
    let text = e.render().to_string();
    let mut message = String::new();
    for line in text.lines().map(str::trim) {
        if line.starts_with("Usage:") || line.starts_with("For more information") {
            break;
        }
        if line.is_empty() {
            continue;
        }
        if !message.is_empty() {
            message.push_str(if message.ends_with(':') { " " } else { "; " });
        }
        message.push_str(line.strip_prefix("error: ").unwrap_or(line));
    }
    message
}

fn dispatch(cli: Cli) -> Result<(), CliError> {
    match cli.command {
        None => fig2::run(&cli.fig2),
        Some(Command::Fig2(args)) => fig2::run(&args),
        Some(Command::Simulate(args)) => simulate::run(&args),
        Some(Command::Compare(args)) => compare::run(&args),
        Some(Command::Sweep(args)) => sweep::run(&args),
        Some(Command::Merge(args)) => merge::run(&args),
        Some(Command::Poincare(args)) => poincare::run(&args),
        Some(Command::Spectrum(args)) => spectrum::run(&args),
        Some(Command::Friction(args)) => friction_fig::run(&args),
        Some(Command::Runup(args)) => runup::run(&args),
        Some(Command::Orbit(args)) => orbit::command::run(&args),
        Some(Command::Continue(args)) => orbit::continue_command::run(&args),
        Some(Command::CheckModel(args)) => model_file::check(&args),
        Some(Command::Presets) => presets::run(),
        Some(Command::Params) => params::run(),
    }
}

fn main() -> ExitCode {
    output::temps::install_handler();
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => match e.kind() {
            ErrorKind::DisplayHelp
            | ErrorKind::DisplayVersion
            | ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => {
                return ExitCode::from(stdio::clap_message(&e));
            }
            _ => {
                stdio::error(&one_line(&e));
                return ExitCode::from(EXIT_INPUT);
            }
        },
    };
    match dispatch(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            if !e.message.is_empty() {
                stdio::error(&e.to_string());
            }
            ExitCode::from(e.code)
        }
    }
}
