//! Per-glyph outlines: the model through [`crate::fit`] and [`crate::orient`].
//!
//! The result is what every output consumes: one [`kurbo::BezPath`] per glyph, in font
//! units (y up), contours oriented for the nonzero rule (outer counter-clockwise).

use kurbo::BezPath;

use crate::fit::fit_contour;
use crate::model::Font;
use crate::orient::orient_contours;
use crate::xspline::{XSpline, XSplineError};

/// One glyph ready for output.
#[derive(Clone, Debug)]
pub struct GlyphOutline {
    pub name: String,
    pub unicodes: Vec<char>,
    pub advance: f64,
    /// Closed subpaths (MoveTo … ClosePath), components resolved.
    pub path: BezPath,
    /// Largest measured distance between the path and the true X-splines (font units).
    pub max_error: f64,
}

/// Outlines of every glyph, in the model's glyph order.
#[derive(Clone, Debug)]
pub struct FontOutlines {
    pub glyphs: Vec<GlyphOutline>,
    /// The tolerance the outlines were fitted to (font units).
    pub tolerance: f64,
}

impl FontOutlines {
    pub fn glyph(&self, name: &str) -> Option<&GlyphOutline> {
        self.glyphs.iter().find(|g| g.name == name)
    }

    /// Largest measured fitting error over all glyphs.
    pub fn max_error(&self) -> f64 {
        self.glyphs.iter().map(|g| g.max_error).fold(0.0, f64::max)
    }
}

/// A contour that is not a valid X-spline (the source checks should have caught it).
#[derive(Clone, Debug, PartialEq)]
pub struct OutlineError {
    pub glyph: String,
    pub contour: usize,
    pub error: XSplineError,
}

impl std::fmt::Display for OutlineError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "glyph '{}', contour {}: {}",
            self.glyph, self.contour, self.error
        )
    }
}

impl std::error::Error for OutlineError {}

/// Fits every glyph of `font` within `tolerance` font units.
pub fn outline_font(font: &Font, tolerance: f64) -> Result<FontOutlines, OutlineError> {
    let glyphs = font
        .glyphs
        .iter()
        .map(|glyph| {
            let mut fitted = Vec::new();
            let mut max_error: f64 = 0.0;
            for (index, contour) in font.resolved_contours(glyph).into_iter().enumerate() {
                let spline = XSpline::new(contour.points).map_err(|error| OutlineError {
                    glyph: glyph.name.clone(),
                    contour: index,
                    error,
                })?;
                let fit = fit_contour(&spline, tolerance);
                max_error = max_error.max(fit.max_error);
                fitted.push(fit.path);
            }
            Ok(GlyphOutline {
                name: glyph.name.clone(),
                unicodes: glyph.unicodes.clone(),
                advance: glyph.advance,
                path: orient_contours(fitted),
                max_error,
            })
        })
        .collect::<Result<_, _>>()?;
    Ok(FontOutlines { glyphs, tolerance })
}
