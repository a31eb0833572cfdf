//! PostScript glyph names for `post` (format 2) and the CFF charset.
//!
//! The OpenType `post` specification restricts names to 1–63 characters from
//! `A–Z a–z 0–9 . _`, not starting with a digit or a period (`.notdef` and `.null` excepted).
//! The loader refuses names that break the rule ([`crate::names::glyph_name_problem`]), so
//! for loaded fonts the names pass unchanged. For a model built another way, a name that
//! breaks the rule is replaced by `uniXXXX` / `uXXXXX` from its first
//! code point, else `glyphN` (N = glyph id); a replacement that collides with another name
//! gets a `.altN` suffix.

use std::collections::BTreeSet;

use super::OtGlyph;

/// The rule lives with the other naming rules; the loader refuses names that break it.
pub use crate::names::is_valid_glyph_name;

/// The PostScript name of each glyph, unique, in glyph order.
pub(crate) fn ps_names(glyphs: &[OtGlyph]) -> Vec<String> {
    let mut taken: BTreeSet<String> = glyphs
        .iter()
        .filter(|g| is_valid_glyph_name(&g.model_name))
        .map(|g| g.model_name.clone())
        .collect();
    glyphs
        .iter()
        .enumerate()
        .map(|(gid, glyph)| {
            if is_valid_glyph_name(&glyph.model_name) {
                return glyph.model_name.clone();
            }
            let base = match glyph.unicodes.first() {
                Some(&c) if u32::from(c) <= 0xFFFF => format!("uni{:04X}", u32::from(c)),
                Some(&c) => format!("u{:05X}", u32::from(c)),
                None => format!("glyph{gid}"),
            };
            let mut name = base.clone();
            let mut n = 1;
            while taken.contains(&name) {
                name = format!("{base}.alt{n}");
                n += 1;
            }
            taken.insert(name.clone());
            name
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn glyph(name: &str, unicodes: &[char]) -> OtGlyph<'static> {
        OtGlyph {
            model_name: name.into(),
            ps_name: String::new(),
            unicodes: unicodes.to_vec(),
            advance: 0,
            path: crate::otf::OtPath::Given(std::borrow::Cow::Owned(kurbo::BezPath::new())),
            from_components: false,
            anchors: Vec::new(),
            outline_mark: false,
        }
    }

    #[test]
    fn validity() {
        for ok in [".notdef", "A", "a.sc", "uni00E9", "f_f_i", "x2"] {
            assert!(is_valid_glyph_name(ok), "{ok}");
        }
        let long = "a".repeat(64);
        for bad in ["", "1a", ".hidden", "a-b", "é", "a b", long.as_str()] {
            assert!(!is_valid_glyph_name(bad), "{bad}");
        }
    }

    #[test]
    fn invalid_names_fall_back() {
        let glyphs = [
            glyph(".notdef", &[]),
            glyph("a-b", &['\u{E9}']),
            glyph("smile face", &['\u{1F600}']),
            glyph("9", &[]),
            glyph("uni00E9", &['\u{E8}']),
            glyph("é", &['\u{E9}']),
        ];
        assert_eq!(
            ps_names(&glyphs),
            [
                ".notdef",
                "uni00E9.alt1",
                "u1F600",
                "glyph3",
                "uni00E9",
                "uni00E9.alt2"
            ]
        );
    }
}
