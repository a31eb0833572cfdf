//! The specimen page: one HTML file that loads the built font with `@font-face` and shows
//! the character set, a waterfall and the kerning pairs.
//!
//! All model text is HTML-escaped; the font file name is percent-encoded inside a quoted
//! CSS `url()`; the CSS family name is a fixed identifier, so no model text reaches CSS or
//! JavaScript. A small script checks the font really loaded: it measures a hidden line of
//! [`specimen_text`] set at one pixel per font unit and writes the width next to the
//! expected one (sum of advances and kerning) into `<output id="font-check">`, with
//! `data-loaded`, `data-width` and `data-expected` attributes for automated checks.
//!
//! Limits: at most [`KERN_ROWS`] kerning pairs are shown and measured (the first in the
//! font's order, with a note giving the total); a pair of two scripts, which no shaper
//! kerns, is not shown. Combining marks (U+0300–036F, U+1AB0–1AFF, U+1DC0–1DFF,
//! U+20D0–20FF, U+FE20–FE2F), control characters and default-ignorable code points are
//! shown in the character set but left out of the sample and measured text, where
//! browsers would compose them or draw nothing. Right-to-left text is measured as if it
//! were left to right.

use std::collections::HashMap;
use std::fmt::Write;

use skrifa::raw::types::Tag;

use crate::layout::strong_script;
use crate::outline::{OutlinedFont, OutlinedGlyph};

/// The CSS family name the page gives the font (never the model's text).
const CSS_FAMILY: &str = "xglyph-specimen";

/// Waterfall sizes in CSS pixels.
const WATERFALL: &[u32] = &[12, 16, 20, 24, 32, 48, 64, 96];

/// HTML text and attribute values use the XML escaping of the SVG outputs (HTML5 reads
/// every entity it writes).
fn escape_html(text: &str) -> String {
    crate::svg::xml::escape(text)
}

/// Percent-encodes everything but unreserved URL characters (RFC 3986).
fn escape_url(text: &str) -> String {
    let mut out = String::new();
    for b in text.bytes() {
        if b.is_ascii_alphanumeric() || b"-._~".contains(&b) {
            out.push(b as char);
        } else {
            let _ = write!(out, "%{b:02X}");
        }
    }
    out
}

/// Whether `c` is left out of the sample and measured text: controls, combining marks
/// (which browsers compose), and the default-ignorable code points (which shapers draw as
/// nothing: soft hyphen, joiners, bidi controls, variation selectors, the BOM).
fn left_out(c: char) -> bool {
    let u = u32::from(c);
    // Unicode 16's Default_Ignorable_Code_Point ranges (DerivedCoreProperties.txt), by
    // hand: no dependency has the property public.
    const IGNORABLE: [(u32, u32); 17] = [
        (0x00AD, 0x00AD),
        (0x034F, 0x034F),
        (0x061C, 0x061C),
        (0x115F, 0x1160),
        (0x17B4, 0x17B5),
        (0x180B, 0x180F),
        (0x200B, 0x200F),
        (0x202A, 0x202E),
        (0x2060, 0x206F),
        (0x3164, 0x3164),
        (0xFE00, 0xFE0F),
        (0xFEFF, 0xFEFF),
        (0xFFA0, 0xFFA0),
        (0xFFF0, 0xFFF8),
        (0x1BCA0, 0x1BCA3),
        (0x1D173, 0x1D17A),
        (0xE0000, 0xE0FFF),
    ];
    c.is_control()
        || (0x0300..=0x036F).contains(&u)
        || (0x1AB0..=0x1AFF).contains(&u)
        || (0x1DC0..=0x1DFF).contains(&u)
        || (0x20D0..=0x20FF).contains(&u)
        || (0xFE20..=0xFE2F).contains(&u)
        || IGNORABLE.iter().any(|&(a, b)| (a..=b).contains(&u))
}

/// Characters to set as text: each glyph's first code point in glyph order, marks and
/// controls left out.
fn sample_chars(font: &OutlinedFont) -> Vec<char> {
    font.glyphs
        .iter()
        .filter_map(|g| g.unicodes.first().copied())
        .filter(|&c| !left_out(c) && c != ' ')
        .collect()
}

/// The kerning pairs that can be typed (both glyphs have a usable code point), in the
/// font's order, at most [`KERN_ROWS`]; and how many there are in all.
fn kern_strings(font: &OutlinedFont) -> (Vec<(String, f64)>, usize) {
    if font.kerning.is_empty() {
        return (Vec::new(), 0);
    }
    let by_name: HashMap<&str, &OutlinedGlyph> =
        font.glyphs.iter().map(|g| (g.name.as_str(), g)).collect();
    let first = |name: &str| {
        by_name
            .get(name)?
            .unicodes
            .iter()
            .copied()
            .find(|&c| !left_out(c))
    };
    // Each glyph's character and its script, once per glyph.
    let typed_as: HashMap<&str, (char, Option<Tag>)> = by_name
        .keys()
        .filter_map(|&name| {
            let c = first(name)?;
            Some((name, (c, strong_script(c))))
        })
        .collect();
    // A pair of two scripts is two runs, which a shaper never kerns.
    let mut typed = font.kerning.iter().filter_map(|k| {
        let (a, sa) = *typed_as.get(k.left.as_str())?;
        let (b, sb) = *typed_as.get(k.right.as_str())?;
        let one_run = sa.is_none() || sb.is_none() || sa == sb;
        one_run.then(|| (format!("{a}{b}"), k.value))
    });
    let shown: Vec<_> = typed.by_ref().take(KERN_ROWS).collect();
    let total = shown.len() + typed.count();
    (shown, total)
}

/// Most kerning pairs the page shows and measures. A font imported with its class
/// kerning expanded can have hundreds of thousands of pairs (Lato Regular: about 273,000),
/// a page no browser lays out in reasonable time.
pub const KERN_ROWS: usize = 500;

/// The measured line: the sample characters, then the kerning pairs shown, separated by
/// spaces when the font has a space glyph.
pub fn specimen_text(font: &OutlinedFont) -> String {
    let sample: String = sample_chars(font).into_iter().collect();
    measured_line(font, &sample, &kern_strings(font).0)
}

/// [`specimen_text`] from the sample and the pairs shown, made once per page.
fn measured_line(font: &OutlinedFont, sample: &str, pairs: &[(String, f64)]) -> String {
    let sep = if font.glyph_for_char(' ').is_some() {
        " "
    } else {
        ""
    };
    let parts = std::iter::once(sample).chain(pairs.iter().map(|(s, _)| s.as_str()));
    parts
        .filter(|p| !p.is_empty())
        .collect::<Vec<_>>()
        .join(sep)
}

/// Width of `text` in font units: advances plus kerning between neighbours, as a shaper
/// applying the `kern` feature gives it (the first pair of two glyphs, as
/// [`OutlinedFont::kern`] takes it, looked up in a map made once). As a browser splits
/// text into runs of one script (a character of none joining the run it is in), two
/// neighbours of different runs are not kerned.
fn text_width(font: &OutlinedFont, text: &str) -> f64 {
    let chars = font.char_map();
    let mut kerning: HashMap<(&str, &str), f64> = HashMap::with_capacity(font.kerning.len());
    for k in &font.kerning {
        kerning.entry((&k.left, &k.right)).or_insert(k.value);
    }
    let mut width = 0.0;
    let mut prev: Option<&str> = None;
    let mut run: Option<Tag> = None;
    for c in text.chars() {
        let Some(glyph) = chars.get(&c) else {
            continue;
        };
        // (Runs only matter to kerning: a CJK font without any is not asked per character.)
        let script = if kerning.is_empty() {
            None
        } else {
            strong_script(c)
        };
        if script.is_some() && run.is_some() && script != run {
            // A new run: nothing kerns across its start.
            prev = None;
        }
        run = script.or(run);
        if let Some(p) = prev {
            width += kerning
                .get(&(p, glyph.name.as_str()))
                .copied()
                .unwrap_or(0.0);
        }
        width += glyph.advance.round();
        prev = Some(&glyph.name);
    }
    width
}

/// The specimen page for the font file `font_file_name` (next to the page).
pub fn specimen_html(font: &OutlinedFont, font_file_name: &str) -> String {
    specimen_html_sources(font, &[font_file_name])
}

/// The CSS `src` list: each file (next to the page) with its `format()` hint from the
/// extension; the browser uses the first it can read, e.g. the WOFF2 before the OTF.
fn font_sources(files: &[&str]) -> String {
    let source = |file: &&str| {
        let ext = file.rsplit_once('.').map(|(_, e)| e.to_ascii_lowercase());
        let format = match ext.as_deref() {
            Some("woff2") => " format(\"woff2\")",
            Some("woff") => " format(\"woff\")",
            Some("otf") => " format(\"opentype\")",
            Some("ttf") => " format(\"truetype\")",
            _ => "",
        };
        format!("url(\"{}\"){format}", escape_url(file))
    };
    files.iter().map(source).collect::<Vec<_>>().join(", ")
}

/// The specimen page loading the first usable of `font_files` (next to the page), e.g.
/// `["Family-Style.woff2", "Family-Style.otf"]`.
pub fn specimen_html_sources(font: &OutlinedFont, font_files: &[&str]) -> String {
    let info = &font.info;
    let title = escape_html(&format!("{} {}", info.family, info.style));
    let upm = info.units_per_em;
    let sample: String = sample_chars(font).into_iter().collect();
    let (pairs, total) = kern_strings(font);
    let measure = measured_line(font, &sample, &pairs);
    let expected = text_width(font, &measure);

    let mut html = String::new();
    let _ = write!(
        html,
        r#"<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<title>{title} — specimen</title>
<style>
@font-face {{ font-family: "{CSS_FAMILY}"; src: {sources}; }}
body {{ font-family: sans-serif; margin: 2em; color: #111; }}
.font {{ font-family: "{CSS_FAMILY}", monospace; font-kerning: normal; }}
.charset {{ display: flex; flex-wrap: wrap; gap: 8px; }}
.cell {{ border: 1px solid #ccc; width: 96px; text-align: center; padding: 4px; }}
.cell .font {{ font-size: 48px; line-height: 1.4; }}
.cell small {{ display: block; font-size: 11px; color: #555; overflow-wrap: anywhere; }}
.waterfall p {{ margin: 0.2em 0; white-space: nowrap; overflow: hidden; }}
.pairs td {{ padding: 4px 12px; }}
.probe {{ position: absolute; left: 0; top: 0; width: 0; height: 0; overflow: hidden; }}
#measure {{ white-space: pre; font-size: {upm}px; line-height: 1; }}
</style>
</head>
<body>
<h1>{title}</h1>
<p>{upm} units per em, ascender {asc}, descender {desc}, x-height {xh}, cap height {ch}.</p>
<p><output id="font-check" data-loaded="pending" data-expected="{expected:.3}">checking font…</output></p>
<h2>Character set</h2>
<div class="charset">
"#,
        sources = font_sources(font_files),
        asc = info.ascender,
        desc = info.descender,
        xh = info.x_height,
        ch = info.cap_height,
    );
    for glyph in &font.glyphs {
        let shown: String = glyph
            .unicodes
            .first()
            .map(|c| c.to_string())
            .unwrap_or_default();
        let codes: Vec<String> = glyph
            .unicodes
            .iter()
            .map(|&c| format!("U+{:04X}", u32::from(c)))
            .collect();
        let _ = writeln!(
            html,
            r#"<div class="cell"><span class="font">{}</span><small>{}</small><small>{}</small></div>"#,
            escape_html(&shown),
            escape_html(&glyph.name),
            codes.join(" ")
        );
    }
    html.push_str("</div>\n<h2>Waterfall</h2>\n<div class=\"waterfall\">\n");
    for size in WATERFALL {
        let _ = writeln!(
            html,
            r#"<p><small>{size}px</small> <span class="font" style="font-size: {size}px">{}</span></p>"#,
            escape_html(&sample)
        );
    }
    html.push_str("</div>\n<h2>Kerning pairs</h2>\n");
    if total > pairs.len() {
        let _ = writeln!(
            html,
            "<p>The first {} of {total} pairs that can be typed.</p>",
            pairs.len()
        );
    }
    html.push_str("<table class=\"pairs\">\n");
    html.push_str("<tr><th>kerned</th><th>not kerned</th><th>value</th></tr>\n");
    for (pair, value) in pairs {
        let _ = writeln!(
            html,
            r#"<tr><td class="font" style="font-size: 64px">{}</td><td class="font" style="font-size: 64px; font-kerning: none">{}</td><td>{value}</td></tr>"#,
            escape_html(&pair),
            escape_html(&pair)
        );
    }
    let _ = write!(
        html,
        r#"</table>
<div class="probe" aria-hidden="true"><span id="measure" class="font">{measure}</span></div>
<script>
document.fonts.ready.then(function () {{
  var out = document.getElementById("font-check");
  var loaded = Array.from(document.fonts).some(function (f) {{ return f.status === "loaded"; }});
  var width = document.getElementById("measure").getBoundingClientRect().width;
  var expected = parseFloat(out.getAttribute("data-expected"));
  out.setAttribute("data-loaded", loaded ? "yes" : "no");
  out.setAttribute("data-width", width.toFixed(3));
  out.textContent = (loaded ? "font loaded" : "font NOT loaded") +
    ": sample width " + width.toFixed(1) + " px, expected " + expected.toFixed(1) + " px";
}});
</script>
</body>
</html>
"#,
        measure = escape_html(&measure)
    );
    html
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn escapes() {
        assert_eq!(
            escape_html("<a href=\"x\">&'\u{7}"),
            "&lt;a href=&quot;x&quot;&gt;&amp;&apos;\u{FFFD}"
        );
        assert_eq!(escape_url("Mini Test\").ttf"), "Mini%20Test%22%29.ttf");
        assert_eq!(escape_url("é.otf"), "%C3%A9.otf");
        assert_eq!(
            font_sources(&["A B.woff2", "A B.otf", "x"]),
            r#"url("A%20B.woff2") format("woff2"), url("A%20B.otf") format("opentype"), url("x")"#
        );
    }
}
