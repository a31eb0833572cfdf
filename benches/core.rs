//! Evaluation, flattening, fitting per contour, and kurbo's two fitters side by side
//! on the same corpus (tests/it/common/corpus.rs). Run: `cargo bench --bench core`.

use criterion::{criterion_group, criterion_main, Criterion};
use kurbo::{fit_to_bezpath, fit_to_bezpath_opt};
use std::hint::black_box;
use xglyph::fit::{fit_contour, stretches, Stretch, StretchSource};
use xglyph::flatten::flatten;

#[path = "../tests/it/common/corpus.rs"]
mod corpus;

const TOLERANCE: f64 = 0.5;

fn bench(c: &mut Criterion) {
    let splines = corpus::corpus();
    c.bench_function("xspline eval+deriv (1000 points)", |b| {
        b.iter(|| {
            let s = &splines[2];
            (0..1000).fold(0.0, |acc, i| {
                acc + s.eval_deriv(black_box(i as f64 * 0.005)).1.x
            })
        })
    });
    c.bench_function("flatten corpus (0.5 units)", |b| {
        b.iter(|| {
            splines
                .iter()
                .map(|s| flatten(black_box(s), TOLERANCE).points.len())
                .sum::<usize>()
        })
    });
    // One contour at a time: a glyph-like bowl with a stem, and a random 10-point contour.
    c.bench_function("fit one contour: D (5 points)", |b| {
        b.iter(|| {
            fit_contour(black_box(&splines[2]), TOLERANCE)
                .path
                .elements()
                .len()
        })
    });
    c.bench_function("fit one contour: S spine (12 points)", |b| {
        b.iter(|| {
            fit_contour(black_box(&splines[3]), TOLERANCE)
                .path
                .elements()
                .len()
        })
    });
    let mut group = c.benchmark_group("fit corpus");
    group.sample_size(10);
    group.bench_function("xglyph fit_contour", |b| {
        b.iter(|| {
            splines
                .iter()
                .map(|s| fit_contour(black_box(s), TOLERANCE).path.elements().len())
                .sum::<usize>()
        })
    });
    let kurbo_run = |opt: bool| {
        let mut total = 0;
        for s in &splines {
            for piece in stretches(s) {
                if let Stretch::Smooth { start, end } = piece {
                    let src = StretchSource {
                        spline: s,
                        start,
                        end,
                    };
                    let path = if opt {
                        fit_to_bezpath_opt(&src, TOLERANCE)
                    } else {
                        fit_to_bezpath(&src, TOLERANCE)
                    };
                    total += path.elements().len();
                }
            }
        }
        total
    };
    group.bench_function("kurbo fit_to_bezpath", |b| b.iter(|| kurbo_run(false)));
    group.bench_function("kurbo fit_to_bezpath_opt", |b| b.iter(|| kurbo_run(true)));
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
