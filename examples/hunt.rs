//! A seed hunt: fits random contours from the fit proptest's distribution
//! (`tests/it/common/curves.rs`: 3-60 points, mixed `s`, scales 1e-3..1e5, near-collinear
//! and nearly coincident points) at the proptest's tolerance (0.5 units per 1000 of scale)
//! and measures each fit with the tests' dense two-sided checker. Prints the worst
//! error/tolerance ratio, where it was found and how to replay it. This is how the
//! numbers in `src/fit.rs` and the README are reproduced.
//!
//! Usage: `cargo run --release --example hunt -- [CONTOURS] [SEED]`. CONTOURS defaults to
//! 4000; SEED (a u64) defaults to a fresh one from the clock and is printed. A contour
//! over the tolerance makes the exit status 1.
//!
//! Limit: it samples the error (200 curve samples per X-spline segment and 200 per path
//! segment, refined by nested scans), as the tests do; it does not prove a bound.

use std::process::ExitCode;
use std::time::{SystemTime, UNIX_EPOCH};

use proptest::strategy::{Strategy, ValueTree};
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};
use xglyph::fit::fit_contour;

// The tests' helpers (`curves` finds `paths` as its sibling, as in `tests/it/common`).
#[path = "../tests/it/common/curves.rs"]
mod curves;
#[path = "../tests/it/common/paths.rs"]
mod paths;

use curves::{hausdorff, random_contour};
use paths::cubic_count;

fn main() -> ExitCode {
    let mut args = std::env::args().skip(1);
    let Some(contours) = parse(args.next(), 4000) else {
        eprintln!("usage: hunt [CONTOURS] [SEED]");
        return ExitCode::from(2);
    };
    let fresh = SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .map_or(0, |d| d.as_nanos() as u64);
    let Some(seed) = parse(args.next(), fresh) else {
        eprintln!("usage: hunt [CONTOURS] [SEED]");
        return ExitCode::from(2);
    };
    let mut seed_bytes = [0u8; 32];
    seed_bytes[..8].copy_from_slice(&seed.to_le_bytes());
    let rng = TestRng::from_seed(RngAlgorithm::ChaCha, &seed_bytes);
    let mut runner = TestRunner::new_with_rng(Config::default(), rng);
    let strategy = random_contour();

    let (mut fitted, mut cubics, mut over) = (0usize, 0usize, 0usize);
    // (error / tolerance, contour index, point count)
    let mut worst = (0.0_f64, 0usize, 0usize);
    let mut ratios = Vec::with_capacity(contours);
    let mut index = 0;
    while fitted < contours {
        index += 1;
        let Ok(tree) = strategy.new_tree(&mut runner) else {
            continue;
        };
        // Fewer than three distinct points: the proptest rejects these too.
        let Some((spline, scale)) = tree.current() else {
            continue;
        };
        let tolerance = 0.5 * scale / 1000.0;
        let fit = fit_contour(&spline, tolerance);
        let ratio = hausdorff(&spline, &fit.path, 200) / tolerance;
        cubics += cubic_count(&fit.path);
        if ratio > 1.0 {
            over += 1;
            println!(
                "over: contour {index} ({} points) at {ratio:.4} of the tolerance",
                spline.segment_count()
            );
        }
        if ratio > worst.0 {
            worst = (ratio, index, spline.segment_count());
        }
        ratios.push(ratio);
        fitted += 1;
    }
    ratios.sort_by(f64::total_cmp);
    let quantile = |q: f64| ratios[((ratios.len() - 1) as f64 * q).round() as usize];
    println!("seed {seed}: {fitted} contours, {cubics} cubics");
    println!(
        "error / tolerance: median {:.3}, 99th percentile {:.3}, worst {:.4} (contour {}, {} points)",
        quantile(0.5),
        quantile(0.99),
        worst.0,
        worst.1,
        worst.2
    );
    println!("contours over the tolerance: {over}");
    if over > 0 {
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    }
}

/// `arg` as a number, `default` when absent; `None` when it is not a number.
fn parse<T: std::str::FromStr>(arg: Option<String>, default: T) -> Option<T> {
    match arg {
        None => Some(default),
        Some(text) => text.parse().ok(),
    }
}
