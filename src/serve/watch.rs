//! Watching the font folder: file events (inotify, FSEvents, ...) through `notify`, no
//! polling, so an idle server sleeps.
//!
//! Events that arrive within [`SETTLE`] of each other are taken as one change (an editor's
//! save or a `git checkout` touches several files, or one file several times); then the
//! font is reloaded once and the outcome broadcast.

use std::path::Path;
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
            let mut relevant = is_source_event(&event);
            loop {
                match rx.recv_timeout(SETTLE) {
                    Ok(more) => relevant |= is_source_event(&more),
                    Err(RecvTimeoutError::Timeout) => break,
                    Err(RecvTimeoutError::Disconnected) => return,
                }
            }
            if !relevant {
                continue;
            }
            let outcome = match studio.lock() {
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

/// Whether an event touches a source file (`*.toml` not starting with `.`).
fn is_source_event(event: &notify::Result<notify::Event>) -> bool {
    let Ok(event) = event else {
        return true;
    };
    if matches!(event.kind, notify::EventKind::Access(_)) {
        return false;
    }
    event.paths.iter().any(|p| {
        let name = p.file_name().map(|n| n.to_string_lossy().into_owned());
        name.is_some_and(|n| n.ends_with(".toml") && !n.starts_with('.'))
    })
}
