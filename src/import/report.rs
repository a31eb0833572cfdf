//! The import report: per glyph the original and X-spline point counts and the measured
//! error, and one summary line.

use std::fmt::Write;

use super::{BUILD_SHARE, IMPORT_SHARE};

/// One glyph's numbers.
#[derive(Clone, Debug, PartialEq)]
pub struct GlyphReport {
    /// Glyph name.
    pub name: String,
    /// On-curve plus off-curve points of the original (implied TrueType points not counted).
    pub original_points: usize,
    /// Control points of the imported X-splines.
    pub xspline_points: usize,
    /// Largest two-sided distance between the X-splines and the original (font units),
    /// measured on the written (rounded) points.
    pub max_error: f64,
    /// Original contours that enclose nothing and were left out.
    pub dropped_contours: usize,
}

/// The whole import.
#[derive(Clone, Debug, PartialEq)]
pub struct Report {
    /// One row per glyph, in the model's order.
    pub rows: Vec<GlyphReport>,
    /// The import tolerance `T` (font units).
    pub tolerance: f64,
    /// Remarks (characters the font lacks, ...), printed after the table.
    pub notes: Vec<String>,
}

impl Report {
    /// Original points over all glyphs.
    pub fn original_points(&self) -> usize {
        self.rows.iter().map(|r| r.original_points).sum()
    }

    /// X-spline control points over all glyphs.
    pub fn xspline_points(&self) -> usize {
        self.rows.iter().map(|r| r.xspline_points).sum()
    }

    /// Largest error over all glyphs (font units).
    pub fn max_error(&self) -> f64 {
        self.rows.iter().map(|r| r.max_error).fold(0.0, f64::max)
    }

    /// Glyphs whose measured error exceeds the import share of the tolerance.
    pub fn over_budget(&self) -> Vec<&GlyphReport> {
        let bound = IMPORT_SHARE * self.tolerance;
        self.rows.iter().filter(|r| r.max_error > bound).collect()
    }

    /// The printed report: a table, notes, and the summary line.
    pub fn render(&self) -> String {
        let width = self
            .rows
            .iter()
            .map(|r| r.name.len())
            .max()
            .unwrap_or(5)
            .max(5);
        let mut out = String::new();
        let _ = writeln!(
            out,
            "{:<width$}  {:>8}  {:>8}  {:>9}",
            "glyph", "original", "xspline", "max error"
        );
        for r in &self.rows {
            let _ = write!(
                out,
                "{:<width$}  {:>8}  {:>8}  {:>9.3}",
                r.name, r.original_points, r.xspline_points, r.max_error
            );
            if r.dropped_contours > 0 {
                let _ = write!(out, "  ({} empty contour(s) left out)", r.dropped_contours);
            }
            out.push('\n');
        }
        for note in &self.notes {
            let _ = writeln!(out, "note: {note}");
        }
        for r in self.over_budget() {
            let _ = writeln!(
                out,
                "warning: glyph `{}` is {:.3} units from the original, above {:.3}",
                r.name,
                r.max_error,
                IMPORT_SHARE * self.tolerance
            );
        }
        let _ = writeln!(out, "{}", self.summary());
        out
    }

    /// `total: G glyphs, O original points, X X-spline points, max error E (tolerance T,
    /// build tolerance B)`.
    pub fn summary(&self) -> String {
        format!(
            "total: {} glyphs, {} original points, {} X-spline points, max error {:.3} \
             (tolerance {}, build tolerance {})",
            self.rows.len(),
            self.original_points(),
            self.xspline_points(),
            self.max_error(),
            crate::source::emit::number(self.tolerance),
            crate::source::emit::number(BUILD_SHARE * self.tolerance),
        )
    }
}
