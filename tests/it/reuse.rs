//! Outputs reused from the last build (`src/reuse.rs`): a sheet page is drawn again only
//! when one of its glyphs changed, the bytes are those of a build without the record, and a
//! damaged record or an output file changed in OUT is never trusted.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use kurbo::{Affine, Vec2};
use xglyph::layout::Layout;
use xglyph::otf;
use xglyph::outline::{outline_font, OutlinedFont};
use xglyph::render::{sheet_png_files_reusing, SheetOptions};
use xglyph::reuse::{font_key, outline_key, KeyBuilder, OutlineKeys, Reuse, REUSE_FILE};

use crate::common::fonts::square_ideographs;

fn repo(path: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(path)
}

fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("reuse-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// 130 square glyphs from U+4E00 on (no Latin, so every label is in the built-in face):
/// three sheet pages of 64, 64 and 2 cells at one column of 32 px.
fn cjk_like() -> OutlinedFont {
    let mut font = square_ideographs(130);
    font.features = None;
    outline_font(&font, 0.5)
}

const OPTS: SheetOptions = SheetOptions {
    cell_px: 32,
    columns: 1,
    overlay: false,
};

/// The sheet pages of `font` through `reuse`, written into `dir` with the record.
fn pages(font: &OutlinedFont, dir: &Path, reuse: &Reuse) -> Vec<(String, Vec<u8>)> {
    let ttf = otf::ttf(font).unwrap();
    let outlines = OutlineKeys::new(font, reuse);
    let key = font_key(font, &ttf, &outlines);
    let layout = Layout::with_ttf(font, ttf).unwrap();
    let files =
        sheet_png_files_reusing(&layout, &OPTS, "sheet", reuse, Some(&key), &outlines).unwrap();
    for (name, bytes) in &files {
        std::fs::write(dir.join(name), bytes).unwrap();
    }
    reuse.save().unwrap();
    files
}

/// The same pages drawn without any record.
fn fresh(font: &OutlinedFont) -> Vec<(String, Vec<u8>)> {
    let layout = Layout::new(font).unwrap();
    let none = OutlineKeys::default();
    sheet_png_files_reusing(&layout, &OPTS, "sheet", &Reuse::off(), None, &none).unwrap()
}

fn load(dir: &Path) -> Reuse {
    let (reuse, ignored) = Reuse::load(dir);
    assert_eq!(ignored, None);
    reuse
}

#[test]
fn only_the_sheet_page_of_an_edited_glyph_is_drawn_again() {
    let dir = scratch("pages");
    let font = cjk_like();
    let first = pages(&font, &dir, &load(&dir));
    let names: Vec<&str> = first.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(names, ["sheet-1.png", "sheet-2.png", "sheet-3.png"]);
    assert_eq!(first, fresh(&font));

    // Nothing changed: every page from OUT, the same bytes.
    let reuse = load(&dir);
    assert_eq!(pages(&font, &dir, &reuse), first);
    assert_eq!(reuse.reused(), 3);

    // Glyph 70 (on page 2) moved by 10 units: page 2 drawn, pages 1 and 3 reused.
    let mut edited = font.clone();
    edited.glyphs[70]
        .path
        .apply_affine(Affine::translate(Vec2::new(10.0, 0.0)));
    let reuse = load(&dir);
    let second = pages(&edited, &dir, &reuse);
    assert_eq!(reuse.reused(), 2);
    assert_eq!(second, fresh(&edited));
    assert_eq!(second[0], first[0]);
    assert_ne!(second[1], first[1]);
    assert_eq!(second[2], first[2]);
}

#[test]
fn a_changed_output_or_a_damaged_record_is_not_trusted() {
    let dir = scratch("untrusted");
    let font = cjk_like();
    let expected = pages(&font, &dir, &load(&dir));

    // Page 1 overwritten with page 2's bytes (a valid PNG, the wrong one): drawn again.
    std::fs::write(dir.join("sheet-1.png"), &expected[1].1).unwrap();
    let reuse = load(&dir);
    assert_eq!(pages(&font, &dir, &reuse), expected);
    assert_eq!(reuse.reused(), 2);

    // A record with one bit flipped, then one cut short: ignored with the reason, every
    // page drawn, the same bytes.
    let record = std::fs::read(dir.join(REUSE_FILE)).unwrap();
    let mut flipped = record.clone();
    flipped[20] ^= 0x01;
    for (damaged, why) in [
        (
            flipped,
            "its checksum does not match (the file is damaged or truncated)",
        ),
        (record[..3].to_vec(), "the file is truncated"),
        (
            b"not a record at all".to_vec(),
            "it is not an xglyph output record",
        ),
    ] {
        std::fs::write(dir.join(REUSE_FILE), &damaged).unwrap();
        let (reuse, ignored) = Reuse::load(&dir);
        assert_eq!(ignored.as_deref(), Some(why));
        assert_eq!(pages(&font, &dir, &reuse), expected);
        assert_eq!(reuse.reused(), 0);
    }
    // The record written again by the last run is whole: everything reused.
    let reuse = load(&dir);
    assert_eq!(pages(&font, &dir, &reuse), expected);
    assert_eq!(reuse.reused(), 3);
}

/// Every file under `dir` but the records of a build (fit cache, outputs, source memo, and
/// their delta files, all named `.xglyph-…`), by relative path, with its bytes. (Whether a
/// build writes a delta file depends on how many of its outputs were old enough to stamp.)
fn output_files(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    let mut out = BTreeMap::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for entry in std::fs::read_dir(&d).unwrap() {
            let path = entry.unwrap().path();
            let name = path.file_name().unwrap().to_string_lossy().into_owned();
            if path.is_dir() {
                stack.push(path);
            } else if !name.starts_with(".xglyph-") {
                let rel = path
                    .strip_prefix(dir)
                    .unwrap()
                    .to_string_lossy()
                    .into_owned();
                out.insert(rel, std::fs::read(&path).unwrap());
            }
        }
    }
    out
}

fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for entry in std::fs::read_dir(from).unwrap() {
        let path = entry.unwrap().path();
        let target = to.join(path.file_name().unwrap());
        if path.is_dir() {
            copy_dir(&path, &target);
        } else {
            std::fs::copy(&path, &target).unwrap();
        }
    }
}

fn build(font_dir: &Path, out: &Path) -> String {
    let output = std::process::Command::new(env!("CARGO_BIN_EXE_xglyph"))
        .args([
            "build",
            font_dir.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(0), "{output:?}");
    String::from_utf8(output.stdout).unwrap()
}

#[test]
fn a_rebuild_takes_unchanged_outputs_and_writes_the_bytes_of_a_fresh_build() {
    let tmp = scratch("build");
    let src = tmp.join("src");
    copy_dir(&repo("tests/fixtures/masters"), &src);
    let out = tmp.join("out");
    let stdout = build(&src, &out);
    assert!(!stdout.contains("took"), "{stdout}");
    // Again: the sheet, the proof, the instances' proof, the static and the variable WOFF2
    // from OUT.
    let stdout = build(&src, &out);
    assert!(
        stdout.contains("took 5 outputs unchanged from the last build"),
        "{stdout}"
    );
    let fresh_out = tmp.join("fresh");
    build(&src, &fresh_out);
    assert_eq!(output_files(&out), output_files(&fresh_out));

    // The WOFF2 in OUT replaced by other bytes: made anew, not trusted.
    let woff2 = output_files(&out)
        .into_keys()
        .find(|n| n.ends_with(".woff2") && !n.contains('['))
        .unwrap();
    std::fs::write(out.join(&woff2), b"wOF2 but not really").unwrap();
    let stdout = build(&src, &out);
    assert!(stdout.contains("took 4 outputs unchanged"), "{stdout}");
    assert_eq!(output_files(&out), output_files(&fresh_out));

    // One glyph edited: its outline changes every output that draws the whole font.
    let glyph = src.join("H_.toml");
    let text = std::fs::read_to_string(&glyph).unwrap();
    let edited = text.replacen("  [160, 320, 0],", "  [170, 320, 0],", 1);
    assert_ne!(edited, text, "{text}");
    std::fs::write(&glyph, edited).unwrap();
    build(&src, &out);
    build(&src, &fresh_out.with_file_name("fresh2"));
    assert_eq!(
        output_files(&out),
        output_files(&fresh_out.with_file_name("fresh2"))
    );
    assert_ne!(output_files(&out), output_files(&fresh_out));
}

#[test]
fn an_output_changed_in_out_is_rewritten_though_its_length_is_the_same() {
    let tmp = scratch("stamps");
    let out = tmp.join("out");
    build(&repo("glyphs"), &out);
    // A file written in the last 50 ms gets no stamp (the file system's clock is coarse);
    // the next build, which writes nothing, stamps every file (in the record, or in its
    // delta file when the first build could stamp most of them already).
    std::thread::sleep(std::time::Duration::from_millis(100));
    build(&repo("glyphs"), &out);
    let built = output_files(&out);
    let mut record = std::fs::read(out.join(REUSE_FILE)).unwrap();
    if let Ok(delta) = std::fs::read(out.join(xglyph::reuse::DELTA_FILE)) {
        record.extend(delta);
    }
    for name in built.keys() {
        let found = record.windows(name.len()).any(|w| w == name.as_bytes());
        assert!(found, "{name} has no stamp");
    }
    // Same length, other bytes, in a glyph SVG and the OTF (never reused by key).
    let svg = built
        .keys()
        .find(|n| n.starts_with("svg/"))
        .unwrap()
        .clone();
    let otf = built.keys().find(|n| n.ends_with(".otf")).unwrap().clone();
    for name in [&svg, &otf] {
        let mut bytes = built[name].clone();
        let mid = bytes.len() / 2;
        bytes[mid] ^= 0x20;
        std::fs::write(out.join(name), &bytes).unwrap();
    }
    build(&repo("glyphs"), &out);
    assert_eq!(output_files(&out), built);
}

#[test]
fn glyph_data_comes_back_from_the_record_and_bad_bytes_are_made_anew() {
    use std::cell::Cell;
    let dir = scratch("data");
    let key = |n: u64| KeyBuilder::new("test data").u64(n).finish();
    let encode = |v: &u32| v.to_le_bytes().to_vec();
    let decode = |b: &[u8]| Some(u32::from_le_bytes(b.try_into().ok()?));
    let made = Cell::new(0);
    let make = |v: u32| {
        made.set(made.get() + 1);
        Ok::<u32, ()>(v)
    };
    let first = load(&dir);
    assert_eq!(
        first.data_or_make(key(1), encode, decode, || make(7)),
        Ok(7)
    );
    assert_eq!(
        first.data_or_make(key(2), encode, decode, || make(8)),
        Ok(8)
    );
    first.save().unwrap();
    assert_eq!(made.get(), 2);
    // The next build takes both from the record; its make is not called.
    let second = load(&dir);
    assert_eq!(
        second.data_or_make(key(1), encode, decode, || make(0)),
        Ok(7)
    );
    // Bytes the decoder refuses are made anew; a key the record lacks too.
    let refuse = |_: &[u8]| None;
    assert_eq!(
        second.data_or_make(key(2), encode, refuse, || make(9)),
        Ok(9)
    );
    assert_eq!(
        second.data_or_make(key(3), encode, decode, || make(10)),
        Ok(10)
    );
    assert_eq!(made.get(), 4);
    second.save().unwrap();
    // What the second build kept, taken or made, comes back.
    let third = load(&dir);
    for (k, v) in [(1, 7), (2, 9), (3, 10)] {
        assert_eq!(
            third.data_or_make(key(k), encode, decode, || make(0)),
            Ok(v)
        );
    }
    assert_eq!(made.get(), 4);
    // Without an output folder: always made, nothing kept.
    let off = Reuse::off();
    assert_eq!(
        off.data_or_make(key(1), encode, decode, || make(11)),
        Ok(11)
    );
    assert_eq!(made.get(), 5);
}

#[test]
fn a_few_changes_go_into_a_delta_file_bound_to_the_record_file() {
    use std::cell::Cell;
    use xglyph::reuse::DELTA_FILE;
    let dir = scratch("delta");
    // Entry k holds the value v under a key of both (a key determines its value).
    let key = |k: usize, v: u64| KeyBuilder::new("test delta").u64(k as u64).u64(v).finish();
    let encode = |v: &u64| v.to_le_bytes().to_vec();
    let decode = |b: &[u8]| Some(u64::from_le_bytes(b.try_into().ok()?));
    let made = Cell::new(0);
    // One build keeping `values`: the files its save would write (names), then saved.
    let build = |values: &[u64]| -> Vec<String> {
        let reuse = load(&dir);
        for (k, &v) in values.iter().enumerate() {
            let make = || {
                made.set(made.get() + 1);
                Ok::<_, ()>(v)
            };
            assert_eq!(reuse.data_or_make(key(k, v), encode, decode, make), Ok(v));
        }
        let files = reuse.files_to_save().unwrap();
        reuse.save().unwrap();
        files
            .iter()
            .map(|(p, _)| p.file_name().unwrap().to_string_lossy().into_owned())
            .collect()
    };
    let read = |name: &str| std::fs::read(dir.join(name)).ok();
    let mut values = vec![0; 100];
    assert_eq!(build(&values), [REUSE_FILE]);
    assert_eq!(made.replace(0), 100);
    let record = read(REUSE_FILE).unwrap();

    // Two entries changed: only they are made, and only the delta file is written; the
    // record file keeps its bytes.
    values[5] = 1;
    values[60] = 1;
    assert_eq!(build(&values), [DELTA_FILE]);
    assert_eq!(made.replace(0), 2);
    assert_eq!(read(REUSE_FILE).unwrap(), record);
    let delta = read(DELTA_FILE).unwrap();
    assert!(delta.len() < record.len() / 10, "{} bytes", delta.len());
    // Unchanged: everything from the two files, nothing written.
    assert_eq!(build(&values), Vec::<String>::new());
    assert_eq!(made.replace(0), 0);

    // A damaged delta is ignored: the two entries it held are made again.
    let mut flipped = delta.clone();
    flipped[30] ^= 0x10;
    std::fs::write(dir.join(DELTA_FILE), &flipped).unwrap();
    build(&values);
    assert_eq!(made.replace(0), 2);
    assert_eq!(read(DELTA_FILE).unwrap(), delta);

    // Twenty entries changed (more than an eighth): the record file whole again.
    for v in &mut values[..20] {
        *v = 2;
    }
    assert_eq!(build(&values), [REUSE_FILE]);
    assert_eq!(made.replace(0), 20);
    assert_ne!(read(REUSE_FILE).unwrap(), record);
    // The delta file left behind is bound to the old record file and ignored: entry 60's
    // value 1 comes from the new record file, entry 5's value 1 (only in the old delta)
    // is made again.
    assert_eq!(read(DELTA_FILE).unwrap(), delta);
    values[5] = 1;
    build(&values);
    assert_eq!(made.replace(0), 1);
}

#[test]
fn outline_keys_are_each_outlines_own_and_tell_an_edit() {
    let dir = scratch("outline-keys");
    let mut font = cjk_like();
    let on = load(&dir);
    let made = OutlineKeys::new(&font, &on);
    let none = OutlineKeys::new(&font, &Reuse::off());
    for (i, g) in font.glyphs.iter().enumerate() {
        assert_eq!(made.get(i, &g.path), outline_key(&g.path), "{}", g.name);
        assert_eq!(none.get(i, &g.path), outline_key(&g.path), "{}", g.name);
    }
    // One point moved by one bit: another key; the other glyphs' keys stay.
    let before = made.get(1, &font.glyphs[1].path);
    if let Some(kurbo::PathEl::LineTo(p)) = font.glyphs[1].path.elements_mut().get_mut(1) {
        p.x = f64::from_bits(p.x.to_bits() + 1);
    } else {
        panic!("glyph 1's second element is a line");
    }
    let after = OutlineKeys::new(&font, &on);
    assert_ne!(after.get(1, &font.glyphs[1].path), before);
    assert_eq!(
        after.get(0, &font.glyphs[0].path),
        made.get(0, &font.glyphs[0].path)
    );
}

#[test]
fn unions_from_the_record_are_those_made_anew() {
    use xglyph::overlap::{remove_overlaps_font, remove_overlaps_font_with};
    let dir = scratch("unions");
    // Glyph 0 of two overlapping squares, glyph 1 of two apart (nothing to union).
    let font = with_overlaps();
    let fresh = remove_overlaps_font(&font);
    let first = load(&dir);
    let made = remove_overlaps_font_with(&font, &first, &OutlineKeys::new(&font, &first));
    first.save().unwrap();
    let second = load(&dir);
    let taken = remove_overlaps_font_with(&font, &second, &OutlineKeys::new(&font, &second));
    for ((a, b), c) in fresh.glyphs.iter().zip(&made.glyphs).zip(&taken.glyphs) {
        assert_eq!(a.path, b.path, "{}", a.name);
        assert_eq!(a.path, c.path, "{}", a.name);
        assert_eq!(a.segments, c.segments, "{}", a.name);
    }
    // Glyph 0's union is one contour (so the record holds an outline), glyph 1 keeps two.
    let subpaths = |p: &kurbo::BezPath| {
        p.elements()
            .iter()
            .filter(|e| matches!(e, kurbo::PathEl::MoveTo(_)))
            .count()
    };
    assert_eq!(subpaths(&fresh.glyphs[0].path), 1);
    assert_eq!(subpaths(&fresh.glyphs[1].path), 2);
    let record = std::fs::read(dir.join(REUSE_FILE)).unwrap();
    assert!(record.len() > 200, "{} bytes", record.len());
}

/// Two glyphs of `cjk_like`: glyph 0 two overlapping squares, glyph 1 two apart.
fn with_overlaps() -> OutlinedFont {
    let mut font = cjk_like();
    for (k, d) in [(0, 300.0), (1, 1000.0)] {
        let mut path = kurbo::BezPath::new();
        for x in [0.0, d] {
            path.extend(kurbo::Shape::path_elements(
                &kurbo::Rect::new(x, x, x + 500.0, x + 500.0),
                0.1,
            ));
        }
        font.glyphs[k].path = path;
    }
    font
}

#[test]
fn unions_kept_unread_give_the_fonts_of_unions_made_anew() {
    use xglyph::otf::GlyphPaths;
    use xglyph::overlap::{remove_overlaps_font, Unions};
    let dir = scratch("kept-unions");
    let font = with_overlaps();
    let fresh = remove_overlaps_font(&font);
    let (want_ttf, want_otf) = (otf::ttf(&fresh).unwrap(), otf::otf(&fresh).unwrap());
    // The first build makes every union and records them (no glyph data: the fonts are not
    // built through the record here).
    let first = load(&dir);
    let made = Unions::new(&font, &first, &OutlineKeys::new(&font, &first));
    for (i, g) in fresh.glyphs.iter().enumerate() {
        assert_eq!(made.path(i).as_ref(), &g.path, "{}", g.name);
    }
    first.save().unwrap();
    // The second holds every union unread, and keeps them for the next build unread.
    let second = load(&dir);
    let kept = Unions::new(&font, &second, &OutlineKeys::new(&font, &second));
    second.save().unwrap();
    // The third decodes them when the fonts' glyph data is not in the record: the fonts
    // are those of the unions made anew, and those of the next build too, taken by key.
    for _ in 0..2 {
        let third = load(&dir);
        let outlines = OutlineKeys::new(&font, &third);
        let kept_now = Unions::new(&font, &third, &outlines);
        let paths: Option<&dyn GlyphPaths> = Some(&kept_now);
        let ttf = otf::ttf_reusing_paths(&font, paths, &third, kept_now.keys()).unwrap();
        let otf = otf::otf_reusing_paths(&font, paths, &third, kept_now.keys()).unwrap();
        assert!(ttf == want_ttf, "TTF differs");
        assert!(otf == want_otf, "OTF differs");
        third.save().unwrap();
    }
    for (i, g) in fresh.glyphs.iter().enumerate() {
        assert_eq!(kept.path(i).as_ref(), &g.path, "{}", g.name);
    }
    // A glyph whose union is not in the record is made at once: an edit.
    let mut edited = font.clone();
    edited.glyphs[0]
        .path
        .apply_affine(Affine::translate(Vec2::new(7.0, 0.0)));
    let fourth = load(&dir);
    let unions = Unions::new(&edited, &fourth, &OutlineKeys::new(&edited, &fourth));
    let want = remove_overlaps_font(&edited);
    assert_eq!(unions.path(0).as_ref(), &want.glyphs[0].path);
    assert_ne!(want.glyphs[0].path, fresh.glyphs[0].path);
}

/// The number in the build's `left N glyph files` line (0 without one).
fn left(stdout: &str) -> usize {
    stdout
        .lines()
        .find_map(|l| l.strip_prefix("left ")?.split(' ').next()?.parse().ok())
        .unwrap_or(0)
}

#[test]
fn glyph_files_of_unchanged_glyphs_are_not_made_and_the_outputs_are_a_fresh_builds() {
    let tmp = scratch("kept");
    let src = tmp.join("src");
    copy_dir(&repo("tests/fixtures/mini"), &src);
    let out = tmp.join("out");
    let settle = || std::thread::sleep(std::time::Duration::from_millis(100));
    // Files just written get no stamp; the second build stamps them, the third trusts them:
    // the 8 glyph SVGs and 8 `.glif`s are left in OUT without being made.
    assert_eq!(left(&build(&src, &out)), 0);
    settle();
    build(&src, &out);
    settle();
    let stdout = build(&src, &out);
    assert_eq!(left(&stdout), 16, "{stdout}");
    assert!(stdout.contains("wrote 29 files"), "{stdout}");
    let fresh = |name: &str| {
        let dir = tmp.join(name);
        build(&src, &dir);
        output_files(&dir)
    };
    let before = fresh("fresh1");
    same(&output_files(&out), &before);

    // `o` edited: its files and those of `oacute` (an `o` with an accent) are made anew.
    let glyph = src.join("o.toml");
    let text = std::fs::read_to_string(&glyph).unwrap();
    let edited = text.replacen("[520, 250, -1]", "[525, 250, -1]", 1);
    assert_ne!(edited, text, "{text}");
    std::fs::write(&glyph, edited).unwrap();
    settle();
    let stdout = build(&src, &out);
    assert_eq!(left(&stdout), 12, "{stdout}");
    let expected = fresh("fresh2");
    let changed: Vec<&String> = expected
        .iter()
        .filter(|(name, bytes)| before.get(*name) != Some(bytes))
        .map(|(name, _)| name)
        .collect();
    for name in [
        "svg/o.svg",
        "svg/oacute.svg",
        "MiniTest-Regular.ufo/glyphs/o.glif",
    ] {
        assert!(changed.contains(&&name.to_string()), "{changed:?}");
    }
    same(&output_files(&out), &expected);

    // A glyph SVG and a `.glif` replaced in OUT by bytes of the same length: their stamps no
    // longer match, so they are made and rewritten.
    settle();
    build(&src, &out);
    let names: Vec<String> = ["svg/A_.svg", "MiniTest-Regular.ufo/glyphs/V_.glif"]
        .map(String::from)
        .to_vec();
    for name in &names {
        let mut bytes = expected[name].clone();
        let mid = bytes.len() / 2;
        bytes[mid] ^= 0x20;
        std::fs::write(out.join(name), &bytes).unwrap();
    }
    settle();
    let stdout = build(&src, &out);
    assert_eq!(left(&stdout), 14, "{stdout}");
    same(&output_files(&out), &expected);

    // A damaged record: ignored, every file made, the same bytes.
    let record = out.join(REUSE_FILE);
    let mut bytes = std::fs::read(&record).unwrap();
    let mid = bytes.len() / 2;
    bytes[mid] ^= 0x01;
    std::fs::write(&record, bytes).unwrap();
    let stdout = build(&src, &out);
    assert_eq!(left(&stdout), 0, "{stdout}");
    same(&output_files(&out), &expected);
}

/// Asserts that two folders' files are the same, naming those that differ.
fn same(got: &BTreeMap<String, Vec<u8>>, want: &BTreeMap<String, Vec<u8>>) {
    let names: std::collections::BTreeSet<&String> = got.keys().chain(want.keys()).collect();
    let differ: Vec<&&String> = names
        .iter()
        .filter(|n| got.get(**n) != want.get(**n))
        .collect();
    assert!(differ.is_empty(), "these files differ: {differ:?}");
}
