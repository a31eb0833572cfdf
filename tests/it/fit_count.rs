//! Segment counts against kurbo's near-optimal `fit_to_bezpath_opt` on the same curves.

use crate::common::corpus;
use crate::common::paths::cubic_count;

use kurbo::fit_to_bezpath_opt;
use xglyph::fit::{fit_contour, stretches, Stretch, StretchSource};

#[test]
/// Issue #2 asks for at most 1.10× kurbo's near-optimal fitter; measured 458 vs 440 (1.04×)
/// at 0.5 units, with our stricter two-sided acceptance.
fn segment_total_against_kurbo_opt() {
    let tolerance = 0.5;
    let (mut ours, mut reference) = (0, 0);
    for spline in corpus::corpus() {
        ours += cubic_count(&fit_contour(&spline, tolerance).path);
        for piece in stretches(&spline) {
            if let Stretch::Smooth { start, end } = piece {
                let source = StretchSource {
                    spline: &spline,
                    start,
                    end,
                };
                reference += cubic_count(&fit_to_bezpath_opt(&source, tolerance));
            }
        }
    }
    println!("cubic segments: xglyph {ours}, kurbo fit_to_bezpath_opt {reference}");
    assert!(reference > 100, "corpus too small: {reference}");
    assert!(
        ours as f64 <= 1.10 * reference as f64,
        "xglyph {ours} vs kurbo opt {reference}"
    );
}
