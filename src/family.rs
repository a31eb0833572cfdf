//! The IR of a font with masters: one compatible Bézier structure per glyph for every
//! master, what the variable-font backend reads.
//!
//! [`OutlinedFamily::default`] is an ordinary [`OutlinedFont`] (the default master), so
//! every static backend can read it unchanged. Each other master holds, per glyph in the
//! same order, a path with **the same elements** (same number of subpaths, and the same
//! kind of segment at each place: `LineTo` where the default has a `LineTo`, `CurveTo` where
//! it has a `CurveTo`), so that the masters differ only in coordinates. Components are
//! resolved into the paths, as in [`OutlinedFont`].
//!
//! The blend of the masters at a position ([`Designspace::weights`]) is the outline of the
//! variable font there; the compatible fitter guarantees that it lies within the tolerance
//! of the X-spline interpolated at the same position, at every position it checked.

use kurbo::BezPath;

use crate::designspace::{Designspace, Location, Region};
use crate::model::KernPair;
use crate::outline::OutlinedFont;

/// A font with masters, every glyph fitted compatibly.
#[derive(Clone, Debug)]
pub struct OutlinedFamily {
    /// Axes and named instances.
    pub designspace: Designspace,
    /// The default master (at every axis default), with the compatible paths.
    pub default: OutlinedFont,
    /// The other masters, in `font.toml` order.
    pub masters: Vec<OutlinedMaster>,
}

/// One non-default master's outlines.
#[derive(Clone, Debug)]
pub struct OutlinedMaster {
    /// Master name, e.g. `"Bold"`.
    pub name: String,
    /// Where it sits (user coordinates).
    pub location: Location,
    /// Its tent in the design space.
    pub region: Region,
    /// One per glyph of [`OutlinedFamily::default`], in the same order.
    pub glyphs: Vec<MasterGlyph>,
    /// This master's kerning; a pair it lacks has value 0 here.
    pub kerning: Vec<KernPair>,
}

/// A glyph in one non-default master.
#[derive(Clone, Debug)]
pub struct MasterGlyph {
    /// Horizontal advance, font units.
    pub advance: f64,
    /// Same elements as the default master's path for this glyph, other coordinates.
    pub path: BezPath,
}

impl OutlinedFamily {
    /// The blend weights at `location`: the default master first, then [`Self::masters`].
    pub fn weights(&self, location: &Location) -> Vec<f64> {
        let regions: Vec<Region> = self.masters.iter().map(|m| m.region).collect();
        self.designspace.weights(&regions, location)
    }
}
