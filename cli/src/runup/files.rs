//! The files of `rotor-rub runup`: one row per forcing period, and every switch with the speed
//! it happened at (both written atomically).

use std::path::{Path, PathBuf};

use rotor_rub::Event;
use rotor_rub::variable_speed::{Revolution, SpeedDirection};

use crate::error::Result;
use crate::output::{AtomicFile, CsvOut};

/// Header of the per-period file.
pub const ROWS_HEADER: [&str; 13] = [
    "direction",
    "period",
    "start",
    "end",
    "speed_ratio",
    "speed_change",
    "max_radius",
    "min_radius",
    "contact_fraction",
    "whirl",
    "whirl_direction",
    "enters",
    "exits",
];

/// Header of the events file.
pub const EVENTS_HEADER: [&str; 9] = [
    "time",
    "speed_ratio",
    "period",
    "direction",
    "kind",
    "x",
    "y",
    "vx",
    "vy",
];

/// A switch with where in the run it happened.
pub struct RunEvent {
    /// The switch.
    pub event: Event,
    /// η at its time.
    pub speed_ratio: f64,
    /// The forcing period it falls in.
    pub period: u64,
    /// Which way the speed went over that period.
    pub direction: SpeedDirection,
}

/// `<stem>-events.csv` next to `out`.
pub fn events_beside(out: &Path) -> PathBuf {
    let stem = out
        .file_stem()
        .map_or_else(|| "runup".into(), |s| s.to_string_lossy().into_owned());
    out.with_file_name(format!("{stem}-events.csv"))
}

/// The per-period file, uncommitted.
pub fn rows_file(path: &Path, rows: &[Revolution]) -> Result<AtomicFile> {
    rows_file_with(path, &ROWS_HEADER, rows)
}

/// The per-period file under `header` (a matrix model names its speed column `speed`),
/// uncommitted.
pub fn rows_file_with(path: &Path, header: &[&str], rows: &[Revolution]) -> Result<AtomicFile> {
    let mut csv = CsvOut::create(path, header)?;
    for r in rows {
        csv.row((
            r.direction().name(),
            r.index,
            r.start,
            r.end,
            r.speed_ratio,
            r.speed_change,
            r.max_radius,
            r.min_radius,
            r.contact_fraction,
            r.whirl,
            r.whirl_direction().name(),
            r.enters,
            r.exits,
        ))?;
    }
    csv.finish()
}

/// The events file, uncommitted.
pub fn events_file(path: &Path, events: &[RunEvent]) -> Result<AtomicFile> {
    let mut csv = CsvOut::create(path, &EVENTS_HEADER)?;
    for e in events {
        let s = e.event.state;
        csv.row((
            e.event.time,
            e.speed_ratio,
            e.period,
            e.direction.name(),
            e.event.kind.name(),
            s.x,
            s.y,
            s.vx,
            s.vy,
        ))?;
    }
    csv.finish()
}
