//! SVG outputs: the glyph set renders like the BezPaths, the SVG font parses back to the
//! same glyphs, advances, code points, kerning and paths, and hostile names stay valid XML.

use std::path::Path;

use kurbo::{Affine, BezPath, PathEl, Point, Shape};
use tiny_skia::{Color, Pixmap, Transform};
use xglyph::model::{Contour, Font, FontInfo, Glyph, KernPair};
use xglyph::outline::{outline_font, OutlinedFont};
use xglyph::render::draw::{fill_glyph, Placement};
use xglyph::source::load_font;
use xglyph::svg::glyph_set::horizontal_extent;
use xglyph::svg::{glyph_set, output_stem, svg_font};
use xglyph::xspline::ControlPoint;

/// Coordinates are written to 1/100 unit: a parsed number is within this of the original.
const ROUNDING: f64 = 0.005 + 1e-9;

fn mini() -> (Font, OutlinedFont) {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/mini");
    let (font, _) = load_font(&dir).expect("mini loads");
    let outlines = outline_font(&font, font.info.tolerance);
    (font, outlines)
}

/// The path without a line back to the start right before a close (`Z` draws it).
fn without_closing_lines(path: &BezPath) -> Vec<PathEl> {
    let els = path.elements();
    let mut start = Point::ORIGIN;
    let mut out = Vec::new();
    for (i, el) in els.iter().enumerate() {
        match *el {
            PathEl::MoveTo(p) => start = p,
            PathEl::LineTo(p) if p == start && els.get(i + 1) == Some(&PathEl::ClosePath) => {
                continue
            }
            _ => {}
        }
        out.push(*el);
    }
    out
}

/// Largest coordinate difference between two paths with the same commands; panics when the
/// commands differ.
fn max_point_difference(parsed: &BezPath, original: &BezPath) -> f64 {
    let (a, b) = (
        without_closing_lines(parsed),
        without_closing_lines(original),
    );
    assert_eq!(a.len(), b.len(), "element counts differ");
    let mut worst: f64 = 0.0;
    for (x, y) in a.iter().zip(&b) {
        let pts = |el: &PathEl| -> Vec<Point> {
            match *el {
                PathEl::MoveTo(p) | PathEl::LineTo(p) => vec![p],
                PathEl::QuadTo(p, q) => vec![p, q],
                PathEl::CurveTo(p, q, r) => vec![p, q, r],
                PathEl::ClosePath => vec![],
            }
        };
        assert_eq!(
            std::mem::discriminant(x),
            std::mem::discriminant(y),
            "{x:?} vs {y:?}"
        );
        for (p, q) in pts(x).into_iter().zip(pts(y)) {
            worst = worst.max((p.x - q.x).abs()).max((p.y - q.y).abs());
        }
    }
    worst
}

/// Per glyph SVG: parse with usvg, render with resvg, and draw the BezPath with tiny-skia in
/// the same place; compare coverage (alpha) pixel by pixel.
///
/// Stated threshold: against the unrounded BezPath, a pixel's coverage may differ by at most
/// 16/255 (tiny-skia anti-aliases with 16 samples per pixel, and rounding the path data to
/// 1/100 unit moves an edge by up to 0.0025 px here, which can flip one sample), on at most
/// 0.2% of the inked pixels. Against the path read back from the file's own `d`, drawn
/// straight with tiny-skia, resvg must match exactly.
#[test]
fn glyph_svgs_render_like_the_bezpaths() {
    let (font, outlines) = mini();
    let set = glyph_set(&outlines);
    assert_eq!(set.len(), outlines.glyphs.len());
    // Pixels per font unit: a 1000-unit em becomes 250 px.
    let scale = 0.25;
    let mut worst_alpha = 0;
    let mut differing = 0;
    let mut inked = 0;
    for (file, glyph) in set.iter().zip(&outlines.glyphs) {
        let tree = usvg::Tree::from_str(&file.svg, &usvg::Options::default())
            .unwrap_or_else(|e| panic!("{}: usvg cannot parse: {e}", file.stem));
        let (x0, width) = horizontal_extent(&font.info, glyph);
        let height = font.info.ascender - font.info.descender;
        assert_eq!(
            (
                f64::from(tree.size().width()),
                f64::from(tree.size().height())
            ),
            (width, height),
            "{}: size",
            file.stem
        );
        let (w, h) = ((width * scale) as u32, (height * scale) as u32);
        let mut from_svg = Pixmap::new(w, h).unwrap();
        resvg::render(
            &tree,
            Transform::from_scale(scale as f32, scale as f32),
            &mut from_svg.as_mut(),
        );
        let at = Placement {
            scale,
            origin_x: -x0 * scale,
            baseline_y: font.info.ascender * scale,
        };
        let mut direct = Pixmap::new(w, h).unwrap();
        fill_glyph(&mut direct.as_mut(), &glyph.path, at, Color::BLACK);
        for (a, b) in from_svg.pixels().iter().zip(direct.pixels()) {
            let d = a.alpha().abs_diff(b.alpha());
            worst_alpha = worst_alpha.max(d);
            differing += usize::from(d > 0);
            inked += usize::from(b.alpha() > 0);
        }
        // The file's own path data, drawn straight: identical pixels.
        let doc = roxmltree::Document::parse(&file.svg).unwrap();
        if let Some(path) = doc.descendants().find(|n| n.has_tag_name("path")) {
            let read_back = Affine::FLIP_Y * BezPath::from_svg(attr(path, "d")).unwrap();
            let mut rounded = Pixmap::new(w, h).unwrap();
            fill_glyph(&mut rounded.as_mut(), &read_back, at, Color::BLACK);
            assert!(rounded.pixels() == from_svg.pixels(), "{}", file.stem);
        }
    }
    assert!(worst_alpha <= 16, "worst alpha difference {worst_alpha}");
    assert!(
        differing * 500 <= inked,
        "{differing} of {inked} pixels differ"
    );
    // The comparison looked at real ink: 7 inked glyphs, tens of thousands of pixels.
    assert!(inked > 20_000, "{inked}");
    eprintln!("{differing} of {inked} inked pixels differ, by at most {worst_alpha}/255");
}

#[test]
fn glyph_svg_paths_are_the_bezpaths_flipped() {
    let (font, outlines) = mini();
    for (file, glyph) in glyph_set(&outlines).iter().zip(&outlines.glyphs) {
        let doc = roxmltree::Document::parse(&file.svg).unwrap();
        let root = doc.root_element();
        let title = root.children().find(|n| n.has_tag_name("title")).unwrap();
        assert_eq!(title.text(), Some(glyph.name.as_str()));
        match root.children().find(|n| n.has_tag_name("path")) {
            Some(path) => {
                let parsed = BezPath::from_svg(path.attribute("d").unwrap()).unwrap();
                let worst = max_point_difference(&(Affine::FLIP_Y * parsed), &glyph.path);
                assert!(worst <= ROUNDING, "{}: {worst}", glyph.name);
            }
            None => assert!(glyph.path.elements().is_empty(), "{}", glyph.name),
        }
    }
    let a = glyph_set(&outlines)
        .into_iter()
        .find(|f| f.stem == "A_")
        .unwrap();
    assert!(
        a.svg
            .contains("width=\"640\" height=\"1000\" viewBox=\"0 -800 640 1000\""),
        "{}",
        a.svg
    );
    // A zero-advance mark's box widens to its ink (x 240..390).
    let mark = outlines.glyph("acutecomb").unwrap();
    assert_eq!(horizontal_extent(&font.info, mark), (0.0, 390.0));
}

fn attr<'a>(node: roxmltree::Node<'a, '_>, name: &str) -> &'a str {
    node.attribute(name)
        .unwrap_or_else(|| panic!("<{}> has no {name}", node.tag_name().name()))
}

fn num(node: roxmltree::Node<'_, '_>, name: &str) -> f64 {
    attr(node, name).parse().unwrap()
}

#[test]
fn svg_font_parses_back() {
    let (_, outlines) = mini();
    let text = svg_font(&outlines);
    let doc = roxmltree::Document::parse(&text).unwrap();
    let font_el = doc.descendants().find(|n| n.has_tag_name("font")).unwrap();
    let face = font_el
        .children()
        .find(|n| n.has_tag_name("font-face"))
        .unwrap();
    assert_eq!(attr(face, "font-family"), "Mini Test");
    assert_eq!(
        [
            "units-per-em",
            "ascent",
            "descent",
            "x-height",
            "cap-height"
        ]
        .map(|a| attr(face, a)),
        ["1000", "800", "200", "500", "700"]
    );
    let missing = font_el
        .children()
        .find(|n| n.has_tag_name("missing-glyph"))
        .unwrap();
    let notdef = outlines.glyph(".notdef").unwrap();
    assert_eq!(num(missing, "horiz-adv-x"), notdef.advance);
    // Outer contours clockwise: the IR's paths reversed.
    let parsed = BezPath::from_svg(attr(missing, "d")).unwrap();
    assert!(max_point_difference(&parsed, &notdef.path.reverse_subpaths()) <= ROUNDING);
    assert!(parsed.area() < 0.0, "{}", parsed.area());

    let glyphs: Vec<_> = font_el
        .children()
        .filter(|n| n.has_tag_name("glyph"))
        .collect();
    // Every glyph but .notdef (which is the missing-glyph), each with one code point.
    assert_eq!(glyphs.len(), 7);
    let mut worst: f64 = 0.0;
    for el in &glyphs {
        let name = attr(*el, "glyph-name");
        let g = outlines.glyph(name).unwrap();
        assert_eq!(num(*el, "horiz-adv-x"), g.advance, "{name}");
        let cps: Vec<char> = attr(*el, "unicode").chars().collect();
        assert_eq!(cps, g.unicodes, "{name}");
        let d = attr(*el, "d");
        if d.is_empty() {
            assert!(g.path.elements().is_empty(), "{name}");
            continue;
        }
        assert!(
            d.chars()
                .filter(|c| c.is_ascii_alphabetic())
                .all(|c| "MLCZ".contains(c)),
            "{name}: {d}"
        );
        let parsed = BezPath::from_svg(d).unwrap();
        worst = worst.max(max_point_difference(&parsed, &g.path.reverse_subpaths()));
        // kurbo's area is negative for a clockwise path (y up); a glyph's outer contours
        // outweigh its counters.
        assert!(parsed.area() < 0.0, "{name}: {}", parsed.area());
    }
    assert!(worst <= ROUNDING, "{worst}");
    let names: Vec<&str> = glyphs.iter().map(|n| attr(*n, "glyph-name")).collect();
    assert_eq!(
        names,
        ["A", "V", "acutecomb", "o", "oacute", "period", "space"]
    );
    // Code points are written as hexadecimal character references.
    assert!(text.contains("glyph-name=\"oacute\" unicode=\"&#xF3;\" horiz-adv-x=\"560\""));
    assert!(text.contains("glyph-name=\"space\" unicode=\"&#x20;\" horiz-adv-x=\"260\" d=\"\""));
    let kerns: Vec<(&str, &str, f64)> = font_el
        .children()
        .filter(|n| n.has_tag_name("hkern"))
        .map(|n| (attr(n, "g1"), attr(n, "g2"), num(n, "k")))
        .collect();
    assert_eq!(kerns, [("A", "V", 60.0), ("V", "o", 40.0)]);
}

fn triangle(name: &str, c: Option<char>) -> Glyph {
    Glyph {
        name: name.into(),
        unicodes: c.into_iter().collect(),
        advance: 500.0,
        contours: vec![Contour::new(vec![
            ControlPoint::new(50.0, 0.0, 0.0),
            ControlPoint::new(450.0, 0.0, 0.0),
            ControlPoint::new(250.0, 600.0, 0.0),
        ])
        .expect("a valid contour")],
        components: vec![],
        anchors: Vec::new(),
        outline_mark: false,
    }
}

#[test]
fn hostile_names_make_valid_xml_and_round_trip() {
    let names = ["<", "&", "\"q\"", "]]>", "a'<&>\"b"];
    let family = "Fam <&\"]]> 'ily'";
    let copyright = "© <b>&amp;</b> \"x\" ]]> --> line\nbreak";
    let font = Font {
        info: FontInfo {
            family: family.into(),
            style: "Bold <Italic>".into(),
            units_per_em: 1000,
            ascender: 750.0,
            descender: -250.0,
            x_height: 500.0,
            cap_height: 700.0,
            tolerance: 0.5,
            copyright: Some(copyright.into()),
            designer: Some("D & \"E\" <F>".into()),
            version: Some("1.0 ]]>".into()),
            license: None,
            license_url: None,
            vendor: None,
        },
        glyphs: names
            .iter()
            .enumerate()
            .map(|(i, n)| triangle(n, char::from_u32(0x41 + i as u32)))
            .collect(),
        kerning: vec![KernPair {
            left: "<".into(),
            right: "]]>".into(),
            value: -25.5,
        }],
        features: None,
    };
    let outlines = outline_font(&font, 0.5);
    let text = svg_font(&outlines);
    let doc = roxmltree::Document::parse(&text).unwrap_or_else(|e| panic!("{e}\n{text}"));
    let glyph_names: Vec<&str> = doc
        .descendants()
        .filter(|n| n.has_tag_name("glyph"))
        .map(|n| attr(n, "glyph-name"))
        .collect();
    assert_eq!(glyph_names, names);
    let face = doc
        .descendants()
        .find(|n| n.has_tag_name("font-face"))
        .unwrap();
    assert_eq!(attr(face, "font-family"), family);
    assert_eq!(attr(face, "font-weight"), "700");
    assert_eq!(attr(face, "font-style"), "italic");
    assert_eq!(
        (attr(face, "ascent"), attr(face, "descent")),
        ("750", "250")
    );
    let meta = doc
        .descendants()
        .find(|n| n.has_tag_name("metadata"))
        .unwrap();
    assert_eq!(
        meta.text(),
        Some(
            "Copyright: © <b>&amp;</b> \"x\" ]]> --> line\nbreak\nDesigner: D & \"E\" <F>\n\
             Version: 1.0 ]]>"
        )
    );
    let kern = doc.descendants().find(|n| n.has_tag_name("hkern")).unwrap();
    assert_eq!(
        (attr(kern, "g1"), attr(kern, "g2"), attr(kern, "k")),
        ("<", "]]>", "25.5")
    );
    let font_el = doc.descendants().find(|n| n.has_tag_name("font")).unwrap();
    // The id and the file stem have no white space and nothing unsafe in a file name.
    assert_eq!(attr(font_el, "id"), "Fam_&_]]_'ily'-Bold_Italic_");
    assert_eq!(output_stem(&font.info), "Fam_&_]]_'ily'-Bold_Italic_");

    let set = glyph_set(&outlines);
    let stems: Vec<&str> = set.iter().map(|f| f.stem.as_str()).collect();
    assert_eq!(stems, ["_", "&", "_q_", "___", "a'_&__b"]);
    for (file, name) in set.iter().zip(names) {
        let doc = roxmltree::Document::parse(&file.svg).unwrap();
        let title = doc.descendants().find(|n| n.has_tag_name("title")).unwrap();
        assert_eq!(title.text(), Some(name));
        usvg::Tree::from_str(&file.svg, &usvg::Options::default()).unwrap();
    }
}

#[test]
fn ascent_and_descent_sum_to_the_em() {
    let (_, mut outlines) = mini();
    outlines.info.ascender = 900.0;
    outlines.info.descender = -300.0;
    let doc_text = svg_font(&outlines);
    let doc = roxmltree::Document::parse(&doc_text).unwrap();
    let face = doc
        .descendants()
        .find(|n| n.has_tag_name("font-face"))
        .unwrap();
    // 300 / 1200 of the em is the descent.
    assert_eq!(
        (attr(face, "ascent"), attr(face, "descent")),
        ("750", "250")
    );
}
