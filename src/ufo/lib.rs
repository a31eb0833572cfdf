//! xglyph's keys in UFO libs: the X-spline sources and the `font.toml` values that
//! `fontinfo.plist` cannot hold exactly.
//!
//! | lib   | key                      | value                                                |
//! |-------|--------------------------|------------------------------------------------------|
//! | glyph | `org.xglyph.xspline`     | the glyph's own contours: an array per contour of    |
//! |       |                          | `[x, y, s]` reals (font units, y up; `s` in -1..1)   |
//! | font  | `org.xglyph.tolerance`   | `font.toml`'s `tolerance` (real, font units)         |
//! | font  | `org.xglyph.version`     | `font.toml`'s `version` text, when it has one        |
//! | font  | `org.xglyph.kerningOrder`| the kerning pairs' source order: `[left, right]`s    |
//! | font  | `public.openTypeCategories` | only when a glyph has `mark = "outline"`: every  |
//! |       |                          | glyph but `.notdef` as xglyph's GDEF classes it,     |
//! |       |                          | "mark" or "base" ([`categories_value`])              |
//!
//! Reals are written in the shortest form that reads back to the same `f64`, so the data
//! round-trips exactly. The importer takes a glyph's `org.xglyph.xspline` instead of
//! fitting its outline; another editor that changes the outline but keeps the lib would
//! make the two disagree, so the importer checks that the lib's contour count matches the
//! outline's and refits otherwise.

use plist::Value;

use crate::model::{Contour, KernPair};
use crate::xspline::{ControlPoint, XSplineError};

/// Glyph lib key of the X-spline contours.
pub const XSPLINE_KEY: &str = "org.xglyph.xspline";
/// Font lib key of the build tolerance.
pub const TOLERANCE_KEY: &str = "org.xglyph.tolerance";
/// Font lib key of the version text.
pub const VERSION_KEY: &str = "org.xglyph.version";
/// Font lib key of the kerning pairs' order.
pub const KERNING_ORDER_KEY: &str = "org.xglyph.kerningOrder";
/// Font lib key of the glyphs' OpenType categories (the UFO spec's public key).
pub const CATEGORIES_KEY: &str = "public.openTypeCategories";

/// The value of [`CATEGORIES_KEY`] for `font`, when it has a mark placed by its outline
/// (`mark = "outline"`): no anchor shows a compiler that such a glyph is a mark, and
/// ufo2ft and fontc then take every GDEF class from this key, so every glyph but
/// `.notdef` is listed: "mark" as [`crate::model::classed_mark`] says, else "base".
/// `None` for any other font (its classes follow from its anchors). Limit: a ligature of
/// the font's own `features.fea` is listed as "base".
pub fn categories_value(font: &crate::outline::OutlinedFont) -> Option<Value> {
    if !font.glyphs.iter().any(|g| g.outline_mark) {
        return None;
    }
    let categories = font
        .glyphs
        .iter()
        .filter(|g| g.name != ".notdef")
        .map(|g| {
            let mark = crate::model::classed_mark(&g.unicodes, &g.anchors, g.outline_mark);
            let category = if mark { "mark" } else { "base" };
            (g.name.clone(), Value::String(category.into()))
        })
        .collect();
    Some(Value::Dictionary(categories))
}

/// The value of [`XSPLINE_KEY`] for these contours.
pub fn xspline_value<'a>(contours: impl IntoIterator<Item = &'a Contour>) -> Value {
    Value::Array(
        contours
            .into_iter()
            .map(|c| {
                Value::Array(
                    c.points()
                        .iter()
                        .map(|p| {
                            // `+ 0.0` turns -0 into 0, which prints as `0`.
                            Value::Array(vec![
                                Value::Real(p.pos.x + 0.0),
                                Value::Real(p.pos.y + 0.0),
                                Value::Real(p.s + 0.0),
                            ])
                        })
                        .collect(),
                )
            })
            .collect(),
    )
}

/// Why a lib value could not be read.
#[derive(Clone, Debug, PartialEq)]
pub enum LibError {
    /// The value does not have the documented shape; the text says where.
    Shape(String),
    /// A contour is not a valid X-spline.
    Contour {
        /// Index of the contour in the array.
        contour: usize,
        /// What is wrong with it.
        error: XSplineError,
    },
}

impl std::fmt::Display for LibError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            LibError::Shape(what) => write!(f, "{XSPLINE_KEY}: {what}"),
            LibError::Contour { contour, error } => {
                write!(f, "{XSPLINE_KEY}: contour {}: {error}", contour + 1)
            }
        }
    }
}

/// The contours of a [`XSPLINE_KEY`] value.
pub fn read_xspline(value: &Value) -> Result<Vec<Contour>, LibError> {
    let contours = value
        .as_array()
        .ok_or_else(|| LibError::Shape("expected an array of contours".into()))?;
    contours
        .iter()
        .enumerate()
        .map(|(ci, contour)| {
            let points = contour.as_array().ok_or_else(|| {
                LibError::Shape(format!("contour {}: expected an array of points", ci + 1))
            })?;
            let points = points
                .iter()
                .enumerate()
                .map(|(pi, p)| {
                    read_point(p).ok_or_else(|| {
                        LibError::Shape(format!(
                            "contour {}, point {}: expected [x, y, s] numbers",
                            ci + 1,
                            pi + 1
                        ))
                    })
                })
                .collect::<Result<Vec<_>, _>>()?;
            Contour::new(points).map_err(|error| LibError::Contour { contour: ci, error })
        })
        .collect()
}

fn read_point(value: &Value) -> Option<ControlPoint> {
    match value.as_array()?.as_slice() {
        [x, y, s] => Some(ControlPoint::new(number(x)?, number(y)?, number(s)?)),
        _ => None,
    }
}

/// A real or an integer as `f64` (other editors may rewrite `1.0` as `<integer>1`).
pub fn number(value: &Value) -> Option<f64> {
    let v = match value {
        Value::Real(r) => *r,
        Value::Integer(i) => i.as_signed().map(|v| v as f64)?,
        _ => return None,
    };
    v.is_finite().then_some(v)
}

/// The value of [`KERNING_ORDER_KEY`] for these pairs.
pub fn kerning_order_value(pairs: &[KernPair]) -> Value {
    Value::Array(
        pairs
            .iter()
            .map(|k| {
                Value::Array(vec![
                    Value::String(k.left.clone()),
                    Value::String(k.right.clone()),
                ])
            })
            .collect(),
    )
}

/// The `(left, right)` pairs of a [`KERNING_ORDER_KEY`] value; entries of another shape are
/// skipped (the order is a hint, the values come from `kerning.plist`).
pub fn read_kerning_order(value: &Value) -> Vec<(String, String)> {
    let Some(items) = value.as_array() else {
        return Vec::new();
    };
    items
        .iter()
        .filter_map(|item| match item.as_array()?.as_slice() {
            [Value::String(l), Value::String(r)] => Some((l.clone(), r.clone())),
            _ => None,
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn xspline_round_trip_is_exact() {
        let contour = Contour::new(vec![
            ControlPoint::new(0.1, -0.0, 0.0),
            ControlPoint::new(1.0 / 3.0, 200.0, -1.0),
            ControlPoint::new(300.25, 1e-7, 0.8),
        ])
        .expect("valid");
        let value = xspline_value([&contour]);
        let mut xml = Vec::new();
        value.to_writer_xml(&mut xml).expect("in memory");
        let text = String::from_utf8(xml).expect("utf-8");
        assert!(text.contains("<real>0.3333333333333333</real>"), "{text}");
        assert!(!text.contains("-0<"), "{text}");
        let back = Value::from_reader_xml(text.as_bytes()).expect("parses");
        let contours = read_xspline(&back).expect("reads");
        assert_eq!(contours[0].points()[1], contour.points()[1]);
        assert_eq!(contours[0].points()[2], contour.points()[2]);
        assert_eq!(contours[0].points()[0].pos.y.to_bits(), 0f64.to_bits());
    }

    #[test]
    fn bad_shapes_are_named() {
        let bad = Value::Array(vec![Value::Array(vec![Value::Array(vec![
            Value::Real(1.0),
            Value::String("y".into()),
            Value::Real(0.0),
        ])])]);
        assert_eq!(
            read_xspline(&bad).unwrap_err().to_string(),
            "org.xglyph.xspline: contour 1, point 1: expected [x, y, s] numbers"
        );
        let one_point = Value::Array(vec![Value::Array(vec![Value::Array(vec![
            Value::Integer(1.into()),
            Value::Integer(2.into()),
            Value::Real(0.0),
        ])])]);
        assert!(matches!(
            read_xspline(&one_point),
            Err(LibError::Contour { contour: 0, .. })
        ));
        assert_eq!(
            read_xspline(&Value::Boolean(true)).unwrap_err().to_string(),
            "org.xglyph.xspline: expected an array of contours"
        );
    }
}
