//! Compatible import: one glyph's Bézier outlines in several masters -> X-spline masters
//! with one structure.
//!
//! ```text
//! contour::compatible_contours (one cleaning for all masters)
//!   -> contour::cut_at the masters' joint break points (a corner in one master is a
//!      corner in all, as `check` demands)
//!   -> fit::fit_compatible (one point count per stretch, each master's positions fitted
//!      to its own outline)
//!   -> rounded alike, and measured: every master against its own outline, and every
//!      checkpoint (a position between masters) against the original there
//! ```
//!
//! Candidates are tried as in [`super::import_glyph`] (the first target, then tighter
//! ones); the last resort is [`fit::compatible_polylines`], whose blends are within the
//! bound of the blended originals wherever the originals interpolate linearly (a gvar
//! without intermediate regions, UFO masters). Limits: a checkpoint measures one position,
//! not the whole segment of the axis; a font whose outlines do not interpolate linearly
//! between the masters taken (intermediate gvar regions) can miss between them, and the
//! report then shows the error.

use kurbo::{BezPath, ParamCurve, PathSeg, Point};

use super::contour::{self, SourceContour};
use super::fit;
use super::report::GlyphReport;
use super::{first_target, round_to, FittedGlyph, SourceGlyph, IMPORT_SHARE, RETRY_SHARES};
use crate::family::{describe, meeting_points};
use crate::model::{Contour, Family, Glyph};
use crate::xspline::{ControlPoint, XSpline};

/// A position between masters where the import is measured too: the masters' blend
/// weights (summing to 1) and, when known, the original outline there (a variable font's
/// own outline at that position). Without one, the masters' outlines are blended.
#[derive(Clone, Debug)]
pub struct Checkpoint {
    /// One weight per master, in master order.
    pub weights: Vec<f64>,
    /// The original outline at this position, if the input has it.
    pub original: Option<BezPath>,
}

impl Checkpoint {
    /// The blend halfway between the default (master 0) and each other master of `count`,
    /// measured against the same blend of the masters' outlines.
    pub fn halfways(count: usize) -> Vec<Checkpoint> {
        (1..count)
            .map(|k| {
                let mut weights = vec![0.0; count];
                weights[0] = 0.5;
                weights[k] = 0.5;
                Checkpoint {
                    weights,
                    original: None,
                }
            })
            .collect()
    }
}

/// Imports one glyph given in every master (the default first): the fitted glyph and its
/// report row per master. The default's row also counts the checkpoints' errors. `Err`
/// when the masters' outlines do not have one structure (they do not interpolate).
pub fn import_compatible_glyph(
    masters: &[SourceGlyph],
    checkpoints: &[Checkpoint],
    tolerance: f64,
    grid: f64,
) -> Result<Vec<FittedGlyph>, String> {
    let name = &masters[0].name;
    let mut paths: Vec<&BezPath> = masters.iter().map(|g| &g.path).collect();
    paths.extend(checkpoints.iter().filter_map(|c| c.original.as_ref()));
    let all = contour::compatible_contours(&paths, 0.1 * tolerance)
        .map_err(|m| format!("glyph `{name}`: the masters' outlines differ: {m}"))?;
    let (own, given) = all.split_at(masters.len());
    let mut rows: Vec<GlyphReport> = masters
        .iter()
        .map(|g| GlyphReport {
            name: g.name.clone(),
            original_points: 0,
            xspline_points: 0,
            max_error: 0.0,
            dropped_contours: 0,
        })
        .collect();
    let mut contours: Vec<Vec<Contour>> = vec![Vec::new(); masters.len()];
    for c in 0..own[0].len() {
        let originals: Vec<&SourceContour> = own.iter().map(|m| &m[c]).collect();
        // The originals at the checkpoints: given, else blended from the masters'.
        let mut given = given.iter();
        let between: Vec<(Vec<f64>, Vec<PathSeg>)> = checkpoints
            .iter()
            .map(|cp| {
                let segs = match cp.original {
                    Some(_) => given.next().map_or_else(Vec::new, |m| m[c].segs.clone()),
                    None => blend_segments(&originals, &cp.weights),
                };
                (cp.weights.clone(), segs)
            })
            .collect();
        for (row, o) in rows.iter_mut().zip(&originals) {
            row.original_points += contour::stored_points(&o.segs);
        }
        match import_contour(&originals, &between, tolerance, grid) {
            Some(result) => {
                for (k, spline) in result.splines.into_iter().enumerate() {
                    rows[k].xspline_points += spline.points().len();
                    rows[k].max_error = rows[k].max_error.max(result.errors[k]);
                    contours[k].push(Contour::from(spline));
                }
                rows[0].max_error = rows[0].max_error.max(result.between_error);
            }
            None => rows.iter_mut().for_each(|r| r.dropped_contours += 1),
        }
    }
    Ok(masters
        .iter()
        .zip(contours)
        .zip(rows)
        .map(|((g, contours), report)| FittedGlyph {
            glyph: Glyph {
                name: g.name.clone(),
                unicodes: g.unicodes.clone(),
                advance: round_to(g.advance, grid),
                contours,
                components: Vec::new(),
                anchors: Vec::new(),
                outline_mark: false,
            },
            report,
        })
        .collect())
}

/// One contour fitted in every master, rounded, and its measured errors.
struct Compatible {
    splines: Vec<XSpline>,
    /// Per master, against its own original.
    errors: Vec<f64>,
    /// The largest at the checkpoints.
    between_error: f64,
}

/// The first candidate whose every master and checkpoint measures within
/// `IMPORT_SHARE · tolerance`: compatible fits at the import's targets, cut at the joint
/// break points ([`contour::compatible_breaks`]), then at every master's corners, then
/// compatible polylines (taken even when a checkpoint misses: the report shows it). `None` when the
/// contour encloses nothing in some master.
fn import_contour(
    originals: &[&SourceContour],
    between: &[(Vec<f64>, Vec<PathSeg>)],
    tolerance: f64,
    grid: f64,
) -> Option<Compatible> {
    let bound = IMPORT_SHARE * tolerance;
    let measure = |points: &[Vec<ControlPoint>], strict: bool| {
        [grid, grid / 100.0].iter().find_map(|&g| {
            let points = points
                .iter()
                .map(|p| rounded(p, g))
                .collect::<Option<Vec<_>>>()?;
            let splines = without_meeting_points(&points, 0.5 * g)
                .into_iter()
                .map(valid)
                .collect::<Option<Vec<_>>>()?;
            let errors: Vec<f64> = splines
                .iter()
                .zip(originals)
                .map(|(s, o)| fit::contour_error(s, &o.segs))
                .collect();
            if strict && errors.iter().any(|&e| e > bound) {
                return None;
            }
            let between_error = between
                .iter()
                .map(|(weights, segs)| match blend_splines(&splines, weights) {
                    Some(s) if !segs.is_empty() => fit::contour_error(&s, segs),
                    _ => f64::INFINITY,
                })
                .fold(0.0, f64::max);
            (!strict || between_error <= bound).then_some(Compatible {
                splines,
                errors,
                between_error,
            })
        })
    };
    let weights: Vec<Vec<f64>> = between.iter().map(|(w, _)| w.clone()).collect();
    for every_corner in [false, true] {
        let breaks = contour::compatible_breaks(originals, every_corner);
        let cuts: Vec<contour::Cut> = originals
            .iter()
            .map(|o| contour::cut_at(o, &breaks))
            .collect();
        let targets = std::iter::once(first_target(tolerance, grid))
            .chain(RETRY_SHARES.iter().map(|share| share * tolerance));
        for target in targets {
            if let Some(fitted) = fit::fit_compatible(&cuts, target, &weights) {
                let points: Vec<Vec<ControlPoint>> = fitted.into_iter().map(|f| f.points).collect();
                if let Some(found) = measure(&points, true) {
                    return Some(found);
                }
            }
        }
    }
    let segs: Vec<&[PathSeg]> = originals.iter().map(|o| o.segs.as_slice()).collect();
    measure(&fit::compatible_polylines(&segs, 0.5 * bound), false)
}

/// Rounds positions to `grid`: unlike the single-master rounding, no point is dropped (the
/// masters must keep one structure). A point on its predecessor (an edge that one master
/// collapses to nothing, as the Bold `six` of the bundled family does) moves one grid step
/// toward the next distinct point; the caller measures the result.
fn rounded(points: &[ControlPoint], grid: f64) -> Option<Vec<ControlPoint>> {
    let mut out: Vec<ControlPoint> = points
        .iter()
        .map(|p| ControlPoint::new(round_to(p.pos.x, grid), round_to(p.pos.y, grid), p.s))
        .collect();
    let n = out.len();
    for i in 0..n {
        let j = (i + 1) % n;
        if out[i].pos != out[j].pos {
            continue;
        }
        let next = (1..n)
            .map(|k| out[(j + k) % n].pos)
            .find(|&p| p != out[j].pos)?;
        let step = (next - out[j].pos).normalize() * grid;
        let moved = out[j].pos + step;
        out[j].pos = Point::new(round_to(moved.x, grid), round_to(moved.y, grid));
    }
    Some(out)
}

/// The X-spline of `points`, if valid and enclosing some area (else the caller tries a
/// finer grid).
fn valid(points: Vec<ControlPoint>) -> Option<XSpline> {
    XSpline::new(points)
        .ok()
        .filter(|spline| crate::source::no_area(spline).is_none())
}

/// `masters` (one point list each, one structure) without the points that meet their
/// predecessor somewhere between two masters: where the edge between two points runs one
/// way in one master and back the other way in another, some blend folds it to nothing
/// (or to less than `near`), and an X-spline cannot have two points at one place. The
/// later point of such a pair goes in every master (the earlier one when only the later is
/// sharp); the caller measures the result. A degenerate original (a TrueType corner whose
/// off-curve points sit on it in one master) rounds to such a fold: two points on the
/// corner there, the second moved a grid step on by [`rounded`], run back against the
/// other master's.
fn without_meeting_points(masters: &[Vec<ControlPoint>], near: f64) -> Vec<Vec<ControlPoint>> {
    let mut out = masters.to_vec();
    let folds = |out: &[Vec<ControlPoint>], i: usize, j: usize| {
        let d: Vec<kurbo::Vec2> = out.iter().map(|m| m[j].pos - m[i].pos).collect();
        d.iter().enumerate().any(|(a, da)| {
            d[a + 1..].iter().any(|db| {
                // The blends (1 - w) da + w db pass closest to zero at w.
                let along = *db - *da;
                let w = (-da.dot(along) / along.hypot2().max(f64::MIN_POSITIVE)).clamp(0.0, 1.0);
                da.dot(*db) < 0.0 && (*da + along * w).hypot() < near
            })
        })
    };
    let mut i = 0;
    while out[0].len() > 3 && i < out[0].len() {
        let j = (i + 1) % out[0].len();
        if folds(&out, i, j) {
            let drop = if out[0][j].is_sharp() && !out[0][i].is_sharp() {
                i
            } else {
                j
            };
            for m in &mut out {
                m.remove(drop);
            }
            i = i.saturating_sub(1);
        } else {
            i += 1;
        }
    }
    out
}

/// Most rounds of [`part_meeting_points`] (each removes one point per contour).
const PARTING_ROUNDS: usize = 64;

/// Removes, in every master, each point that lands on its neighbour at a position the
/// build checks ([`meeting_points`]), and says so in one note per point. The pairwise
/// check of `without_meeting_points` sees a fold between two masters; this one sees the
/// blends of several axes at once, where the deltas of several masters add up (a corner of
/// four axes, some weights negative). The later point goes (the earlier one when only the
/// later is sharp), as there; the other one when that would leave two points of a master on
/// one place. Limits: the glyph's reported error was measured before the
/// removal, as its note says; `Err` names a contour that a removal would leave invalid.
pub fn part_meeting_points(family: &mut Family) -> Result<Vec<String>, String> {
    let mut notes = Vec::new();
    for _ in 0..PARTING_ROUNDS {
        let found = meeting_points(family).map_err(|e| format!("{e:?}"))?;
        if found.is_empty() {
            return Ok(notes);
        }
        for m in found {
            let name = family.default.glyphs[m.glyph].name.clone();
            let points = family.default.glyphs[m.glyph].contours[m.contour].points();
            let first = if points[m.next].is_sharp() && !points[m.index].is_sharp() {
                m.index
            } else {
                m.next
            };
            // The other point goes when the first would leave a master invalid.
            let mut tried = Vec::new();
            let mut parted = None;
            for drop in [first, m.index + m.next - first] {
                match without_point(family, m.glyph, m.contour, drop) {
                    Ok(contours) => {
                        parted = Some((drop, contours));
                        break;
                    }
                    Err(e) => tried.push(format!("without point {drop}: {e}")),
                }
            }
            let Some((drop, contours)) = parted else {
                return Err(format!(
                    "glyph `{name}`, contour {}: points {} and {} meet at {}; {}",
                    m.contour,
                    m.index,
                    m.next,
                    describe(&family.designspace, &m.at),
                    tried.join("; ")
                ));
            };
            let glyphs = std::iter::once(&mut family.default.glyphs[m.glyph]).chain(
                family
                    .masters
                    .iter_mut()
                    .filter_map(|master| master.glyphs.get_mut(m.glyph)),
            );
            // The same glyphs, in the same order, as `without_point` took.
            let slots = glyphs.filter_map(|g| g.contours.get_mut(m.contour));
            for (slot, contour) in slots.zip(contours) {
                *slot = contour;
            }
            notes.push(format!(
                "glyph `{name}`, contour {}: point {drop} removed in every master, as points {} \
                 and {} met at {} (its error was measured before)",
                m.contour,
                m.index,
                m.next,
                describe(&family.designspace, &m.at)
            ));
        }
    }
    Err(format!(
        "points still meet between the masters after {PARTING_ROUNDS} removals per contour"
    ))
}

/// Contour `contour` of glyph `glyph` without point `drop`, in the default and then in
/// every master, or why one of them would be no X-spline.
fn without_point(
    family: &Family,
    glyph: usize,
    contour: usize,
    drop: usize,
) -> Result<Vec<Contour>, crate::xspline::XSplineError> {
    std::iter::once(&family.default.glyphs[glyph])
        .chain(family.masters.iter().filter_map(|m| m.glyphs.get(glyph)))
        .filter_map(|g| g.contours.get(contour))
        .map(|c| {
            let mut points = c.points().to_vec();
            if drop < points.len() {
                points.remove(drop);
            }
            Contour::new(points)
        })
        .collect()
}

/// The X-spline at a position between masters: positions and shapes blended by `weights`.
pub fn blend_splines(splines: &[XSpline], weights: &[f64]) -> Option<XSpline> {
    let n = splines[0].points().len();
    let points = (0..n)
        .map(|i| {
            let (mut x, mut y, mut s) = (0.0, 0.0, 0.0);
            for (spline, w) in splines.iter().zip(weights) {
                let p = spline.points().get(i)?;
                x += w * p.pos.x;
                y += w * p.pos.y;
                s += w * p.s;
            }
            Some(ControlPoint::blended(x, y, s))
        })
        .collect::<Option<Vec<_>>>()?;
    XSpline::new(points).ok()
}

/// One contour of several masters (one structure) blended by `weights`, as Bézier masters
/// interpolate: every control point.
fn blend_segments(masters: &[&SourceContour], weights: &[f64]) -> Vec<PathSeg> {
    let mix = |f: &dyn Fn(&SourceContour) -> Point| -> Point {
        masters
            .iter()
            .zip(weights)
            .fold(Point::ZERO, |acc, (m, w)| acc + *w * f(m).to_vec2())
    };
    (0..masters[0].segs.len())
        .map(|i| match masters[0].segs[i] {
            PathSeg::Line(_) => PathSeg::Line(kurbo::Line::new(
                mix(&|m| m.segs[i].start()),
                mix(&|m| m.segs[i].end()),
            )),
            PathSeg::Quad(_) => PathSeg::Quad(kurbo::QuadBez::new(
                mix(&|m| m.segs[i].start()),
                mix(&|m| match m.segs[i] {
                    PathSeg::Quad(q) => q.p1,
                    other => other.start(),
                }),
                mix(&|m| m.segs[i].end()),
            )),
            PathSeg::Cubic(_) => PathSeg::Cubic(kurbo::CubicBez::new(
                mix(&|m| m.segs[i].start()),
                mix(&|m| match m.segs[i] {
                    PathSeg::Cubic(c) => c.p1,
                    other => other.start(),
                }),
                mix(&|m| match m.segs[i] {
                    PathSeg::Cubic(c) => c.p2,
                    other => other.end(),
                }),
                mix(&|m| m.segs[i].end()),
            )),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn points_that_meet_between_the_masters_go_in_every_master() {
        // A TrueType corner whose off-curve points sit on it in the Bold: rounded, the
        // edge from point 2 to 3 runs up 0.2 in the Regular and down 0.1 in the Bold, so a
        // blend two thirds of the way folds it to nothing.
        let p = |x: f64, y: f64, s: f64| ControlPoint::new(x, y, s);
        let regular = vec![
            p(128.0, 305.0, 0.0),
            p(417.0, 305.0, 0.0),
            p(417.0, 306.3, 1.0),
            p(417.0, 306.5, 0.0),
            p(417.0, 333.0, 0.0),
            p(300.0, 450.0, 1.0),
        ];
        let bold = vec![
            p(183.0, 300.0, 0.0),
            p(434.0, 300.0, 0.0),
            p(434.0, 300.1, 1.0),
            p(434.0, 300.0, 0.0),
            p(434.0, 317.0, 0.0),
            p(320.0, 430.0, 1.0),
        ];
        let masters = vec![regular.clone(), bold.clone()];
        assert!(blend_splines(
            &masters
                .iter()
                .map(|m| XSpline::new(m.clone()).unwrap())
                .collect::<Vec<_>>(),
            &[1.0 / 3.0, 2.0 / 3.0]
        )
        .is_none());
        let kept = without_meeting_points(&masters, 0.05);
        // Point 3 is sharp and point 2 is not: point 2 goes, in both masters.
        let mut want = (regular, bold);
        want.0.remove(2);
        want.1.remove(2);
        assert_eq!(kept, vec![want.0, want.1]);
        // Edges that only shrink, or keep their direction, stay.
        assert_eq!(without_meeting_points(&kept, 0.05), kept);
    }
    use kurbo::{RoundedRect, Shape};

    fn source(path: BezPath) -> SourceGlyph {
        SourceGlyph {
            name: "o".into(),
            unicodes: vec!['o'],
            advance: 600.0,
            path,
        }
    }

    #[test]
    fn two_masters_get_one_structure_and_their_blend_follows_the_originals() {
        // A light and a heavy rounded rectangle: the same Bézier structure (one cubic per
        // corner at kurbo's coarsest accuracy), other radii.
        let light = RoundedRect::new(100.0, 0.0, 500.0, 700.0, 120.0).to_path(1e3);
        let heavy = RoundedRect::new(60.0, -10.0, 560.0, 710.0, 220.0).to_path(1e3);
        let halfway = RoundedRect::new(80.0, -5.0, 530.0, 705.0, 170.0).to_path(1e3);
        let checkpoint = Checkpoint {
            weights: vec![0.5, 0.5],
            original: None,
        };
        let fitted = import_compatible_glyph(
            &[source(light.clone()), source(heavy.clone())],
            &[checkpoint],
            1.0,
            0.1,
        )
        .unwrap();
        let shape = |g: &Glyph| -> Vec<Vec<bool>> {
            g.contours
                .iter()
                .map(|c| c.points().iter().map(|p| p.is_sharp()).collect())
                .collect()
        };
        assert_eq!(shape(&fitted[0].glyph), shape(&fitted[1].glyph));
        // Four straight edges: eight sharp points, and curves between them.
        assert_eq!(shape(&fitted[0].glyph)[0].iter().filter(|&&s| s).count(), 8);
        for (f, original) in fitted.iter().zip([&light, &heavy]) {
            let spline = f.glyph.contours[0].spline();
            let error = fit::contour_error(spline, &contour::contours(original)[0].segs);
            assert!(error <= 0.75 && f.report.max_error <= 0.75, "{error}");
        }
        let splines: Vec<XSpline> = fitted
            .iter()
            .map(|f| f.glyph.contours[0].spline().clone())
            .collect();
        let blend = blend_splines(&splines, &[0.5, 0.5]).unwrap();
        let error = fit::contour_error(&blend, &contour::contours(&halfway)[0].segs);
        assert!(error <= 0.75, "halfway: {error}");
    }

    #[test]
    fn masters_of_other_structures_are_an_error() {
        let square = kurbo::Rect::new(0.0, 0.0, 100.0, 100.0).to_path(1e-9);
        let circle = kurbo::Circle::new((50.0, 50.0), 50.0).to_path(1e3);
        let err =
            import_compatible_glyph(&[source(square), source(circle)], &[], 1.0, 0.1).unwrap_err();
        assert_eq!(
            err,
            "glyph `o`: the masters' outlines differ: contour 0: master 1 has other segments \
             than the default (CCCC against LLLL)"
        );
    }

    #[test]
    fn compatible_polylines_blend_within_their_tolerance() {
        let a = [PathSeg::Quad(kurbo::QuadBez::new(
            (0.0, 0.0),
            (100.0, 200.0),
            (200.0, 0.0),
        ))];
        let b = [PathSeg::Quad(kurbo::QuadBez::new(
            (0.0, 0.0),
            (150.0, 400.0),
            (260.0, 10.0),
        ))];
        let lines = fit::compatible_polylines(&[&a, &b], 0.5);
        assert_eq!(lines[0].len(), lines[1].len());
        let w = 0.3;
        let blend = |p: Point, q: Point| p.lerp(q, w);
        let curve = kurbo::QuadBez::new(
            blend(Point::new(0.0, 0.0), Point::new(0.0, 0.0)),
            blend(Point::new(100.0, 200.0), Point::new(150.0, 400.0)),
            blend(Point::new(200.0, 0.0), Point::new(260.0, 10.0)),
        );
        let steps = lines[0].len();
        // The blended chord from vertex k to k + 1 against the blended curve there.
        for k in 0..steps {
            let (p, q) = (
                blend(lines[0][k].pos, lines[1][k].pos),
                if k + 1 < steps {
                    blend(lines[0][k + 1].pos, lines[1][k + 1].pos)
                } else {
                    curve.p2
                },
            );
            for j in 0..=8 {
                let u = j as f64 / 8.0;
                let t = (k as f64 + u) / steps as f64;
                let d = (p.lerp(q, u) - curve.eval(t)).hypot();
                assert!(d <= 0.5, "vertex {k}, u {u}: {d}");
            }
        }
    }
}
