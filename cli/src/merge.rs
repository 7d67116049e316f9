//! `rotor-rub merge`: join sweep shards into the file the unsharded sweep writes.

use std::path::PathBuf;

use crate::error::{CliError, Result};
use crate::output::{CsvOut, ensure_dir};
use crate::sweep::{HEADER, Row, plot_rows, sort_rows};

/// Join the shard files of a sharded sweep into one file, byte for byte what the unsharded sweep
/// writes (rows ordered by value, then period). The order of the shard arguments does not
/// matter.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// The merged CSV (the plot goes next to it, .svg and .png)
    #[arg(value_name = "OUT.csv")]
    pub out: PathBuf,

    /// The shard files written by `rotor-rub sweep --shard I/N`
    #[arg(value_name = "SHARD.csv", required = true)]
    pub shards: Vec<PathBuf>,

    /// Name of the swept parameter, for the plot's axis label
    #[arg(long, value_name = "NAME", default_value = "value")]
    pub param: String,

    /// Do not draw the plot
    #[arg(long)]
    pub no_plot: bool,
}

/// The rows of one shard file: the raw record (written back unchanged) and its parsed values.
fn read_shard(path: &PathBuf) -> Result<Vec<(csv::StringRecord, Row)>> {
    let shown = path.display();
    let mut reader = csv::ReaderBuilder::new()
        .has_headers(true)
        .from_path(path)
        .map_err(|e| CliError::input(format!("shard {shown}: cannot read: {e}")))?;
    let header = reader
        .headers()
        .map_err(|e| CliError::input(format!("shard {shown}: cannot read: {e}")))?;
    if header.iter().ne(HEADER) {
        return Err(CliError::input(format!(
            "shard {shown}: not a sweep file: the header must be {}",
            HEADER.join(",")
        )));
    }
    let mut rows = Vec::new();
    for (line, record) in reader.records().enumerate() {
        let bad =
            |what: String| CliError::input(format!("shard {shown}, row {}: {what}", line + 2));
        let record = record.map_err(|e| bad(e.to_string()))?;
        let number = |i: usize| -> Result<f64> {
            record[i]
                .parse::<f64>()
                .map_err(|_| bad(format!("{} '{}' is not a number", HEADER[i], &record[i])))
        };
        let period = record[1]
            .parse::<u64>()
            .map_err(|_| bad(format!("period '{}' is not an integer >= 0", &record[1])))?;
        let row = (
            number(0)?,
            period,
            number(2)?,
            number(3)?,
            number(4)?,
            number(5)?,
        );
        rows.push((record, row));
    }
    Ok(rows)
}

/// Run the command.
pub fn run(args: &Args) -> Result<()> {
    let mut rows = Vec::new();
    for shard in &args.shards {
        rows.extend(read_shard(shard)?);
    }
    sort_rows(&mut rows, |(_, r)| (r.0, r.1));
    if let Some(dir) = args.out.parent().filter(|d| !d.as_os_str().is_empty()) {
        ensure_dir(dir)?;
    }
    let mut out = CsvOut::create(&args.out, &HEADER)?;
    for (record, _) in &rows {
        out.record(record)?;
    }
    let plotted = if args.no_plot {
        None
    } else {
        let parsed: Vec<Row> = rows.iter().map(|(_, r)| *r).collect();
        Some(plot_rows(&parsed, &args.param, "", &args.out)?)
    };
    out.commit()?;
    println!(
        "merged {} rows from {} shards into {}",
        rows.len(),
        args.shards.len(),
        args.out.display()
    );
    if let Some([svg, png]) = plotted {
        println!("plot written to {} and {}", svg.display(), png.display());
    }
    Ok(())
}
