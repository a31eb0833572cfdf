//! Fits the benchmark corpus (`tests/it/common/corpus.rs`) and prints the cubic count and
//! the largest measured error: a fixed workload for profilers, whose instruction counts
//! do not depend on the machine's load (`valgrind --tool=callgrind`).
//!
//! Usage: `cargo run --release --example fit_corpus -- [ROUNDS]` (default 1).

use xglyph::fit::fit_contour;

#[path = "../tests/it/common/corpus.rs"]
mod corpus;
#[path = "../tests/it/common/paths.rs"]
mod paths;

use paths::cubic_count;

/// The bench's tolerance, in font units (1000 per em).
const TOLERANCE: f64 = 0.5;

fn main() {
    let rounds: usize = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(1);
    let splines = corpus::corpus();
    let (mut cubics, mut worst) = (0, 0.0_f64);
    for _ in 0..rounds {
        cubics = 0;
        for spline in &splines {
            let fit = fit_contour(spline, TOLERANCE);
            cubics += cubic_count(&fit.path);
            worst = worst.max(fit.max_error);
        }
    }
    println!("cubics {cubics}, largest measured error {worst:.4} of tolerance {TOLERANCE}");
}
