//! Diagnostics: one problem in the sources, with its file, 1-based line and column, and the
//! source line it points into (taken from the text that was loaded, never re-read).
//!
//! A file reports at most [`MAX_PER_FILE`] diagnostics; the rest are counted and summed
//! up in one "… and N more" line, so that a file with a million bad points costs a million
//! counter increments, not a million messages. Lines and columns come from a line index
//! built once per file (binary search per diagnostic), not by scanning from the start.

use std::collections::HashMap;
use std::fmt;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// Diagnostics shown per file; further ones are only counted.
pub const MAX_PER_FILE: usize = 100;

/// Source lines longer than this many characters are shown as a window around the column.
const SNIPPET_CHARS: usize = 120;

/// How serious a diagnostic is. Errors stop every command; warnings are printed only.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Severity {
    /// The sources cannot be built.
    Error,
    /// Built anyway, but worth a look.
    Warning,
}

impl Severity {
    /// `"error"` or `"warning"`, as printed.
    pub fn as_str(self) -> &'static str {
        match self {
            Severity::Error => "error",
            Severity::Warning => "warning",
        }
    }
}

/// One problem found in the sources.
///
/// `line` and `col` are 1-based (`col` counts characters); both are 0 when the problem
/// belongs to a whole file or folder rather than a place in it (a missing `font.toml`).
#[derive(Clone, Debug, PartialEq)]
pub struct Diagnostic {
    /// The source file.
    pub path: PathBuf,
    /// Line, from 1.
    pub line: usize,
    /// Column in characters, from 1.
    pub col: usize,
    /// Error or warning.
    pub severity: Severity,
    /// What is wrong, and what would be right.
    pub message: String,
    /// The source line at `line`, for showing with a caret (`None` without a position).
    pub snippet: Option<Snippet>,
    /// How many problems this diagnostic stands for: 1, or for an "… and N more" line the
    /// number of problems left out (see [`MAX_PER_FILE`]).
    pub count: usize,
}

/// The text of the line a diagnostic points into, with the caret's column in that text.
#[derive(Clone, Debug, PartialEq)]
pub struct Snippet {
    /// The line (a window of it, marked with `…`, when it is very long).
    pub text: String,
    /// 1-based character column of the caret within `text`.
    pub caret: usize,
}

impl Diagnostic {
    /// A diagnostic about a whole file or folder (no line or column).
    pub fn whole(path: &Path, severity: Severity, message: impl Into<String>) -> Self {
        Diagnostic {
            path: path.to_path_buf(),
            line: 0,
            col: 0,
            severity,
            message: message.into(),
            snippet: None,
            count: 1,
        }
    }

    /// Whether the diagnostic points at a place in its file.
    pub fn has_position(&self) -> bool {
        self.line > 0
    }
}

impl fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.path.display())?;
        if self.has_position() {
            write!(f, ":{}:{}", self.line, self.col)?;
        }
        write!(f, ": {}: {}", self.severity.as_str(), self.message)
    }
}

/// 1-based line and column (in characters) of a byte offset.
///
/// Scans `text` up to `offset`; for many offsets into one text use a `LineIndex`.
pub fn line_col(text: &str, offset: usize) -> (usize, usize) {
    LineIndex::new(text).line_col(text, offset)
}

/// Where each line of a text starts, for turning byte offsets into lines and columns.
#[derive(Clone, Debug)]
pub(super) struct LineIndex {
    starts: Vec<usize>,
}

impl LineIndex {
    pub fn new(text: &str) -> Self {
        let mut starts = vec![0];
        starts.extend(text.match_indices('\n').map(|(i, _)| i + 1));
        LineIndex { starts }
    }

    /// 1-based line and character column of `offset` (clamped to the text, moved back to
    /// a character boundary).
    pub fn line_col(&self, text: &str, offset: usize) -> (usize, usize) {
        let mut off = offset.min(text.len());
        while !text.is_char_boundary(off) {
            off -= 1;
        }
        let line = self.starts.partition_point(|&s| s <= off);
        let start = self.starts[line - 1];
        (line, text[start..off].chars().count() + 1)
    }

    /// The text of 1-based `line`, without its line end.
    fn line<'t>(&self, text: &'t str, line: usize) -> &'t str {
        let start = self.starts[line - 1];
        let end = self.starts.get(line).map_or(text.len(), |&e| e - 1);
        text[start..end].trim_end_matches('\r')
    }

    /// The snippet for `line` with the caret at character column `col`.
    fn snippet(&self, text: &str, line: usize, col: usize) -> Snippet {
        let full = self.line(text, line);
        let chars = full.chars().count();
        if chars <= SNIPPET_CHARS {
            return Snippet {
                text: full.to_string(),
                caret: col,
            };
        }
        let half = SNIPPET_CHARS / 2;
        let first = col.saturating_sub(half + 1).min(chars - SNIPPET_CHARS);
        let mut window: String = full.chars().skip(first).take(SNIPPET_CHARS).collect();
        let mut caret = col - first;
        if first > 0 {
            window.insert(0, '…');
            caret += 1;
        }
        if first + SNIPPET_CHARS < chars {
            window.push('…');
        }
        Snippet {
            text: window,
            caret,
        }
    }
}

/// The diagnostics of one load: at most [`MAX_PER_FILE`] kept per file, the rest counted.
#[derive(Debug, Default)]
pub(super) struct Diagnostics {
    kept: Vec<Diagnostic>,
    per_file: HashMap<PathBuf, usize>,
    left_out: HashMap<(PathBuf, Severity), usize>,
}

impl Diagnostics {
    /// Whether another diagnostic for `path` would be kept; when not, counts it as left out.
    fn admit(&mut self, path: &Path, severity: Severity) -> bool {
        let shown = self.per_file.entry(path.to_path_buf()).or_default();
        if *shown < MAX_PER_FILE {
            *shown += 1;
            return true;
        }
        *self
            .left_out
            .entry((path.to_path_buf(), severity))
            .or_default() += 1;
        false
    }

    pub fn push(&mut self, d: Diagnostic) {
        if self.admit(&d.path, d.severity) {
            self.kept.push(d);
        }
    }

    /// Adds the diagnostics of `other`, gathered for other files than this one's (the
    /// per-file limit is not applied again).
    pub fn absorb(&mut self, other: Diagnostics) {
        self.kept.extend(other.kept);
        for (path, n) in other.per_file {
            *self.per_file.entry(path).or_default() += n;
        }
        for (key, n) in other.left_out {
            *self.left_out.entry(key).or_default() += n;
        }
    }

    /// Whether nothing was reported.
    pub fn is_empty(&self) -> bool {
        self.kept.is_empty() && self.left_out.is_empty()
    }

    pub fn has_errors(&self) -> bool {
        self.kept.iter().any(|d| d.severity == Severity::Error)
            || self.left_out.keys().any(|(_, s)| *s == Severity::Error)
    }

    /// Every diagnostic, sorted by `rank` of its path, then by position; after each file's
    /// own, one "… and N more" line per severity that had some left out.
    pub fn into_sorted(mut self, rank: impl Fn(&Path) -> usize) -> Vec<Diagnostic> {
        let mut more: Vec<Diagnostic> = self
            .left_out
            .into_iter()
            .map(|((path, severity), n)| {
                let noun = match (severity, n) {
                    (Severity::Error, 1) => "error",
                    (Severity::Error, _) => "errors",
                    (Severity::Warning, 1) => "warning",
                    (Severity::Warning, _) => "warnings",
                };
                let message = format!(
                    "… and {n} more {noun} in this file (only the first {MAX_PER_FILE} \
                     problems of a file are listed)"
                );
                Diagnostic {
                    count: n,
                    ..Diagnostic::whole(&path, severity, message)
                }
            })
            .collect();
        more.sort_by_key(|d| (rank(&d.path), d.severity));
        self.kept.sort_by_key(|d| (rank(&d.path), d.line, d.col));
        // Each file's "… and N more" lines go after its own diagnostics.
        let mut out = Vec::with_capacity(self.kept.len() + more.len());
        let mut more = more.into_iter().peekable();
        for d in self.kept {
            while let Some(m) = more.next_if(|m| rank(&m.path) < rank(&d.path)) {
                out.push(m);
            }
            out.push(d);
        }
        out.extend(more);
        out
    }

    /// Every diagnostic in the order found (for loading one file).
    pub fn into_vec(self) -> Vec<Diagnostic> {
        self.into_sorted(|_| 0)
    }
}

/// Diagnostics being gathered for one file: byte offsets become line and column.
pub(super) struct Ctx<'a> {
    pub path: &'a Path,
    text: Text<'a>,
    pub out: &'a mut Diagnostics,
    /// Built on the first diagnostic.
    lines: Option<LineIndex>,
}

/// The text of a [`Ctx`]'s file.
#[derive(Clone, Copy)]
enum Text<'a> {
    Read(&'a str),
    /// Not read yet: read on first use (a file the source memo gave by its stamp, whose
    /// text only a diagnostic needs).
    Later(&'a OnceLock<String>),
}

impl<'a> Ctx<'a> {
    pub fn new(path: &'a Path, text: &'a str, out: &'a mut Diagnostics) -> Self {
        Ctx {
            path,
            text: Text::Read(text),
            out,
            lines: None,
        }
    }

    /// A context whose text `text` is read from `path` when first needed. A file that
    /// cannot be read then has no text (its messages point at line 1).
    pub fn later(path: &'a Path, text: &'a OnceLock<String>, out: &'a mut Diagnostics) -> Self {
        Ctx {
            path,
            text: Text::Later(text),
            out,
            lines: None,
        }
    }

    /// The file's text.
    pub fn text(&self) -> &'a str {
        match self.text {
            Text::Read(text) => text,
            Text::Later(cell) => cell.get_or_init(|| {
                std::fs::read(self.path)
                    .map(|b| String::from_utf8_lossy(&b).into_owned())
                    .unwrap_or_default()
            }),
        }
    }

    /// 1-based line and column of a byte offset in this file.
    pub fn line_col(&mut self, offset: usize) -> (usize, usize) {
        let text = self.text();
        self.lines
            .get_or_insert_with(|| LineIndex::new(text))
            .line_col(text, offset)
    }

    pub fn at(&mut self, offset: usize, severity: Severity, message: impl Into<String>) {
        if !self.out.admit(self.path, severity) {
            return;
        }
        let (line, col) = self.line_col(offset);
        let text = self.text();
        let snippet = self.lines.as_ref().map(|l| l.snippet(text, line, col));
        self.out.kept.push(Diagnostic {
            path: self.path.to_path_buf(),
            line,
            col,
            severity,
            message: message.into(),
            snippet,
            count: 1,
        });
    }

    pub fn err(&mut self, offset: usize, message: impl Into<String>) {
        self.at(offset, Severity::Error, message);
    }

    pub fn warn(&mut self, offset: usize, message: impl Into<String>) {
        self.at(offset, Severity::Warning, message);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_and_columns() {
        let text = "ab\ncdé\n\nx";
        let index = LineIndex::new(text);
        assert_eq!(index.line_col(text, 0), (1, 1));
        assert_eq!(index.line_col(text, 2), (1, 3));
        assert_eq!(index.line_col(text, 3), (2, 1));
        // Inside `é` (two bytes): moved back to its start.
        assert_eq!(index.line_col(text, 6), (2, 3));
        assert_eq!(index.line_col(text, 8), (3, 1));
        assert_eq!(index.line_col(text, 9), (4, 1));
        assert_eq!(index.line_col(text, 99), (4, 2));
        assert_eq!(line_col(text, 5), (2, 3));
        assert_eq!(index.line(text, 2), "cdé");
        assert_eq!(index.line(text, 3), "");
    }

    #[test]
    fn long_lines_are_windowed_around_the_caret() {
        let text = format!("{}X{}", "a".repeat(500), "b".repeat(500));
        let index = LineIndex::new(&text);
        let s = index.snippet(&text, 1, 501);
        assert_eq!(s.text.chars().count(), SNIPPET_CHARS + 2);
        assert_eq!(s.text.chars().nth(s.caret - 1), Some('X'));
        assert!(s.text.starts_with('…') && s.text.ends_with('…'));
        let start = index.snippet(&text, 1, 1);
        assert_eq!((start.caret, start.text.chars().next()), (1, Some('a')));
    }

    #[test]
    fn a_file_keeps_the_first_hundred() {
        let mut out = Diagnostics::default();
        let text = "x\n".repeat(300);
        let mut ctx = Ctx::new(Path::new("a.toml"), &text, &mut out);
        for i in 0..250 {
            ctx.err(2 * i, format!("bad {i}"));
        }
        ctx.warn(0, "w");
        let all = out.into_vec();
        assert_eq!(all.len(), MAX_PER_FILE + 2);
        assert_eq!(
            all[MAX_PER_FILE - 1].to_string(),
            "a.toml:100:1: error: bad 99"
        );
        let more: Vec<(String, usize)> = all[MAX_PER_FILE..]
            .iter()
            .map(|d| (d.to_string(), d.count))
            .collect();
        assert_eq!(
            more,
            [
                (
                    "a.toml: error: … and 150 more errors in this file (only the first 100 \
                     problems of a file are listed)"
                        .to_string(),
                    150
                ),
                (
                    "a.toml: warning: … and 1 more warning in this file (only the first 100 \
                     problems of a file are listed)"
                        .to_string(),
                    1
                )
            ]
        );
    }
}
