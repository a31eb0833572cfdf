//! Instances: a position in the design space -> a static [`Font`], the masters blended
//! with [`Designspace::weights`](crate::designspace::Designspace::weights).
//!
//! Every number that may differ between masters is blended the same way, as the weighted
//! sum over the masters (default first): control points' `x`, `y` and `s`, advances,
//! component offsets and kerning values (a pair a master lacks counts as 0 there). At a
//! master's location its weight is exactly 1 and the others exactly 0, so the instance is
//! that master bit for bit. With masters on the axes the weights are a convex combination,
//! so `s` stays in [-1, 1]; sparse corner masters can weigh some masters negatively, and a
//! blended `s` is then kept inside [-1, 1] ([`ControlPoint::blended`]). A point sharp in
//! every master stays sharp.

use std::collections::{HashMap, HashSet};
use std::fmt;

use crate::designspace::{Designspace, Location, RegionError};
use crate::model::{Anchor, Component, Contour, Family, Font, Glyph, GlyphModels, KernPair};
use crate::source::emit;
use crate::xspline::{ControlPoint, XSplineError};

/// Why an instance could not be built.
#[derive(Clone, Debug, PartialEq)]
pub enum InstanceError {
    /// The masters' locations do not form a valid set (the loader refuses these).
    Regions(RegionError),
    /// A blended contour is not a valid X-spline (e.g. two neighbouring points meet at this
    /// position although they differ in every master).
    Contour {
        /// The glyph.
        glyph: String,
        /// Index of the contour in the glyph.
        contour: usize,
        /// What is wrong with it.
        error: XSplineError,
    },
}

impl fmt::Display for InstanceError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            InstanceError::Regions(e) => write!(f, "the masters cannot be blended: {e:?}"),
            InstanceError::Contour {
                glyph,
                contour,
                error,
            } => write!(
                f,
                "glyph `{glyph}`, contour {contour}: the blended contour is not a valid \
                 X-spline here: {error}"
            ),
        }
    }
}

impl std::error::Error for InstanceError {}

/// Applies the rules' substitutions to a static font as fontmake's instancer does: each
/// glyph and its alternate trade drawings (outlines, components, advance, anchors), and
/// every component and kerning pair that names one names the other, so that the code
/// point shows the alternate and everything else looks as before. A pair given both ways
/// is swapped once.
fn swap_glyphs(font: &mut Font, substitutions: &[(String, String)]) {
    let mut done: HashSet<(&str, &str)> = HashSet::new();
    for (a, b) in substitutions {
        if !done.insert((b.as_str(), a.as_str())) || !done.insert((a.as_str(), b.as_str())) {
            continue;
        }
        let find = |n: &str| font.glyphs.iter().position(|g| g.name == n);
        let (Some(i), Some(j)) = (find(a), find(b)) else {
            continue;
        };
        let (lo, hi) = (i.min(j), i.max(j));
        let (left, right) = font.glyphs.split_at_mut(hi);
        let (x, y) = (&mut left[lo], &mut right[0]);
        std::mem::swap(&mut x.contours, &mut y.contours);
        std::mem::swap(&mut x.components, &mut y.components);
        std::mem::swap(&mut x.advance, &mut y.advance);
        std::mem::swap(&mut x.anchors, &mut y.anchors);
        std::mem::swap(&mut x.outline_mark, &mut y.outline_mark);
        let other = |n: &mut String| {
            if n == a {
                n.clone_from(b);
            } else if n == b {
                n.clone_from(a);
            }
        };
        for g in &mut font.glyphs {
            for c in &mut g.components {
                other(&mut c.base);
            }
        }
        for k in &mut font.kerning {
            other(&mut k.left);
            other(&mut k.right);
        }
    }
}

/// `Σ weights[i] × values[i]`, in master order (default first).
fn blend(weights: &[f64], values: impl IntoIterator<Item = f64>) -> f64 {
    let mut terms = weights.iter().zip(values).map(|(w, v)| w * v);
    let first = terms.next().unwrap_or(0.0);
    terms.fold(first, |acc, t| acc + t)
}

impl Family {
    /// The static font at `location` (user coordinates; an axis left out is at its
    /// default, a value beyond the axis range is clamped). The info and glyph set are the
    /// default master's; the style name is left as it is. Each glyph blends from the
    /// masters that draw it ([`GlyphModels`]), the kerning from the full masters.
    pub fn instance_at(&self, location: &Location) -> Result<Font, InstanceError> {
        let models = self.glyph_models().map_err(InstanceError::Regions)?;
        let n = self.masters.len();
        let per_set: Vec<Vec<f64>> = models
            .sets
            .iter()
            .map(|(set, model)| GlyphModels::spread(&self.designspace, n, (set, model), location))
            .collect();
        let glyphs = (0..self.default.glyphs.len())
            .map(|gi| self.blend_glyph(gi, &per_set[models.own_of_glyph[gi]]))
            .collect::<Result<Vec<_>, _>>()?;
        let (set, model) = &models.kerning;
        let kerning_weights = GlyphModels::spread(&self.designspace, n, (set, model), location);
        let mut font = Font {
            info: self.default.info.clone(),
            glyphs,
            kerning: self.kerning_at(&kerning_weights),
            features: self.default.features.clone(),
        };
        let substitutions = self
            .designspace
            .substitutions_at(location, font.glyphs.iter().map(|g| g.name.as_str()));
        swap_glyphs(&mut font, &substitutions);
        Ok(font)
    }

    /// Fills in what sparse masters leave out: each glyph a sparse master does not draw
    /// becomes the blend of the masters that draw it, at the sparse master's location, and
    /// a sparse master's kerning, unless it has its own, the kerned masters' blend there.
    /// So every master holds every glyph, and a blend over all masters gives, along one
    /// axis, exactly what the glyphs' own models give. The loader calls this once.
    pub fn fill_sparse(&mut self) -> Result<(), InstanceError> {
        if !self.has_sparse() {
            return Ok(());
        }
        let models = self.glyph_models().map_err(InstanceError::Regions)?;
        let n = self.masters.len();
        for m in 0..n {
            if !self.masters[m].sparse {
                continue;
            }
            let location = self.masters[m].location.clone();
            for gi in 0..self.default.glyphs.len() {
                if self.masters[m].drawn[gi] {
                    continue;
                }
                let w = GlyphModels::spread(&self.designspace, n, models.own(gi), &location);
                self.masters[m].glyphs[gi] = self.blend_glyph(gi, &w)?;
            }
            if !self.masters[m].kerned {
                let (set, model) = &models.kerning;
                let w = GlyphModels::spread(&self.designspace, n, (set, model), &location);
                self.masters[m].kerning = self.kerning_at(&w);
            }
        }
        Ok(())
    }

    /// Glyph `gi` blended with `w` (default first, then [`Family::masters`]).
    fn blend_glyph(&self, gi: usize, w: &[f64]) -> Result<Glyph, InstanceError> {
        let d = &self.default.glyphs[gi];
        let masters: Vec<&Glyph> = std::iter::once(d)
            .chain(self.masters.iter().map(|m| &m.glyphs[gi]))
            .collect();
        let mut contours = Vec::with_capacity(d.contours.len());
        for (ci, contour) in d.contours.iter().enumerate() {
            let points = (0..contour.points().len())
                .map(|pi| {
                    let at = |f: fn(&ControlPoint) -> f64| {
                        blend(w, masters.iter().map(|g| f(&g.contours[ci].points()[pi])))
                    };
                    ControlPoint::blended(at(|p| p.pos.x), at(|p| p.pos.y), at(|p| p.s))
                })
                .collect();
            let contour = Contour::new(points).map_err(|error| InstanceError::Contour {
                glyph: d.name.clone(),
                contour: ci,
                error,
            })?;
            contours.push(contour);
        }
        let components = d
            .components
            .iter()
            .enumerate()
            .map(|(k, c)| Component {
                base: c.base.clone(),
                offset: (
                    blend(w, masters.iter().map(|g| g.components[k].offset.0)),
                    blend(w, masters.iter().map(|g| g.components[k].offset.1)),
                ),
            })
            .collect();
        Ok(Glyph {
            outline_mark: d.outline_mark,
            name: d.name.clone(),
            unicodes: d.unicodes.clone(),
            advance: blend(w, masters.iter().map(|g| g.advance)),
            contours,
            components,
            anchors: d
                .anchors
                .iter()
                .map(|a| {
                    // The same anchor in each master (by name); `check` requires it, and a
                    // master without it holds the default's position.
                    let at = |g: &Glyph| {
                        g.anchors
                            .iter()
                            .find(|b| b.name == a.name)
                            .map_or(a.position, |b| b.position)
                    };
                    Anchor {
                        name: a.name.clone(),
                        position: (
                            blend(w, masters.iter().map(|g| at(g).0)),
                            blend(w, masters.iter().map(|g| at(g).1)),
                        ),
                    }
                })
                .collect(),
        })
    }

    /// The kerning blended with `weights`: the default's pairs in order, then pairs only
    /// other masters have (in master order), each left out where it blends to 0.
    fn kerning_at(&self, weights: &[f64]) -> Vec<KernPair> {
        let tables: Vec<HashMap<(&str, &str), f64>> = std::iter::once(&self.default.kerning)
            .chain(self.masters.iter().map(|m| &m.kerning))
            .map(|pairs| {
                pairs
                    .iter()
                    .map(|k| ((k.left.as_str(), k.right.as_str()), k.value))
                    .collect()
            })
            .collect();
        let mut seen: HashSet<(&str, &str)> = HashSet::new();
        let mut out = Vec::new();
        let all = std::iter::once(&self.default.kerning)
            .chain(self.masters.iter().map(|m| &m.kerning))
            .enumerate();
        for (t, pairs) in all {
            for pair in pairs {
                let key = (pair.left.as_str(), pair.right.as_str());
                if !seen.insert(key) {
                    continue;
                }
                let v = blend(
                    weights,
                    tables.iter().map(|tb| tb.get(&key).copied().unwrap_or(0.0)),
                );
                if t == 0 || v != 0.0 {
                    out.push(KernPair {
                        left: pair.left.clone(),
                        right: pair.right.clone(),
                        value: v,
                    });
                }
            }
        }
        out
    }
}

/// Parses a position given on the command line, `TAG=VALUE[,TAG=VALUE...]` in user
/// coordinates (e.g. `wght=650`), against the font's axes. The error names the `--at`
/// flag and says what is wrong.
pub fn parse_location(designspace: &Designspace, text: &str) -> Result<Location, String> {
    let flag = format!("--at {text}");
    let axes = || {
        designspace
            .axes
            .iter()
            .map(|a| {
                format!(
                    "`{}` ({}..{})",
                    a.tag,
                    emit::number(a.min),
                    emit::number(a.max)
                )
            })
            .collect::<Vec<_>>()
            .join(", ")
    };
    if designspace.axes.is_empty() {
        return Err(format!(
            "{flag}: the font has no axes (no `[[axis]]` in font.toml), so it has one position \
             only; leave out --at"
        ));
    }
    let mut location = Location::default();
    for (tag, x) in assignments(text)? {
        let Some(axis) = designspace.axes.iter().find(|a| a.tag == tag) else {
            return Err(format!(
                "{flag}: unknown axis `{tag}`; the font's axes are {}",
                axes()
            ));
        };
        if !(axis.min..=axis.max).contains(&x) {
            return Err(format!(
                "{flag}: {tag} = {} is outside the axis range {}..{}",
                emit::number(x),
                emit::number(axis.min),
                emit::number(axis.max)
            ));
        }
        location.0.insert(tag, x);
    }
    Ok(location)
}

/// The `TAG=VALUE[,TAG=VALUE...]` of an `--at` flag as `(tag, value)` pairs in their order,
/// each value a finite number and each tag given once; what they mean is the caller's
/// ([`parse_location`]: a position of a font; the designspace import: a discrete location).
/// The error names the flag and says what is wrong.
pub fn assignments(text: &str) -> Result<Vec<(String, f64)>, String> {
    let flag = format!("--at {text}");
    let mut out: Vec<(String, f64)> = Vec::new();
    for item in text.split(',') {
        let Some((tag, value)) = item.split_once('=') else {
            return Err(format!(
                "{flag}: expected TAG=VALUE (several separated by commas), such as wght=650; \
                 found `{item}`"
            ));
        };
        let (tag, value) = (tag.trim(), value.trim());
        let x: f64 = match value.parse::<f64>() {
            Ok(x) if x.is_finite() => x,
            _ => {
                return Err(format!(
                    "{flag}: `{value}` is not a number (the {tag} value)"
                ))
            }
        };
        if out.iter().any(|(t, _)| t == tag) {
            return Err(format!("{flag}: axis `{tag}` is given twice"));
        }
        out.push((tag.to_string(), x));
    }
    Ok(out)
}

/// A style name for the font at `location`: the named instance there, or the axis values,
/// e.g. `"wght650"` (for file and font names of an instance that has no name).
pub fn style_at(designspace: &Designspace, location: &Location) -> String {
    let here = designspace.normalize(location);
    if let Some(named) = designspace
        .instances
        .iter()
        .find(|i| designspace.normalize(&i.location) == here)
    {
        return named.name.clone();
    }
    designspace
        .axes
        .iter()
        .map(|a| format!("{}{}", a.tag, emit::number(location.get(a))))
        .collect::<Vec<_>>()
        .join(" ")
}
