//! The speed program of a stepped run-up ([`super::matrix`]): (time, speed) points, from a
//! model file's speed options (Ω in rad/s, t in s) or the paper model's program (η, τ).

use super::Args;
use crate::error::{CliError, Result, num};

/// Forcing periods held at --from before a model file's ramp when --settle is not given.
pub const MODEL_SETTLE: f64 = 20.0;
/// Forcing periods of a model file's ramp when neither --rate nor --ramp-periods is given.
pub const MODEL_RAMP_PERIODS: f64 = 200.0;

/// A speed program: (time, speed) points, the speed linear in between and held after the last.
#[derive(Clone, Debug, PartialEq)]
pub struct Program {
    /// The points, time increasing.
    pub points: Vec<(f64, f64)>,
    /// For the report and the plot.
    pub description: String,
}

impl Program {
    /// The speed at `t`.
    pub fn speed_at(&self, t: f64) -> f64 {
        let mut last = self.points.first().map_or(1.0, |p| p.1);
        for w in self.points.windows(2) {
            if let [(t0, s0), (t1, s1)] = w {
                if t <= *t1 {
                    if t <= *t0 || t1 <= t0 {
                        return *s0;
                    }
                    return s0 + (s1 - s0) * (t - t0) / (t1 - t0);
                }
                last = *s1;
            }
        }
        last
    }

    /// The first and last times.
    pub fn span(&self) -> (f64, f64) {
        (
            self.points.first().map_or(0.0, |p| p.0),
            self.points.last().map_or(0.0, |p| p.0),
        )
    }
}

/// A model file's speed program from the speed options (Ω in rad/s, t in s): --from and --to
/// (required), --settle and --dwell forcing periods, the ramp by --rate (rad/s²) or
/// --ramp-periods (forcing periods of its mean speed), and back unless --one-way.
///
/// # Errors
/// A missing or out-of-range value, naming the option.
pub fn model_program(args: &Args) -> Result<Program> {
    let s = &args.speed;
    if s.profile.is_some() {
        return Err(CliError::input(
            "--profile applies only to the paper's planar model; with --model give the ramp by --from, --to (rad/s) and --rate (rad/s²) or --ramp-periods",
        ));
    }
    let speed = |flag: &str, v: Option<f64>| match v {
        Some(x) if x.is_finite() && x > 0.0 && x <= 1e6 => Ok(x),
        Some(x) => Err(CliError::input(format!(
            "{flag} {x} is out of range: with --model it is the speed Ω in rad/s, in (0, 1e6]"
        ))),
        None => Err(CliError::input(format!(
            "{flag} is required with --model: the speed Ω in rad/s (the program's ramp is in the paper's η)"
        ))),
    };
    let (from, to) = (speed("--from", s.from)?, speed("--to", s.to)?);
    if from == to {
        return Err(CliError::input(format!(
            "--from, --to: the ramp needs two different speeds, not {} and {} rad/s",
            num(from),
            num(to)
        )));
    }
    let periods = |flag: &str, v: Option<f64>, default: f64| match v.unwrap_or(default) {
        x if x.is_finite() && (0.0..=1e6).contains(&x) => Ok(x),
        x => Err(CliError::input(format!(
            "{flag} {x} is out of range: it must be in [0, 1e6] forcing periods"
        ))),
    };
    let settle = periods("--settle", s.settle, MODEL_SETTLE)?;
    let dwell = periods("--dwell", s.dwell, 0.0)?;
    if s.one_way && dwell != 0.0 {
        return Err(CliError::input(format!(
            "--dwell {} holds the speed at --to before the ramp back, but the ramp is one-way (--one-way): drop one of them",
            num(dwell)
        )));
    }
    let mean = 0.5 * (from + to);
    let ramp = match (s.rate, s.ramp_periods) {
        (Some(r), _) if r.is_finite() && r > 0.0 => (to - from).abs() / r,
        (Some(r), _) => {
            return Err(CliError::input(format!(
                "--rate {r} is out of range: with --model it is |dΩ/dt| in rad/s², a finite number > 0"
            )));
        }
        (None, n) => {
            let n = n.unwrap_or(MODEL_RAMP_PERIODS);
            if !(n.is_finite() && (1.0..=1e6).contains(&n)) {
                return Err(CliError::input(format!(
                    "--ramp-periods {n} is out of range: it must be in [1, 1e6]"
                )));
            }
            n * std::f64::consts::TAU / mean
        }
    };
    let tau = std::f64::consts::TAU;
    let mut t = 0.0;
    let mut points = vec![(t, from)];
    t += settle * tau / from;
    if settle > 0.0 {
        points.push((t, from));
    }
    t += ramp;
    points.push((t, to));
    if !s.one_way {
        if dwell > 0.0 {
            t += dwell * tau / to;
            points.push((t, to));
        }
        t += ramp;
        points.push((t, from));
    }
    let back = if s.one_way {
        String::new()
    } else {
        format!(" -> {}", num(from))
    };
    Ok(Program {
        points,
        description: format!(
            "Ω {} -> {}{back} rad/s at |dΩ/dt| = {} rad/s², stepped: {} forcing period(s) per held speed",
            num(from),
            num(to),
            num((to - from).abs() / ramp),
            args.hold.unwrap_or(1)
        ),
    })
}
