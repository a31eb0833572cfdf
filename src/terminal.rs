//! Text for a terminal: what a font's data can hold is printed, never obeyed.
//!
//! Family and glyph names, file names, source lines and messages quoting them can hold any
//! character; printed raw, `ESC` sequences would retitle the window, clear the screen or
//! fake output, and `BEL` rings. Every command prints through `out!`/`outln!` and
//! `err!`/`errln!` (crate macros), which pass the text through [`escape`]: each control character
//! except newline and tab, and each bidirectional-override character, becomes a Rust-style
//! escape (`\u{1b}`). JSON output is left to serde_json, which escapes C0 controls itself.

use std::borrow::Cow;
use std::fmt::Write;

/// `text` with every control character (C0, DEL, C1) other than `\n` and `\t`, and every
/// bidirectional embedding, override or isolate, written as `\u{..}` (lowercase hex).
/// Borrows when there is nothing to escape.
pub fn escape(text: &str) -> Cow<'_, str> {
    if !text.chars().any(needs_escape) {
        return Cow::Borrowed(text);
    }
    let mut out = String::with_capacity(text.len() + 8);
    for c in text.chars() {
        if needs_escape(c) {
            let _ = write!(out, "\\u{{{:x}}}", u32::from(c));
        } else {
            out.push(c);
        }
    }
    Cow::Owned(out)
}

fn needs_escape(c: char) -> bool {
    (c.is_control() && c != '\n' && c != '\t')
        || matches!(c, '\u{202a}'..='\u{202e}' | '\u{2066}'..='\u{2069}')
}

/// `print!` through [`escape`].
macro_rules! out {
    ($($arg:tt)*) => {
        ::std::print!("{}", $crate::terminal::escape(&::std::format!($($arg)*)))
    };
}

/// `println!` through [`escape`].
macro_rules! outln {
    ($($arg:tt)*) => {
        ::std::println!("{}", $crate::terminal::escape(&::std::format!($($arg)*)))
    };
}

/// `eprint!` through [`escape`].
macro_rules! err {
    ($($arg:tt)*) => {
        ::std::eprint!("{}", $crate::terminal::escape(&::std::format!($($arg)*)))
    };
}

/// `eprintln!` through [`escape`].
macro_rules! errln {
    ($($arg:tt)*) => {
        ::std::eprintln!("{}", $crate::terminal::escape(&::std::format!($($arg)*)))
    };
}

pub(crate) use {err, errln, out, outln};

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn control_characters_become_escapes() {
        assert_eq!(
            escape("A\u{1b}]0;pwned\u{7}\u{1b}[2J"),
            "A\\u{1b}]0;pwned\\u{7}\\u{1b}[2J"
        );
        assert_eq!(escape("a\u{7f}b\u{9b}c\0"), "a\\u{7f}b\\u{9b}c\\u{0}");
        assert_eq!(escape("abc\u{202e}cba"), "abc\\u{202e}cba");
        assert_eq!(escape("crlf\r\n"), "crlf\\u{d}\n");
    }

    #[test]
    fn plain_text_is_borrowed() {
        let text = "Xglyph Sans: wrote 3 files\n\t| é ü 中";
        assert!(matches!(escape(text), Cow::Borrowed(t) if t == text));
    }
}
