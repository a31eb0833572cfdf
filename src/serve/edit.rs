//! Edits of a glyph file's text that keep every byte they do not change.
//!
//! The text is parsed with spans (`toml`'s `DeTable`, as the loader does); an op replaces
//! only the number literals whose value changes, an insert or delete touches only that
//! array element and one separator (copied from its neighbours, so the file's layout
//! stays). Numbers are written as `fmt` writes them ([`crate::source::emit::number`]).
//! The result is not validated here: the caller loads it through the normal loader.

use std::ops::Range;

use serde::Deserialize;
use toml::de::{DeTable, DeValue};
use toml::Spanned;

use crate::source::emit::number;

/// One edit, as the API takes it (`{"op": "move", ...}`).
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(tag = "op", rename_all = "lowercase", deny_unknown_fields)]
pub enum Op {
    /// Moves a point to `(x, y)`.
    Move {
        /// Contour index in the glyph file.
        contour: usize,
        /// Point index in the contour.
        point: usize,
        /// New x, font units.
        x: f64,
        /// New y, font units.
        y: f64,
    },
    /// Sets the shape parameter of a point.
    Shape {
        /// Contour index in the glyph file.
        contour: usize,
        /// Point index in the contour.
        point: usize,
        /// New shape parameter (the loader checks `[-1, 1]`).
        s: f64,
    },
    /// Inserts a point so that it gets index `index` (the contour's length appends).
    Insert {
        /// Contour index in the glyph file.
        contour: usize,
        /// Index the new point gets.
        index: usize,
        /// `[x, y, s]`.
        point: [f64; 3],
    },
    /// Deletes a point.
    Delete {
        /// Contour index in the glyph file.
        contour: usize,
        /// Point index in the contour.
        point: usize,
    },
    /// Sets the advance.
    Advance {
        /// New advance, font units.
        value: f64,
    },
}

/// Why an op cannot be applied to the text.
#[derive(Clone, Debug, PartialEq)]
pub enum EditError {
    /// A contour or point index outside the glyph (HTTP 400).
    OutOfRange(String),
    /// The file does not have the shape an edit needs (not TOML, points not an array...);
    /// the loader would report it (HTTP 422).
    Unreadable(String),
}

impl std::fmt::Display for EditError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            EditError::OutOfRange(m) | EditError::Unreadable(m) => f.write_str(m),
        }
    }
}

/// Applies `ops` in order to `text`; every op sees the result of the ones before it.
pub fn apply(text: &str, ops: &[Op]) -> Result<String, EditError> {
    let mut text = text.to_string();
    for op in ops {
        for (range, replacement) in splices(&text, op)?.into_iter().rev() {
            text.replace_range(range, &replacement);
        }
    }
    Ok(text)
}

/// The replacements (byte range, new text) that perform `op` on `text`, in text order;
/// none when nothing changes.
fn splices(text: &str, op: &Op) -> Result<Vec<(Range<usize>, String)>, EditError> {
    let doc = DeTable::parse(text)
        .map_err(|e| EditError::Unreadable(format!("invalid TOML: {}", e.message().trim())))?;
    let table = doc.get_ref();
    match *op {
        Op::Advance { value } => {
            let v = get(table, "advance")
                .ok_or_else(|| EditError::Unreadable("the file has no `advance`".into()))?;
            Ok(replace_number(v, value))
        }
        Op::Move {
            contour,
            point,
            x,
            y,
        } => {
            let p = coordinates(points(table, contour)?, contour, point)?;
            let mut out = replace_number(&p[0], x);
            out.extend(replace_number(&p[1], y));
            Ok(out)
        }
        Op::Shape { contour, point, s } => {
            let p = coordinates(points(table, contour)?, contour, point)?;
            Ok(replace_number(&p[2], s))
        }
        Op::Insert {
            contour,
            index,
            point,
        } => {
            let items = points(table, contour)?;
            if index > items.len() {
                return Err(EditError::OutOfRange(format!(
                    "insert index {index} is out of range: contour {contour} has {} points",
                    items.len()
                )));
            }
            let new = format!(
                "[{}, {}, {}]",
                number(point[0]),
                number(point[1]),
                number(point[2])
            );
            let sep = separator(text, items, index);
            if index < items.len() {
                let at = items[index].span().start;
                Ok(vec![(at..at, format!("{new}{sep}"))])
            } else if let Some(last) = items.last() {
                let at = last.span().end;
                Ok(vec![(at..at, format!("{sep}{new}"))])
            } else {
                Err(EditError::Unreadable(format!(
                    "contour {contour} has no points to insert between"
                )))
            }
        }
        Op::Delete { contour, point } => {
            let items = points(table, contour)?;
            if point >= items.len() {
                return Err(out_of_range(contour, point, items.len()));
            }
            let range = if point + 1 < items.len() {
                items[point].span().start..items[point + 1].span().start
            } else if point > 0 {
                items[point - 1].span().end..items[point].span().end
            } else {
                items[point].span()
            };
            Ok(vec![(range, String::new())])
        }
    }
}

fn get<'t, 'i>(table: &'t DeTable<'i>, key: &str) -> Option<&'t Spanned<DeValue<'i>>> {
    table
        .iter()
        .find(|(k, _)| k.get_ref() == key)
        .map(|(_, v)| v)
}

/// The point elements of contour `contour`.
fn points<'t, 'i>(
    table: &'t DeTable<'i>,
    contour: usize,
) -> Result<&'t [Spanned<DeValue<'i>>], EditError> {
    let contours = match get(table, "contour").map(Spanned::get_ref) {
        Some(DeValue::Array(a)) => &a[..],
        _ => &[],
    };
    let c = contours.get(contour).ok_or_else(|| {
        EditError::OutOfRange(format!(
            "contour {contour} is out of range: the glyph has {} contours",
            contours.len()
        ))
    })?;
    let DeValue::Table(t) = c.get_ref() else {
        return Err(EditError::Unreadable(format!(
            "contour {contour} is not a table"
        )));
    };
    match get(t, "points").map(Spanned::get_ref) {
        Some(DeValue::Array(a)) => Ok(&a[..]),
        _ => Err(EditError::Unreadable(format!(
            "contour {contour} has no `points` array"
        ))),
    }
}

/// The `[x, y, s]` values of point `point`.
fn coordinates<'t, 'i>(
    items: &'t [Spanned<DeValue<'i>>],
    contour: usize,
    point: usize,
) -> Result<&'t [Spanned<DeValue<'i>>], EditError> {
    let item = items
        .get(point)
        .ok_or_else(|| out_of_range(contour, point, items.len()))?;
    match item.get_ref() {
        DeValue::Array(a) if a.len() == 3 => Ok(&a[..]),
        _ => Err(EditError::Unreadable(format!(
            "point {point} is not an [x, y, s] array"
        ))),
    }
}

fn out_of_range(contour: usize, point: usize, len: usize) -> EditError {
    EditError::OutOfRange(format!(
        "point {point} is out of range: contour {contour} has {len} points"
    ))
}

/// What goes between two points: `", "` on one line, or a comma, a line break and the
/// indentation of the points when they are one per line (comments are not copied).
fn separator(text: &str, items: &[Spanned<DeValue<'_>>], index: usize) -> String {
    let k = index.min(items.len().saturating_sub(1)).max(1);
    let (Some(a), Some(b)) = (items.get(k - 1), items.get(k)) else {
        return ", ".to_string();
    };
    let start = b.span().start;
    if !text[a.span().end..start].contains('\n') {
        return ", ".to_string();
    }
    let line_start = text[..start].rfind('\n').map_or(0, |i| i + 1);
    let indent = &text[line_start..start];
    let indent: String = indent.chars().filter(|c| c.is_whitespace()).collect();
    format!(",\n{indent}")
}

/// Replaces a number literal by `value`, or nothing when the literal already reads as
/// `value` (so `1.50` stays `1.50`).
fn replace_number(v: &Spanned<DeValue<'_>>, value: f64) -> Vec<(Range<usize>, String)> {
    let current = match v.get_ref() {
        DeValue::Integer(i) => i64::from_str_radix(&i.as_str().replace('_', ""), i.radix())
            .ok()
            .map(|n| n as f64),
        DeValue::Float(f) => f.as_str().replace('_', "").parse::<f64>().ok(),
        _ => None,
    };
    if current == Some(value) {
        Vec::new()
    } else {
        vec![(v.span(), number(value))]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const TEXT: &str = "\
# a comment
name = \"t\"  # trailing
advance = 500

[[contour]]
points = [
  [0, 0, 0],   # first
  [100, 0, 1.50e-1],
  [50, 100, -1],
]
";

    #[test]
    fn move_changes_only_its_numbers() {
        let ops = [Op::Move {
            contour: 0,
            point: 1,
            x: 120.5,
            y: 0.0,
        }];
        let out = apply(TEXT, &ops).unwrap();
        assert_eq!(
            out,
            TEXT.replace("[100, 0, 1.50e-1]", "[120.5, 0, 1.50e-1]")
        );
    }

    #[test]
    fn insert_and_delete_keep_the_layout() {
        let ins = [Op::Insert {
            contour: 0,
            index: 3,
            point: [10.0, 50.0, 0.5],
        }];
        let out = apply(TEXT, &ins).unwrap();
        assert_eq!(
            out,
            TEXT.replace("[50, 100, -1],", "[50, 100, -1],\n  [10, 50, 0.5],")
        );
        let del = [Op::Delete {
            contour: 0,
            point: 3,
        }];
        assert_eq!(apply(&out, &del).unwrap(), TEXT);
        let first = [Op::Insert {
            contour: 0,
            index: 0,
            point: [1.0, 2.0, 0.0],
        }];
        let out = apply(TEXT, &first).unwrap();
        assert_eq!(
            out,
            TEXT.replace("  [0, 0, 0],", "  [1, 2, 0],\n  [0, 0, 0],")
        );
    }

    #[test]
    fn shape_advance_and_ranges() {
        let out = apply(
            TEXT,
            &[
                Op::Shape {
                    contour: 0,
                    point: 2,
                    s: 0.25,
                },
                Op::Advance { value: 480.0 },
            ],
        )
        .unwrap();
        assert_eq!(
            out,
            TEXT.replace("[50, 100, -1]", "[50, 100, 0.25]")
                .replace("advance = 500", "advance = 480")
        );
        let bad = apply(
            TEXT,
            &[Op::Delete {
                contour: 0,
                point: 3,
            }],
        );
        assert_eq!(
            bad,
            Err(EditError::OutOfRange(
                "point 3 is out of range: contour 0 has 3 points".into()
            ))
        );
        let bad = apply(
            TEXT,
            &[Op::Shape {
                contour: 1,
                point: 0,
                s: 0.0,
            }],
        );
        assert_eq!(
            bad,
            Err(EditError::OutOfRange(
                "contour 1 is out of range: the glyph has 1 contours".into()
            ))
        );
    }
}
