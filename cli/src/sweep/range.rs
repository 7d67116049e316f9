//! The values a sweep runs: the range `--from`..`--to` in `--steps` values, the slice of them a
//! shard runs, and the description all shards of one sweep share.

use rotor_rub::{Options, Problem};

use super::Args;
use crate::error::{CliError, Result, num};

/// `I/N`: shard I of N (0 <= I < N).
pub fn parse_shard(text: &str) -> Result<(usize, usize), String> {
    let bad = || format!("'{text}' is not a shard I/N with integers 0 <= I < N");
    let (i, n) = text.split_once('/').ok_or_else(bad)?;
    let (i, n): (usize, usize) = (
        i.trim().parse().map_err(|_| bad())?,
        n.trim().parse().map_err(|_| bad())?,
    );
    if n == 0 || i >= n {
        return Err(bad());
    }
    Ok((i, n))
}

/// How many of `steps` values shard `shard` of `shards` runs (round robin).
pub fn shard_len(steps: u64, shard: u64, shards: u64) -> u64 {
    steps.saturating_sub(shard).div_ceil(shards)
}

/// `--to` when it is not given.
pub const DEFAULT_TO: f64 = 3.5;

/// The last value of the sweep: `--to`, checked against `--steps` so that no value given is
/// ignored (`--steps 1` runs `--from` alone, so a different `--to` is refused) and no two values
/// are the same (`--steps` ≥ 2 needs `--to` ≠ `--from`).
pub fn last_value(args: &Args) -> Result<f64> {
    match (args.steps, args.to) {
        (1, Some(to)) if to != args.from => Err(CliError::input(format!(
            "--steps 1 runs the single value --from {}, so --to {} would be ignored: leave out \
             --to (or give it equal to --from), or ask for --steps >= 2",
            num(args.from),
            num(to)
        ))),
        (1, _) => Ok(args.from),
        (steps, given) => {
            let to = given.unwrap_or(DEFAULT_TO);
            if to == args.from {
                let default = if given.is_none() {
                    " (its default)"
                } else {
                    ""
                };
                return Err(CliError::input(format!(
                    "--steps {steps} values from --from {} to --to {}{default} would all be the \
                     same value: give different ends, or --steps 1",
                    num(args.from),
                    num(to)
                )));
            }
            Ok(to)
        }
    }
}

/// The run every shard of this sweep shares, for the shard metadata.
pub fn run_description(args: &Args, to: f64, base: &Problem, options: &Options) -> String {
    format!(
        "rotor-rub {}; param {}; from {:e} to {:e}; steps {}; transient {}; keep {}; skip_errors {}; {:?}; {:?}",
        env!("CARGO_PKG_VERSION"),
        args.param,
        args.from,
        to,
        args.steps,
        args.transient,
        args.keep,
        args.skip_errors,
        options,
        base
    )
}
