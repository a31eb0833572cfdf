//! A font directory -> the typed model: reads every file, runs the per-file loaders, then
//! the checks across files. Every problem of every file is collected in one run.
//!
//! Only regular files (or links to them) are read: a FIFO, socket, device, folder or
//! dangling link named `*.toml` is reported and skipped, so loading never blocks.

use std::collections::{BTreeMap, BTreeSet, HashMap};
use std::fs::FileType;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use super::anchors::{check_anchors, place_components};
use super::compat::check_master;
use super::components::{check_components, ComponentGraph};
use super::designspace::{load_designspace, DesignspaceSpec};
use super::diagnostic::{Ctx, Diagnostic, Diagnostics, Severity};
use super::emit;
use super::geometry::{distance_outside, glyph_box, FAR_EMS};
use super::glyph::{load_glyph, GlyphSpans};
use super::info::load_info;
use super::kerning::load_kerning;
use super::limits;
use super::memo::SourceMemo;
use crate::designspace::Designspace;
use crate::model::{glyph_order, Family, FeatureFile, Font, FontInfo, Glyph, Master};

/// What a source file holds.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum SourceKind {
    /// `font.toml`.
    Info,
    /// A glyph file, with the name of its glyph.
    Glyph(String),
    /// `kerning.toml`.
    Kerning,
    /// A glyph file of a non-default master: the master's index in
    /// [`LoadedFont::masters`], and the glyph's name.
    MasterGlyph(usize, String),
    /// The `kerning.toml` of a non-default master (its index).
    MasterKerning(usize),
}

/// One source file as it was read.
#[derive(Clone, Debug)]
pub struct SourceFile {
    /// The file.
    pub path: PathBuf,
    /// Its text.
    pub text: String,
    /// What it holds.
    pub kind: SourceKind,
}

/// A font that loaded without errors, with its warnings and the files it came from.
#[derive(Clone, Debug)]
pub struct LoadedFont {
    /// The model.
    pub font: Font,
    /// Warnings of the sources.
    pub warnings: Vec<Diagnostic>,
    /// `font.toml`, the glyph files in file-name order, then `kerning.toml` if present;
    /// then the same for each non-default master, in `font.toml` order.
    pub files: Vec<SourceFile>,
    /// Axes and named instances; empty for a single-master font.
    pub designspace: Designspace,
    /// The non-default masters, compatible with [`LoadedFont::font`].
    pub masters: Vec<Master>,
}

/// Load a font directory with its masters ([`load_sources`]): the family and its warnings,
/// or every diagnostic when there are errors.
pub fn load_family(dir: &Path) -> Result<(Family, Vec<Diagnostic>), Vec<Diagnostic>> {
    load_family_with(dir, &SourceMemo::off())
}

/// [`load_family`], taking each glyph file that did not change since the last build from
/// `memo` instead of parsing and checking it again ([`SourceMemo`]).
pub fn load_family_with(
    dir: &Path,
    memo: &SourceMemo,
) -> Result<(Family, Vec<Diagnostic>), Vec<Diagnostic>> {
    // Without the files' texts: the memo gives unchanged files unread.
    let l = load_sources_with(dir, memo, false)?;
    let mut family = Family {
        default: l.font,
        designspace: l.designspace,
        masters: l.masters,
    };
    // What sparse masters leave out, blended from the others.
    if let Err(e) = family.fill_sparse() {
        return Err(vec![Diagnostic::whole(
            &dir.join("font.toml"),
            Severity::Error,
            format!("a glyph that a sparse master does not draw cannot be blended there: {e}"),
        )]);
    }
    Ok((family, l.warnings))
}

/// Load a font directory: `font.toml`, optional `kerning.toml`, and one glyph per other
/// `*.toml` (files whose name starts with `.` are ignored). Returns the font and its
/// warnings, or every diagnostic when there are errors.
pub fn load_font(dir: &Path) -> Result<(Font, Vec<Diagnostic>), Vec<Diagnostic>> {
    load_sources(dir).map(|l| (l.font, l.warnings))
}

/// A loaded glyph with its file and where its parts were written.
pub(super) struct GlyphFile {
    /// Possibly incomplete when `complete` is false (see [`load_glyph`]).
    pub glyph: Glyph,
    pub complete: bool,
    pub spans: GlyphSpans,
    pub path: PathBuf,
    /// Its text; not read yet for a file the memo gave by its stamp.
    pub text: OnceLock<String>,
}

impl GlyphFile {
    /// A context for diagnostics in this file (its text read only if there is one).
    pub fn ctx<'a>(&'a self, out: &'a mut Diagnostics) -> Ctx<'a> {
        Ctx::later(&self.path, &self.text, out)
    }

    /// Its glyph, and its file of kind `kind` with its text (read now if it was not).
    fn into_source(self, kind: impl FnOnce(&Glyph) -> SourceKind) -> (Glyph, SourceFile) {
        let GlyphFile {
            glyph, path, text, ..
        } = self;
        let text = text
            .into_inner()
            .or_else(|| read(&path, &mut Diagnostics::default()))
            .unwrap_or_default();
        let kind = kind(&glyph);
        (glyph, SourceFile { path, text, kind })
    }
}

/// [`load_font`], also returning the text of every source file (for `fmt`).
///
/// Diagnostics come in file order (`font.toml`, glyph files and skipped `*.toml` by name,
/// `kerning.toml`), and by position within a file; at most
/// [`super::diagnostic::MAX_PER_FILE`] per file, then one "… and N more" line.
pub fn load_sources(dir: &Path) -> Result<LoadedFont, Vec<Diagnostic>> {
    load_sources_with(dir, &SourceMemo::off(), true)
}

/// [`load_sources`] with glyph files from `memo`; with `texts` false,
/// [`LoadedFont::files`] holds only `font.toml` and `kerning.toml`.
fn load_sources_with(
    dir: &Path,
    memo: &SourceMemo,
    texts: bool,
) -> Result<LoadedFont, Vec<Diagnostic>> {
    let mut out = Diagnostics::default();
    let font_path = dir.join("font.toml");
    let kern_path = dir.join("kerning.toml");
    let (glyph_paths, candidates) = match glyph_files(dir, &mut out) {
        Ok(paths) => paths,
        Err(d) => return Err(vec![d]),
    };

    let info_text = match regular_file(&font_path) {
        Ok(true) => read(&font_path, &mut out),
        Ok(false) => {
            out.push(Diagnostic::whole(
                &font_path,
                Severity::Error,
                "missing `font.toml`: a font directory needs one with at least `family`, \
                 `units_per_em`, `ascender`, `descender`, `x_height` and `cap_height`",
            ));
            None
        }
        Err(what) => {
            out.push(Diagnostic::whole(
                &font_path,
                Severity::Error,
                format!("`font.toml` is {what}, not a regular file"),
            ));
            None
        }
    };
    let info = info_text
        .as_deref()
        .and_then(|text| load_info(&mut Ctx::new(&font_path, text, &mut out)));
    let spec = info_text
        .as_deref()
        .and_then(|text| load_designspace(&mut Ctx::new(&font_path, text, &mut out), dir));

    if glyph_paths.is_empty() {
        out.push(Diagnostic::whole(
            dir,
            Severity::Warning,
            "no glyph files: add one `<glyph>.toml` per glyph next to `font.toml`",
        ));
    }
    let (mut glyphs, mut glyph_failed) = load_glyph_files(&glyph_paths, memo, &mut out);

    check_unique(&glyphs, &mut out);
    let graph = ComponentGraph::new(&glyphs);
    check_components(&glyphs, &graph, &mut out);
    check_anchors(&glyphs, &mut out);
    place_components(&mut glyphs, &graph, &mut out);
    limits::check_font(dir, &glyphs, &graph, &mut out);
    if let Some(info) = &info {
        check_far_points(&glyphs, info, &mut out);
    }

    let names: BTreeSet<String> = glyphs.iter().map(|g| g.glyph.name.clone()).collect();
    if let (Some(spec), Some(text), false) = (&spec, info_text.as_deref(), glyph_failed) {
        let mut ctx = Ctx::new(&font_path, text, &mut out);
        for (rule, glyph, at) in &spec.rule_glyphs {
            if !names.contains(glyph) {
                ctx.err(
                    *at,
                    format!("rule `{rule}` names glyph `{glyph}`, which the font does not have"),
                );
            }
        }
    }
    let mut kern_text = None;
    let kerning = match regular_file(&kern_path) {
        Ok(true) => {
            kern_text = read(&kern_path, &mut out);
            kern_text
                .as_deref()
                .and_then(|text| load_kerning(&mut Ctx::new(&kern_path, text, &mut out), &names))
        }
        Ok(false) => Some(Vec::new()),
        Err(what) => {
            out.push(Diagnostic::whole(
                &kern_path,
                Severity::Warning,
                format!("`kerning.toml` is {what}, not a regular file; skipped (no kerning)"),
            ));
            Some(Vec::new())
        }
    };

    // `features.fea` is read here and compiled by the OpenType backend, which reports its
    // errors at file:line:col (`check` runs that compiler too).
    let fea_path = dir.join("features.fea");
    let features = match regular_file(&fea_path) {
        Ok(true) => read(&fea_path, &mut out).map(|text| FeatureFile {
            path: fea_path,
            text,
        }),
        Ok(false) => None,
        Err(what) => {
            out.push(Diagnostic::whole(
                &fea_path,
                Severity::Error,
                format!("`features.fea` is {what}, not a regular file"),
            ));
            None
        }
    };

    // The masters: each folder's glyphs and kerning, compared with the default's.
    let spec = spec.unwrap_or_default();
    let mut masters = Vec::new();
    let mut master_order = Vec::new();
    for (index, m) in spec.masters.iter().enumerate() {
        let mdir = dir.join(&m.folder);
        let (paths, mcandidates) = match glyph_files(&mdir, &mut out) {
            Ok(found) => found,
            Err(d) => {
                out.push(d);
                glyph_failed = true;
                continue;
            }
        };
        master_order.push(mdir.clone());
        master_order.extend(mcandidates);
        let (mut mglyphs, failed) = load_glyph_files(&paths, memo, &mut out);
        glyph_failed |= failed;
        check_unique(&mglyphs, &mut out);
        // Each master places its components by its own anchors (compared with the
        // default's names in `check_master`).
        let mgraph = ComponentGraph::new(&mglyphs);
        place_components(&mut mglyphs, &mgraph, &mut out);
        // The outputs' limits hold for each master, so every instance between fits too
        // (an instance's extent and counts are within its masters').
        limits::check_font(&mdir, &mglyphs, &mgraph, &mut out);
        if let Some(info) = &info {
            check_far_points(&mglyphs, info, &mut out);
        }
        if let Some(text) = &info_text {
            check_master(m, (&font_path, text), &glyphs, &mglyphs, &mut out);
        }
        let mkern_path = mdir.join("kerning.toml");
        master_order.push(mkern_path.clone());
        let (mkerning, mkern_text) = match regular_file(&mkern_path) {
            Ok(true) => {
                let text = read(&mkern_path, &mut out);
                let pairs = text.as_deref().and_then(|text| {
                    load_kerning(&mut Ctx::new(&mkern_path, text, &mut out), &names)
                });
                (pairs, text)
            }
            Ok(false) => (Some(Vec::new()), None),
            Err(what) => {
                out.push(Diagnostic::whole(
                    &mkern_path,
                    Severity::Error,
                    format!("`kerning.toml` is {what}, not a regular file"),
                ));
                (None, None)
            }
        };
        glyph_failed |= mkerning.is_none();
        masters.push(LoadedMaster {
            index,
            glyphs: mglyphs,
            kerning: mkerning.unwrap_or_default(),
            kern: mkern_text.map(|t| (mkern_path, t)),
        });
    }

    let mut rank: HashMap<PathBuf, usize> = HashMap::new();
    let order = [dir.to_path_buf(), font_path.clone()]
        .into_iter()
        .chain(candidates)
        .chain([kern_path.clone()])
        .chain(master_order);
    for (i, path) in order.enumerate() {
        rank.entry(path).or_insert(i);
    }
    let has_errors = out.has_errors();
    let out = out.into_sorted(|p| rank.get(p).copied().unwrap_or(rank.len()));

    let (Some(info), Some(info_text), Some(kerning), false, false) =
        (info, info_text, kerning, glyph_failed, has_errors)
    else {
        return Err(out);
    };

    let mut files = vec![SourceFile {
        path: font_path,
        text: info_text,
        kind: SourceKind::Info,
    }];
    let mut model_glyphs = Vec::with_capacity(glyphs.len());
    for g in glyphs {
        if texts {
            let (glyph, file) = g.into_source(|g| SourceKind::Glyph(g.name.clone()));
            files.push(file);
            model_glyphs.push(glyph);
        } else {
            model_glyphs.push(g.glyph);
        }
    }
    if let Some(text) = kern_text {
        files.push(SourceFile {
            path: kern_path,
            text,
            kind: SourceKind::Kerning,
        });
    }
    model_glyphs.sort_by(|a, b| glyph_order(&a.name, &b.name));
    let model_masters = model_masters(&spec, masters, &model_glyphs, texts.then_some(&mut files));
    Ok(LoadedFont {
        font: Font {
            info,
            glyphs: model_glyphs,
            kerning,
            features,
        },
        warnings: out,
        files,
        designspace: spec.designspace,
        masters: model_masters,
    })
}

/// A non-default master's files as loaded.
struct LoadedMaster {
    /// Index in the spec's masters.
    index: usize,
    glyphs: Vec<GlyphFile>,
    kerning: Vec<crate::model::KernPair>,
    /// Its `kerning.toml` and text, when present.
    kern: Option<(PathBuf, String)>,
}

/// The model's masters (glyphs parallel to `default`, code points from the default), and
/// their files appended to `files`. The masters loaded without errors, so each has exactly
/// the default's glyphs.
fn model_masters(
    spec: &DesignspaceSpec,
    loaded: Vec<LoadedMaster>,
    default: &[Glyph],
    mut files: Option<&mut Vec<SourceFile>>,
) -> Vec<Master> {
    let mut masters = Vec::with_capacity(loaded.len());
    for m in loaded {
        let s = &spec.masters[m.index];
        let mut by_name: HashMap<String, Glyph> = HashMap::new();
        for g in m.glyphs {
            let glyph = match files.as_deref_mut() {
                Some(files) => {
                    let kind = |g: &Glyph| SourceKind::MasterGlyph(m.index, g.name.clone());
                    let (glyph, file) = g.into_source(kind);
                    files.push(file);
                    glyph
                }
                None => g.glyph,
            };
            by_name.insert(glyph.name.clone(), glyph);
        }
        // A sparse master's kerning is its own when its folder has a `kerning.toml`.
        let kerned = !s.sparse || m.kern.is_some();
        if let (Some(files), Some((path, text))) = (files.as_deref_mut(), m.kern) {
            files.push(SourceFile {
                path,
                text,
                kind: SourceKind::MasterKerning(m.index),
            });
        }
        // A glyph a sparse master does not draw holds the default's for now
        // ([`Family::fill_sparse`] blends it).
        let (glyphs, drawn): (Vec<Glyph>, Vec<bool>) = default
            .iter()
            .map(|d| match by_name.remove(&d.name) {
                Some(mut g) => {
                    g.unicodes.clone_from(&d.unicodes);
                    g.outline_mark = d.outline_mark;
                    (g, true)
                }
                None => (d.clone(), false),
            })
            .unzip();
        masters.push(Master {
            name: s.name.clone(),
            folder: PathBuf::from(&s.folder),
            location: s.location.clone(),
            glyphs,
            kerning: m.kerning,
            sparse: s.sparse,
            kerned,
            drawn,
        });
    }
    masters
}

/// Reads and loads each glyph file; also whether any failed (unreadable, or with an error
/// of its own).
fn load_glyph_files(
    paths: &[GlyphPath],
    memo: &SourceMemo,
    out: &mut Diagnostics,
) -> (Vec<GlyphFile>, bool) {
    use rayon::prelude::*;
    // Each file on any core with diagnostics of its own, merged in path order: a file's
    // diagnostics (and its per-file limit) concern its path alone, so the merged list is
    // the one a sequential load gathers, whatever the thread count.
    let loaded: Vec<(Option<GlyphFile>, Diagnostics)> = paths
        .par_iter()
        // Small pieces, so that the load does not end on one core.
        .with_max_len(64)
        .map(|(path, meta)| {
            let mut mine = Diagnostics::default();
            let file = load_glyph_file(path, meta.as_ref(), memo, &mut mine);
            (file, mine)
        })
        .collect();
    let mut glyphs = Vec::with_capacity(loaded.len());
    let mut failed = false;
    for (file, diagnostics) in loaded {
        out.absorb(diagnostics);
        match file {
            Some(file) => {
                failed |= !file.complete;
                glyphs.push(file);
            }
            None => failed = true,
        }
    }
    (glyphs, failed)
}

/// One glyph file read and loaded (`None`: unreadable or not a glyph at all). `meta`: its
/// settled metadata, taken before the read ([`crate::write::settled_meta`]).
/// A file `memo` holds as it is now is taken from it (it loaded complete and without any
/// diagnostic), unread when its stamp is the memo's; a file that loads so is kept in it.
fn load_glyph_file(
    path: &Path,
    meta: Option<&[u64; 6]>,
    memo: &SourceMemo,
    out: &mut Diagnostics,
) -> Option<GlyphFile> {
    let stamp = meta
        .filter(|_| memo.is_on())
        .map(|meta| SourceMemo::stamp(path, meta));
    let from_memo = |(glyph, spans), text| GlyphFile {
        glyph,
        complete: true,
        spans,
        path: path.to_path_buf(),
        text,
    };
    if let Some(taken) = stamp.as_ref().and_then(|s| memo.take_stamped(s)) {
        return Some(from_memo(taken, OnceLock::new()));
    }
    let text = read(path, out)?;
    let key = SourceMemo::key(path, &text);
    if let Some(taken) = memo.take(&key, stamp) {
        return Some(from_memo(taken, OnceLock::from(text)));
    }
    let mut own = Diagnostics::default();
    let loaded = load_glyph(&mut Ctx::new(path, &text, &mut own));
    if let Some(loaded) = loaded.as_ref().filter(|l| l.complete && own.is_empty()) {
        memo.keep(key, stamp, &loaded.glyph, &loaded.spans);
    }
    out.absorb(own);
    let loaded = loaded?;
    Some(GlyphFile {
        glyph: loaded.glyph,
        complete: loaded.complete,
        spans: loaded.spans,
        path: path.to_path_buf(),
        text: OnceLock::from(text),
    })
}

/// A glyph file and its settled metadata ([`crate::write::settled_meta`]), if any.
type GlyphPath = (PathBuf, Option<[u64; 6]>);

/// The glyph files of `dir`, sorted: every `*.toml` except `font.toml`, `kerning.toml`
/// and names starting with `.` (editor and temporary files). A `*.toml` that is not a
/// regular file (or a link to one) gets a warning and is skipped. Also returns every
/// candidate, skipped ones included, sorted (the order of their diagnostics).
fn glyph_files(
    dir: &Path,
    out: &mut Diagnostics,
) -> Result<(Vec<GlyphPath>, Vec<PathBuf>), Diagnostic> {
    use rayon::prelude::*;
    let entries = std::fs::read_dir(dir).map_err(|e| {
        let why = if e.kind() == std::io::ErrorKind::NotFound {
            "font directory not found".to_string()
        } else {
            format!("cannot read font directory: {e}")
        };
        Diagnostic::whole(dir, Severity::Error, why)
    })?;
    let mut paths: Vec<PathBuf> = entries
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .filter(|p| {
            let name = p.file_name().map(|f| f.to_string_lossy().into_owned());
            let name = name.as_deref().unwrap_or(".");
            !name.starts_with('.') && name != "font.toml" && name != "kerning.toml"
        })
        .collect();
    paths.sort();
    // Each file's metadata on any core (a CJK font's 20,902), the warnings in order.
    let found: Vec<_> = paths.par_iter().map(|p| regular_meta(p)).collect();
    let mut files = Vec::with_capacity(paths.len());
    for (p, found) in paths.iter().zip(found) {
        match found {
            Ok(Some(meta)) => files.push((p.clone(), crate::write::settled_meta(&meta))),
            Ok(None) => {}
            Err(what) => out.push(Diagnostic::whole(
                p,
                Severity::Warning,
                format!("{what}, not a regular file; skipped"),
            )),
        }
    }
    Ok((files, paths))
}

/// Whether `path` is a regular file (following links): `Ok(true)`; absent: `Ok(false)`;
/// anything else: `Err` with what it is ("a FIFO", "a dangling symbolic link", ...).
///
/// Checked before opening, because opening a FIFO blocks until a writer appears. (A file
/// swapped for a FIFO between this check and the read could still block; that needs a
/// writer racing the loader on purpose.)
fn regular_file(path: &Path) -> Result<bool, String> {
    regular_meta(path).map(|meta| meta.is_some())
}

/// [`regular_file`], with the file's metadata when it is one.
fn regular_meta(path: &Path) -> Result<Option<std::fs::Metadata>, String> {
    match std::fs::metadata(path) {
        Ok(m) if m.is_file() => Ok(Some(m)),
        Ok(m) => Err(describe(m.file_type()).to_string()),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            match std::fs::symlink_metadata(path) {
                Ok(m) if m.file_type().is_symlink() => {
                    Err("a dangling symbolic link (its target does not exist)".to_string())
                }
                _ => Ok(None),
            }
        }
        Err(e) => Err(format!("unreadable ({e})")),
    }
}

/// What a file type is, for messages.
fn describe(t: FileType) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if t.is_fifo() {
            return "a FIFO (named pipe)";
        }
        if t.is_socket() {
            return "a socket";
        }
        if t.is_block_device() || t.is_char_device() {
            return "a device";
        }
    }
    if t.is_dir() {
        "a folder"
    } else {
        "not a file"
    }
}

/// The text of a source file; a file that is not UTF-8 is reported at its first bad byte.
fn read(path: &Path, out: &mut Diagnostics) -> Option<String> {
    let bytes = match std::fs::read(path) {
        Ok(b) => b,
        Err(e) => {
            out.push(Diagnostic::whole(
                path,
                Severity::Error,
                format!("cannot read file: {e}"),
            ));
            return None;
        }
    };
    match String::from_utf8(bytes) {
        Ok(text) => Some(text),
        Err(e) => {
            let good = e.utf8_error().valid_up_to();
            let bytes = e.as_bytes();
            let valid = std::str::from_utf8(&bytes[..good]).unwrap_or_default();
            Ctx::new(path, valid, out).err(
                good,
                format!(
                    "file is not valid UTF-8 (byte 0x{:02X}); save it as UTF-8",
                    bytes[good]
                ),
            );
            None
        }
    }
}

/// Duplicate glyph names and code points (the later file is reported).
fn check_unique(glyphs: &[GlyphFile], out: &mut Diagnostics) {
    let mut names: BTreeMap<&str, &Path> = BTreeMap::new();
    let mut code_points: BTreeMap<char, &str> = BTreeMap::new();
    for g in glyphs {
        let mut ctx = g.ctx(out);
        let name = g.glyph.name.as_str();
        if let Some(prev) = names.get(name) {
            ctx.err(
                g.spans.name,
                format!("duplicate glyph name `{name}` (also in {})", prev.display()),
            );
        } else {
            names.insert(name, &g.path);
        }
        for (c, off) in g.glyph.unicodes.iter().zip(&g.spans.unicodes) {
            if let Some(prev) = code_points.get(c) {
                ctx.err(
                    *off,
                    format!(
                        "code point U+{:04X} is already mapped to `{prev}`",
                        u32::from(*c)
                    ),
                );
            } else {
                code_points.insert(*c, name);
            }
        }
    }
}

/// Warns about control points more than [`FAR_EMS`] ems outside the glyph box (`x` from
/// 0 to the advance, `y` from descender to ascender): usually a typo such as `5000` for
/// `500`. One warning per contour, at its first such point. Component offsets are not
/// checked, nor glyphs with errors of their own.
fn check_far_points(glyphs: &[GlyphFile], info: &FontInfo, out: &mut Diagnostics) {
    let limit = FAR_EMS * f64::from(info.units_per_em);
    for g in glyphs.iter().filter(|g| g.complete) {
        let bounds = glyph_box(g.glyph.advance, info.descender, info.ascender);
        let mut ctx = g.ctx(out);
        for (contour, offs) in g.glyph.contours.iter().zip(&g.spans.points) {
            let points = contour.points();
            let far: Vec<usize> = (0..points.len())
                .filter(|&i| distance_outside(points[i].pos, bounds) > limit)
                .collect();
            let Some(&i) = far.first() else {
                continue;
            };
            let p = points[i].pos;
            let more = match far.len() - 1 {
                0 => String::new(),
                1 => "; 1 more point of this contour too".to_string(),
                n => format!("; {n} more points of this contour too"),
            };
            ctx.warn(
                offs[i],
                format!(
                    "point [{}, {}] is {} units outside the glyph box x 0..{}, y {}..{} \
                     (more than {FAR_EMS} em){more}",
                    emit::number(p.x),
                    emit::number(p.y),
                    emit::number(distance_outside(p, bounds).round()),
                    emit::number(bounds.x1),
                    emit::number(info.descender),
                    emit::number(info.ascender),
                ),
            );
        }
    }
}
