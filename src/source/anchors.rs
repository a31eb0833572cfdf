//! Anchors across files: components placed by anchors, and the checks that need the whole
//! font (a mark attaches to an anchor some glyph has; a combining character is a mark).
//!
//! Placement (the automatic alignment of glyphsLib and ufo2ft): a component written without
//! `offset` that is a mark (an anchor `_x`) goes where its `_x` lands on the latest `x`
//! among the components before it, their anchors moved by their offsets and propagated as
//! [`propagate_anchors`] does (a mark attached by `_x` brings its own `x`, so a second mark
//! stacks on the first). The first component without `offset`, if it is not a mark, is the
//! base at `[0, 0]`. Any later component without `offset` must be a mark. Glyphs are
//! placed bases first ([`ComponentGraph::order`]), each master on its own anchors, so the
//! model's [`crate::model::Component::offset`] is always the resolved one.
//!
//! Limits: a mark with several `_` anchors attaches by the first one that finds a match;
//! glyphs on a component cycle or with errors of their own are not placed (they fail
//! anyway).

use std::collections::BTreeSet;

use super::components::ComponentGraph;
use super::diagnostic::Diagnostics;
use super::load::GlyphFile;
use crate::model::{propagate_anchors, Anchor, Font, Glyph};

/// The combining blocks whose code points must map to marks: Combining Diacritical Marks
/// (U+0300–U+036F), its Extended (U+1AB0–U+1AFF) and Supplement (U+1DC0–U+1DFF) blocks,
/// Combining Diacritical Marks for Symbols (U+20D0–U+20FF) and Combining Half Marks
/// (U+FE20–U+FE2F). A table of blocks rather than a Unicode database: these hold the
/// general category Mn marks of Latin, Greek and Cyrillic text (plus a few enclosing Me
/// marks in U+20DD–U+20E4, which attach too); other scripts' marks are not checked.
pub const COMBINING_BLOCKS: &[(char, char)] = &[
    ('\u{0300}', '\u{036F}'),
    ('\u{1AB0}', '\u{1AFF}'),
    ('\u{1DC0}', '\u{1DFF}'),
    ('\u{20D0}', '\u{20FF}'),
    ('\u{FE20}', '\u{FE2F}'),
];

/// Whether `c` is in one of the [`COMBINING_BLOCKS`].
pub fn is_combining(c: char) -> bool {
    COMBINING_BLOCKS
        .iter()
        .any(|&(lo, hi)| (lo..=hi).contains(&c))
}

/// Places every component written without `offset` (see the module docs) and reports,
/// at the component, a mark that finds no anchor to attach to and a later component
/// without `offset` that is not a mark.
pub(super) fn place_components(
    glyphs: &mut [GlyphFile],
    graph: &ComponentGraph,
    out: &mut Diagnostics,
) {
    // Per glyph, its effective anchors once placed (bases come first in `graph.order`).
    let mut effective: Vec<Option<Vec<Anchor>>> = vec![None; glyphs.len()];
    for &g in &graph.order {
        let file = &glyphs[g];
        if file.glyph.components.is_empty() {
            effective[g] = Some(file.glyph.anchors.clone());
            continue;
        }
        if !file.complete || graph.in_cycle(g) {
            continue;
        }
        let mut ctx = file.ctx(out);
        let mut placed: Vec<((f64, f64), Vec<Anchor>)> = Vec::new();
        for (k, c) in file.glyph.components.iter().enumerate() {
            let anchors = match graph.bases[g][k] {
                Some(b) => effective[b]
                    .clone()
                    .unwrap_or_else(|| glyphs[b].glyph.anchors.clone()),
                None => Vec::new(),
            };
            let written = file.spans.offsets[k].is_some();
            let offset = if written || graph.bases[g][k].is_none() {
                c.offset
            } else {
                let at = file.spans.bases[k];
                let before =
                    propagate_anchors(&[], placed.iter().map(|(off, a)| (*off, a.as_slice())));
                let outline_mark = graph.bases[g][k].is_some_and(|b| glyphs[b].glyph.outline_mark);
                match attach(&c.base, outline_mark, &anchors, &before, k) {
                    Ok(offset) => offset,
                    Err(message) => {
                        ctx.err(at, message);
                        c.offset
                    }
                }
            };
            placed.push((offset, anchors));
        }
        let anchors = propagate_anchors(
            &file.glyph.anchors,
            placed.iter().map(|(off, a)| (*off, a.as_slice())),
        );
        effective[g] = Some(anchors);
        for (c, (offset, _)) in glyphs[g].glyph.components.iter_mut().zip(placed) {
            c.offset = offset;
        }
    }
}

/// Places the components of `glyph` (loaded alone, so each component without `offset` is at
/// `[0, 0]`) by the anchors of `font`'s glyphs, as the loader would: for a glyph file read
/// without reloading its font (the studio's edits while another file has errors).
/// `offsets_written` says which components had an `offset` ([`super::offsets_written`]).
/// A component that cannot be placed stays where it is; the loader reports it.
pub fn place_in_font(font: &Font, glyph: &mut Glyph, offsets_written: &[bool]) {
    let index = font.index();
    let mut placed: Vec<((f64, f64), Vec<Anchor>)> = Vec::new();
    for (k, c) in glyph.components.iter_mut().enumerate() {
        let base = index.get(&c.base);
        let anchors = base.map(|b| font.anchors_in(&index, b)).unwrap_or_default();
        if !offsets_written.get(k).copied().unwrap_or(true) {
            let before = propagate_anchors(&[], placed.iter().map(|(o, a)| (*o, a.as_slice())));
            let outline_mark = base.is_some_and(|b| b.outline_mark);
            if let Ok(offset) = attach(&c.base, outline_mark, &anchors, &before, k) {
                c.offset = offset;
            }
        }
        placed.push((c.offset, anchors));
    }
}

/// The offset of component `k` (glyph `base`, with `anchors`; `outline_mark` when it says
/// `mark = "outline"`) written without `offset`, given the anchors of the components
/// `before` it; or the error message.
fn attach(
    base: &str,
    outline_mark: bool,
    anchors: &[Anchor],
    before: &[Anchor],
    k: usize,
) -> Result<(f64, f64), String> {
    let marks: Vec<&Anchor> = anchors
        .iter()
        .filter(|a| a.attaches_to().is_some())
        .collect();
    if marks.is_empty() {
        if k == 0 {
            return Ok((0.0, 0.0));
        }
        if outline_mark {
            return Err(format!(
                "component `{base}` has no `offset`, and it is a mark placed by its outline \
                 (`mark = \"outline\"`), which no anchor places: write `offset = [x, y]` \
                 (`[0, 0]` to overlay it where its outline is drawn)"
            ));
        }
        return Err(format!(
            "component `{base}` has no `offset` and is not a mark (it has no `_` anchor such \
             as `_top`), so nothing places it: give `{base}` an anchor like `_top`, or write \
             `offset = [x, y]` (`[0, 0]` to overlay it)"
        ));
    }
    for m in &marks {
        let name = m.attaches_to().unwrap_or_default();
        if let Some(to) = before.iter().find(|a| a.name == name) {
            return Ok((to.position.0 - m.position.0, to.position.1 - m.position.1));
        }
    }
    let wanted: Vec<String> = marks
        .iter()
        .map(|m| format!("`{}`", m.attaches_to().unwrap_or_default()))
        .collect();
    let what = if k == 0 {
        "it is the first component".to_string()
    } else {
        let have: Vec<String> = before.iter().map(|a| format!("`{}`", a.name)).collect();
        if have.is_empty() {
            "the components before it have no anchors".to_string()
        } else {
            format!("the components before it have {}", have.join(", "))
        }
    };
    Err(format!(
        "mark `{base}` has no `offset` and nothing to attach to: it needs an anchor {} \
         before it, but {what}; put a base with that anchor first, or write \
         `offset = [x, y]`",
        wanted.join(" or ")
    ))
}

/// The checks of a font's anchors that need every glyph: a mark anchor `_x` for which no
/// glyph has an anchor `x`, and a glyph mapped to a combining code point
/// ([`COMBINING_BLOCKS`]) that is no mark (no `_` anchor, no `mark = "outline"`).
pub(super) fn check_anchors(glyphs: &[GlyphFile], out: &mut Diagnostics) {
    let bases: BTreeSet<&str> = glyphs
        .iter()
        .flat_map(|g| &g.glyph.anchors)
        .filter(|a| a.attaches_to().is_none())
        .map(|a| a.name.as_str())
        .collect();
    for g in glyphs {
        let mut ctx = g.ctx(out);
        for (a, &at) in g.glyph.anchors.iter().zip(&g.spans.anchors) {
            let Some(to) = a.attaches_to() else { continue };
            if !bases.contains(to) {
                ctx.err(
                    at,
                    format!(
                        "unknown base: mark anchor `{}` attaches to `{to}`, but no glyph has \
                         an anchor `{to}`; add one to the bases, or rename this anchor",
                        a.name
                    ),
                );
            }
        }
        // A `mark` written with a bad value has its error at the value already.
        if g.glyph.is_mark() || g.spans.mark > 0 {
            continue;
        }
        let combining = g.glyph.unicodes.iter().zip(&g.spans.unicodes);
        if let Some((&c, &at)) = combining.into_iter().find(|(&c, _)| is_combining(c)) {
            ctx.err(
                at,
                format!(
                    "glyph `{}` is mapped to U+{:04X}, a combining mark, but has no `_` \
                     anchor to attach by; add one, e.g. `[[anchor]]` with name = \"_top\", \
                     or write mark = \"outline\" if its outline places it",
                    g.glyph.name,
                    u32::from(c)
                ),
            );
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn combining_blocks() {
        assert!(is_combining('\u{0300}') && is_combining('\u{036F}'));
        assert!(is_combining('\u{0327}') && is_combining('\u{1DC0}'));
        assert!(!is_combining('\u{02C6}') && !is_combining('\u{0370}') && !is_combining('a'));
    }
}
