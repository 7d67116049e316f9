//! The speed program of `rotor-rub runup`: a named run-up program (`--program`) whose ramp the
//! options override part by part, or a profile file (`--profile`).

use std::path::PathBuf;

use rotor_rub::params::Number;
use rotor_rub::speed::{Ramp, RampPace, RunupPreset, SpeedPoint};

use super::profile_csv;
use crate::error::{CliError, Result};
use crate::options::parse_finite;

/// A run-up program by name.
pub fn parse_program(name: &str) -> Result<RunupPreset, String> {
    RunupPreset::from_name(name).ok_or_else(|| {
        format!(
            "unknown run-up program '{}': expected one of {}",
            name.escape_debug(),
            RunupPreset::ALL.map(RunupPreset::name).join(", ")
        )
    })
}

/// `--program`'s help, from the runtime's list.
pub fn program_help() -> String {
    let list: Vec<String> = RunupPreset::ALL
        .iter()
        .map(|p| format!("{}: {}", p.name(), p.description()))
        .collect();
    format!(
        "Run-up program: a rotor preset and a speed ramp ({}); --preset, --config, --set and the speed options override its parts",
        list.join("; ")
    )
}

/// The speed options: a ramp (overriding the program's) or a profile file.
#[derive(clap::Args, Debug, Clone)]
pub struct SpeedArgs {
    /// Speed ratio η at the start of the ramp [default: the program's]
    #[arg(long, value_name = "ETA", value_parser = parse_finite, allow_hyphen_values = true)]
    pub from: Option<f64>,

    /// Speed ratio η the ramp turns at (or ends at, with --one-way) [default: the program's]
    #[arg(long, value_name = "ETA", value_parser = parse_finite, allow_hyphen_values = true)]
    pub to: Option<f64>,

    /// Ramp rate |dη/dτ|, in (0, 1] [default: the program's]
    #[arg(long, value_name = "RATE", value_parser = parse_finite, allow_hyphen_values = true, conflicts_with = "ramp_periods")]
    pub rate: Option<f64>,

    /// Ramp length in forcing periods of its mean speed (a ramp from a to b over N periods turns
    /// the unbalance N times), instead of --rate
    #[arg(long, value_name = "N", value_parser = parse_finite, allow_hyphen_values = true)]
    pub ramp_periods: Option<f64>,

    /// Forcing periods held at --from before the ramp starts (the start transient dies out)
    /// [default: the program's]
    #[arg(long, value_name = "P", value_parser = parse_finite, allow_hyphen_values = true)]
    pub settle: Option<f64>,

    /// Forcing periods held at --to before running back [default: the program's]
    #[arg(long, value_name = "P", value_parser = parse_finite, allow_hyphen_values = true)]
    pub dwell: Option<f64>,

    /// Stop at --to instead of running back to --from (a run-up alone, or a coast-down alone
    /// when --from is above --to)
    #[arg(long)]
    pub one_way: bool,

    /// Speed profile instead of a ramp: a CSV file of rows time,speed_ratio (τ increasing, η
    /// linear between rows and held after the last; an optional header line, # comments; a
    /// regular file of at most 1 MiB). The run goes from the first row's time to the last's
    #[arg(
        long,
        value_name = "FILE.csv",
        conflicts_with_all = ["from", "to", "rate", "ramp_periods", "settle", "dwell", "one_way"]
    )]
    pub profile: Option<PathBuf>,
}

/// The speed program of a run: its points and a one-line description.
pub struct Program {
    /// The profile's points.
    pub points: Vec<SpeedPoint>,
    /// For the report and the plot's title.
    pub description: String,
}

impl SpeedArgs {
    /// The program's ramp with the given options applied.
    pub fn ramp(&self, program: RunupPreset) -> Ramp {
        let base = program.ramp();
        Ramp {
            from: self.from.unwrap_or(base.from),
            to: self.to.unwrap_or(base.to),
            pace: match (self.rate, self.ramp_periods) {
                (Some(r), _) => RampPace::Rate(r),
                (None, Some(n)) => RampPace::Periods(n),
                (None, None) => base.pace,
            },
            settle_periods: self.settle.unwrap_or(base.settle_periods),
            dwell_periods: self.dwell.unwrap_or(base.dwell_periods),
            one_way: self.one_way || base.one_way,
            ..base
        }
    }

    /// The speed program: the profile file's points, or the ramp's (an input error naming the
    /// value and its range for a bad one).
    pub fn program(&self, program: RunupPreset) -> Result<Program> {
        if let Some(path) = &self.profile {
            let points = profile_csv::read(path)?;
            let description = format!(
                "speed profile {} ({} points, τ {} to {})",
                path.display(),
                points.len(),
                Number(points.first().map_or(0.0, |p| p.time)),
                Number(points.last().map_or(0.0, |p| p.time))
            );
            return Ok(Program {
                points,
                description,
            });
        }
        let ramp = self.ramp(program);
        let points = ramp
            .points()
            .map_err(|e| CliError::input(format!("invalid speed ramp: {e}")))?;
        let back = if ramp.one_way {
            String::new()
        } else {
            format!(" -> {}", Number(ramp.from))
        };
        Ok(Program {
            points: points.as_slice().to_vec(),
            description: format!(
                "η {} -> {}{back} at dη/dτ = {}",
                Number(ramp.from),
                Number(ramp.to),
                Number(ramp.rate())
            ),
        })
    }
}
