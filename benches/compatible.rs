//! Compatible fitting of two masters against a static fit of one (issue 16), in the same
//! run, on six bundled glyphs (`a g S ampersand O R`, 11 contours) with two second masters:
//! - the bundled Bold master (`glyphs/bold/`, the same `s` as the Regular at every point,
//!   so one bound covers every position between the masters);
//! - a synthetic bold made by `tests/it/common/masters.rs` (every point 30 units along its
//!   normal, `s` × 0.9: `s` differs everywhere, so positions are bounded one by one).
//!
//! Run: `cargo bench --bench compatible -- --warm-up-time 1 --measurement-time 3`.
//!
//! Positions: the 11 evenly spaced ones of the tests (the masters included), and the
//! masters plus their midpoint only.

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
    let (family, _) = xglyph::source::load_family(&dir).expect("the bundled glyphs load");
    let font = &family.default;
    let bold_master = &family.masters[0];
    let tolerance = font.info.tolerance;
    let mut bundled: Vec<(XSpline, XSpline)> = Vec::new();
    let mut synthetic: Vec<(XSpline, XSpline)> = Vec::new();
    for name in GLYPHS {
        let index = font
            .glyphs
            .iter()
            .position(|g| g.name == name)
            .expect("a bundled glyph");
        let bold = &bold_master.glyphs[index];
        for (light, heavy) in font.glyphs[index].contours.iter().zip(&bold.contours) {
            let light = light.spline().clone();
            let made = masters::bold(&light, 30.0, 0.9).expect("a valid bold master");
            bundled.push((light.clone(), heavy.spline().clone()));
            synthetic.push((light, made));
        }
    }
    let eleven = masters::evenly_spaced(11);
    let three = masters::evenly_spaced(3);
    let mut group = c.benchmark_group("compatible");
    group.sample_size(10);
    group.bench_function("static fit, Regular (reference)", |b| {
        b.iter(|| {
            bundled
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
    for (label, pairs) in [("Bold", &bundled), ("synthetic bold", &synthetic)] {
        group.bench_function(format!("static fit, {label}"), |b| {
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
        for (at, positions) in [("11 positions", &eleven), ("masters + midpoint", &three)] {
            group.bench_function(format!("compatible fit, Regular + {label}, {at}"), |b| {
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
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
