//! File names for glyphs: safe on case-insensitive file systems and on Windows.
//!
//! The rule is the UFO 3 "user name to file name" convention: every uppercase letter is
//! followed by `_` (so `A` -> `A_` and `a` -> `a`, which never collide when case is folded),
//! characters illegal in file names are replaced by `_`, a leading `.` becomes `_`, and
//! reserved device names (`con`, `nul`, `com1`, ...) and the font directory's own file
//! stems (`font`, `kerning`) get a `_` prefix. Glyph sources and the
//! SVG glyph set use the same stems. Written here rather than taken from a crate: no
//! maintained Rust crate implements the UFO rule.

/// Characters that are illegal in a file name on at least one common file system.
const ILLEGAL: &[char] = &['"', '*', '+', '/', ':', '<', '>', '?', '[', '\\', ']', '|'];

/// Windows device names, reserved with any extension (compared case-insensitively).
const RESERVED: &[&str] = &[
    "con", "prn", "aux", "clock$", "nul", "com1", "com2", "com3", "com4", "com5", "com6", "com7",
    "com8", "com9", "lpt1", "lpt2", "lpt3", "lpt4", "lpt5", "lpt6", "lpt7", "lpt8", "lpt9",
];

/// Stems of a font directory's own files (`font.toml`, `kerning.toml`), which a glyph file
/// must never take (compared case-insensitively).
const FONT_FILE_STEMS: &[&str] = &["font", "kerning"];

/// The file stem (no extension) for one glyph name.
///
/// Distinct names can still map to one stem (`a/b` and `a:b` both give `a_b`); use
/// [`file_stems`] for a whole glyph set.
pub fn file_stem(name: &str) -> String {
    let mut stem = String::with_capacity(name.len() + 4);
    for (i, c) in name.chars().enumerate() {
        if (i == 0 && c == '.') || c.is_control() || ILLEGAL.contains(&c) {
            stem.push('_');
        } else {
            stem.push(c);
            if c.is_uppercase() {
                stem.push('_');
            }
        }
    }
    let head = stem.split('.').next().unwrap_or("");
    if RESERVED.contains(&head.to_lowercase().as_str())
        || FONT_FILE_STEMS.contains(&stem.to_lowercase().as_str())
    {
        stem.insert(0, '_');
    }
    stem
}

/// File stems for a whole glyph set, in the same order as `names`, unique even when
/// compared case-insensitively (a clash gets a numeric suffix: `a_b`, `a_b.1`, ...).
pub fn file_stems<'a>(names: impl IntoIterator<Item = &'a str>) -> Vec<String> {
    let mut taken = std::collections::HashSet::new();
    names
        .into_iter()
        .map(|name| {
            let base = file_stem(name);
            let mut stem = base.clone();
            let mut n = 1;
            while !taken.insert(stem.to_lowercase()) {
                stem = format!("{base}.{n}");
                n += 1;
            }
            stem
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ufo_convention() {
        assert_eq!(file_stem("A"), "A_");
        assert_eq!(file_stem("a"), "a");
        assert_eq!(file_stem("AE"), "A_E_");
        assert_eq!(file_stem(".notdef"), "_notdef");
        assert_eq!(file_stem("a/b:c"), "a_b_c");
        assert_eq!(file_stem("con"), "_con");
        assert_eq!(file_stem("aux.alt"), "_aux.alt");
        assert_eq!(file_stem("Aux"), "A_ux");
        assert_eq!(file_stem("<&\">"), "_&__");
        // A glyph file never takes the name of font.toml or kerning.toml.
        assert_eq!(file_stem("font"), "_font");
        assert_eq!(file_stem("kerning"), "_kerning");
        assert_eq!(file_stem("font.alt"), "font.alt");
        assert_eq!(file_stems(["font", "_font"]), ["_font", "_font.1"]);
    }

    #[test]
    fn stems_unique_case_insensitively() {
        let stems = file_stems(["a/b", "a:b", "A", "a"]);
        assert_eq!(stems, ["a_b", "a_b.1", "A_", "a"]);
    }
}
