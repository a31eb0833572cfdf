//! `font.toml`'s `[[axis]]`, `[[master]]` and `[[instance]]` tables -> a [`Designspace`]
//! and the non-default masters' names, folders and locations.
//!
//! Checks here need `font.toml` and the font folder only (tags, ranges, folders, the
//! master set as [`Designspace::model`] sees it); the glyph files of the masters are read
//! and compared with the default's in [`super::load`] and [`super::compat`].

use std::collections::BTreeMap;
use std::path::{Component, Path};

use toml::de::{DeTable, DeValue};
use toml::Spanned;

use super::diagnostic::{Ctx, Diagnostic, Diagnostics};
use super::emit;
use super::limits;
use super::value::{check_keys, get, number, require, string, tables, type_name};
use crate::designspace::{
    Axis, Designspace, Location, NamedInstance, RegionError, Rule, MAX_RULE_BOXES,
};

/// A non-default master as `font.toml` names it, with where its keys were written.
#[derive(Clone, Debug)]
pub(super) struct MasterSpec {
    pub name: String,
    /// As written: relative to the font folder.
    pub folder: String,
    pub location: Location,
    /// Byte offset of the `folder` value.
    pub folder_at: usize,
    /// `sparse = true`: the master draws only some glyphs.
    pub sparse: bool,
}

/// The design space of `font.toml` and its masters; both empty for a single-master font.
#[derive(Clone, Debug, Default)]
pub(super) struct DesignspaceSpec {
    pub designspace: Designspace,
    pub masters: Vec<MasterSpec>,
    /// Each glyph name a `[[rule]]` substitutes, with the rule's name and where it was
    /// written, to check against the glyph files.
    pub rule_glyphs: Vec<(String, String, usize)>,
}

/// A `[[master]]` as `font.toml` writes it: name, folder, location, sparse.
pub type MasterEntry = (String, String, Location, bool);

/// Loads the masters' tables of one `font.toml` from memory (`path` labels diagnostics,
/// `dir` is the font folder, for the master folders): the design space and each master's
/// name, folder and location, or every diagnostic when there is an error. What `fmt`
/// checks its rewrite of `font.toml` against.
pub fn load_designspace_text(
    path: &Path,
    text: &str,
    dir: &Path,
) -> Result<(Designspace, Vec<MasterEntry>), Vec<Diagnostic>> {
    let mut out = Diagnostics::default();
    match load_designspace(&mut Ctx::new(path, text, &mut out), dir) {
        Some(spec) if !out.has_errors() => Ok((
            spec.designspace,
            spec.masters
                .into_iter()
                .map(|m| (m.name, m.folder, m.location, m.sparse))
                .collect(),
        )),
        _ => Err(out.into_vec()),
    }
}

/// Reads the masters' tables of `font.toml` (`dir` is the font folder, for the master
/// folders). `None` when there is an error (reported), including a master set that
/// [`Designspace::model`] refuses.
pub(super) fn load_designspace(ctx: &mut Ctx<'_>, dir: &Path) -> Option<DesignspaceSpec> {
    let text = ctx.text();
    // Invalid TOML is reported by `load_info`.
    let table = DeTable::parse(text).ok()?;
    let t = table.get_ref();
    let mut ok = true;

    let mut axes: Vec<(Axis, AxisSpans)> = Vec::new();
    if let Some(v) = get(t, "axis") {
        for (at, header) in tables(ctx, v, "axis", &mut ok) {
            match load_axis(ctx, at, header) {
                Some((axis, spans)) => {
                    if let Some((_, first)) = axes.iter().find(|(a, _)| a.tag == axis.tag) {
                        let (line, _) = ctx.line_col(first.tag);
                        ctx.err(
                            spans.tag,
                            format!(
                                "duplicate axis tag `{}` (first written at line {line})",
                                axis.tag
                            ),
                        );
                        ok = false;
                    } else {
                        axes.push((axis, spans));
                    }
                }
                None => ok = false,
            }
        }
    }
    if !ok {
        // Locations are checked against the axes; with a broken axis they would only
        // report follow-on errors.
        return None;
    }
    let axis_list: Vec<Axis> = axes.iter().map(|(a, _)| a.clone()).collect();

    let mut masters: Vec<(MasterSpec, usize, usize)> = Vec::new();
    if let Some(v) = get(t, "master") {
        for (mt, header) in tables(ctx, v, "master", &mut ok) {
            if axis_list.is_empty() && ok {
                ctx.err(
                    header,
                    "a `[[master]]` needs the axes it sits on: add an `[[axis]]` table",
                );
                ok = false;
                continue;
            }
            match load_master(ctx, mt, header, dir, &axis_list) {
                Some((spec, name_at, location_at)) => {
                    if masters.iter().any(|m| m.0.name == spec.name) {
                        ctx.err(name_at, format!("duplicate master name `{}`", spec.name));
                        ok = false;
                    } else {
                        masters.push((spec, name_at, location_at));
                    }
                }
                None => ok = false,
            }
        }
    }

    let family = get(t, "family").and_then(|v| match v.get_ref() {
        DeValue::String(f) => Some(f.to_string()),
        _ => None,
    });
    let mut instances: Vec<NamedInstance> = Vec::new();
    if let Some(v) = get(t, "instance") {
        for (it, header) in tables(ctx, v, "instance", &mut ok) {
            if axis_list.is_empty() {
                if ok {
                    ctx.err(
                        header,
                        "an `[[instance]]` needs the axes it sits on: add an `[[axis]]` table",
                    );
                }
                ok = false;
                continue;
            }
            let suggested = check_keys(ctx, it, &["name", "location"]);
            let name = require(ctx, it, "name", "name = \"Bold\"", header, &suggested)
                .and_then(|v| non_empty(ctx, v, "name"));
            let location = require(
                ctx,
                it,
                "location",
                "location = { wght = 700 }",
                header,
                &suggested,
            )
            .and_then(|v| location(ctx, v, &axis_list));
            // The instance is a static font `<family>-<name>`: the same file-name limit
            // as `family` and `style`.
            let name = name.filter(|(n, at)| match &family {
                Some(f) => limits::family_style(ctx, f, n, *at),
                None => true,
            });
            match (name, location) {
                (Some((name, at)), Some(location)) => {
                    if instances.iter().any(|i| i.name == name) {
                        ctx.err(at, format!("duplicate instance name `{name}`"));
                        ok = false;
                    } else {
                        instances.push(NamedInstance { name, location });
                    }
                }
                _ => ok = false,
            }
        }
    }
    let mut rules: Vec<Rule> = Vec::new();
    let mut rule_glyphs = Vec::new();
    if let Some(v) = get(t, "rule") {
        for (rt, header) in tables(ctx, v, "rule", &mut ok) {
            if axis_list.is_empty() {
                if ok {
                    ctx.err(
                        header,
                        "a `[[rule]]` substitutes glyphs by place on the axes: add an \
                         `[[axis]]` table",
                    );
                }
                ok = false;
                continue;
            }
            match load_rule(ctx, rt, header, &axis_list) {
                Some((rule, name_at, glyphs)) => {
                    if rule.holds_at(&axis_list, &Location::default()) {
                        ctx.warn(
                            header,
                            format!(
                                "rule `{}` holds at the default location: the variable font \
                                 and the instances there substitute, but the default master's \
                                 own static fonts, sheets and proofs show the glyphs unchanged",
                                rule.name
                            ),
                        );
                    }
                    let boxes: usize = rules.iter().map(|r| r.conditions.len()).sum::<usize>()
                        + rule.conditions.len();
                    if rules.iter().any(|r| r.name == rule.name) {
                        ctx.err(name_at, format!("duplicate rule name `{}`", rule.name));
                        ok = false;
                    } else if boxes > MAX_RULE_BOXES {
                        ctx.err(
                            header,
                            format!(
                                "the rules have {boxes} condition boxes so far, more than the \
                                 {MAX_RULE_BOXES} xglyph overlays; merge boxes or rules"
                            ),
                        );
                        ok = false;
                    } else {
                        rule_glyphs
                            .extend(glyphs.into_iter().map(|(g, at)| (rule.name.clone(), g, at)));
                        rules.push(rule);
                    }
                }
                None => ok = false,
            }
        }
    }
    if !ok {
        return None;
    }

    let rules_last = match get(t, "rules_processing") {
        None => false,
        Some(v) => match string(ctx, v, "rules_processing").as_deref() {
            Some("first") => false,
            Some("last") => true,
            Some(other) => {
                ctx.err(
                    v.span().start,
                    format!("`rules_processing` must be \"first\" or \"last\", found \"{other}\""),
                );
                return None;
            }
            None => return None,
        },
    };
    let designspace = Designspace {
        axes: axis_list,
        instances,
        rules,
        rules_last,
    };
    if !designspace.axes.is_empty() {
        let locations: Vec<Location> = masters.iter().map(|m| m.0.location.clone()).collect();
        if let Err(e) = designspace.model(&locations) {
            region_error(ctx, &e, &designspace, &masters);
            return None;
        }
        uncovered_end_warnings(ctx, &designspace, &masters, &axes);
    }
    Some(DesignspaceSpec {
        designspace,
        masters: masters.into_iter().map(|m| m.0).collect(),
        rule_glyphs,
    })
}

/// One `[[rule]]`: `name`, `conditions = [{ wght = [600, 700] }, ...]` (boxes in user
/// values, inclusive, inside the axis ranges) and `substitutions = { dollar =
/// "dollar.nostroke" }`. Returns the rule, where its name was written, and each glyph name
/// it uses with where it was written.
#[allow(clippy::type_complexity)]
fn load_rule(
    ctx: &mut Ctx<'_>,
    t: &DeTable<'_>,
    header: usize,
    axes: &[Axis],
) -> Option<(Rule, usize, Vec<(String, usize)>)> {
    let suggested = check_keys(ctx, t, &["name", "conditions", "substitutions"]);
    let name = require(
        ctx,
        t,
        "name",
        "name = \"heavy dollar\"",
        header,
        &suggested,
    )
    .and_then(|v| non_empty(ctx, v, "name"));
    let conditions = require(
        ctx,
        t,
        "conditions",
        "conditions = [{ wght = [600, 700] }]",
        header,
        &suggested,
    )
    .and_then(|v| rule_conditions(ctx, v, axes));
    let substitutions = require(
        ctx,
        t,
        "substitutions",
        "substitutions = { dollar = \"dollar.nostroke\" }",
        header,
        &suggested,
    )
    .and_then(|v| rule_substitutions(ctx, v));
    let ((name, name_at), conditions, (substitutions, glyphs)) =
        (name?, conditions?, substitutions?);
    Some((
        Rule {
            name,
            conditions,
            substitutions,
        },
        name_at,
        glyphs,
    ))
}

/// A rule's `conditions`: a non-empty array of boxes, each a table of axis -> [min, max].
fn rule_conditions(
    ctx: &mut Ctx<'_>,
    v: &Spanned<DeValue<'_>>,
    axes: &[Axis],
) -> Option<Vec<BTreeMap<String, (f64, f64)>>> {
    let DeValue::Array(boxes) = v.get_ref() else {
        ctx.err(
            v.span().start,
            format!(
                "`conditions` must be an array of boxes such as [{{ wght = [600, 700] }}], found {}",
                type_name(v.get_ref())
            ),
        );
        return None;
    };
    if boxes.is_empty() {
        ctx.err(
            v.span().start,
            "`conditions` is empty, so the rule never holds; add a box such as { wght = [600, 700] }",
        );
        return None;
    }
    let mut ok = true;
    let mut out = Vec::new();
    for b in boxes {
        let DeValue::Table(bt) = b.get_ref() else {
            ctx.err(
                b.span().start,
                format!(
                    "each condition must be a table of axis ranges such as {{ wght = [600, 700] }}, found {}",
                    type_name(b.get_ref())
                ),
            );
            ok = false;
            continue;
        };
        if bt.is_empty() {
            ctx.err(
                b.span().start,
                "an empty condition holds everywhere; give each one at least one axis range",
            );
            ok = false;
            continue;
        }
        let mut ranges = BTreeMap::new();
        for (k, range) in bt.iter() {
            let tag: &str = k.get_ref();
            let Some(axis) = axes.iter().find(|a| a.tag == tag) else {
                let known: Vec<String> = axes.iter().map(|a| format!("`{}`", a.tag)).collect();
                ctx.err(
                    k.span().start,
                    format!(
                        "unknown axis `{tag}` in `conditions`; the axes are {}",
                        known.join(", ")
                    ),
                );
                ok = false;
                continue;
            };
            let pair = match range.get_ref() {
                DeValue::Array(a) if a.len() == 2 => {
                    match (number(ctx, &a[0], tag), number(ctx, &a[1], tag)) {
                        (Some(min), Some(max)) => Some((min, max, a[1].span().start)),
                        _ => None,
                    }
                }
                other => {
                    ctx.err(
                        range.span().start,
                        format!(
                            "`{tag}` in a condition must be a range [min, max] such as [600, 700], found {}",
                            type_name(other)
                        ),
                    );
                    None
                }
            };
            let Some((min, max, max_at)) = pair else {
                ok = false;
                continue;
            };
            if min > max {
                ctx.err(
                    max_at,
                    format!(
                        "the range of `{tag}` runs backwards: {} comes after {}",
                        emit::number(max),
                        emit::number(min)
                    ),
                );
                ok = false;
                continue;
            }
            if min < axis.min || max > axis.max {
                ctx.err(
                    range.span().start,
                    format!(
                        "{tag} {}..{} reaches outside the axis range {}..{}",
                        emit::number(min),
                        emit::number(max),
                        emit::number(axis.min),
                        emit::number(axis.max)
                    ),
                );
                ok = false;
                continue;
            }
            ranges.insert(tag.to_string(), (min, max));
        }
        out.push(ranges);
    }
    ok.then_some(out)
}

/// A rule's `substitutions`: glyph -> alternate, each a string; returns the pairs in the
/// order written and every name with where it was written.
#[allow(clippy::type_complexity)]
fn rule_substitutions(
    ctx: &mut Ctx<'_>,
    v: &Spanned<DeValue<'_>>,
) -> Option<(Vec<(String, String)>, Vec<(String, usize)>)> {
    let DeValue::Table(t) = v.get_ref() else {
        ctx.err(
            v.span().start,
            format!(
                "`substitutions` must be a table such as {{ dollar = \"dollar.nostroke\" }}, found {}",
                type_name(v.get_ref())
            ),
        );
        return None;
    };
    if t.is_empty() {
        ctx.err(
            v.span().start,
            "`substitutions` is empty; name a glyph and its alternate",
        );
        return None;
    }
    let mut ok = true;
    let mut pairs = Vec::new();
    let mut names = Vec::new();
    for (k, alt) in t.iter() {
        let from: &str = k.get_ref();
        let Some(to) = string(ctx, alt, from) else {
            ok = false;
            continue;
        };
        if to == from {
            ctx.err(
                alt.span().start,
                format!("`{from}` is substituted by itself"),
            );
            ok = false;
            continue;
        }
        names.push((from.to_string(), k.span().start));
        names.push((to.clone(), alt.span().start));
        pairs.push((from.to_string(), to));
    }
    ok.then_some((pairs, names))
}

/// Where an axis's keys were written.
struct AxisSpans {
    tag: usize,
    min: usize,
    max: usize,
}

fn load_axis(ctx: &mut Ctx<'_>, t: &DeTable<'_>, header: usize) -> Option<(Axis, AxisSpans)> {
    let suggested = check_keys(ctx, t, &["tag", "name", "min", "default", "max", "map"]);
    let tag = require(ctx, t, "tag", "tag = \"wght\"", header, &suggested).and_then(|v| {
        let tag = string(ctx, v, "tag")?;
        let printable = tag.bytes().all(|b| (0x20..=0x7E).contains(&b));
        if (1..=4).contains(&tag.len()) && printable {
            Some((tag, v.span().start))
        } else {
            ctx.err(
                v.span().start,
                format!(
                    "`tag` must be 1 to 4 printable ASCII characters (an OpenType axis tag \
                     such as \"wght\"), found {tag:?}"
                ),
            );
            None
        }
    });
    let name = require(ctx, t, "name", "name = \"Weight\"", header, &suggested)
        .and_then(|v| non_empty(ctx, v, "name"));
    let value = |ctx: &mut Ctx<'_>, key: &str, example: &str| {
        require(ctx, t, key, example, header, &suggested)
            .and_then(|v| Some((number(ctx, v, key)?, v.span().start)))
    };
    let min = value(ctx, "min", "min = 400");
    let default = value(ctx, "default", "default = 400");
    let max = value(ctx, "max", "max = 700");
    let (Some((tag, tag_at)), Some((name, _)), Some((min, min_at)), Some((default, d_at))) =
        (tag, name, min, default)
    else {
        return None;
    };
    let (max, max_at) = max?;
    if min > max {
        ctx.err(
            min_at,
            format!(
                "`min` = {} is greater than `max` = {}",
                emit::number(min),
                emit::number(max)
            ),
        );
        return None;
    }
    if !(min..=max).contains(&default) {
        ctx.err(
            d_at,
            format!(
                "`default` = {} is outside the axis range {}..{}",
                emit::number(default),
                emit::number(min),
                emit::number(max)
            ),
        );
        return None;
    }
    let map = match get(t, "map") {
        Some(v) => axis_map(ctx, v, min, max)?,
        None => Vec::new(),
    };
    Some((
        Axis {
            tag,
            name,
            min,
            default,
            max,
            map,
        },
        AxisSpans {
            tag: tag_at,
            min: min_at,
            max: max_at,
        },
    ))
}

/// An axis `map`: `[user, design]` pairs from `min` to `max`, both values strictly
/// increasing (so that the map can be inverted, as a designspace's sources need), or `None`
/// with a diagnostic at the entry to fix.
fn axis_map(
    ctx: &mut Ctx<'_>,
    v: &Spanned<DeValue<'_>>,
    min: f64,
    max: f64,
) -> Option<Vec<(f64, f64)>> {
    const SHAPE: &str = "a list of [user, design] pairs such as [[400, 0], [550, 70], [700, 100]]";
    let DeValue::Array(entries) = v.get_ref() else {
        ctx.err(
            v.span().start,
            format!("`map` must be {SHAPE}, found {}", type_name(v.get_ref())),
        );
        return None;
    };
    let mut pairs: Vec<(f64, f64, usize)> = Vec::with_capacity(entries.len());
    let mut ok = true;
    for e in entries {
        let at = e.span().start;
        match e.get_ref() {
            DeValue::Array(p) if p.len() == 2 => {
                match (number(ctx, &p[0], "map"), number(ctx, &p[1], "map")) {
                    (Some(u), Some(d)) => pairs.push((u, d, at)),
                    _ => ok = false,
                }
            }
            other => {
                let found = match other {
                    DeValue::Array(p) => format!("an array of {} values", p.len()),
                    other => type_name(other).to_string(),
                };
                ctx.err(at, format!("`map` must be {SHAPE}, found {found}"));
                ok = false;
            }
        }
    }
    if !ok {
        return None;
    }
    let num = |x: f64| emit::number(x);
    let (Some(&(first, _, first_at)), Some(&(last, _, last_at))) = (pairs.first(), pairs.last())
    else {
        ctx.err(
            v.span().start,
            format!("`map` must be {SHAPE}, found an empty list; leave it out for a linear axis"),
        );
        return None;
    };
    for w in pairs.windows(2) {
        let ((u0, d0, _), (u1, d1, at)) = (w[0], w[1]);
        let (what, was, is) = if u1 <= u0 {
            ("user", u0, u1)
        } else if d1 <= d0 {
            ("design", d0, d1)
        } else {
            continue;
        };
        ctx.err(
            at,
            format!(
                "`map` {what} values must increase: {} follows {}",
                num(is),
                num(was)
            ),
        );
        return None;
    }
    if first != min {
        ctx.err(
            first_at,
            format!(
                "`map` must start at the axis `min` = {}, found user value {}",
                num(min),
                num(first)
            ),
        );
        return None;
    }
    if last != max {
        ctx.err(
            last_at,
            format!(
                "`map` must end at the axis `max` = {}, found user value {}",
                num(max),
                num(last)
            ),
        );
        return None;
    }
    Some(pairs.into_iter().map(|(u, d, _)| (u, d)).collect())
}

/// A `[[master]]`: the spec, and where its `name` and `location` were written.
fn load_master(
    ctx: &mut Ctx<'_>,
    t: &DeTable<'_>,
    header: usize,
    dir: &Path,
    axes: &[Axis],
) -> Option<(MasterSpec, usize, usize)> {
    let suggested = check_keys(ctx, t, &["name", "folder", "location", "sparse"]);
    let sparse = match get(t, "sparse") {
        None => Some(false),
        Some(v) => match v.get_ref() {
            DeValue::Boolean(b) => Some(*b),
            other => {
                ctx.err(
                    v.span().start,
                    format!("`sparse` must be true or false, found {}", type_name(other)),
                );
                None
            }
        },
    };
    let name = require(ctx, t, "name", "name = \"Bold\"", header, &suggested)
        .and_then(|v| non_empty(ctx, v, "name"));
    let folder = require(ctx, t, "folder", "folder = \"bold\"", header, &suggested)
        .and_then(|v| Some((string(ctx, v, "folder")?, v.span().start)))
        .and_then(|(f, at)| check_folder(ctx, dir, &f, at).then_some((f, at)));
    let loc = require(
        ctx,
        t,
        "location",
        "location = { wght = 700 }",
        header,
        &suggested,
    );
    let location_at = loc.map(|v| v.span().start);
    let location = loc.and_then(|v| location(ctx, v, axes));
    let ((name, name_at), (folder, folder_at), location, location_at, sparse) =
        (name?, folder?, location?, location_at?, sparse?);
    Some((
        MasterSpec {
            name,
            folder,
            location,
            folder_at,
            sparse,
        },
        name_at,
        location_at,
    ))
}

/// A master folder: relative, without `..`, inside the font folder (links followed), and
/// an existing folder. Reports and returns false otherwise.
fn check_folder(ctx: &mut Ctx<'_>, dir: &Path, folder: &str, at: usize) -> bool {
    let path = Path::new(folder);
    let why = if folder.trim().is_empty() {
        Some("`folder` must not be empty; name a sub-folder such as \"bold\"".to_string())
    } else if path.is_absolute() || path.has_root() {
        Some(format!(
            "`folder` must be relative to the font folder, found {folder:?}"
        ))
    } else if path.components().any(|c| c == Component::ParentDir) {
        Some(format!(
            "`folder` must stay inside the font folder (no `..`), found {folder:?}"
        ))
    } else if path.components().all(|c| c == Component::CurDir) {
        Some(
            "`folder` must be a sub-folder: the font folder itself is the default master"
                .to_string(),
        )
    } else {
        let full = dir.join(path);
        match (full.canonicalize(), dir.canonicalize()) {
            (Ok(f), Ok(d)) if !f.starts_with(&d) => Some(format!(
                "`folder` {folder:?} leads outside the font folder (through a link)"
            )),
            (Ok(f), _) if !f.is_dir() => Some(format!("`folder` {folder:?} is not a folder")),
            (Ok(_), _) => None,
            (Err(_), _) => Some(format!("master folder {} not found", full.display())),
        }
    };
    match why {
        Some(why) => {
            ctx.err(at, why);
            false
        }
        None => true,
    }
}

/// A location: an inline table of axis tag = user value, each a known axis, inside its
/// range.
fn location(ctx: &mut Ctx<'_>, v: &Spanned<DeValue<'_>>, axes: &[Axis]) -> Option<Location> {
    let DeValue::Table(t) = v.get_ref() else {
        ctx.err(
            v.span().start,
            format!(
                "`location` must be a table of axis values such as {{ wght = 700 }}, found {}",
                type_name(v.get_ref())
            ),
        );
        return None;
    };
    let mut ok = true;
    let mut out = BTreeMap::new();
    for (k, value) in t.iter() {
        let tag: &str = k.get_ref();
        let Some(axis) = axes.iter().find(|a| a.tag == tag) else {
            let known: Vec<String> = axes.iter().map(|a| format!("`{}`", a.tag)).collect();
            ctx.err(
                k.span().start,
                format!(
                    "unknown axis `{tag}` in `location`; the axes are {}",
                    known.join(", ")
                ),
            );
            ok = false;
            continue;
        };
        let Some(x) = number(ctx, value, tag) else {
            ok = false;
            continue;
        };
        if !(axis.min..=axis.max).contains(&x) {
            ctx.err(
                value.span().start,
                format!(
                    "{tag} = {} is outside the axis range {}..{}",
                    emit::number(x),
                    emit::number(axis.min),
                    emit::number(axis.max)
                ),
            );
            ok = false;
            continue;
        }
        out.insert(tag.to_string(), x);
    }
    ok.then_some(Location(out))
}

/// A non-empty string and where it was written.
fn non_empty(ctx: &mut Ctx<'_>, v: &Spanned<DeValue<'_>>, key: &str) -> Option<(String, usize)> {
    let s = string(ctx, v, key)?;
    if s.trim().is_empty() {
        ctx.err(v.span().start, format!("`{key}` must not be empty"));
        return None;
    }
    Some((s, v.span().start))
}

/// `location` as `font.toml` writes it, e.g. `wght = 700, wdth = 75` (every axis).
fn describe(designspace: &Designspace, location: &Location) -> String {
    designspace
        .axes
        .iter()
        .map(|a| format!("{} = {}", a.tag, emit::number(location.get(a))))
        .collect::<Vec<_>>()
        .join(", ")
}

/// Reports why the master set cannot blend, at the master's `location`.
fn region_error(
    ctx: &mut Ctx<'_>,
    e: &RegionError,
    designspace: &Designspace,
    masters: &[(MasterSpec, usize, usize)],
) {
    match *e {
        RegionError::AtDefault { master } => {
            let (m, _, at) = &masters[master];
            ctx.err(
                *at,
                format!(
                    "master `{}` is at the default location ({}), where the font folder itself \
                     is the default master; move it along an axis",
                    m.name,
                    describe(designspace, &m.location)
                ),
            );
        }
        RegionError::Duplicate { first, second } => {
            let (m, _, at) = &masters[second];
            ctx.err(
                *at,
                format!(
                    "master `{}` is at the same location as master `{}` ({})",
                    m.name,
                    masters[first].0.name,
                    describe(designspace, &m.location)
                ),
            );
        }
    }
}

/// Warns about each axis end without a master on that axis alone, at that end's `min` or
/// `max`: past the outermost master the design blends back to the default, which is
/// seldom meant. An end where only sparse masters sit gets its own warning: the glyphs
/// they do not draw blend back there.
fn uncovered_end_warnings(
    ctx: &mut Ctx<'_>,
    designspace: &Designspace,
    masters: &[(MasterSpec, usize, usize)],
    axes: &[(Axis, AxisSpans)],
) {
    let all: Vec<Location> = masters.iter().map(|m| m.0.location.clone()).collect();
    let full: Vec<Location> = masters
        .iter()
        .filter(|m| !m.0.sparse)
        .map(|m| m.0.location.clone())
        .collect();
    let uncovered = designspace.uncovered_ends(&all);
    // A location on axis `axis` alone (the others at their defaults).
    let on_axis = |l: &Location, axis: usize| {
        designspace
            .axes
            .iter()
            .enumerate()
            .all(|(k, b)| k == axis || l.get(b) == b.default)
    };
    for (axis, user) in designspace.uncovered_ends(&full) {
        let (a, spans) = &axes[axis];
        let (key, at) = if user == a.max {
            ("max", spans.max)
        } else {
            ("min", spans.min)
        };
        let end = emit::number(user);
        if !uncovered.contains(&(axis, user)) {
            let sparse = masters
                .iter()
                .find(|(m, _, _)| {
                    m.sparse && m.location.get(a) == user && on_axis(&m.location, axis)
                })
                .map_or_else(String::new, |(m, _, _)| m.name.clone());
            ctx.warn(
                at,
                format!(
                    "axis `{}` ends at {key} = {end} where only sparse master `{sparse}` is: a \
                     glyph it does not draw blends back to the default there, past the \
                     outermost master that draws it",
                    a.tag
                ),
            );
            continue;
        }
        // The outermost master on this axis alone, on that side of the default.
        let outermost = masters
            .iter()
            .filter(|(m, _, _)| {
                let v = m.location.get(a);
                on_axis(&m.location, axis) && (v - a.default) * (user - a.default) > 0.0
            })
            .max_by(|x, y| {
                let d = |m: &MasterSpec| (m.location.get(a) - a.default).abs();
                d(&x.0).total_cmp(&d(&y.0))
            });
        let what = match outermost {
            Some((m, _, _)) => {
                let v = emit::number(m.location.get(a));
                format!(
                    "past master `{}` ({} = {v}) the design blends back to the default, \
                     which it reaches at {end}, as fontmake and fontc build it; add a \
                     `[[master]]` with location {{ {} = {end} }}, or set {key} to {v}",
                    m.name, a.tag, a.tag
                )
            }
            None => {
                // A corner master at that end does not cover it: its delta is what it
                // adds to the masters on each of its axes.
                let corner = masters
                    .iter()
                    .find(|(m, _, _)| m.location.get(a) == user)
                    .map(|(m, _, _)| {
                        format!(
                            " (only corner master `{}`, which blends from the masters on \
                             each of its axes)",
                            m.name
                        )
                    })
                    .unwrap_or_default();
                format!(
                    "no master on this axis alone is on that side, so along the axis the \
                     design stays the default there{corner}; add a `[[master]]` with location \
                     {{ {} = {end} }}, or set {key} to the default",
                    a.tag
                )
            }
        };
        ctx.warn(
            at,
            format!(
                "axis `{}` ends at {key} = {end} but no master is there: {what}",
                a.tag
            ),
        );
    }
}
