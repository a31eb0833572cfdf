//! Glyph names, and file names for glyphs.
//!
//! Glyph names follow the OpenType `post` rule ([`glyph_name_problem`]); the loader refuses
//! any other name, so every output (the `post` table, the CFF charset, the SVG font's
//! kerning lists, file names) can carry each name unchanged.
//!
//! File names are safe on case-insensitive file systems and on Windows: the UFO 3 "user
//! name to file name" rule, as norad implements it ([`norad::user_name_to_file_name`]), so
//! glyph sources, the SVG glyph set and an exported UFO's `.glif` files share their stems.
//! Every uppercase letter is followed by `_` (so `A` -> `A_` and `a` -> `a`, which never
//! collide when case is folded), characters illegal in file names become `_`, a leading `.`
//! becomes `_`, reserved device names (`con`, `nul`, `com1`, ...) get a `_` prefix, and a
//! clash gets a two-digit counter (`a_b01`). Two additions of ours: the font directory's own
//! file stems (`font`, `kerning`) get a `_` prefix, and past norad's 99 counters a clash
//! gets `.100`, `.101`, ... instead of norad's panic.

/// Stems of a font directory's own files (`font.toml`, `kerning.toml`), which a glyph file
/// must never take (compared case-insensitively).
const FONT_FILE_STEMS: &[&str] = &["font", "kerning"];

/// Longest glyph name: the OpenType `post` specification's limit.
pub const MAX_GLYPH_NAME: usize = 63;

/// Why a glyph name breaks the OpenType `post` rule: 1 to 63 characters from
/// `A-Z a-z 0-9 . _`, not starting with a digit or a period (`.notdef` and `.null`
/// excepted). `None` for a valid name.
pub fn glyph_name_problem(name: &str) -> Option<String> {
    if name == ".notdef" || name == ".null" {
        return None;
    }
    let rule = "glyph names are 1 to 63 characters from A-Z a-z 0-9 . _ (the OpenType `post` rule)";
    let chars = name.chars().count();
    if let Some(bad) = name
        .chars()
        .find(|&c| !(c.is_ascii_alphanumeric() || c == '.' || c == '_'))
    {
        Some(format!("contains {}; {rule}", describe(bad)))
    } else if chars > MAX_GLYPH_NAME {
        Some(format!("has {chars} characters; {rule}"))
    } else if name.starts_with(|c: char| c.is_ascii_digit()) {
        Some(format!(
            "starts with a digit; {rule}, not starting with a digit"
        ))
    } else if name.starts_with('.') {
        Some("starts with `.`; only `.notdef` and `.null` may (the OpenType `post` rule)".into())
    } else if name.is_empty() {
        Some(format!("is empty; {rule}"))
    } else {
        None
    }
}

/// Whether `name` follows the OpenType `post` rule (see [`glyph_name_problem`]).
pub fn is_valid_glyph_name(name: &str) -> bool {
    glyph_name_problem(name).is_none()
}

/// A glyph name that follows the rule, made from any text (an SVG file's stem): every
/// other character becomes `_`, a leading digit or `.` gets a `_` in front, and the result
/// is cut to [`MAX_GLYPH_NAME`] characters. `arrow-left` -> `arrow_left`, `1st` -> `_1st`.
pub fn glyph_name_from(text: &str) -> String {
    if is_valid_glyph_name(text) {
        return text.to_string();
    }
    let mut name: String = text
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '.' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect();
    if name.is_empty() || name.starts_with(|c: char| c.is_ascii_digit() || c == '.') {
        name.insert(0, '_');
    }
    name.truncate(MAX_GLYPH_NAME);
    name
}

/// A character for a message: `` `,` ``, or its code point when it does not print.
fn describe(c: char) -> String {
    if c.is_control() || c.is_whitespace() {
        format!("U+{:04X}", u32::from(c))
    } else {
        format!("`{c}`")
    }
}

/// The file stem (no extension) for one glyph name.
///
/// Distinct names can still map to one stem (`a/b` and `a:b` both give `a_b`); use
/// [`file_stems`] for a whole glyph set.
pub fn file_stem(name: &str) -> String {
    stem_with(name, |_| true)
}

/// [`file_stem`] with norad's clash counter, asking `accept` (given the lowercased
/// candidate, font-file prefix applied) whether a candidate is free.
fn stem_with(name: &str, mut accept: impl FnMut(&str) -> bool) -> String {
    // Control characters cannot be in a UFO name; norad leaves them, so replace them first.
    let clean: String = name
        .chars()
        .map(|c| if c.is_control() { '_' } else { c })
        .collect();
    let stem = norad::user_name_to_file_name(&clean, "", "", |candidate| {
        accept(&font_file_safe(candidate))
    });
    font_file_safe(&stem.to_string_lossy())
}

/// `stem` with a `_` in front when it is a font directory's own file stem.
fn font_file_safe(stem: &str) -> String {
    if FONT_FILE_STEMS.contains(&stem.to_lowercase().as_str()) {
        format!("_{stem}")
    } else {
        stem.to_string()
    }
}

/// File stems for a whole glyph set, in the same order as `names`, unique even when
/// compared case-insensitively (a clash gets norad's counter: `a_b`, `a_b01`, ...).
pub fn file_stems<'a>(names: impl IntoIterator<Item = &'a str>) -> Vec<String> {
    let mut taken = std::collections::HashSet::new();
    names
        .into_iter()
        .map(|name| {
            let mut tries = 0;
            // Accepting the 100th candidate stops norad before its panic; a clash left
            // then gets a counter of ours.
            let base = stem_with(name, |candidate| {
                tries += 1;
                !taken.contains(&candidate.to_lowercase()) || tries == 100
            });
            if taken.insert(base.to_lowercase()) {
                return base;
            }
            let plain = file_stem(name);
            (100..)
                .map(|n| format!("{plain}.{n}"))
                .find(|stem| taken.insert(stem.to_lowercase()))
                .unwrap_or(plain)
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
        assert_eq!(file_stems(["font", "_font"]), ["_font", "_font01"]);
    }

    #[test]
    fn post_rule() {
        for ok in [
            ".notdef", ".null", "A", "a.sc", "uni00E9", "f_f_i", "x2", "_part",
        ] {
            assert_eq!(glyph_name_problem(ok), None, "{ok}");
        }
        let rule =
            "glyph names are 1 to 63 characters from A-Z a-z 0-9 . _ (the OpenType `post` rule)";
        let long = "a".repeat(64);
        for (bad, why) in [
            ("a,b", format!("contains `,`; {rule}")),
            ("a b", format!("contains U+0020; {rule}")),
            ("a\u{1b}", format!("contains U+001B; {rule}")),
            ("é", format!("contains `é`; {rule}")),
            (long.as_str(), format!("has 64 characters; {rule}")),
            (
                "1a",
                format!("starts with a digit; {rule}, not starting with a digit"),
            ),
            (
                ".hidden",
                "starts with `.`; only `.notdef` and `.null` may (the OpenType `post` rule)"
                    .to_string(),
            ),
            ("", format!("is empty; {rule}")),
        ] {
            assert_eq!(glyph_name_problem(bad), Some(why), "{bad}");
            assert!(!is_valid_glyph_name(bad));
        }
        assert!(is_valid_glyph_name(&"a".repeat(63)));
        for (text, name) in [
            ("arrow-left", "arrow_left"),
            ("1st", "_1st"),
            (".hidden", "_.hidden"),
            ("é b", "__b"),
            ("", "_"),
            ("a.sc", "a.sc"),
        ] {
            assert_eq!(glyph_name_from(text), name);
            assert!(is_valid_glyph_name(&glyph_name_from(text)));
        }
        assert_eq!(glyph_name_from(&"-".repeat(100)), "_".repeat(63));
    }

    #[test]
    fn stems_unique_case_insensitively() {
        let stems = file_stems(["a/b", "a:b", "A", "a"]);
        assert_eq!(stems, ["a_b", "a_b01", "A_", "a"]);
        // Past norad's 99 counters: ours, never a panic. Each of these 128 names spells
        // `abcdefg` with a capital or a lowercase letter plus `_`, so all share one stem
        // when case is folded.
        let names: Vec<String> = (0..128u32)
            .map(|bits| {
                "abcdefg"
                    .chars()
                    .enumerate()
                    .map(|(i, c)| {
                        if bits & (1 << i) != 0 {
                            c.to_ascii_uppercase().to_string()
                        } else {
                            format!("{c}_")
                        }
                    })
                    .collect()
            })
            .collect();
        let stems = file_stems(names.iter().map(String::as_str));
        let folded: std::collections::HashSet<String> =
            stems.iter().map(|s| s.to_lowercase()).collect();
        assert_eq!(folded.len(), 128);
        assert_eq!(stems[1], "A_b_c_d_e_f_g_01");
        assert_eq!(stems[99], "A_B_c_d_e_F_G_99");
        assert_eq!(stems[100], "a_b_C_d_e_F_G_.100");
        assert_eq!(stems[127], "A_B_C_D_E_F_G_.127");
    }
}
