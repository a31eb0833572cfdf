//! XML text: escaping and compact, deterministic numbers.
//!
//! Hand-written rather than taken from an XML writer crate: we need only escaping, and the
//! number format (1/100 unit, no trailing zeros, no `-0`) is ours to fix for stable diffs.

/// Whether XML 1.0 allows `c` at all (even as a character reference).
pub fn is_xml_char(c: char) -> bool {
    matches!(c, '\t' | '\n' | '\r' | '\u{20}'..='\u{D7FF}' | '\u{E000}'..='\u{FFFD}' | '\u{10000}'..)
}

/// `text` escaped for an attribute value (in double quotes) or element text: `& < > " '`
/// become entities, tab/newline/CR become character references (attribute values would
/// otherwise normalise them to spaces), characters XML cannot hold become U+FFFD.
pub fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            '\t' => out.push_str("&#x9;"),
            '\n' => out.push_str("&#xA;"),
            '\r' => out.push_str("&#xD;"),
            c if is_xml_char(c) => out.push(c),
            _ => out.push('\u{FFFD}'),
        }
    }
    out
}

/// A number rounded to 1/100, without trailing zeros, never `-0`: `12`, `-3.5`, `0.25`.
/// Non-finite values (which validated outlines never contain) are written as `0`.
pub fn num(v: f64) -> String {
    if !v.is_finite() {
        return "0".into();
    }
    let r = (v * 100.0).round() / 100.0;
    if r == 0.0 {
        return "0".into();
    }
    let s = format!("{r:.2}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    s.to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers() {
        assert_eq!(num(12.0), "12");
        assert_eq!(num(-3.5), "-3.5");
        assert_eq!(num(0.254), "0.25");
        assert_eq!(num(0.256), "0.26");
        assert_eq!(num(-0.001), "0");
        assert_eq!(num(-0.0), "0");
        assert_eq!(num(100.0), "100");
        assert_eq!(num(1234.999), "1235");
        assert_eq!(num(f64::NAN), "0");
    }

    #[test]
    fn escaping() {
        assert_eq!(
            escape("<a & \"b\" 'c' ]]>\u{1}\n"),
            "&lt;a &amp; &quot;b&quot; &apos;c&apos; ]]&gt;\u{FFFD}&#xA;"
        );
    }
}
