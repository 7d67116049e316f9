//! Output files, written atomically: every file goes to a temporary file and reaches its
//! destination only when complete, so a failed or interrupted run leaves no file behind and never
//! truncates an existing one. What "reaching the destination" means depends on what is there
//! ([`target`]): a rename over a regular file or new path (a symlink's target, for a symlink), a
//! copy into a device node or FIFO. The report on stdout comes after every file is in place
//! ([`crate::stdio::out`]).

pub mod target;
pub mod temps;

use std::fs::{self, File, OpenOptions};
use std::io::{self, Seek, Write};
use std::path::{Path, PathBuf};

use serde::Serialize;
use tempfile::NamedTempFile;

pub use target::check_distinct;
use target::{Target, parent_dir, resolve};

use crate::error::{CliError, Result};

fn io_error(path: &Path, what: &str, e: impl std::fmt::Display) -> CliError {
    CliError::failure(format!("cannot {what} {}: {e}", path.display()))
}

/// Create `dir` and its parents if needed.
pub fn ensure_dir(dir: &Path) -> Result<()> {
    fs::create_dir_all(dir).map_err(|e| io_error(dir, "create directory", e))
}

/// Create the directory `file` goes to, if it has one and it is missing.
pub fn ensure_parent(file: &Path) -> Result<()> {
    match file.parent().filter(|d| !d.as_os_str().is_empty()) {
        Some(dir) => ensure_dir(dir),
        None => Ok(()),
    }
}

/// A file being written: a temporary file that reaches `dest` on [`AtomicFile::commit`] and
/// disappears if dropped uncommitted (or on an interrupt).
pub struct AtomicFile {
    tmp: Option<NamedTempFile>,
    dest: PathBuf,
    target: Target,
}

impl AtomicFile {
    /// Start writing `dest`. The temporary file keeps `dest`'s extension, so writers that choose
    /// a format by extension (PNG) see the right one.
    pub fn create(dest: &Path) -> Result<Self> {
        let target = resolve(dest)?;
        let suffix = dest
            .extension()
            .map(|e| format!(".{}", e.to_string_lossy()))
            .unwrap_or_default();
        let mut builder = tempfile::Builder::new();
        builder.prefix(".rotor-rub-").suffix(&suffix);
        // Temporary files are private (0600) by default; outputs get the usual mode (0666 less
        // the umask), or keep the mode of the file they replace.
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            let mode = match fs::metadata(target.path()) {
                Ok(meta) if meta.is_file() => meta.permissions().mode() & 0o7777,
                _ => 0o666,
            };
            builder.permissions(fs::Permissions::from_mode(mode));
        }
        let dir = match &target {
            Target::Replace(path) => parent_dir(path).to_path_buf(),
            Target::Through(_) => std::env::temp_dir(),
        };
        let mut live = temps::lock();
        let tmp = builder
            .tempfile_in(&dir)
            .map_err(|e| io_error(dest, "create", e))?;
        live.push(tmp.path().to_path_buf());
        drop(live);
        Ok(Self {
            tmp: Some(tmp),
            dest: dest.to_path_buf(),
            target,
        })
    }

    /// Path of the temporary file (for writers that take a path).
    pub fn temp_path(&self) -> &Path {
        self.tmp.as_ref().map_or(Path::new(""), |t| t.path())
    }

    fn file(&mut self) -> io::Result<&mut File> {
        self.tmp
            .as_mut()
            .map(NamedTempFile::as_file_mut)
            .ok_or_else(|| io::Error::other("output already committed"))
    }

    /// Move the finished file into place.
    pub fn commit(mut self) -> Result<()> {
        let Some(mut tmp) = self.tmp.take() else {
            return Ok(());
        };
        let dest = self.dest.clone();
        tmp.flush().map_err(|e| io_error(&dest, "write", e))?;
        let mut live = temps::lock();
        let temp_path = tmp.path().to_path_buf();
        let result = match &self.target {
            Target::Replace(path) => tmp.persist(path).map(drop).map_err(|e| e.error),
            Target::Through(path) => copy_into(tmp.as_file_mut(), path),
        };
        temps::forget(&mut live, &temp_path);
        result.map_err(|e| io_error(&dest, "write", e))
    }
}

/// Write the whole of `from` into the existing special file `path` (never created or renamed).
fn copy_into(from: &mut File, path: &Path) -> io::Result<()> {
    from.rewind()?;
    let mut to = OpenOptions::new().write(true).open(path)?;
    io::copy(from, &mut to)?;
    to.flush()
}

impl Drop for AtomicFile {
    fn drop(&mut self) {
        if let Some(tmp) = self.tmp.take() {
            let mut live = temps::lock();
            temps::forget(&mut live, tmp.path());
            drop(tmp);
        }
    }
}

impl Write for AtomicFile {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        self.file()?.write(buf)
    }
    fn flush(&mut self) -> io::Result<()> {
        self.file()?.flush()
    }
}

/// Move finished files into place, in order. Everything that can fail in writing has happened
/// before (each file is complete and flushed), so the group is replaced together.
pub fn commit_all(files: impl IntoIterator<Item = AtomicFile>) -> Result<()> {
    files.into_iter().try_for_each(AtomicFile::commit)
}

/// A CSV file being written atomically. Floats are written in shortest round-trip form (ryu).
pub struct CsvOut {
    writer: csv::Writer<AtomicFile>,
    dest: PathBuf,
}

impl CsvOut {
    /// Start `dest` with the given header.
    pub fn create(dest: &Path, header: &[&str]) -> Result<Self> {
        Self::start(AtomicFile::create(dest)?, header)
    }

    /// Continue `file` (possibly holding a preamble) with the given header.
    pub fn start(file: AtomicFile, header: &[&str]) -> Result<Self> {
        let dest = file.dest.clone();
        let mut writer = csv::WriterBuilder::new()
            .has_headers(false)
            .from_writer(file);
        writer
            .write_record(header)
            .map_err(|e| io_error(&dest, "write", e))?;
        Ok(Self { writer, dest })
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

    /// Flush: the finished file, ready for [`commit_all`].
    pub fn finish(self) -> Result<AtomicFile> {
        let dest = self.dest;
        self.writer
            .into_inner()
            .map_err(|e| io_error(&dest, "write", e.error()))
    }
}
