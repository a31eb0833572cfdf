//! Orienting a glyph of many contours (issue 13, item 9): the nesting sweep of
//! `xglyph::orient` against the all-pairs definition it replaced, kept here as the
//! reference, on the same fitted contours. Run: `cargo bench --bench orient`.
//!
//! The glyph: a grid of rings (an outer square and a hole), 2k, 4k and 8k contours, fitted
//! as in a build. `fit + orient 8k` is the whole per-glyph outline step.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use kurbo::{BezPath, PathEl, Shape};
use std::hint::black_box;
use xglyph::fit::fit_contour;
use xglyph::orient::{nesting_depths, orient_contours};
use xglyph::xspline::{ControlPoint, XSpline};

/// `contours` X-spline contours: rings of two squares with rounded (`s = 1`) corners on
/// a grid, 100 units apart.
fn splines(contours: usize) -> Vec<XSpline> {
    let rings = contours / 2;
    let side = (rings as f64).sqrt().ceil() as usize;
    let ring = |x: f64, y: f64, r: f64, s: f64| {
        XSpline::new(vec![
            ControlPoint::new(x - r, y - r, s),
            ControlPoint::new(x + r, y - r, s),
            ControlPoint::new(x + r, y + r, s),
            ControlPoint::new(x - r, y + r, s),
        ])
        .expect("a valid square")
    };
    (0..rings)
        .flat_map(|k| {
            let (x, y) = ((k % side) as f64 * 100.0, (k / side) as f64 * 100.0);
            [ring(x, y, 40.0, 0.0), ring(x, y, 20.0, 1.0)]
        })
        .collect()
}

fn fitted(contours: usize) -> Vec<BezPath> {
    splines(contours)
        .iter()
        .map(|s| fit_contour(s, 0.5).path)
        .collect()
}

/// The code this replaced: every contour's winding tested around every first point.
fn orient_all_pairs(contours: Vec<BezPath>) -> BezPath {
    let first = |p: &BezPath| {
        p.elements().iter().find_map(|el| match el {
            PathEl::MoveTo(p) => Some(*p),
            _ => None,
        })
    };
    let probes: Vec<_> = contours.iter().map(first).collect();
    let mut out = BezPath::new();
    for (i, contour) in contours.iter().enumerate() {
        let depth = contours
            .iter()
            .enumerate()
            .filter(|&(j, other)| j != i && probes[i].is_some_and(|p| other.winding(p) != 0))
            .count();
        if (contour.area() > 0.0) == (depth % 2 == 0) {
            out.extend(contour.iter());
        } else {
            out.extend(contour.reverse_subpaths().iter());
        }
    }
    out
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("orient");
    group.sample_size(10);
    for n in [2000, 4000, 8000] {
        let contours = fitted(n);
        // Same result, element for element, before timing anything.
        assert_eq!(
            orient_contours(contours.clone()),
            orient_all_pairs(contours.clone())
        );
        assert_eq!(
            nesting_depths(&contours)
                .iter()
                .filter(|&&d| d == 1)
                .count(),
            n / 2
        );
        group.bench_with_input(BenchmarkId::new("sweep", n), &contours, |b, c| {
            b.iter(|| orient_contours(black_box(c.clone())))
        });
        group.bench_with_input(BenchmarkId::new("all pairs (old)", n), &contours, |b, c| {
            b.iter(|| orient_all_pairs(black_box(c.clone())))
        });
    }
    group.finish();

    let mut group = c.benchmark_group("outline one glyph");
    group.sample_size(10);
    let splines = splines(8000);
    group.bench_function("fit + orient 8k contours", |b| {
        b.iter(|| {
            let fitted = splines.iter().map(|s| fit_contour(s, 0.5).path).collect();
            orient_contours(black_box(fitted)).elements().len()
        })
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
