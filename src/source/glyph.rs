//! One glyph file -> [`Glyph`]: name, code points, advance, `mark`, contours, components,
//! anchors.
//!
//! Checks here need only the file itself; the checks across files (duplicate names and
//! code points, component bases and cycles, points far outside the metrics) are in
//! [`super::load`], and the anchor checks and the placement of components by anchors are
//! in [`super::anchors`]. A component written without `offset` is read at `[0, 0]` here;
//! [`GlyphSpans::offsets`] records that it had none, for the placement and for `fmt`.

use std::path::Path;

use toml::de::{DeTable, DeValue};
use toml::Spanned;

use super::diagnostic::{Ctx, Diagnostic, Diagnostics};
use super::geometry::{no_area, NoArea};
use super::limits;
use super::value::{
    check_keys, first_offset, get, integer, number, parse, require, string, tables, type_name,
};
use crate::model::{Anchor, Component, Contour, Glyph};
use crate::xspline::{ControlPoint, XSplineError};

/// Every key a glyph file may contain at the top level.
const KEYS: &[&str] = &[
    "name",
    "unicode",
    "advance",
    "mark",
    "contour",
    "component",
    "anchor",
];

/// Where the parts of a glyph were written (byte offsets), for diagnostics across files.
#[derive(Clone, Debug, Default)]
pub(super) struct GlyphSpans {
    /// The first key (where a missing key is reported).
    pub start: usize,
    /// The `name` value; 0 when the file has no `name` (a written value never starts at 0).
    pub name: usize,
    /// The `mark` value; 0 when the file has none.
    pub mark: usize,
    pub unicodes: Vec<usize>,
    pub bases: Vec<usize>,
    /// Per component: where its `offset` was written, `None` when it has none (then the
    /// loader places it by anchors).
    pub offsets: Vec<Option<usize>>,
    /// Per anchor: where its `name` value was written.
    pub anchors: Vec<usize>,
    /// Per contour, per point.
    pub points: Vec<Vec<usize>>,
}

/// Loads one glyph file from memory. `path` labels the diagnostics and its stem is the
/// glyph name when the file has no `name`. Only the checks that need this file alone run
/// (see [`super::load_font`] for the rest). Returns the glyph and its warnings, or every
/// diagnostic when there is an error.
pub fn load_glyph_text(
    path: &Path,
    text: &str,
) -> Result<(Glyph, Vec<Diagnostic>), Vec<Diagnostic>> {
    let mut out = Diagnostics::default();
    let glyph = load_glyph(&mut Ctx::new(path, text, &mut out));
    match glyph {
        Some(loaded) if loaded.complete && !out.has_errors() => Ok((loaded.glyph, out.into_vec())),
        _ => Err(out.into_vec()),
    }
}

/// A glyph as far as it could be read.
pub(super) struct Loaded {
    /// When not `complete`: the parts that were well-formed (an unreadable advance is 0).
    pub glyph: Glyph,
    pub spans: GlyphSpans,
    /// Whether the file had no error of its own.
    pub complete: bool,
}

/// Reads a glyph file, reporting every problem of the file itself. `None` only when the
/// file is not TOML or its name is unusable; otherwise the glyph, possibly incomplete, so
/// that the checks across files still see its name, code points and components.
pub(super) fn load_glyph(ctx: &mut Ctx<'_>) -> Option<Loaded> {
    let stem = ctx
        .path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    let text = ctx.text();
    let table = parse(ctx, text)?;
    let t = table.get_ref();
    let suggested = check_keys(ctx, t, KEYS);
    let at = first_offset(t, 0);
    let mut ok = true;
    let mut spans = GlyphSpans {
        start: at,
        ..GlyphSpans::default()
    };

    let name = match get(t, "name") {
        None => Some(stem),
        Some(v) => {
            spans.name = v.span().start;
            match string(ctx, v, "name") {
                Some(n) if n.is_empty() => {
                    ctx.err(
                        v.span().start,
                        "`name` must not be empty; remove it to use the file name",
                    );
                    None
                }
                other => other,
            }
        }
    };

    let mut unicodes = Vec::new();
    if let Some(v) = get(t, "unicode") {
        let items: Vec<&Spanned<DeValue<'_>>> = match v.get_ref() {
            DeValue::Array(a) => a.iter().collect(),
            _ => vec![v],
        };
        for item in items {
            match integer(ctx, item, "unicode").and_then(|n| code_point(ctx, item, n)) {
                Some(c) => {
                    unicodes.push(c);
                    spans.unicodes.push(item.span().start);
                }
                None => ok = false,
            }
        }
    }

    let advance = require(ctx, t, "advance", "advance = 500", at, &suggested)
        .and_then(|v| limits::advance(ctx, v));

    let outline_mark = match get(t, "mark") {
        None => false,
        Some(v) => {
            spans.mark = v.span().start;
            let is_outline = mark_kind(ctx, v);
            ok &= is_outline;
            is_outline
        }
    };

    let mut contours = Vec::new();
    if let Some(v) = get(t, "contour") {
        for (ct, header) in tables(ctx, v, "contour", &mut ok) {
            match load_contour(ctx, ct, header) {
                Some((contour, offs)) => {
                    contours.push(contour);
                    spans.points.push(offs);
                }
                None => ok = false,
            }
        }
    }

    let mut components = Vec::new();
    if let Some(v) = get(t, "component") {
        for (ct, header) in tables(ctx, v, "component", &mut ok) {
            match load_component(ctx, ct, header) {
                Some((component, base_off, offset_off)) => {
                    components.push(component);
                    spans.bases.push(base_off);
                    spans.offsets.push(offset_off);
                }
                None => ok = false,
            }
        }
    }

    let mut anchors: Vec<Anchor> = Vec::new();
    if let Some(v) = get(t, "anchor") {
        for (at, header) in tables(ctx, v, "anchor", &mut ok) {
            let Some((anchor, name_off)) = load_anchor(ctx, at, header) else {
                ok = false;
                continue;
            };
            if let Some(k) = anchors.iter().position(|a| a.name == anchor.name) {
                let (line, _) = ctx.line_col(spans.anchors[k]);
                ctx.err(
                    name_off,
                    format!(
                        "duplicate anchor `{}` (also on line {line}); anchor names are unique \
                         in a glyph",
                        anchor.name
                    ),
                );
                ok = false;
                continue;
            }
            anchors.push(anchor);
            spans.anchors.push(name_off);
        }
    }

    if outline_mark {
        if let Some(k) = anchors.iter().position(|a| a.attaches_to().is_some()) {
            let (line, _) = ctx.line_col(spans.anchors[k]);
            ctx.err(
                spans.mark,
                format!(
                    "`mark = \"outline\"` says the outline places this mark, but it has the \
                     anchor `{}` (line {line}) to attach by; keep one of the two",
                    anchors[k].name
                ),
            );
            ok = false;
        }
    }

    let name = name?;
    let complete = ok && advance.is_some();
    let advance = advance.unwrap_or(0.0);
    if complete && contours.is_empty() && components.is_empty() && advance == 0.0 {
        ctx.warn(
            at,
            format!("glyph `{name}` is empty: no contours, no components and advance 0"),
        );
    }
    let glyph = Glyph {
        name,
        unicodes,
        advance,
        contours,
        components,
        anchors,
        outline_mark,
    };
    Some(Loaded {
        glyph,
        spans,
        complete,
    })
}

/// Whether the `mark` value is `"outline"`, the one kind of mark the key names (a mark
/// placed by its outline); anything else is reported at the value.
fn mark_kind(ctx: &mut Ctx<'_>, v: &Spanned<DeValue<'_>>) -> bool {
    let found = match v.get_ref() {
        DeValue::String(s) if s.as_ref() == "outline" => return true,
        DeValue::String(s) => super::emit::string(s),
        other => type_name(other).to_string(),
    };
    ctx.err(
        v.span().start,
        format!(
            "`mark` must be \"outline\" (a mark placed by its own outline, with no `_` \
             anchor), found {found}"
        ),
    );
    false
}

/// A Unicode scalar value, or `None` with a diagnostic saying why `n` is not one.
fn code_point(ctx: &mut Ctx<'_>, v: &Spanned<DeValue<'_>>, n: i64) -> Option<char> {
    let why = if n < 0 {
        format!("invalid code point {n}: code points are 0x0..0x10FFFF")
    } else if n > 0x10FFFF {
        format!("invalid code point {n:#X}: the largest is 0x10FFFF")
    } else if (0xD800..=0xDFFF).contains(&n) {
        format!("invalid code point {n:#X}: surrogates 0xD800..0xDFFF are not characters")
    } else {
        return u32::try_from(n).ok().and_then(char::from_u32);
    };
    ctx.err(v.span().start, why);
    None
}

/// One `[[contour]]` table: the validated contour and where each point was written.
///
/// The rules of a closed X-spline are [`Contour::new`]'s; this reads the points and puts
/// its error at the place of the point it names. Each `s` is also range-checked as it is
/// read, like every number, so that one unreadable point does not hide a bad `s` in
/// another (the contour check needs every point).
fn load_contour(
    ctx: &mut Ctx<'_>,
    ct: &DeTable<'_>,
    header: usize,
) -> Option<(Contour, Vec<usize>)> {
    let suggested = check_keys(ctx, ct, &["points"]);
    let example = "points = [[0, 0, 0], [100, 0, 0], [50, 100, 0]]";
    let v = require(ctx, ct, "points", example, header, &suggested)?;
    let DeValue::Array(arr) = v.get_ref() else {
        ctx.err(
            v.span().start,
            format!(
                "`points` must be an array of [x, y, s] points, found {}",
                type_name(v.get_ref())
            ),
        );
        return None;
    };
    let mut points = Vec::new();
    // Per point: where it starts and where its `s` is.
    let mut offs = Vec::new();
    let mut s_offs = Vec::new();
    let mut ok = true;
    for p in arr {
        let items = match p.get_ref() {
            DeValue::Array(a) if a.len() == 3 => a,
            DeValue::Array(a) => {
                ctx.err(
                    p.span().start,
                    format!("a point must be [x, y, s], found {} values", a.len()),
                );
                ok = false;
                continue;
            }
            other => {
                ctx.err(
                    p.span().start,
                    format!(
                        "a point must be an array [x, y, s], found {}",
                        type_name(other)
                    ),
                );
                ok = false;
                continue;
            }
        };
        let x = limits::coordinate(ctx, &items[0], "x");
        let y = limits::coordinate(ctx, &items[1], "y");
        let s = number(ctx, &items[2], "s");
        if let Some(s) = s {
            if !(-1.0..=1.0).contains(&s) {
                ctx.err(items[2].span().start, format!("s = {s} is outside [-1, 1]"));
                ok = false;
            }
        }
        match (x, y, s) {
            (Some(x), Some(y), Some(s)) => {
                points.push(ControlPoint::new(x, y, s));
                offs.push(p.span().start);
                s_offs.push(items[2].span().start);
            }
            _ => ok = false,
        }
    }
    if !ok {
        return None;
    }
    let contour = match Contour::new(points) {
        Ok(contour) => contour,
        Err(error) => {
            let (at, message) = match error {
                XSplineError::TooFewPoints { count } => (
                    v.span().start,
                    format!("a contour needs at least 3 points, found {count}"),
                ),
                XSplineError::ShapeOutOfRange { index, s } => {
                    (s_offs[index], format!("s = {s} is outside [-1, 1]"))
                }
                XSplineError::CoincidentPoints { index, next } => (
                    offs[next],
                    format!("point {next} coincides with point {index} before it"),
                ),
                // `number` already refused non-finite values; kept for completeness.
                XSplineError::NonFinite { index } => (offs[index], error.to_string()),
            };
            ctx.err(at, message);
            return None;
        }
    };
    if let Some(why) = no_area(contour.spline()) {
        let n = contour.points().len();
        let how = match why {
            NoArea::Collinear => format!("its {n} points lie on one straight line"),
            NoArea::OutAndBack => "it runs out and back along itself".to_string(),
        };
        ctx.err(v.span().start, format!("contour encloses no area: {how}"));
        return None;
    }
    Some((contour, offs))
}

/// One `[[component]]` table, where its `base` was written, and where its `offset` was
/// written (`None` without one: the component is read at `[0, 0]` and placed later).
fn load_component(
    ctx: &mut Ctx<'_>,
    ct: &DeTable<'_>,
    header: usize,
) -> Option<(Component, usize, Option<usize>)> {
    let suggested = check_keys(ctx, ct, &["base", "offset"]);
    let base = require(ctx, ct, "base", "base = \"acutecomb\"", header, &suggested)
        .and_then(|b| Some((string(ctx, b, "base")?, b.span().start)));
    let offset = match get(ct, "offset") {
        None => Some(((0.0, 0.0), None)),
        Some(o) => xy(ctx, o, "offset").map(|xy| (xy, Some(o.span().start))),
    };
    let ((base, base_off), (offset, offset_off)) = (base?, offset?);
    Some((Component { base, offset }, base_off, offset_off))
}

/// One `[[anchor]]` table and where its `name` was written.
fn load_anchor(ctx: &mut Ctx<'_>, at: &DeTable<'_>, header: usize) -> Option<(Anchor, usize)> {
    let suggested = check_keys(ctx, at, &["name", "position"]);
    let name = require(ctx, at, "name", "name = \"top\"", header, &suggested).and_then(|v| {
        let name = string(ctx, v, "name")?;
        if name.is_empty() || name == "_" || name.chars().any(char::is_whitespace) {
            ctx.err(
                v.span().start,
                format!(
                    "anchor name {} is not usable: write a word such as `top`, or `_top` \
                     on a mark",
                    super::emit::string(&name)
                ),
            );
            return None;
        }
        Some((name, v.span().start))
    });
    let example = "position = [250, 500]";
    let position = require(ctx, at, "position", example, header, &suggested)
        .and_then(|v| xy(ctx, v, "position"));
    let ((name, name_off), position) = (name?, position?);
    Some((Anchor { name, position }, name_off))
}

/// A point `[x, y]` in font units (a component's `offset`, an anchor's `position`), each
/// number a coordinate within the outputs' limits.
fn xy(ctx: &mut Ctx<'_>, v: &Spanned<DeValue<'_>>, key: &str) -> Option<(f64, f64)> {
    match v.get_ref() {
        DeValue::Array(xy) if xy.len() == 2 => {
            let x = limits::coordinate(ctx, &xy[0], "x");
            match (x, limits::coordinate(ctx, &xy[1], "y")) {
                (Some(x), Some(y)) => Some((x, y)),
                _ => None,
            }
        }
        DeValue::Array(xy) => {
            ctx.err(
                v.span().start,
                format!("`{key}` must be [x, y], found {} values", xy.len()),
            );
            None
        }
        other => {
            ctx.err(
                v.span().start,
                format!(
                    "`{key}` must be an array [x, y], found {}",
                    type_name(other)
                ),
            );
            None
        }
    }
}

/// Per component of the glyph file `text`: whether it has an `offset` written (`fmt`
/// keeps a component without one that way). `None` when the file does not load alone.
pub fn offsets_written(path: &Path, text: &str) -> Option<Vec<bool>> {
    let mut out = Diagnostics::default();
    let loaded = load_glyph(&mut Ctx::new(path, text, &mut out))?;
    (loaded.complete && !out.has_errors())
        .then(|| loaded.spans.offsets.iter().map(Option::is_some).collect())
}
