//! X-spline -> cubic Béziers within a tolerance. (Temporary polyline placeholder.)

use kurbo::BezPath;

use crate::xspline::XSpline;

/// A fitted closed contour.
#[derive(Clone, Debug)]
pub struct ContourFit {
    pub path: BezPath,
    pub max_error: f64,
}

/// Fits one closed X-spline.
pub fn fit_contour(spline: &XSpline, _tolerance: f64) -> ContourFit {
    let mut path = BezPath::new();
    let n = spline.segment_count();
    path.move_to(spline.eval(0.0));
    for i in 1..n * 16 {
        path.line_to(spline.eval(i as f64 / 16.0));
    }
    path.close_path();
    ContourFit {
        path,
        max_error: 0.0,
    }
}
