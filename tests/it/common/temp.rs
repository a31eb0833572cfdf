//! Temporary folders for tests, removed when dropped (also when the test fails).

use std::ffi::OsStr;
use std::ops::Deref;
use std::path::Path;

/// A fresh folder in the temp dir named from a tag; it derefs to its path.
pub struct TempFolder(tempfile::TempDir);

impl TempFolder {
    /// A new empty folder `xglyph-<tag>-<random>`.
    pub fn new(tag: &str) -> TempFolder {
        let dir = tempfile::Builder::new()
            .prefix(&format!("xglyph-{tag}-"))
            .tempdir()
            .expect("a temporary folder");
        TempFolder(dir)
    }
}

impl Deref for TempFolder {
    type Target = Path;
    fn deref(&self) -> &Path {
        self.0.path()
    }
}

impl AsRef<Path> for TempFolder {
    fn as_ref(&self) -> &Path {
        self.0.path()
    }
}

impl AsRef<OsStr> for TempFolder {
    fn as_ref(&self) -> &OsStr {
        self.0.path().as_os_str()
    }
}
