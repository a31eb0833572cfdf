//! `xglyph check`: load and validate a font directory, printing every diagnostic.
//!
//! Exit code 1 when there is at least one error, 0 otherwise (warnings included), in both
//! output formats. A file lists at most [`crate::source::MAX_PER_FILE`] problems, then
//! "… and N more"; the counts in the summary include the ones left out.

use std::path::PathBuf;
use std::process::ExitCode;

use serde_json::json;

use super::CommandError;
use crate::source::{load_font, Diagnostic, Severity};
use crate::terminal::out;

/// How `check` prints its diagnostics.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum Format {
    /// `path:line:col: severity: message`, the source line with a caret, and a summary.
    #[default]
    Text,
    /// One JSON object: `diagnostics` (path, line, column, severity, message) and counts.
    Json,
}

#[derive(Debug, clap::Args)]
pub struct CheckArgs {
    /// Font directory to check.
    #[arg(default_value = "glyphs")]
    pub font_dir: PathBuf,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Text)]
    pub format: Format,
}

pub fn run(args: CheckArgs) -> Result<ExitCode, CommandError> {
    let diags = match load_font(&args.font_dir) {
        Ok((font, mut warnings)) => {
            // features.fea, once the sources load (it needs their glyph names).
            warnings.extend(crate::pipeline::feature_diagnostics(&font));
            warnings
        }
        Err(diags) => diags,
    };
    let (errors, warnings) = counts(&diags);
    match args.format {
        Format::Text => {
            for d in &diags {
                out!("{}", text(d));
            }
            println!("{}", summary(errors, warnings));
        }
        Format::Json => println!("{}", self::json(&diags, errors, warnings)),
    }
    Ok(if errors > 0 {
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    })
}

/// `(errors, warnings)`, counting what the "… and N more" lines stand for.
pub fn counts(diags: &[Diagnostic]) -> (usize, usize) {
    diags.iter().fold((0, 0), |(e, w), d| match d.severity {
        Severity::Error => (e + d.count, w),
        Severity::Warning => (e, w + d.count),
    })
}

/// One diagnostic as text: its line, then the source line (as it was loaded) with a caret
/// under the column.
pub fn text(d: &Diagnostic) -> String {
    let mut out = format!("{d}\n");
    if let Some(snippet) = &d.snippet {
        // Tabs stay tabs so that the caret lines up with the character above it.
        let indent: String = snippet
            .text
            .chars()
            .take(snippet.caret - 1)
            .map(|c| if c == '\t' { '\t' } else { ' ' })
            .collect();
        out.push_str(&format!("  | {}\n  | {indent}^\n", snippet.text));
    }
    out
}

/// Every diagnostic and the counts as one JSON document (pretty-printed, keys sorted).
///
/// `line` and `column` are 1-based, or `null` for a diagnostic about a whole file.
pub fn json(diags: &[Diagnostic], errors: usize, warnings: usize) -> String {
    let items: Vec<_> = diags
        .iter()
        .map(|d| {
            let (line, column) = if d.has_position() {
                (json!(d.line), json!(d.col))
            } else {
                (json!(null), json!(null))
            };
            json!({
                "path": d.path.to_string_lossy(),
                "line": line,
                "column": column,
                "severity": d.severity.as_str(),
                "message": d.message,
            })
        })
        .collect();
    let doc = json!({ "diagnostics": items, "errors": errors, "warnings": warnings });
    serde_json::to_string_pretty(&doc).unwrap_or_default()
}

/// `1 error, 2 warnings`: the counts with singular or plural nouns.
pub fn summary(errors: usize, warnings: usize) -> String {
    let plural = |n: usize, word: &str| {
        if n == 1 {
            format!("{n} {word}")
        } else {
            format!("{n} {word}s")
        }
    };
    format!(
        "{}, {}",
        plural(errors, "error"),
        plural(warnings, "warning")
    )
}
