//! Writing outputs all-or-nothing: an [`OutputSet`] of `(path, bytes)` is committed as one
//! transaction.
//!
//! [`OutputSet::commit`] works in two phases:
//!
//! 1. **Stage.** Each output folder is asked once whether it exists. A file of an existing
//!    folder goes to a new temporary file in that folder, created exclusively (`O_EXCL`)
//!    under an unpredictable name (`.xglyph-PID-RANDOM.tmp`, by [`tempfile`]), so a planted
//!    file or link at a guessed name is never opened or followed. A missing folder is not
//!    made in place: the top-most missing folder of each new tree is staged whole, as a new
//!    folder of an unpredictable name next to it (`.xglyph-PID-RANDOM.dir`), and the tree's
//!    folders and files are made inside it under their final names (a cold build into a
//!    new OUT then renames once, not 42,000 times). The staged files and trees are flushed
//!    to disk. An output whose file already holds exactly its bytes (a regular file, not a
//!    link) is not staged at all: a rebuild rewrites only what changed, and a build that
//!    changes nothing writes nothing. To know that without reading the file back, a set
//!    can be given the [`FileStamp`]s of the last commit ([`OutputSet::trusting`]): a file
//!    whose length, inode, modification and change times are those recorded, and whose
//!    recorded SHA-256 is that of the new bytes, holds them already. Anything else is
//!    compared byte for byte. A file changed in the last 50 ms gets no stamp (the file
//!    system's clock is coarse: see [`FileStamp`]). Outputs whose bytes the caller did not
//!    make, because it knows from their stamps that OUT holds them already, are declared
//!    with [`OutputSet::keeping`]: they are left alone and only count for the duplicate
//!    check and the cleaning of their folders.
//! 2. **Commit.** Each staged tree is renamed onto its top-most folder's name, which must
//!    still be free (on Linux the rename itself refuses to replace anything). Then each
//!    staged file is renamed over its final name (atomic on one file system; a link at the
//!    final name is replaced, never followed). A file it replaces is kept first under a
//!    backup name (`.xglyph-PID-RANDOM.old`, a hard link where the file system allows it, so
//!    the final name never goes missing).
//!
//! If anything fails, everything is rolled back: temporary files are removed, replaced
//! files are restored from their backups, added files are removed, and staged trees are
//! renamed back off their final names and removed, so the output folders are left exactly
//! as they were. The error names the output path (for a new folder, its final name) and
//! the reason. On success the backups are removed.
//!
//! A build killed with `SIGKILL` leaves only complete files under final names (each one
//! old or new; a new folder appears whole or not at all), plus temporary or backup files
//! and staged trees of our naming. The next commit into the same folder, or staging a new
//! tree in it, removes those whose process is gone ([`remove_stale`]); it never touches
//! another name, nor the files of a build that is still running. A staged tree left next
//! to a new OUT stays there until a commit stages a tree in that folder again.
//!
//! Limits: folders on the way to an output may be links (an output folder that is a link to
//! another folder is written through); only the final name is never followed. A rollback
//! can itself fail (the disk removed mid-way): the error then says so and which file is
//! affected. A second build writing into the same folder at the same time is not locked
//! out; each file is still whole, but the set may mix both builds (two builds making the
//! same new folder: the second one fails and rolls back). Two spellings of one new folder
//! that the file system takes as the same (case-insensitive names) are staged as two trees,
//! and the commit fails at the second one's rename.

use std::collections::{HashMap, HashSet};
use std::fmt;
use std::fs::{self, File};
use std::io::{self, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

use rayon::prelude::*;
use tempfile::{Builder, TempPath};

/// Prefix of every temporary or backup file we create (followed by `PID-`).
const PREFIX: &str = ".xglyph-";
/// Suffix of a staged file.
const TMP: &str = ".tmp";
/// Suffix of a backup of a replaced file.
const OLD: &str = ".old";
/// Suffix of a staged new folder tree.
const DIR: &str = ".dir";
/// Random characters in a temporary name (62 possibilities each).
const RANDOM_LEN: usize = 10;

/// Outputs to write together: all of them, or none.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct OutputSet {
    files: Vec<(PathBuf, Vec<u8>)>,
    /// What the last commit left in the files (by output path), trusted while the files'
    /// metadata match.
    earlier: HashMap<PathBuf, FileStamp>,
    /// Outputs that stay as they are in OUT, not written ([`OutputSet::keeping`]).
    kept: Vec<PathBuf>,
}

/// What a file held when a commit last wrote (or kept) it: its metadata (length, inode,
/// modification and change times, to the nanosecond) and the SHA-256 of its bytes. The
/// change time cannot be set back by a user, so a file whose metadata still match was not
/// written since. Only on Unix; elsewhere no stamp matches and files are compared.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FileStamp {
    /// Length, inode, modification time (s, ns), change time (s, ns).
    pub meta: [u64; 6],
    /// SHA-256 of the bytes.
    pub sha256: [u8; 32],
}

/// How long after its last change a file gets a [`FileStamp`]. File systems keep times
/// from a coarse clock (a tick of a few milliseconds): a file changed again within the tick
/// of its last change would keep its times. A file older than this can only be changed in a
/// later tick, which moves its change time. (Git's "racy" index entries, the same problem.)
/// A file whose change time is in whole seconds waits 2 s instead.
pub const SETTLED: std::time::Duration = std::time::Duration::from_millis(50);

impl FileStamp {
    /// The stamp of the file at `path` (not following a link), holding bytes of `sha256`;
    /// none for a file changed less than [`SETTLED`] ago (the next commit compares it).
    fn of(path: &Path, sha256: [u8; 32]) -> Option<FileStamp> {
        let meta = fs::symlink_metadata(path).ok()?;
        settled_meta(&meta).map(|meta| FileStamp { meta, sha256 })
    }

    /// Whether the file at `path` (not following a link) still has this stamp's metadata.
    pub fn matches(&self, path: &Path) -> bool {
        fs::symlink_metadata(path)
            .ok()
            .and_then(|meta| stamp_meta(&meta))
            == Some(self.meta)
    }
}

/// The metadata a [`FileStamp`] records of a regular file, when it last changed at least
/// [`SETTLED`] ago: while these metadata stay the same, so do its bytes. `None` for a file
/// changed more recently (it may change again within the same clock tick), for anything
/// but a regular file, and off Unix. Take it before reading the file: a change after the
/// read then moves the metadata away from the ones recorded.
pub fn settled_meta(meta: &fs::Metadata) -> Option<[u64; 6]> {
    let stamp = stamp_meta(meta)?;
    settled(&stamp, std::time::SystemTime::now()).then_some(stamp)
}

/// Whether a file of metadata `stamp` ([`stamp_meta`]) last changed long enough before
/// `now` for a later change to move its change time.
fn settled(stamp: &[u64; 6], now: std::time::SystemTime) -> bool {
    let Ok(nanos) = u32::try_from(stamp[5]) else {
        return false;
    };
    let changed = std::time::UNIX_EPOCH + std::time::Duration::new(stamp[4], nanos);
    // A change time in whole seconds most likely comes from a file system that keeps
    // seconds only (FAT keeps two): its tick is then taken as 2 s.
    let tick = if nanos == 0 { COARSE_TICK } else { SETTLED };
    now.duration_since(changed).is_ok_and(|age| age >= tick)
}

/// How long after its last change a file with a change time in whole seconds gets a stamp.
const COARSE_TICK: std::time::Duration = std::time::Duration::from_secs(2);

/// The metadata a [`FileStamp`] records, of a regular file (`None` for anything else).
#[cfg(unix)]
fn stamp_meta(meta: &fs::Metadata) -> Option<[u64; 6]> {
    use std::os::unix::fs::MetadataExt;
    meta.is_file().then(|| {
        [
            meta.len(),
            meta.ino(),
            meta.mtime() as u64,
            meta.mtime_nsec() as u64,
            meta.ctime() as u64,
            meta.ctime_nsec() as u64,
        ]
    })
}

#[cfg(not(unix))]
fn stamp_meta(_: &fs::Metadata) -> Option<[u64; 6]> {
    None
}

/// The SHA-256 of `bytes`.
pub fn sha256(bytes: &[u8]) -> [u8; 32] {
    use sha2::{Digest, Sha256};
    Sha256::digest(bytes).into()
}

/// Why an [`OutputSet`] could not be committed: the output path and the reason.
#[derive(Debug)]
pub struct WriteError {
    /// The output file or folder that could not be written or created.
    pub path: PathBuf,
    /// What went wrong.
    pub kind: WriteErrorKind,
    /// Set when the rollback also failed: what could not be restored, and why.
    pub rollback: Option<String>,
}

/// The reason part of a [`WriteError`].
#[derive(Debug)]
pub enum WriteErrorKind {
    /// A folder stands where the output file goes.
    FolderInTheWay,
    /// A file (not a folder) stands where an output folder goes.
    FileInTheWay,
    /// Two outputs of one set have the same path.
    Duplicate,
    /// The file system refused to create an output folder.
    Folder(io::Error),
    /// The file system refused to write or rename an output file.
    Io(io::Error),
    /// Ctrl-C arrived while the set was being written ([`exit_on_interrupt`]).
    Interrupted,
}

impl fmt::Display for WriteError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let path = self.path.display();
        match &self.kind {
            WriteErrorKind::FolderInTheWay => {
                write!(
                    f,
                    "cannot write {path}: a folder of that name is in the way"
                )
            }
            WriteErrorKind::FileInTheWay => write!(
                f,
                "cannot create the folder {path}: a file of that name is in the way"
            ),
            WriteErrorKind::Duplicate => write!(f, "cannot write {path} twice in one set"),
            WriteErrorKind::Folder(e) => {
                write!(f, "cannot create the folder {path}: {}", reason(e))
            }
            WriteErrorKind::Io(e) => write!(f, "cannot write {path}: {}", reason(e)),
            WriteErrorKind::Interrupted => write!(f, "interrupted while writing {path}"),
        }?;
        if let Some(rollback) = &self.rollback {
            write!(f, "; and the rollback failed: {rollback}")?;
        }
        Ok(())
    }
}

impl std::error::Error for WriteError {}

/// The operating system's message for `e`, without the `(os error N)` tail and with a
/// lowercase first letter, to follow a colon ("file name too long").
pub fn reason(e: &io::Error) -> String {
    let text = e.to_string();
    let text = match text.rfind(" (os error ") {
        Some(i) if text.ends_with(')') => &text[..i],
        _ => &text,
    };
    let mut chars = text.chars();
    match chars.next() {
        Some(c) => c.to_lowercase().chain(chars).collect(),
        None => String::new(),
    }
}

impl OutputSet {
    /// An empty set.
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds an output. Parent folders are created on commit. A link at `path` is replaced
    /// by the file, not followed (resolve it first to write through it).
    pub fn add(&mut self, path: impl Into<PathBuf>, bytes: impl Into<Vec<u8>>) {
        self.files.push((path.into(), bytes.into()));
    }

    /// The outputs in the order they were added.
    pub fn files(&self) -> &[(PathBuf, Vec<u8>)] {
        &self.files
    }

    /// Number of outputs.
    pub fn len(&self) -> usize {
        self.files.len()
    }

    /// Whether the set has no outputs.
    pub fn is_empty(&self) -> bool {
        self.files.is_empty()
    }

    /// Trusts `earlier` (by output path, as [`OutputSet::commit_stamped`] returned them):
    /// an output whose file still has its stamp's metadata, and whose bytes have its
    /// stamp's hash, is left alone without being read.
    pub fn trusting(mut self, earlier: HashMap<PathBuf, FileStamp>) -> Self {
        self.earlier = earlier;
        self
    }

    /// Declares outputs that are already in place and stay as they are (the caller knows
    /// their files hold their bytes: [`crate::reuse::Reuse::kept_or_make`]). They are not
    /// written; they count for the duplicate check, and their folders are cleaned of stale
    /// temporary files like those of written outputs.
    pub fn keeping(mut self, kept: Vec<PathBuf>) -> Self {
        self.kept = kept;
        self
    }

    /// Writes every output, or none (see the module docs). Stale temporary files of a
    /// killed earlier commit in the output folders are removed first.
    pub fn commit(self) -> Result<(), WriteError> {
        self.commit_with(Transaction::default(), false).map(drop)
    }

    /// [`OutputSet::commit`], returning each output's [`FileStamp`] after the commit (for
    /// the next commit's [`OutputSet::trusting`]); an output whose file cannot be stat'ed
    /// has none.
    pub fn commit_stamped(self) -> Result<HashMap<PathBuf, FileStamp>, WriteError> {
        self.commit_with(Transaction::default(), true)
    }

    fn commit_with(
        self,
        mut tx: Transaction,
        stamped: bool,
    ) -> Result<HashMap<PathBuf, FileStamp>, WriteError> {
        let _committing = Committing::start();
        // Hashed on every core (a CJK font's 700 MB of outputs), only when stamps are used.
        let hashes: Vec<[u8; 32]> = if stamped || !self.earlier.is_empty() {
            self.files.par_iter().map(|(_, b)| sha256(b)).collect()
        } else {
            Vec::new()
        };
        let result = tx.run(&self.files, &hashes, &self.earlier, &self.kept);
        match result {
            Ok(()) => {
                tx.finish();
                if !stamped {
                    return Ok(HashMap::new());
                }
                Ok(self
                    .files
                    .par_iter()
                    .zip(hashes)
                    .filter_map(|((path, _), sha)| Some((path.clone(), FileStamp::of(path, sha)?)))
                    .collect())
            }
            Err(mut err) => {
                err.rollback = tx.roll_back();
                Err(err)
            }
        }
    }
}

/// One output on its way into place: the backup of the file it replaces, and whether the
/// new file is in place yet.
struct Committed {
    path: PathBuf,
    backup: Option<PathBuf>,
    placed: bool,
}

/// Where the files of one output folder go.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Place {
    /// The folder exists: each file is staged next to its final name, then renamed.
    Existing,
    /// This commit makes the folder: its files are written under their final names into
    /// its staged copy, [`Transaction::new_dirs`]`[i]`, inside a [`NewTree`].
    New(usize),
}

/// A folder tree this commit makes: staged whole under a temporary name next to its
/// top-most folder `root`, and renamed onto `root` at commit time (one rename for all its
/// files: a cold CJK build's 42,000 outputs lie in one new OUT).
struct NewTree {
    root: PathBuf,
    temp: PathBuf,
    /// Renamed onto `root` already.
    placed: bool,
}

/// The undo log of one commit.
#[derive(Default)]
struct Transaction {
    /// The new folder trees, in the order they were staged.
    trees: Vec<NewTree>,
    /// Where each new folder is staged (inside one of `trees`), by [`Place::New`] index.
    new_dirs: Vec<PathBuf>,
    /// Staged files not yet renamed; dropping one removes it.
    /// Closed as soon as written: a font of 20,000 glyphs stages 40,000 files, far more
    /// than a process may keep open.
    staged: Vec<(TempPath, PathBuf)>,
    committed: Vec<Committed>,
    /// Tests: fail just before the rename with this index (the new trees first, then the
    /// staged files, each in the outputs' order).
    #[cfg(test)]
    fail_before_rename: Option<usize>,
    /// Tests: wait until the staged files are old enough for stamps before renaming.
    #[cfg(test)]
    settle_before_renames: bool,
}

impl Transaction {
    fn run(
        &mut self,
        files: &[(PathBuf, Vec<u8>)],
        hashes: &[[u8; 32]],
        earlier: &HashMap<PathBuf, FileStamp>,
        kept: &[PathBuf],
    ) -> Result<(), WriteError> {
        let mut seen = std::collections::HashSet::new();
        for path in files.iter().map(|(path, _)| path).chain(kept) {
            if !seen.insert(path.as_path()) {
                return Err(error(path, WriteErrorKind::Duplicate));
            }
        }
        // Each folder is asked once (a CJK build's 42,000 outputs lie in a few folders), in
        // the outputs' order, so that the first folder error in that order is reported.
        let mut known = HashMap::new();
        let mut cleaned = std::collections::HashSet::new();
        let mut places = Vec::with_capacity(files.len());
        for (path, _) in files {
            let dir = parent(path);
            let place = self.locate(dir, &mut known)?;
            // A new folder holds no stale files.
            if place == Place::Existing && cleaned.insert(dir.to_path_buf()) {
                remove_stale(dir, files);
            }
            check_interrupt(path)?;
            places.push(place);
        }
        // Which files already hold their bytes, asked on every core (a CJK build's 42,000
        // `stat`s): a file's answer depends only on its own path. A file of a new folder is
        // new.
        let changed: Vec<bool> = files
            .par_iter()
            .zip(&places)
            .enumerate()
            .map(|(k, ((path, bytes), place))| {
                *place != Place::Existing
                    || !unchanged(path, bytes, earlier.get(path), hashes.get(k))
            })
            .collect();
        let to_stage: Vec<_> = files
            .iter()
            .zip(places)
            .zip(changed)
            .filter_map(|((file, place), changed)| changed.then_some((file, place)))
            .collect();
        // Staged on every core (a CJK build creates 42,000 files); the first error in the
        // outputs' order is reported, and every staged file, kept or dropped, is removed on
        // an error (those in new folders with their tree, by the rollback).
        let new_dirs = &self.new_dirs;
        let staged: Vec<Result<Option<(TempPath, PathBuf)>, WriteError>> = to_stage
            .par_iter()
            .map(|((path, bytes), place)| {
                check_interrupt(path)?;
                match place {
                    Place::Existing => stage(path, bytes).map(Some),
                    Place::New(i) => write_new(path, &new_dirs[*i], bytes).map(|()| None),
                }
            })
            .collect();
        for staged in staged {
            if let Some(staged) = staged? {
                self.staged.push(staged);
            }
        }
        // The folders the new trees are staged in may hold a killed commit's staged tree.
        let tree_parents: Vec<PathBuf> = self
            .trees
            .iter()
            .map(|t| parent(&t.root).to_path_buf())
            .collect();
        let kept_dirs = kept.iter().map(|path| parent(path).to_path_buf());
        for dir in kept_dirs.chain(tree_parents) {
            if !cleaned.contains(&dir) {
                remove_stale(&dir, files);
                cleaned.insert(dir);
            }
        }
        if self.staged.is_empty() && self.trees.is_empty() {
            // Every output already holds its bytes: nothing to write, nothing to flush.
            return Ok(());
        }
        self.sync_staged()?;
        #[cfg(test)]
        if self.settle_before_renames {
            std::thread::sleep(SETTLED * 2);
        }
        // The new trees first, one rename each; a kill between two renames leaves whole
        // files, each old or new, like a kill between two file renames.
        for k in 0..self.trees.len() {
            let root = self.trees[k].root.clone();
            self.injected_failure(k, &root, true)?;
            check_interrupt(&root)?;
            rename_new(&self.trees[k].temp, &root)
                .map_err(|e| error(&root, WriteErrorKind::Folder(e)))?;
            self.trees[k].placed = true;
        }
        // The files of existing folders, renamed on every core (a rebuild that changes
        // every glyph renames 42,000 files): each file's undo record is kept whatever the
        // others do; after an error the renames not begun are skipped, which drops (removes)
        // their staged files, and the first error in the outputs' order is reported.
        let staged = std::mem::take(&mut self.staged);
        let failed = AtomicBool::new(false);
        let this = &*self;
        let done: Vec<(Option<Committed>, Result<(), WriteError>)> = staged
            .into_par_iter()
            .enumerate()
            .map(|(k, (temp, path))| {
                if failed.load(Ordering::Relaxed) {
                    return (None, Ok(()));
                }
                let ready = this.injected_failure(this.trees.len() + k, &path, false);
                let done = match ready.and_then(|()| check_interrupt(&path)) {
                    Ok(()) => rename_into_place(temp, path),
                    Err(e) => (None, Err(e)),
                };
                if done.1.is_err() {
                    failed.store(true, Ordering::Relaxed);
                }
                done
            })
            .collect();
        let mut first_error = None;
        for (record, result) in done {
            self.committed.extend(record);
            if let Err(e) = result {
                first_error.get_or_insert(e);
            }
        }
        if let Some(e) = first_error {
            return Err(e);
        }
        sync_renames(&self.committed, &self.trees);
        Ok(())
    }

    /// Tests: the injected failure before rename `k` (of `path`, a new tree's top-most
    /// folder when `folder`).
    #[cfg(test)]
    fn injected_failure(&self, k: usize, path: &Path, folder: bool) -> Result<(), WriteError> {
        if self.fail_before_rename != Some(k) {
            return Ok(());
        }
        let injected = io::Error::other("injected failure");
        let kind = if folder {
            WriteErrorKind::Folder(injected)
        } else {
            WriteErrorKind::Io(injected)
        };
        Err(error(path, kind))
    }

    #[cfg(not(test))]
    fn injected_failure(&self, _: usize, _: &Path, _: bool) -> Result<(), WriteError> {
        Ok(())
    }

    /// Where the files of output folder `dir` go; `known` holds the folders asked already.
    /// A missing folder is made in the staged copy of its tree; the top-most missing one
    /// starts a new tree ([`Transaction::stage_tree`]). Errors name the final folder.
    fn locate(
        &mut self,
        dir: &Path,
        known: &mut HashMap<PathBuf, Place>,
    ) -> Result<Place, WriteError> {
        let mut missing = Vec::new();
        let mut at = dir;
        let mut place = loop {
            if let Some(&place) = known.get(at) {
                break place;
            }
            if at.as_os_str().is_empty() {
                break Place::Existing;
            }
            match fs::metadata(at) {
                Ok(meta) if meta.is_dir() => break Place::Existing,
                Ok(_) => return Err(error(at, WriteErrorKind::FileInTheWay)),
                // A folder ending in `..` names no new folder: only an existing one resolves.
                Err(e) if e.kind() == io::ErrorKind::NotFound => match at.file_name() {
                    Some(name) => missing.push((at, name)),
                    None => return Err(error(at, WriteErrorKind::Folder(e))),
                },
                Err(e) => return Err(error(at, WriteErrorKind::Folder(e))),
            }
            at = parent(at);
        };
        known.insert(at.to_path_buf(), place);
        for (d, name) in missing.into_iter().rev() {
            let staged = match place {
                Place::Existing => self.stage_tree(d)?,
                Place::New(i) => {
                    let staged = self.new_dirs[i].join(name);
                    fs::create_dir(&staged).map_err(|e| error(d, WriteErrorKind::Folder(e)))?;
                    staged
                }
            };
            self.new_dirs.push(staged);
            place = Place::New(self.new_dirs.len() - 1);
            known.insert(d.to_path_buf(), place);
        }
        Ok(place)
    }

    /// Creates the staged copy of new folder `root`, in its parent folder under a new name
    /// (`.xglyph-PID-RANDOM.dir`, created exclusively, so nothing planted is followed).
    fn stage_tree(&mut self, root: &Path) -> Result<PathBuf, WriteError> {
        let prefix = format!("{PREFIX}{}-", std::process::id());
        let temp = Builder::new()
            .prefix(&prefix)
            .suffix(DIR)
            .rand_bytes(RANDOM_LEN)
            .make_in(parent(root), |name| fs::create_dir(name))
            .and_then(|made| made.into_temp_path().keep().map_err(|e| e.error))
            .map_err(|e| error(root, WriteErrorKind::Folder(e)))?;
        self.trees.push(NewTree {
            root: root.to_path_buf(),
            temp: temp.clone(),
            placed: false,
        });
        Ok(temp)
    }

    /// Puts every staged file's data, and every new tree, on disk before the first rename,
    /// so that no final name can ever point at unwritten data. On Linux one `syncfs` per
    /// file system does it (through the staged file's or tree's folder): a build of 4,000
    /// glyph SVGs spent 2 s in 4,000 `fsync`s, against 0.5 s of work. Elsewhere each file
    /// was synced as it was written, and each new folder is synced here (Unix).
    fn sync_staged(&self) -> Result<(), WriteError> {
        let files = self.staged.iter().map(|(temp, path)| {
            let temp: &Path = temp;
            (temp, parent(path), path.as_path())
        });
        let trees = self
            .trees
            .iter()
            .map(|t| (t.temp.as_path(), t.temp.as_path(), t.root.as_path()));
        #[cfg(target_os = "linux")]
        {
            use std::os::unix::fs::MetadataExt;
            let mut synced = std::collections::HashSet::new();
            for (staged, dir, path) in files.chain(trees) {
                let io_err = |e| error(path, WriteErrorKind::Io(e));
                let device = fs::symlink_metadata(staged).map_err(io_err)?.dev();
                if synced.insert(device) {
                    let dir = File::open(dir_or_current(dir)).map_err(io_err)?;
                    rustix::fs::syncfs(&dir).map_err(|e| io_err(e.into()))?;
                }
            }
        }
        #[cfg(not(target_os = "linux"))]
        {
            let _ = (files, trees);
            if cfg!(unix) {
                for dir in &self.new_dirs {
                    let synced = File::open(dir).and_then(|d| d.sync_all());
                    synced.map_err(|e| error(dir, WriteErrorKind::Folder(e)))?;
                }
            }
        }
        Ok(())
    }

    /// Undoes everything; `None` when it all came back, else what did not.
    fn roll_back(&mut self) -> Option<String> {
        self.staged.clear();
        let mut failures = Vec::new();
        while let Some(c) = self.committed.pop() {
            if let Err(e) = restore(&c) {
                failures.push(format!("{}: {}", c.path.display(), reason(&e)));
            }
        }
        while let Some(tree) = self.trees.pop() {
            // Off its final name first (one rename), then removed.
            if tree.placed {
                if let Err(e) = fs::rename(&tree.root, &tree.temp) {
                    failures.push(format!("{}: {}", tree.root.display(), reason(&e)));
                    continue;
                }
            }
            if let Err(e) = fs::remove_dir_all(&tree.temp) {
                failures.push(format!("{}: {}", tree.temp.display(), reason(&e)));
            }
        }
        self.new_dirs.clear();
        (!failures.is_empty()).then(|| failures.join("; "))
    }

    /// After success: the backups are no longer needed.
    fn finish(&mut self) {
        for c in self.committed.drain(..) {
            if let Some(b) = c.backup {
                // A backup left behind is stale and removed by the next commit.
                let _ = fs::remove_file(b);
            }
        }
        self.trees.clear();
        self.new_dirs.clear();
    }
}

/// Backs up what is at `path`, then renames the staged file over it; returns the undo
/// record (when a backup was made or the rename tried: a failed rename still restores the
/// backup) and the outcome.
fn rename_into_place(temp: TempPath, path: PathBuf) -> (Option<Committed>, Result<(), WriteError>) {
    let backup = match fs::symlink_metadata(&path) {
        Ok(meta) if meta.is_dir() => {
            return (None, Err(error(&path, WriteErrorKind::FolderInTheWay)));
        }
        Ok(_) => match back_up(&path) {
            Ok(backup) => Some(backup),
            Err(e) => return (None, Err(error(&path, WriteErrorKind::Io(e)))),
        },
        Err(e) if e.kind() == io::ErrorKind::NotFound => None,
        Err(e) => return (None, Err(error(&path, WriteErrorKind::Io(e)))),
    };
    let result = temp.persist(&path).map(drop);
    let result = result.map_err(|e| error(&path, WriteErrorKind::Io(e.error)));
    let placed = result.is_ok();
    let record = Committed {
        path,
        backup,
        placed,
    };
    (Some(record), result)
}

/// Renames the staged tree `from` onto `to`, where nothing may be: on Linux atomically
/// (`RENAME_NOREPLACE`). Elsewhere, or on a Linux file system without that flag, after
/// checking that nothing is at `to` (limit: on Unix, an empty folder made at `to` in
/// between would be replaced).
fn rename_new(from: &Path, to: &Path) -> io::Result<()> {
    #[cfg(target_os = "linux")]
    {
        use rustix::fs::{renameat_with, RenameFlags, CWD};
        use rustix::io::Errno;
        match renameat_with(CWD, from, CWD, to, RenameFlags::NOREPLACE) {
            Err(e) if e == Errno::INVAL || e == Errno::NOSYS => {}
            done => return done.map_err(io::Error::from),
        }
    }
    match fs::symlink_metadata(to) {
        Ok(_) => Err(io::Error::from(io::ErrorKind::AlreadyExists)),
        Err(e) if e.kind() == io::ErrorKind::NotFound => fs::rename(from, to),
        Err(e) => Err(e),
    }
}

/// Writes `bytes` under `path`'s name into `staged_dir`, the staged copy of its new folder,
/// which only this commit writes into: a new file (created exclusively), visible under
/// `path` once its tree is renamed into place.
fn write_new(path: &Path, staged_dir: &Path, bytes: &[u8]) -> Result<(), WriteError> {
    let io_err = |e| error(path, WriteErrorKind::Io(e));
    let Some(name) = path.file_name() else {
        // A path ending in `..` names a folder.
        return Err(error(path, WriteErrorKind::FolderInTheWay));
    };
    let staged = staged_dir.join(name);
    let mut file = match fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(&staged)
    {
        Ok(file) => file,
        // Another output's folder of that name, made by this commit.
        Err(_) if fs::symlink_metadata(&staged).is_ok_and(|m| m.is_dir()) => {
            return Err(error(path, WriteErrorKind::FolderInTheWay));
        }
        Err(e) => return Err(io_err(e)),
    };
    file.write_all(bytes).map_err(io_err)?;
    // Linux flushes the whole file system once instead (`sync_staged`).
    #[cfg(not(target_os = "linux"))]
    file.sync_all().map_err(io_err)?;
    Ok(())
}

/// Writes `bytes` to a new temporary file next to `path`.
fn stage(path: &Path, bytes: &[u8]) -> Result<(TempPath, PathBuf), WriteError> {
    let io_err = |e| error(path, WriteErrorKind::Io(e));
    let existing = match fs::symlink_metadata(path) {
        Ok(meta) if meta.is_dir() => {
            return Err(error(path, WriteErrorKind::FolderInTheWay));
        }
        Ok(meta) => Some(meta),
        Err(e) if e.kind() == io::ErrorKind::NotFound => None,
        Err(e) => return Err(io_err(e)),
    };
    let prefix = format!("{PREFIX}{}-", std::process::id());
    let mut options = fs::OpenOptions::new();
    // Exclusive: fails on any existing name, a link included, which is never followed.
    options.write(true).create_new(true);
    #[cfg(unix)]
    {
        // A new file's mode as `File::create` gives it, 0o666 less the umask
        // (tempfile's own default is 0o600).
        use std::os::unix::fs::OpenOptionsExt;
        options.mode(0o666);
    }
    // `make_in` retries on a name clash and, unlike `tempfile_in`, returns the file
    // system's error as it is (no temporary path in the message).
    let mut temp = Builder::new()
        .prefix(&prefix)
        .suffix(TMP)
        .rand_bytes(RANDOM_LEN)
        .make_in(parent(path), |name| options.open(name))
        .map_err(io_err)?;
    // A replaced regular file keeps its permissions (a link gets a new file's).
    if let Some(meta) = existing.filter(|m| m.is_file()) {
        temp.as_file()
            .set_permissions(meta.permissions())
            .map_err(io_err)?;
    }
    temp.as_file_mut().write_all(bytes).map_err(io_err)?;
    // Linux flushes the whole file system once instead (`sync_staged`).
    #[cfg(not(target_os = "linux"))]
    temp.as_file().sync_all().map_err(io_err)?;
    Ok((temp.into_temp_path(), path.to_path_buf()))
}

/// Set by the Ctrl-C handler of [`exit_on_interrupt`].
static INTERRUPTED: AtomicBool = AtomicBool::new(false);
/// Commits under way in this process.
static COMMITTING: AtomicUsize = AtomicUsize::new(0);

/// Makes Ctrl-C (SIGINT, and SIGTERM) leave the outputs as they were, for a command that
/// writes with [`OutputSet`]: outside a commit the process exits at once with status 130
/// (nothing is written before the commit); during one, the commit stops at its next file,
/// rolls back (removing its temporary files, restoring what it replaced) and fails with
/// [`WriteErrorKind::Interrupted`], and the command exits. Call it once, early; an error
/// means a handler was already set (the outputs then stay whole files, as after a kill).
pub fn exit_on_interrupt() -> Result<(), ctrlc::Error> {
    ctrlc::set_handler(|| {
        // SeqCst on both sides: either this sees the commit, or the commit sees the flag
        // before it writes anything.
        INTERRUPTED.store(true, Ordering::SeqCst);
        if COMMITTING.load(Ordering::SeqCst) == 0 {
            std::process::exit(130);
        }
    })
}

/// A commit in progress, for [`exit_on_interrupt`]'s handler.
struct Committing;

impl Committing {
    fn start() -> Self {
        COMMITTING.fetch_add(1, Ordering::SeqCst);
        Committing
    }
}

impl Drop for Committing {
    fn drop(&mut self) {
        COMMITTING.fetch_sub(1, Ordering::SeqCst);
    }
}

fn check_interrupt(path: &Path) -> Result<(), WriteError> {
    if INTERRUPTED.load(Ordering::SeqCst) {
        return Err(error(path, WriteErrorKind::Interrupted));
    }
    Ok(())
}

/// Puts `c.path` back as it was: the backup over it, or else removes the new file.
fn restore(c: &Committed) -> io::Result<()> {
    match &c.backup {
        Some(b) => fs::rename(b, &c.path),
        None if c.placed => fs::remove_file(&c.path),
        None => Ok(()),
    }
}

/// Keeps what is at `path` under a new backup name in its folder: a hard link, so `path`
/// stays in place; where the file system has no hard links, the file itself is moved (onto
/// a name reserved exclusively first).
fn back_up(path: &Path) -> io::Result<PathBuf> {
    let prefix = format!("{PREFIX}{}-", std::process::id());
    let mut builder = Builder::new();
    builder.prefix(&prefix).suffix(OLD).rand_bytes(RANDOM_LEN);
    let dir = parent(path);
    match builder.make_in(dir, |name| fs::hard_link(path, name)) {
        Ok(linked) => return linked.into_temp_path().keep().map_err(|e| e.error),
        Err(e) if e.kind() == io::ErrorKind::StorageFull => return Err(e),
        Err(_) => {}
    }
    let reserved = builder.tempfile_in(dir)?.into_temp_path();
    fs::rename(path, &reserved)?;
    reserved.keep().map_err(|e| e.error)
}

/// Removes, from `dir`, temporary and backup files left by a killed commit: regular files
/// named `.xglyph-PID-RANDOM.tmp` or `.old` whose process `PID` is gone, folders named
/// `.xglyph-PID-RANDOM.dir` (a staged new folder tree, removed with its contents, links in
/// it not followed), and the temporary names of earlier versions (`.NAME.tmpPID`) for the
/// outputs `files` write into `dir`. Links and every other name are left alone. Errors are
/// ignored (a file that stays is harmless).
pub fn remove_stale(dir: &Path, files: &[(PathBuf, Vec<u8>)]) {
    let Ok(entries) = fs::read_dir(if dir.as_os_str().is_empty() {
        Path::new(".")
    } else {
        dir
    }) else {
        return;
    };
    // The legacy temporary names' stems, `.NAME.tmp`, looked up by hash: a folder of
    // 20,000 outputs would otherwise compare every entry with every name.
    let ours: HashSet<String> = files
        .iter()
        .filter(|(p, _)| parent(p) == dir)
        .filter_map(|(p, _)| Some(format!(".{}.tmp", p.file_name()?.to_str()?)))
        .collect();
    for entry in entries.flatten() {
        let name = entry.file_name();
        let Some(name) = name.to_str() else { continue };
        let tree = our_pid(name, DIR);
        let pid = tree
            .or_else(|| our_pid(name, TMP))
            .or_else(|| our_pid(name, OLD));
        let pid = pid.or_else(|| {
            let digits = name.len() - name.bytes().rev().take_while(u8::is_ascii_digit).count();
            let (stem, pid) = name.split_at(digits);
            ours.contains(stem).then(|| parse_pid(pid)).flatten()
        });
        let Some(pid) = pid else { continue };
        if process_alive(pid) {
            continue;
        }
        // Not following a link: `file_type` is the entry's own.
        let Ok(kind) = entry.file_type() else {
            continue;
        };
        if tree.is_some() && kind.is_dir() {
            let _ = fs::remove_dir_all(entry.path());
        } else if tree.is_none() && kind.is_file() {
            let _ = fs::remove_file(entry.path());
        }
    }
}

/// The PID in a name of our temporary naming with this suffix, `.xglyph-PID-RANDOM.tmp`
/// (`.old`, `.dir`).
fn our_pid(name: &str, suffix: &str) -> Option<u32> {
    let rest = name.strip_prefix(PREFIX)?;
    let rest = rest.strip_suffix(suffix)?;
    let (pid, random) = rest.split_once('-')?;
    let random_ok = random.len() == RANDOM_LEN && random.bytes().all(|b| b.is_ascii_alphanumeric());
    random_ok.then(|| parse_pid(pid)).flatten()
}

fn parse_pid(digits: &str) -> Option<u32> {
    if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    digits.parse().ok()
}

/// Whether process `pid` may still be running (and writing its temporary files). Ours is;
/// on Linux, any PID with an entry in /proc is. Where that cannot be known (no /proc), every
/// process counts as alive, so nothing is removed.
fn process_alive(pid: u32) -> bool {
    if pid == std::process::id() {
        return true;
    }
    let proc = Path::new("/proc");
    if !proc.join("self").exists() {
        return true;
    }
    proc.join(pid.to_string()).exists()
}

/// Whether `path` is a regular file (not a link) holding exactly `bytes` already: then the
/// commit leaves it alone (no staging, no rename, no flush), so a rebuild that changes one
/// glyph rewrites only the files that glyph is in. The file's `stamp` from the last commit,
/// when the file still has its metadata, answers without reading it: the file holds the
/// bytes the stamp hashed, so it holds `bytes` when their hash `sha256` is the stamp's
/// (a 14 MB TTF of the same length is not read to find it changed). Otherwise the file is
/// read and compared. Any doubt (unreadable, a link, another length) counts as changed.
fn unchanged(
    path: &Path,
    bytes: &[u8],
    stamp: Option<&FileStamp>,
    sha256: Option<&[u8; 32]>,
) -> bool {
    match fs::symlink_metadata(path) {
        Ok(meta) if meta.is_file() && meta.len() == bytes.len() as u64 => {
            let stamp = stamp.filter(|s| stamp_meta(&meta) == Some(s.meta));
            if let (Some(stamp), Some(sha256)) = (stamp, sha256) {
                return stamp.sha256 == *sha256;
            }
            fs::read(path).is_ok_and(|old| old == bytes)
        }
        _ => false,
    }
}

/// `dir`, or `.` for the empty path (a bare file name's folder).
fn dir_or_current(dir: &Path) -> &Path {
    if dir.as_os_str().is_empty() {
        Path::new(".")
    } else {
        dir
    }
}

/// The folder of `path` (empty for a bare file name, meaning the current folder).
fn parent(path: &Path) -> &Path {
    path.parent().unwrap_or(Path::new(""))
}

fn error(path: &Path, kind: WriteErrorKind) -> WriteError {
    WriteError {
        path: path.to_path_buf(),
        kind,
        rollback: None,
    }
}

/// Flushes the renames (errors ignored: the files are in place, only their durability
/// across a power cut is at stake). On Linux one `syncfs` per file system, as for the data
/// ([`Transaction::sync_staged`]): the bundled typeface's build spent 1.1 s in seven folder
/// `fsync`s on a busy disk, each one a journal commit of its own. Elsewhere each folder
/// that received a file or a new tree is synced (Unix; a no-op on other systems).
fn sync_renames(committed: &[Committed], trees: &[NewTree]) {
    let files = committed.iter().map(|c| parent(&c.path));
    let mut dirs: Vec<&Path> = files.chain(trees.iter().map(|t| parent(&t.root))).collect();
    dirs.sort();
    dirs.dedup();
    #[cfg(target_os = "linux")]
    {
        use std::os::unix::fs::MetadataExt;
        let mut synced = std::collections::HashSet::new();
        for d in dirs {
            let Ok(f) = File::open(if d.as_os_str().is_empty() {
                Path::new(".")
            } else {
                d
            }) else {
                continue;
            };
            if f.metadata().is_ok_and(|m| synced.insert(m.dev())) {
                let _ = rustix::fs::syncfs(&f);
            }
        }
    }
    #[cfg(not(target_os = "linux"))]
    for d in dirs {
        let d = if d.as_os_str().is_empty() {
            Path::new(".")
        } else {
            d
        };
        if cfg!(unix) {
            if let Ok(f) = File::open(d) {
                let _ = f.sync_all();
            }
        }
    }
}

/// Writes one file atomically (an [`OutputSet`] of one).
pub fn write_atomic(path: &Path, bytes: &[u8]) -> io::Result<()> {
    let mut set = OutputSet::new();
    set.add(path, bytes);
    set.commit().map_err(io::Error::other)
}

/// Writes every `(path, bytes)` pair, all or none (an [`OutputSet`]).
pub fn write_all_atomic<P: AsRef<Path>>(files: &[(P, Vec<u8>)]) -> io::Result<()> {
    let mut set = OutputSet::new();
    for (path, bytes) in files {
        set.add(path.as_ref(), bytes.clone());
    }
    set.commit().map_err(io::Error::other)
}

// The folder snapshot the integration tests use too (unit tests cannot reach `tests/`).
#[cfg(test)]
#[path = "../tests/it/common/tree.rs"]
mod test_tree;

#[cfg(test)]
mod tests {
    use super::*;

    use super::test_tree::{entries, tree};

    #[test]
    fn a_change_time_in_whole_seconds_settles_after_two_seconds_not_fifty_milliseconds() {
        use std::time::{Duration, UNIX_EPOCH};
        let at = |secs: u64, nanos: u32| UNIX_EPOCH + Duration::new(secs, nanos);
        // Metadata of a file changed at 1000 s (length, inode, modified, changed).
        let fine = [10, 7, 1000, 123_456_789, 1000, 123_456_789];
        let coarse = [10, 7, 1000, 0, 1000, 0];
        assert!(!settled(&fine, at(1000, 160_000_000)));
        assert!(settled(&fine, at(1000, 180_000_000)));
        assert!(!settled(&coarse, at(1001, 500_000_000)));
        assert!(settled(&coarse, at(1002, 0)));
        // A change time after now (a clock set back) never settles.
        assert!(!settled(&fine, at(999, 0)));
    }

    #[test]
    fn commit_writes_every_file_and_creates_folders() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("out");
        let mut set = OutputSet::new();
        set.add(out.join("a.txt"), "A");
        set.add(out.join("sub/deeper/b.txt"), "B");
        set.commit().unwrap();
        assert_eq!(
            tree(&out),
            entries(&[
                ("a.txt", "A"),
                ("sub", "/"),
                ("sub/deeper", "/"),
                ("sub/deeper/b.txt", "B")
            ])
        );
    }

    #[cfg(unix)]
    #[test]
    fn a_stamp_is_trusted_only_while_the_file_is_untouched() {
        let dir = tempfile::tempdir().unwrap();
        let (a, b) = (dir.path().join("a.txt"), dir.path().join("b.txt"));
        let set = |a_bytes: &str| {
            let mut set = OutputSet::new();
            set.add(&a, a_bytes);
            set.add(&b, "bee");
            set
        };
        // Just written: too fresh to stamp (see `SETTLED`).
        assert!(set("new1").commit_stamped().unwrap().is_empty());
        std::thread::sleep(SETTLED * 2);
        let stamps = set("new1").commit_stamped().unwrap();
        assert_eq!(stamps.len(), 2);
        assert_eq!(stamps[&a].sha256, sha256(b"new1"));
        assert_eq!(stamps[&a].meta[0], 4);

        // The same bytes again: nothing is staged, the stamps are unchanged.
        let again = set("new1")
            .trusting(stamps.clone())
            .commit_stamped()
            .unwrap();
        assert_eq!(again, stamps);

        // Another writer replaces a.txt with bytes of the same length: its metadata no
        // longer match the stamp, so the file is read, found different and rewritten.
        std::fs::write(&a, "XXXX").unwrap();
        std::thread::sleep(SETTLED * 2);
        let after = set("new1")
            .trusting(stamps.clone())
            .commit_stamped()
            .unwrap();
        assert_eq!(std::fs::read(&a).unwrap(), b"new1");
        assert!(!after.contains_key(&a), "rewritten just now: not stamped");
        assert_eq!(after[&b], stamps[&b]);

        // The trust is in the metadata: a stamp claiming the new bytes for the file as it
        // is now (forged here) makes the commit leave the file alone, unread.
        std::fs::write(&a, "YYYY").unwrap();
        std::thread::sleep(SETTLED * 2);
        let forged = FileStamp::of(&a, sha256(b"new1")).unwrap();
        set("new1")
            .trusting(HashMap::from([(a.clone(), forged)]))
            .commit()
            .unwrap();
        assert_eq!(std::fs::read(&a).unwrap(), b"YYYY");
        // A stamp of other bytes answers too, unread: the file is rewritten.
        let other = FileStamp::of(&a, sha256(b"new2")).unwrap();
        set("new1")
            .trusting(HashMap::from([(a.clone(), other)]))
            .commit()
            .unwrap();
        assert_eq!(std::fs::read(&a).unwrap(), b"new1");
        // Even when the file holds the new bytes already (the stamp forged again): it is
        // replaced (another inode) rather than read and compared.
        std::thread::sleep(SETTLED * 2);
        use std::os::unix::fs::MetadataExt;
        let inode = std::fs::metadata(&a).unwrap().ino();
        let forged = FileStamp::of(&a, sha256(b"new2")).unwrap();
        set("new1")
            .trusting(HashMap::from([(a.clone(), forged)]))
            .commit()
            .unwrap();
        assert_eq!(std::fs::read(&a).unwrap(), b"new1");
        assert_ne!(std::fs::metadata(&a).unwrap().ino(), inode);
        // Without a stamp it is read, found the same and left alone.
        let inode = std::fs::metadata(&a).unwrap().ino();
        set("new1").commit().unwrap();
        assert_eq!(std::fs::metadata(&a).unwrap().ino(), inode);
    }

    #[cfg(unix)]
    #[test]
    fn new_files_get_the_usual_mode_and_replaced_files_keep_theirs() {
        use std::os::unix::fs::PermissionsExt;
        let dir = tempfile::tempdir().unwrap();
        let usual = dir.path().join("usual");
        File::create(&usual).unwrap();
        let mode = |p: &Path| fs::metadata(p).unwrap().permissions().mode() & 0o777;
        let kept = dir.path().join("kept.txt");
        fs::write(&kept, "old").unwrap();
        fs::set_permissions(&kept, fs::Permissions::from_mode(0o640)).unwrap();
        let mut set = OutputSet::new();
        set.add(dir.path().join("new.txt"), "new");
        set.add(&kept, "replaced");
        set.commit().unwrap();
        assert_eq!(mode(&dir.path().join("new.txt")), mode(&usual));
        assert_eq!(mode(&kept), 0o640);
        assert_eq!(fs::read_to_string(&kept).unwrap(), "replaced");
    }

    #[cfg(unix)]
    #[test]
    fn a_link_at_an_output_name_is_replaced_not_followed() {
        let dir = tempfile::tempdir().unwrap();
        let victim = dir.path().join("victim");
        fs::write(&victim, "precious").unwrap();
        let out = dir.path().join("out");
        fs::create_dir(&out).unwrap();
        std::os::unix::fs::symlink("../victim", out.join("sheet.png")).unwrap();
        let mut set = OutputSet::new();
        set.add(out.join("sheet.png"), "png");
        set.commit().unwrap();
        assert_eq!(fs::read_to_string(&victim).unwrap(), "precious");
        assert_eq!(tree(&out), entries(&[("sheet.png", "png")]));
    }

    /// A set writing into existing folders and into three new trees: one inside OUT
    /// (`c/`, nested), another (`e/f/`), and a whole new OUT beside it (`out2/`).
    fn mixed_set(root: &Path) -> OutputSet {
        let out = root.join("out");
        let mut set = OutputSet::new();
        set.add(out.join("a.txt"), "new a");
        set.add(out.join("c/new.txt"), "new c");
        set.add(out.join("link"), "no longer a link");
        set.add(out.join("c/d/deep.txt"), "deep");
        set.add(out.join("e/f/g.txt"), "g");
        set.add(root.join("out2/x/y.txt"), "y");
        set.add(out.join("b.txt"), "new b");
        set.add(out.join("c/d/also.txt"), "also");
        set
    }

    /// `root` holding `out/` with `a.txt`, `b.txt` and a link to `a.txt`.
    #[cfg(unix)]
    fn mixed_out(root: &Path) {
        let out = root.join("out");
        fs::create_dir(&out).unwrap();
        fs::write(out.join("a.txt"), "old a").unwrap();
        fs::write(out.join("b.txt"), "old b").unwrap();
        std::os::unix::fs::symlink("a.txt", out.join("link")).unwrap();
    }

    #[cfg(unix)]
    #[test]
    fn a_failure_while_renaming_restores_everything() {
        let dir = tempfile::tempdir().unwrap();
        mixed_out(dir.path());
        let before = tree(dir.path());
        // The three new trees are renamed first, then the files of existing folders.
        let renames = [
            ("folder", "out/c"),
            ("folder", "out/e"),
            ("folder", "out2"),
            ("file", "out/a.txt"),
            ("file", "out/link"),
            ("file", "out/b.txt"),
        ];
        for (fail_at, (what, failed)) in renames.into_iter().enumerate() {
            let tx = Transaction {
                fail_before_rename: Some(fail_at),
                ..Transaction::default()
            };
            let err = mixed_set(dir.path()).commit_with(tx, false).unwrap_err();
            let failed = dir.path().join(failed);
            let want = match what {
                "folder" => format!("cannot create the folder {}", failed.display()),
                _ => format!("cannot write {}", failed.display()),
            };
            assert_eq!(err.to_string(), format!("{want}: injected failure"));
            assert_eq!(tree(dir.path()), before, "failing before rename {fail_at}");
        }
        // Without a failure: exactly the outputs, and no temporary name anywhere.
        mixed_set(dir.path()).commit().unwrap();
        assert_eq!(
            tree(dir.path()),
            entries(&[
                ("out", "/"),
                ("out/a.txt", "new a"),
                ("out/b.txt", "new b"),
                ("out/c", "/"),
                ("out/c/d", "/"),
                ("out/c/d/also.txt", "also"),
                ("out/c/d/deep.txt", "deep"),
                ("out/c/new.txt", "new c"),
                ("out/e", "/"),
                ("out/e/f", "/"),
                ("out/e/f/g.txt", "g"),
                ("out/link", "no longer a link"),
                ("out2", "/"),
                ("out2/x", "/"),
                ("out2/x/y.txt", "y"),
            ])
        );
    }

    #[cfg(unix)]
    #[test]
    fn a_failure_among_renames_on_every_core_restores_every_file() {
        use std::os::unix::fs::MetadataExt;
        let dir = tempfile::tempdir().unwrap();
        let names: Vec<PathBuf> = (0..300)
            .map(|i| {
                dir.path()
                    .join(["svg", "glyphs"][i % 2])
                    .join(format!("g{i}"))
            })
            .collect();
        for (i, name) in names.iter().enumerate() {
            fs::create_dir_all(parent(name)).unwrap();
            fs::write(name, format!("old {i}")).unwrap();
        }
        let inodes = || -> Vec<u64> {
            names
                .iter()
                .map(|n| fs::metadata(n).unwrap().ino())
                .collect()
        };
        let (before, inodes_before) = (tree(dir.path()), inodes());
        // Before, at and after the split of the work between two cores.
        for fail_at in [0, 100, 149, 150, 250, 299] {
            let mut set = OutputSet::new();
            for (i, name) in names.iter().enumerate() {
                set.add(name, format!("new {i}"));
            }
            let tx = Transaction {
                fail_before_rename: Some(fail_at),
                ..Transaction::default()
            };
            let err = set.commit_with(tx, false).unwrap_err();
            let want = format!(
                "cannot write {}: injected failure",
                names[fail_at].display()
            );
            assert_eq!(err.to_string(), want);
            // The same files: their own inodes, put back from their backups.
            assert_eq!(tree(dir.path()), before, "failing before rename {fail_at}");
            assert_eq!(inodes(), inodes_before, "failing before rename {fail_at}");
        }
    }

    #[cfg(unix)]
    #[test]
    fn each_new_tree_is_staged_whole_next_to_its_top_folder() {
        let dir = tempfile::tempdir().unwrap();
        mixed_out(dir.path());
        let before = tree(dir.path());
        let set = mixed_set(dir.path());
        // Stopped before the first rename, the transaction is left staged to look at.
        let mut tx = Transaction {
            fail_before_rename: Some(0),
            ..Transaction::default()
        };
        assert!(tx.run(&set.files, &[], &HashMap::new(), &[]).is_err());
        let staged = tree(dir.path());
        let temp_name = |name: &str| {
            let me = std::process::id();
            name.starts_with(&format!(".xglyph-{me}-")) && name.ends_with(".dir")
        };
        // In `root`: OUT's three files, OUT's two staged trees, and out2's staged tree;
        // each tree's folders and files under their final names.
        let mut shapes: Vec<String> = staged
            .iter()
            .map(|(name, bytes)| {
                let parts: Vec<String> = name
                    .split('/')
                    .map(|p| if temp_name(p) { "T" } else { p }.to_string())
                    .collect();
                format!("{} {}", parts.join("/"), String::from_utf8_lossy(bytes))
            })
            .collect();
        shapes.sort();
        let mut want = vec![
            "T /",
            "T/x /",
            "T/x/y.txt y",
            "out /",
            "out/T /",
            "out/T /",
            "out/T/d /",
            "out/T/d/also.txt also",
            "out/T/d/deep.txt deep",
            "out/T/f /",
            "out/T/f/g.txt g",
            "out/T/new.txt new c",
            "out/a.txt old a",
            "out/b.txt old b",
            "out/link -> a.txt",
        ];
        want.sort();
        // Three staged files of existing folders, whose names are random too.
        let temp_files = shapes.iter().filter(|s| s.starts_with("out/.xglyph-"));
        assert_eq!(temp_files.count(), 3, "{shapes:?}");
        shapes.retain(|s| !s.starts_with("out/.xglyph-"));
        assert_eq!(shapes, want);
        assert_eq!(tx.roll_back(), None);
        assert_eq!(tree(dir.path()), before);
    }

    #[cfg(unix)]
    #[test]
    fn stamps_of_files_in_a_new_tree_are_trusted_by_the_next_commit() {
        use std::os::unix::fs::MetadataExt;
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("new/out");
        let set = |g: &str| {
            let mut set = OutputSet::new();
            set.add(out.join("font.ttf"), "ttf");
            set.add(out.join("svg/a.svg"), "a");
            set.add(out.join("svg/g.svg"), g.to_string());
            set
        };
        // The files settle between staging and the tree's rename, so that they get stamps
        // taken after the rename from their final paths.
        let tx = Transaction {
            settle_before_renames: true,
            ..Transaction::default()
        };
        let stamps = set("g").commit_with(tx, true).unwrap();
        assert_eq!(stamps.len(), 3);
        let inodes = |out: &Path| -> Vec<u64> {
            ["font.ttf", "svg/a.svg", "svg/g.svg"]
                .iter()
                .map(|n| fs::metadata(out.join(n)).unwrap().ino())
                .collect()
        };
        let first = inodes(&out);
        for (path, stamp) in &stamps {
            assert!(stamp.matches(path), "{}", path.display());
            assert_eq!(stamp.sha256, sha256(&fs::read(path).unwrap()));
        }
        // The next commit finds every file as stamped: nothing is replaced.
        let again = set("g").trusting(stamps.clone()).commit_stamped().unwrap();
        assert_eq!(again, stamps);
        assert_eq!(inodes(&out), first);
        // A changed output is replaced, the others are left alone.
        set("G").trusting(stamps).commit().unwrap();
        let after = inodes(&out);
        assert_eq!(fs::read_to_string(out.join("svg/g.svg")).unwrap(), "G");
        assert_eq!((after[0], after[1]), (first[0], first[1]));
        assert_ne!(after[2], first[2]);
    }

    #[test]
    fn an_output_and_a_folder_of_one_name_in_a_new_tree_are_refused() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("out");
        let mut set = OutputSet::new();
        set.add(out.join("a"), "file");
        set.add(out.join("a/b.txt"), "in the folder");
        let err = set.commit().unwrap_err();
        assert_eq!(
            err.to_string(),
            format!(
                "cannot write {}: a folder of that name is in the way",
                out.join("a").display()
            )
        );
        assert_eq!(tree(dir.path()), []);
    }

    #[test]
    fn a_new_folder_named_through_dot_dot_is_refused() {
        let dir = tempfile::tempdir().unwrap();
        fs::create_dir(dir.path().join("out")).unwrap();
        let mut set = OutputSet::new();
        set.add(dir.path().join("out/missing/../x.txt"), "x");
        let err = set.commit().unwrap_err();
        assert_eq!(
            err.to_string(),
            format!(
                "cannot create the folder {}: no such file or directory",
                dir.path().join("out/missing/..").display()
            )
        );
        assert_eq!(tree(dir.path()), entries(&[("out", "/")]));
    }

    #[test]
    fn things_in_the_way_are_named_and_nothing_is_left() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("out");
        fs::create_dir_all(out.join("proof.png")).unwrap();
        fs::write(out.join("svg"), "a file").unwrap();
        let before = tree(&out);

        let long = "n".repeat(300) + ".svg";
        // The files of each set after `sheet.png` (which could be written), and the error.
        let cases = [
            (
                vec![
                    (out.join("new/folder/x.svg"), "x"),
                    (out.join("proof.png"), "proof"),
                ],
                format!(
                    "cannot write {}: a folder of that name is in the way",
                    out.join("proof.png").display()
                ),
            ),
            (
                vec![(out.join("svg/a.svg"), "a")],
                format!(
                    "cannot create the folder {}: a file of that name is in the way",
                    out.join("svg").display()
                ),
            ),
            (
                vec![(out.join("glyphs").join(&long), "long")],
                format!(
                    "cannot write {}: file name too long",
                    out.join("glyphs").join(&long).display()
                ),
            ),
            // A folder name too long: the error names it as a folder.
            (
                vec![(out.join("new").join(&long).join("x.svg"), "x")],
                format!(
                    "cannot create the folder {}: file name too long",
                    out.join("new").join(&long).display()
                ),
            ),
        ];
        for (files, message) in cases {
            let mut set = OutputSet::new();
            set.add(out.join("sheet.png"), "sheet");
            for (file, bytes) in files {
                set.add(file, bytes);
            }
            assert_eq!(set.commit().unwrap_err().to_string(), message);
            assert_eq!(tree(&out), before, "{message}");
        }
    }

    #[test]
    fn a_path_given_twice_is_refused() {
        let dir = tempfile::tempdir().unwrap();
        let mut set = OutputSet::new();
        set.add(dir.path().join("a"), "1");
        set.add(dir.path().join("a"), "2");
        let err = set.commit().unwrap_err();
        assert_eq!(
            err.to_string(),
            format!(
                "cannot write {} twice in one set",
                dir.path().join("a").display()
            )
        );
        assert_eq!(tree(dir.path()), []);
    }

    #[test]
    fn only_stale_files_of_our_naming_are_removed() {
        let dir = tempfile::tempdir().unwrap();
        // A PID that is gone: a child that has exited and been waited for.
        let mut child = std::process::Command::new("true").spawn().unwrap();
        child.wait().unwrap();
        let dead = child.id();
        let live = std::process::id();
        let stale = [
            format!(".xglyph-{dead}-abcdeABCDE.tmp"),
            format!(".xglyph-{dead}-0123456789.old"),
            format!(".sheet.png.tmp{dead}"),
        ];
        let kept = [
            format!(".xglyph-{live}-abcdeABCDE.tmp"),
            format!(".xglyph-{dead}-short.tmp"),
            format!(".xglyph-{dead}-abcdeABCDE.tmp.bak"),
            format!("xglyph-{dead}-abcdeABCDE.tmp"),
            format!(".other.png.tmp{dead}"),
            ".sheet.png.tmpabc".to_string(),
            "notes.tmp".to_string(),
        ];
        for name in stale.iter().chain(&kept) {
            fs::write(dir.path().join(name), "x").unwrap();
        }
        // A folder of our naming stays too.
        let folder = format!(".xglyph-{dead}-folderFOLD.tmp");
        fs::create_dir(dir.path().join(&folder)).unwrap();
        remove_stale(dir.path(), &[(dir.path().join("sheet.png"), Vec::new())]);
        let mut left: Vec<String> = fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        left.sort();
        let mut want: Vec<String> = kept.to_vec();
        want.push(folder);
        want.sort();
        assert_eq!(left, want);
    }

    #[cfg(unix)]
    #[test]
    fn only_stale_trees_of_our_naming_are_removed_and_no_link_is_followed() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("out");
        fs::create_dir(&out).unwrap();
        let mut child = std::process::Command::new("true").spawn().unwrap();
        child.wait().unwrap();
        let dead = child.id();
        let live = std::process::id();
        // Someone else's folder, reached through links in and at stale names.
        let victim = dir.path().join("victim");
        fs::create_dir(&victim).unwrap();
        fs::write(victim.join("precious"), "precious").unwrap();
        let stale = out.join(format!(".xglyph-{dead}-treeTREE12.dir"));
        fs::create_dir_all(stale.join("svg")).unwrap();
        fs::write(stale.join("svg/a.svg"), "a").unwrap();
        std::os::unix::fs::symlink(&victim, stale.join("svg/link")).unwrap();
        let kept = [
            format!(".xglyph-{live}-liveLIVE12.dir"),
            format!(".xglyph-{dead}-short.dir"),
        ];
        for name in &kept {
            fs::create_dir(out.join(name)).unwrap();
        }
        let file = format!(".xglyph-{dead}-fileFILE12.dir");
        fs::write(out.join(&file), "a file").unwrap();
        let link = format!(".xglyph-{dead}-linkLINK12.dir");
        std::os::unix::fs::symlink(&victim, out.join(&link)).unwrap();
        remove_stale(&out, &[]);
        let mut want = kept.to_vec();
        want.extend([file, link]);
        want.sort();
        let left: Vec<String> = tree(&out)
            .into_iter()
            .map(|(name, _)| name)
            .filter(|name| !name.contains('/'))
            .collect();
        assert_eq!(left, want);
        assert_eq!(tree(&victim), entries(&[("precious", "precious")]));
    }

    #[test]
    fn reasons_read_after_a_colon() {
        let e = io::Error::from_raw_os_error(28);
        assert_eq!(reason(&e), "no space left on device");
        assert_eq!(reason(&io::Error::other("Odd")), "odd");
    }
}
