//! UFO 3 export: an [`OutlinedFont`] as a Unified Font Object, written with norad.
//!
//! ```text
//! OutlinedFont -> info.rs (fontinfo.plist, font lib) + glyph.rs (one .glif per glyph)
//!              -> norad::Font -> files in memory (norad's FontSink), or a directory
//! ```
//!
//! What goes where:
//! - Each glyph's own contours are the build's fitted cubics (the same subpaths, in the
//!   same direction, as the TTF/OTF/SVG outputs), coordinates rounded to 1/1000 font unit;
//!   components stay components, placed by their offsets; code points and advance as in
//!   the sources.
//! - `kerning.plist` holds the pairs by glyph name (no groups); `fontinfo.plist` the names,
//!   metrics and licence of `font.toml` plus the underline, vendor and version fields font
//!   compilers and checkers read.
//! - The X-spline sources ride along in the libs ([`lib`]), so
//!   [`crate::import::import_ufo`] gives back the same model: export then import is exact.
//!   A font with a `mark = "outline"` glyph also gets `public.openTypeCategories`
//!   ([`lib::categories_value`]): no anchor tells ufo2ft or fontc that the glyph is a mark.
//!
//! One call per master: [`export`] reads one outlined font, so a family exports each
//! master's [`OutlinedFont`] in turn; [`designspace`] does that for a font with masters and
//! writes the `.designspace` file that ties the UFOs together.
//!
//! Glyph file names are norad's (the UFO 3 user-name-to-file-name rule); glyph names follow
//! the OpenType `post` rule already, so every name is a valid UFO name. The output is
//! deterministic: fixed key order in every plist, glyphs in the font's order.
//!
//! Anchors are written with their names and exact positions. Limits: no guidelines (the
//! model has none); a font without a `.notdef` gets
//! none in the UFO (compilers then make their own); the files are meant for a fresh
//! `<Family>-<Style>.ufo` folder: glyph files of an older export that are no longer in the
//! font are not removed by writing into the same folder (they are not in
//! `contents.plist`, so UFO readers ignore them).

pub mod designspace;
mod glyph;
mod info;
pub mod lib;

pub(crate) use info::version_numbers;

use std::collections::{HashMap, HashSet};
use std::fmt;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

use crate::outline::OutlinedFont;
use crate::reuse::{OutlineKeys, Reuse};
use crate::svg::output_stem;

/// Why a font could not be exported as UFO.
#[derive(Debug)]
pub enum UfoError {
    /// A glyph name that UFO does not allow (empty, or with control characters); only a
    /// model built in code can have one, the loader refuses them.
    GlyphName(String),
    /// An anchor name that UFO does not allow (empty, or with control characters).
    AnchorName {
        /// The glyph that has the anchor.
        glyph: String,
        /// The anchor's name.
        anchor: String,
    },
    /// Two masters would write the same UFO folder (their styles differ only in spaces or
    /// in characters a file name cannot hold).
    MasterName(String),
    /// More than 99 glyph names share one file name once case is folded (norad's limit).
    FileNameClash(String),
    /// norad refused to write the font.
    Write(String),
}

impl fmt::Display for UfoError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            UfoError::GlyphName(name) => {
                write!(f, "UFO export: glyph name {name:?} is not a valid UFO name")
            }
            UfoError::AnchorName { glyph, anchor } => write!(
                f,
                "UFO export: glyph `{glyph}` has the anchor name {anchor:?}, which is not a \
                 valid UFO name"
            ),
            UfoError::MasterName(dir) => write!(
                f,
                "UFO export: two masters would both be written as {dir}; give them styles \
                 that differ in more than spaces"
            ),
            UfoError::FileNameClash(name) => write!(
                f,
                "UFO export: too many glyph names share the file name of `{name}` when case is \
                 ignored; rename some of them"
            ),
            UfoError::Write(e) => write!(f, "UFO export: {e}"),
        }
    }
}

impl std::error::Error for UfoError {}

/// The UFO's folder name among the build outputs: `<Family>-<Style>.ufo`, the stem of
/// the other font files.
pub fn ufo_dir_name(font: &OutlinedFont) -> String {
    format!("{}.ufo", output_stem(&font.info))
}

/// The font as a norad UFO: fontinfo, font lib, kerning and one glyph per outlined glyph,
/// in the font's glyph order.
pub fn export(font: &OutlinedFont) -> Result<norad::Font, UfoError> {
    check_file_names(font)?;
    let mut ufo = norad::Font::new();
    let layer = ufo.default_layer_mut();
    for (g, own) in font.glyphs.iter().zip(own_contours(font)) {
        layer.insert_glyph(glyph::glyph(g, own)?);
    }
    fill_font(&mut ufo, font)?;
    Ok(ufo)
}

/// How many of each glyph's contours are its own: they come first, then every
/// component's (recursively placed).
fn own_contours(font: &OutlinedFont) -> Vec<usize> {
    let contours: HashMap<&str, usize> = font
        .glyphs
        .iter()
        .map(|g| (g.name.as_str(), g.contours.len()))
        .collect();
    font.glyphs
        .iter()
        .map(|g| {
            let placed: usize = g
                .components
                .iter()
                .map(|c| contours.get(c.base.as_str()).copied().unwrap_or(0))
                .sum();
            g.contours.len().saturating_sub(placed)
        })
        .collect()
}

/// The font-wide parts of the UFO: fontinfo, font lib, features and kerning.
fn fill_font(ufo: &mut norad::Font, font: &OutlinedFont) -> Result<(), UfoError> {
    ufo.font_info = info::font_info(&font.info);
    ufo.lib = info::font_lib(font);
    // The font's own features.fea, as written: fontmake and fontc add kern and mark from
    // the kerning and anchors, as xglyph does.
    if let Some(features) = &font.features {
        ufo.features = features.text.clone();
    }
    for k in &font.kerning {
        let (left, right) = (name(&k.left)?, name(&k.right)?);
        ufo.kerning
            .entry(left)
            .or_default()
            .insert(right, k.value + 0.0);
    }
    Ok(())
}

/// Every file of the UFO in memory, paths relative to the build's output folder
/// (`<Family>-<Style>.ufo/metainfo.plist`, …), sorted by path: what `build` writes.
pub fn output_files(font: &OutlinedFont) -> Result<Vec<(PathBuf, Vec<u8>)>, UfoError> {
    output_files_reusing(font, &Reuse::off(), &OutlineKeys::default(), &[])
}

/// One file of a UFO: its path and bytes.
type UfoFile = (PathBuf, Vec<u8>);

/// A layer besides the default one: a sparse master's glyphs, in the UFO of the default
/// master, as fontmake and fontc read a designspace source on a layer.
pub struct ExtraLayer<'a> {
    /// The layer's name (the master's).
    pub name: &'a str,
    /// The master as a whole font (every glyph, so that components count right).
    pub font: &'a OutlinedFont,
    /// Per glyph of [`Self::font`], whether the layer holds it.
    pub glyphs: &'a [bool],
}

/// [`output_files`], leaving out each `.glif` that OUT holds already as the last build made
/// it from the same glyph ([`Reuse::kept_or_make`]). The `.glif`s are encoded on every core
/// (norad, as it would write them); the other files are norad's, of the font with empty
/// glyphs of the same names (so `contents.plist` and the file names are norad's too).
/// `outlines` are the font's [`OutlineKeys`]. `layers` are written after the default layer
/// (their `.glif`s made on each build).
pub fn output_files_reusing(
    font: &OutlinedFont,
    reuse: &Reuse,
    outlines: &OutlineKeys,
    layers: &[ExtraLayer<'_>],
) -> Result<Vec<(PathBuf, Vec<u8>)>, UfoError> {
    use rayon::prelude::*;
    check_file_names(font)?;
    let dir = PathBuf::from(ufo_dir_name(font));
    let mut ufo = norad::Font::new();
    let layer = ufo.default_layer_mut();
    for g in &font.glyphs {
        layer.insert_glyph(norad::Glyph::new(&g.name));
    }
    let mut layer_dirs = Vec::with_capacity(layers.len() + 1);
    let mut extra_glifs = Vec::new();
    for extra in layers {
        let new = ufo
            .layers
            .new_layer(extra.name)
            .map_err(|e| UfoError::Write(format!("layer `{}`: {}", extra.name, error_chain(&e))))?;
        let held = extra.font.glyphs.iter().zip(extra.glyphs);
        for (g, _) in held.clone().filter(|(_, &h)| h) {
            new.insert_glyph(norad::Glyph::new(&g.name));
        }
        let new_dir = new.path().to_path_buf();
        for ((g, _), own) in held.zip(own_contours(extra.font)).filter(|((_, &h), _)| h) {
            let file = new.get_path(&g.name).ok_or_else(|| {
                UfoError::Write(format!("no file name for the glyph `{}`", g.name))
            })?;
            let bytes = glyph::glyph(g, own)?
                .encode_xml()
                .map_err(|e| UfoError::Write(error_chain(&e)))?;
            extra_glifs.push((new_dir.join(file), bytes));
        }
        layer_dirs.push(new_dir);
    }
    let layer = ufo.default_layer();
    let layer_dir = layer.path().to_path_buf();
    layer_dirs.push(layer_dir.clone());
    let owns = own_contours(font);
    // In font order, so that the first glyph in error is the one reported.
    let glifs: Vec<Result<Option<UfoFile>, UfoError>> = font
        .glyphs
        .par_iter()
        .zip(owns)
        .enumerate()
        .map(|(i, (g, own))| {
            let file = layer.get_path(&g.name).ok_or_else(|| {
                UfoError::Write(format!("no file name for the glyph `{}`", g.name))
            })?;
            let path = layer_dir.join(file);
            let make = || {
                glyph::glyph(g, own)?
                    .encode_xml()
                    .map_err(|e| UfoError::Write(error_chain(&e)))
            };
            let key = glyph::key(g, own, &outlines.get(i, &g.path));
            let bytes = reuse.kept_or_make(&dir.join(&path), key, make)?;
            Ok(bytes.map(|bytes| (path, bytes)))
        })
        .collect();
    let mut glif_files = Vec::with_capacity(glifs.len());
    for glif in glifs {
        glif_files.extend(glif?);
    }
    fill_font(&mut ufo, font)?;
    // The empty glyphs' files are dropped: the `.glif`s are those made above.
    let is_glif = |path: &Path| {
        path.parent()
            .is_some_and(|p| layer_dirs.iter().any(|d| d.as_path() == p))
            && path.extension().is_some_and(|e| e == "glif")
    };
    let mut files: Vec<(PathBuf, Vec<u8>)> = files(&ufo)?
        .into_iter()
        .filter(|(path, _)| !is_glif(path))
        .collect();
    files.extend(glif_files);
    files.extend(extra_glifs);
    files.sort();
    Ok(files
        .into_iter()
        .map(|(path, bytes)| (dir.join(path), bytes))
        .collect())
}

/// Every file of `ufo`, paths relative to the `.ufo` folder, sorted by path.
pub fn files(ufo: &norad::Font) -> Result<Vec<(PathBuf, Vec<u8>)>, UfoError> {
    let out = Mutex::new(Vec::new());
    let sink = |path: &Path, data: &[u8]| {
        out.lock()
            .map_err(|_| std::io::Error::other("a writer thread panicked"))?
            .push((path.to_path_buf(), data.to_vec()));
        Ok(())
    };
    ufo.save_to_sink(&sink, &norad::WriteOptions::default())
        .map_err(|e| UfoError::Write(error_chain(&e)))?;
    let mut files = out
        .into_inner()
        .map_err(|_| UfoError::Write("a writer thread panicked".into()))?;
    files.sort();
    Ok(files)
}

/// Writes the UFO of `font` as the folder `path` (replacing a folder already there).
pub fn save(font: &OutlinedFont, path: &Path) -> Result<(), UfoError> {
    export(font)?
        .save(path)
        .map_err(|e| UfoError::Write(format!("{}: {}", path.display(), error_chain(&e))))
}

fn name(text: &str) -> Result<norad::Name, UfoError> {
    norad::Name::new(text).map_err(|_| UfoError::GlyphName(text.to_string()))
}

/// An error and its sources on one line (norad's errors nest).
pub(crate) fn error_chain(e: &dyn std::error::Error) -> String {
    let mut text = e.to_string();
    let mut source = e.source();
    while let Some(s) = source {
        text.push_str(": ");
        text.push_str(&s.to_string());
        source = s.source();
    }
    text
}

/// Runs norad's file-name rule over the glyph names in the order norad will, so that a
/// set norad cannot name (it panics after 99 case-folded clashes) is an error instead.
fn check_file_names(font: &OutlinedFont) -> Result<(), UfoError> {
    let mut taken: HashSet<String> = HashSet::new();
    for g in &font.glyphs {
        name(&g.name)?;
        let mut tries = 0;
        let file = norad::user_name_to_file_name(&g.name, "", ".glif", |candidate| {
            tries += 1;
            // Accepting the 100th candidate stops norad before its panic.
            !taken.contains(candidate) || tries == 100
        });
        let file = file.to_string_lossy().to_lowercase();
        if !taken.insert(file) {
            return Err(UfoError::FileNameClash(g.name.clone()));
        }
    }
    Ok(())
}
