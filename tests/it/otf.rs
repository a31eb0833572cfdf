//! TTF and OTF export read back with ttf-parser: glyph order, names, cmap, advances,
//! metrics, kerning, and every outline against the fitted BezPaths by dense two-sided
//! sampling.

use std::path::Path;

use crate::common::paths;

use kurbo::{BezPath, Shape};
use ttf_parser::{Face, GlyphId};
use xglyph::import::font::glyph_outline;
use xglyph::model::{Contour, Font, Glyph, KernPair};
use xglyph::otf::{glyph_order, otf, specimen_html, specimen_text, ttf, PULLED};
use xglyph::outline::{outline_font, OutlinedFont};
use xglyph::source::load_font;
use xglyph::xspline::ControlPoint;

/// Largest distance grid rounding can move a point of a Bézier curve (√2/2 units).
const GRID: f64 = std::f64::consts::FRAC_1_SQRT_2;

fn mini() -> (Font, OutlinedFont) {
    let (font, _) = load_font(Path::new("tests/fixtures/mini")).expect("mini loads");
    let outlines = outline_font(&font, font.info.tolerance);
    (font, outlines)
}

fn outline(face: &Face, gid: u16) -> BezPath {
    glyph_outline(face, GlyphId(gid)).unwrap_or_default()
}

/// Two-sided (Hausdorff) distance between two outlines, by dense sampling.
fn distance(a: &BezPath, b: &BezPath) -> f64 {
    paths::two_sided(a, b, 64)
}

fn contour_count(p: &BezPath) -> usize {
    p.elements()
        .iter()
        .filter(|e| matches!(e, kurbo::PathEl::MoveTo(_)))
        .count()
}

/// Checks one built font against the model; returns the worst outline distance.
fn check_font(bytes: &[u8], font: &Font, outlines: &OutlinedFont, cff: bool) -> f64 {
    let face = Face::parse(bytes, 0).expect("font parses");
    assert_eq!(face.units_per_em(), 1000);
    assert_eq!(face.number_of_glyphs(), 8);
    let names: Vec<String> = (0..8)
        .map(|g| face.glyph_name(GlyphId(g)).expect("glyph name").to_owned())
        .collect();
    assert_eq!(
        names,
        [
            ".notdef",
            "A",
            "V",
            "acutecomb",
            "o",
            "oacute",
            "period",
            "space"
        ]
    );
    let order = glyph_order(outlines).unwrap();
    let mut worst: f64 = 0.0;
    for (gid, g) in order.iter().enumerate() {
        let gid = gid as u16;
        let model = font.glyph(&g.model_name).unwrap();
        assert_eq!(
            face.glyph_hor_advance(GlyphId(gid)),
            Some(model.advance as u16),
            "{}",
            g.model_name
        );
        for &c in &model.unicodes {
            assert_eq!(face.glyph_index(c), Some(GlyphId(gid)), "{c:?}");
        }
        let exact = &outlines.glyph(&g.model_name).unwrap().path;
        let built = outline(&face, gid);
        assert_eq!(
            contour_count(&built),
            contour_count(exact),
            "{}",
            g.model_name
        );
        if exact.elements().is_empty() {
            continue;
        }
        // Direction: CFF keeps the counter-clockwise outer contours, TrueType reverses them.
        let sign = if cff { 1.0 } else { -1.0 };
        assert!(
            built.area() * exact.area() * sign > 0.0,
            "{}: direction",
            g.model_name
        );
        let d = distance(&built, exact);
        eprintln!(
            "{} {}: {d:.4} units",
            if cff { "OTF" } else { "TTF" },
            g.model_name
        );
        worst = worst.max(d);
        // Glyph boxes lie on the grid and contain the outline.
        let bbox = face.glyph_bounding_box(GlyphId(gid)).unwrap();
        let tight = exact.bounding_box();
        let slack = if cff {
            GRID + 1.0
        } else {
            font.info.tolerance + GRID + 1.0
        };
        assert!(f64::from(bbox.x_min) <= tight.x0 + slack);
        assert!(f64::from(bbox.x_max) >= tight.x1 - slack);
    }
    // Characters that are not in the font map to nothing.
    assert_eq!(face.glyph_index('B'), None);

    // Vertical metrics: the model's, everywhere.
    assert_eq!(face.ascender(), 800);
    assert_eq!(face.descender(), -200);
    assert_eq!(face.line_gap(), 0);
    assert_eq!(face.typographic_ascender(), Some(800));
    assert_eq!(face.typographic_descender(), Some(-200));
    assert_eq!(face.x_height(), Some(500));
    assert_eq!(face.capital_height(), Some(700));
    let os2 = face.tables().os2.unwrap();
    assert!(os2.use_typographic_metrics());
    let hhea = face.tables().hhea;
    assert_eq!((hhea.ascender, hhea.descender), (800, -200));
    let global = face.global_bounding_box();
    // The o's bottom passes through y = -12. CFF stores the tight box of the rounded
    // cubics; glyf the box of all points, off-curve ones included (may reach lower).
    // The fitted cubics may pass up to the tolerance (0.5) below it, then round.
    if cff {
        assert!((-13..=-12).contains(&global.y_min), "{}", global.y_min);
    } else {
        assert!((-14..=-12).contains(&global.y_min), "{}", global.y_min);
    }
    assert_eq!(global.y_max, 700);
    assert_eq!(os2.windows_ascender(), 800);
    assert_eq!(os2.windows_descender(), -200);

    // Names.
    let name = |id: u16| {
        face.names()
            .into_iter()
            .find(|n| n.name_id == id && n.platform_id == ttf_parser::PlatformId::Windows)
            .and_then(|n| n.to_string())
    };
    assert_eq!(name(1).as_deref(), Some("Mini Test"));
    assert_eq!(name(2).as_deref(), Some("Regular"));
    assert_eq!(name(4).as_deref(), Some("Mini Test Regular"));
    assert_eq!(name(5).as_deref(), Some("Version 1.000"));
    assert_eq!(name(6).as_deref(), Some("MiniTest-Regular"));

    // Kerning in GPOS: A V -60, V o -40, nothing else; then `mark` from the anchors
    // (tests/it/features.rs checks it).
    let gpos = face.tables().gpos.expect("GPOS");
    let tags: Vec<_> = gpos.features.into_iter().map(|f| f.tag).collect();
    assert_eq!(tags, [b"kern", b"mark"].map(ttf_parser::Tag::from_bytes));
    let lookup = gpos.lookups.get(0).unwrap();
    let subtable = lookup
        .subtables
        .get::<ttf_parser::gpos::PositioningSubtable>(0)
        .unwrap();
    let ttf_parser::gpos::PositioningSubtable::Pair(ttf_parser::gpos::PairAdjustment::Format1 {
        coverage,
        sets,
    }) = subtable
    else {
        panic!("expected PairPosFormat1");
    };
    let kern = |l: u16, r: u16| {
        coverage
            .get(GlyphId(l))
            .and_then(|i| sets.get(i))
            .and_then(|set| set.get(GlyphId(r)))
            .map(|(v1, _)| v1.x_advance)
    };
    assert_eq!(kern(1, 2), Some(-60));
    assert_eq!(kern(2, 4), Some(-40));
    assert_eq!(kern(2, 1), None);
    assert_eq!(kern(4, 2), None);
    // The legacy table, TTF only.
    match face.tables().kern {
        Some(k) => {
            assert!(!cff);
            let sub = k.subtables.into_iter().next().unwrap();
            assert_eq!(sub.glyphs_kerning(GlyphId(1), GlyphId(2)), Some(-60));
            assert_eq!(sub.glyphs_kerning(GlyphId(2), GlyphId(4)), Some(-40));
            assert_eq!(sub.glyphs_kerning(GlyphId(1), GlyphId(4)), None);
        }
        None => assert!(cff),
    }
    worst
}

#[test]
fn ttf_reads_back_within_tolerance() {
    let (font, outlines) = mini();
    let bytes = ttf(&outlines).unwrap();
    let worst = check_font(&bytes, &font, &outlines, false);
    eprintln!("TTF worst: {worst:.4} units");
    // Quadratic conversion within the tolerance (0.5), then grid rounding.
    assert!(worst <= font.info.tolerance + GRID, "{worst}");
    // Straight-edged glyphs only move by rounding; the round ones use the budget.
    assert!(worst > 0.3, "{worst}");
    assert_eq!(ttf(&outlines).unwrap(), bytes, "deterministic");
}

#[test]
fn otf_reads_back_within_grid_rounding() {
    let (font, outlines) = mini();
    let bytes = otf(&outlines).unwrap();
    let worst = check_font(&bytes, &font, &outlines, true);
    eprintln!("OTF worst: {worst:.4} units");
    // The cubics are exact; only grid rounding moves them.
    assert!(worst <= GRID, "{worst}");
    assert!(worst > 0.1, "{worst}");
    assert_eq!(otf(&outlines).unwrap(), bytes, "deterministic");
}

fn square(x0: f64, y0: f64, x1: f64, y1: f64) -> Contour {
    Contour::new(vec![
        ControlPoint::new(x0, y0, 0.0),
        ControlPoint::new(x1, y0, 0.0),
        ControlPoint::new(x1, y1, 0.0),
        ControlPoint::new(x0, y1, 0.0),
    ])
    .expect("a valid contour")
}

fn glyph(name: &str, unicodes: &[char], advance: f64, contours: Vec<Contour>) -> Glyph {
    Glyph {
        name: name.into(),
        unicodes: unicodes.to_vec(),
        advance,
        contours,
        components: Vec::new(),
        anchors: Vec::new(),
        outline_mark: false,
    }
}

#[test]
fn synthetic_notdef_and_fallback_names() {
    let (mut font, _) = mini();
    font.glyphs.retain(|g| g.name != ".notdef");
    font.glyphs.push(glyph(
        "smile face",
        &['\u{1F600}'],
        800.0,
        vec![square(100.0, 0.0, 700.0, 600.0)],
    ));
    font.glyphs.push(glyph("9x", &[], 300.0, vec![]));
    let outlines = outline_font(&font, font.info.tolerance);
    for bytes in [ttf(&outlines).unwrap(), otf(&outlines).unwrap()] {
        let face = Face::parse(&bytes, 0).unwrap();
        assert_eq!(face.number_of_glyphs(), 10);
        assert_eq!(face.glyph_name(GlyphId(0)), Some(".notdef"));
        assert_eq!(face.glyph_hor_advance(GlyphId(0)), Some(500));
        let b = face.glyph_bounding_box(GlyphId(0)).unwrap();
        assert_eq!((b.x_min, b.y_min, b.x_max, b.y_max), (50, 0, 450, 700));
        assert_eq!(contour_count(&outline(&face, 0)), 2);
        assert_eq!(face.glyph_name(GlyphId(8)), Some("u1F600"));
        assert_eq!(face.glyph_index('\u{1F600}'), Some(GlyphId(8)));
        assert_eq!(face.glyph_name(GlyphId(9)), Some("glyph9"));
        assert_eq!(face.glyph_hor_advance(GlyphId(9)), Some(300));
    }
}

#[test]
fn unrepresentable_models_are_errors() {
    let (font, _) = mini();

    let mut wide = font.clone();
    wide.glyphs.push(glyph(
        "wide",
        &[],
        500.0,
        vec![square(0.0, 0.0, 40000.0, 100.0)],
    ));
    let outlines = outline_font(&wide, 0.5);
    let err = ttf(&outlines).unwrap_err().to_string();
    assert_eq!(
        err,
        "x coordinate in glyph 'wide' is 40000, outside the OpenType range -32768..=32767"
    );
    assert_eq!(otf(&outlines).unwrap_err().to_string(), err);

    let mut negative = font.clone();
    negative.glyphs[1].advance = -5.0;
    let outlines = outline_font(&negative, 0.5);
    assert_eq!(
        ttf(&outlines).unwrap_err().to_string(),
        "advance of 'A' is -5, outside the OpenType range 0..=32767"
    );

    let mut kern = font.clone();
    kern.kerning.push(KernPair {
        left: "o".into(),
        right: "o".into(),
        value: 1e6,
    });
    let outlines = outline_font(&kern, 0.5);
    assert_eq!(
        otf(&outlines).unwrap_err().to_string(),
        "kerning o o is 1000000, outside the OpenType range -32768..=32767"
    );

    let mut many = font.clone();
    many.glyphs
        .extend((0..65535).map(|i| glyph(&format!("g{i}"), &[], 100.0, vec![])));
    let outlines = outline_font(&many, 0.5);
    assert_eq!(
        ttf(&outlines).unwrap_err().to_string(),
        "65543 glyphs: an OpenType font holds at most 65535"
    );
}

#[test]
fn specimen_escapes_and_expects_the_advances() {
    let (_, mut font) = mini();
    assert_eq!(specimen_text(&font), "AVoó. AV Vo");
    let html = specimen_html(&font, "MiniTest-Regular.ttf");
    // A+V-60, V+o-40, ó, period, space, A+V-60, space, V+o-40.
    assert!(html.contains(r#"data-expected="5340.000""#), "{html}");
    assert!(html.contains(r#"src: url("MiniTest-Regular.ttf")"#));
    assert!(html.contains(">AVoó. AV Vo</span>"));

    font.info.family = "<b>Mini & \"Test\"</b>".into();
    font.glyphs[1].name = "A<script>".into();
    let html = specimen_html(&font, "a b\").ttf");
    assert!(html.contains("&lt;b&gt;Mini &amp; &quot;Test&quot;&lt;/b&gt;"));
    assert!(html.contains("A&lt;script&gt;"));
    assert!(!html.contains("<b>Mini"));
    assert!(!html.contains("A<script>"));
    assert!(html.contains(r#"src: url("a%20b%22%29.ttf")"#));
}

#[test]
fn a_specimen_shows_its_first_kerning_pairs_and_how_many_there_are() {
    // Every pair of 32 Cyrillic letters kerned: 1,024 pairs. An import that expands class
    // kerning gets hundreds of thousands (Lato Regular: about 273,000); the page listed and
    // measured them all, and its width sum searched the kerning list once per character,
    // which took minutes.
    let (mut font, _) = mini();
    let letters: Vec<char> = ('а'..='я').collect();
    for (i, &c) in letters.iter().enumerate() {
        font.glyphs
            .push(glyph(&format!("cyr{i}"), &[c], 500.0 + i as f64, vec![]));
    }
    let before = font.kerning.len();
    for i in 0..letters.len() {
        for j in 0..letters.len() {
            font.kerning.push(KernPair {
                left: format!("cyr{i}"),
                right: format!("cyr{j}"),
                value: -((i + j) as f64),
            });
        }
    }
    let outlines = outline_font(&font, font.info.tolerance);
    let html = specimen_html(&outlines, "Mini.ttf");
    let rows = html.matches(r#"<tr><td class="font""#).count();
    assert_eq!(rows, xglyph::otf::KERN_ROWS);
    // The mini font's own pairs come first: two of them can be typed.
    assert!(before >= 2);
    assert!(
        html.contains("<p>The first 500 of 1026 pairs that can be typed.</p>"),
        "{}",
        &html[..2000]
    );
    // The measured line: the sample, then the pairs shown; its expected width is the sum
    // of advances and of the kerning between neighbours, counted here by a plain search.
    let text = specimen_text(&outlines);
    assert_eq!(text.split(' ').count(), 1 + xglyph::otf::KERN_ROWS);
    let by_char = |c: char| outlines.glyphs.iter().find(|g| g.unicodes.contains(&c));
    let mut width = 0.0;
    let mut prev: Option<&str> = None;
    for c in text.chars() {
        let Some(g) = by_char(c) else { continue };
        if let Some(p) = prev {
            width += outlines.kern(p, &g.name);
        }
        width += g.advance.round();
        prev = Some(&g.name);
    }
    assert!(
        html.contains(&format!(r#"data-expected="{width:.3}""#)),
        "{width}"
    );
}

#[test]
fn chromium_measures_the_specimen_line_as_expected_with_invisible_and_greek_letters() {
    // The mini font plus a soft hyphen (which browsers draw as nothing) and a Greek Alpha
    // kerned against the Latin A (pairs of two script runs, which browsers do not kern).
    // The page counted both: imported Gentium's line measured 690 px short, Lato's 613.
    let Some(mut browser) = crate::studio_browser::Browser::start() else {
        return;
    };
    let (mut font, _) = mini();
    font.glyphs
        .push(glyph("softhyphen", &['\u{AD}'], 333.0, vec![]));
    font.glyphs.push(glyph("Alpha", &['Α'], 640.0, vec![]));
    for (left, right, value) in [
        ("A", "Alpha", -150.0),
        ("Alpha", "A", -120.0),
        ("Alpha", "Alpha", -45.0),
    ] {
        font.kerning.push(KernPair {
            left: left.into(),
            right: right.into(),
            value,
        });
    }
    let outlines = outline_font(&font, font.info.tolerance);
    assert_eq!(specimen_text(&outlines), "AVoó.Α AV Vo ΑΑ");
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("Mini.ttf"), ttf(&outlines).unwrap()).unwrap();
    let page = dir.path().join("specimen.html");
    std::fs::write(&page, specimen_html(&outlines, "Mini.ttf")).unwrap();
    browser.open_until(
        &format!("file://{}", page.display()),
        "document.getElementById('font-check')?.dataset.loaded === 'yes'",
    );
    let attr = |browser: &mut crate::studio_browser::Browser, name: &str| {
        let v = browser.eval(&format!(
            "parseFloat(document.getElementById('font-check').getAttribute('{name}'))"
        ));
        v.as_f64().unwrap()
    };
    let (width, expected) = (
        attr(&mut browser, "data-width"),
        attr(&mut browser, "data-expected"),
    );
    // A+V −60, V+o −40, Α+Α −45; no soft hyphen, no A|Α across the runs.
    let advances: f64 = [
        "A", "V", "o", "oacute", "period", "Alpha", "space", "A", "V", "space", "V", "o", "space",
        "Alpha", "Alpha",
    ]
    .iter()
    .map(|n| outlines.glyph(n).unwrap().advance.round())
    .sum();
    assert_eq!(expected, advances - 60.0 - 40.0 - 60.0 - 40.0 - 45.0);
    assert!(
        (width - expected).abs() <= 0.5,
        "Chromium {width} px, expected {expected} px"
    );
}

#[test]
fn names_styles_and_em_size_from_the_model() {
    let (mut font, _) = mini();
    font.info.style = "Light Italic".into();
    font.info.copyright = Some("© 2026 The Mini Authors".into());
    font.info.designer = Some("Ada Designer".into());
    font.info.version = Some("2.5".into());
    font.info.units_per_em = 2048;
    let outlines = outline_font(&font, font.info.tolerance);
    for (bytes, cff) in [
        (ttf(&outlines).unwrap(), false),
        (otf(&outlines).unwrap(), true),
    ] {
        let face = Face::parse(&bytes, 0).unwrap();
        let names: Vec<(u16, String)> = face
            .names()
            .into_iter()
            .filter_map(|n| Some((n.name_id, n.to_string()?)))
            .collect();
        let want: Vec<(u16, String)> = [
            (0, "© 2026 The Mini Authors"),
            (1, "Mini Test Light"),
            (2, "Italic"),
            (3, "2.500;XGLY;MiniTest-LightItalic"),
            (4, "Mini Test Light Italic"),
            (5, "Version 2.500"),
            (6, "MiniTest-LightItalic"),
            (9, "Ada Designer"),
            (16, "Mini Test"),
            (17, "Light Italic"),
        ]
        .into_iter()
        .map(|(id, s)| (id, s.to_owned()))
        .collect();
        assert_eq!(names, want);
        assert_eq!(face.units_per_em(), 2048);
        assert!(face.is_italic());
        assert!(!face.is_bold());
        assert_eq!(face.weight(), ttf_parser::Weight::Light);
        let head = face.tables().head;
        assert_eq!(head.units_per_em, 2048);
        // Outlines stay in font units (the model's coordinates, not rescaled).
        let a = face.glyph_bounding_box(GlyphId(1)).unwrap();
        assert_eq!((a.x_min, a.x_max, a.y_max), (20, 620, 700));
        let raw = face.raw_face().table(ttf_parser::Tag::from_bytes(b"CFF "));
        assert_eq!(raw.is_some(), cff);
        if let Some(cff_table) = raw {
            // FontMatrix [1/2048 0 0 1/2048 0 0]: 4.8828125E-4 as a DICT real, then `12 7`.
            let scale = [0x1e, 0x4a, 0x88, 0x28, 0x12, 0x5c, 0x4f];
            let zero = [0x1e, 0x0f];
            let matrix: Vec<u8> =
                [&scale[..], &zero, &zero, &scale, &zero, &zero, &[12, 7]].concat();
            assert!(cff_table.windows(matrix.len()).any(|w| w == matrix));
            assert_eq!(&cff_table[..4], [1, 0, 4, 4]);
        }
    }
}

#[test]
fn bold_style_bits_and_overlap_flag() {
    let (mut font, _) = mini();
    font.info.style = "Bold".into();
    let outlines = outline_font(&font, font.info.tolerance);
    let bytes = ttf(&outlines).unwrap();
    let face = Face::parse(&bytes, 0).unwrap();
    assert!(face.is_bold());
    assert!(!face.is_italic());
    // OS/2.fsSelection (offset 62): BOLD | USE_TYPO_METRICS, not REGULAR.
    let os2 = face
        .raw_face()
        .table(ttf_parser::Tag::from_bytes(b"OS/2"))
        .unwrap();
    assert_eq!(u16::from_be_bytes([os2[62], os2[63]]), 0x00A0);
    assert_eq!(face.weight(), ttf_parser::Weight::Bold);
    let ids: Vec<u16> = face.names().into_iter().map(|n| n.name_id).collect();
    assert_eq!(ids, [1, 2, 3, 4, 5, 6]);
    // head.macStyle (offset 44): bold bit.
    let head = face
        .raw_face()
        .table(ttf_parser::Tag::from_bytes(b"head"))
        .unwrap();
    assert_eq!(u16::from_be_bytes([head[44], head[45]]), 1);
    // oacute (gid 5) is built from components: OVERLAP_SIMPLE on its first point's flags;
    // o (gid 4) is not.
    let glyf = face
        .raw_face()
        .table(ttf_parser::Tag::from_bytes(b"glyf"))
        .unwrap();
    let loca = face
        .raw_face()
        .table(ttf_parser::Tag::from_bytes(b"loca"))
        .unwrap();
    let offset = |gid: usize| -> usize {
        if face.tables().head.index_to_location_format
            == ttf_parser::head::IndexToLocationFormat::Short
        {
            usize::from(u16::from_be_bytes([loca[2 * gid], loca[2 * gid + 1]])) * 2
        } else {
            u32::from_be_bytes(loca[4 * gid..4 * gid + 4].try_into().unwrap()) as usize
        }
    };
    let first_flag = |gid: usize| {
        let g = &glyf[offset(gid)..];
        let contours = usize::from(u16::from_be_bytes([g[0], g[1]]));
        let ins_at = 10 + 2 * contours;
        let ins_len = usize::from(u16::from_be_bytes([g[ins_at], g[ins_at + 1]]));
        g[ins_at + 2 + ins_len]
    };
    assert_eq!(first_flag(5) & 0x40, 0x40);
    assert_eq!(first_flag(4) & 0x40, 0);
}

#[test]
fn large_kerning_survives_packing() {
    let (mut font, _) = mini();
    for i in 0..400u32 {
        let c = char::from_u32(0x4E00 + i).unwrap();
        font.glyphs
            .push(glyph(&format!("g{i:03}"), &[c], 500.0, Vec::new()));
    }
    for i in 0..400 {
        for j in 0..100 {
            font.kerning.push(KernPair {
                left: format!("g{i:03}"),
                right: format!("g{:03}", (i + j) % 400),
                value: -10.0 - f64::from(j),
            });
        }
    }
    let outlines = outline_font(&font, 0.5);
    let bytes = otf(&outlines).unwrap();
    let face = Face::parse(&bytes, 0).unwrap();
    let gpos = face.tables().gpos.unwrap();
    let lookup = gpos.lookups.get(0).unwrap();
    // 40 002 pairs do not fit one 16-bit-offset subtable: write-fonts splits them (and
    // promotes the lookup to Extension); every pair must still be found.
    assert!(lookup.subtables.len() > 1);
    let kern = |l: u16, r: u16| {
        (0..lookup.subtables.len()).find_map(|i| {
            match lookup
                .subtables
                .get::<ttf_parser::gpos::PositioningSubtable>(i)?
            {
                ttf_parser::gpos::PositioningSubtable::Pair(
                    ttf_parser::gpos::PairAdjustment::Format1 { coverage, sets },
                ) => sets
                    .get(coverage.get(GlyphId(l))?)?
                    .get(GlyphId(r))
                    .map(|(v, _)| v.x_advance),
                _ => None,
            }
        })
    };
    // Glyph ids: .notdef, A, V, acutecomb, o, oacute, period, space, g000 = 8, ...
    assert_eq!(kern(8, 9), Some(-11));
    assert_eq!(kern(8 + 399, 8 + 98), Some(-109));
    assert_eq!(kern(8 + 399, 8 + 99), None);
    assert_eq!(kern(1, 2), Some(-60));
    let pairs: usize = (0..400u16)
        .flat_map(|l| (0..400u16).map(move |r| (l, r)))
        .filter(|&(l, r)| kern(8 + l, 8 + r).is_some())
        .count();
    assert_eq!(pairs, 40_000);
    // The legacy table cannot hold them: left out of the TTF.
    let ttf_bytes = ttf(&outlines).unwrap();
    assert!(Face::parse(&ttf_bytes, 0).unwrap().tables().kern.is_none());
}

/// Every glyph of the bundled typeface (glyphs/) reads back within the bounds.
#[test]
fn bundled_typeface_reads_back_within_bounds() {
    let (font, _) = load_font(Path::new("glyphs")).expect("glyphs/ loads");
    let outlines = outline_font(&font, font.info.tolerance);
    let order = glyph_order(&outlines).unwrap();
    let mut worst = [0.0f64; 2];
    for (i, (bytes, bound)) in [
        (ttf(&outlines).unwrap(), font.info.tolerance + GRID),
        (otf(&outlines).unwrap(), PULLED),
    ]
    .into_iter()
    .enumerate()
    {
        let face = Face::parse(&bytes, 0).unwrap();
        assert_eq!(usize::from(face.number_of_glyphs()), order.len());
        for (gid, g) in order.iter().enumerate() {
            let Some(exact) = outlines.glyph(&g.model_name).map(|o| &o.path) else {
                continue; // synthesised .notdef
            };
            assert_eq!(
                face.glyph_name(GlyphId(gid as u16)),
                Some(g.ps_name.as_str())
            );
            assert_eq!(face.glyph_hor_advance(GlyphId(gid as u16)), Some(g.advance));
            let built = outline(&face, gid as u16);
            assert_eq!(
                contour_count(&built),
                contour_count(exact),
                "{}",
                g.model_name
            );
            let d = distance(&built, exact);
            assert!(d <= bound, "{}: {d} > {bound}", g.model_name);
            worst[i] = worst[i].max(d);
        }
    }
    eprintln!(
        "bundled typeface: TTF worst {:.4}, OTF worst {:.4}",
        worst[0], worst[1]
    );
}
