//! Sources out: the typed model -> canonical TOML text (the inverse of [`super::load_font`]).
//!
//! One layout for everything xglyph writes (`fmt`, `import`): keys in a fixed order, one
//! control point per line, numbers in their shortest round-tripping form (`280`, `12.5`,
//! never `280.0` or `-0`), code points as `0x` hex. Loading the text gives back the same model.
//! Written by hand rather than through `toml::to_string`: serde output cannot put one point
//! per line or choose hex for code points.

use std::fmt::Write;

use crate::designspace::{Designspace, Location};
use crate::model::{Font, FontInfo, Glyph, KernPair, Master};
use crate::names::file_stems;

/// Every source file of `font` as `(file name, text)`: `font.toml`, one `<stem>.toml` per
/// glyph (stems by `names::file_stems`), `kerning.toml` when there is kerning, and
/// `features.fea` as it was read.
pub fn font_sources(font: &Font) -> Vec<(String, String)> {
    let mut files = vec![("font.toml".to_string(), font_toml(&font.info))];
    let stems = file_stems(font.glyphs.iter().map(|g| g.name.as_str()));
    for (glyph, stem) in font.glyphs.iter().zip(stems) {
        files.push((format!("{stem}.toml"), glyph_toml(glyph)));
    }
    if !font.kerning.is_empty() {
        files.push(("kerning.toml".to_string(), kerning_toml(&font.kerning)));
    }
    if let Some(features) = &font.features {
        files.push(("features.fea".to_string(), features.text.clone()));
    }
    files
}

/// `font.toml`: metadata and metrics.
pub fn font_toml(info: &FontInfo) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "family = {}", string(&info.family));
    let _ = writeln!(out, "style = {}", string(&info.style));
    let _ = writeln!(out, "units_per_em = {}", info.units_per_em);
    let _ = writeln!(out, "ascender = {}", number(info.ascender));
    let _ = writeln!(out, "descender = {}", number(info.descender));
    let _ = writeln!(out, "x_height = {}", number(info.x_height));
    let _ = writeln!(out, "cap_height = {}", number(info.cap_height));
    let _ = writeln!(out, "tolerance = {}", number(info.tolerance));
    for (key, value) in [
        ("copyright", &info.copyright),
        ("designer", &info.designer),
        ("version", &info.version),
        ("license", &info.license),
        ("license_url", &info.license_url),
        ("vendor", &info.vendor),
    ] {
        if let Some(value) = value {
            let _ = writeln!(out, "{key} = {}", string(value));
        }
    }
    out
}

/// `font.toml` of a font with masters: [`font_toml`], then the `[[axis]]`, `[[master]]` and
/// `[[instance]]` and `[[rule]]` tables in model order. Without axes it is [`font_toml`].
pub fn family_font_toml(info: &FontInfo, designspace: &Designspace, masters: &[Master]) -> String {
    let mut out = font_toml(info);
    if designspace.rules_last {
        let _ = writeln!(out, "rules_processing = \"last\"");
    }
    for a in &designspace.axes {
        let _ = writeln!(out, "\n[[axis]]");
        let _ = writeln!(out, "tag = {}", string(&a.tag));
        let _ = writeln!(out, "name = {}", string(&a.name));
        let _ = writeln!(out, "min = {}", number(a.min));
        let _ = writeln!(out, "default = {}", number(a.default));
        let _ = writeln!(out, "max = {}", number(a.max));
        if !a.map.is_empty() {
            let pairs: Vec<String> = a
                .map
                .iter()
                .map(|&(u, d)| format!("[{}, {}]", number(u), number(d)))
                .collect();
            let _ = writeln!(out, "map = [{}]", pairs.join(", "));
        }
    }
    for m in masters {
        let _ = writeln!(out, "\n[[master]]");
        let _ = writeln!(out, "name = {}", string(&m.name));
        let folder = m.folder.to_string_lossy();
        let _ = writeln!(out, "folder = {}", string(&folder));
        let _ = writeln!(out, "location = {}", location(designspace, &m.location));
        if m.sparse {
            let _ = writeln!(out, "sparse = true");
        }
    }
    for i in &designspace.instances {
        let _ = writeln!(out, "\n[[instance]]");
        let _ = writeln!(out, "name = {}", string(&i.name));
        let _ = writeln!(out, "location = {}", location(designspace, &i.location));
    }
    for r in &designspace.rules {
        let _ = writeln!(out, "\n[[rule]]");
        let _ = writeln!(out, "name = {}", string(&r.name));
        // Each box's ranges in axis order.
        let boxes: Vec<String> = r
            .conditions
            .iter()
            .map(|b| {
                let ranges: Vec<String> = designspace
                    .axes
                    .iter()
                    .filter_map(|a| {
                        let (min, max) = b.get(&a.tag)?;
                        Some(format!(
                            "{} = [{}, {}]",
                            key(&a.tag),
                            number(*min),
                            number(*max)
                        ))
                    })
                    .collect();
                format!("{{ {} }}", ranges.join(", "))
            })
            .collect();
        let _ = writeln!(out, "conditions = [{}]", boxes.join(", "));
        let subs: Vec<String> = r
            .substitutions
            .iter()
            .map(|(from, to)| format!("{} = {}", key(from), string(to)))
            .collect();
        let _ = writeln!(out, "substitutions = {{ {} }}", subs.join(", "));
    }
    out
}

/// An inline table of the coordinates `location` writes, in axis order:
/// `{ wght = 700 }`.
fn location(designspace: &Designspace, location: &Location) -> String {
    let items: Vec<String> = designspace
        .axes
        .iter()
        .filter_map(|a| {
            let v = location.0.get(&a.tag)?;
            Some(format!("{} = {}", key(&a.tag), number(*v)))
        })
        .collect();
    if items.is_empty() {
        "{}".to_string()
    } else {
        format!("{{ {} }}", items.join(", "))
    }
}

/// A computed value for a message, at 6 decimals ([`number`] of the rounded value): check
/// positions are computed, so 116.8 can come out as 116.80000000000001.
pub fn computed_number(x: f64) -> String {
    number((x * 1e6).round() / 1e6)
}

/// A TOML key: bare when it can be, else quoted.
fn key(k: &str) -> String {
    let bare = !k.is_empty()
        && k.chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-');
    if bare {
        k.to_string()
    } else {
        string(k)
    }
}

/// One glyph file: name, code points, advance, `mark`, contours, components, anchors.
pub fn glyph_toml(glyph: &Glyph) -> String {
    glyph_text(glyph, true, true, &[])
}

/// A glyph file of a non-default master that leaves out `unicode` and `mark` (a master's
/// glyph has the default's): [`glyph_toml`] without them.
pub fn master_glyph_toml(glyph: &Glyph) -> String {
    glyph_text(glyph, false, false, &[])
}

/// A glyph file as `fmt` rewrites it: [`glyph_toml`], with `unicode` only when `unicodes`,
/// and an `offset` only for the components whose entry in `offsets_written` is true (or
/// missing): a component placed by anchors stays without one.
pub fn glyph_source(glyph: &Glyph, unicodes: bool, offsets_written: &[bool]) -> String {
    glyph_text(glyph, unicodes, true, offsets_written)
}

fn glyph_text(glyph: &Glyph, unicodes: bool, mark: bool, offsets_written: &[bool]) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "name = {}", string(&glyph.name));
    let shown: &[char] = if unicodes { &glyph.unicodes } else { &[] };
    match shown {
        [] => {}
        [c] => {
            let _ = writeln!(out, "unicode = {}", code_point(*c));
        }
        many => {
            let list: Vec<_> = many.iter().map(|&c| code_point(c)).collect();
            let _ = writeln!(out, "unicode = [{}]", list.join(", "));
        }
    }
    let _ = writeln!(out, "advance = {}", number(glyph.advance));
    if mark && glyph.outline_mark {
        out.push_str("mark = \"outline\"\n");
    }
    for contour in &glyph.contours {
        out.push_str("\n[[contour]]\npoints = [\n");
        for p in contour.points() {
            let _ = writeln!(
                out,
                "  [{}, {}, {}],",
                number(p.pos.x),
                number(p.pos.y),
                number(p.s)
            );
        }
        out.push_str("]\n");
    }
    for (k, component) in glyph.components.iter().enumerate() {
        let _ = writeln!(out, "\n[[component]]");
        let _ = writeln!(out, "base = {}", string(&component.base));
        if offsets_written.get(k).copied().unwrap_or(true) {
            let (x, y) = component.offset;
            let _ = writeln!(out, "offset = [{}, {}]", number(x), number(y));
        }
    }
    for anchor in &glyph.anchors {
        let _ = writeln!(out, "\n[[anchor]]");
        let _ = writeln!(out, "name = {}", string(&anchor.name));
        let (x, y) = anchor.position;
        let _ = writeln!(out, "position = [{}, {}]", number(x), number(y));
    }
    out
}

/// `kerning.toml`: one `[[pair]]` table per pair, in model order.
pub fn kerning_toml(pairs: &[KernPair]) -> String {
    let mut out = String::new();
    for (i, pair) in pairs.iter().enumerate() {
        if i > 0 {
            out.push('\n');
        }
        let _ = writeln!(out, "[[pair]]");
        let _ = writeln!(out, "left = {}", string(&pair.left));
        let _ = writeln!(out, "right = {}", string(&pair.right));
        let _ = writeln!(out, "value = {}", number(pair.value));
    }
    out
}

/// The shortest decimal that reads back as the same `f64`, without `.0` or `-0`.
///
/// Limit: the model never holds non-finite numbers (the loader rejects them); one would be
/// written as `nan`/`inf`, which TOML reads back but the loader refuses.
pub fn number(x: f64) -> String {
    if x == 0.0 {
        return "0".to_string();
    }
    if x.is_nan() {
        return "nan".to_string();
    }
    if x.is_infinite() {
        return if x > 0.0 { "inf" } else { "-inf" }.to_string();
    }
    // `Display` for f64 is the shortest round-tripping form and never uses an exponent.
    format!("{x}")
}

/// A code point as TOML hex, at least four digits (`0x0041`).
pub fn code_point(c: char) -> String {
    format!("0x{:04X}", u32::from(c))
}

/// A TOML basic string with every character that needs it escaped.
pub fn string(s: &str) -> String {
    let mut out = String::with_capacity(s.len() + 2);
    out.push('"');
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\t' => out.push_str("\\t"),
            '\r' => out.push_str("\\r"),
            c if c.is_control() => {
                let _ = write!(out, "\\u{:04X}", u32::from(c));
            }
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_shortest_round_trip() {
        assert_eq!(number(280.0), "280");
        assert_eq!(number(-0.0), "0");
        assert_eq!(number(12.5), "12.5");
        assert_eq!(number(0.1), "0.1");
        assert_eq!(number(-1.0 / 3.0), "-0.3333333333333333");
        assert_eq!(number(1e-7), "0.0000001");
        for x in [0.1, 1.0 / 3.0, 123456.789, 1e-12, 9.5e15, -2.5e-3] {
            assert_eq!(number(x).parse::<f64>().ok(), Some(x));
        }
    }

    #[test]
    fn strings_escape() {
        assert_eq!(string(r#"a"b\c"#), r#""a\"b\\c""#);
        assert_eq!(string("x\u{7}y\nz"), r#""x\u0007y\nz""#);
        assert_eq!(code_point('A'), "0x0041");
        assert_eq!(code_point('\u{1F600}'), "0x1F600");
    }
}
