//! Fits every contour of a font folder once, on one thread, and prints the cubic count and
//! the largest measured error: the fitting of a `build` alone, as a fixed workload for
//! profilers (`perf`, `valgrind --tool=callgrind`) on real sources such as the CJK block of
//! `benches/cjk.sh`.
//!
//! Usage: `cargo run --release --example fit_font -- FONT_DIR [ROUNDS]` (default 1 round).
//! The tolerance is the font's own (`font.toml`).

use std::path::Path;

use kurbo::PathEl;
use xglyph::fit::fit_contour;

fn main() {
    let mut args = std::env::args().skip(1);
    let Some(dir) = args.next() else {
        eprintln!("usage: fit_font FONT_DIR [ROUNDS]");
        std::process::exit(2);
    };
    let rounds: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(1);
    let font = match xglyph::source::load_font(Path::new(&dir)) {
        Ok((font, _)) => font,
        Err(diagnostics) => {
            eprintln!("{dir}: {} errors; run `xglyph check`", diagnostics.len());
            std::process::exit(1);
        }
    };
    let tolerance = font.info.tolerance;
    let contours: Vec<_> = font.glyphs.iter().flat_map(|g| &g.contours).collect();
    let (mut cubics, mut lines, mut worst) = (0, 0, 0.0_f64);
    for _ in 0..rounds {
        (cubics, lines) = (0, 0);
        for contour in &contours {
            let fit = fit_contour(contour.spline(), tolerance);
            for el in fit.path.elements() {
                match el {
                    PathEl::CurveTo(..) => cubics += 1,
                    PathEl::LineTo(..) => lines += 1,
                    _ => {}
                }
            }
            worst = worst.max(fit.max_error);
        }
    }
    println!(
        "{} contours: {cubics} cubics, {lines} lines, largest measured error {worst:.4} of \
         tolerance {tolerance}",
        contours.len()
    );
}
