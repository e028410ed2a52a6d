//! Files noncirc writes and reads: atomic writes that name the file in their errors, and
//! bounded reads of regular files.

use crate::{Error, Result};
use std::path::Path;
use std::sync::atomic::{AtomicU64, Ordering};

/// Writes `contents` to `path` atomically: a temporary file of this process's own in the
/// same directory (two runs sharing a path never share it), synced, renamed over `path`,
/// and the directory synced so the rename survives a power cut.
pub fn write_atomic(path: &Path, contents: &[u8]) -> std::io::Result<()> {
    use std::io::Write;
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let name = path.file_name().ok_or_else(|| {
        std::io::Error::new(std::io::ErrorKind::InvalidInput, "the path names no file")
    })?;
    let tmp = path.with_file_name(format!(
        ".{}.{}-{}.tmp",
        name.to_string_lossy(),
        std::process::id(),
        COUNTER.fetch_add(1, Ordering::Relaxed)
    ));
    let written = (|| {
        let mut f = std::fs::File::create(&tmp)?;
        f.write_all(contents)?;
        f.sync_all()?;
        std::fs::rename(&tmp, path)
    })();
    if written.is_err() {
        std::fs::remove_file(&tmp).ok();
    }
    written?;
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    // Directories cannot be opened for syncing everywhere (Windows): best effort.
    if let Ok(d) = std::fs::File::open(dir) {
        d.sync_all().ok();
    }
    Ok(())
}

/// [`write_atomic`], naming the file in the error (nothing is left behind on failure).
pub fn write_file(path: &Path, contents: &[u8]) -> Result<()> {
    write_atomic(path, contents).map_err(|e| Error::file("write", path, e))
}

/// Creates a directory and its parents, naming it in the error.
pub fn create_dir(dir: &Path) -> Result<()> {
    std::fs::create_dir_all(dir).map_err(|e| Error::file("create", dir, e))
}

/// Reads a regular file of at most `max` bytes, naming the path in every error.
pub fn read_limited(path: &Path, max: u64) -> Result<Vec<u8>> {
    let meta = std::fs::metadata(path).map_err(|e| Error::file("read", path, e))?;
    if !meta.is_file() {
        return Err(Error::Input(format!(
            "{} is not a regular file",
            path.display()
        )));
    }
    if meta.len() > max {
        return Err(Error::Input(format!(
            "{} is {} bytes, more than the {max} this reads",
            path.display(),
            meta.len()
        )));
    }
    std::fs::read(path).map_err(|e| Error::file("read", path, e))
}

/// Pretty JSON of `value` (`what` names it in the error).
pub fn json_text(value: &impl serde::Serialize, what: &'static str) -> Result<String> {
    serde_json::to_string_pretty(value).map_err(|e| Error::Serialise {
        what,
        message: e.to_string(),
    })
}

/// TOML of `value` (`what` names it in the error).
pub fn toml_text(value: &impl serde::Serialize, what: &'static str) -> Result<String> {
    toml::to_string(value).map_err(|e| Error::Serialise {
        what,
        message: e.to_string(),
    })
}
