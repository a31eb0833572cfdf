//! Contour orientation for the nonzero fill rule. (Temporary placeholder.)

use kurbo::BezPath;

/// Orients closed contours: outer counter-clockwise (y up), counters clockwise.
pub fn orient_contours(contours: Vec<BezPath>) -> BezPath {
    let mut out = BezPath::new();
    for c in contours {
        out.extend(c);
    }
    out
}
