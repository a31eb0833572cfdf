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
//!
//! Before Criterion, in the same run, an **interleaved probe** over every bundled contour
//! (143) at the 11 positions: per contour, a static fit of the Regular and a compatible fit
//! timed alternately, best of 5 each, summed. Interleaving exposes both to the same load,
//! which Criterion's consecutive groups do not. `XGLYPH_PROBE_ONLY=Bold` (or `="synthetic bold"`)
//! runs that master's probe once (one round, no Criterion), for `valgrind --tool=callgrind`.
//! `XGLYPH_PROBE_DIGEST=1` prints what the fits give (segments, largest error, a hash of
//! the outputs' bits) and nothing else, to compare two binaries' outputs.

use criterion::Criterion;
use std::hint::black_box;
use std::time::{Duration, Instant};
use xglyph::compatible::fit_compatible;
use xglyph::fit::fit_contour;
use xglyph::xspline::XSpline;

#[path = "../tests/it/common/masters.rs"]
mod masters;

/// Glyphs with bowls, stems, terminals and mixed `s`.
const GLYPHS: [&str; 6] = ["a", "g", "S", "ampersand", "O", "R"];

/// Contours paired with a second master.
type Pairs = Vec<(XSpline, XSpline)>;

/// Every bundled contour with its Bold master and with the synthetic bold.
fn all_pairs() -> (Pairs, Pairs, f64) {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("glyphs");
    let (family, _) = xglyph::source::load_family(&dir).expect("the bundled glyphs load");
    let mut bundled = Vec::new();
    let mut synthetic = Vec::new();
    for (light, heavy) in family.default.glyphs.iter().zip(&family.masters[0].glyphs) {
        for (a, b) in light.contours.iter().zip(&heavy.contours) {
            let a = a.spline().clone();
            let made = masters::bold(&a, 30.0, 0.9).expect("a valid bold master");
            bundled.push((a.clone(), b.spline().clone()));
            synthetic.push((a, made));
        }
    }
    (bundled, synthetic, family.default.info.tolerance)
}

/// How long `f` takes, once.
fn time(mut f: impl FnMut() -> usize) -> Duration {
    let start = Instant::now();
    black_box(f());
    start.elapsed()
}

/// The interleaved probe: Σ over contours of the best static fit of the Regular and the
/// best compatible fit, timed alternately per contour; prints both and their ratio.
/// `only`: `"Bold"` or `"synthetic bold"` probes that master alone.
fn probe(rounds: usize, only: Option<&str>) {
    let (bundled, synthetic, tolerance) = all_pairs();
    let eleven = masters::evenly_spaced(11);
    for (label, pairs) in [("Bold", &bundled), ("synthetic bold", &synthetic)] {
        if only.is_some_and(|o| o != label) {
            continue;
        }
        let (mut fixed, mut joint) = (Duration::ZERO, Duration::ZERO);
        for (light, bold) in pairs {
            let (mut one, mut two) = (Duration::MAX, Duration::MAX);
            for _ in 0..rounds.max(1) {
                one = one.min(time(|| {
                    fit_contour(black_box(light), tolerance)
                        .path
                        .elements()
                        .len()
                }));
                two = two.min(time(|| {
                    fit_compatible(&[light, bold], black_box(&eleven), tolerance)
                        .map_or(0, |fit| fit.segments)
                }));
            }
            fixed += one;
            joint += two;
        }
        println!(
            "probe, Regular + {label}, {} contours, 11 positions: static {:.1} ms, \
             compatible {:.1} ms, ratio {:.2}",
            pairs.len(),
            fixed.as_secs_f64() * 1e3,
            joint.as_secs_f64() * 1e3,
            joint.as_secs_f64() / fixed.as_secs_f64()
        );
    }
}

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

/// What the compatible fits of every bundled contour at the 11 positions give, per second
/// master: segments, the largest `max_error`, and a hash of every path's and error's bits
/// (to tell whether two binaries give the same outputs).
fn digest() {
    use std::hash::{Hash, Hasher};
    let (bundled, synthetic, tolerance) = all_pairs();
    let eleven = masters::evenly_spaced(11);
    for (label, pairs) in [("Bold", &bundled), ("synthetic bold", &synthetic)] {
        let mut hasher = std::collections::hash_map::DefaultHasher::new();
        let (mut segments, mut worst) = (0, 0.0_f64);
        for (light, bold) in pairs {
            let fit = fit_compatible(&[light, bold], &eleven, tolerance).expect("a fit");
            segments += fit.segments;
            for path in &fit.paths {
                // Rust prints an `f64` in the fewest digits that read back to it: exact.
                path.to_svg().hash(&mut hasher);
            }
            for error in &fit.max_error {
                error.to_bits().hash(&mut hasher);
                worst = worst.max(*error);
            }
        }
        println!(
            "digest, Regular + {label}: {segments} segments, worst max_error {worst:.6}, \
             hash {:016x}",
            hasher.finish()
        );
    }
}

fn main() {
    if std::env::var_os("XGLYPH_PROBE_DIGEST").is_some() {
        digest();
        return;
    }
    if let Some(only) = std::env::var_os("XGLYPH_PROBE_ONLY") {
        probe(1, only.to_str());
        return;
    }
    probe(5, None);
    let mut criterion = Criterion::default().configure_from_args();
    bench(&mut criterion);
    criterion.final_summary();
}
