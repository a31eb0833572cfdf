//! Overlap removal (`xglyph::overlap`) on the bundled typeface, against outlining the same
//! font (`outline_font`: fit + orient), measured in the same run as the reference. Run:
//! `cargo bench --bench overlap`.
//!
//! Three fonts: the typeface as it is (no overlaps: one sweep per glyph, paths kept), every
//! composite with its accent lowered 250 units into its base (39 glyphs unioned), and
//! every glyph over a copy of itself moved by (37, 23) (153 glyphs unioned).

use criterion::{criterion_group, criterion_main, Criterion};
use kurbo::Affine;
use std::hint::black_box;
use xglyph::outline::{outline_font, OutlinedFont};
use xglyph::overlap::remove_overlaps_font;
use xglyph::source::load_font;

fn fonts() -> (xglyph::Font, [(&'static str, OutlinedFont); 3]) {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("glyphs");
    let font = load_font(&dir).expect("the bundled typeface loads").0;
    let tolerance = font.info.tolerance;
    let plain = outline_font(&font, tolerance);
    let mut lowered = font.clone();
    for glyph in &mut lowered.glyphs {
        if glyph.components.len() >= 2 {
            if let Some(accent) = glyph.components.last_mut() {
                accent.offset.1 -= 250.0;
            }
        }
    }
    let lowered = outline_font(&lowered, tolerance);
    let mut shifted = plain.clone();
    for glyph in &mut shifted.glyphs {
        let copy = Affine::translate((37.0, 23.0)) * glyph.path.clone();
        glyph.path.extend(copy.iter());
    }
    (
        font,
        [
            ("union bundled", plain),
            ("union lowered accents", lowered),
            ("union shifted copies", shifted),
        ],
    )
}

fn bench(c: &mut Criterion) {
    let (font, outlined) = fonts();
    let mut group = c.benchmark_group("overlap");
    group.sample_size(10);
    group.bench_function("outline_font (reference)", |b| {
        b.iter(|| outline_font(black_box(&font), font.info.tolerance))
    });
    for (name, f) in &outlined {
        group.bench_function(*name, |b| b.iter(|| remove_overlaps_font(black_box(f))));
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
