//! `xglyph import`: a font file, a UFO, a designspace or SVG drawings -> a font directory of
//! X-spline sources (with a master folder per designspace source).
//!
//! Everything is fitted in memory first (glyphs in parallel); the files are then written
//! into a new temporary folder next to the output, which is renamed into place only when
//! every file was written, so a failure (a full disk) leaves nothing behind. Never into a
//! non-empty directory without `--force` (then the files are moved in one by one).
//! Progress goes to stderr when it is a terminal.

use std::collections::BTreeMap;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::Arc;

use super::CommandError;
use crate::import::{self, font::parse_glyph_list, ImportError, ImportOptions, Progress};
use crate::source::emit::font_sources;
use crate::terminal::{errln, out, outln};

#[derive(Debug, clap::Args)]
pub struct ImportArgs {
    /// One font (.ttf, .otf, .woff, .woff2, or a collection .ttc, .otc), one UFO folder (.ufo), one
    /// designspace (.designspace: a font with masters), or one or more SVG drawings (.svg,
    /// one glyph each).
    #[arg(required = true)]
    pub inputs: Vec<PathBuf>,
    /// Output font directory (must be empty or absent unless --force).
    #[arg(short, long)]
    pub output: PathBuf,
    /// Fonts: characters to import, e.g. `A-Z,a-z,0-9`, with the glyphs their default
    /// shaping substitutes in (default: every mapped character and every glyph the font's
    /// substitutions reach).
    #[arg(long)]
    pub glyphs: Option<String>,
    /// Collections: which font to import, from 0 (default 0).
    #[arg(long)]
    pub face: Option<u32>,
    /// Largest distance (font units) from the original after import and build
    /// (default: 1/1000 em).
    #[arg(long)]
    pub tolerance: Option<f64>,
    /// Family name of the new font.
    #[arg(long)]
    pub family: Option<String>,
    /// SVG: TOML file mapping glyph names (file stems) to code points, e.g. `home = 0xE001`
    /// or `home = "h"`.
    #[arg(long)]
    pub codepoints: Option<PathBuf>,
    /// SVG: first code point for unmapped drawings, in hex (default E000).
    #[arg(long)]
    pub first_codepoint: Option<String>,
    /// SVG: units per em of the new font (default 1000).
    #[arg(long)]
    pub units_per_em: Option<u16>,
    /// Designspace with discrete axes (`<axis … values="0 1"/>`, such as an italic axis):
    /// the discrete location to import, `TAG=VALUE` in user values, several separated by
    /// commas, e.g. `ital=1`. xglyph's axes are continuous, so an import takes one discrete
    /// location (as fontmake builds one variable font per location): its sources, instances
    /// and rules, with the continuous axes whole. A discrete axis not named is at its
    /// default, and a note on stderr says which other values it has.
    #[arg(long, value_name = "TAG=VALUE")]
    pub at: Option<String>,
    /// Write into a non-empty output directory, replacing files of the same name.
    #[arg(long)]
    pub force: bool,
}

enum Kind {
    Font,
    Svg,
    Ufo,
    Designspace,
}

fn kind(path: &Path) -> Result<Kind, ImportError> {
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_lowercase())
        .unwrap_or_default();
    match ext.as_str() {
        "ttf" | "otf" | "ttc" | "otc" | "woff" | "woff2" => Ok(Kind::Font),
        "svg" => Ok(Kind::Svg),
        "ufo" => Ok(Kind::Ufo),
        "designspace" => Ok(Kind::Designspace),
        _ => Err(ImportError::at(
            path,
            "unknown input type; expected a font (.ttf, .otf, .ttc, .otc, .woff, .woff2), \
             a .svg or .designspace file or a .ufo folder",
        )),
    }
}

fn read(path: &Path) -> Result<Vec<u8>, ImportError> {
    std::fs::read(path).map_err(|e| ImportError::at(path, format!("cannot read: {e}")))
}

/// A font file's bytes, unpacked when it is WOFF or WOFF2.
fn read_font(path: &Path) -> Result<Vec<u8>, ImportError> {
    import::webfont::unpacked(read(path)?).map_err(|message| ImportError::at(path, message))
}

pub fn run(args: ImportArgs) -> Result<ExitCode, CommandError> {
    check_output_dir(&args.output, args.force)?;
    refuse_at(&args)?;
    let progress = std::io::stderr().is_terminal().then(terminal_progress);
    if let [one] = args.inputs.as_slice() {
        match kind(one) {
            Ok(Kind::Designspace) => return import_family(&args, Progress(progress)),
            Ok(Kind::Font) => {
                let data = read_font(one)?;
                if import::variable::is_variable(&data, args.face.unwrap_or(0)) {
                    return import_variable(&args, &data, Progress(progress));
                }
            }
            _ => {}
        }
    }
    let imported = import_inputs(&args, Progress(progress))?;
    let files = font_sources(&imported.font);
    let written = write_font_dir(&args.output, &files)?;
    out!("{}", imported.report.render());
    outln!("wrote {written} files to {}", args.output.display());
    Ok(ExitCode::SUCCESS)
}

/// A designspace: its sources as a font with masters, each source's report in turn.
fn import_family(args: &ImportArgs, progress: Progress) -> Result<ExitCode, CommandError> {
    check_designspace_flags(args)?;
    let opts = ufo_options(args, progress);
    let imported = import::designspace::import_designspace(&args.inputs[0], &opts)?;
    let files = import::designspace::family_sources(&imported.family);
    let written = write_font_dir(&args.output, &files)?;
    if let Some(place) = &imported.discrete {
        for notice in place.notices() {
            errln!("note: {notice}");
        }
    }
    for (style, report) in &imported.reports {
        outln!("source {style}:");
        out!("{}", report.render());
    }
    if let Some(place) = &imported.discrete {
        outln!(
            "{}",
            place.summary(imported.family.designspace.instances.len())
        );
        for note in &place.notes {
            outln!("note: {note}");
        }
    }
    outln!("wrote {written} files to {}", args.output.display());
    Ok(ExitCode::SUCCESS)
}

/// A variable font: its masters as a font with masters, each master's report in turn.
fn import_variable(
    args: &ImportArgs,
    data: &[u8],
    progress: Progress,
) -> Result<ExitCode, CommandError> {
    refuse_svg_flags(args)?;
    let opts = ImportOptions {
        tolerance: args.tolerance,
        family: args.family.clone(),
        face: args.face.unwrap_or(0),
        glyphs: args.glyphs.as_deref().map(parse_glyph_list).transpose()?,
        progress,
        ..ImportOptions::default()
    };
    let imported = import::variable::import_variable_font(&args.inputs[0], data, &opts)?;
    write_family(args, &imported)
}

/// Writes an imported family and prints each master's report.
fn write_family(
    args: &ImportArgs,
    imported: &import::designspace::ImportedFamily,
) -> Result<ExitCode, CommandError> {
    let files = import::designspace::family_sources(&imported.family);
    let written = write_font_dir(&args.output, &files)?;
    for (style, report) in &imported.reports {
        outln!("master {style}:");
        out!("{}", report.render());
    }
    outln!("wrote {written} files to {}", args.output.display());
    Ok(ExitCode::SUCCESS)
}

/// Refuses the SVG-only flags for a font.
fn refuse_svg_flags(args: &ImportArgs) -> Result<(), ImportError> {
    for (given, flag) in [
        (args.codepoints.is_some(), "--codepoints"),
        (args.first_codepoint.is_some(), "--first-codepoint"),
        (args.units_per_em.is_some(), "--units-per-em"),
    ] {
        if given {
            return Err(ImportError::plain(format!(
                "{flag} applies to SVG drawings, not to fonts"
            )));
        }
    }
    Ok(())
}

/// A `\r12/345 glyphs` counter on stderr, redrawn about 200 times in all, ended by a
/// newline when the last glyph is fitted.
fn terminal_progress() -> Arc<dyn Fn(usize, usize) + Send + Sync> {
    Arc::new(|done, total| {
        let step = (total / 200).max(1);
        if done % step == 0 || done == total {
            let end = if done == total { "\n" } else { "" };
            eprint!("\r{done}/{total} glyphs{end}");
        }
    })
}

/// Writes `files` (name, text) into `dir` through a temporary folder next to it; the
/// number of files written. On failure nothing new is left behind.
fn write_font_dir(dir: &Path, files: &[(String, String)]) -> Result<usize, ImportError> {
    let fail = |what: &str, path: &Path, e: std::io::Error| {
        ImportError::at(path, format!("cannot {what}: {e}"))
    };
    let parent = match dir.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    std::fs::create_dir_all(&parent).map_err(|e| fail("create the folder", &parent, e))?;
    // Created exclusively with an unpredictable name; removed on drop unless renamed away.
    let stem = dir
        .file_name()
        .map_or_else(|| "font".into(), |n| n.to_string_lossy().into_owned());
    let temp = tempfile::Builder::new()
        .prefix(&format!(".{stem}.import-"))
        .tempdir_in(&parent)
        .map_err(|e| fail("create a folder in", &parent, e))?;
    for (name, text) in files {
        let path = temp.path().join(name);
        // A master's files are in its folder (`bold/a.toml`).
        if let Some(folder) = path.parent() {
            std::fs::create_dir_all(folder).map_err(|e| fail("create the folder", folder, e))?;
        }
        std::fs::write(&path, text).map_err(|e| {
            let path = dir.join(name);
            fail("write", &path, e)
        })?;
    }
    // An absent or empty output folder is replaced whole (rename(2) replaces an empty
    // directory); a non-empty one (--force) gets the files moved in one by one.
    let empty = std::fs::read_dir(dir).map_or(true, |mut d| d.next().is_none());
    if empty {
        if dir.is_dir() {
            std::fs::remove_dir(dir).map_err(|e| fail("replace", dir, e))?;
        }
        std::fs::rename(temp.path(), dir).map_err(|e| fail("create", dir, e))?;
    } else {
        for (name, _) in files {
            let to = dir.join(name);
            if let Some(folder) = to.parent() {
                std::fs::create_dir_all(folder)
                    .map_err(|e| fail("create the folder", folder, e))?;
            }
            std::fs::rename(temp.path().join(name), &to).map_err(|e| fail("write", &to, e))?;
        }
    }
    Ok(files.len())
}

/// Reads and fits the inputs per the arguments (no file is written).
pub fn import_inputs(
    args: &ImportArgs,
    progress: Progress,
) -> Result<import::Imported, ImportError> {
    let kinds = args
        .inputs
        .iter()
        .map(|p| kind(p))
        .collect::<Result<Vec<_>, _>>()?;
    let fonts = kinds.iter().filter(|k| matches!(k, Kind::Font)).count();
    if kinds.iter().any(|k| matches!(k, Kind::Designspace)) {
        return Err(ImportError::plain(
            "import one designspace at a time, without other inputs",
        ));
    }
    if kinds.iter().any(|k| matches!(k, Kind::Ufo)) {
        return import_ufo(args, progress);
    }
    let mut opts = ImportOptions {
        tolerance: args.tolerance,
        family: args.family.clone(),
        units_per_em: args.units_per_em,
        face: args.face.unwrap_or(0),
        progress,
        ..ImportOptions::default()
    };
    if fonts > 0 {
        if args.inputs.len() > 1 {
            return Err(ImportError::plain(
                "import one font at a time, and fonts and SVG drawings separately",
            ));
        }
        refuse_svg_flags(args)?;
        opts.glyphs = args.glyphs.as_deref().map(parse_glyph_list).transpose()?;
        let path = &args.inputs[0];
        return import::import_font(path, &read_font(path)?, &opts);
    }
    if args.glyphs.is_some() {
        return Err(ImportError::plain(
            "--glyphs applies to fonts; SVG drawings become one glyph per file",
        ));
    }
    if args.face.is_some() {
        return Err(ImportError::plain(
            "--face applies to font collections, not to SVG drawings",
        ));
    }
    if let Some(map) = &args.codepoints {
        opts.codepoints = read_codepoints(map)?;
    }
    if let Some(hex) = &args.first_codepoint {
        opts.first_codepoint = Some(parse_hex_char(hex).ok_or_else(|| {
            ImportError::plain(format!(
                "--first-codepoint `{hex}` is not a hex code point such as E000"
            ))
        })?);
    }
    let files = args
        .inputs
        .iter()
        .map(|p| read(p).map(|d| (p.clone(), d)))
        .collect::<Result<Vec<_>, _>>()?;
    import::import_svgs(&files, &opts)
}

/// A UFO: alone, with only the flags that apply to it.
fn import_ufo(args: &ImportArgs, progress: Progress) -> Result<import::Imported, ImportError> {
    if args.inputs.len() > 1 {
        return Err(ImportError::plain(
            "import one UFO at a time, and UFOs, fonts and SVG drawings separately",
        ));
    }
    refuse_font_flags(args, "a UFO (it imports every glyph of its default layer)")?;
    import::import_ufo(&args.inputs[0], &ufo_options(args, progress))
}

/// The options of a UFO or designspace import (the caller checked the flags).
fn ufo_options(args: &ImportArgs, progress: Progress) -> ImportOptions {
    ImportOptions {
        tolerance: args.tolerance,
        family: args.family.clone(),
        progress,
        at: args.at.clone(),
        ..ImportOptions::default()
    }
}

/// Refuses `--at` for an input that is not a designspace (named in the error).
fn refuse_at(args: &ImportArgs) -> Result<(), ImportError> {
    if args.at.is_none() {
        return Ok(());
    }
    for path in &args.inputs {
        let what = match kind(path)? {
            Kind::Designspace => continue,
            Kind::Font => "a font",
            Kind::Ufo => "a UFO",
            Kind::Svg => "SVG drawings",
        };
        return Err(ImportError::at(
            path,
            format!(
                "--at applies to a designspace (it picks one location of its discrete axes), \
                 not to {what}"
            ),
        ));
    }
    Ok(())
}

/// Refuses the flags that do not apply to a designspace.
fn check_designspace_flags(args: &ImportArgs) -> Result<(), ImportError> {
    refuse_font_flags(
        args,
        "a designspace (it imports every glyph of each source's layer)",
    )
}

/// Refuses the flags of font and SVG imports for an input that takes none of them:
/// "`--flag` does not apply to {what}".
fn refuse_font_flags(args: &ImportArgs, what: &str) -> Result<(), ImportError> {
    for (given, flag) in [
        (args.glyphs.is_some(), "--glyphs"),
        (args.face.is_some(), "--face"),
        (args.codepoints.is_some(), "--codepoints"),
        (args.first_codepoint.is_some(), "--first-codepoint"),
        (args.units_per_em.is_some(), "--units-per-em"),
    ] {
        if given {
            return Err(ImportError::plain(format!(
                "{flag} does not apply to {what}"
            )));
        }
    }
    Ok(())
}

fn parse_hex_char(s: &str) -> Option<char> {
    let digits = s
        .strip_prefix("U+")
        .or_else(|| s.strip_prefix("0x"))
        .unwrap_or(s);
    u32::from_str_radix(digits, 16)
        .ok()
        .and_then(char::from_u32)
}

/// A code point map: `name = 0xE001` (an integer) or `name = "h"` (one character).
fn read_codepoints(path: &Path) -> Result<BTreeMap<String, char>, ImportError> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| ImportError::at(path, format!("cannot read: {e}")))?;
    let table: toml::Table = toml::from_str(&text).map_err(|e| {
        let (line, col) = crate::source::line_col(&text, e.span().map_or(0, |s| s.start));
        ImportError::plain(format!(
            "{}:{line}:{col}: invalid TOML: {}",
            path.display(),
            e.message()
        ))
    })?;
    let mut out = BTreeMap::new();
    for (name, value) in table {
        let c = match &value {
            toml::Value::Integer(n) => u32::try_from(*n).ok().and_then(char::from_u32),
            toml::Value::String(s) => {
                let mut it = s.chars();
                match (it.next(), it.next()) {
                    (Some(c), None) => Some(c),
                    _ => None,
                }
            }
            _ => None,
        };
        let c = c.ok_or_else(|| {
            ImportError::at(
                path,
                format!("`{name}`: expected a code point (0xE001) or one character (\"h\")"),
            )
        })?;
        out.insert(name, c);
    }
    Ok(out)
}

fn check_output_dir(dir: &Path, force: bool) -> Result<(), ImportError> {
    match std::fs::read_dir(dir) {
        Ok(mut entries) => {
            if entries.next().is_some() && !force {
                return Err(ImportError::at(
                    dir,
                    "the output directory is not empty; choose another or pass --force",
                ));
            }
            Ok(())
        }
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(()),
        Err(e) => Err(ImportError::at(
            dir,
            format!("cannot use as output directory: {e}"),
        )),
    }
}
