//! The limits of the outputs, checked at the source with file:line:col, so that a font
//! that passes `check` builds: no late failure, no silently corrupt table.
//!
//! Values are checked where they are read (`coordinate`, `advance`, `metric`,
//! `kern_value`, `text`); what needs the whole font (glyph names, the glyph count, and
//! each glyph's size and extent with its components placed) is checked by `check_font`,
//! which computes every glyph's expanded size once, bases before the glyphs that use them,
//! so that components that double at each level cost one addition per component.
//!
//! Where the limits come from (docs/format.md has the table):
//! - TrueType stores coordinates, kerning and vertical metrics as signed 16-bit numbers,
//!   and advances as unsigned 16-bit numbers that several readers take as signed.
//! - A TrueType glyph holds at most 65,535 points and 32,766 contours; a font at most
//!   65,535 glyphs (`.notdef` included).
//! - Glyph names follow the OpenType `post` rule (`names::glyph_name_problem`).
//! - `<family>-<style>.ttf` must fit the 255-byte file-name limit of common file systems.
//! - The `name` table addresses its strings with 16-bit offsets.
//!
//! Limit: the point count is checked on the control points. A TrueType glyph has at least
//! one point per control point (more where curves become several quadratic pieces), so a
//! glyph under the limit here can still exceed it after fitting; the TrueType writer checks
//! the final count and names the glyph.

use kurbo::{Rect, Vec2};
use toml::de::DeValue;
use toml::Spanned;

use super::components::ComponentGraph;
use super::diagnostic::{Ctx, Diagnostic, Diagnostics, Severity};
use super::emit;
use super::load::GlyphFile;
use super::value::number;
use crate::names::glyph_name_problem;

/// Largest coordinate magnitude of a control point, with components placed, and of a
/// component offset (font units). Half the 16-bit range, so that the curve, which may bulge
/// past its control points, and the Bézier handles of the fitted outline stay inside it.
pub const MAX_COORDINATE: f64 = 16384.0;

/// Largest advance, font units (after rounding): the `hmtx` field is unsigned 16-bit, but
/// several readers take it as signed.
pub const MAX_ADVANCE: f64 = 32767.0;

/// The signed 16-bit range of kerning values and vertical metrics (after rounding).
pub const INT16: (f64, f64) = (-32768.0, 32767.0);

/// Most points of one glyph, components included (TrueType: 16-bit point indices).
pub const MAX_GLYPH_POINTS: u64 = 65535;

/// Most contours of one glyph, components included (TrueType's count is signed 16-bit;
/// write-fonts, which writes the table, accepts one fewer than 32,767).
pub const MAX_GLYPH_CONTOURS: u64 = 32766;

/// Most glyphs in a font, `.notdef` included (16-bit glyph ids).
pub const MAX_GLYPHS: usize = 65535;

/// Most control points in the whole font, components included: far above any real font
/// (a 20,000-glyph CJK font has about 2 million), low enough that a build finishes.
pub const MAX_FONT_POINTS: u64 = 10_000_000;

/// Most bytes of `family` and `style` together: `<family>-<style>.ttf` must stay within
/// the 255-byte file-name limit.
pub const MAX_FAMILY_STYLE_BYTES: usize = 240;

/// Most UTF-16 code units of `copyright`, `designer`, `version`, `license` and
/// `license_url` each (the `name` table stores UTF-16 behind 16-bit offsets; `version` is
/// stored twice; all of them at this limit still end below offset 65535).
pub const MAX_TEXT_UTF16: usize = 5000;

/// A coordinate (`x`, `y`, or an offset's): a finite number within ±[`MAX_COORDINATE`].
pub(super) fn coordinate(ctx: &mut Ctx<'_>, v: &Spanned<DeValue<'_>>, what: &str) -> Option<f64> {
    let x = number(ctx, v, what)?;
    if x.abs() <= MAX_COORDINATE {
        return Some(x);
    }
    ctx.err(
        v.span().start,
        format!(
            "`{what}` = {} is outside -{m}..{m} font units: TrueType stores 16-bit \
             coordinates, and curves may bulge past their points",
            shown(x),
            m = MAX_COORDINATE
        ),
    );
    None
}

/// A glyph's advance: a finite number, not negative, at most [`MAX_ADVANCE`] when rounded.
pub(super) fn advance(ctx: &mut Ctx<'_>, v: &Spanned<DeValue<'_>>) -> Option<f64> {
    let a = number(ctx, v, "advance")?;
    let why = if a < 0.0 {
        format!("`advance` must not be negative, found {a}")
    } else if a.round() > MAX_ADVANCE {
        format!(
            "`advance` = {} is more than {MAX_ADVANCE} font units, the largest advance \
             TrueType's `hmtx` table holds",
            shown(a)
        )
    } else {
        return Some(a);
    };
    ctx.err(v.span().start, why);
    None
}

/// A vertical metric of `font.toml`: a finite number within [`INT16`] when rounded.
pub(super) fn metric(ctx: &mut Ctx<'_>, v: &Spanned<DeValue<'_>>, key: &str) -> Option<f64> {
    in_int16(
        ctx,
        v,
        key,
        "a 16-bit field of the `hhea` and `OS/2` tables",
    )
}

/// A kerning `value`: a finite number within [`INT16`] when rounded.
pub(super) fn kern_value(ctx: &mut Ctx<'_>, v: &Spanned<DeValue<'_>>) -> Option<f64> {
    in_int16(
        ctx,
        v,
        "value",
        "kerning is 16-bit in the `kern` and `GPOS` tables",
    )
}

fn in_int16(ctx: &mut Ctx<'_>, v: &Spanned<DeValue<'_>>, key: &str, why: &str) -> Option<f64> {
    let x = number(ctx, v, key)?;
    let (lo, hi) = INT16;
    if (lo..=hi).contains(&x.round()) {
        return Some(x);
    }
    ctx.err(
        v.span().start,
        format!(
            "`{key}` = {} is outside {lo}..{hi} font units ({why})",
            shown(x)
        ),
    );
    None
}

/// A number for a message: as written when moderate, else in exponent form (`1e308`, not
/// 309 digits).
fn shown(x: f64) -> String {
    if x.abs() < 1e9 {
        emit::number(x)
    } else {
        format!("{x:e}")
    }
}

/// Checks `copyright`, `designer`, `version`, `license` and `license_url`: at most
/// [`MAX_TEXT_UTF16`] UTF-16 code units each. Returns whether it passed. (Control characters
/// are not refused: the SVG font writes U+FFFD for what XML cannot hold, and the terminal
/// output escapes them.) Any of these or `style` with white space at its start or end gets
/// a warning: the fonts' `name` table carries it, and FontBakery fails it.
pub(super) fn text(ctx: &mut Ctx<'_>, value: &str, offset: usize, key: &str) -> bool {
    if value.trim() != value {
        ctx.warn(
            offset,
            format!(
                "`{key}` begins or ends with white space, which the fonts' `name` table \
                 would carry and FontBakery fails; remove it"
            ),
        );
    }
    let units = value.encode_utf16().count();
    if matches!(
        key,
        "copyright" | "designer" | "version" | "license" | "license_url"
    ) && units > MAX_TEXT_UTF16
    {
        ctx.err(
            offset,
            format!(
                "`{key}` is {units} UTF-16 code units long; at most {MAX_TEXT_UTF16} fit the \
                 font's `name` table"
            ),
        );
        return false;
    }
    true
}

/// Checks `family` and `style` together: `<family>-<style>.ttf` must be a valid file name.
pub(super) fn family_style(ctx: &mut Ctx<'_>, family: &str, style: &str, offset: usize) -> bool {
    let bytes = family.len() + style.len();
    if bytes <= MAX_FAMILY_STYLE_BYTES {
        return true;
    }
    ctx.err(
        offset,
        format!(
            "`family` and `style` are {bytes} bytes together; at most \
             {MAX_FAMILY_STYLE_BYTES}, so that the output file name `<family>-<style>.ttf` \
             fits the 255-byte limit of file systems"
        ),
    );
    false
}

/// A glyph's size with its components placed: control points, contours, and the box of
/// its control points (`None` without any).
#[derive(Clone, Copy, Debug, Default)]
struct Expanded {
    points: u64,
    contours: u64,
    bounds: Option<Rect>,
}

/// The checks that need the whole font: glyph names, the glyph count, and each glyph's
/// point and contour counts and extent with its components placed.
///
/// An over-limit glyph is reported once, where it crosses the limit (the contour, or the
/// component that brings it over); glyphs that use it are not reported again. Glyphs on a
/// component cycle, and glyphs using them, are skipped (the cycle is reported).
pub(super) fn check_font(
    dir: &std::path::Path,
    glyphs: &[GlyphFile],
    graph: &ComponentGraph,
    out: &mut Diagnostics,
) {
    check_names(glyphs, out);
    let has_notdef = glyphs.iter().any(|g| g.glyph.name == ".notdef");
    let count = glyphs.len() + usize::from(!has_notdef);
    if count > MAX_GLYPHS {
        let added = if has_notdef {
            ""
        } else {
            " (counting the `.notdef` that the fonts get when there is none)"
        };
        out.push(Diagnostic::whole(
            dir,
            Severity::Error,
            format!(
                "{count} glyphs{added}: a TrueType or OpenType font holds at most \
                 {MAX_GLYPHS}"
            ),
        ));
    }

    // `None`: not computed (on or behind a cycle) or over a limit (already reported).
    let mut sizes: Vec<Option<Expanded>> = vec![None; glyphs.len()];
    let mut font_points: u64 = 0;
    let mut font_reported = false;
    for &g in &graph.order {
        let file = &glyphs[g];
        if graph.in_cycle(g) {
            continue;
        }
        let Some(size) = expand(file, &graph.bases[g], &sizes, out) else {
            continue;
        };
        font_points = font_points.saturating_add(size.points);
        if font_points > MAX_FONT_POINTS && !font_reported {
            font_reported = true;
            let at = file.spans.name;
            file.ctx(out).err(
                at,
                format!(
                    "with glyph `{}`, the font has more than {MAX_FONT_POINTS} control points \
                     (components placed); split it into several fonts",
                    file.glyph.name
                ),
            );
        }
        sizes[g] = Some(size);
    }
}

/// Glyph names that the outputs cannot carry, at the `name` (or the whole file when the
/// name comes from the file name).
fn check_names(glyphs: &[GlyphFile], out: &mut Diagnostics) {
    for file in glyphs {
        let name = &file.glyph.name;
        let Some(why) = glyph_name_problem(name) else {
            continue;
        };
        let shown: String = name.chars().flat_map(char::escape_debug).collect();
        // A written `name` value never starts at offset 0 (its key comes first).
        if file.spans.name > 0 {
            file.ctx(out)
                .err(file.spans.name, format!("glyph name `{shown}` {why}"));
        } else {
            out.push(Diagnostic::whole(
                &file.path,
                Severity::Error,
                format!(
                    "glyph name `{shown}` (from the file name) {why}; add a `name` line \
                     that follows it"
                ),
            ));
        }
    }
}

/// The size of one glyph with its components placed, from its bases' sizes; `None` after
/// reporting a limit it crosses, or when a base has no size.
fn expand(
    file: &GlyphFile,
    bases: &[Option<usize>],
    sizes: &[Option<Expanded>],
    out: &mut Diagnostics,
) -> Option<Expanded> {
    let glyph = &file.glyph;
    let mut ctx = file.ctx(out);
    let mut size = Expanded::default();
    for (c, contour) in glyph.contours.iter().enumerate() {
        size.points += contour.points().len() as u64;
        size.contours += 1;
        let at = || file.spans.points[c].first().copied().unwrap_or(0);
        if size.contours > MAX_GLYPH_CONTOURS {
            ctx.err(
                at(),
                format!(
                    "glyph `{}` has {} contours; a TrueType glyph holds at most \
                     {MAX_GLYPH_CONTOURS}",
                    glyph.name,
                    glyph.contours.len()
                ),
            );
            return None;
        }
        if size.points > MAX_GLYPH_POINTS {
            let total: usize = glyph.contours.iter().map(|c| c.points().len()).sum();
            ctx.err(
                at(),
                format!(
                    "glyph `{}` has {total} points; a TrueType glyph holds at most \
                     {MAX_GLYPH_POINTS}",
                    glyph.name
                ),
            );
            return None;
        }
        for p in contour.points() {
            size.bounds = Some(match size.bounds {
                Some(r) => r.union_pt(p.pos),
                None => Rect::from_points(p.pos, p.pos),
            });
        }
    }
    let placed = glyph.components.iter().zip(bases).zip(&file.spans.bases);
    for ((component, base), &at) in placed {
        let Some(base) = base else { continue };
        let base_size = sizes[*base]?;
        size.points = size.points.saturating_add(base_size.points);
        size.contours = size.contours.saturating_add(base_size.contours);
        let over = if size.contours > MAX_GLYPH_CONTOURS {
            Some(format!(
                "{} contours; a TrueType glyph holds at most {MAX_GLYPH_CONTOURS}",
                size.contours
            ))
        } else if size.points > MAX_GLYPH_POINTS {
            Some(format!(
                "{} points; a TrueType glyph holds at most {MAX_GLYPH_POINTS}",
                size.points
            ))
        } else {
            None
        };
        if let Some(over) = over {
            ctx.err(
                at,
                format!(
                    "with component `{}` ({} contours, {} points), glyph `{}` has at least \
                     {over}",
                    component.base, base_size.contours, base_size.points, glyph.name
                ),
            );
            return None;
        }
        let Some(b) = base_size.bounds else { continue };
        let (dx, dy) = component.offset;
        let moved = b + Vec2::new(dx, dy);
        if let Some((axis, v)) = outside(moved) {
            ctx.err(
                at,
                format!(
                    "component `{}` at offset [{}, {}] reaches {axis} = {}, outside \
                     -{m}..{m} font units: TrueType stores 16-bit coordinates",
                    component.base,
                    emit::number(dx),
                    emit::number(dy),
                    emit::number(v),
                    m = MAX_COORDINATE
                ),
            );
            return None;
        }
        size.bounds = Some(size.bounds.map_or(moved, |r| r.union(moved)));
    }
    Some(size)
}

/// The first side of `r` outside ±[`MAX_COORDINATE`], as `("x", value)` or `("y", value)`.
fn outside(r: Rect) -> Option<(&'static str, f64)> {
    let m = MAX_COORDINATE;
    [("x", r.x0), ("x", r.x1), ("y", r.y0), ("y", r.y1)]
        .into_iter()
        .find(|(_, v)| v.abs() > m)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Glyph;
    use crate::source::glyph::GlyphSpans;
    use std::path::Path;

    fn file(name: &str) -> GlyphFile {
        GlyphFile {
            glyph: Glyph {
                name: name.to_string(),
                unicodes: Vec::new(),
                advance: 0.0,
                contours: Vec::new(),
                components: Vec::new(),
                anchors: Vec::new(),
                outline_mark: false,
            },
            complete: true,
            spans: GlyphSpans::default(),
            path: format!("{name}.toml").into(),
            text: String::new().into(),
        }
    }

    /// 65,535 glyphs fit only with a `.notdef` among them (the fonts add one otherwise).
    #[test]
    fn glyph_count() {
        let run = |glyphs: &[GlyphFile]| {
            let mut out = Diagnostics::default();
            check_font(
                Path::new("f"),
                glyphs,
                &ComponentGraph::new(glyphs),
                &mut out,
            );
            out.into_vec()
                .iter()
                .map(|d| d.to_string())
                .collect::<Vec<_>>()
        };
        let mut glyphs: Vec<GlyphFile> = (0..MAX_GLYPHS).map(|i| file(&format!("g{i}"))).collect();
        assert_eq!(
            run(&glyphs),
            [
                "f: error: 65536 glyphs (counting the `.notdef` that the fonts get when there is \
              none): a TrueType or OpenType font holds at most 65535"
            ]
        );
        glyphs[0] = file(".notdef");
        assert_eq!(run(&glyphs), Vec::<String>::new());
        glyphs.push(file("extra"));
        assert_eq!(
            run(&glyphs),
            ["f: error: 65536 glyphs: a TrueType or OpenType font holds at most 65535"]
        );
    }
}
