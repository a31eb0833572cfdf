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
    let mut out = String::new();
    push_num(&mut out, v);
    out
}

/// Appends [`num`]`(v)` to `out`.
///
/// Hand-written because Rust's `{:.2}` runs an exact (arbitrary precision) conversion per
/// number, a tenth of a 20,000-glyph build's time. Below 10^15 hundredths the number is
/// the integer `k = round(100 v)` printed with a decimal point, which is what `{:.2}` of
/// `k / 100` prints (that double lies within 2^-53 relative of `k / 100`, far inside the
/// rounding margin of 0.005); larger magnitudes take the exact path.
pub fn push_num(out: &mut String, v: f64) {
    if !v.is_finite() {
        out.push('0');
        return;
    }
    let scaled = (v * 100.0).round();
    if scaled.abs() >= 1e15 {
        out.push_str(&exact_num(scaled / 100.0));
        return;
    }
    // |scaled| < 10^15, so the cast is exact.
    let k = scaled as i64;
    if k == 0 {
        out.push('0');
        return;
    }
    if k < 0 {
        out.push('-');
    }
    let k = k.unsigned_abs();
    let (int, frac) = (k / 100, k % 100);
    // The integer part's digits, last first: `write!` costs several times more through
    // `core::fmt`, and a large font writes millions of numbers.
    let mut digits = [0u8; 20];
    let mut n = int;
    let mut start = digits.len();
    loop {
        start -= 1;
        digits[start] = b'0' + (n % 10) as u8;
        n /= 10;
        if n == 0 {
            break;
        }
    }
    out.extend(digits[start..].iter().map(|&b| char::from(b)));
    if frac != 0 {
        out.push('.');
        out.push(char::from(b'0' + (frac / 10) as u8));
        if frac % 10 != 0 {
            out.push(char::from(b'0' + (frac % 10) as u8));
        }
    }
}

/// `r` (a multiple of 1/100 as a double, not zero) with two decimals, trailing zeros cut.
fn exact_num(r: f64) -> String {
    let s = format!("{r:.2}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
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

    /// The formatter before [`push_num`]: `{:.2}` of the value rounded to hundredths.
    fn reference(v: f64) -> String {
        if !v.is_finite() {
            return "0".into();
        }
        let r = (v * 100.0).round() / 100.0;
        if r == 0.0 {
            return "0".into();
        }
        let s = format!("{r:.2}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    }

    #[test]
    fn the_fast_formatter_writes_the_reference_bytes() {
        let mut special = vec![
            0.0,
            -0.0,
            0.004999,
            0.005,
            -0.005,
            0.015,
            0.025,
            0.125,
            -0.125,
            1.005,
            2.675,
            -2.675,
            0.300_000_000_000_000_04,
            999.995,
            -999.995,
            1e13,
            9.999_999_999_999e12,
            1e14,
            1e15,
            -1e15,
            1e20,
            1.5e300,
            f64::MAX,
            f64::MIN,
            f64::MIN_POSITIVE,
            5e-324,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            4_503_599_627_370_495.5,
            10_000_000_000_000.005,
        ];
        // Halves of hundredths and their neighbours, over many magnitudes.
        for k in -2000..2000 {
            let half = (f64::from(k) + 0.5) / 100.0;
            special.extend([half, half.next_up(), half.next_down(), f64::from(k) / 100.0]);
        }
        // A deterministic spread of values (an LCG over the bits of doubles and of reals
        // of font-sized magnitudes).
        let mut state: u64 = 0x2545_F491_4F6C_DD1D;
        for _ in 0..200_000 {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            let unit = (state >> 11) as f64 / (1u64 << 53) as f64;
            let exponent = ((state >> 3) % 34) as i32 - 18;
            let sign = if state & 1 == 0 { 1.0 } else { -1.0 };
            special.push(sign * unit * 10f64.powi(exponent));
            special.push(f64::from_bits(state));
        }
        for v in special {
            let mut fast = String::from("x");
            push_num(&mut fast, v);
            assert_eq!(&fast[1..], reference(v), "{v:e} ({:#x})", v.to_bits());
            assert_eq!(num(v), reference(v));
        }
    }

    #[test]
    fn escaping() {
        assert_eq!(
            escape("<a & \"b\" 'c' ]]>\u{1}\n"),
            "&lt;a &amp; &quot;b&quot; &apos;c&apos; ]]&gt;\u{FFFD}&#xA;"
        );
    }
}
