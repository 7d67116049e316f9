//! Where an output path really goes, and which outputs are the same file.
//!
//! A regular file or a new path is replaced atomically (temporary file in the same directory,
//! then rename). A symlink is followed: its final target is replaced the same way, in the
//! target's directory, so the link itself stays a link. Anything else that is not a directory
//! (a device node such as `/dev/null`, a FIFO) is written through: the finished output is
//! copied into it, and it is never renamed over or removed.

use std::fs;
use std::io;
use std::path::{Component, Path, PathBuf};

use crate::error::{CliError, Result};

/// How many symlinks are followed before a path is declared a loop (as the kernel's ELOOP).
const MAX_LINKS: usize = 40;

/// Where an output goes.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Target {
    /// A regular file or a new path: replaced by renaming a finished temporary file over it.
    Replace(PathBuf),
    /// A device node, FIFO or other special file: the finished output is written into it.
    Through(PathBuf),
}

impl Target {
    /// The path written.
    pub fn path(&self) -> &Path {
        match self {
            Target::Replace(p) | Target::Through(p) => p,
        }
    }
}

/// The directory a file goes to (`.` for a bare file name).
pub fn parent_dir(path: &Path) -> &Path {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    }
}

fn invalid(path: &Path, why: &str) -> CliError {
    CliError::input(format!("cannot write {}: {why}", path.display()))
}

/// Resolve `path` (following symlinks, also dangling ones) to where its output goes.
pub fn resolve(path: &Path) -> Result<Target> {
    let mut current = path.to_path_buf();
    for _ in 0..MAX_LINKS {
        let meta = match fs::symlink_metadata(&current) {
            Ok(meta) => meta,
            Err(e) if e.kind() == io::ErrorKind::NotFound => return Ok(Target::Replace(current)),
            Err(e) => return Err(invalid(path, &e.to_string())),
        };
        let kind = meta.file_type();
        if kind.is_symlink() {
            let link = fs::read_link(&current).map_err(|e| invalid(path, &e.to_string()))?;
            current = parent_dir(&current).join(link);
        } else if kind.is_dir() {
            return Err(invalid(path, "it is a directory"));
        } else if kind.is_file() {
            return Ok(Target::Replace(current));
        } else {
            return Ok(Target::Through(current));
        }
    }
    Err(invalid(path, "too many levels of symbolic links"))
}

/// What identifies an output file: its device and inode when it exists, else its absolute path
/// with `.`, `..` and symlinked directories resolved as far as the path exists.
#[derive(Clone, Debug, PartialEq, Eq)]
enum Identity {
    Inode(u64, u64),
    Path(PathBuf),
}

/// Whether two outputs at this target may share it: character devices (`/dev/null`, a
/// terminal) take any number of writers without losing anything.
fn shareable(path: &Path) -> bool {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        fs::metadata(path).is_ok_and(|m| m.file_type().is_char_device())
    }
    #[cfg(not(unix))]
    {
        let _ = path;
        false
    }
}

fn identity(target: &Target) -> Identity {
    let path = target.path();
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        if let Ok(meta) = fs::metadata(path) {
            return Identity::Inode(meta.dev(), meta.ino());
        }
    }
    // A new path: canonicalize its longest existing ancestor, then append the rest lexically.
    let absolute = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
    let mut existing = absolute.as_path();
    let mut rest = Vec::new();
    while fs::canonicalize(existing).is_err() {
        match (existing.parent(), existing.file_name()) {
            (Some(parent), Some(name)) => {
                rest.push(name.to_os_string());
                existing = parent;
            }
            _ => break,
        }
    }
    let mut resolved = fs::canonicalize(existing).unwrap_or_else(|_| existing.to_path_buf());
    for part in rest.iter().rev() {
        for component in Path::new(part).components() {
            match component {
                Component::ParentDir => {
                    resolved.pop();
                }
                Component::CurDir => {}
                other => resolved.push(other),
            }
        }
    }
    Identity::Path(resolved)
}

/// Refuse a command whose outputs (flag name and path), or an output and an input, are the same
/// file however spelled (`a` and `./a`, a symlink, a hard link): one would overwrite the other.
pub fn check_distinct(outputs: &[(&str, &Path)], inputs: &[(&str, &Path)]) -> Result<()> {
    let mut seen: Vec<(&str, &Path, Identity, bool)> = Vec::new();
    for &(name, path) in inputs {
        let target = Target::Replace(path.to_path_buf());
        seen.push((name, path, identity(&target), false));
    }
    for &(name, path) in outputs {
        let target = resolve(path)?;
        if shareable(target.path()) {
            continue;
        }
        let id = identity(&target);
        if let Some((other, other_path, _, is_output)) = seen.iter().find(|s| s.2 == id) {
            let role = if *is_output { "output" } else { "input" };
            return Err(CliError::input(format!(
                "{name} {} and {other} {} are the same file: the {role} would be overwritten; \
                 choose different paths",
                path.display(),
                other_path.display()
            )));
        }
        seen.push((name, path, id, true));
    }
    Ok(())
}
