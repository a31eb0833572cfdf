//! Watching the font folder: file events (inotify, FSEvents, ...) through `notify`, no
//! polling, so an idle server sleeps.
//!
//! Events that arrive within [`SETTLE`] of each other are taken as one change (an editor's
//! save or a `git checkout` touches several files, or one file several times); then the
//! font is reloaded once and the outcome broadcast.

use std::path::{Path, PathBuf};
use std::sync::mpsc::{channel, RecvTimeoutError};
use std::sync::{Arc, Mutex};
use std::time::Duration;

use notify::{RecursiveMode, Watcher};

use super::events::Hub;
use super::state::Studio;
use super::{reload_message, ServeError};

/// How long the folder must be quiet before a reload.
const SETTLE: Duration = Duration::from_millis(8);

/// Starts watching `dir`; the watcher lives as long as the returned value.
pub fn watch(
    dir: &Path,
    studio: Arc<Mutex<Studio>>,
    hub: Arc<Hub>,
) -> Result<notify::RecommendedWatcher, ServeError> {
    let (tx, rx) = channel();
    let mut watcher = notify::recommended_watcher(tx)?;
    watcher.watch(dir, RecursiveMode::NonRecursive)?;
    std::thread::spawn(move || {
        while let Ok(event) = rx.recv() {
            let mut paths = Vec::new();
            let mut relevant = source_paths(event, &mut paths);
            loop {
                match rx.recv_timeout(SETTLE) {
                    Ok(more) => relevant |= source_paths(more, &mut paths),
                    Err(RecvTimeoutError::Timeout) => break,
                    Err(RecvTimeoutError::Disconnected) => return,
                }
            }
            if !relevant {
                continue;
            }
            let outcome = match studio.lock() {
                Ok(studio) if studio.is_current(&paths) => continue,
                Ok(mut studio) => studio.reload(),
                Err(_) => return,
            };
            if let Some(message) = reload_message(&outcome) {
                hub.broadcast(&message);
            }
        }
    });
    Ok(watcher)
}

/// Whether an event touches a source file (`*.toml` not starting with `.`); its paths
/// are added to `paths`. An error from the watcher counts as a change (reload to be sure).
fn source_paths(event: notify::Result<notify::Event>, paths: &mut Vec<PathBuf>) -> bool {
    let Ok(event) = event else {
        paths.push(PathBuf::new());
        return true;
    };
    if matches!(event.kind, notify::EventKind::Access(_)) {
        return false;
    }
    let mut relevant = false;
    for p in event.paths {
        let name = p.file_name().map(|n| n.to_string_lossy().into_owned());
        if name.is_some_and(|n| n.ends_with(".toml") && !n.starts_with('.')) {
            relevant = true;
            paths.push(p);
        }
    }
    relevant
}
