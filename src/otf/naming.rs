//! Font naming from `font.toml`: the `name` table, the PostScript font name, the version
//! and the style facts (weight class, italic, bold) the other tables need.
//!
//! Records are Windows (3, 1, en-US) only, which every current consumer reads. A style
//! other than Regular, Italic, Bold or Bold Italic gets the typographic family/style
//! (IDs 16/17) and a legacy family with the style's non-italic words (ID 1) plus
//! Regular or Italic (ID 2). Weight class is read from the style's words (Thin … Black).

use write_fonts::tables::name::{Name, NameRecord};
use write_fonts::types::{NameId, Tag};

use crate::model::{FontInfo, DEFAULT_VENDOR};

/// Names and style facts derived from `font.toml`.
pub struct Naming {
    pub family: String,
    pub style: String,
    pub ps_name: String,
    pub full_name: String,
    pub version_text: String,
    pub revision: f64,
    pub weight: u16,
    pub italic: bool,
    /// Style is one of Regular, Italic, Bold, Bold Italic.
    pub ribbi: bool,
    /// OS/2 vendor ID, padded with spaces to four characters.
    pub vendor: Tag,
    /// The vendor ID as written in name ID 3 (without the padding).
    pub vendor_text: String,
}

impl Naming {
    pub fn new(info: &FontInfo) -> Self {
        let family = info.family.trim().to_owned();
        let style = info.style.trim().to_owned();
        let (revision, version_text) = parse_version(info.version.as_deref());
        let words: Vec<String> = style.split_whitespace().map(str::to_lowercase).collect();
        let italic = words.iter().any(|w| w == "italic" || w == "oblique");
        let weight = crate::model::weight_class(&style);
        let ribbi = matches!(
            style.as_str(),
            "Regular" | "Italic" | "Bold" | "Bold Italic"
        );
        let vendor_text = info
            .vendor
            .as_deref()
            .map(str::trim_end)
            .filter(|v| !v.is_empty())
            .unwrap_or(DEFAULT_VENDOR)
            .to_owned();
        Naming {
            vendor: vendor_tag(&vendor_text),
            vendor_text,
            ps_name: ps_font_name(&family, &style),
            full_name: format!("{family} {style}"),
            family,
            style,
            version_text,
            revision,
            weight,
            italic,
            ribbi,
        }
    }

    /// Bold in the RIBBI sense (style "Bold" or "Bold Italic").
    pub fn bold(&self) -> bool {
        self.ribbi && self.weight == 700
    }
}

/// A vendor ID as a tag: at most four bytes, padded with spaces. The loader accepts only
/// 1 to 4 printable ASCII characters; anything else (a model built in code) is cut or
/// replaced with `?` so the tag stays valid.
fn vendor_tag(text: &str) -> Tag {
    let mut bytes = [b' '; 4];
    for (slot, b) in bytes.iter_mut().zip(text.bytes()) {
        *slot = if (0x20..=0x7E).contains(&b) { b } else { b'?' };
    }
    Tag::new(&bytes)
}

/// `(font revision, name ID 5 text)`: `1.2` gives `(1.2, "Version 1.200")`; text that is
/// not a number is kept after a default `Version 1.000; `.
fn parse_version(version: Option<&str>) -> (f64, String) {
    let Some(text) = version.map(str::trim) else {
        return (1.0, "Version 1.000".into());
    };
    let bare = text.strip_prefix("Version ").unwrap_or(text);
    match bare.parse::<f64>() {
        Ok(v) if v.is_finite() && (0.0..32768.0).contains(&v) => (v, format!("Version {v:.3}")),
        _ => (1.0, format!("Version 1.000; {text}")),
    }
}

/// PostScript font name: `Family-Style` without spaces, printable ASCII other than
/// `[](){}<>/%`, at most 63 characters.
pub(crate) fn ps_font_name(family: &str, style: &str) -> String {
    let clean = |s: &str| -> String {
        s.chars()
            .filter(|c| c.is_ascii_graphic() && !"[](){}<>/%".contains(*c))
            .collect()
    };
    let mut family = clean(family);
    if family.is_empty() {
        family = "Untitled".into();
    }
    let style = clean(style);
    let mut name = if style.is_empty() {
        family
    } else {
        format!("{family}-{style}")
    };
    name.truncate(63);
    name
}

/// Windows (3, 1, en-US) name records, sorted by name ID.
pub fn name_table(info: &FontInfo, naming: &Naming) -> Name {
    let mut records: Vec<(u16, String)> = Vec::new();
    if let Some(c) = &info.copyright {
        records.push((0, c.clone()));
    }
    let (family1, style2) = if naming.ribbi {
        (naming.family.clone(), naming.style.clone())
    } else {
        let rest: Vec<&str> = naming
            .style
            .split_whitespace()
            .filter(|w| !w.eq_ignore_ascii_case("italic"))
            .collect();
        let style2 = if naming.italic { "Italic" } else { "Regular" };
        let family1 = if rest.is_empty() {
            naming.family.clone()
        } else {
            format!("{} {}", naming.family, rest.join(" "))
        };
        (family1, style2.to_owned())
    };
    records.push((1, family1));
    records.push((2, style2));
    let short_version = naming
        .version_text
        .strip_prefix("Version ")
        .unwrap_or(&naming.version_text)
        .split(';')
        .next()
        .unwrap_or("1.000")
        .to_owned();
    records.push((
        3,
        format!("{short_version};{};{}", naming.vendor_text, naming.ps_name),
    ));
    records.push((4, naming.full_name.clone()));
    records.push((5, naming.version_text.clone()));
    records.push((6, naming.ps_name.clone()));
    if let Some(d) = &info.designer {
        records.push((9, d.clone()));
    }
    if let Some(license) = &info.license {
        records.push((13, license.clone()));
    }
    if let Some(url) = &info.license_url {
        records.push((14, url.clone()));
    }
    if !naming.ribbi {
        records.push((16, naming.family.clone()));
        records.push((17, naming.style.clone()));
    }
    Name::new(
        records
            .into_iter()
            .map(|(id, text)| NameRecord::new(3, 1, 0x409, NameId::new(id), text.into()))
            .collect(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn versions() {
        assert_eq!(parse_version(None), (1.0, "Version 1.000".into()));
        assert_eq!(parse_version(Some("1.2")), (1.2, "Version 1.200".into()));
        assert_eq!(
            parse_version(Some("Version 2.015")),
            (2.015, "Version 2.015".into())
        );
        assert_eq!(
            parse_version(Some("beta 3")),
            (1.0, "Version 1.000; beta 3".into())
        );
    }

    #[test]
    fn vendor_ids_and_licence_names() {
        let mut info = crate::model::test_info();
        assert_eq!(Naming::new(&info).vendor, Tag::new(b"XGLY"));
        info.vendor = Some("AB".into());
        info.license = Some("OFL 1.1".into());
        info.license_url = Some("https://openfontlicense.org".into());
        let naming = Naming::new(&info);
        assert_eq!(naming.vendor, Tag::new(b"AB  "));
        let records: Vec<(u16, String)> = name_table(&info, &naming)
            .name_record
            .iter()
            .map(|r| (r.name_id.to_u16(), r.string.to_string()))
            .collect();
        assert!(records.contains(&(3, "1.000;AB;Test-Regular".into())));
        assert!(records.contains(&(13, "OFL 1.1".into())));
        assert!(records.contains(&(14, "https://openfontlicense.org".into())));
        assert_eq!(vendor_tag("é"), Tag::new(b"??  "));
    }

    #[test]
    fn postscript_font_names() {
        assert_eq!(ps_font_name("Mini Test", "Regular"), "MiniTest-Regular");
        assert_eq!(ps_font_name("A (b) c%", "Bold Italic"), "Abc-BoldItalic");
        assert_eq!(ps_font_name("Größe", ""), "Gre");
        assert_eq!(ps_font_name(&"x".repeat(80), "Regular").len(), 63);
    }
}
