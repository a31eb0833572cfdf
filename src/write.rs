//! Atomic output: a file is written to a temporary name in its folder, then renamed.
//!
//! Callers render every output into memory first and write only when all succeeded, so a
//! failed build leaves no half-written file; a reader never sees a partial file.

use std::fs;
use std::io::{self, Write};
use std::path::Path;

/// Writes `bytes` to `path` atomically (temp file in the same folder, fsync, rename),
/// creating the parent folder if needed.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> io::Result<()> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    fs::create_dir_all(dir)?;
    let name = path.file_name().ok_or_else(|| {
        io::Error::new(io::ErrorKind::InvalidInput, "output path has no file name")
    })?;
    let tmp = dir.join(format!(
        ".{}.tmp{}",
        name.to_string_lossy(),
        std::process::id()
    ));
    let result = (|| {
        let mut file = fs::File::create(&tmp)?;
        file.write_all(bytes)?;
        file.sync_all()?;
        fs::rename(&tmp, path)
    })();
    if result.is_err() {
        let _ = fs::remove_file(&tmp);
    }
    result
}

/// Writes every `(path, bytes)` pair atomically, in order; stops at the first error.
pub fn write_all_atomic<P: AsRef<Path>>(files: &[(P, Vec<u8>)]) -> io::Result<()> {
    for (path, bytes) in files {
        write_atomic(path.as_ref(), bytes)?;
    }
    Ok(())
}
