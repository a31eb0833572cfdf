//! `font.toml` -> [`FontInfo`]: family, style, metrics, tolerance, free-form metadata.

use std::path::Path;

use super::diagnostic::{Ctx, Diagnostic, Diagnostics};
use super::limits;
use super::value::{check_keys, first_offset, get, integer, number, parse, require, string};
use crate::model::FontInfo;

/// Every key `font.toml` may contain.
const KEYS: &[&str] = &[
    "family",
    "style",
    "units_per_em",
    "ascender",
    "descender",
    "x_height",
    "cap_height",
    "tolerance",
    "copyright",
    "designer",
    "version",
    "license",
    "license_url",
    "vendor",
    // The masters' tables, read by `super::designspace`.
    "axis",
    "master",
    "instance",
    "rule",
    "rules_processing",
];

/// Default `tolerance` in font units.
pub const DEFAULT_TOLERANCE: f64 = 0.5;

/// Smallest `tolerance` accepted, in font units (here, on the command line and for
/// imports): far finer than any font's grid, and far above the floor where floating point
/// stops the fitter from meeting a tolerance on glyph-sized contours
/// ([`crate::xspline::XSpline::min_tolerance`]).
pub const MIN_TOLERANCE: f64 = 1e-4;

/// Largest `tolerance` accepted in `font.toml`, in font units: far coarser than any
/// outline needs (a whole em in most fonts).
pub const MAX_TOLERANCE: f64 = 1000.0;

/// Checks a `--tolerance` given on the command line: finite and at least [`MIN_TOLERANCE`].
pub fn check_tolerance_flag(t: f64) -> Result<f64, String> {
    if t.is_finite() && t >= MIN_TOLERANCE {
        Ok(t)
    } else {
        Err(format!(
            "--tolerance must be a number of at least {MIN_TOLERANCE} font units, got {t}"
        ))
    }
}

/// Loads one `font.toml` from memory (`path` only labels diagnostics): the info and its
/// warnings, or every diagnostic when there is an error.
pub fn load_info_text(
    path: &Path,
    text: &str,
) -> Result<(FontInfo, Vec<Diagnostic>), Vec<Diagnostic>> {
    let mut out = Diagnostics::default();
    match load_info(&mut Ctx::new(path, text, &mut out)) {
        Some(info) if !out.has_errors() => Ok((info, out.into_vec())),
        _ => Err(out.into_vec()),
    }
}

pub(super) fn load_info(ctx: &mut Ctx<'_>) -> Option<FontInfo> {
    let text = ctx.text();
    let table = parse(ctx, text)?;
    let t = table.get_ref();
    let suggested = check_keys(ctx, t, KEYS);
    let at = first_offset(t, 0);
    let mut ok = true;

    let family = require(ctx, t, "family", "family = \"My Sans\"", at, &suggested)
        .and_then(|v| Some((string(ctx, v, "family")?, v.span().start)));
    let family = match family {
        Some((f, off)) if f.trim().is_empty() => {
            ctx.err(off, "`family` must not be empty");
            None
        }
        other => other,
    };

    let upm = require(
        ctx,
        t,
        "units_per_em",
        "units_per_em = 1000",
        at,
        &suggested,
    )
    .and_then(|v| Some((integer(ctx, v, "units_per_em")?, v.span().start)))
    .and_then(|(n, off)| match u16::try_from(n) {
        Ok(n) if (16..=16384).contains(&n) => Some(n),
        _ => {
            ctx.err(off, "`units_per_em` must be an integer in 16..16384");
            None
        }
    });

    let metric = |ctx: &mut Ctx<'_>, key: &str, example: &str| {
        require(ctx, t, key, example, at, &suggested)
            .and_then(|v| Some((limits::metric(ctx, v, key)?, v.span().start)))
    };
    let ascender = metric(ctx, "ascender", "ascender = 800");
    let descender = metric(ctx, "descender", "descender = -200");
    let x_height = metric(ctx, "x_height", "x_height = 500");
    let cap_height = metric(ctx, "cap_height", "cap_height = 700");
    if let (Some((a, a_off)), Some((d, d_off))) = (ascender, descender) {
        if a <= d {
            ctx.err(a_off, "`ascender` must be greater than `descender`");
            ok = false;
        } else if d > 0.0 {
            ctx.err(
                d_off,
                format!("`descender` must be 0 or negative (y up: below the baseline), found {d}"),
            );
            ok = false;
        }
    }

    let tolerance = match get(t, "tolerance") {
        None => Some(DEFAULT_TOLERANCE),
        Some(v) => match number(ctx, v, "tolerance") {
            Some(x) if x > MAX_TOLERANCE => {
                ctx.err(
                    v.span().start,
                    format!(
                        "`tolerance` must be at most {MAX_TOLERANCE} font units, found {x} \
                         (at that distance the outlines need not resemble the glyphs)"
                    ),
                );
                None
            }
            Some(x) if x >= MIN_TOLERANCE => Some(x),
            Some(x) if x > 0.0 => {
                ctx.err(
                    v.span().start,
                    format!(
                        "`tolerance` must be at least {MIN_TOLERANCE} font units, found {x} \
                         (no font grid is that fine)"
                    ),
                );
                None
            }
            Some(x) => {
                ctx.err(
                    v.span().start,
                    format!("`tolerance` must be positive (font units), found {x}"),
                );
                None
            }
            None => None,
        },
    };

    let optional = |ctx: &mut Ctx<'_>, key: &str| match get(t, key) {
        None => Some(None),
        Some(v) => string(ctx, v, key)
            .filter(|s| limits::text(ctx, s, v.span().start, key))
            .map(Some),
    };
    let style = optional(ctx, "style");
    let copyright = optional(ctx, "copyright");
    let designer = optional(ctx, "designer");
    let version = optional(ctx, "version");
    let license = optional(ctx, "license");
    let license_url = optional(ctx, "license_url");
    let vendor = match get(t, "vendor") {
        None => Some(None),
        Some(v) => match string(ctx, v, "vendor") {
            Some(id) if is_vendor_id(&id) => Some(Some(id)),
            Some(id) => {
                ctx.err(
                    v.span().start,
                    format!(
                        "`vendor` must be 1 to 4 printable ASCII characters (an OS/2 vendor \
                         ID such as \"XGLY\"), found {id:?}"
                    ),
                );
                None
            }
            None => None,
        },
    };

    if let (Some((f, off)), Some(style)) = (&family, &style) {
        ok &= limits::family_style(ctx, f, style.as_deref().unwrap_or("Regular"), *off);
    }
    // Every field that loaded, or nothing (each failure is already reported).
    let info = || {
        Some(FontInfo {
            family: family?.0,
            style: style?.unwrap_or_else(|| "Regular".to_string()),
            units_per_em: upm?,
            ascender: ascender?.0,
            descender: descender?.0,
            x_height: x_height?.0,
            cap_height: cap_height?.0,
            tolerance: tolerance?,
            copyright: copyright?,
            designer: designer?,
            version: version?,
            license: license?,
            license_url: license_url?,
            vendor: vendor?,
        })
    };
    ok.then(info).flatten()
}

/// An OS/2 vendor ID: 1 to 4 printable ASCII characters (space included; the table pads
/// shorter ones with spaces).
fn is_vendor_id(id: &str) -> bool {
    (1..=4).contains(&id.len()) && id.bytes().all(|b| (0x20..=0x7E).contains(&b))
}
