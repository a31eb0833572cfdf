//! `xglyph build`: the main job. Load, outline, render every output in memory, write them
//! all atomically, print a summary.
//!
//! Nothing is written unless every output rendered: a source error or a render error
//! leaves OUT untouched (not even created).

use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use super::{CommandError, FontArgs};
use crate::cache::{FitCache, LoadOutcome, CACHE_FILE};
use crate::designspace::Location;
use crate::family::FamilySummary;
use crate::model::Family;
use crate::outline::{OutlineOptions, Progress};
use crate::pipeline::{self, BuildOptions, Loaded, OutputFile, PipelineError, Summary};
use crate::render::ProofOptions;
use crate::reuse::{Reuse, REUSE_FILE};
use crate::source::emit;
use crate::source::{Diagnostic, SourceMemo, MEMO_FILE};
use crate::terminal::{err, errln, out, outln};

#[derive(Debug, clap::Args)]
#[command(after_help = "\
Writes into OUT:
  <Family>-<Style>.svg   SVG 1.1 font (FontForge, svg2ttf)
  svg/<glyph>.svg        one standalone SVG per glyph
  sheet.png              glyph sheet with metric guides (sheet-1.png, sheet-2.png, ...
                         when the font has more than 512 glyphs)
  proof.png              text proof at several sizes
  <Family>-<Style>.ttf   TrueType font (quadratic outlines within the tolerance)
  <Family>-<Style>.otf   OpenType CFF font (the cubics)
  <Family>-<Style>.ufo/  UFO 3 source (fitted cubics, X-splines in the glyph lib)
  specimen.html          specimen page loading the OTF with @font-face
With masters, also: <Family>[<axes>].ttf and .woff2 (variable font), one
  <Family>-<Master>.ufo/ per master (compatible cubics) and <Family>.designspace

Examples:
  xglyph build                            # glyphs/ -> out/
  xglyph build my-font -o dist
  xglyph build --tolerance 0.1 --text 'Hamburgefonstiv'")]
pub struct BuildArgs {
    #[command(flatten)]
    pub font: FontArgs,
    /// Proof text (default: lines the font covers); `\n` in the text starts a new line.
    #[arg(long)]
    pub text: Option<String>,
    /// Write the TTF, OTF and WOFF2 with overlapping contours as drawn (by default they are
    /// unioned into one outline).
    #[arg(long)]
    pub keep_overlaps: bool,
}

/// Prints a diagnostic as `check` does (source line and caret), to stderr.
pub fn print_diagnostic(d: &Diagnostic) {
    err!("{}", crate::commands::check::text(d));
}

/// [`pipeline::load`], printing the warnings, or every diagnostic of a failed load.
pub fn load(font_dir: &Path, tolerance: Option<f64>) -> Result<Loaded, CommandError> {
    load_cached(font_dir, tolerance, None)
}

/// [`load`] with fits from `cache`; shows the fitting progress on stderr when it is a
/// terminal and fitting takes more than a second.
pub fn load_cached(
    font_dir: &Path,
    tolerance: Option<f64>,
    cache: Option<&FitCache>,
) -> Result<Loaded, CommandError> {
    outline_sources(pipeline::read_sources(font_dir, tolerance), cache)
}

/// The second half of [`load_cached`]: fits the loaded `sources` (printing their warnings),
/// or prints every diagnostic of a failed load.
fn outline_sources(
    sources: Result<pipeline::Sources, PipelineError>,
    cache: Option<&FitCache>,
) -> Result<Loaded, CommandError> {
    let progress = Progress::default();
    let opts = OutlineOptions {
        cache,
        progress: Some(&progress),
    };
    let loaded = sources.map(|sources| show_progress(&progress, || sources.outline(opts)));
    match loaded {
        Ok(loaded) => {
            loaded.warnings.iter().for_each(print_diagnostic);
            Ok(loaded)
        }
        Err(err) => {
            if let PipelineError::Sources { diagnostics, .. } = &err {
                diagnostics.iter().for_each(print_diagnostic);
            }
            Err(err.into())
        }
    }
}

/// Runs `work`, meanwhile printing `fitting glyphs: done/total` on stderr every 200 ms when
/// stderr is a terminal (after the first second, so quick runs print nothing); the line is
/// cleared at the end.
fn show_progress<T>(progress: &Progress, work: impl FnOnce() -> T) -> T {
    with_status_line(
        || {
            let total = progress.total.load(Ordering::Relaxed);
            let done = progress.done.load(Ordering::Relaxed);
            (total > 0).then(|| format!("fitting glyphs: {done}/{total}"))
        },
        work,
    )
}

/// Runs `work`, meanwhile printing `what` and the seconds spent on stderr when it is a
/// terminal, as `show_progress` does: rendering and writing a 20,000-glyph font take
/// seconds too.
pub fn show_phase<T>(what: &str, work: impl FnOnce() -> T) -> T {
    let start = Instant::now();
    with_status_line(
        || Some(format!("{what}: {} s", start.elapsed().as_secs())),
        work,
    )
}

/// Runs `work`; when stderr is a terminal, prints `status()` (if any) on one line every
/// 200 ms after the first second, and clears the line at the end.
fn with_status_line<T>(status: impl Fn() -> Option<String> + Sync, work: impl FnOnce() -> T) -> T {
    if !std::io::stderr().is_terminal() {
        return work();
    }
    let finished = AtomicBool::new(false);
    std::thread::scope(|scope| {
        let printer = scope.spawn(|| {
            let start = Instant::now();
            let mut shown = false;
            while !finished.load(Ordering::Relaxed) {
                std::thread::park_timeout(Duration::from_millis(200));
                if start.elapsed() <= Duration::from_secs(1) {
                    continue;
                }
                if let Some(line) = status() {
                    // Back to the line start, clear it, print.
                    eprint!("\r\x1b[K{line}");
                    shown = true;
                }
            }
            if shown {
                eprint!("\r\x1b[K");
            }
        });
        let result = work();
        finished.store(true, Ordering::Relaxed);
        printer.thread().unpark();
        result
    })
}

/// The summary printed after a build.
pub fn summary(summary: &Summary, family: &str, out: &Path, files: &[&Path]) -> String {
    // Three significant digits of the tolerance's order, at least three decimals.
    let digits = (2.0 - summary.tolerance.log10().floor()).clamp(3.0, 12.0) as usize;
    let worst = match &summary.worst {
        Some((name, error)) => format!("{error:.digits$} font units (glyph `{name}`)"),
        None => "none".into(),
    };
    // `files`: the outputs written, then those left in OUT (never at the top level).
    let top: Vec<String> = files
        .iter()
        .filter(|p| p.parent() == Some(Path::new("")))
        .map(|p| p.display().to_string())
        .collect();
    // Sheet pages as one item: `sheet-1.png … sheet-41.png (41 pages)`.
    let pages = top.iter().filter(|n| n.starts_with("sheet-")).count();
    let top: Vec<String> = if pages > 3 {
        let mut listed: Vec<String> = top
            .iter()
            .filter(|n| !n.starts_with("sheet-"))
            .cloned()
            .collect();
        let item = format!("sheet-1.png … sheet-{pages}.png ({pages} pages)");
        listed.insert(1.min(listed.len()), item);
        listed
    } else {
        top
    };
    let in_svg = files.iter().filter(|p| p.starts_with("svg")).count();
    // UFO folders as one item each: `XglyphSans-Regular.ufo/ (158 files)`.
    let mut ufos: Vec<(String, usize)> = Vec::new();
    for p in files {
        if let Some(first) = p.components().next() {
            let first = first.as_os_str().to_string_lossy();
            if first.ends_with(".ufo") && p.parent() != Some(Path::new("")) {
                match ufos.iter_mut().find(|(n, _)| *n == first) {
                    Some((_, count)) => *count += 1,
                    None => ufos.push((first.into_owned(), 1)),
                }
            }
        }
    }
    let ufos: String = ufos
        .iter()
        .map(|(n, count)| format!(", {n}/ ({count} files)"))
        .collect();
    format!(
        "built {family}: {} glyphs, {} contours, {} segments\n\
         worst error against the X-splines: {worst}, tolerance {}\n\
         wrote {} files to {}: {}{ufos}, svg/ ({in_svg} glyph SVGs)\n",
        summary.glyphs,
        summary.contours,
        summary.segments,
        summary.tolerance,
        files.len(),
        out.display(),
        top.join(", "),
    )
}

/// The line a build of a font with masters adds: the masters and the named instances with
/// their positions.
fn masters_line(family: &Family) -> String {
    let ds = &family.designspace;
    let at = |location: &Location| -> String {
        ds.axes
            .iter()
            .map(|a| format!("{} {}", a.tag, emit::number(location.get(a))))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let mut masters = vec![format!(
        "{} ({}, default)",
        family.default.info.style,
        at(&Location::default())
    )];
    masters.extend(family.masters.iter().map(|m| match m.sparse {
        true => {
            let drawn = m.drawn.iter().filter(|&&d| d).count();
            let glyphs = if drawn == 1 { "glyph" } else { "glyphs" };
            format!("{} ({}, sparse: {drawn} {glyphs})", m.name, at(&m.location))
        }
        false => format!("{} ({})", m.name, at(&m.location)),
    }));
    let instances: Vec<String> = ds
        .instances
        .iter()
        .map(|i| format!("{} ({})", i.name, at(&i.location)))
        .collect();
    format!(
        "masters: {}; named instances: {}",
        masters.join(", "),
        if instances.is_empty() {
            "none".to_string()
        } else {
            instances.join(", ")
        }
    )
}

/// The line on the variable font's compatible fit: its segments against static fits of the
/// most demanding master, and the worst error over every checked position.
fn variable_line(fs: &FamilySummary, family: &Family, tolerance: f64) -> String {
    let ratio = fs.compatible_segments as f64 / fs.static_segments.max(1) as f64;
    let worst = match &fs.worst {
        Some((glyph, at, e)) => {
            let where_: Vec<String> = family
                .designspace
                .axes
                .iter()
                .map(|a| format!("{} {}", a.tag, emit::computed_number(at.get(a))))
                .collect();
            format!(
                "; worst {} of {} in `{glyph}` at {}",
                emit::number((e * 1e4).round() / 1e4),
                emit::number(tolerance),
                where_.join(", ")
            )
        }
        None => String::new(),
    };
    format!(
        "variable font: {} segments in every master as fitted (before the splits at \
         extrema), static fits of the most demanding master {} ({ratio:.3}x); checked at {} \
         positions{worst}",
        fs.compatible_segments, fs.static_segments, fs.positions
    )
}

/// Most glyphs [`over_line`] names.
const OVER_NAMED: usize = 8;

/// The warning for glyphs of the variable font over the tolerance somewhere, if any.
fn over_line(fs: &FamilySummary, tolerance: f64) -> Option<String> {
    if fs.over.is_empty() {
        return None;
    }
    let mut named: Vec<String> = fs
        .over
        .iter()
        .take(OVER_NAMED)
        .map(|(g, e)| format!("`{g}` {}", emit::number((e * 1e4).round() / 1e4)))
        .collect();
    if fs.over.len() > OVER_NAMED {
        named.push(format!("and {} more", fs.over.len() - OVER_NAMED));
    }
    let count = fs.over.len();
    let glyphs = if count == 1 { "glyph is" } else { "glyphs are" };
    Some(format!(
        "warning: in the variable font, {count} {glyphs} over the tolerance {} at some checked \
         position: {}. One Bézier structure for every master does not always follow the \
         blended X-spline: where a point's `s` differs between masters, or a cusp forms \
         between them.",
        emit::number(tolerance),
        named.join(", ")
    ))
}

/// Adds `newer` to `files`, where a top-level name (file or folder) that `newer` has
/// replaces everything `files` has under it: the default master's UFO from the compatible
/// fit replaces the static fit's UFO folder as a whole.
fn replace_outputs(files: &mut Vec<OutputFile>, newer: &[OutputFile]) {
    let top = |p: &Path| p.components().next().map(|c| c.as_os_str().to_owned());
    let replaced: std::collections::HashSet<_> = newer.iter().map(|(p, _)| top(p)).collect();
    files.retain(|(p, _)| !replaced.contains(&top(p)));
    files.extend(newer.iter().cloned());
}

/// What a command keeps in OUT for the next run besides its outputs: the source memo
/// ([`MEMO_FILE`]) and the fit cache ([`CACHE_FILE`]), as loaded ([`load_stored`]).
pub struct Stores {
    /// The glyph files as the last run loaded them.
    pub memo: SourceMemo,
    /// Where the memo is read and written.
    pub memo_path: PathBuf,
    /// The fitted contours of the last run; this run's are added.
    pub cache: FitCache,
    /// Where the cache is read and written.
    pub cache_path: PathBuf,
}

impl Stores {
    /// How `svg` and `render` make and write a part of a build's outputs, as `build` does:
    /// `make` runs while the fit cache is encoded, the files `files` takes from what it
    /// made are written into `out` while the memo is encoded, and the records are left to
    /// [`Written::save_records`] after them (a failed run leaves OUT as it was). A font with
    /// masters keeps the fits not used ([`FitCache::keep_unused`]): they are `build`'s
    /// compatible fits and named instances.
    pub fn make_and_write<M: Send>(
        &self,
        loaded: &Loaded,
        out: &Path,
        make: impl FnOnce() -> M + Send,
        files: impl FnOnce(M) -> Result<Vec<OutputFile>, CommandError>,
    ) -> Result<Written, CommandError> {
        if loaded.family.is_variable() {
            self.cache.keep_unused();
        }
        let fits = (self.cache.hits(), self.cache.misses());
        let (made, cache_files) = rayon::join(make, || self.cache.files_to_save(&self.cache_path));
        let files = files(made)?;
        let paths = files.iter().map(|(path, _)| path.clone()).collect();
        let (written, memo_files) = show_phase(&format!("writing {} files", files.len()), || {
            rayon::join(
                || pipeline::write_output_files(out, files),
                || self.memo.files_to_save(&self.memo_path),
            )
        });
        written?;
        Ok(Written {
            paths,
            fits,
            cache_path: self.cache_path.clone(),
            records: memo_files.into_iter().chain(cache_files).collect(),
        })
    }
}

/// What [`Stores::make_and_write`] wrote, and the records still to write.
pub struct Written {
    /// The outputs written, relative to OUT, in order.
    pub paths: Vec<PathBuf>,
    fits: (usize, usize),
    cache_path: PathBuf,
    records: Vec<OutputFile>,
}

impl Written {
    /// Prints how many fits came from the cache ([`print_fits`]) and writes the records
    /// ([`save_records`]).
    pub fn save_records(self) {
        print_fits(&self.cache_path, self.fits);
        save_records(self.records);
    }
}

/// Loads the font of `args` as `build` and `svg` do: its sources through the source memo
/// in OUT while the fit cache in OUT and `beside` (`build`'s output record) are read on
/// any core (a CJK font's are 20,000 files and 60 MB, 100 MB and 20 MB); prints a note for
/// a memo or cache ignored (and why), then fits the default master through the cache
/// ([`load_cached`]: its warnings, or every diagnostic of a failed load). The messages keep
/// their order whatever the threads.
pub fn load_stored<R: Send>(
    args: &FontArgs,
    beside: impl FnOnce() -> R + Send,
) -> Result<(Loaded, Stores, R), CommandError> {
    let cache_path = args.out.join(CACHE_FILE);
    let memo_path = args.out.join(MEMO_FILE);
    let (((mut memo, memo_ignored), sources), ((cache, outcome), beside)) = rayon::join(
        || {
            let memo = SourceMemo::load(&memo_path);
            let sources = pipeline::read_sources_with(&args.font_dir, args.tolerance, &memo.0);
            (memo, sources)
        },
        || rayon::join(|| FitCache::load(&cache_path), beside),
    );
    memo.release_unused();
    if let Some(reason) = memo_ignored {
        errln!(
            "note: ignoring {}: {reason}; every glyph file is read anew",
            memo_path.display()
        );
    }
    if let LoadOutcome::Ignored(reason) = &outcome {
        errln!(
            "note: ignoring the fit cache {}: {reason}; every contour is refitted",
            cache_path.display()
        );
    }
    let loaded = outline_sources(sources, Some(&cache))?;
    let stores = Stores {
        memo,
        memo_path,
        cache,
        cache_path,
    };
    Ok((loaded, stores, beside))
}

/// Prints how many contours were fitted and how many fits came from the cache at
/// `cache_path`, when any did: `(hits, misses)`.
pub fn print_fits(cache_path: &Path, (hits, misses): (usize, usize)) {
    if hits > 0 {
        outln!(
            "refitted {misses} contours; {hits} fits from the cache {}",
            cache_path.display()
        );
    }
}

/// Writes the records for the next run (the output record's, the memo's and the fit
/// cache's files), once the outputs are written, in one transaction (one flush to disk);
/// a record that cannot be written only costs the next run time, so it is a warning.
pub fn save_records(files: impl IntoIterator<Item = (PathBuf, Vec<u8>)>) {
    let mut records = crate::write::OutputSet::new();
    for (path, bytes) in files {
        records.add(path, bytes);
    }
    if !records.is_empty() {
        if let Err(e) = records.commit() {
            errln!("warning: {e}");
        }
    }
}

/// A group of outputs, made.
type Made = Result<Vec<OutputFile>, PipelineError>;

/// The variable font's outputs and its summary, made (`None`: the font has no masters).
type MadeVariable = Result<Option<(Vec<OutputFile>, FamilySummary)>, PipelineError>;

/// The three groups of outputs of a build on every core (rayon), errors in this order:
/// the default master's ([`pipeline::static_outputs_with`]), the named instances' and the
/// variable font's.
///
/// The longest chains start first: the variable font (its compatible fit on every core,
/// then its WOFF2, Brotli on one core), then the named instances (fits, fonts, then their
/// proof); started last, either left one core working alone at the end of a bundled
/// build. Rayon runs the first closure here and lends the oldest waiting job first.
fn render_outputs(
    loaded: &Loaded,
    opts: &BuildOptions,
    reuse: &Reuse,
    cache: Option<&FitCache>,
) -> (Made, Made, MadeVariable) {
    let (variable, (instances, default)) = rayon::join(
        || pipeline::variable_outputs_with(loaded, cache, reuse),
        || {
            rayon::join(
                || pipeline::instance_outputs_reusing(loaded, opts, cache, reuse),
                || {
                    // A font with masters writes the UFOs of its compatible fit instead.
                    let ufo = !loaded.family.is_variable();
                    pipeline::static_outputs_with(&loaded.font, opts, reuse, ufo)
                },
            )
        },
    );
    (default, instances, variable)
}

/// Runs `xglyph build`.
pub fn run(args: BuildArgs) -> Result<ExitCode, CommandError> {
    // Ctrl-C leaves OUT as it was (a handler already set only means plain SIGINT).
    let _ = crate::write::exit_on_interrupt();
    let (mut loaded, stores, (reuse, ignored)) =
        load_stored(&args.font, || Reuse::load(&args.font.out))?;
    let Stores {
        memo,
        memo_path,
        cache,
        cache_path,
    } = stores;
    if let Some(reason) = ignored {
        errln!(
            "note: ignoring {}: {reason}; every output is made anew",
            args.font.out.join(REUSE_FILE).display()
        );
    }
    let opts = BuildOptions {
        proof: ProofOptions {
            text: args.text.map(|t| t.replace("\\n", "\n")),
            ..ProofOptions::default()
        },
        keep_overlaps: args.keep_overlaps,
        ..BuildOptions::default()
    };
    // A font without masters fits nothing more: its cache is encoded while the outputs are
    // made (a CJK font's: 0.7 s on one core) and its maps dropped then (hundreds of MB);
    // the file is still written after the outputs, so a failed build leaves OUT alone. Its
    // sources' glyphs are dropped now (70 MB for a CJK font): the outputs read the
    // outlined font only.
    let (cache, encode) = if loaded.family.is_variable() {
        (Some(cache), None)
    } else {
        loaded.family.default.glyphs = Vec::new();
        (None, Some(cache))
    };
    let encode = || {
        encode.map(|cache| {
            let stats = (cache.hits(), cache.misses());
            (cache.files_to_save(&cache_path), stats)
        })
    };
    let ((files, instance_files, variable), mut to_save) =
        show_phase("rendering the outputs", || {
            rayon::join(
                || render_outputs(&loaded, &opts, &reuse, cache.as_ref()),
                encode,
            )
        });
    let mut files = files?;
    files.extend(instance_files?);
    let variable = variable?;
    if let Some((var_files, _)) = &variable {
        replace_outputs(&mut files, var_files);
    }
    let info = &loaded.font.info;
    let family = format!("{} {}", info.family, info.style);
    // The outputs left in OUT unmade count as written.
    let kept = reuse.kept_paths();
    let paths: Vec<&Path> = files
        .iter()
        .map(|(p, _)| p.as_path())
        .chain(kept.iter().map(|p| p.as_path()))
        .collect();
    let report = summary(&Summary::new(&loaded.font), &family, &args.font.out, &paths);
    // The memo is encoded while the outputs are written (it depends on the sources only).
    let (written, memo_files) = show_phase(&format!("writing {} files", files.len()), || {
        rayon::join(
            || pipeline::write_output_files_with(&args.font.out, files, &reuse),
            || memo.files_to_save(&memo_path),
        )
    });
    written?;
    out!("{report}");
    if loaded.family.is_variable() {
        outln!("{}", masters_line(&loaded.family));
    }
    if let Some((_, fs)) = &variable {
        outln!(
            "{}",
            variable_line(fs, &loaded.family, loaded.font.tolerance)
        );
        if let Some(warning) = over_line(fs, loaded.font.tolerance) {
            errln!("{warning}");
        }
    }
    if let Some(cache) = &cache {
        to_save = Some((
            cache.files_to_save(&cache_path),
            (cache.hits(), cache.misses()),
        ));
    }
    let (cache_files, fits) = to_save.unwrap_or((Vec::new(), (0, 0)));
    print_fits(&cache_path, fits);
    if reuse.reused() > 0 {
        outln!(
            "took {} outputs unchanged from the last build (sheet pages, proof, WOFF2)",
            reuse.reused()
        );
    }
    if !kept.is_empty() {
        outln!(
            "left {} glyph files (SVG, UFO) of unchanged glyphs as the last build wrote them",
            kept.len()
        );
    }
    // The outputs are written: the records for the next build.
    let reuse_files = reuse.files_to_save().unwrap_or_else(|e| {
        errln!(
            "warning: cannot write {}: {}",
            args.font.out.join(REUSE_FILE).display(),
            crate::write::reason(&e)
        );
        Vec::new()
    });
    save_records(reuse_files.into_iter().chain(memo_files).chain(cache_files));
    // The command ends here and the process with it: the outlined font, the memo and the
    // records (a CJK font's millions of small allocations) are left to the exit instead of
    // being freed one by one (an edited CJK build: 2.95 s instead of 3.0 s).
    std::mem::forget((loaded, memo, reuse, cache, variable, kept));
    Ok(ExitCode::SUCCESS)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn summary(over: Vec<(String, f64)>) -> FamilySummary {
        FamilySummary {
            compatible_segments: 10,
            static_segments: 10,
            positions: 13,
            worst: None,
            over,
        }
    }

    #[test]
    fn glyphs_over_the_tolerance_are_named_in_a_warning() {
        assert_eq!(over_line(&summary(Vec::new()), 0.5), None);
        let over: Vec<(String, f64)> = (0..10).map(|k| (format!("g{k}"), 0.61234)).collect();
        let line = over_line(&summary(over), 0.5).expect("a warning");
        assert!(
            line.starts_with(
                "warning: in the variable font, 10 glyphs are over the tolerance 0.5 at some \
                 checked position: `g0` 0.6123, `g1` 0.6123, `g2` 0.6123, `g3` 0.6123, `g4` \
                 0.6123, `g5` 0.6123, `g6` 0.6123, `g7` 0.6123, and 2 more. One Bézier"
            ),
            "{line}"
        );
        let one = over_line(&summary(vec![("a".into(), 0.75)]), 0.5).expect("a warning");
        assert!(
            one.contains("1 glyph is over the tolerance 0.5 at some checked position: `a` 0.75."),
            "{one}"
        );
    }
}
