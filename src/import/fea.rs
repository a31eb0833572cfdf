//! A UFO's `features.fea` made to stand alone in the sources: `include(...)` statements
//! replaced by the files they name, and glyph names the import renamed renamed here too.
//!
//! Written here rather than with fea-rs: its parser gives a lossless tree, but rewriting
//! tokens in it and printing it back is more machinery than this one pass needs, and the
//! text must stay as the designer wrote it (comments, layout) apart from the replaced
//! names. The pass knows comments (`#` to the end of the line) and strings (`"…"`); a name
//! is a run of `A–Z a–z 0–9 . _ -` (with an optional `\` escape before it); class names
//! (`@…`) are not glyph names and are left alone.
//!
//! Includes are looked up as ufo2ft (feaLib's `includeDir`) does: next to the `.ufo`
//! folder, then inside it. Limits: a glyph range written without spaces (`a-z`) whose
//! ends are renamed is not rewritten (it is one name to this pass); includes nest at most
//! [`MAX_DEPTH`] deep.

use std::collections::HashMap;
use std::path::Path;

/// How deep includes may nest (a cycle stops here).
pub const MAX_DEPTH: usize = 32;

/// `text` with its includes inlined (looked up in `dirs`, in order) and every name in
/// `renamed` replaced; an error names an include that cannot be read.
pub fn stand_alone(
    text: &str,
    dirs: &[&Path],
    renamed: &HashMap<String, String>,
) -> Result<String, String> {
    carry(text, dirs, renamed, 0)
}

fn carry(
    text: &str,
    dirs: &[&Path],
    renamed: &HashMap<String, String>,
    depth: usize,
) -> Result<String, String> {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(c) = rest.chars().next() {
        if c == '#' {
            let end = rest.find('\n').unwrap_or(rest.len());
            out.push_str(&rest[..end]);
            rest = &rest[end..];
        } else if c == '"' {
            let end = rest[1..].find('"').map_or(rest.len(), |i| i + 2);
            out.push_str(&rest[..end]);
            rest = &rest[end..];
        } else if c == '@' {
            let end = 1 + name_len(&rest[1..]);
            out.push_str(&rest[..end]);
            rest = &rest[end..];
        } else if c == '\\' || is_name_char(c) {
            let skip = usize::from(c == '\\');
            let end = skip + name_len(&rest[skip..]);
            let name = &rest[skip..end];
            if skip == 0 && name == "include" {
                if let Some((path, after)) = include_statement(&rest[end..]) {
                    if depth >= MAX_DEPTH {
                        return Err(format!(
                            "features.fea: includes nest more than {MAX_DEPTH} deep (at `{path}`)"
                        ));
                    }
                    let included = read_include(path, dirs)?;
                    out.push_str(&carry(&included, dirs, renamed, depth + 1)?);
                    if !out.ends_with('\n') {
                        out.push('\n');
                    }
                    rest = after;
                    continue;
                }
            }
            out.push_str(&rest[..skip]);
            out.push_str(renamed.get(name).map_or(name, String::as_str));
            rest = &rest[end..];
        } else {
            out.push(c);
            rest = &rest[c.len_utf8()..];
        }
    }
    Ok(out)
}

fn is_name_char(c: char) -> bool {
    c.is_ascii_alphanumeric() || matches!(c, '.' | '_' | '-')
}

fn name_len(s: &str) -> usize {
    s.find(|c: char| !is_name_char(c)).unwrap_or(s.len())
}

/// After the keyword `include`: `( path )` and an optional `;`; the path and what follows.
fn include_statement(s: &str) -> Option<(&str, &str)> {
    let s = s.trim_start().strip_prefix('(')?;
    let close = s.find(')')?;
    let path = s[..close].trim();
    let after = s[close + 1..].trim_start();
    Some((path, after.strip_prefix(';').unwrap_or(after)))
}

fn read_include(path: &str, dirs: &[&Path]) -> Result<String, String> {
    let wanted = Path::new(path);
    let found = if wanted.is_absolute() {
        Some(wanted.to_path_buf())
    } else {
        dirs.iter().map(|d| d.join(wanted)).find(|p| p.is_file())
    };
    let Some(file) = found else {
        return Err(format!(
            "features.fea includes `{path}`, which is not next to the UFO nor inside it"
        ));
    };
    std::fs::read_to_string(&file)
        .map_err(|e| format!("features.fea includes `{}`: {e}", file.display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_renamed_outside_comments_strings_and_classes() {
        let renamed: HashMap<String, String> = [("beh-ar", "beh_ar"), ("a.sc", "a.sc")]
            .into_iter()
            .map(|(a, b)| (a.to_string(), b.to_string()))
            .collect();
        let text = "@beh-ar = [beh-ar a.sc];\n# beh-ar in a comment\nsub \\beh-ar by a.sc; \
                    name \"beh-ar\";\n";
        assert_eq!(
            stand_alone(text, &[], &renamed).unwrap(),
            "@beh-ar = [beh_ar a.sc];\n# beh-ar in a comment\nsub \\beh_ar by a.sc; \
             name \"beh-ar\";\n"
        );
    }

    #[test]
    fn includes_are_inlined_from_the_first_folder_that_has_them() {
        let dir = tempfile::tempdir().unwrap();
        let (outer, inner) = (dir.path().join("outer"), dir.path().join("inner"));
        std::fs::create_dir_all(&outer).unwrap();
        std::fs::create_dir_all(&inner).unwrap();
        std::fs::write(
            outer.join("a.fea"),
            "include (b.fea) ;\nlanguagesystem DFLT dflt;",
        )
        .unwrap();
        std::fs::write(inner.join("b.fea"), "# b").unwrap();
        let text = "include(a.fea);\nfeature liga { } liga;";
        let renamed = HashMap::new();
        let dirs = [outer.as_path(), inner.as_path()];
        assert_eq!(
            stand_alone(text, &dirs, &renamed).unwrap(),
            "# b\n\nlanguagesystem DFLT dflt;\n\nfeature liga { } liga;"
        );
        // A file that includes itself stops at the depth limit, with a message.
        std::fs::write(outer.join("loop.fea"), "include(loop.fea);").unwrap();
        let err = stand_alone("include(loop.fea);", &dirs, &renamed).unwrap_err();
        assert_eq!(
            err,
            "features.fea: includes nest more than 32 deep (at `loop.fea`)"
        );
        let err = stand_alone("include(gone.fea);", &dirs, &renamed).unwrap_err();
        assert_eq!(
            err,
            "features.fea includes `gone.fea`, which is not next to the UFO nor inside it"
        );
    }
}
