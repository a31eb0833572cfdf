//! The studio's font: the last good model and outlines, the source file of every glyph
//! with its version, and the errors of the sources as they are now.
//!
//! This is the only module of the server that knows the font model and the outliner
//! (`Font`, `fit_contour`, `OutlinedGlyph`): everything else sees names, JSON and file versions.
//!
//! A reload loads the whole folder again (the checks across files need it) but fits only
//! the contours that changed: each glyph's own contours are fitted once and kept, and a
//! glyph that places components takes its bases' fits, translated. The fit of a translated
//! contour is the translated fit up to rounding: on the bundled typeface every outline is
//! the one `build` makes at 1/100 unit (the precision of every output) and measured errors
//! agree to about 1e-6 (`tests/it/serve.rs`). While the sources have
//! errors the last good font is kept and served.

use std::collections::{BTreeMap, BTreeSet};
use std::hash::Hasher;
use std::path::{Path, PathBuf};

use kurbo::{Affine, BezPath, PathEl, Vec2};
use serde_json::{json, Value};

use crate::extrema::add_extrema;
use crate::fit::fit_contour;
use crate::model::{Contour, Font, Glyph};
use crate::orient::orient_contours;
use crate::outline::{min_piece, OutlinedGlyph, PlacedContour};
use crate::source::{
    load_glyph_text, load_sources, offsets_written, place_in_font, Diagnostic, Severity, SourceKind,
};
use crate::svg::glyph_svg;
use crate::svg::path_data::path_data;

/// The opaque version of a file: a hash of its bytes (FNV-1a 64, as 16 hex digits).
pub fn version(bytes: &[u8]) -> String {
    let mut h = fnv::FnvHasher::default();
    h.write(bytes);
    format!("{:016x}", h.finish())
}

/// One glyph fitted within the font's tolerance.
#[derive(Clone, Debug)]
struct Fitted {
    /// Components resolved, oriented for the nonzero rule; font units, y up.
    path: BezPath,
    segments: usize,
    worst_error: f64,
}

/// The fits of one glyph's own contours (no components, not yet oriented), with what they
/// were fitted from: a composite places its bases' fits, translated, instead of fitting
/// their contours again.
#[derive(Clone, Debug)]
struct OwnFit {
    contours: Vec<Contour>,
    tolerance: f64,
    /// Per contour: the path and its largest measured error.
    fits: Vec<(BezPath, f64)>,
}

/// What a reload found.
#[derive(Clone, Debug, PartialEq)]
pub enum Reload {
    /// The sources load; these glyphs (sorted) changed, possibly none. `fixed`: the
    /// sources had errors before this reload (pages must clear them even if no glyph
    /// changed).
    Changed {
        /// The glyphs that changed, by name.
        names: Vec<String>,
        /// Whether the sources had errors before.
        fixed: bool,
    },
    /// The sources have errors; the last good font is still served.
    Errors(Vec<Diagnostic>),
    /// The sources have the very errors they had at the last reload (an editor's save
    /// can reach the watcher as two events): nothing new to announce.
    SameErrors,
}

/// The font being served.
pub struct Studio {
    dir: PathBuf,
    font: Font,
    /// Glyph name -> its source file and the version of the text the model came from.
    files: BTreeMap<String, (PathBuf, String)>,
    fitted: BTreeMap<String, Fitted>,
    own: BTreeMap<String, OwnFit>,
    /// Errors of the sources on disk now (empty when they load).
    errors: Vec<Diagnostic>,
}

impl Studio {
    /// Loads and fits the font in `dir`, or returns every diagnostic when it has errors.
    pub fn open(dir: &Path) -> Result<Studio, Vec<Diagnostic>> {
        let loaded = load_sources(dir)?;
        let mut studio = Studio {
            dir: dir.to_path_buf(),
            font: loaded.font,
            files: files_of(&loaded.files),
            fitted: BTreeMap::new(),
            own: BTreeMap::new(),
            errors: Vec::new(),
        };
        let all: Vec<String> = studio.font.glyphs.iter().map(|g| g.name.clone()).collect();
        studio.refit(&all);
        Ok(studio)
    }

    /// The font folder.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// Loads the sources again. On success the model is replaced and the glyphs that
    /// changed (or place a changed glyph) are refitted; on errors nothing is replaced.
    pub fn reload(&mut self) -> Reload {
        let loaded = match load_sources(&self.dir) {
            Ok(loaded) => loaded,
            Err(diags) => {
                let errors = errors_only(diags);
                if errors == self.errors {
                    return Reload::SameErrors;
                }
                self.errors = errors;
                return Reload::Errors(self.errors.clone());
            }
        };
        let fixed = !self.errors.is_empty();
        self.errors.clear();
        let old = std::mem::replace(&mut self.font, loaded.font);
        self.files = files_of(&loaded.files);
        let changed = self.changed_since(&old);
        let refit: Vec<String> = changed
            .iter()
            .filter(|n| self.font.glyph(n).is_some())
            .cloned()
            .collect();
        self.fitted.retain(|name, _| self.files.contains_key(name));
        self.own.retain(|name, _| self.files.contains_key(name));
        self.refit(&refit);
        Reload::Changed {
            names: changed.into_iter().collect(),
            fixed,
        }
    }

    /// Replaces one glyph by a model read from `text` (already validated alone), for an
    /// edit made while another file has errors: the font is not reloaded, so this glyph
    /// shows its edit and the rest stay as they were.
    pub fn replace_glyph(&mut self, name: &str, text: &str) -> Vec<String> {
        let Some((path, _)) = self.files.get(name).cloned() else {
            return Vec::new();
        };
        let Ok((mut glyph, _)) = load_glyph_text(&path, text) else {
            return Vec::new();
        };
        // Components without `offset` go where the font's anchors put them.
        let written = offsets_written(&path, text).unwrap_or_default();
        place_in_font(&self.font, &mut glyph, &written);
        let old = self.font.clone();
        if let Some(slot) = self.font.glyphs.iter_mut().find(|g| g.name == name) {
            *slot = glyph;
        }
        self.files
            .insert(name.to_string(), (path, version(text.as_bytes())));
        let changed: Vec<String> = self.changed_since(&old).into_iter().collect();
        self.refit(&changed);
        changed
    }

    /// Glyph names whose model differs from `old` (added and removed ones included), and
    /// every glyph that places one of them; everything when the metrics or tolerance moved.
    fn changed_since(&self, old: &Font) -> BTreeSet<String> {
        if old.info != self.font.info {
            let mut all: BTreeSet<String> =
                self.font.glyphs.iter().map(|g| g.name.clone()).collect();
            all.extend(old.glyphs.iter().map(|g| g.name.clone()));
            return all;
        }
        let mut changed = BTreeSet::new();
        for g in &self.font.glyphs {
            if old.glyph(&g.name) != Some(g) {
                changed.insert(g.name.clone());
            }
        }
        for g in &old.glyphs {
            if self.font.glyph(&g.name).is_none() {
                changed.insert(g.name.clone());
            }
        }
        // Kerning is shown in the text line: its pairs' glyphs count as changed.
        for k in old.kerning.iter().chain(&self.font.kerning) {
            let same = old.kerning.contains(k) && self.font.kerning.contains(k);
            if !same {
                changed.insert(k.left.clone());
                changed.insert(k.right.clone());
            }
        }
        // Composites of changed glyphs, to any depth.
        loop {
            let more: Vec<String> = self
                .font
                .glyphs
                .iter()
                .filter(|g| !changed.contains(&g.name))
                .filter(|g| g.components.iter().any(|c| changed.contains(&c.base)))
                .map(|g| g.name.clone())
                .collect();
            if more.is_empty() {
                break;
            }
            changed.extend(more);
        }
        changed
    }

    /// Fits `names` again: a glyph's own contours when they changed, then its outline
    /// with the fits of its components placed.
    fn refit(&mut self, names: &[String]) {
        let tolerance = self.font.info.tolerance;
        for name in names {
            let Some(glyph) = self.font.glyph(name) else {
                continue;
            };
            let fresh = self
                .own
                .get(name)
                .is_some_and(|o| o.tolerance == tolerance && o.contours == glyph.contours);
            if !fresh {
                self.own.insert(name.clone(), fit_own(glyph, tolerance));
            }
        }
        for name in names {
            if let Some(glyph) = self.font.glyph(name) {
                let fitted = self.compose(glyph);
                self.fitted.insert(name.clone(), fitted);
            }
        }
    }

    /// A glyph's outline: its own fits and its components' (recursively, translated),
    /// oriented together, as [`crate::outline`] orients the fits of resolved contours.
    fn compose(&self, glyph: &Glyph) -> Fitted {
        let mut contours = Vec::new();
        let mut worst_error: f64 = 0.0;
        let depth = self.font.glyphs.len();
        self.place(glyph, Vec2::ZERO, depth, &mut contours, &mut worst_error);
        let path = add_extrema(&orient_contours(contours), min_piece(&self.font.info));
        let segments = path
            .elements()
            .iter()
            .filter(|el| !matches!(el, PathEl::MoveTo(_) | PathEl::ClosePath))
            .count();
        Fitted {
            path,
            segments,
            worst_error,
        }
    }

    /// Adds `glyph`'s own fits moved by `offset`, then its components'; `depth` bounds the
    /// recursion (the loader refuses cycles; this is a safety net).
    fn place(
        &self,
        glyph: &Glyph,
        offset: Vec2,
        depth: usize,
        out: &mut Vec<BezPath>,
        worst: &mut f64,
    ) {
        if let Some(own) = self.own.get(&glyph.name) {
            for (path, error) in &own.fits {
                out.push(if offset == Vec2::ZERO {
                    path.clone()
                } else {
                    Affine::translate(offset) * path
                });
                *worst = worst.max(*error);
            }
        }
        if depth == 0 {
            return;
        }
        for component in &glyph.components {
            if let Some(base) = self.font.glyph(&component.base) {
                let moved = offset + Vec2::new(component.offset.0, component.offset.1);
                self.place(base, moved, depth - 1, out, worst);
            }
        }
    }

    /// Whether every source file among `paths` is, byte for byte, what the served font
    /// was loaded from (then a file event needs no reload: an edit made here). Any other
    /// file, or errors being shown, means a reload.
    pub fn is_current(&self, paths: &[PathBuf]) -> bool {
        self.errors.is_empty()
            && paths.iter().all(|path| {
                let name = path.file_name().map(|n| n.to_string_lossy().into_owned());
                if name.is_some_and(|n| n.starts_with('.') || !n.ends_with(".toml")) {
                    return true;
                }
                // One folder: the file name identifies the file, however the path is spelt.
                let known = self
                    .files
                    .values()
                    .find(|(p, _)| p.file_name() == path.file_name());
                match (known, std::fs::read(path)) {
                    (Some((_, v)), Ok(bytes)) => *v == version(&bytes),
                    _ => false,
                }
            })
    }

    /// The errors of the sources on disk, empty when they load.
    pub fn errors(&self) -> &[Diagnostic] {
        &self.errors
    }

    /// The source file of glyph `name`, if the font has that glyph. This is the only way a
    /// request reaches a file: the path comes from the folder listing, never from the name.
    pub fn glyph_file(&self, name: &str) -> Option<&Path> {
        self.files.get(name).map(|(p, _)| p.as_path())
    }

    /// Checks an edited glyph file alone, as `check` would; the error diagnostics if any.
    pub fn check_glyph_text(&self, name: &str, text: &str) -> Result<(), Vec<Diagnostic>> {
        let Some(path) = self.glyph_file(name) else {
            return Ok(());
        };
        match load_glyph_text(path, text) {
            Ok((glyph, _)) if glyph.name == name => Ok(()),
            Ok((glyph, _)) => Err(vec![Diagnostic::whole(
                path,
                Severity::Error,
                format!("the edit renamed glyph `{name}` to `{}`", glyph.name),
            )]),
            Err(diags) => Err(errors_only(diags)),
        }
    }

    /// `GET /api/font`: the font.toml fields, kerning, and every glyph with its outline.
    pub fn font_json(&self) -> Value {
        let info = &self.font.info;
        let glyphs: Vec<Value> = self
            .font
            .glyphs
            .iter()
            .map(|g| {
                let mut entry = json!({
                    "name": g.name,
                    "unicodes": unicodes(g),
                    "advance": g.advance,
                });
                if let Some(f) = self.fitted.get(&g.name) {
                    entry["path"] = json!(path_data(&f.path, Affine::IDENTITY));
                    entry["segments"] = json!(f.segments);
                    entry["worst_error"] = json!(f.worst_error);
                }
                entry
            })
            .collect();
        let kerning: Vec<Value> = self
            .font
            .kerning
            .iter()
            .map(|k| json!({"left": k.left, "right": k.right, "value": k.value}))
            .collect();
        json!({
            "info": {
                "family": info.family,
                "style": info.style,
                "units_per_em": info.units_per_em,
                "ascender": info.ascender,
                "descender": info.descender,
                "x_height": info.x_height,
                "cap_height": info.cap_height,
                "tolerance": info.tolerance,
                "copyright": info.copyright,
                "designer": info.designer,
                "version": info.version,
            },
            "glyphs": glyphs,
            "kerning": kerning,
        })
    }

    /// `GET /api/glyph/{name}`: the control points, components (with the outline each one
    /// places), the fitted outline as SVG path data (font units, y up), and its figures.
    pub fn glyph_json(&self, name: &str) -> Option<Value> {
        let glyph = self.font.glyph(name)?;
        let fitted = self.fitted.get(name)?;
        let (_, version) = self.files.get(name)?;
        let contours: Vec<Value> = glyph
            .contours
            .iter()
            .map(|c| {
                let points: Vec<Value> = c
                    .points()
                    .iter()
                    .map(|p| json!([p.pos.x, p.pos.y, p.s]))
                    .collect();
                json!({ "points": points })
            })
            .collect();
        let components: Vec<Value> = glyph
            .components
            .iter()
            .map(|c| {
                let placed = self
                    .fitted
                    .get(&c.base)
                    .map(|f| path_data(&f.path, Affine::translate((c.offset.0, c.offset.1))));
                json!({"base": c.base, "offset": [c.offset.0, c.offset.1], "path": placed})
            })
            .collect();
        Some(json!({
            "name": glyph.name,
            "unicodes": unicodes(glyph),
            "advance": glyph.advance,
            "version": version,
            "contours": contours,
            "components": components,
            "path": path_data(&fitted.path, Affine::IDENTITY),
            "segments": fitted.segments,
            "worst_error": fitted.worst_error,
        }))
    }

    /// `GET /glyph/{name}.svg`: the standalone SVG that `build` writes into `svg/`.
    pub fn glyph_svg(&self, name: &str) -> Option<String> {
        let glyph = self.font.glyph(name)?;
        let fitted = self.fitted.get(name)?;
        let outline = OutlinedGlyph {
            name: glyph.name.clone(),
            unicodes: glyph.unicodes.clone(),
            advance: glyph.advance,
            components: glyph.components.clone(),
            anchors: glyph.anchors.clone(),
            placed_anchors: self.font.anchors(glyph),
            outline_mark: glyph.outline_mark,
            contours: self
                .font
                .placed_contours(glyph)
                .into_iter()
                .map(|(contour, (dx, dy))| PlacedContour {
                    spline: contour.spline().clone(),
                    offset: Vec2::new(dx, dy),
                })
                .collect(),
            path: fitted.path.clone(),
            max_error: fitted.worst_error,
            segments: fitted.segments,
        };
        Some(glyph_svg(&self.font.info, &outline))
    }
}

/// Glyph name -> (file, version) from the loader's file list.
fn files_of(files: &[crate::source::SourceFile]) -> BTreeMap<String, (PathBuf, String)> {
    files
        .iter()
        .filter_map(|f| match &f.kind {
            SourceKind::Glyph(name) => {
                Some((name.clone(), (f.path.clone(), version(f.text.as_bytes()))))
            }
            _ => None,
        })
        .collect()
}

fn errors_only(diags: Vec<Diagnostic>) -> Vec<Diagnostic> {
    diags
        .into_iter()
        .filter(|d| d.severity == Severity::Error)
        .collect()
}

fn unicodes(glyph: &Glyph) -> Vec<u32> {
    glyph.unicodes.iter().map(|&c| u32::from(c)).collect()
}

/// Fits a glyph's own contours (the model holds validated X-splines).
fn fit_own(glyph: &Glyph, tolerance: f64) -> OwnFit {
    let fits = glyph
        .contours
        .iter()
        .map(|contour| {
            let fit = fit_contour(contour.spline(), tolerance);
            (fit.path, fit.max_error)
        })
        .collect();
    OwnFit {
        contours: glyph.contours.clone(),
        tolerance,
        fits,
    }
}

/// A diagnostic as the event stream and the API give it (`check --format json` fields).
pub fn diagnostic_json(d: &Diagnostic) -> Value {
    json!({
        "file": d.path.to_string_lossy(),
        "line": d.line,
        "column": d.col,
        "message": d.message,
        "text": d.to_string(),
    })
}
