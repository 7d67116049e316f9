//! `spectrum` on a model file or the ring with mass (`crate::model_file::Subject`).

use super::{Args, Written, finish, sample_count};
use crate::analysis::spectrum::{peaks, real_amplitudes, whirl_amplitudes};
use crate::error::{CliError, Result};
use crate::limits::{add_counts, fits_memory};
use crate::model_file::{Subject, chosen_columns};
use crate::output::{CsvOut, check_distinct, ensure_parent};
use crate::plot::spectrum::{Curve, SECOND};
use crate::plot::{self, ANALYTIC};

/// `spectrum` on a model file or the ring with mass: the amplitude spectra of the chosen
/// columns (or the whirl of two of them) in orders of the running speed, sampled by the matrix
/// propagator at the same times as the planar model's.
pub fn run_matrix(args: &Args, subject: &Subject) -> Result<()> {
    let options = args.method.options()?;
    subject.check(&options)?;
    let end_period = add_counts(("--transient", args.transient), ("--periods", args.periods))?;
    let all = subject.columns();
    let default: Vec<String> = subject.orbit_columns()[..2]
        .iter()
        .map(|c| c.to_string())
        .collect();
    let picked = chosen_columns(subject, "--columns", args.columns.as_deref(), &default)?;
    if args.whirl && picked.len() != 2 {
        return Err(CliError::input(format!(
            "--whirl takes exactly two --columns (the whirl's x and y), not {}",
            picked.len()
        )));
    }
    let n = sample_count(args.periods, args.samples_per_period)?;
    fits_memory(
        "--periods × --samples-per-period (samples)",
        n as u64,
        8 * (all.len() + 2),
    )?;
    let budget = args.limits.budget();
    budget.plan("--periods × --samples-per-period", n as u64)?;
    let [svg, png] = plot::beside(&args.out);
    let mut inputs = args.problem.input_files();
    if let Some(m) = &args.model {
        inputs.push(("--model", m.as_path()));
    }
    check_distinct(
        &[
            ("--out", args.out.as_path()),
            ("the plot", svg.as_path()),
            ("the plot", png.as_path()),
        ],
        &inputs,
    )?;
    ensure_parent(&args.out)?;
    let names: Vec<&str> = picked
        .iter()
        .filter_map(|&i| all.get(i).map(String::as_str))
        .collect();
    let header: Vec<&str> = if args.whirl {
        vec!["order", "whirl"]
    } else {
        std::iter::once("order")
            .chain(names.iter().copied())
            .collect()
    };
    let mut out = CsvOut::create(&args.out, &header)?;
    let period = subject.period();
    let start = args.transient as f64 * period;
    let dt = period / args.samples_per_period as f64;
    let times: Vec<f64> = (0..n).map(|i| start + i as f64 * dt).collect();
    let mut tracker = budget.run(subject.start_time(), end_period as f64 * period);
    let table = subject.sample(&options, &times, &mut tracker)?;
    let signals: Vec<Vec<f64>> = picked.iter().map(|&i| table.column(i)).collect();
    let order = |bin: f64| bin / args.periods as f64;
    let unit = subject.length_unit();
    let (curves, lines) = if let [x, y] = signals.as_slice()
        && args.whirl
    {
        let w = whirl_amplitudes(x, y);
        for &(k, a) in &w {
            out.row((order(k as f64), a))?;
        }
        let amps: Vec<f64> = w.iter().map(|p| p.1).collect();
        let lines: Vec<String> = peaks(&amps, 6)
            .into_iter()
            .filter_map(|i| w.get(i))
            .map(|&(k, a)| format!("{:+.4}× {a:.4e}", order(k as f64)))
            .collect();
        let curve = Curve {
            label: format!("whirl {}", names.join(" + i ")),
            color: ANALYTIC,
            points: w.iter().map(|&(k, a)| (order(k as f64), a)).collect(),
        };
        (vec![curve], lines)
    } else {
        let amps: Vec<Vec<f64>> = signals.iter().map(|s| real_amplitudes(s)).collect();
        let bins = amps.first().map_or(0, Vec::len);
        for k in 0..bins {
            let fields = std::iter::once(order(k as f64))
                .chain(amps.iter().map(|a| a.get(k).copied().unwrap_or(f64::NAN)))
                .map(|x| format!("{x:?}"));
            out.record(fields)?;
        }
        let mut lines = Vec::new();
        let mut curves = Vec::new();
        for (j, (name, a)) in names.iter().zip(&amps).enumerate() {
            let top: Vec<String> = peaks(a, 6)
                .into_iter()
                .filter_map(|i| a.get(i).map(|v| format!("{:.4}× {v:.4e}", order(i as f64))))
                .collect();
            lines.push(format!("{name}: {}", top.join(", ")));
            curves.push(Curve {
                label: (*name).to_string(),
                color: if j % 2 == 0 { ANALYTIC } else { SECOND },
                points: a
                    .iter()
                    .enumerate()
                    .map(|(k, &v)| (order(k as f64), v))
                    .collect(),
            });
        }
        (curves, lines)
    };
    let written = Written {
        out,
        plot: [svg, png],
        samples: n,
        end_period,
    };
    finish(
        args,
        &options,
        written,
        (&subject.speed_label(), unit),
        curves,
        &lines,
    )
}
