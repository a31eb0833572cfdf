//! Diagnostics: one problem in the sources, with its file, 1-based line and column.

use std::fmt;
use std::path::{Path, PathBuf};

/// How serious a diagnostic is. Errors stop every command; warnings are printed only.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Severity {
    Error,
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
    pub path: PathBuf,
    pub line: usize,
    pub col: usize,
    pub severity: Severity,
    pub message: String,
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
pub fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let mut off = offset.min(text.len());
    while !text.is_char_boundary(off) {
        off -= 1;
    }
    let before = &text[..off];
    let line = before.matches('\n').count() + 1;
    let start = before.rfind('\n').map_or(0, |i| i + 1);
    (line, before[start..].chars().count() + 1)
}

/// Diagnostics being gathered for one file: byte offsets become line and column.
pub(super) struct Ctx<'a> {
    pub path: &'a Path,
    pub text: &'a str,
    pub out: &'a mut Vec<Diagnostic>,
}

impl Ctx<'_> {
    pub fn at(&mut self, offset: usize, severity: Severity, message: impl Into<String>) {
        let (line, col) = line_col(self.text, offset);
        self.out.push(Diagnostic {
            path: self.path.to_path_buf(),
            line,
            col,
            severity,
            message: message.into(),
        });
    }

    pub fn err(&mut self, offset: usize, message: impl Into<String>) {
        self.at(offset, Severity::Error, message);
    }

    pub fn warn(&mut self, offset: usize, message: impl Into<String>) {
        self.at(offset, Severity::Warning, message);
    }
}
