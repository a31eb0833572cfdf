//! `kerning.toml` -> [`KernPair`]s, checked against the glyph names.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

use super::diagnostic::{Ctx, Diagnostic, Diagnostics};
use super::limits;
use super::value::{check_keys, get, parse, require, string, tables};
use crate::model::KernPair;

/// Loads one `kerning.toml` from memory (`path` only labels diagnostics), with `names`
/// the glyph names of the font: the pairs, or every diagnostic when there is an error.
pub fn load_kerning_text(
    path: &Path,
    text: &str,
    names: &BTreeSet<String>,
) -> Result<Vec<KernPair>, Vec<Diagnostic>> {
    let mut out = Diagnostics::default();
    match load_kerning(&mut Ctx::new(path, text, &mut out), names) {
        Some(pairs) if !out.has_errors() => Ok(pairs),
        _ => Err(out.into_vec()),
    }
}

/// Loads the pairs in file order. Every side must name an existing glyph; a pair written
/// twice is an error (which value would win is not obvious), even with the same value.
pub(super) fn load_kerning(ctx: &mut Ctx<'_>, names: &BTreeSet<String>) -> Option<Vec<KernPair>> {
    let text = ctx.text();
    let table = parse(ctx, text)?;
    let t = table.get_ref();
    check_keys(ctx, t, &["pair"]);
    let mut ok = true;
    let mut pairs = Vec::new();
    let mut seen: BTreeMap<(String, String), usize> = BTreeMap::new();
    let Some(v) = get(t, "pair") else {
        return Some(pairs);
    };
    for (pt, header) in tables(ctx, v, "pair", &mut ok) {
        let suggested = check_keys(ctx, pt, &["left", "right", "value"]);
        let side = |ctx: &mut Ctx<'_>, key: &str, example: &str| {
            let v = require(ctx, pt, key, example, header, &suggested)?;
            let name = string(ctx, v, key)?;
            if !names.contains(&name) {
                ctx.err(v.span().start, format!("unknown glyph `{name}`"));
                return None;
            }
            Some(name)
        };
        let left = side(ctx, "left", "left = \"A\"");
        let right = side(ctx, "right", "right = \"V\"");
        let value = require(ctx, pt, "value", "value = -60", header, &suggested)
            .and_then(|v| limits::kern_value(ctx, v));
        let (Some(left), Some(right), Some(value)) = (left, right, value) else {
            ok = false;
            continue;
        };
        let key = (left.clone(), right.clone());
        if let Some(first) = seen.get(&key) {
            let (line, _) = ctx.line_col(*first);
            ctx.err(
                header,
                format!("duplicate kerning pair `{left}` `{right}` (first written at line {line})"),
            );
            ok = false;
            continue;
        }
        seen.insert(key, header);
        pairs.push(KernPair { left, right, value });
    }
    ok.then_some(pairs)
}
