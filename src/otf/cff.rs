//! The `CFF ` table (Adobe TN #5176): one name-keyed font, no subroutines, no hints.
//!
//! Layout: header, Name INDEX, Top DICT INDEX, String INDEX, empty Global Subr INDEX,
//! charset (format 0), CharStrings INDEX, Private DICT. Offsets in the Top DICT use the
//! fixed five-byte integer form so the DICT's size does not depend on them.
//! `defaultWidthX` and `nominalWidthX` are 0: every non-zero width is written in its
//! charstring. `FontMatrix` is written only when units per em is not 1000.
//! Hand-written: write-fonts 0.55 has no CFF encoder and no maintained crate provides one.

use std::collections::HashMap;
use std::sync::OnceLock;

use read_fonts::ps::Sid;

/// Number of standard strings (SIDs 0..=390) in the CFF specification, Appendix A.
const STANDARD_STRING_COUNT: u16 = 391;

// Top DICT operators.
const OP_VERSION: u16 = 0;
const OP_FULL_NAME: u16 = 2;
const OP_FAMILY_NAME: u16 = 3;
const OP_FONT_BBOX: u16 = 5;
const OP_CHARSET: u16 = 15;
const OP_CHAR_STRINGS: u16 = 17;
const OP_PRIVATE: u16 = 18;
/// Escaped operators are `12 x`; stored here as `0x0c00 | x`.
const OP_COPYRIGHT: u16 = 0x0c00;
const OP_FONT_MATRIX: u16 = 0x0c07;
// Private DICT operators.
const OP_DEFAULT_WIDTH_X: u16 = 20;
const OP_NOMINAL_WIDTH_X: u16 = 21;

/// What the Top DICT says about the font.
pub struct CffInfo<'a> {
    /// PostScript font name (the Name INDEX entry).
    pub ps_name: &'a str,
    pub version: &'a str,
    pub copyright: Option<&'a str>,
    pub full_name: &'a str,
    pub family_name: &'a str,
    pub units_per_em: u16,
    /// xMin, yMin, xMax, yMax over all glyphs.
    pub bbox: [i16; 4],
}

/// An INDEX: count, offset size, offsets (1-based), data. An empty INDEX is two zero bytes.
pub fn encode_index<T: AsRef<[u8]>>(items: &[T]) -> Vec<u8> {
    let count = items.len().min(usize::from(u16::MAX));
    let mut out = Vec::new();
    out.extend((count as u16).to_be_bytes());
    if count == 0 {
        return out;
    }
    let data_len: usize = items[..count].iter().map(|i| i.as_ref().len()).sum();
    let last_offset = data_len + 1;
    let off_size: usize = match last_offset {
        0..=0xFF => 1,
        0x100..=0xFFFF => 2,
        0x1_0000..=0xFF_FFFF => 3,
        _ => 4,
    };
    out.push(off_size as u8);
    let mut offset = 1usize;
    let push_offset = |out: &mut Vec<u8>, offset: usize| {
        let bytes = (offset as u32).to_be_bytes();
        out.extend(&bytes[4 - off_size..]);
    };
    push_offset(&mut out, offset);
    for item in &items[..count] {
        offset += item.as_ref().len();
        push_offset(&mut out, offset);
    }
    for item in &items[..count] {
        out.extend(item.as_ref());
    }
    out
}

/// A DICT integer operand in its shortest form.
pub fn encode_dict_int(v: i32, out: &mut Vec<u8>) {
    match v {
        -107..=107 => out.push((v + 139) as u8),
        108..=1131 => {
            let w = v - 108;
            out.extend([(w / 256 + 247) as u8, (w % 256) as u8]);
        }
        -1131..=-108 => {
            let w = -v - 108;
            out.extend([(w / 256 + 251) as u8, (w % 256) as u8]);
        }
        -32768..=32767 => {
            out.push(28);
            out.extend((v as i16).to_be_bytes());
        }
        _ => encode_dict_int5(v, out),
    }
}

/// A DICT integer operand in the fixed five-byte form (for offsets).
fn encode_dict_int5(v: i32, out: &mut Vec<u8>) {
    out.push(29);
    out.extend(v.to_be_bytes());
}

/// A DICT real operand: nibbles of the shorter of the plain and exponent decimal forms.
pub fn encode_dict_real(v: f64, out: &mut Vec<u8>) {
    let plain = format!("{v}");
    let exp = format!("{v:e}").replace("e-", "E-").replace('e', "E");
    let text = if exp.len() < plain.len() { exp } else { plain };
    encode_dict_real_str(&text, out);
}

/// A DICT real operand from its decimal text (`-2.25`, `0.140541E-3`).
fn encode_dict_real_str(text: &str, out: &mut Vec<u8>) {
    let mut nibbles = Vec::new();
    let mut chars = text.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '0'..='9' => nibbles.push(c as u8 - b'0'),
            '.' => nibbles.push(0xa),
            '-' => nibbles.push(0xe),
            'E' if chars.peek() == Some(&'-') => {
                chars.next();
                nibbles.push(0xc);
            }
            'E' => nibbles.push(0xb),
            _ => {}
        }
    }
    nibbles.push(0xf);
    if nibbles.len() % 2 == 1 {
        nibbles.push(0xf);
    }
    out.push(30);
    out.extend(nibbles.chunks(2).map(|p| (p[0] << 4) | p[1]));
}

fn push_op(op: u16, out: &mut Vec<u8>) {
    if op >= 0x0c00 {
        out.extend([12, (op & 0xff) as u8]);
    } else {
        out.push(op as u8);
    }
}

/// String IDs: standard strings by number, the rest in the String INDEX. Both are looked
/// up in maps: a CJK font's charset names 20,000 glyphs, and a linear search per name was
/// quadratic.
#[derive(Default)]
struct Strings {
    custom: Vec<String>,
    /// Custom string -> index in `custom`.
    index: HashMap<String, usize>,
}

impl Strings {
    fn sid(&mut self, s: &str) -> i32 {
        if let Some(&sid) = standard_sids().get(s.as_bytes()) {
            return i32::from(sid);
        }
        let index = match self.index.get(s) {
            Some(&i) => i,
            None => {
                self.custom.push(s.to_owned());
                self.index.insert(s.to_owned(), self.custom.len() - 1);
                self.custom.len() - 1
            }
        };
        i32::from(STANDARD_STRING_COUNT) + index as i32
    }
}

/// The standard strings and their SIDs (the first SID of a string, were one repeated).
fn standard_sids() -> &'static HashMap<&'static [u8], u16> {
    static MAP: OnceLock<HashMap<&'static [u8], u16>> = OnceLock::new();
    MAP.get_or_init(|| {
        let mut map = HashMap::new();
        for i in 0..STANDARD_STRING_COUNT {
            if let Ok(bytes) = Sid::new(i).resolve_standard() {
                map.entry(bytes).or_insert(i);
            }
        }
        map
    })
}

/// The Top DICT with the given offsets (charset, CharStrings, Private size and offset).
fn top_dict(fields: &[(u16, Vec<Operand>)]) -> Vec<u8> {
    let mut out = Vec::new();
    for (op, operands) in fields {
        for operand in operands {
            match *operand {
                Operand::Int(v) => encode_dict_int(v, &mut out),
                Operand::Offset(v) => encode_dict_int5(v, &mut out),
                Operand::Real(v) => encode_dict_real(v, &mut out),
            }
        }
        push_op(*op, &mut out);
    }
    out
}

#[derive(Clone, Copy)]
enum Operand {
    Int(i32),
    Offset(i32),
    Real(f64),
}

/// The whole `CFF ` table. `glyph_names[0]` is `.notdef`; `charstrings` are in glyph order.
pub fn cff_table(info: &CffInfo, glyph_names: &[&str], charstrings: &[Vec<u8>]) -> Vec<u8> {
    let mut strings = Strings::default();
    let mut fields: Vec<(u16, Vec<Operand>)> = Vec::new();
    fields.push((OP_VERSION, vec![Operand::Int(strings.sid(info.version))]));
    if let Some(copyright) = info.copyright {
        fields.push((OP_COPYRIGHT, vec![Operand::Int(strings.sid(copyright))]));
    }
    fields.push((
        OP_FULL_NAME,
        vec![Operand::Int(strings.sid(info.full_name))],
    ));
    fields.push((
        OP_FAMILY_NAME,
        vec![Operand::Int(strings.sid(info.family_name))],
    ));
    fields.push((
        OP_FONT_BBOX,
        info.bbox
            .iter()
            .map(|&v| Operand::Int(i32::from(v)))
            .collect(),
    ));
    if info.units_per_em != 1000 {
        let scale = 1.0 / f64::from(info.units_per_em);
        fields.push((
            OP_FONT_MATRIX,
            [scale, 0.0, 0.0, scale, 0.0, 0.0]
                .into_iter()
                .map(Operand::Real)
                .collect(),
        ));
    }
    let mut charset = vec![0u8]; // format 0
    for name in glyph_names.iter().skip(1) {
        charset.extend((strings.sid(name) as u16).to_be_bytes());
    }

    let mut private = Vec::new();
    encode_dict_int(0, &mut private);
    push_op(OP_DEFAULT_WIDTH_X, &mut private);
    encode_dict_int(0, &mut private);
    push_op(OP_NOMINAL_WIDTH_X, &mut private);

    let header = [1u8, 0, 4, 4];
    let name_index = encode_index(&[info.ps_name.as_bytes()]);
    let string_index = encode_index(&strings.custom);
    let gsubr_index = encode_index::<&[u8]>(&[]);
    let charstrings_index = encode_index(charstrings);

    let with_offsets = |charset_at: i32, charstrings_at: i32, private_at: i32| {
        let mut f = fields.clone();
        f.push((OP_CHARSET, vec![Operand::Offset(charset_at)]));
        f.push((OP_CHAR_STRINGS, vec![Operand::Offset(charstrings_at)]));
        f.push((
            OP_PRIVATE,
            vec![
                Operand::Offset(private.len() as i32),
                Operand::Offset(private_at),
            ],
        ));
        encode_index(&[top_dict(&f)])
    };
    // The Top DICT INDEX has the same size whatever the (fixed-width) offsets are.
    let top_len = with_offsets(0, 0, 0).len();
    let charset_at =
        header.len() + name_index.len() + top_len + string_index.len() + gsubr_index.len();
    let charstrings_at = charset_at + charset.len();
    let private_at = charstrings_at + charstrings_index.len();
    let top_index = with_offsets(charset_at as i32, charstrings_at as i32, private_at as i32);

    let mut out = Vec::with_capacity(private_at + private.len());
    out.extend(header);
    out.extend(name_index);
    out.extend(top_index);
    out.extend(string_index);
    out.extend(gsubr_index);
    out.extend(charset);
    out.extend(charstrings_index);
    out.extend(private);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn int(v: i32) -> Vec<u8> {
        let mut out = Vec::new();
        encode_dict_int(v, &mut out);
        out
    }

    /// TN #5176, Table 4 "Integer Format Examples".
    #[test]
    fn dict_integers_from_the_spec() {
        assert_eq!(int(0), [0x8b]);
        assert_eq!(int(100), [0xef]);
        assert_eq!(int(-100), [0x27]);
        assert_eq!(int(1000), [0xfa, 0x7c]);
        assert_eq!(int(-1000), [0xfe, 0x7c]);
        assert_eq!(int(10000), [0x1c, 0x27, 0x10]);
        assert_eq!(int(-10000), [0x1c, 0xd8, 0xf0]);
        assert_eq!(int(100000), [0x1d, 0x00, 0x01, 0x86, 0xa0]);
        assert_eq!(int(-100000), [0x1d, 0xff, 0xfe, 0x79, 0x60]);
    }

    /// TN #5176, section 4 "Real Number Encoding" examples.
    #[test]
    fn dict_reals_from_the_spec() {
        let mut out = Vec::new();
        encode_dict_real_str("-2.25", &mut out);
        assert_eq!(out, [0x1e, 0xe2, 0xa2, 0x5f]);
        out.clear();
        encode_dict_real_str("0.140541E-3", &mut out);
        assert_eq!(out, [0x1e, 0x0a, 0x14, 0x05, 0x41, 0xc3, 0xff]);
        out.clear();
        encode_dict_real(1.0 / 2048.0, &mut out); // 4.8828125E-4, shorter than 0.00048828125
        assert_eq!(out, [0x1e, 0x4a, 0x88, 0x28, 0x12, 0x5c, 0x4f]);
        out.clear();
        encode_dict_real(0.0, &mut out);
        assert_eq!(out, [0x1e, 0x0f]);
    }

    #[test]
    fn index_encoding() {
        assert_eq!(encode_index::<&[u8]>(&[]), [0, 0]);
        assert_eq!(
            encode_index(&[b"ab".as_slice(), b"c"]),
            [0, 2, 1, 1, 3, 4, b'a', b'b', b'c']
        );
        // 300 bytes of data: offsets need two bytes.
        let big = vec![7u8; 300];
        let encoded = encode_index(&[big.as_slice()]);
        assert_eq!(&encoded[..7], [0, 1, 2, 0, 1, 0x01, 0x2d]);
        assert_eq!(encoded.len(), 7 + 300);
    }

    #[test]
    fn standard_strings_are_not_stored() {
        let mut strings = Strings::default();
        assert_eq!(strings.sid(".notdef"), 0);
        assert_eq!(strings.sid("A"), 34);
        assert_eq!(strings.sid("oacute"), 216); // Appendix A
        assert_eq!(strings.sid("Regular"), 388);
        assert_eq!(strings.sid("acutecomb"), 391);
        assert_eq!(strings.sid("Mini Test"), 392);
        assert_eq!(strings.sid("acutecomb"), 391);
        assert_eq!(strings.custom, ["acutecomb", "Mini Test"]);
    }
}
