//! Production details of the bundled typeface's fonts (issue #18): the NBSP glyph, one line
//! box that covers the accents, smart dropout control and `gasp` in the TTF, licence names
//! and vendor ID, and the WOFF2 `xglyph build` writes next to the TTF and OTF.

use std::path::Path;

use kurbo::Shape;
use ttf_parser::{name_id, Face, GlyphId, Tag};
use xglyph::import::font::glyph_outline;
use xglyph::otf::{otf, ttf, woff2};
use xglyph::outline::{outline_font, OutlinedFont};
use xglyph::pipeline::{outputs, BuildOptions};
use xglyph::source::load_font;

fn bundled() -> OutlinedFont {
    let (font, _) = load_font(Path::new("glyphs")).expect("glyphs/ loads");
    outline_font(&font, font.info.tolerance)
}

fn raw_table<'a>(face: &Face<'a>, tag: &[u8; 4]) -> Option<&'a [u8]> {
    face.raw_face().table(Tag::from_bytes(tag))
}

fn name(face: &Face, id: u16) -> Option<String> {
    face.names()
        .into_iter()
        .find(|n| n.name_id == id)
        .and_then(|n| n.to_string())
}

#[test]
fn nbsp_is_a_space() {
    let font = bundled();
    for bytes in [ttf(&font).expect("ttf"), otf(&font).expect("otf")] {
        let face = Face::parse(&bytes, 0).expect("parses");
        let nbsp = face.glyph_index('\u{a0}').expect("U+00A0 is mapped");
        let space = face.glyph_index(' ').expect("space is mapped");
        assert_ne!(nbsp, space);
        assert_eq!(face.glyph_name(nbsp), Some("uni00A0"));
        assert_eq!(face.glyph_hor_advance(nbsp), Some(250));
        assert_eq!(face.glyph_hor_advance(nbsp), face.glyph_hor_advance(space));
        assert_eq!(face.glyph_bounding_box(nbsp), None, "no ink");
    }
}

#[test]
fn one_line_box_covers_the_accents() {
    let font = bundled();
    assert_eq!((font.info.ascender, font.info.descender), (800.0, -200.0));
    for bytes in [ttf(&font).expect("ttf"), otf(&font).expect("otf")] {
        let face = Face::parse(&bytes, 0).expect("parses");
        // Measured from the glyphs themselves: the highest and lowest ink, as each flavour
        // boxes it (glyf: every point, what the table stores; CFF: the curves' extrema).
        let cff = face.tables().cff.is_some();
        let ink = |g: GlyphId| -> Option<(i16, i16)> {
            if cff {
                let path = glyph_outline(&face, g)?;
                let r = path.bounding_box();
                Some((r.y0.floor() as i16, r.y1.ceil() as i16))
            } else {
                face.glyph_bounding_box(g).map(|b| (b.y_min, b.y_max))
            }
        };
        let boxes: Vec<_> = (0..face.number_of_glyphs())
            .filter_map(|g| ink(GlyphId(g)))
            .collect();
        let top = boxes.iter().map(|b| b.1).max().expect("ink");
        let bottom = boxes.iter().map(|b| b.0).min().expect("ink");
        let agrave = face.glyph_index('À').expect("Agrave");
        let agrave_top = ink(agrave).expect("ink").1;
        assert!(agrave_top > 900, "the grave reaches {agrave_top}");
        assert!(
            top >= agrave_top && top > 800 && bottom < -200,
            "{top} {bottom}"
        );
        let os2 = face.tables().os2.expect("OS/2");
        let hhea = face.tables().hhea;
        assert!(os2.use_typographic_metrics());
        assert_eq!(face.typographic_ascender(), Some(top));
        assert_eq!(face.typographic_descender(), Some(bottom));
        assert_eq!((hhea.ascender, hhea.descender), (top, bottom));
        assert_eq!(
            (os2.windows_ascender(), os2.windows_descender()),
            (top, bottom)
        );
        assert_eq!((face.line_gap(), face.typographic_line_gap()), (0, Some(0)));
    }
}

#[test]
fn truetype_has_smart_dropout_control_and_gasp() {
    let font = bundled();
    let bytes = ttf(&font).expect("ttf");
    let face = Face::parse(&bytes, 0).expect("parses");
    // PUSHW[0] 511, SCANCTRL, PUSHB[0] 4, SCANTYPE.
    assert_eq!(
        raw_table(&face, b"prep"),
        Some(&[0xB8, 0x01, 0xFF, 0x85, 0xB0, 0x04, 0x8D][..])
    );
    // One range up to 65535 ppem with grid fitting and smoothing, symmetric too.
    assert_eq!(
        raw_table(&face, b"gasp"),
        Some(&[0, 1, 0, 1, 0xFF, 0xFF, 0, 0x0F][..])
    );
    // maxp.maxStackElements (offset 24 in version 1.0) holds the one value pushed.
    let maxp = raw_table(&face, b"maxp").expect("maxp");
    assert_eq!(u16::from_be_bytes([maxp[24], maxp[25]]), 1);
    // The CFF font carries no TrueType programs.
    let cff = otf(&font).expect("otf");
    let face = Face::parse(&cff, 0).expect("parses");
    assert_eq!(raw_table(&face, b"prep"), None);
    assert_eq!(raw_table(&face, b"gasp"), None);
}

#[test]
fn licence_names_and_vendor_id() {
    let font = bundled();
    let license = font.info.license.clone().expect("font.toml has a licence");
    assert!(license.contains("SIL Open Font License"));
    for bytes in [ttf(&font).expect("ttf"), otf(&font).expect("otf")] {
        let face = Face::parse(&bytes, 0).expect("parses");
        assert_eq!(name(&face, name_id::LICENSE), Some(license.clone()));
        assert_eq!(
            name(&face, name_id::LICENSE_URL).as_deref(),
            Some("https://openfontlicense.org")
        );
        assert_eq!(
            name(&face, name_id::UNIQUE_ID).as_deref(),
            Some("0.100;XGLY;XglyphSans-Regular")
        );
        let os2 = raw_table(&face, b"OS/2").expect("OS/2");
        assert_eq!(&os2[58..62], b"XGLY", "achVendID");
    }
}

/// Reads a WOFF2 UIntBase128 at `*at`.
fn base128(data: &[u8], at: &mut usize) -> u32 {
    let mut value = 0u32;
    loop {
        let b = data[*at];
        *at += 1;
        value = (value << 7) | u32::from(b & 0x7F);
        if b & 0x80 == 0 {
            return value;
        }
    }
}

/// The first 29 known-table tags of the WOFF2 table directory (index = flags & 63).
fn known_tag(index: u8) -> [u8; 4] {
    const TAGS: [&[u8; 4]; 29] = [
        b"cmap", b"head", b"hhea", b"hmtx", b"maxp", b"name", b"OS/2", b"post", b"cvt ", b"fpgm",
        b"glyf", b"loca", b"prep", b"CFF ", b"VORG", b"EBDT", b"EBLC", b"gasp", b"hdmx", b"kern",
        b"LTSH", b"PCLT", b"VDMX", b"vhea", b"vmtx", b"BASE", b"GDEF", b"GPOS", b"GSUB",
    ];
    *TAGS[usize::from(index)]
}

#[test]
fn woff2_holds_the_truetype_tables() {
    let font = bundled();
    let ttf_bytes = ttf(&font).expect("ttf");
    let w = woff2(&font).expect("woff2");
    assert_eq!(&w[0..4], b"wOF2");
    assert_eq!(&w[4..8], &[0, 1, 0, 0], "TrueType flavour");
    assert!(
        w.len() * 2 < ttf_bytes.len(),
        "{} vs {}",
        w.len(),
        ttf_bytes.len()
    );
    let num_tables = u16::from_be_bytes([w[12], w[13]]);
    let compressed = u32::from_be_bytes([w[20], w[21], w[22], w[23]]) as usize;
    // Table directory after the 48-byte header: flags, optional tag, origLength,
    // (transformLength when transformed: never, the tables are stored as they are).
    let mut at = 48;
    let mut dir = Vec::new();
    for _ in 0..num_tables {
        let flags = w[at];
        at += 1;
        let tag = if flags & 63 == 63 {
            at += 4;
            [w[at - 4], w[at - 3], w[at - 2], w[at - 1]]
        } else {
            known_tag(flags & 63)
        };
        let transform = flags >> 6;
        // glyf/loca: version 3 means untransformed; other tables: version 0.
        let untransformed = if &tag == b"glyf" || &tag == b"loca" {
            3
        } else {
            0
        };
        assert_eq!(
            transform,
            untransformed,
            "{}",
            String::from_utf8_lossy(&tag)
        );
        dir.push((tag, base128(&w, &mut at) as usize));
    }
    let mut stream = Vec::new();
    brotli::BrotliDecompress(&mut &w[at..at + compressed], &mut stream).expect("brotli");
    let face = Face::parse(&ttf_bytes, 0).expect("ttf parses");
    let mut offset = 0;
    for (tag, len) in &dir {
        let table = &stream[offset..offset + len];
        offset += len;
        if tag == b"head" {
            // checkSumAdjustment (bytes 8..12) is the encoder's to recompute.
            let ours = raw_table(&face, tag).expect("head");
            assert_eq!((&table[..8], &table[12..]), (&ours[..8], &ours[12..]));
        } else {
            assert_eq!(
                Some(table),
                raw_table(&face, tag),
                "{}",
                String::from_utf8_lossy(tag)
            );
        }
    }
    assert_eq!(offset, stream.len());
    assert_eq!(dir.len(), face.raw_face().table_records.len() as usize);
}

#[test]
fn build_writes_the_woff2_and_the_specimen_loads_it() {
    let font = bundled();
    let files = outputs(&font, &BuildOptions::default()).expect("outputs");
    let file = |name: &str| {
        files
            .iter()
            .find(|(p, _)| p == Path::new(name))
            .map(|(_, b)| b.clone())
            .unwrap_or_else(|| panic!("{name} is not an output"))
    };
    assert_eq!(
        file("XglyphSans-Regular.woff2"),
        woff2(&font).expect("woff2")
    );
    let html = String::from_utf8(file("specimen.html")).expect("utf-8");
    assert!(
        html.contains(
            r#"src: url("XglyphSans-Regular.woff2") format("woff2"), url("XglyphSans-Regular.otf") format("opentype");"#
        ),
        "{html}"
    );
}

#[test]
fn font_toml_licence_and_vendor_errors_name_the_place() {
    let base = "family = \"T\"\nunits_per_em = 1000\nascender = 800\ndescender = -200\n\
                x_height = 500\ncap_height = 700\n";
    let cases = [
        (
            "vendor = \"TOOLONG\"\n".to_string(),
            "font.toml:7:10: error: `vendor` must be 1 to 4 printable ASCII characters (an OS/2 \
             vendor ID such as \"XGLY\"), found \"TOOLONG\"",
        ),
        (
            "vendor = \"é\"\n".to_string(),
            "font.toml:7:10: error: `vendor` must be 1 to 4 printable ASCII characters (an OS/2 \
             vendor ID such as \"XGLY\"), found \"é\"",
        ),
        (
            format!("license = \"{}\"\n", "x".repeat(6000)),
            "font.toml:7:11: error: `license` is 6000 UTF-16 code units long; at most 5000 fit \
             the font's `name` table",
        ),
        (
            "license_url = 14\n".to_string(),
            "font.toml:7:15: error: `license_url` must be a string, found integer",
        ),
    ];
    for (extra, want) in cases {
        let text = format!("{base}{extra}");
        let errors =
            xglyph::source::load_info_text(Path::new("font.toml"), &text).expect_err("an error");
        let shown: Vec<String> = errors.iter().map(ToString::to_string).collect();
        assert_eq!(shown, [want], "{extra}");
    }
    // Valid ones load and round-trip through `fmt`'s writer.
    let text = format!("{base}license = \"OFL\"\nlicense_url = \"https://x\"\nvendor = \"AB\"\n");
    let (info, _) = xglyph::source::load_info_text(Path::new("font.toml"), &text).expect("ok");
    assert_eq!(
        (
            info.license.as_deref(),
            info.license_url.as_deref(),
            info.vendor.as_deref()
        ),
        (Some("OFL"), Some("https://x"), Some("AB"))
    );
    let emitted = xglyph::source::emit::font_toml(&info);
    assert!(emitted.ends_with("license = \"OFL\"\nlicense_url = \"https://x\"\nvendor = \"AB\"\n"));
    let (again, _) = xglyph::source::load_info_text(Path::new("font.toml"), &emitted).expect("ok");
    assert_eq!(again, info);
}

/// The contours of glyph `name`, as x ranges of their outline's bounding boxes, left to
/// right, and the caret positions `GDEF` gives the glyph (none for a glyph it does not list).
fn ligature(bytes: &[u8], name: &str) -> (Vec<(f64, f64)>, Vec<i16>) {
    use read_fonts::tables::gdef::CaretValue;
    use read_fonts::{FontRef, TableProvider};

    let face = Face::parse(bytes, 0).expect("parses");
    let gid = face.glyph_index_by_name(name).expect(name);
    let path = glyph_outline(&face, gid).expect(name);
    let mut boxes: Vec<(f64, f64)> = path
        .elements()
        .split(|el| matches!(el, kurbo::PathEl::ClosePath))
        .filter(|els| !els.is_empty())
        .map(|els| {
            let b = kurbo::BezPath::from_vec(els.to_vec()).bounding_box();
            (b.x0, b.x1)
        })
        .collect();
    boxes.sort_by(|a, b| a.0.total_cmp(&b.0));
    let gdef = FontRef::new(bytes).expect("reads").gdef().expect("GDEF");
    let carets = gdef.lig_caret_list().expect("carets").expect("reads");
    // A glyph outside the caret list's coverage has none.
    let Some(index) = carets.coverage().unwrap().get(gid.0) else {
        return (boxes, Vec::new());
    };
    let lig = carets.lig_glyphs().get(index as usize).unwrap();
    let carets = lig
        .caret_values()
        .iter()
        .map(|c| match c.unwrap() {
            CaretValue::Format1(c) => c.coordinate(),
            _ => panic!("{name}: a caret by position was written"),
        })
        .collect();
    (boxes, carets)
}

/// Issue 18 (FontBakery `contour_count`): `fi` is f, dotless i and dot (3 contours) and `fl`
/// is f and l (2) in the TTF and OTF, at Regular, wght 550 and Bold, so overlap removal
/// found nothing touching. They are ligatures: the i or l stem sits closer to the f than in
/// f + i set apart. In the default master the caret lies in the gap between f and stem.
#[test]
fn fi_and_fl_are_separate_contours_with_the_caret_between() {
    use xglyph::designspace::Location;

    let loaded = xglyph::pipeline::load(Path::new("glyphs"), None).expect("glyphs/ loads");
    let at = |w: f64| Location([("wght".to_string(), w)].into_iter().collect());
    let instance = |w| xglyph::pipeline::instance(&loaded, &at(w), None).expect("instance");
    for (w, font) in [
        (400.0, bundled()),
        (550.0, instance(550.0)),
        (700.0, instance(700.0)),
    ] {
        let advance = |n: &str| font.glyphs.iter().find(|g| g.name == n).expect(n).advance;
        for (flavour, bytes) in [("TTF", ttf(&font).unwrap()), ("OTF", otf(&font).unwrap())] {
            for (lig, second, contours) in [("fi", "i", 3), ("fl", "l", 2)] {
                let (boxes, carets) = ligature(&bytes, lig);
                let at = format!("{lig} at wght {w} ({flavour})");
                assert_eq!(boxes.len(), contours, "{at}: {boxes:?}");
                // The f, then the stem (the dot over the stem): a white gap between them.
                let (f, stem) = (boxes[0], boxes[1]);
                assert!(
                    f.1 + 20.0 < stem.0,
                    "{at}: f {f:?} touches the stem {stem:?}"
                );
                // Tighter than f and i side by side (the stem at f's advance + i's left side).
                let (single, _) = ligature(&bytes, second);
                let apart = advance("f") + single[0].0;
                assert!(
                    stem.0 < apart - 30.0,
                    "{at}: stem at {}, apart {apart}",
                    stem.0
                );
                if w == 400.0 {
                    assert_eq!(carets.len(), 1, "{at}");
                    let caret = f64::from(carets[0]);
                    assert!(
                        f.1 < caret && caret < stem.0,
                        "{at}: caret {caret}, {boxes:?}"
                    );
                }
            }
        }
    }
}
