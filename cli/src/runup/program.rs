//! The speed program of `rotor-rub runup`: a named run-up program (`--program`) whose ramp the
//! options override part by part, or a profile file (`--profile`).

use std::path::PathBuf;

use rotor_rub::params::Number;
use rotor_rub::speed::{Ramp, RampError, RampPace, RunupPreset, SpeedPoint};

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

    /// Forcing periods held at --to before running back (so not with --one-way) [default: the
    /// program's]
    #[arg(long, value_name = "P", value_parser = parse_finite, allow_hyphen_values = true)]
    pub dwell: Option<f64>,

    /// Stop at --to instead of running back to --from (a run-up alone, or a coast-down alone
    /// when --from is above --to)
    #[arg(long)]
    pub one_way: bool,

    /// Speed profile instead of a ramp: a CSV file of rows time,speed_ratio (τ increasing, η
    /// linear between rows and held after the last; # comments; a regular file of at most
    /// 1 MiB; LF, CRLF or CR line ends, a UTF-8 BOM and quoted fields are read). A first row
    /// naming the columns (time, tau, τ or t; speed_ratio, eta, η or speed) is a header; every
    /// other row is two numbers. The run goes from the first row's time to the last's
    #[arg(
        long,
        value_name = "FILE.csv",
        conflicts_with_all = ["from", "to", "rate", "ramp_periods", "settle", "dwell", "one_way"]
    )]
    pub profile: Option<PathBuf>,
}

impl SpeedArgs {
    /// A refused ramp as an input error led by the option that set the value (`--rate: ramp
    /// rate dη/dτ = 5 is out of range …`); a refusal of the ramp as a whole names none.
    fn ramp_error(&self, e: RampError) -> CliError {
        let flag = match e {
            RampError::Speed { which: "from", .. } => Some("--from"),
            RampError::Speed { which: "to", .. } => Some("--to"),
            RampError::SameSpeeds { .. } => match (self.from, self.to) {
                (Some(_), Some(_)) => Some("--from, --to"),
                (Some(_), None) => Some("--from"),
                (None, Some(_)) => Some("--to"),
                (None, None) => None,
            },
            RampError::Rate { periods: None, .. } => Some("--rate"),
            RampError::Rate {
                periods: Some(_), ..
            } => Some("--ramp-periods"),
            RampError::Periods {
                which: "periods", ..
            } => Some("--ramp-periods"),
            RampError::Periods {
                which: "settle", ..
            } => Some("--settle"),
            RampError::Periods { which: "dwell", .. } => Some("--dwell"),
            _ => None,
        };
        match flag {
            Some(flag) => CliError::input(format!("{flag}: {e}")),
            None => CliError::input(format!("invalid speed ramp: {e}")),
        }
    }
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
        if let (Some(dwell), true) = (self.dwell.filter(|d| *d != 0.0), ramp.one_way) {
            return Err(CliError::input(format!(
                "--dwell {} holds the speed at --to before the ramp back, but the ramp is one-way \
                 (--one-way): drop one of them",
                Number(dwell)
            )));
        }
        let points = ramp.points().map_err(|e| self.ramp_error(e))?;
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
