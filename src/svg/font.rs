//! The SVG 1.1 font (`<font>`): for FontForge, svg2ttf and icon-font pipelines.
//!
//! Conventions real consumers need (see docs/design.md): integer `units-per-em`, `ascent`
//! and a positive `descent` with `ascent + descent = units-per-em` (when the font's
//! ascender - descender differs from the em, the descent is scaled to keep that sum);
//! y-up path data with absolute `M L C Z`, outer contours clockwise (as TrueType wants
//! them: svg2ttf keeps each contour's direction); `horiz-adv-x` on every glyph; code points as
//! `&#xHEX;`; `.notdef` becomes the `<missing-glyph>` (when the font has none, the box of
//! [`crate::outline::notdef_box`], as in the TTF and OTF);
//! `d=""` for empty glyphs; kerning as `<hkern g1 g2 k>` with `k = -value` (positive =
//! tighter). Metadata (copyright, designer, version) goes into `<metadata>`.
//!
//! Limits: SVG `unicode` is a string (several characters mean a ligature), so a glyph with
//! several code points is written once per code point, same name and outline. Code points
//! XML cannot hold (C0 controls, U+FFFE/U+FFFF) are left out. `g1`/`g2` are
//! comma-separated lists in SVG, so a glyph name containing a comma will be misread by
//! consumers (the XML stays valid).

use kurbo::{Affine, BezPath};
use rayon::prelude::*;

use super::path_data::path_data;
use super::xml::{escape, is_xml_char, num};
use crate::model::FontInfo;
use crate::outline::{OutlinedFont, OutlinedGlyph};

/// `(ascent, descent)` as positive integers with `ascent + descent = units_per_em`.
pub fn ascent_descent(info: &FontInfo) -> (i64, i64) {
    let upm = i64::from(info.units_per_em);
    let span = info.ascender - info.descender;
    let descent = if span > 0.0 {
        (-info.descender * f64::from(info.units_per_em) / span).round() as i64
    } else {
        0
    };
    let descent = descent.clamp(0, upm);
    (upm - descent, descent)
}

/// CSS `font-weight` and `font-style` guessed from the style name (`"Bold Italic"`).
pub fn weight_and_style(style: &str) -> (u16, &'static str) {
    let s = style.to_lowercase().replace([' ', '-', '_'], "");
    let weight = crate::model::weight_class(style);
    let slant = if s.contains("italic") {
        "italic"
    } else if s.contains("oblique") {
        "oblique"
    } else {
        "normal"
    };
    (weight, slant)
}

fn glyph_element(
    out: &mut String,
    tag: &str,
    name: Option<&str>,
    c: Option<char>,
    adv: f64,
    d: &str,
) {
    out.push('<');
    out.push_str(tag);
    if let Some(name) = name {
        out.push_str(&format!(" glyph-name=\"{}\"", escape(name)));
    }
    if let Some(c) = c {
        out.push_str(&format!(" unicode=\"&#x{:X};\"", u32::from(c)));
    }
    out.push_str(&format!(" horiz-adv-x=\"{}\" d=\"{d}\"/>\n", num(adv)));
}

/// The path data of a glyph of the font: y up, outer contours clockwise. The IR's outer
/// contours run counter-clockwise; an SVG font's consumers turn it into TrueType
/// (svg2ttf keeps each contour's direction, and TrueType wants outer contours
/// clockwise) or read it as FontForge does (clockwise outer contours, else "wrong
/// direction" on every glyph). Fill is nonzero either way.
fn clockwise_path_data(path: &BezPath) -> String {
    path_data(&path.reverse_subpaths(), Affine::IDENTITY)
}

/// The `<glyph>` elements of `g` (not `.notdef`): one per code point XML can hold, in
/// order, or one without `unicode`.
pub fn glyph_elements(g: &OutlinedGlyph) -> String {
    let d = clockwise_path_data(&g.path);
    let mut cps: Vec<char> = g
        .unicodes
        .iter()
        .copied()
        .filter(|&c| is_xml_char(c))
        .collect();
    cps.sort_unstable();
    cps.dedup();
    let mut s = String::with_capacity((d.len() + 80) * cps.len().max(1));
    if cps.is_empty() {
        glyph_element(&mut s, "glyph", Some(&g.name), None, g.advance, &d);
    }
    for c in cps {
        glyph_element(&mut s, "glyph", Some(&g.name), Some(c), g.advance, &d);
    }
    s
}

/// The SVG font document for `font`.
pub fn svg_font(font: &OutlinedFont) -> String {
    svg_font_with(font, |_, g| glyph_elements(g))
}

/// [`svg_font`], with each glyph's elements from `elements(index, glyph)`: [`glyph_elements`]
/// or a copy of it kept from an earlier build. Called on every core, for every glyph but
/// `.notdef`.
pub fn svg_font_with(
    font: &OutlinedFont,
    elements: impl Fn(usize, &OutlinedGlyph) -> String + Sync,
) -> String {
    let info = &font.info;
    let (ascent, descent) = ascent_descent(info);
    let (weight, slant) = weight_and_style(&info.style);
    let missing = font.notdef();
    let missing_adv = missing.advance;
    let mut s = String::new();
    s.push_str("<?xml version=\"1.0\" encoding=\"UTF-8\" standalone=\"no\"?>\n");
    s.push_str("<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\">\n");
    let meta: Vec<String> = [
        ("Copyright", &info.copyright),
        ("Designer", &info.designer),
        ("Version", &info.version),
    ]
    .into_iter()
    .filter_map(|(k, v)| v.as_ref().map(|v| format!("{k}: {}", escape(v))))
    .collect();
    if !meta.is_empty() {
        s.push_str(&format!("<metadata>{}</metadata>\n", meta.join("&#xA;")));
    }
    s.push_str("<defs>\n");
    s.push_str(&format!(
        "<font id=\"{}\" horiz-adv-x=\"{}\">\n",
        escape(&super::output_stem(info)),
        num(missing_adv)
    ));
    s.push_str(&format!(
        "<font-face font-family=\"{}\" font-weight=\"{weight}\" font-style=\"{slant}\" \
         units-per-em=\"{}\" ascent=\"{ascent}\" descent=\"{descent}\" x-height=\"{}\" \
         cap-height=\"{}\"/>\n",
        escape(&info.family),
        info.units_per_em,
        info.x_height.round(),
        info.cap_height.round(),
    ));
    let d = clockwise_path_data(&missing.path);
    glyph_element(&mut s, "missing-glyph", None, None, missing_adv, &d);
    let elements: Vec<String> = font
        .glyphs
        .par_iter()
        .enumerate()
        .filter(|(_, g)| g.name != ".notdef")
        .map(|(i, g)| elements(i, g))
        .collect();
    s.reserve(elements.iter().map(String::len).sum());
    for e in &elements {
        s.push_str(e);
    }
    for k in &font.kerning {
        let known = |n: &str| n != ".notdef" && font.glyph(n).is_some();
        if known(&k.left) && known(&k.right) {
            s.push_str(&format!(
                "<hkern g1=\"{}\" g2=\"{}\" k=\"{}\"/>\n",
                escape(&k.left),
                escape(&k.right),
                num(-k.value)
            ));
        }
    }
    s.push_str("</font>\n</defs>\n</svg>\n");
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn weights_and_slants_from_style_names() {
        assert_eq!(weight_and_style("Regular"), (400, "normal"));
        assert_eq!(weight_and_style("Bold Italic"), (700, "italic"));
        assert_eq!(weight_and_style("Semi-Bold"), (600, "normal"));
        assert_eq!(weight_and_style("ExtraLight Oblique"), (200, "oblique"));
        assert_eq!(weight_and_style("Black"), (900, "normal"));
    }
}
