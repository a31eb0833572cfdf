//! Hostile sources through the loader (what `check` and the start of `build` run): 8,000
//! contours in one glyph, a 4,000-deep chain of components, components doubling at each of
//! 14 levels, and a file with 10,000 errors; the bundled typeface is the reference measured
//! in the same run. Also the outlines of the 4,000-deep chain against 4,000 independent
//! glyphs of the same triangle, which shows the cost of resolving components.
//! Run: `cargo bench --bench limits`.

use std::fmt::Write;
use std::path::{Path, PathBuf};

use criterion::{criterion_group, criterion_main, Criterion};
use xglyph::outline::outline_font;
use xglyph::source::load_font;

const FONT: &str = "family = \"T\"\nunits_per_em = 1000\nascender = 800\ndescender = -200\n\
                    x_height = 500\ncap_height = 700\n";
const TRIANGLE: &str =
    "advance = 500\n[[contour]]\npoints = [[0, 0, 0], [100, 0, 0], [0, 100, 0]]\n";

/// A font folder under the temporary folder with `font.toml` and `files`.
fn font_dir(name: &str, files: &[(String, String)]) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("xglyph-bench-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("mkdir");
    std::fs::write(dir.join("font.toml"), FONT).expect("write");
    for (file, text) in files {
        std::fs::write(dir.join(file), text).expect("write");
    }
    dir
}

/// One glyph of `n` small triangles on a grid (no two overlap).
fn contours(n: usize) -> Vec<(String, String)> {
    let mut text = String::from("advance = 500\n");
    for i in 0..n {
        let (x, y) = ((i % 100) as f64 * 10.0, (i / 100) as f64 * 10.0);
        let _ = write!(
            text,
            "[[contour]]\npoints = [[{x}, {y}, 0], [{}, {y}, 0], [{x}, {}, 0]]\n",
            x + 5.0,
            y + 5.0
        );
    }
    vec![("a.toml".into(), text)]
}

/// `g0000` a triangle, each next glyph one component of the one before.
fn chain(n: usize) -> Vec<(String, String)> {
    (0..n)
        .map(|i| {
            let text = if i == 0 {
                TRIANGLE.to_string()
            } else {
                format!("advance = 500\n[[component]]\nbase = \"g{:04}\"\n", i - 1)
            };
            (format!("g{i:04}.toml"), text)
        })
        .collect()
}

/// `n` independent triangles.
fn flat(n: usize) -> Vec<(String, String)> {
    (0..n)
        .map(|i| (format!("g{i:04}.toml"), TRIANGLE.to_string()))
        .collect()
}

/// `o`, then `b01` = two `o`, `bN` = two `b(N-1)`: `b14` expands to 16,384 contours.
fn doubling(levels: usize) -> Vec<(String, String)> {
    let mut files = vec![("o.toml".to_string(), TRIANGLE.to_string())];
    let mut prev = "o".to_string();
    for i in 1..=levels {
        let name = format!("b{i:02}");
        files.push((
            format!("{name}.toml"),
            format!(
                "advance = 500\n[[component]]\nbase = \"{prev}\"\n[[component]]\nbase = \
                 \"{prev}\"\noffset = [1, 1]\n"
            ),
        ));
        prev = name;
    }
    files
}

/// One contour whose `n` points each have `s` out of range: `n` errors in one file.
fn errors(n: usize) -> Vec<(String, String)> {
    let mut text = String::from("advance = 500\n[[contour]]\npoints = [\n");
    for i in 0..n {
        let _ = writeln!(text, "  [{}, 0, 5],", i % 1000);
    }
    text.push_str("]\n");
    vec![("a.toml".into(), text)]
}

fn load(dir: &Path) -> usize {
    match load_font(dir) {
        Ok((font, _)) => font.glyphs.len(),
        Err(diags) => diags.len(),
    }
}

fn bench(c: &mut Criterion) {
    let bundled = Path::new(env!("CARGO_MANIFEST_DIR")).join("glyphs");
    let cases = [
        ("contours8k", font_dir("contours8k", &contours(8000))),
        ("chain4000", font_dir("chain4000", &chain(4000))),
        ("doubling14", font_dir("doubling14", &doubling(14))),
        ("errors10k", font_dir("errors10k", &errors(10_000))),
    ];
    let mut group = c.benchmark_group("load (check)");
    group.sample_size(10);
    group.bench_function("bundled typeface (reference)", |b| {
        b.iter(|| load(&bundled))
    });
    for (name, dir) in &cases {
        group.bench_function(*name, |b| b.iter(|| load(dir)));
    }
    group.finish();

    let flat_dir = font_dir("flat4000", &flat(4000));
    let chain_font = load_font(&cases[1].1).expect("chain loads").0;
    let flat_font = load_font(&flat_dir).expect("flat loads").0;
    let mut group = c.benchmark_group("outline");
    group.sample_size(10);
    group.bench_function("4000 independent triangles (reference)", |b| {
        b.iter(|| outline_font(&flat_font, 0.5).glyphs.len())
    });
    group.bench_function("4000-deep chain of components", |b| {
        b.iter(|| outline_font(&chain_font, 0.5).glyphs.len())
    });
    group.finish();
    for dir in cases.iter().map(|(_, d)| d).chain([&flat_dir]) {
        let _ = std::fs::remove_dir_all(dir);
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
