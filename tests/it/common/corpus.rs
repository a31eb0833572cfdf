//! A fixed corpus of closed X-splines for comparing fitters: glyph-like contours plus
//! deterministic random ones (shared by `tests/it/fit_count.rs`, `benches/core.rs` and
//! `benches/fig2dev.rs`).

use xglyph::xspline::{ControlPoint, XSpline};

/// A tiny deterministic generator (xorshift64*), so the corpus is the same everywhere.
pub struct Rng(pub u64);

impl Rng {
    /// The next number in [0, 1).
    pub fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn contour(points: &[(f64, f64, f64)]) -> XSpline {
    XSpline::new(
        points
            .iter()
            .map(|&(x, y, s)| ControlPoint::new(x, y, s))
            .collect(),
    )
    .expect("corpus contours are valid")
}

/// Glyph-like contours (font units, 1000 per em) and 40 random star-shaped ones.
pub fn corpus() -> Vec<XSpline> {
    let mut out = vec![
        // o: outer and counter, interpolating extremes.
        contour(&[
            (280.0, -12.0, -1.0),
            (520.0, 250.0, -1.0),
            (280.0, 512.0, -1.0),
            (40.0, 250.0, -1.0),
        ]),
        contour(&[
            (280.0, 78.0, -1.0),
            (130.0, 250.0, -1.0),
            (280.0, 422.0, -1.0),
            (430.0, 250.0, -1.0),
        ]),
        // D: stem corners and a bowl.
        contour(&[
            (80.0, 0.0, 0.0),
            (330.0, 0.0, -1.0),
            (600.0, 350.0, -1.0),
            (330.0, 700.0, -1.0),
            (80.0, 700.0, 0.0),
        ]),
        // S-like spine with approximating points.
        contour(&[
            (60.0, 80.0, 0.0),
            (300.0, -20.0, 1.0),
            (520.0, 180.0, 0.6),
            (140.0, 420.0, 0.8),
            (330.0, 640.0, 1.0),
            (500.0, 600.0, 0.0),
            (480.0, 690.0, 0.0),
            (150.0, 720.0, 1.0),
            (30.0, 480.0, 0.7),
            (420.0, 260.0, 0.9),
            (230.0, 60.0, 1.0),
            (70.0, 170.0, 0.0),
        ]),
        // A soft-cornered square, mixed shapes.
        contour(&[
            (0.0, 0.0, 0.5),
            (700.0, 0.0, -0.5),
            (700.0, 700.0, 1.0),
            (0.0, 700.0, -1.0),
        ]),
    ];
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    let shapes = [-1.0, -0.5, 0.0, 0.5, 1.0];
    for _ in 0..40 {
        let n = 4 + (rng.next() * 10.0) as usize;
        let pts: Vec<(f64, f64, f64)> = (0..n)
            .map(|i| {
                let angle = std::f64::consts::TAU * (i as f64 + 0.8 * rng.next()) / n as f64;
                let radius = 150.0 + 350.0 * rng.next();
                let s = if rng.next() < 0.5 {
                    shapes[(rng.next() * 5.0) as usize % 5]
                } else {
                    2.0 * rng.next() - 1.0
                };
                (
                    500.0 + radius * angle.cos(),
                    350.0 + radius * angle.sin(),
                    s,
                )
            })
            .collect();
        out.push(contour(&pts));
    }
    out
}
