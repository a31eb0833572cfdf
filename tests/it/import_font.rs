//! `xglyph import` of a real font: DejaVu Sans A–Z, a–z, 0–9 (a copy of Debian fonts-dejavu-core, in tests/fixtures/import).
//!
//! Asserts, against outlines read here directly with ttf-parser: every imported X-spline
//! within 0.75 T of the original (two-sided, dense sampling, T = 1/1000 em), fewer control
//! points than the original's stored points, a report consistent with the written files,
//! the round trip import -> load -> build within T of the original, marks that come in
//! with their GPOS anchors and sit where HarfBuzz puts them in the original, and a mark
//! the original places by its outline that comes in with `mark = "outline"`.

use std::path::{Path, PathBuf};
use std::sync::OnceLock;
use std::time::Instant;

use crate::common::paths;

use kurbo::{BezPath, ParamCurve, PathSeg, Point};
use xglyph::import::font::glyph_outline;
use xglyph::import::{import_font, ImportOptions, Imported, IMPORT_SHARE};
use xglyph::outline::outline_font;
use xglyph::source::emit::font_sources;
use xglyph::source::load_font;
use xglyph::xspline::XSpline;

/// A copy of Debian fonts-dejavu-core 2.37 (license next to it), so the numbers are fixed.
const DEJAVU: &str = "tests/fixtures/import/DejaVuSans.ttf";
const LIST: &str = "A-Z,a-z,0-9";
/// The default import tolerance: 1/1000 of DejaVu's 2048-unit em.
const T: f64 = 2.048;

fn font_bytes() -> Vec<u8> {
    std::fs::read(DEJAVU).unwrap_or_else(|e| {
        panic!("{DEJAVU} is needed for this test (a copy of Debian fonts-dejavu-core): {e}")
    })
}

/// The import, done once for all tests of this file; with its wall time in seconds.
fn imported() -> &'static (Imported, f64) {
    static CELL: OnceLock<(Imported, f64)> = OnceLock::new();
    CELL.get_or_init(|| {
        let opts = ImportOptions {
            glyphs: Some(xglyph::import::font::parse_glyph_list(LIST).unwrap()),
            ..ImportOptions::default()
        };
        let start = Instant::now();
        let imp = import_font(Path::new(DEJAVU), &font_bytes(), &opts).unwrap();
        (imp, start.elapsed().as_secs_f64())
    })
}

/// The original outline of the glyph named `name` (DejaVu's post-table name, which the
/// import keeps), read with ttf-parser.
fn original(face: &ttf_parser::Face, name: &str) -> BezPath {
    let gid = face
        .glyph_index_by_name(name)
        .expect("the glyph is in the font");
    glyph_outline(face, gid).unwrap_or_default()
}

/// The glyphs `liga` makes of A–Z, a–z, 0–9 in DejaVu: they come in with the letters.
const LIGATURES: [&str; 5] = ["fi", "fl", "uniFB00", "uniFB03", "uniFB04"];

fn two_sided(a: &BezPath, b: &BezPath) -> f64 {
    paths::two_sided(a, b, 32)
}

/// X-splines as a fine polyline (256 samples per segment; the chord error at that density
/// is far below a thousandth of a unit for these glyphs).
fn polyline(splines: &[XSpline]) -> BezPath {
    let mut path = BezPath::new();
    for s in splines {
        let n = s.segment_count() * 256;
        path.move_to(s.eval(0.0));
        for k in 1..n {
            path.line_to(s.eval(k as f64 / 256.0));
        }
        path.close_path();
    }
    path
}

#[test]
fn dejavu_within_tolerance_with_fewer_points() {
    let (imp, seconds) = imported();
    let report = &imp.report;
    let data = font_bytes();
    let face = ttf_parser::Face::parse(&data, 0).unwrap();
    assert_eq!(report.rows.len(), 62 + LIGATURES.len());
    assert_eq!(imp.font.glyphs.len(), 62 + LIGATURES.len());
    let unmapped: Vec<&str> = imp
        .font
        .glyphs
        .iter()
        .filter(|g| g.unicodes.is_empty())
        .map(|g| g.name.as_str())
        .collect();
    assert_eq!(unmapped, LIGATURES);
    assert_eq!(report.tolerance, T);
    let mut worst = (0.0, String::new());
    for glyph in &imp.font.glyphs {
        let splines: Vec<XSpline> = glyph
            .contours
            .iter()
            .map(|k| XSpline::new(k.points().to_vec()).unwrap())
            .collect();
        let orig = original(&face, &glyph.name);
        let err = two_sided(&polyline(&splines), &orig);
        let row = report.rows.iter().find(|r| r.name == glyph.name).unwrap();
        assert!(
            err <= IMPORT_SHARE * T + 0.01,
            "glyph {}: measured {err}, bound {}",
            glyph.name,
            IMPORT_SHARE * T
        );
        // The report's own measurement agrees with this independent one.
        assert!(
            (err - row.max_error).abs() < 0.05,
            "glyph {}: report says {}, measured {err}",
            glyph.name,
            row.max_error
        );
        if err > worst.0 {
            worst = (err, glyph.name.clone());
        }
    }
    let (before, after) = (report.original_points(), report.xspline_points());
    eprintln!(
        "{}\nworst glyph {} at {:.3} units; import took {seconds:.1} s",
        report.summary(),
        worst.1,
        worst.0
    );
    // On+off points as stored (TrueType implied midpoints not counted; explicit points that
    // sit exactly on a midpoint are not counted either, so this undercounts a little).
    // 1229 for the 62 characters, 170 for the five ligatures.
    assert_eq!(before, 1229 + 170);
    assert!(
        after <= before,
        "{after} X-spline points > {before} original"
    );
}

#[test]
fn dejavu_shapes_are_clean() {
    let (imp, _) = imported();
    let glyph = |name: &str| imp.font.glyph(name).unwrap();
    // Straight-edged glyphs: exactly the original corners, all sharp, no error.
    for (name, count) in [("A", 11), ("l", 4), ("H", 12), ("seven", 7)] {
        let g = glyph(name);
        let pts: Vec<_> = g.contours.iter().flat_map(|c| c.points()).collect();
        assert_eq!(pts.len(), count, "{name}");
        assert!(pts.iter().all(|p| p.s == 0.0), "{name}");
        let row = imp.report.rows.iter().find(|r| r.name == name).unwrap();
        assert_eq!(row.original_points, count, "{name}");
        assert!(row.max_error < 1e-9, "{name}: {}", row.max_error);
    }
    // 'o': two smooth loops, no sharp point.
    let o = glyph("o");
    assert_eq!(o.contours.len(), 2);
    assert!(o
        .contours
        .iter()
        .flat_map(|c| c.points())
        .all(|p| p.s > 0.0));
    // Metrics and names from the font.
    let info = &imp.font.info;
    assert_eq!(info.family, "DejaVu Sans");
    assert_eq!(info.style, "Book");
    assert_eq!(info.units_per_em, 2048);
    assert_eq!((info.ascender, info.descender), (1901.0, -483.0));
    assert_eq!((info.x_height, info.cap_height), (1120.0, 1493.0));
    assert_eq!(info.tolerance, 0.512);
    assert_eq!(glyph("A").advance, 1401.0);
    assert_eq!(glyph("A").unicodes, vec!['A']);
}

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("xglyph-import-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

fn write(imp: &Imported, dir: &Path) {
    std::fs::create_dir_all(dir).unwrap();
    for (name, text) in font_sources(&imp.font) {
        std::fs::write(dir.join(name), text).unwrap();
    }
}

#[test]
fn report_matches_written_files() {
    let (imp, _) = imported();
    let dir = temp_dir("report");
    write(imp, &dir);
    let (font, warnings) = load_font(&dir).unwrap();
    assert!(warnings.is_empty(), "{warnings:?}");
    let text = imp.report.render();
    let mut lines = text.lines();
    // The column is as wide as the longest name (the ligature `uniFB00`).
    assert_eq!(
        lines.next().unwrap(),
        "glyph    original   xspline  max error"
    );
    let mut rows = 0;
    let mut sum = (0, 0);
    for line in lines.by_ref().take(67) {
        let cols: Vec<&str> = line.split_whitespace().collect();
        let g = font.glyph(cols[0]).unwrap();
        let points: usize = g.contours.iter().map(|c| c.points().len()).sum();
        assert_eq!(cols[2].parse::<usize>().unwrap(), points, "{line}");
        let err: f64 = cols[3].parse().unwrap();
        assert!(err <= IMPORT_SHARE * T, "{line}");
        sum.0 += cols[1].parse::<usize>().unwrap();
        sum.1 += points;
        rows += 1;
    }
    assert_eq!(rows, 67);
    let summary = lines.next().unwrap();
    assert!(
        summary.starts_with(&format!(
            "total: 67 glyphs, {} original points, {} X-spline points, max error ",
            sum.0, sum.1
        )),
        "{summary}"
    );
    assert!(summary.ends_with("(tolerance 2.048, build tolerance 0.512)"));
    assert_eq!(lines.next(), None);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn round_trip_import_build_within_tolerance() {
    let (imp, _) = imported();
    let dir = temp_dir("roundtrip");
    write(imp, &dir);
    let (font, _) = load_font(&dir).unwrap();
    assert_eq!(
        font, imp.font,
        "the written sources load back to the same model"
    );
    let built = outline_font(&font, font.info.tolerance);
    let data = font_bytes();
    let face = ttf_parser::Face::parse(&data, 0).unwrap();
    let mut worst: f64 = 0.0;
    for g in &built.glyphs {
        let err = two_sided(&g.path, &original(&face, &g.name));
        assert!(
            err <= T,
            "glyph {}: built outline {err} from the original",
            g.name
        );
        worst = worst.max(err);
    }
    eprintln!("round trip: worst {worst:.3} font units (T = {T})");
    let _ = std::fs::remove_dir_all(&dir);
}

/// At joins that are smooth in the original (a straight segment meeting a curve along its
/// tangent, which becomes an `s = 0` point), the imported X-spline turns by at most 2°.
#[test]
fn smooth_joins_stay_smooth() {
    let (imp, _) = imported();
    let data = font_bytes();
    let face = ttf_parser::Face::parse(&data, 0).unwrap();
    let angle = |a: kurbo::Vec2, b: kurbo::Vec2| {
        (a.dot(b) / (a.hypot() * b.hypot()))
            .clamp(-1.0, 1.0)
            .acos()
            .to_degrees()
    };
    let tangents = |s: PathSeg| -> (kurbo::Vec2, kurbo::Vec2) {
        let pts: Vec<Point> = match s {
            PathSeg::Line(l) => vec![l.p0, l.p1],
            PathSeg::Quad(q) => vec![q.p0, q.p1, q.p2],
            PathSeg::Cubic(c) => vec![c.p0, c.p1, c.p2, c.p3],
        };
        let n = pts.len();
        (pts[1] - pts[0], pts[n - 1] - pts[n - 2])
    };
    let (mut joins, mut worst) = (0, (0.0, String::new()));
    for glyph in &imp.font.glyphs {
        let segs: Vec<PathSeg> = paths::with_boxes(&original(&face, &glyph.name))
            .into_iter()
            .map(|(s, _)| s)
            .collect();
        for contour in &glyph.contours {
            let spline = XSpline::new(contour.points().to_vec()).unwrap();
            let n = spline.segment_count();
            for k in 0..n {
                if contour.points()[k].s != 0.0 {
                    continue;
                }
                let p = contour.points()[k].pos;
                // The original join at this point: a segment ending here, one starting here.
                let ins = segs.iter().find(|s| (s.end() - p).hypot() < 1e-6);
                let outs = segs.iter().find(|s| (s.start() - p).hypot() < 1e-6);
                let (Some(&a), Some(&b)) = (ins, outs) else {
                    continue;
                };
                if angle(tangents(a).1, tangents(b).0) > 0.5 {
                    continue;
                }
                let turn = angle(
                    spline.segment(k + n - 1).end_direction(),
                    spline.segment(k).start_direction(),
                );
                joins += 1;
                if turn > worst.0 {
                    worst = (turn, glyph.name.clone());
                }
            }
        }
    }
    eprintln!(
        "{joins} smooth joins, worst turn {:.2}° in {}",
        worst.0, worst.1
    );
    assert!(joins > 50, "{joins}");
    assert!(worst.0 <= 2.0, "{worst:?}");
}

/// The imported kerning by character pair, for glyphs with one code point each (the
/// ligatures that come in unmapped are kerned in no pair HarfBuzz sees with `liga` off).
fn kerning_by_chars(imp: &Imported) -> std::collections::BTreeMap<String, f64> {
    let chars: std::collections::HashMap<&str, char> = imp
        .font
        .glyphs
        .iter()
        .filter_map(|g| Some((g.name.as_str(), *g.unicodes.first()?)))
        .collect();
    imp.font
        .kerning
        .iter()
        .filter_map(|p| {
            let (left, right) = (chars.get(p.left.as_str())?, chars.get(p.right.as_str())?);
            Some((format!("{left}{right}"), p.value))
        })
        .collect()
}

#[test]
fn kerning_equals_harfbuzz_on_every_pair() {
    // DejaVu kerns with class pairs (GPOS format 2) in two lookups: Latin text takes both,
    // other scripts only the second, and a Latin letter beside a Cyrillic one is not kerned
    // at all (two script runs). The Cyrillic import checks all three.
    if !crate::common::tools::available(
        crate::common::tools::python_imports("uharfbuzz"),
        "uharfbuzz",
        "pip install uharfbuzz",
    ) {
        return;
    }
    let cyrillic = "AVToyАГТУоя.";
    let opts = ImportOptions {
        glyphs: Some(xglyph::import::font::parse_glyph_list("А,Г,Т,У,о,я,A,V,T,o,y,.").unwrap()),
        ..ImportOptions::default()
    };
    let mixed = import_font(Path::new(DEJAVU), &font_bytes(), &opts).unwrap();
    let latin: String = ('A'..='Z').chain('a'..='z').chain('0'..='9').collect();
    for (imp, chars) in [(&imported().0, latin.as_str()), (&mixed, cyrillic)] {
        let expected: std::collections::BTreeMap<String, f64> =
            crate::common::tools::python_json(HB_PAIRS, &[&DEJAVU, &chars]);
        let got = kerning_by_chars(imp);
        assert!(
            expected.len() >= 15,
            "{chars}: HarfBuzz kerns only {expected:?}"
        );
        assert_eq!(got, expected, "{chars}");
    }
}

/// DejaVu with the lookup list offset of its `tag` table (GSUB or GPOS) pointed past the
/// end of the table, imported with `--glyphs glyphs`: the import stops before fitting,
/// names the file and the table, and writes nothing.
fn assert_a_damaged_lookup_list_is_named(tag: &str, glyphs: &str) {
    let mut data = font_bytes();
    let (offset, length) = table(&data, tag.as_bytes().try_into().unwrap());
    let lookup_list = offset + 8;
    data[lookup_list..lookup_list + 2].copy_from_slice(&(length as u16 + 16).to_be_bytes());
    let case = format!("damaged-{}", tag.to_lowercase());
    let (font, out) = written(&case, "damaged.ttf", &data);
    let dir = font.parent().unwrap().to_path_buf();
    let err = crate::common::cli::import_fails(&[font.to_str().unwrap(), "--glyphs", glyphs], &out);
    assert_eq!(
        err,
        format!(
            "error: {}: damaged {tag} table: An offset was out of bounds\n",
            font.display()
        )
    );
    assert!(!out.exists());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_damaged_gpos_is_an_error_naming_the_file() {
    assert_a_damaged_lookup_list_is_named("GPOS", "A-C");
}

#[test]
fn a_damaged_gsub_is_an_error_naming_the_file() {
    assert_a_damaged_lookup_list_is_named("GSUB", "f,i");
}

/// DejaVu with its GPOS hidden (the table record renamed `GPOX`, which keeps the
/// directory sorted): a font with only its legacy `kern` table, as many older fonts are.
fn dejavu_without_gpos() -> Vec<u8> {
    let mut data = font_bytes();
    let tables = usize::from(u16::from_be_bytes([data[4], data[5]]));
    let record = (0..tables)
        .map(|i| 12 + 16 * i)
        .find(|&r| &data[r..r + 4] == b"GPOS")
        .expect("DejaVu has a GPOS");
    data[record + 3] = b'X';
    data
}

#[test]
fn a_font_without_gpos_kerning_is_kerned_by_its_kern_table_as_harfbuzz_does() {
    if !crate::common::tools::available(
        crate::common::tools::python_imports("uharfbuzz"),
        "uharfbuzz",
        "pip install uharfbuzz",
    ) {
        return;
    }
    let data = dejavu_without_gpos();
    let (font, _) = written("legacy-kern", "legacy-kern.ttf", &data);
    let opts = ImportOptions {
        glyphs: Some(xglyph::import::font::parse_glyph_list(LIST).unwrap()),
        ..ImportOptions::default()
    };
    let imp = import_font(&font, &data, &opts).unwrap();
    let latin: String = ('A'..='Z').chain('a'..='z').chain('0'..='9').collect();
    // HarfBuzz applies the `kern` table when GPOS has no `kern` feature.
    let expected: std::collections::BTreeMap<String, f64> =
        crate::common::tools::python_json(HB_PAIRS, &[&font.to_str().unwrap(), &latin]);
    let got = kerning_by_chars(&imp);
    assert!(expected.len() > 150, "HarfBuzz kerns only {expected:?}");
    // Before, such a font came in with no kerning at all.
    assert_eq!(got, expected);
    let _ = std::fs::remove_dir_all(font.parent().unwrap());
}

/// HarfBuzz's kerning of each pair of `chars`: the width of the shaped pair minus the two
/// advances alone, for the pairs where they differ (ligatures off). (With a legacy `kern`
/// table HarfBuzz puts half the value on each glyph: only the width is the pair's value.)
const HB_PAIRS: &str = r#"
import json, sys, uharfbuzz as hb
font = hb.Font(hb.Face(hb.Blob.from_file_path(sys.argv[1])))
chars = sys.argv[2]
off = {"liga": False, "clig": False, "dlig": False, "calt": False, "rlig": False}
def width(text):
    buf = hb.Buffer()
    buf.add_str(text)
    buf.guess_segment_properties()
    hb.shape(font, buf, off)
    assert len(buf.glyph_positions) == len(text), text
    return sum(p.x_advance for p in buf.glyph_positions)
alone = {c: width(c) for c in chars}
out = {}
for a in chars:
    for b in chars:
        kern = width(a + b) - alone[a] - alone[b]
        if kern != 0:
            out[a + b] = kern
print(json.dumps(out))
"#;

#[test]
fn a_damaged_kern_table_is_an_error_naming_it() {
    // The GPOS hidden, and the `kern` subtable's pair count far past the table's end.
    let mut data = dejavu_without_gpos();
    let (offset, _) = table(&data, b"kern");
    // Table header (version, nTables: 4 bytes), subtable header (version, length,
    // coverage: 6 bytes), then nPairs.
    let pairs = offset + 4 + 6;
    data[pairs..pairs + 2].copy_from_slice(&u16::MAX.to_be_bytes());
    let (font, out) = written("damaged-kern", "damaged.ttf", &data);
    let dir = font.parent().unwrap().to_path_buf();
    let err = crate::common::cli::import_fails(&[font.to_str().unwrap(), "--glyphs", "A-C"], &out);
    assert_eq!(
        err,
        format!(
            "error: {}: damaged kern table: An offset was out of bounds\n",
            font.display()
        )
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// The offset and length of table `tag` in the font bytes `data`.
fn table(data: &[u8], tag: &[u8; 4]) -> (usize, usize) {
    let tables = usize::from(u16::from_be_bytes([data[4], data[5]]));
    let record = (0..tables)
        .map(|i| 12 + 16 * i)
        .find(|&r| &data[r..r + 4] == tag)
        .expect("DejaVu has the table");
    let at = |k: usize| u32::from_be_bytes(data[k..k + 4].try_into().unwrap()) as usize;
    (at(record + 8), at(record + 12))
}

/// DejaVu with the `glyf` data of the glyph for `c` changed by `edit`, which gets the
/// bytes, the `loca` entries' offsets in them (`entry(gid)`), and the glyph's id.
fn dejavu_with_glyph_edited(
    c: char,
    edit: impl FnOnce(&mut Vec<u8>, &dyn Fn(u16) -> usize, u16),
) -> Vec<u8> {
    let mut data = font_bytes();
    let gid = ttf_parser::Face::parse(&data, 0)
        .unwrap()
        .glyph_index(c)
        .unwrap()
        .0;
    let (head, _) = table(&data, b"head");
    let (loca, _) = table(&data, b"loca");
    assert_eq!(
        &data[head + 50..head + 52],
        &[0, 1],
        "DejaVu's loca is long"
    );
    let entry = move |g: u16| loca + 4 * usize::from(g);
    edit(&mut data, &entry, gid);
    data
}

/// Where in the font bytes `data` the glyph whose long `loca` entry is at `entry` starts.
fn glyph_start(data: &[u8], entry: usize) -> usize {
    let (glyf, _) = table(data, b"glyf");
    glyf + u32::from_be_bytes(data[entry..entry + 4].try_into().unwrap()) as usize
}

/// The font bytes `data` written as `name` in a fresh folder for the test `case`: the
/// font's path and an output folder next to it.
fn written(case: &str, name: &str, data: &[u8]) -> (PathBuf, PathBuf) {
    let dir = temp_dir(case);
    std::fs::create_dir_all(&dir).unwrap();
    let font = dir.join(name);
    std::fs::write(&font, data).unwrap();
    (font, dir.join("out"))
}

#[test]
fn a_letter_the_font_leaves_empty_comes_in_empty_with_a_note() {
    // `b`'s loca entry moved to its end: no glyf data, as a font's blank glyph has.
    let data = dejavu_with_glyph_edited('b', |d, entry, gid| {
        let end: [u8; 4] = d[entry(gid + 1)..entry(gid + 1) + 4].try_into().unwrap();
        d[entry(gid)..entry(gid) + 4].copy_from_slice(&end);
    });
    assert_b_comes_in_empty("empty-letter", &data);
}

#[test]
fn a_letter_drawn_as_one_point_comes_in_empty_with_a_note() {
    // `b` as Material Icons stores its letters: one contour of one point at the origin
    // (1 contour, a zero box, end point 0, no instructions, one flag: on-curve, x and y
    // unchanged). It outlines nothing; before, the import stopped at it as damaged.
    let data = dejavu_with_glyph_edited('b', |d, entry, gid| {
        let start = glyph_start(d, entry(gid));
        let one_point = [0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0x31];
        d[start..start + one_point.len()].copy_from_slice(&one_point);
    });
    assert_b_comes_in_empty("point-letter", &data);
}

/// The import of `a`-`c` from the font bytes `data` (DejaVu with `b` edited): `b` comes in
/// empty with its note, `a` and `c` with their contours.
fn assert_b_comes_in_empty(case: &str, data: &[u8]) {
    let (font, out) = written(case, "edited-b.ttf", data);
    let dir = font.parent().unwrap().to_path_buf();
    let stdout = crate::common::cli::import_ok(&[font.to_str().unwrap(), "--glyphs", "a-c"], &out);
    assert!(
        stdout.contains("\nnote: glyph `b` (U+0062) is empty in the font\n"),
        "{stdout}"
    );
    let (font, _) = load_font(&out).unwrap();
    let contours = |name: &str| font.glyph(name).unwrap().contours.len();
    assert_eq!((contours("a"), contours("b"), contours("c")), (2, 0, 1));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_glyph_neither_reader_can_read_is_an_error_naming_it() {
    // `b` claims 30,000 contours in a glyph of a few dozen bytes.
    let data = dejavu_with_glyph_edited('b', |d, entry, gid| {
        let start = glyph_start(d, entry(gid));
        d[start..start + 2].copy_from_slice(&30_000u16.to_be_bytes());
    });
    let (font, out) = written("damaged-glyph", "damaged-b.ttf", &data);
    let dir = font.parent().unwrap().to_path_buf();
    let err = crate::common::cli::import_fails(&[font.to_str().unwrap(), "--glyphs", "a-c"], &out);
    assert_eq!(
        err,
        format!(
            "error: {}: glyph `b` (U+0062) has no readable outline; the font may be damaged\n",
            font.display()
        )
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_names_come_from_the_english_records_when_others_come_first_and_trimmed() {
    // DejaVu's name table with a Traditional Chinese (0x404) family and copyright added:
    // sorted by language, they come before the English ones, as in WenQuanYi Zen Hei.
    // Its copyright records get a leading space and a trailing "\r\n".
    use skrifa::raw::{FontRef, TableProvider};
    use write_fonts::tables::name::{Name, NameRecord};
    use write_fonts::types::NameId;
    let data = font_bytes();
    let font = FontRef::new(&data).unwrap();
    let name = font.name().unwrap();
    let mut records: Vec<NameRecord> = name
        .name_record()
        .iter()
        .map(|r| {
            let mut text: String = r.string(name.string_data()).unwrap().chars().collect();
            if r.name_id() == NameId::COPYRIGHT_NOTICE {
                // Line ends as old tools left them (Gentium's copyright and license).
                text = format!(" {text}\r\n");
            }
            NameRecord::new(
                r.platform_id(),
                r.encoding_id(),
                r.language_id(),
                r.name_id(),
                text.into(),
            )
        })
        .collect();
    for (id, text) in [(0, "版權"), (1, "德加武無襯線")] {
        records.push(NameRecord::new(
            3,
            1,
            0x404,
            NameId::new(id),
            text.to_string().into(),
        ));
    }
    records.sort_by_key(|r| (r.platform_id, r.encoding_id, r.language_id, r.name_id));
    let mut builder = write_fonts::FontBuilder::new();
    for r in font.table_directory.table_records() {
        builder.add_raw(
            r.tag(),
            font.table_data(r.tag()).unwrap().as_bytes().to_vec(),
        );
    }
    builder.add_table(&Name::new(records)).unwrap();
    let dir = temp_dir("names");
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("names.ttf");
    std::fs::write(&path, builder.build()).unwrap();
    let out = dir.join("out");
    crate::common::cli::import_ok(&[path.to_str().unwrap(), "--glyphs", "A"], &out);
    let (font, _) = load_font(&out).unwrap();
    assert_eq!(font.info.family, "DejaVu Sans");
    let copyright = font.info.copyright.unwrap_or_default();
    assert!(
        copyright.starts_with("Copyright (c) 2003 by Bitstream, Inc."),
        "{copyright}"
    );
    // Trimmed: FontBakery fails trailing white space in a name record.
    assert_eq!(copyright, copyright.trim(), "{copyright:?}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// HarfBuzz's positions (x advance, x offset, y offset) of each text of `argv[3]`
/// (comma-separated) in the fonts `argv[1]` and `argv[2]`.
const HB_MARKS: &str = r#"
import json, sys, uharfbuzz as hb
def shape(path, text):
    font = hb.Font(hb.Face(hb.Blob.from_file_path(path)))
    buf = hb.Buffer()
    buf.add_str(text)
    buf.guess_segment_properties()
    hb.shape(font, buf, {})
    return [[p.x_advance, p.x_offset, p.y_offset] for p in buf.glyph_positions]
print(json.dumps({t: [shape(sys.argv[1], t), shape(sys.argv[2], t)] for t in sys.argv[3].split(",")}))
"#;

/// Marks on bases, above and below, that Unicode does not compose (so HarfBuzz positions
/// the mark on the base rather than taking a precomposed glyph).
const MARK_TEXTS: [&str; 10] = [
    "n\u{308}", "n\u{304}", "n\u{306}", "n\u{30A}", "n\u{302}", "a\u{327}", "o\u{327}", "A\u{327}",
    "O\u{327}", "u\u{327}",
];

#[test]
fn marks_come_in_with_their_gpos_anchors_and_sit_where_harfbuzz_puts_them() {
    // DejaVu attaches marks in GPOS mark-to-base and mark-to-mark lookups. Without their
    // anchors the imported combining marks would fail `check`; with them the built font
    // must position each mark exactly as the original does.
    let stacked = "n\u{308}\u{304}";
    let mut chars = std::collections::BTreeSet::new();
    for text in MARK_TEXTS.iter().chain([&stacked]) {
        chars.extend(text.chars());
    }
    let list: Vec<String> = chars
        .iter()
        .map(|c| format!("U+{:04X}", u32::from(*c)))
        .collect();
    let opts = ImportOptions {
        glyphs: Some(xglyph::import::font::parse_glyph_list(&list.join(",")).unwrap()),
        ..ImportOptions::default()
    };
    let imp = import_font(Path::new(DEJAVU), &font_bytes(), &opts).unwrap();
    let glyph = |c: char| imp.font.glyphs.iter().find(|g| g.unicodes == [c]).unwrap();
    let anchor = |c: char, name: &str| {
        let a = glyph(c).anchors.iter().find(|a| a.name == name);
        a.unwrap_or_else(|| panic!("U+{:04X} has no `{name}`", u32::from(c)))
            .position
    };
    // The main classes take the plain names; DejaVu's diaeresis attaches at (-512, 1147).
    assert_eq!(anchor('\u{308}', "_top"), (-512.0, 1147.0));
    assert_eq!(anchor('a', "top"), (586.0, 1147.0));
    assert!(anchor('\u{327}', "_bottom").1 <= 0.0);
    let dir = temp_dir("marks");
    write(&imp, &dir);
    let (font, warnings) = load_font(&dir).expect("the imported marks pass check");
    assert!(warnings.is_empty(), "{warnings:?}");
    // Every one of the six combining marks imported is a mark (it has a `_` anchor).
    let marks = font
        .glyphs
        .iter()
        .filter(|g| g.anchors.iter().any(|a| a.name.starts_with('_')))
        .map(|g| g.name.as_str());
    // Besides the six, the capital forms DejaVu's `ccmp` puts above capitals come in.
    assert_eq!(
        marks.collect::<Vec<_>>(),
        [
            "Breve",
            "Circumflex",
            "Dieresis",
            "Ringabove",
            "uni0302",
            "uni0304",
            "uni0306",
            "uni0308",
            "uni030A",
            "uni0327"
        ]
    );
    let out = dir.join("out");
    let (code, _, stderr) =
        crate::common::cli::xglyph(&["build", dir.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    assert_eq!(code, 0, "{stderr}");
    if !crate::common::tools::available(
        crate::common::tools::python_imports("uharfbuzz"),
        "uharfbuzz",
        "pip install uharfbuzz",
    ) {
        return;
    }
    let built = out.join("DejaVuSans-Book.ttf");
    let texts = MARK_TEXTS.join(",") + "," + stacked;
    let shaped: std::collections::BTreeMap<String, [Vec<[i64; 3]>; 2]> =
        crate::common::tools::python_json(HB_MARKS, &[&DEJAVU, &built, &texts]);
    for text in MARK_TEXTS {
        let [original, ours] = &shaped[text];
        assert_eq!(ours, original, "{text:?}");
        // Attached: the zero-width mark is moved off the pen position.
        assert!(ours[1][1] != 0 || ours[1][2] != 0, "{text:?}: {ours:?}");
    }
    // A mark on a mark stacks by their mark-to-mark anchors. DejaVu lists its `mkmk` lookup
    // before its `mark` lookups, so HarfBuzz re-attaches the macron to the base there and the
    // two marks overlap; xglyph's `mark` comes first and the macron stays stacked.
    let (diaeresis, macron) = (glyph('\u{308}'), glyph('\u{304}'));
    let on = macron.anchors.iter().find_map(|a| {
        let name = a.name.strip_prefix('_')?;
        let below = diaeresis.anchors.iter().find(|b| b.name == name)?;
        (name != "top").then_some(below.position.1 - a.position.1)
    });
    let [original, ours] = &shaped[stacked];
    assert_eq!(ours[1], original[1], "the diaeresis on the n");
    assert_eq!(Some((ours[2][2] - ours[1][2]) as f64), on, "{ours:?}");
    assert_eq!(on, Some(274.0));
    let _ = std::fs::remove_dir_all(&dir);
}

/// GDEF glyph class of each glyph named in `argv[2]` (comma-separated) in the font
/// `argv[1]` (0 for a glyph the class table leaves out), read with fontTools.
const GDEF_CLASSES: &str = r#"
import json, sys
from fontTools.ttLib import TTFont
classes = TTFont(sys.argv[1])["GDEF"].table.GlyphClassDef.classDefs
print(json.dumps({n: classes.get(n, 0) for n in sys.argv[2].split(",")}))
"#;

#[test]
fn a_mark_placed_by_its_outline_comes_in_with_mark_outline_and_shapes_as_in_dejavu() {
    // DejaVu positions its overlay tilde (U+0334) by its outline: no GPOS anchor comes in,
    // so it comes in with `mark = "outline"`, passes `check` and builds.
    let opts = ImportOptions {
        glyphs: Some(xglyph::import::font::parse_glyph_list("n,U+0308,U+0334").unwrap()),
        ..ImportOptions::default()
    };
    let imp = import_font(Path::new(DEJAVU), &font_bytes(), &opts).unwrap();
    let notes: Vec<&String> = imp
        .report
        .notes
        .iter()
        .filter(|n| n.contains("mark"))
        .collect();
    assert_eq!(
        notes,
        [
            "1 mark(s) with no `_` anchor in the font's GPOS came in with mark = \"outline\" \
             (their outlines place them): `uni0334`"
        ]
    );
    let by_name = |name: &str| imp.font.glyphs.iter().find(|g| g.name == name).unwrap();
    let tilde = by_name("uni0334");
    assert!(tilde.outline_mark && tilde.anchors.is_empty());
    assert_eq!(tilde.advance, 0.0);
    // The diaeresis attaches by its GPOS anchor; `n` is a base.
    assert!(!by_name("uni0308").outline_mark && by_name("uni0308").is_mark());
    assert!(!by_name("n").outline_mark && !by_name("n").is_mark());

    let dir = temp_dir("outline-mark");
    write(&imp, &dir);
    let text = std::fs::read_to_string(dir.join("uni0334.toml")).unwrap();
    assert!(
        text.starts_with(
            "name = \"uni0334\"\nunicode = 0x0334\nadvance = 0\nmark = \"outline\"\n\n[[contour]]"
        ),
        "{text}"
    );
    let (code, stdout, stderr) = crate::common::cli::xglyph(&["check", dir.to_str().unwrap()]);
    assert_eq!(code, 0, "{stdout}{stderr}");
    assert!(stdout.ends_with("0 errors, 0 warnings\n"), "{stdout}");
    let out = dir.join("out");
    let (code, _, stderr) =
        crate::common::cli::xglyph(&["build", dir.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    assert_eq!(code, 0, "{stderr}");
    // The UFO export comes back with the key (its `public.openTypeCategories`).
    let ufo =
        xglyph::import::import_ufo(&out.join("DejaVuSans-Book.ufo"), &ImportOptions::default())
            .unwrap();
    let back = ufo
        .font
        .glyphs
        .iter()
        .find(|g| g.name == "uni0334")
        .unwrap();
    assert!(back.outline_mark);
    assert_eq!(ufo.font.glyphs.iter().filter(|g| g.outline_mark).count(), 1);
    if !crate::common::tools::available(
        crate::common::tools::python_imports("uharfbuzz, fontTools"),
        "uharfbuzz/fontTools",
        "pip install uharfbuzz fonttools",
    ) {
        return;
    }
    let built = out.join("DejaVuSans-Book.ttf");
    let texts = "n\u{334},n\u{308},n\u{308}\u{334}";
    let shaped: std::collections::BTreeMap<String, [Vec<[i64; 3]>; 2]> =
        crate::common::tools::python_json(HB_MARKS, &[&DEJAVU, &built, &texts]);
    let [original, ours] = &shaped["n\u{334}"];
    assert_eq!(ours, original);
    // Zero advance, not moved: the outline places it.
    assert_eq!(ours[1], [0, 0, 0]);
    // With a diaeresis too (reordered after the overlay, canonical class 230 after 1), the
    // diaeresis attaches to the `n` across the overlay, a GDEF mark here, exactly as
    // without it. DejaVu classes U+0334 a base, so there the diaeresis finds no anchor on
    // it and stays put: the one place the import shapes differently, by design.
    let [_, alone] = &shaped["n\u{308}"];
    let [original, ours] = &shaped["n\u{308}\u{334}"];
    assert_eq!(ours[..2], original[..2]);
    assert_eq!(ours[2], alone[1]);
    assert_eq!(ours[2], [0, -137, 0]);
    assert_eq!(original[2], [0, 0, 0]);
    let classes: std::collections::BTreeMap<String, u16> =
        crate::common::tools::python_json(GDEF_CLASSES, &[&built, &"n,uni0308,uni0334"]);
    let want: std::collections::BTreeMap<String, u16> = [("n", 1), ("uni0308", 3), ("uni0334", 3)]
        .map(|(n, c)| (n.to_string(), c))
        .into();
    assert_eq!(classes, want);
    let _ = std::fs::remove_dir_all(&dir);
}

/// A whole-font import reads the characters DejaVu's cmap maps, and no others: its format-4
/// segments also span code points they map to glyph 0 (U+0000, U+02F4, U+02F5 among them;
/// ttf-parser lists every code point of a segment), which are not mapped and get no note.
/// A character asked for with `--glyphs` that the font lacks keeps its note. The count is
/// fontTools' (`len(getBestCmap())`: 5,918, each to its own glyph).
#[test]
fn a_whole_font_import_reads_the_mapped_characters_only() {
    use xglyph::import::font::read_font;
    let data = font_bytes();
    let path = Path::new(DEJAVU);
    let whole = read_font(path, &data, 0, None, |_| Vec::new()).expect("DejaVu reads");
    let chars: Vec<char> = whole
        .glyphs
        .iter()
        .flat_map(|g| g.unicodes.clone())
        .collect();
    assert_eq!((chars.len(), whole.glyphs.len()), (5918, 5918));
    for c in ['\u{0}', '\u{02F4}', '\u{02F5}'] {
        assert!(
            !chars.contains(&c),
            "U+{:04X} is mapped to glyph 0",
            u32::from(c)
        );
    }
    assert_eq!(whole.notes(), Vec::<String>::new());
    // Asked for: one note each.
    let asked = ['A', '\u{02F4}', '\u{E000}'];
    let some = read_font(path, &data, 0, Some(&asked), |_| Vec::new()).expect("DejaVu reads");
    assert_eq!(some.glyphs.len(), 1);
    assert_eq!(
        some.notes(),
        [
            "no glyph for '\u{02F4}' (U+02F4) in the font",
            "no glyph for '\u{E000}' (U+E000) in the font"
        ]
    );
}

/// GPOS features other than `kern`, `mark` and `mkmk` are named in one note, since the
/// sources cannot hold them: a font built from the `mini` fixture with a `cpsp` and a
/// `dist` feature (fea-rs compiles them into its GPOS, next to the kerning's `kern` and
/// the anchors' `mark`) imports with that note and no other. (DejaVu, whose GPOS has only
/// the three, gets none: `report_matches_written_files`.)
#[test]
fn gpos_features_not_imported_are_named() {
    let dir = temp_dir("gpos-unread");
    let src = dir.join("src");
    std::fs::create_dir_all(&src).unwrap();
    let mini = Path::new("tests/fixtures/mini");
    for entry in std::fs::read_dir(mini).unwrap() {
        let path = entry.unwrap().path();
        std::fs::copy(&path, src.join(path.file_name().unwrap())).unwrap();
    }
    std::fs::write(
        src.join("features.fea"),
        "languagesystem DFLT dflt;\nlanguagesystem latn dflt;\n\
         feature cpsp {\n    pos A <5 0 10 0>;\n} cpsp;\n\
         feature dist {\n    pos A 3;\n} dist;\n",
    )
    .unwrap();
    let out = dir.join("out");
    let (code, _, stderr) =
        crate::common::cli::xglyph(&["build", src.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    assert_eq!(code, 0, "{stderr}");
    let ttf = out.join("MiniTest-Regular.ttf");
    let data = std::fs::read(&ttf).unwrap();
    let imp = import_font(&ttf, &data, &ImportOptions::default()).expect("the built font imports");
    assert_eq!(
        imp.report.notes,
        [
            "GPOS feature(s) not imported: `cpsp`, `dist` (xglyph reads `kern`, `mark` and \
          `mkmk`); the built font does not position glyphs by them"
        ]
    );
    let _ = std::fs::remove_dir_all(&dir);
}
