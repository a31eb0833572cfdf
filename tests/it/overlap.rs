//! Overlap removal (`src/overlap.rs`) on the bundled typeface and on hand-made shapes.
//!
//! Oracles independent of linesweeper:
//! - crossings: every segment of a contour against a fine flattening (0.001 units) of every
//!   other contour's segments, and of its own non-adjacent ones, with kurbo's
//!   `PathSeg::intersect_line`; a crossing is a hit inside both pieces (not at an end);
//! - pixels: tiny-skia's nonzero fill of the reference and of the union, at 0.25 px per
//!   font unit (250 px per em) and at 1 px per unit for the small shapes, both flattened to
//!   lines within 1e-5 px first and offset by odd pixel fractions. The reference is the
//!   glyph's parts (the whole IR path, or for a composite each component's own outline):
//!   aliased, each part painted, at most [`aliased_limit`] pixels may differ; anti-aliased,
//!   the parts filled as one path, no pixel's coverage may differ by more than
//!   [`AA_LEVELS`] of 255 (an inner edge splits tiny-skia's supersampled coverage runs);
//! - distances: every union boundary point lies on the original boundary, and every original
//!   boundary point that is still a boundary (filled on exactly one side, by the original's
//!   winding) lies on the union's, both within [`MAX_SHIFT`] font units.

use kurbo::{
    Affine, BezPath, Circle, Line, ParamCurve, ParamCurveDeriv, PathEl, PathSeg, Point, Rect,
    Shape, Vec2,
};
use tiny_skia::{FillRule, Paint, PathBuilder, Pixmap, Transform};
use xglyph::outline::{outline_font, OutlinedFont, OutlinedGlyph};
use xglyph::overlap::{remove_overlaps, remove_overlaps_font, UNION_SHARE};
use xglyph::source::load_font;
use xglyph::Font;

use crate::common::paths::one_sided;

/// Largest per-pixel coverage difference (of 255) between the original and the union,
/// anti-aliased: one of tiny-skia's four sub-scanlines (an inner edge that the union
/// removes splits a coverage run, and each run's ends are rounded on their own). Was 32
/// until `j` over its shifted copy measured 47 with the session-9 fitter's cubics, its
/// union within 1.2e-4 units of the original and no aliased pixel differing.
const AA_LEVELS: u8 = 64;
/// Most pixels that may differ, aliased (pixel centres sampled by the nonzero rule), for a
/// glyph that covers `covered` pixels: 2, plus 1 in 2000. A pixel centre within about
/// 1/10000 px of both the union's edge and the original's can fall either way (tiny-skia's
/// fixed-point edges), which happens along nearly parallel crossing edges.
fn aliased_limit(covered: usize) -> usize {
    2 + covered / 2000
}

/// Largest distance between the union's boundary and the original's (font units).
const MAX_SHIFT: f64 = 5e-3;
/// How far off the curve [`kept_boundary_shift`] probes the winding (font units).
const PROBE: f64 = 1e-3;

fn contours(path: &BezPath) -> Vec<BezPath> {
    path.elements()
        .split_inclusive(|e| matches!(e, PathEl::ClosePath))
        .map(|els| BezPath::from_vec(els.to_vec()))
        .filter(|c| c.segments().next().is_some())
        .collect()
}

/// Non-degenerate segments of a contour, and each one flattened to lines.
fn pieces(contour: &BezPath) -> Vec<(PathSeg, Vec<Line>)> {
    contour
        .segments()
        .filter(|s| !matches!(s, PathSeg::Line(l) if l.p0 == l.p1))
        .map(|s| {
            let mut lines = Vec::new();
            let mut last = s.start();
            kurbo::flatten([PathEl::MoveTo(s.start()), s.as_path_el()], 1e-3, |el| {
                if let PathEl::LineTo(p) = el {
                    lines.push(Line::new(last, p));
                    last = p;
                }
            });
            (s, lines)
        })
        .collect()
}

/// Crossings between contours and of a contour with itself (adjacent segments excluded).
fn crossings(path: &BezPath) -> usize {
    const END: f64 = 1e-6;
    let all: Vec<Vec<(PathSeg, Vec<Line>)>> = contours(path).iter().map(pieces).collect();
    let mut count = 0;
    for (ci, a) in all.iter().enumerate() {
        for (cj, b) in all.iter().enumerate() {
            for (si, (seg, _)) in a.iter().enumerate() {
                for (sj, (_, lines)) in b.iter().enumerate() {
                    let n = a.len();
                    if ci == cj && (si == sj || (si + 1) % n == sj || (sj + 1) % n == si) {
                        continue;
                    }
                    if ci > cj || (ci == cj && si > sj) {
                        continue;
                    }
                    let bbox = seg.bounding_box();
                    for line in lines {
                        let lb = line.bounding_box();
                        if bbox.x0 <= lb.x1
                            && lb.x0 <= bbox.x1
                            && bbox.y0 <= lb.y1
                            && lb.y0 <= bbox.y1
                        {
                            count += seg
                                .intersect_line(*line)
                                .iter()
                                .filter(|x| x.segment_t > END && x.segment_t < 1.0 - END)
                                .filter(|x| x.line_t > END && x.line_t < 1.0 - END)
                                .count();
                        }
                    }
                }
            }
        }
    }
    count
}

/// Nonzero fill of each of `parts`, painted one over the other (their union), anti-aliased
/// or not, `scale` px per unit, the box `frame` in view.
fn render(parts: &[BezPath], frame: Rect, scale: f64, anti_alias: bool) -> Pixmap {
    let w = (frame.width() * scale).ceil() as u32 + 2;
    let h = (frame.height() * scale).ceil() as u32 + 2;
    // Offset by odd fractions of a pixel, so that no edge of a font-unit grid runs exactly
    // through pixel centres (where the aliased fill is a tie either way).
    let map = |p: Point| {
        (
            ((p.x - frame.x0) * scale + 1.0 + 0.1234) as f32,
            ((frame.y1 - p.y) * scale + 1.0 + 0.2345) as f32,
        )
    };
    let mut pixmap = Pixmap::new(w, h).unwrap();
    let mut paint = Paint::default();
    paint.set_color_rgba8(0, 0, 0, 255);
    paint.anti_alias = anti_alias;
    for path in parts {
        // Flattened here, finely (1e-5 px), so that tiny-skia's own coarser flattening of a
        // cubic and of a piece of it cannot differ by a pixel.
        let mut pb = PathBuilder::new();
        kurbo::flatten(path, 1e-5 / scale, |el| match el {
            PathEl::MoveTo(p) => {
                let (x, y) = map(p);
                pb.move_to(x, y);
            }
            PathEl::LineTo(p) => {
                let (x, y) = map(p);
                pb.line_to(x, y);
            }
            PathEl::ClosePath => pb.close(),
            PathEl::QuadTo(..) | PathEl::CurveTo(..) => unreachable!("flattened"),
        });
        if let Some(p) = pb.finish() {
            pixmap.fill_path(&p, &paint, FillRule::Winding, Transform::identity(), None);
        }
    }
    pixmap
}

/// Anti-aliased: the largest per-pixel coverage difference; aliased: the pixels that
/// differ; and the pixels the original covers (aliased).
fn pixel_diff(a: &[BezPath], b: &BezPath, scale: f64) -> (u8, usize, usize) {
    let frame = a
        .iter()
        .fold(b.bounding_box(), |r, p| r.union(p.bounding_box()));
    let b = std::slice::from_ref(b);
    // Anti-aliased, the parts are filled as one path: painted one over another, two edges
    // in one pixel would composite (a + b - ab), not cover. Aliased, each part is painted.
    let joined = [a.iter().flat_map(|p| p.iter()).collect::<BezPath>()];
    let alpha = |p: Pixmap| p.pixels().iter().map(|c| c.alpha()).collect::<Vec<u8>>();
    let smooth = |parts| alpha(render(parts, frame, scale, true));
    let worst = smooth(&joined)
        .iter()
        .zip(smooth(b))
        .map(|(x, y)| x.abs_diff(y))
        .max()
        .unwrap_or(0);
    let (sa, sb) = (
        alpha(render(a, frame, scale, false)),
        alpha(render(b, frame, scale, false)),
    );
    let differ = sa.iter().zip(&sb).filter(|(x, y)| x != y).count();
    let covered = sa.iter().filter(|&&x| x > 127).count();
    (worst, differ, covered)
}

/// Distance from the original's remaining boundary (samples filled on exactly one side, by
/// the original's nonzero winding, `side` units off the curve) to the union.
///
/// A sample within `side` of another contour can be taken for boundary although it lies
/// inside that contour (one probe crosses it), and its distance to the union is then up to
/// `side`: so `side` ([`PROBE`]) stays well below [`MAX_SHIFT`].
fn kept_boundary_shift(original: &BezPath, union: &BezPath, side: f64) -> f64 {
    let target = crate::common::paths::with_boxes(union);
    let mut hint = 0;
    let mut worst: f64 = 0.0;
    for seg in original.segments() {
        let deriv = seg.to_cubic().deriv();
        for i in 0..=32 {
            let t = f64::from(i) / 32.0;
            let d = deriv.eval(t).to_vec2();
            if d.hypot() == 0.0 {
                continue;
            }
            let n = Vec2::new(-d.y, d.x) / d.hypot() * side;
            let p = seg.eval(t);
            let left = original.winding(p + n) != 0;
            let right = original.winding(p - n) != 0;
            if left != right {
                let dist = crate::common::paths::to_segments(&target, p, &mut hint);
                worst = worst.max(dist);
            }
        }
    }
    worst
}

/// Vertices where a polygon turns (more than 1e-6 radians).
fn corners(path: &BezPath) -> usize {
    let mut n = 0;
    for c in contours(path) {
        let segs: Vec<PathSeg> = c.segments().filter(|s| s.start() != s.end()).collect();
        for (i, s) in segs.iter().enumerate() {
            let next = segs[(i + 1) % segs.len()];
            let (a, b) = (s.end() - s.start(), next.end() - next.start());
            n += usize::from(a.cross(b).atan2(a.dot(b)).abs() > 1e-6);
        }
    }
    n
}

/// Signed areas of the contours, outer (positive) first.
fn areas(path: &BezPath) -> Vec<f64> {
    let mut a: Vec<f64> = contours(path).iter().map(|c| c.area()).collect();
    a.sort_by(|x, y| y.total_cmp(x));
    a
}

/// Checks one unioned font against the font it came from; returns the names of the
/// glyphs whose contours crossed, and prints the measurements. `reference` gives a glyph's
/// parts, each oriented on its own: the union must fill what they fill together.
fn check_font(
    label: &str,
    font: &OutlinedFont,
    reference: impl Fn(&OutlinedGlyph) -> Vec<BezPath>,
) -> Vec<String> {
    let union = remove_overlaps_font(font);
    assert_eq!(union.glyphs.len(), font.glyphs.len());
    let mut overlapping = Vec::new();
    let (mut worst_px, mut worst_shift, mut worst_kept) = (0u8, 0.0f64, 0.0f64);
    let mut ink = 0;
    let mut worst_ratio = 0.0f64;
    let (mut worst_differ, mut total_differ) = (0, 0);
    let (mut segs_before, mut segs_after) = (0, 0);
    for (before, after) in font.glyphs.iter().zip(&union.glyphs) {
        assert_eq!(before.name, after.name);
        assert_eq!(
            after.segments,
            after.path.segments().count(),
            "{}",
            after.name
        );
        let parts = reference(before);
        let joined: BezPath = parts.iter().flat_map(|p| p.iter()).collect();
        let crossed = crossings(&joined);
        if crossed == 0 {
            // No crossing: the path is kept to the bit.
            assert!(
                before.path == after.path,
                "{label} {}: changed",
                before.name
            );
            continue;
        }
        overlapping.push(before.name.clone());
        assert!(before.path != after.path, "{label} {}: kept", before.name);
        assert_eq!(
            crossings(&after.path),
            0,
            "{label} {}: still crossing",
            after.name
        );
        let (px, differ, covered) = pixel_diff(&parts, &after.path, 0.25);
        assert!(
            differ <= aliased_limit(covered),
            "{label} {}: {differ} pixels differ",
            after.name
        );
        worst_differ = worst_differ.max(differ);
        worst_ratio = worst_ratio.max(differ as f64 / covered as f64);
        total_differ += differ;
        let shift = one_sided(&after.path, &joined, 16);
        let kept = kept_boundary_shift(&joined, &after.path, PROBE);
        assert!(
            px <= AA_LEVELS,
            "{label} {}: a pixel differs by {px}",
            after.name
        );
        assert!(covered > 100, "{label} {}: too little ink", after.name);
        assert!(
            shift <= MAX_SHIFT,
            "{label} {}: union {shift} off",
            after.name
        );
        assert!(kept <= MAX_SHIFT, "{label} {}: kept {kept} off", after.name);
        // The fit plus the union stay within the font's tolerance.
        assert!(after.max_error + shift.max(kept) <= font.tolerance);
        worst_px = worst_px.max(px);
        ink += covered;
        worst_shift = worst_shift.max(shift);
        worst_kept = worst_kept.max(kept);
        segs_before += before.segments;
        segs_after += after.segments;
    }
    eprintln!(
        "{label}: {} of {} glyphs crossed and were unioned; aliased {total_differ} of {ink} inked pixels differ (at most {worst_differ} in a glyph, at most {:.3} % of one's), \
         anti-aliased at most {worst_px}/255, \
         union->original {worst_shift:.1e}, kept original->union {worst_kept:.1e} units \
         (eps {:.1e}); segments {segs_before} -> {segs_after}",
        overlapping.len(),
        font.glyphs.len(),
        100.0 * worst_ratio,
        UNION_SHARE * font.tolerance,
    );
    overlapping
}

fn bundled() -> Font {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("glyphs");
    load_font(&dir).unwrap().0
}

#[test]
fn bundled_glyphs_have_no_overlaps_and_are_kept() {
    // The typeface's accents clear their bases and no contour crosses another: the union
    // changes nothing, to the bit.
    let font = bundled();
    let outlined = outline_font(&font, font.info.tolerance);
    let whole = |g: &OutlinedGlyph| vec![g.path.clone()];
    assert_eq!(
        check_font("bundled", &outlined, whole),
        Vec::<String>::new()
    );
}

#[test]
fn bundled_composites_with_lowered_accents_are_unioned() {
    // Every composite with its last component (the accent) lowered 250 units into its base.
    let mut font = bundled();
    for glyph in &mut font.glyphs {
        if glyph.components.len() >= 2 {
            if let Some(accent) = glyph.components.last_mut() {
                accent.offset.1 -= 250.0;
            }
        }
    }
    let outlined = outline_font(&font, font.info.tolerance);
    // The reference paints each component's own outline (the base glyph's, moved): the IR
    // orients the lowered accent by its nesting in the whole glyph (a hole where it lies in
    // the base's ink), so its nonzero fill is not what the glyph means.
    let components = |g: &OutlinedGlyph| {
        if g.components.is_empty() {
            return vec![g.path.clone()];
        }
        g.components
            .iter()
            .map(|c| {
                let base = outlined.glyph(&c.base).unwrap();
                assert!(base.components.is_empty());
                Affine::translate(c.offset) * base.path.clone()
            })
            .collect()
    };
    let crossed = check_font("lowered accents", &outlined, components);
    let composites: Vec<&str> = font
        .glyphs
        .iter()
        .filter(|g| g.components.len() >= 2)
        .map(|g| g.name.as_str())
        .collect();
    eprintln!("composites {}: {composites:?}", composites.len());
    eprintln!("crossed {}: {crossed:?}", crossed.len());
    // The others: a cedilla moves away from its base, and dieresis dots, or an accent
    // between two stems (U, u), pass beside the base.
    assert_eq!((composites.len(), crossed.len()), (50, 39));
}

#[test]
fn bundled_glyphs_over_a_shifted_copy_are_unioned() {
    // Every glyph drawn twice, the copy moved by (37, 23): all of the typeface's shapes,
    // crossing themselves.
    let font = bundled();
    let mut outlined = outline_font(&font, font.info.tolerance);
    for glyph in &mut outlined.glyphs {
        let copy = Affine::translate((37.0, 23.0)) * glyph.path.clone();
        glyph.path.extend(copy.iter());
        glyph.segments *= 2;
    }
    let whole = |g: &OutlinedGlyph| vec![g.path.clone()];
    let crossed = check_font("shifted copies", &outlined, whole);
    let inked = outlined
        .glyphs
        .iter()
        .filter(|g| !g.path.elements().is_empty())
        .count();
    assert_eq!(crossed.len(), inked);
}

fn square(x: f64, y: f64, side: f64) -> BezPath {
    Rect::new(x, y, x + side, y + side).to_path(0.1)
}

/// Runs one hand-made case: the union fills like the original, nothing crosses after it,
/// and the boundary stays put. Returns the union.
fn check_case(name: &str, path: &BezPath) -> BezPath {
    let union = remove_overlaps(path, 1e-4);
    let (px, differ, covered) = pixel_diff(std::slice::from_ref(path), &union, 1.0);
    let shift = one_sided(&union, path, 32);
    let kept = kept_boundary_shift(path, &union, PROBE);
    eprintln!(
        "{name}: {} crossings -> {}, pixels: max diff {px}, {differ} differ of {covered}; \
         shift {shift:.2e}, kept {kept:.2e}",
        crossings(path),
        crossings(&union)
    );
    assert_eq!(crossings(&union), 0, "{name}");
    assert!(px <= AA_LEVELS, "{name}: {px}");
    assert!(
        differ <= aliased_limit(covered),
        "{name}: {differ} pixels differ"
    );
    assert!(
        shift <= MAX_SHIFT && kept <= MAX_SHIFT,
        "{name}: {shift} {kept}"
    );
    union
}

#[test]
fn hand_made_overlaps() {
    // Two overlapping squares: one L-shaped... octagon of 8 corners.
    let mut two = square(0.0, 0.0, 100.0);
    two.extend(square(50.0, 50.0, 100.0).iter());
    assert_eq!(crossings(&two), 2);
    let u = check_case("two squares", &two);
    assert_eq!(areas(&u), [17500.0]);
    assert_eq!(u.segments().filter(|s| s.start() != s.end()).count(), 8);

    // A ring (outer counter-clockwise, hole clockwise): nothing overlaps, kept as it is.
    let mut ring = Circle::new((100.0, 100.0), 90.0).to_path(0.01);
    ring.extend(
        Circle::new((100.0, 100.0), 50.0)
            .to_path(0.01)
            .reverse_subpaths()
            .iter(),
    );
    assert_eq!(crossings(&ring), 0);
    assert_eq!(remove_overlaps(&ring, 1e-4), ring);

    // Two rings that cross: the outer circles cross each other and the other's hole (six
    // crossings); one outline and two holes remain.
    let mut rings = ring.clone();
    rings.extend((kurbo::Affine::translate((120.0, 0.0)) * ring.clone()).iter());
    assert_eq!(crossings(&rings), 6);
    let u = check_case("two rings", &rings);
    let a = areas(&u);
    assert_eq!(a.iter().filter(|&&x| x > 0.0).count(), 1, "{a:?}");
    assert_eq!(a.iter().filter(|&&x| x < 0.0).count(), 2, "{a:?}");

    // A self-overlap: a pentagram drawn in one stroke winds twice around its centre.
    let star: Vec<Point> = (0..5)
        .map(|i| {
            let a = std::f64::consts::FRAC_PI_2 + f64::from(i * 2) * std::f64::consts::TAU / 5.0;
            Point::new(100.0 + 90.0 * a.cos(), 100.0 + 90.0 * a.sin())
        })
        .collect();
    let mut pentagram = BezPath::new();
    pentagram.move_to(star[0]);
    for p in &star[1..] {
        pentagram.line_to(*p);
    }
    pentagram.close_path();
    assert_eq!(crossings(&pentagram), 5);
    let u = check_case("pentagram", &pentagram);
    // The outline of the star: ten corners, one contour, counter-clockwise (the sweep may
    // leave an extra vertex on a straight edge, where it cut it).
    assert_eq!(areas(&u).len(), 1);
    assert!(areas(&u)[0] > 0.0);
    assert_eq!(corners(&u), 10);

    // Touching edges: two squares sharing a side become one rectangle of 4 (or 6, with the
    // shared side's ends kept as vertices) edges, no inner edge left.
    let mut touching = square(0.0, 0.0, 100.0);
    touching.extend(square(100.0, 0.0, 100.0).iter());
    let u = check_case("touching squares", &touching);
    assert_eq!(areas(&u), [20000.0]);
    assert!(u
        .segments()
        .all(|s| !(s.start().x == 100.0 && s.end().x == 100.0)));

    // Cubics: two overlapping circles keep cubic pieces of the originals.
    let mut circles = Circle::new((100.0, 100.0), 80.0).to_path(0.01);
    circles.extend(Circle::new((200.0, 100.0), 80.0).to_path(0.01).iter());
    let u = check_case("two circles", &circles);
    assert!(u
        .elements()
        .iter()
        .all(|e| !matches!(e, PathEl::QuadTo(..))));
    assert!(
        u.elements()
            .iter()
            .filter(|e| matches!(e, PathEl::CurveTo(..)))
            .count()
            >= 8
    );
}

/// `build` unions the TTF and OTF outlines; `--keep-overlaps` writes them as drawn. An
/// oacute whose accent is lowered into the o crosses it: 3 contours as drawn, 2 unioned.
#[test]
fn build_unions_unless_keep_overlaps() {
    use read_fonts::{FontRef, TableProvider};
    let dir = tempfile::tempdir().unwrap();
    let src = dir.path().join("font");
    std::fs::create_dir(&src).unwrap();
    let mini = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/mini");
    for e in std::fs::read_dir(&mini).unwrap() {
        let p = e.unwrap().path();
        std::fs::copy(&p, src.join(p.file_name().unwrap())).unwrap();
    }
    let oacute = std::fs::read_to_string(src.join("oacute.toml")).unwrap();
    let lowered = oacute.replace(LOWERED_FROM, LOWERED_TO);
    assert_ne!(lowered, oacute, "the fixture's accent offset moved");
    std::fs::write(src.join("oacute.toml"), lowered).unwrap();
    let contours = |keep: bool| -> usize {
        let out = dir.path().join(if keep { "kept" } else { "unioned" });
        let mut args = vec!["build", src.to_str().unwrap(), "-o", out.to_str().unwrap()];
        if keep {
            args.push("--keep-overlaps");
        }
        let (code, _, err) = crate::common::cli::xglyph(&args);
        assert_eq!(code, 0, "{err}");
        let bytes = std::fs::read(out.join("MiniTest-Regular.ttf")).unwrap();
        let font = FontRef::new(&bytes).unwrap();
        let gid = font
            .cmap()
            .unwrap()
            .map_codepoint(0xF3u32)
            .expect("oacute is mapped");
        let loca = font.loca(None).unwrap();
        let glyf = font.glyf().unwrap();
        match loca.get_glyf(gid, &glyf).unwrap() {
            Some(read_fonts::tables::glyf::Glyph::Simple(g)) => g.end_pts_of_contours().len(),
            _ => panic!("oacute is not a simple glyph"),
        }
    };
    assert_eq!(contours(true), 3);
    assert_eq!(contours(false), 2);
}

/// The mini fixture's acute, placed 100 units lower: its foot (y 460) lands in the o's
/// ink (422 to 512), so the two cross.
const LOWERED_FROM: &str = "base = \"acutecomb\"\noffset = [0, 0]";
const LOWERED_TO: &str = "base = \"acutecomb\"\noffset = [0, -100]";
