//! Compatible masters for the tests and benches of `xglyph::compatible`: a plausible bold
//! variant of any contour, and the X-spline blended at given weights.
// Each test crate uses a different subset.
#![allow(dead_code)]

use kurbo::Vec2;
use xglyph::xspline::{ControlPoint, XSpline};

/// A plausible bold master: every point moved `offset` units along its control polygon's
/// normal (the perpendicular of the chord between its neighbours), every `s` multiplied by
/// `s_scale` (sharp points stay sharp). `None` if the result is not a valid contour.
pub fn bold(spline: &XSpline, offset: f64, s_scale: f64) -> Option<XSpline> {
    let pts = spline.points();
    let n = pts.len();
    let moved = (0..n)
        .map(|k| {
            let chord = pts[(k + 1) % n].pos - pts[(k + n - 1) % n].pos;
            let len = chord.hypot();
            let normal = if len > 0.0 {
                Vec2::new(chord.y, -chord.x) / len
            } else {
                Vec2::ZERO
            };
            ControlPoint {
                pos: pts[k].pos + offset * normal,
                s: s_scale * pts[k].s,
            }
        })
        .collect();
    XSpline::new(moved).ok()
}

/// The X-spline blended at `weights` (x, y and s), `None` if it is not a valid contour.
pub fn blend(masters: &[&XSpline], weights: &[f64]) -> Option<XSpline> {
    let n = masters[0].points().len();
    let points = (0..n)
        .map(|k| {
            let mut p = ControlPoint::new(0.0, 0.0, 0.0);
            for (m, w) in masters.iter().zip(weights) {
                let q = m.points()[k];
                p.pos.x += w * q.pos.x;
                p.pos.y += w * q.pos.y;
                p.s += w * q.s;
            }
            p
        })
        .collect();
    XSpline::new(points).ok()
}

/// Two-master positions `[1 - t, t]` at `count` evenly spaced `t` from 0 to 1.
pub fn evenly_spaced(count: usize) -> Vec<Vec<f64>> {
    (0..count)
        .map(|k| {
            let t = k as f64 / (count - 1) as f64;
            vec![1.0 - t, t]
        })
        .collect()
}
