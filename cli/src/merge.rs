//! `rotor-rub merge`: join sweep shards into the file the unsharded sweep writes.

use std::fs;
use std::io::Read;
use std::path::{Path, PathBuf};

use crate::error::{CliError, Result};
use crate::limits::{fits_memory, reserve};
use crate::output::{CsvOut, check_distinct, commit_all, ensure_parent};
use crate::plot;
use crate::shard::{ShardInfo, checksum};
use crate::stdio;
use crate::sweep::{HEADER, Row, plot_rows, sort_rows};

/// Join the shard files of a sharded sweep into one file, byte for byte what the unsharded sweep
/// writes (rows ordered by value, then period). The order of the shard arguments does not
/// matter; the set must be complete (every shard 0..N once), from one sweep (same version,
/// range, periods, method, tolerance and parameters) and undamaged (row count and checksum of
/// each shard's metadata line), else nothing is written.
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

/// One shard file: its metadata and rows (the raw record, written back unchanged, and its
/// parsed values).
struct Shard {
    info: ShardInfo,
    rows: Vec<(csv::StringRecord, Row)>,
}

/// Read and check one shard file: metadata line, checksum, header, row count.
fn read_shard(path: &Path) -> Result<Shard> {
    let shown = path.display();
    let fail = |what: String| CliError::input(format!("shard {shown}: {what}"));
    let size = fs::metadata(path)
        .map_err(|e| fail(format!("cannot read: {e}")))?
        .len();
    fits_memory("shard file size in bytes", size, 3)?;
    let mut bytes = Vec::new();
    reserve(
        &mut bytes,
        usize::try_from(size).unwrap_or(usize::MAX),
        "shard file size in bytes",
    )?;
    fs::File::open(path)
        .and_then(|mut file| file.read_to_end(&mut bytes))
        .map_err(|e| fail(format!("cannot read: {e}")))?;
    let split = bytes
        .iter()
        .position(|&b| b == b'\n')
        .map_or(bytes.len(), |i| i + 1);
    let (first, body) = bytes.split_at(split);
    let line = String::from_utf8_lossy(first);
    let info = ShardInfo::parse(line.trim_end()).map_err(fail)?;
    if checksum(body) != info.checksum {
        return Err(fail(
            "its contents do not match its checksum: the file is truncated or was changed".into(),
        ));
    }
    let mut reader = csv::ReaderBuilder::new()
        .has_headers(true)
        .from_reader(body);
    let header = reader
        .headers()
        .map_err(|e| fail(format!("cannot read: {e}")))?;
    if header.iter().ne(HEADER) {
        return Err(fail(format!(
            "not a sweep file: the header must be {}",
            HEADER.join(",")
        )));
    }
    let mut rows = Vec::new();
    for (line, record) in reader.records().enumerate() {
        let bad = |what: String| fail(format!("row {}: {what}", line + 3));
        let record = record.map_err(|e| bad(e.to_string()))?;
        let field = |i: usize| record.get(i).unwrap_or("");
        let number = |i: usize| -> Result<f64> {
            field(i)
                .parse::<f64>()
                .map_err(|_| bad(format!("{} '{}' is not a number", HEADER[i], field(i))))
        };
        let period = field(1)
            .parse::<u64>()
            .map_err(|_| bad(format!("period '{}' is not an integer >= 0", field(1))))?;
        let row = (
            number(0)?,
            period,
            number(2)?,
            number(3)?,
            number(4)?,
            number(5)?,
        );
        reserve(&mut rows, 1, "rows")?;
        rows.push((record, row));
    }
    if rows.len() as u64 != info.rows {
        return Err(fail(format!(
            "{} rows, but its metadata says {}: the file is truncated or was changed",
            rows.len(),
            info.rows
        )));
    }
    Ok(Shard { info, rows })
}

/// Check that `shards` (with their paths) are the complete set 0..N of one sweep, each once.
fn check_set(shards: &[(&Path, Shard)]) -> Result<()> {
    let Some((first_path, first)) = shards.first() else {
        return Err(CliError::input("no shard files given"));
    };
    let count = first.info.count;
    for (path, shard) in shards {
        if shard.info.count != count {
            return Err(CliError::input(format!(
                "shard {} is shard {}/{}, but {} is shard {}/{}: they come from differently \
                 sharded sweeps",
                path.display(),
                shard.info.index,
                shard.info.count,
                first_path.display(),
                first.info.index,
                count
            )));
        }
        if shard.info.run != first.info.run {
            return Err(CliError::input(format!(
                "shards {} and {} come from different sweeps (version, range, periods, method, \
                 tolerance or parameters differ): {} vs {}",
                first_path.display(),
                path.display(),
                first.info.run,
                shard.info.run
            )));
        }
    }
    let mut seen: Vec<Option<&Path>> =
        vec![None; usize::try_from(count).unwrap_or(0).min(shards.len() + 1)];
    if seen.len() as u64 != count {
        return Err(CliError::input(format!(
            "the sweep has {count} shards, but only {} files were given",
            shards.len()
        )));
    }
    for (path, shard) in shards {
        let slot = usize::try_from(shard.info.index)
            .ok()
            .and_then(|i| seen.get_mut(i))
            .ok_or_else(|| CliError::input("shard index out of range"))?;
        if let Some(other) = slot {
            return Err(CliError::input(format!(
                "shard {}/{count} is given twice: {} and {}",
                shard.info.index,
                other.display(),
                path.display()
            )));
        }
        *slot = Some(path);
    }
    let missing: Vec<String> = seen
        .iter()
        .enumerate()
        .filter(|(_, p)| p.is_none())
        .map(|(i, _)| format!("{i}/{count}"))
        .collect();
    if !missing.is_empty() {
        return Err(CliError::input(format!(
            "incomplete set: missing shard {}",
            missing.join(", ")
        )));
    }
    Ok(())
}

/// Run the command.
pub fn run(args: &Args) -> Result<()> {
    let [svg, png] = plot::beside(&args.out);
    let mut outputs = vec![("the merged file", args.out.as_path())];
    if !args.no_plot {
        outputs.extend([("the plot", svg.as_path()), ("the plot", png.as_path())]);
    }
    let inputs: Vec<(&str, &Path)> = args.shards.iter().map(|p| ("shard", p.as_path())).collect();
    check_distinct(&outputs, &inputs)?;
    let shards = args
        .shards
        .iter()
        .map(|p| Ok((p.as_path(), read_shard(p)?)))
        .collect::<Result<Vec<_>>>()?;
    check_set(&shards)?;
    let mut rows: Vec<(csv::StringRecord, Row)> =
        shards.into_iter().flat_map(|(_, s)| s.rows).collect();
    sort_rows(&mut rows, |(_, r)| (r.0, r.1));
    ensure_parent(&args.out)?;
    let mut out = CsvOut::create(&args.out, &HEADER)?;
    for (record, _) in &rows {
        out.record(record)?;
    }
    let mut files = vec![out.finish()?];
    if !args.no_plot {
        let parsed: Vec<Row> = rows.iter().map(|(_, r)| *r).collect();
        files.extend(plot_rows(&parsed, &args.param, "", &args.out)?);
    }
    commit_all(files)?;
    let mut report = format!(
        "merged {} rows from {} shards into {}\n",
        rows.len(),
        args.shards.len(),
        args.out.display()
    );
    if !args.no_plot {
        report += &format!("plot written to {} and {}\n", svg.display(), png.display());
    }
    stdio::out(&report)
}
