//! The rewrite `xglyph fmt` performs: every source file in the canonical layout of
//! [`super::emit`], each glyph staying in its own file. A component written without
//! `offset` (placed by anchors) stays without one: the model holds its resolved offset,
//! the file keeps what the author wrote.
//!
//! Comments: the canonical text is generated from the model, which has no comments. A
//! file's leading comment block (the lines before the first key, when they hold a comment)
//! is kept verbatim above the canonical text; any other comment would be lost,
//! and [`Rewrite::dropped_comments`] says where they are, so that `fmt` can refuse unless
//! forced. Comments are found with a small scanner rather than a TOML editing crate: the
//! text has already parsed, so only strings need to be skipped.

use std::path::PathBuf;

use super::emit;
use super::glyph::{load_glyph_text, offsets_written};
use super::load::{LoadedFont, SourceKind};

/// One source file and its canonical text.
#[derive(Clone, Debug, PartialEq)]
pub struct Rewrite {
    /// The file.
    pub path: PathBuf,
    /// What the file holds.
    pub kind: SourceKind,
    /// Its text as read.
    pub old: String,
    /// Its canonical text.
    pub new: String,
    /// Byte offsets (in `old`) of the comments the rewrite drops.
    pub dropped_comments: Vec<usize>,
}

impl Rewrite {
    /// Whether the canonical text differs from the file.
    pub fn changes(&self) -> bool {
        self.old != self.new
    }
}

/// The canonical text of every file of `loaded` (unchanged files included), in file order.
pub fn rewrites(loaded: &LoadedFont) -> Vec<Rewrite> {
    let font = &loaded.font;
    loaded
        .files
        .iter()
        .filter_map(|file| {
            let body = match &file.kind {
                SourceKind::Info => {
                    emit::family_font_toml(&font.info, &loaded.designspace, &loaded.masters)
                }
                SourceKind::Glyph(name) => {
                    let offsets = offsets_written(&file.path, &file.text).unwrap_or_default();
                    emit::glyph_source(font.glyph(name)?, true, &offsets)
                }
                SourceKind::Kerning => emit::kerning_toml(&font.kerning),
                SourceKind::MasterGlyph(m, name) => {
                    let master = loaded.masters.get(*m)?;
                    let glyph = master.glyphs.iter().find(|g| &g.name == name)?;
                    // `unicode` and `mark` stay as the author has them: written (then they
                    // are the default's, the loader checked) or left out.
                    let written = load_glyph_text(&file.path, &file.text).ok().map(|(g, _)| g);
                    let unicodes = written.as_ref().is_some_and(|g| !g.unicodes.is_empty());
                    let mut glyph = glyph.clone();
                    glyph.outline_mark = written.is_some_and(|g| g.outline_mark);
                    let offsets = offsets_written(&file.path, &file.text).unwrap_or_default();
                    emit::glyph_source(&glyph, unicodes, &offsets)
                }
                SourceKind::MasterKerning(m) => {
                    emit::kerning_toml(&loaded.masters.get(*m)?.kerning)
                }
            };
            let comments = comment_offsets(&file.text);
            let header_end = header_len(&file.text, &comments);
            // Canonical line ends are `\n`, in the kept header too.
            let mut new = file.text[..header_end].replace("\r\n", "\n");
            if !new.is_empty() && !new.ends_with('\n') && !body.is_empty() {
                new.push('\n');
            }
            new.push_str(&body);
            Some(Rewrite {
                path: file.path.clone(),
                kind: file.kind.clone(),
                old: file.text.clone(),
                new,
                dropped_comments: comments.into_iter().filter(|&c| c >= header_end).collect(),
            })
        })
        .collect()
}

/// Length of the leading comment block: every line before the first line that is neither
/// blank nor a comment, blank lines included (0 when those lines hold no comment).
fn header_len(text: &str, comments: &[usize]) -> usize {
    let mut pos = 0;
    let mut any_comment = false;
    for line in text.split_inclusive('\n') {
        let trimmed = line.trim_start();
        if trimmed.starts_with('#') && comments.contains(&(pos + line.len() - trimmed.len())) {
            any_comment = true;
        } else if !trimmed.trim_end().is_empty() {
            break;
        }
        pos += line.len();
    }
    if any_comment {
        pos
    } else {
        0
    }
}

/// Byte offsets of every `#` that starts a comment in valid TOML `text`.
pub fn comment_offsets(text: &str) -> Vec<usize> {
    let bytes = text.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        match bytes[i] {
            b'#' => {
                out.push(i);
                while i < bytes.len() && bytes[i] != b'\n' {
                    i += 1;
                }
            }
            q @ (b'"' | b'\'') => {
                let triple = bytes[i..].starts_with(&[q, q, q]);
                i += if triple { 3 } else { 1 };
                loop {
                    match bytes.get(i) {
                        None => break,
                        Some(b'\\') if q == b'"' => i += 2,
                        Some(&c) if c == q => {
                            if !triple {
                                i += 1;
                                break;
                            }
                            if bytes[i..].starts_with(&[q, q, q]) {
                                i += 3;
                                // Up to two more quotes belong to the string's content.
                                let mut extra = 0;
                                while extra < 2 && bytes.get(i) == Some(&q) {
                                    i += 1;
                                    extra += 1;
                                }
                                break;
                            }
                            i += 1;
                        }
                        Some(b'\n') if !triple => break,
                        Some(_) => i += 1,
                    }
                }
                continue;
            }
            _ => i += 1,
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn comments_outside_strings() {
        let text = "# head\na = \"x # not\" # c1\nb = 'y#' \nc = \"\"\"\n# in\n\"\"\"\n#c2\n";
        let found: Vec<&str> = comment_offsets(text)
            .into_iter()
            .map(|o| &text[o..o + text[o..].find('\n').unwrap_or(text.len() - o)])
            .collect();
        assert_eq!(found, ["# head", "# c1", "#c2"]);
        assert_eq!(comment_offsets(r##"a = "q\"#" # c"##), [11]);
        assert_eq!(comment_offsets("a = '''x''''' # c\n"), [14]);
    }

    #[test]
    fn leading_block() {
        let text = "# one\n\n  # two\nfamily = \"x\" # three\n";
        let comments = comment_offsets(text);
        assert_eq!(comments.len(), 3);
        assert_eq!(&text[..header_len(text, &comments)], "# one\n\n  # two\n");
        let text = "# one\n\n\nname = 1\n";
        assert_eq!(header_len(text, &comment_offsets(text)), 8);
        assert_eq!(
            header_len("a = 1\n# late\n", &comment_offsets("a = 1\n# late\n")),
            0
        );
        assert_eq!(header_len("\n\na = 1\n", &[]), 0);
    }
}
