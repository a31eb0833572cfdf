//! `xglyph import` of SVG drawings (tests/fixtures/import: transforms, arcs, a skewed
//! rounded rectangle, holes by even-odd and by nonzero; strokes with their widths, joins,
//! caps, miter limits and dashes, alone and with fills): the imported glyphs, built to
//! Béziers, render like the originals (resvg).
//!
//! Both are rasterised at 240 px per canvas height: the original with resvg, the glyph
//! (import -> sources -> load -> outline_font) with tiny-skia, in the same frame. At most
//! 0.05 % of the pixels may differ in coverage by more than half, and 0.1 % by more than a
//! quarter (the import tolerance, 1 unit of a 1000-unit em, is a quarter pixel here, so
//! only a few edge pixels may change much). A 2-pixel shift of the same glyph is checked
//! to fail by far, so the comparison can fail.

use std::path::{Path, PathBuf};

use kurbo::{BezPath, PathEl};
use tiny_skia::{FillRule, Paint, PathBuilder, Pixmap, Transform};
use xglyph::import::{import_svgs, ImportOptions};
use xglyph::outline::{outline_font, OutlinedFont};
use xglyph::source::emit::font_sources;
use xglyph::source::load_font;
use xglyph::Font;

const PX: f64 = 240.0;
const DIR: &str = "tests/fixtures/import";

fn fixture(name: &str) -> (PathBuf, Vec<u8>) {
    let path = Path::new(DIR).join(name);
    let data = std::fs::read(&path).unwrap();
    (path, data)
}

fn render_original(data: &[u8]) -> Pixmap {
    let tree = usvg::Tree::from_data(data, &usvg::Options::default()).unwrap();
    let size = tree.size();
    let k = PX as f32 / size.height();
    let mut pixmap = Pixmap::new(
        (size.width() * k).round() as u32,
        (size.height() * k).round() as u32,
    )
    .unwrap();
    resvg::render(&tree, Transform::from_scale(k, k), &mut pixmap.as_mut());
    pixmap
}

/// The glyph in the original's pixel frame: font units (y up, canvas top at the ascender
/// 800, canvas height = 1000 units) -> pixels, shifted right by `shift` pixels.
fn render_glyph(path: &BezPath, width: u32, height: u32, shift: f64) -> Pixmap {
    let k = PX / 1000.0;
    let map = |p: kurbo::Point| ((p.x * k + shift) as f32, ((800.0 - p.y) * k) as f32);
    let mut pb = PathBuilder::new();
    for el in path.elements() {
        match *el {
            PathEl::MoveTo(p) => {
                let (x, y) = map(p);
                pb.move_to(x, y);
            }
            PathEl::LineTo(p) => {
                let (x, y) = map(p);
                pb.line_to(x, y);
            }
            PathEl::QuadTo(a, p) => {
                let ((ax, ay), (x, y)) = (map(a), map(p));
                pb.quad_to(ax, ay, x, y);
            }
            PathEl::CurveTo(a, b, p) => {
                let ((ax, ay), (bx, by), (x, y)) = (map(a), map(b), map(p));
                pb.cubic_to(ax, ay, bx, by, x, y);
            }
            PathEl::ClosePath => pb.close(),
        }
    }
    let mut pixmap = Pixmap::new(width, height).unwrap();
    let mut paint = Paint::default();
    paint.set_color_rgba8(0, 0, 0, 255);
    paint.anti_alias = true;
    pixmap.fill_path(
        &pb.finish().unwrap(),
        &paint,
        FillRule::Winding,
        Transform::identity(),
        None,
    );
    pixmap
}

/// Pixels whose alpha differs by more than `threshold` (of 255), and pixels covered at
/// least half in `a`.
fn compare(a: &Pixmap, b: &Pixmap, threshold: u8) -> (usize, usize) {
    let alpha = |p: &Pixmap| p.pixels().iter().map(|c| c.alpha()).collect::<Vec<u8>>();
    let (aa, bb) = (alpha(a), alpha(b));
    let differ = aa
        .iter()
        .zip(&bb)
        .filter(|(x, y)| x.abs_diff(**y) > threshold)
        .count();
    let covered = aa.iter().filter(|&&x| x > 127).count();
    (differ, covered)
}

#[test]
fn svg_icons_render_like_the_originals() {
    let names = ["ring.svg", "house.svg", "drop.svg"];
    let files: Vec<(PathBuf, Vec<u8>)> = names.iter().map(|n| fixture(n)).collect();
    let mut opts = ImportOptions::default();
    opts.codepoints.insert("ring".into(), '\u{E100}');
    opts.codepoints.insert("house".into(), 'h');
    let imp = import_svgs(&files, &opts).unwrap();
    eprint!("{}", imp.report.render());

    // Through the sources: write, load (as `xglyph check` does), build.
    let dir = std::env::temp_dir().join(format!("xglyph-import-svg-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    for (name, text) in font_sources(&imp.font) {
        std::fs::write(dir.join(name), text).unwrap();
    }
    let (font, warnings) = load_font(&dir).unwrap();
    assert!(warnings.is_empty());
    let _ = std::fs::remove_dir_all(&dir);
    let built = outline_font(&font, font.info.tolerance);

    assert_eq!(font.info.units_per_em, 1000);
    assert_eq!(font.info.family, "Imported Icons");
    assert_eq!(font.info.tolerance, 0.25);
    let unicodes: Vec<(&str, Vec<char>, f64)> = font
        .glyphs
        .iter()
        .map(|g| (g.name.as_str(), g.unicodes.clone(), g.advance))
        .collect();
    assert_eq!(
        unicodes,
        vec![
            ("drop", vec!['\u{E000}'], 1333.3),
            ("house", vec!['h'], 1000.0),
            ("ring", vec!['\u{E100}'], 1000.0),
        ]
    );
    // Contours: ring 2 (outer, hole); house 2 (the outline, unioned with the rounded rect
    // that overlaps it as a chimney, and the door); drop 3.
    let contours: Vec<usize> = font.glyphs.iter().map(|g| g.contours.len()).collect();
    assert_eq!(contours, vec![3, 2, 2]);
    for row in &imp.report.rows {
        assert!(row.max_error <= 0.75, "{}: {}", row.name, row.max_error);
    }

    assert_renders_like_originals(&names, &files, &built);
}

/// Each drawing's glyph, built, against resvg's rendering of the original (limits in the
/// module docs); a 2-pixel shift must fail by far.
fn assert_renders_like_originals(
    names: &[&str],
    files: &[(PathBuf, Vec<u8>)],
    built: &OutlinedFont,
) {
    for (name, (_, data)) in names.iter().zip(files) {
        let stem = name.trim_end_matches(".svg");
        let original = render_original(data);
        let glyph = built.glyph(&stem.replace('-', "_")).unwrap();
        let (w, h) = (original.width(), original.height());
        let rendered = render_glyph(&glyph.path, w, h, 0.0);
        let (differ, covered) = compare(&original, &rendered, 127);
        let (edge, _) = compare(&original, &rendered, 63);
        let total = (w * h) as usize;
        let limit = total / 2000;
        eprintln!(
            "{name}: {differ} of {total} pixels differ by > 1/2 (limit {limit}), \
             {edge} by > 1/4 (limit {}), {covered} covered",
            2 * limit
        );
        assert!(
            covered > total / 10,
            "{name}: the drawing covers too little"
        );
        assert!(differ <= limit, "{name}: {differ} pixels differ");
        assert!(
            edge <= 2 * limit,
            "{name}: {edge} pixels differ by a quarter"
        );
        let (shifted, _) = compare(&original, &render_glyph(&glyph.path, w, h, 2.0), 127);
        assert!(
            shifted > 20 * limit.max(1),
            "{name}: a shift gives only {shifted}"
        );
    }
}

/// Imports `names` through the sources (write, load as `xglyph check` does, build).
fn import_and_build(
    names: &[&str],
    opts: &ImportOptions,
) -> (Vec<(PathBuf, Vec<u8>)>, Font, OutlinedFont) {
    let files: Vec<(PathBuf, Vec<u8>)> = names.iter().map(|n| fixture(n)).collect();
    let imp = import_svgs(&files, opts).unwrap();
    eprint!("{}", imp.report.render());
    for row in &imp.report.rows {
        assert!(row.max_error <= 0.75, "{}: {}", row.name, row.max_error);
        assert_eq!(row.dropped_contours, 0, "{}", row.name);
    }
    let dir = std::env::temp_dir().join(format!(
        "xglyph-import-svg-{}-{}",
        std::process::id(),
        names.len()
    ));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    for (name, text) in font_sources(&imp.font) {
        std::fs::write(dir.join(name), text).unwrap();
    }
    let (font, warnings) = load_font(&dir).unwrap();
    assert!(warnings.is_empty());
    let _ = std::fs::remove_dir_all(&dir);
    let built = outline_font(&font, font.info.tolerance);
    (files, font, built)
}

#[test]
fn svg_strokes_render_like_the_originals() {
    // Strokes become outlines (tiny-skia's stroker: widths, joins, caps, miter limits,
    // dashes), unioned with the fills: compared with resvg's rendering of the strokes.
    let names = [
        "stroke-circle.svg",
        "stroke-polyline.svg",
        "stroke-rect.svg",
        "stroke-mixed.svg",
    ];
    let (files, font, built) = import_and_build(&names, &ImportOptions::default());
    let contours: Vec<(&str, usize)> = font
        .glyphs
        .iter()
        .map(|g| (g.name.as_str(), g.contours.len()))
        .collect();
    // circle: a ring (2); polyline: one outline around the two holes where it crosses
    // itself (3); rect: the rotated frame (2) and the two chevrons, whose square caps
    // overlap (1); mixed: the triangle, the circle with the curve across it, the even-odd
    // ring (2), and three dashes with round caps (3).
    assert_eq!(
        contours,
        vec![
            ("stroke_circle", 2),
            ("stroke_mixed", 7),
            ("stroke_polyline", 3),
            ("stroke_rect", 3),
        ]
    );
    assert_renders_like_originals(&names, &files, &built);
}

#[test]
fn svg_clip_paths_keep_only_what_shows() {
    // Clip paths: a rectangle, an even-odd ring, one in the clipped shape's own box, one
    // with its own transform and its own clip path; and a square wholly outside the
    // canvas, left out with a note.
    let names = ["clip.svg"];
    let (files, font, built) = import_and_build(&names, &ImportOptions::default());
    // The half disc, the ring (2), the disc and the diamond's lower corner.
    assert_eq!(font.glyphs[0].contours.len(), 5);
    assert_renders_like_originals(&names, &files, &built);
    let imp = import_svgs(&files, &ImportOptions::default()).unwrap();
    assert_eq!(
        imp.report.notes,
        vec![format!(
            "{}: 1 path(s) wholly outside the canvas left out (no viewer shows them)",
            files[0].0.display()
        )]
    );
}

/// Liberation Mono Bold `sigma1` (2048 units per em, its TrueType outline as an SVG at one
/// unit per unit): a line meets the tail's curve at a sharp corner. Held on the original's
/// tangent ray there, the corner's neighbour once came out 8 units behind the corner, so the
/// X-spline left the corner backwards and hooked round (within the tolerance, but the
/// built font crossed itself beside the corner, as FontForge reported). It must lie ahead.
#[test]
fn a_corner_is_left_forwards_never_in_a_hook() {
    // y down: the font's y is 1638.4 - y here (the canvas is the em, ascender 0.8 em).
    let svg = "<svg xmlns='http://www.w3.org/2000/svg' viewBox='0 0 1229 2048'>\
        <path d='M420,1163.4 Q420,1266.4 481,1324.4 Q542,1382.4 708,1421.4 \
        Q895,1465.4 966.5,1503.4 Q1038,1541.4 1074.5,1599.4 Q1111,1657.4 1111,1748.4 \
        Q1111,1806.4 1079,1887.9 Q1047,1969.4 998,2039.4 L820,1965.4 Q880,1869.4 880,1811.4 \
        Q880,1772.4 853.5,1745.4 Q827,1718.4 773,1698.4 Q719,1678.4 552,1646.4 \
        Q406,1619.4 322.5,1562 Q239,1504.4 199,1415.4 Q159,1326.4 159,1200.4 \
        Q159,1022.4 231,860.4 Q303,698.4 423.5,617.4 Q544,536.4 701,536.4 \
        Q935,536.4 1092,707.4 L946,863.4 Q822,733.4 689,733.4 Q613,733.4 552.5,786.4 \
        Q492,839.4 456,942.4 Q420,1045.4 420,1163.4 Z'/></svg>";
    let files = vec![(PathBuf::from("sigma1.svg"), svg.as_bytes().to_vec())];
    let opts = ImportOptions {
        units_per_em: Some(2048),
        ..ImportOptions::default()
    };
    let imp = import_svgs(&files, &opts).unwrap();
    let glyph = &imp.font.glyphs[0];
    let points = glyph.contours[0].points();
    // The corner where the line from (998, -401) meets the tail, which leaves it toward
    // (880, -231) in the font's y-up units.
    let corner = kurbo::Point::new(820.0, -327.0);
    let tangent = kurbo::Vec2::new(60.0, 96.0);
    let n = points.len();
    let at = points
        .iter()
        .position(|p| (p.pos - corner).hypot() < 1e-6)
        .expect("the corner is a control point");
    assert_eq!(points[at].s, 0.0);
    // Its neighbour on the tail's side: the one not on the line toward (998, -401).
    let line = kurbo::Point::new(998.0, -401.0) - corner;
    let sides = [points[(at + 1) % n], points[(at + n - 1) % n]];
    let tail = sides
        .iter()
        .map(|p| p.pos - corner)
        .find(|v| v.cross(line).abs() > 1e-6 * v.hypot() * line.hypot())
        .expect("a neighbour off the line");
    assert!(
        tail.dot(tangent) > 0.0,
        "the X-spline leaves the corner toward {tail:?}, behind the tail's tangent {tangent:?}"
    );
    for row in &imp.report.rows {
        assert!(row.max_error <= 2.048, "{}: {}", row.name, row.max_error);
    }
}
