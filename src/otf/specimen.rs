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
//! Limits: combining marks (U+0300–036F, U+1AB0–1AFF, U+1DC0–1DFF, U+20D0–20FF,
//! U+FE20–FE2F) and control characters are shown in the character set but left out of
//! the sample and measured text, where browsers would compose or reorder them.

use std::fmt::Write;

use crate::outline::OutlinedFont;

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

fn is_combining_or_control(c: char) -> bool {
    let u = u32::from(c);
    c.is_control()
        || (0x0300..=0x036F).contains(&u)
        || (0x1AB0..=0x1AFF).contains(&u)
        || (0x1DC0..=0x1DFF).contains(&u)
        || (0x20D0..=0x20FF).contains(&u)
        || (0xFE20..=0xFE2F).contains(&u)
}

/// Characters to set as text: each glyph's first code point in glyph order, marks and
/// controls left out.
fn sample_chars(font: &OutlinedFont) -> Vec<char> {
    font.glyphs
        .iter()
        .filter_map(|g| g.unicodes.first().copied())
        .filter(|&c| !is_combining_or_control(c) && c != ' ')
        .collect()
}

/// The kerning pairs that can be typed (both glyphs have a usable code point).
fn kern_strings(font: &OutlinedFont) -> Vec<(String, f64)> {
    font.kerning
        .iter()
        .filter_map(|k| {
            let first = |name: &str| {
                font.glyph(name)?
                    .unicodes
                    .iter()
                    .copied()
                    .find(|&c| !is_combining_or_control(c))
            };
            Some((format!("{}{}", first(&k.left)?, first(&k.right)?), k.value))
        })
        .collect()
}

/// The measured line: the sample characters, then the kerning pairs, separated by spaces
/// when the font has a space glyph.
pub fn specimen_text(font: &OutlinedFont) -> String {
    let sep = if font.glyph_for_char(' ').is_some() {
        " "
    } else {
        ""
    };
    let mut parts: Vec<String> = vec![sample_chars(font).into_iter().collect()];
    parts.extend(kern_strings(font).into_iter().map(|(s, _)| s));
    parts.retain(|p| !p.is_empty());
    parts.join(sep)
}

/// Width of `text` in font units: advances plus kerning between neighbours, as a shaper
/// applying the `kern` feature gives it.
fn text_width(font: &OutlinedFont, text: &str) -> f64 {
    let chars = font.char_map();
    let mut width = 0.0;
    let mut prev: Option<&str> = None;
    for c in text.chars() {
        let Some(glyph) = chars.get(&c) else {
            continue;
        };
        if let Some(p) = prev {
            width += font.kern(p, &glyph.name);
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
    let measure = specimen_text(font);
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
    html.push_str("</div>\n<h2>Kerning pairs</h2>\n<table class=\"pairs\">\n");
    html.push_str("<tr><th>kerned</th><th>not kerned</th><th>value</th></tr>\n");
    for (pair, value) in kern_strings(font) {
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
