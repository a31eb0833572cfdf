//! `xglyph fmt`: rewrite the sources in the canonical layout of [`crate::source::emit`].
//!
//! Only when the sources load without errors (otherwise the diagnostics are printed and
//! nothing is touched); only the files whose text changes; each glyph stays in its file;
//! all changed files are written together or none ([`crate::write::OutputSet`]). A source
//! that is a symbolic link is written through: its target gets the new text and the link
//! stays. `--check` writes nothing and lists the files that
//! would change (exit 1 if any), for CI.
//!
//! Comments: a file's leading comment block is kept. Any other comment would be lost, so
//! `fmt` then refuses to write anything (exit 1, listing each such comment) unless
//! `--force` is given, which drops them.

use std::fs;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use super::check;
use super::CommandError;
use crate::designspace::Location;
use crate::model::Glyph;
use crate::source::format::{rewrites, Rewrite};
use crate::source::{
    line_col, load_designspace_text, load_glyph_text, load_info_text, load_kerning_text,
    load_sources, offsets_written, LoadedFont, SourceKind,
};
use crate::terminal::{err, errln, outln};
use crate::write::{reason, OutputSet};

#[derive(Debug, clap::Args)]
pub struct FmtArgs {
    /// Font directory to format.
    #[arg(default_value = "glyphs")]
    pub font_dir: PathBuf,
    /// Write nothing; list the files that are not canonical and exit 1 if there are any.
    #[arg(long)]
    pub check: bool,
    /// Rewrite files even when that drops comments (the leading comment block is kept).
    #[arg(long)]
    pub force: bool,
}

pub fn run(args: FmtArgs) -> Result<ExitCode, CommandError> {
    let loaded = match load_sources(&args.font_dir) {
        Ok(loaded) => loaded,
        Err(diags) => {
            for d in &diags {
                err!("{}", check::text(d));
            }
            errln!("fmt: the sources have errors; nothing was changed");
            return Ok(ExitCode::FAILURE);
        }
    };
    for d in &loaded.warnings {
        err!("{}", check::text(d));
    }
    let changes: Vec<Rewrite> = rewrites(&loaded)
        .into_iter()
        .filter(Rewrite::changes)
        .collect();

    if args.check {
        for r in &changes {
            outln!("{}", r.path.display());
        }
        if changes.is_empty() {
            return Ok(ExitCode::SUCCESS);
        }
        errln!("fmt --check: {} files are not formatted", changes.len());
        return Ok(ExitCode::FAILURE);
    }

    let with_comments: Vec<&Rewrite> = changes
        .iter()
        .filter(|r| !r.dropped_comments.is_empty())
        .collect();
    if !args.force && !with_comments.is_empty() {
        for r in &with_comments {
            for &off in &r.dropped_comments {
                let (line, col) = line_col(&r.old, off);
                errln!(
                    "{}:{line}:{col}: error: fmt would drop this comment",
                    r.path.display()
                );
            }
        }
        errln!(
            "fmt: only the comment block at the top of a file survives formatting; move these \
             comments there, or run `xglyph fmt --force` to drop them. Nothing was changed."
        );
        return Ok(ExitCode::FAILURE);
    }

    verify(&loaded, &changes)?;
    let mut set = OutputSet::new();
    for r in &changes {
        set.add(write_through(&r.path)?, r.new.as_bytes());
    }
    set.commit()
        .map_err(|e| format!("{e}; nothing was changed"))?;
    for r in &changes {
        outln!("{}", r.path.display());
    }
    Ok(ExitCode::SUCCESS)
}

/// Where the formatted text of `path` goes: the file itself, or for a link the file it
/// points to (the link stays a link).
fn write_through(path: &Path) -> Result<PathBuf, CommandError> {
    let link = fs::symlink_metadata(path).is_ok_and(|m| m.file_type().is_symlink());
    if !link {
        return Ok(path.to_path_buf());
    }
    fs::canonicalize(path).map_err(|e| {
        format!(
            "cannot follow the link {}: {}; nothing was changed",
            path.display(),
            reason(&e)
        )
        .into()
    })
}

/// A safety net before writing: every new text loads back to the same model (the writer
/// is the loader's inverse; this guards against a bug in it breaking a font).
fn verify(loaded: &LoadedFont, changes: &[Rewrite]) -> Result<(), CommandError> {
    let font = &loaded.font;
    let names = font.glyphs.iter().map(|g| g.name.clone()).collect();
    for r in changes {
        let same = match &r.kind {
            SourceKind::Info => {
                let dir = r.path.parent().unwrap_or(Path::new("."));
                let masters: Vec<(String, String, Location, bool)> = loaded
                    .masters
                    .iter()
                    .map(|m| {
                        let folder = m.folder.to_string_lossy().into_owned();
                        (m.name.clone(), folder, m.location.clone(), m.sparse)
                    })
                    .collect();
                load_info_text(&r.path, &r.new).is_ok_and(|(i, _)| i == font.info)
                    && load_designspace_text(&r.path, &r.new, dir)
                        .is_ok_and(|(ds, ms)| ds == loaded.designspace && ms == masters)
            }
            SourceKind::Glyph(name) => font
                .glyph(name)
                .is_some_and(|want| same_glyph(r, want, true)),
            SourceKind::Kerning => {
                load_kerning_text(&r.path, &r.new, &names).is_ok_and(|k| k == font.kerning)
            }
            SourceKind::MasterGlyph(m, name) => {
                let want = loaded.masters[*m].glyphs.iter().find(|g| &g.name == name);
                want.is_some_and(|want| same_glyph(r, want, false))
            }
            SourceKind::MasterKerning(m) => load_kerning_text(&r.path, &r.new, &names)
                .is_ok_and(|k| k == loaded.masters[*m].kerning),
        };
        if !same {
            return Err(format!(
                "internal error: the formatted {} would not load back the same; nothing was changed",
                r.path.display()
            )
            .into());
        }
    }
    Ok(())
}

/// Whether the rewritten glyph file loads back as `want`: the same name, advance, contours,
/// components and anchors (and code points, with `unicodes`), with an `offset` written
/// for exactly the components that had one. A component without `offset` reads back at
/// `[0, 0]` alone (its placement needs the font), so its offset is not compared.
fn same_glyph(r: &Rewrite, want: &Glyph, unicodes: bool) -> bool {
    let Ok((mut got, _)) = load_glyph_text(&r.path, &r.new) else {
        return false;
    };
    let written = offsets_written(&r.path, &r.new);
    if written.is_none() || written != offsets_written(&r.path, &r.old) {
        return false;
    }
    let written = written.unwrap_or_default();
    for ((c, w), &kept) in got
        .components
        .iter_mut()
        .zip(&want.components)
        .zip(&written)
    {
        if !kept {
            c.offset = w.offset;
        }
    }
    (
        &got.name,
        got.advance,
        &got.contours,
        &got.components,
        &got.anchors,
    ) == (
        &want.name,
        want.advance,
        &want.contours,
        &want.components,
        &want.anchors,
    ) && (!unicodes || got.unicodes == want.unicodes)
}
