//! A folder's whole contents as one comparable value, shared by the integration tests of
//! writing (`tests/it/writes.rs`) and the unit tests of `src/write.rs` (included there by
//! path, as unit tests cannot reach `tests/`).
// Each includer uses a different subset.
#![allow(dead_code)]

use std::fs;
use std::path::Path;

/// Everything under `dir`, hidden files included, sorted by relative path: the bytes of a
/// file, `-> target` for a link (not followed), `/` for a folder. Empty when `dir` does
/// not exist.
pub fn tree(dir: &Path) -> Vec<(String, Vec<u8>)> {
    fn walk(root: &Path, dir: &Path, out: &mut Vec<(String, Vec<u8>)>) {
        for entry in fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            let rel = path.strip_prefix(root).unwrap().display().to_string();
            let meta = fs::symlink_metadata(&path).unwrap();
            if meta.file_type().is_symlink() {
                let target = fs::read_link(&path).unwrap();
                out.push((rel, format!("-> {}", target.display()).into_bytes()));
            } else if meta.is_dir() {
                out.push((rel, b"/".to_vec()));
                walk(root, &path, out);
            } else {
                out.push((rel, fs::read(&path).unwrap()));
            }
        }
    }
    let mut out = Vec::new();
    if dir.exists() {
        walk(dir, dir, &mut out);
    }
    out.sort();
    out
}

/// The expected form of [`tree`] from `(relative path, contents)` pairs written as text.
pub fn entries(list: &[(&str, &str)]) -> Vec<(String, Vec<u8>)> {
    list.iter()
        .map(|(name, contents)| (name.to_string(), contents.as_bytes().to_vec()))
        .collect()
}
