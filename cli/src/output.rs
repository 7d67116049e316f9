//! Output files, written atomically: every file goes to a temporary file in its destination's
//! directory and is renamed over the destination only when complete, so a failed run leaves no
//! file behind and never truncates an existing one.

use std::fs;
use std::io::{self, Write};
use std::path::{Path, PathBuf};

use serde::Serialize;
use tempfile::NamedTempFile;

use crate::error::{CliError, Result};

fn io_error(path: &Path, what: &str, e: impl std::fmt::Display) -> CliError {
    CliError::failure(format!("cannot {what} {}: {e}", path.display()))
}

/// The directory a file goes to (`.` for a bare file name).
fn parent_dir(path: &Path) -> &Path {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    }
}

/// Create `dir` and its parents if needed.
pub fn ensure_dir(dir: &Path) -> Result<()> {
    fs::create_dir_all(dir).map_err(|e| io_error(dir, "create directory", e))
}

/// A file being written: a temporary file that becomes `dest` on [`AtomicFile::commit`] and
/// disappears if dropped uncommitted.
pub struct AtomicFile {
    tmp: NamedTempFile,
    dest: PathBuf,
}

impl AtomicFile {
    /// Start writing `dest`. The temporary file keeps `dest`'s extension, so writers that choose
    /// a format by extension (PNG) see the right one.
    pub fn create(dest: &Path) -> Result<Self> {
        let suffix = dest
            .extension()
            .map(|e| format!(".{}", e.to_string_lossy()))
            .unwrap_or_default();
        let mut builder = tempfile::Builder::new();
        builder.prefix(".rotor-rub-").suffix(&suffix);
        // Temporary files are private (0600) by default; outputs get the usual mode (0666 less
        // the umask).
        #[cfg(unix)]
        builder.permissions(std::os::unix::fs::PermissionsExt::from_mode(0o666));
        let tmp = builder
            .tempfile_in(parent_dir(dest))
            .map_err(|e| io_error(dest, "create", e))?;
        Ok(Self {
            tmp,
            dest: dest.to_path_buf(),
        })
    }

    /// Path of the temporary file (for writers that take a path).
    pub fn temp_path(&self) -> &Path {
        self.tmp.path()
    }

    /// Move the finished file into place.
    pub fn commit(self) -> Result<()> {
        let dest = self.dest;
        self.tmp
            .persist(&dest)
            .map_err(|e| io_error(&dest, "write", e.error))?;
        Ok(())
    }
}

impl Write for AtomicFile {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        self.tmp.write(buf)
    }
    fn flush(&mut self) -> io::Result<()> {
        self.tmp.flush()
    }
}

/// A CSV file being written atomically. Floats are written in shortest round-trip form (ryu).
pub struct CsvOut {
    writer: csv::Writer<AtomicFile>,
    dest: PathBuf,
}

impl CsvOut {
    /// Start `dest` with the given header.
    pub fn create(dest: &Path, header: &[&str]) -> Result<Self> {
        let file = AtomicFile::create(dest)?;
        let mut writer = csv::WriterBuilder::new()
            .has_headers(false)
            .from_writer(file);
        writer
            .write_record(header)
            .map_err(|e| io_error(dest, "write", e))?;
        Ok(Self {
            writer,
            dest: dest.to_path_buf(),
        })
    }

    /// Append one row (a tuple or a sequence of fields).
    pub fn row(&mut self, row: impl Serialize) -> Result<()> {
        self.writer
            .serialize(row)
            .map_err(|e| io_error(&self.dest, "write", e))
    }

    /// Append one row of raw fields.
    pub fn record<I, T>(&mut self, fields: I) -> Result<()>
    where
        I: IntoIterator<Item = T>,
        T: AsRef<[u8]>,
    {
        self.writer
            .write_record(fields)
            .map_err(|e| io_error(&self.dest, "write", e))
    }

    /// Flush and move the file into place.
    pub fn commit(self) -> Result<()> {
        let dest = self.dest;
        let file = self
            .writer
            .into_inner()
            .map_err(|e| io_error(&dest, "write", e.error()))?;
        file.commit()
    }
}
