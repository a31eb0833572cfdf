//! Compatible fitting of two masters against a static fit of one (issue 16, item 3), in
//! the same run: bundled glyphs with a bold master made by `tests/it/common/masters.rs`
//! (every point 30 units along its normal, `s` × 0.9).
//! Run: `cargo bench --bench compatible`.
//!
//! Positions: the 11 evenly spaced ones of the tests (the masters included), and the
//! masters plus their midpoint only (what the span search checks before verification).

use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use xglyph::compatible::fit_compatible;
use xglyph::fit::fit_contour;
use xglyph::xspline::XSpline;

#[path = "../tests/it/common/masters.rs"]
mod masters;

/// Glyphs with bowls, stems, terminals and mixed `s`.
const GLYPHS: [&str; 6] = ["a", "g", "S", "ampersand", "O", "R"];

fn bench(c: &mut Criterion) {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("glyphs");
    let (font, _) = xglyph::source::load_font(&dir).expect("the bundled glyphs load");
    let tolerance = font.info.tolerance;
    let pairs: Vec<(XSpline, XSpline)> = GLYPHS
        .iter()
        .flat_map(|name| &font.glyph(name).expect("a bundled glyph").contours)
        .map(|contour| {
            let light = contour.spline().clone();
            let bold = masters::bold(&light, 30.0, 0.9).expect("a valid bold master");
            (light, bold)
        })
        .collect();
    let eleven = masters::evenly_spaced(11);
    let three = masters::evenly_spaced(3);
    let mut group = c.benchmark_group("compatible");
    group.sample_size(10);
    group.bench_function("static fit, light master (reference)", |b| {
        b.iter(|| {
            pairs
                .iter()
                .map(|(light, _)| {
                    fit_contour(black_box(light), tolerance)
                        .path
                        .elements()
                        .len()
                })
                .sum::<usize>()
        })
    });
    group.bench_function("static fit, bold master", |b| {
        b.iter(|| {
            pairs
                .iter()
                .map(|(_, bold)| {
                    fit_contour(black_box(bold), tolerance)
                        .path
                        .elements()
                        .len()
                })
                .sum::<usize>()
        })
    });
    for (label, positions) in [("11 positions", &eleven), ("masters + midpoint", &three)] {
        group.bench_function(format!("compatible fit, 2 masters, {label}"), |b| {
            b.iter(|| {
                pairs
                    .iter()
                    .map(|(light, bold)| {
                        fit_compatible(&[light, bold], black_box(positions), tolerance)
                            .map_or(0, |fit| fit.segments)
                    })
                    .sum::<usize>()
            })
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
