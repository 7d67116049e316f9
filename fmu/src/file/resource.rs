//! The model-file FMU's resource at instantiation: where the importer says the resources are
//! (FMI 3.0's path, FMI 2.0's `file:` URI), and the model read from there.

use std::path::PathBuf;

use super::description::file_token;
use super::{FileModel, RESOURCE};

/// The FMU's resource directory from the importer's resource location: FMI 3.0's path (with
/// its trailing separator) or FMI 2.0's `file:` URI (`file:///p`, `file://localhost/p`,
/// `file:/p`; `%XX` decoded).
pub fn resource_dir(location: &str) -> PathBuf {
    let path = match location.strip_prefix("file:") {
        Some(rest) => {
            let rest = rest.strip_prefix("//localhost").unwrap_or(rest);
            // `file:///p` → `/p` (an empty authority).
            let rest = rest.strip_prefix("//").unwrap_or(rest);
            let mut out = Vec::new();
            let bytes = rest.as_bytes();
            let mut k = 0;
            while let Some(&b) = bytes.get(k) {
                let hex = bytes
                    .get(k + 1..k + 3)
                    .and_then(|h| std::str::from_utf8(h).ok())
                    .and_then(|h| u8::from_str_radix(h, 16).ok());
                match (b, hex) {
                    (b'%', Some(v)) => {
                        out.push(v);
                        k += 3;
                    }
                    _ => {
                        out.push(b);
                        k += 1;
                    }
                }
            }
            String::from_utf8_lossy(&out).into_owned()
        }
        None => location.to_owned(),
    };
    PathBuf::from(path)
}

/// The resource's text and the model it states, read from the resource location `location`
/// for an instance given `token`; `Ok(None)` when there is no model resource there (then the
/// token is not a model-file FMU's).
///
/// # Errors
/// A resource that cannot be read or parsed, or a token that is not the resource's.
pub fn read_resource(location: Option<&str>, token: &str) -> Result<Option<FileModel>, String> {
    let Some(location) = location else {
        return Ok(None);
    };
    let path = resource_dir(location).join(RESOURCE);
    let Ok(text) = std::fs::read_to_string(&path) else {
        return Ok(None);
    };
    if file_token(&text) != token {
        return Err(format!(
            "instantiation token {token:?} is not that of the model in {} (rebuild the FMU with cargo xtask fmu --model)",
            path.display()
        ));
    }
    FileModel::parse(&text)
        .map(Some)
        .map_err(|e| format!("{}: {e}", path.display()))
}
