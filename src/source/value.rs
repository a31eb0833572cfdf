//! Typed reading of TOML values with spans: numbers, integers, strings, keys.
//!
//! Every reader reports a problem at the value's position and returns `None`, so one run
//! collects every problem of a file instead of stopping at the first.

use toml::de::{DeTable, DeValue};
use toml::Spanned;

use super::diagnostic::Ctx;

/// A parsed TOML document, or `None` with an `invalid TOML` diagnostic.
pub(super) fn parse<'i>(ctx: &mut Ctx<'_>, text: &'i str) -> Option<Spanned<DeTable<'i>>> {
    match DeTable::parse(text) {
        Ok(t) => Some(t),
        Err(e) => {
            let off = e.span().map_or(0, |s| s.start);
            let msg = e.message().trim().to_string();
            ctx.err(off, format!("invalid TOML: {msg}"));
            None
        }
    }
}

/// The value of `key` in `table`.
pub(super) fn get<'t, 'i>(table: &'t DeTable<'i>, key: &str) -> Option<&'t Spanned<DeValue<'i>>> {
    table
        .iter()
        .find(|(k, _)| k.get_ref() == key)
        .map(|(_, v)| v)
}

/// Where a table's first key (or `[[header]]`) is written, in source order; `fallback`
/// for an empty table. Missing keys are reported here.
pub(super) fn first_offset(table: &DeTable<'_>, fallback: usize) -> usize {
    table
        .iter()
        .map(|(k, v)| k.span().start.min(v.span().start))
        .min()
        .unwrap_or(fallback)
}

fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut cur = vec![i + 1];
        for (j, cb) in b.iter().enumerate() {
            let sub = prev[j] + usize::from(ca != *cb);
            cur.push(sub.min(prev[j + 1] + 1).min(cur[j] + 1));
        }
        prev = cur;
    }
    prev[b.len()]
}

/// Reports every key of `table` that is not in `allowed`, suggesting the closest allowed key
/// (edit distance ≤ 2). Returns the suggested keys, so that a misspelt required key gives
/// one error ("unknown key `advnce`; did you mean `advance`?") rather than two.
pub(super) fn check_keys(
    ctx: &mut Ctx<'_>,
    table: &DeTable<'_>,
    allowed: &[&'static str],
) -> Vec<&'static str> {
    let mut suggested = Vec::new();
    for (k, _) in table.iter() {
        let key: &str = k.get_ref();
        if allowed.contains(&key) {
            continue;
        }
        let best = allowed
            .iter()
            .map(|a| (edit_distance(key, a), *a))
            .min_by_key(|(d, _)| *d);
        let msg = match best {
            Some((d, a)) if d <= 2 => {
                if get(table, a).is_none() {
                    suggested.push(a);
                }
                format!("unknown key `{key}`; did you mean `{a}`?")
            }
            _ => format!(
                "unknown key `{key}`; expected one of {}",
                allowed
                    .iter()
                    .map(|a| format!("`{a}`"))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        };
        ctx.err(k.span().start, msg);
    }
    suggested
}

/// The value of a required key. When it is absent, reports "missing required key" at
/// `at` with an example line to add, unless a misspelling of it was already reported.
pub(super) fn require<'t, 'i>(
    ctx: &mut Ctx<'_>,
    table: &'t DeTable<'i>,
    key: &str,
    example: &str,
    at: usize,
    suggested: &[&str],
) -> Option<&'t Spanned<DeValue<'i>>> {
    let v = get(table, key);
    if v.is_none() && !suggested.contains(&key) {
        ctx.err(
            at,
            format!("missing required key `{key}`; add a line such as `{example}`"),
        );
    }
    v
}

/// The name TOML gives a value's type, for "found ..." messages.
pub(super) fn type_name(v: &DeValue<'_>) -> &'static str {
    v.type_str()
}

/// A number (integer or float), or `None` with a diagnostic. Non-finite numbers are refused.
pub(super) fn number(ctx: &mut Ctx<'_>, v: &Spanned<DeValue<'_>>, what: &str) -> Option<f64> {
    let x = match v.get_ref() {
        DeValue::Integer(i) => {
            let digits = without_underscores(i.as_str());
            let Ok(n) = i64::from_str_radix(&digits, i.radix()) else {
                ctx.err(
                    v.span().start,
                    format!("`{what}` = {digits} does not fit a TOML integer (64-bit)"),
                );
                return None;
            };
            Some(n as f64)
        }
        DeValue::Float(f) => {
            let s = without_underscores(f.as_str());
            match s.trim_start_matches(['+', '-']) {
                "inf" | "nan" => Some(f64::NAN),
                _ => s.parse::<f64>().ok(),
            }
        }
        other => {
            ctx.err(
                v.span().start,
                format!("`{what}` must be a number, found {}", type_name(other)),
            );
            return None;
        }
    };
    match x {
        Some(x) if x.is_finite() => Some(x),
        _ => {
            ctx.err(v.span().start, format!("`{what}` must be a finite number"));
            None
        }
    }
}

/// A TOML number's digits without its `_` separators, copied only when it has some (a
/// font's sources are mostly numbers, and a copy of each was a tenth of parsing them).
fn without_underscores(digits: &str) -> std::borrow::Cow<'_, str> {
    if digits.contains('_') {
        digits.replace('_', "").into()
    } else {
        digits.into()
    }
}

/// An integer, or `None` with a diagnostic (floats are refused, not truncated).
pub(super) fn integer(ctx: &mut Ctx<'_>, v: &Spanned<DeValue<'_>>, what: &str) -> Option<i64> {
    match v.get_ref() {
        DeValue::Integer(i) => {
            let digits = i.as_str().replace('_', "");
            let r = i64::from_str_radix(&digits, i.radix()).ok();
            if r.is_none() {
                ctx.err(v.span().start, format!("`{what}` is out of range"));
            }
            r
        }
        other => {
            ctx.err(
                v.span().start,
                format!("`{what}` must be an integer, found {}", type_name(other)),
            );
            None
        }
    }
}

/// A string, or `None` with a diagnostic.
pub(super) fn string(ctx: &mut Ctx<'_>, v: &Spanned<DeValue<'_>>, what: &str) -> Option<String> {
    match v.get_ref() {
        DeValue::String(s) => Some(s.to_string()),
        other => {
            ctx.err(
                v.span().start,
                format!("`{what}` must be a string, found {}", type_name(other)),
            );
            None
        }
    }
}

/// The tables of an array of tables (`[[key]]` or `key = [{...}]`), or `None` with a
/// diagnostic; entries that are not tables are reported and skipped (`all_ok` turns false).
pub(super) fn tables<'t, 'i>(
    ctx: &mut Ctx<'_>,
    v: &'t Spanned<DeValue<'i>>,
    what: &str,
    all_ok: &mut bool,
) -> Vec<(&'t DeTable<'i>, usize)> {
    let DeValue::Array(a) = v.get_ref() else {
        ctx.err(
            v.span().start,
            format!(
                "`{what}` must be an array of tables (`[[{what}]]`), found {}",
                type_name(v.get_ref())
            ),
        );
        *all_ok = false;
        return Vec::new();
    };
    let mut out = Vec::new();
    for item in a {
        match item.get_ref() {
            DeValue::Table(t) => out.push((t, item.span().start)),
            other => {
                ctx.err(
                    item.span().start,
                    format!(
                        "`{what}` entries must be tables, found {}",
                        type_name(other)
                    ),
                );
                *all_ok = false;
            }
        }
    }
    out
}
