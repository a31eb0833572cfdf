//! Loading a font directory into the typed model, collecting diagnostics.

use std::collections::{BTreeMap, HashMap, HashSet};
use std::fmt;
use std::path::{Path, PathBuf};

use toml::de::{DeTable, DeValue};
use toml::Spanned;

use crate::model::{Component, Contour, Font, FontInfo, Glyph, KernPair};
use crate::xspline::ControlPoint;

/// How serious a diagnostic is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Severity {
    Error,
    Warning,
}

/// One problem found in the sources, with a 1-based line and column.
#[derive(Clone, Debug, PartialEq)]
pub struct Diagnostic {
    pub path: PathBuf,
    pub line: usize,
    pub col: usize,
    pub severity: Severity,
    pub message: String,
}

impl fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let sev = match self.severity {
            Severity::Error => "error",
            Severity::Warning => "warning",
        };
        write!(
            f,
            "{}:{}:{}: {}: {}",
            self.path.display(),
            self.line,
            self.col,
            sev,
            self.message
        )
    }
}

/// Diagnostics being gathered for one file.
struct Ctx<'a> {
    path: &'a Path,
    text: &'a str,
    out: &'a mut Vec<Diagnostic>,
}

impl Ctx<'_> {
    fn at(&mut self, offset: usize, severity: Severity, message: String) {
        let (line, col) = line_col(self.text, offset);
        self.out.push(Diagnostic {
            path: self.path.to_path_buf(),
            line,
            col,
            severity,
            message,
        });
    }
    fn err(&mut self, offset: usize, message: impl Into<String>) {
        self.at(offset, Severity::Error, message.into());
    }
}

/// 1-based line and column (in characters) of a byte offset.
pub fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let mut off = offset.min(text.len());
    while !text.is_char_boundary(off) {
        off -= 1;
    }
    let before = &text[..off];
    let line = before.matches('\n').count() + 1;
    let start = before.rfind('\n').map_or(0, |i| i + 1);
    (line, before[start..].chars().count() + 1)
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

fn check_keys(ctx: &mut Ctx<'_>, table: &DeTable<'_>, allowed: &[&str]) {
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
            Some((d, a)) if d <= 2 => format!("unknown key `{key}`; did you mean `{a}`?"),
            _ => format!("unknown key `{key}`"),
        };
        ctx.err(k.span().start, msg);
    }
}

fn get<'t, 'i>(table: &'t DeTable<'i>, key: &str) -> Option<&'t Spanned<DeValue<'i>>> {
    table
        .iter()
        .find(|(k, _)| k.get_ref() == key)
        .map(|(_, v)| v)
}

/// A number (integer or float) from a value, or `None` with a diagnostic.
fn number(ctx: &mut Ctx<'_>, v: &Spanned<DeValue<'_>>, what: &str) -> Option<f64> {
    let x = match v.get_ref() {
        DeValue::Integer(i) => {
            let digits = i.as_str().replace('_', "");
            i64::from_str_radix(&digits, i.radix())
                .ok()
                .map(|n| n as f64)
        }
        DeValue::Float(f) => {
            let s = f.as_str().replace('_', "");
            match s.trim_start_matches(['+', '-']) {
                "inf" | "nan" => Some(f64::NAN),
                _ => s.parse::<f64>().ok(),
            }
        }
        other => {
            ctx.err(
                v.span().start,
                format!("`{what}` must be a number, found {}", other.type_str()),
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

fn integer(ctx: &mut Ctx<'_>, v: &Spanned<DeValue<'_>>, what: &str) -> Option<i64> {
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
                format!("`{what}` must be an integer, found {}", other.type_str()),
            );
            None
        }
    }
}

fn string(ctx: &mut Ctx<'_>, v: &Spanned<DeValue<'_>>, what: &str) -> Option<String> {
    match v.get_ref() {
        DeValue::String(s) => Some(s.to_string()),
        other => {
            ctx.err(
                v.span().start,
                format!("`{what}` must be a string, found {}", other.type_str()),
            );
            None
        }
    }
}

fn parse_text<'i>(ctx: &mut Ctx<'_>, text: &'i str) -> Option<Spanned<DeTable<'i>>> {
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

fn read(path: &Path, out: &mut Vec<Diagnostic>) -> Option<String> {
    match std::fs::read_to_string(path) {
        Ok(s) => Some(s),
        Err(e) => {
            out.push(Diagnostic {
                path: path.to_path_buf(),
                line: 1,
                col: 1,
                severity: Severity::Error,
                message: format!("cannot read file: {e}"),
            });
            None
        }
    }
}

const FONT_KEYS: &[&str] = &[
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
];

fn load_info(path: &Path, text: &str, out: &mut Vec<Diagnostic>) -> Option<FontInfo> {
    let mut ctx = Ctx { path, text, out };
    let table = parse_text(&mut ctx, text)?;
    let t = table.get_ref();
    check_keys(&mut ctx, t, FONT_KEYS);
    let mut ok = true;
    let mut req_num = |ctx: &mut Ctx<'_>, key: &str| -> f64 {
        match get(t, key) {
            Some(v) => number(ctx, v, key).unwrap_or_else(|| {
                ok = false;
                0.0
            }),
            None => {
                ctx.err(0, format!("missing required key `{key}`"));
                ok = false;
                0.0
            }
        }
    };
    let upm = req_num(&mut ctx, "units_per_em");
    let ascender = req_num(&mut ctx, "ascender");
    let descender = req_num(&mut ctx, "descender");
    let x_height = req_num(&mut ctx, "x_height");
    let cap_height = req_num(&mut ctx, "cap_height");
    let mut ok2 = true;
    let tolerance = match get(t, "tolerance") {
        Some(v) => match number(&mut ctx, v, "tolerance") {
            Some(x) if x > 0.0 => x,
            Some(_) => {
                ctx.err(v.span().start, "`tolerance` must be positive");
                ok2 = false;
                0.5
            }
            None => {
                ok2 = false;
                0.5
            }
        },
        None => 0.5,
    };
    if let Some(v) = get(t, "units_per_em") {
        if !(16.0..=16384.0).contains(&upm) || upm.fract() != 0.0 {
            if ok {
                ctx.err(
                    v.span().start,
                    "`units_per_em` must be an integer in 16..16384",
                );
            }
            ok2 = false;
        }
    }
    if ok && ascender <= descender {
        let off = get(t, "ascender").map_or(0, |v| v.span().start);
        ctx.err(off, "`ascender` must be greater than `descender`");
        ok2 = false;
    }
    let family = match get(t, "family") {
        Some(v) => string(&mut ctx, v, "family"),
        None => {
            ctx.err(0, "missing required key `family`");
            None
        }
    };
    let opt = |ctx: &mut Ctx<'_>, key: &str| -> Result<Option<String>, ()> {
        match get(t, key) {
            Some(v) => string(ctx, v, key).map(Some).ok_or(()),
            None => Ok(None),
        }
    };
    let style = opt(&mut ctx, "style");
    let copyright = opt(&mut ctx, "copyright");
    let designer = opt(&mut ctx, "designer");
    let version = opt(&mut ctx, "version");
    let (Some(family), Ok(style), Ok(copyright), Ok(designer), Ok(version)) =
        (family, style, copyright, designer, version)
    else {
        return None;
    };
    if !ok || !ok2 {
        return None;
    }
    Some(FontInfo {
        family,
        style: style.unwrap_or_else(|| "Regular".to_string()),
        units_per_em: upm as u16,
        ascender,
        descender,
        x_height,
        cap_height,
        tolerance,
        copyright,
        designer,
        version,
    })
}

/// A glyph plus where its name and code points were written.
struct Loaded {
    glyph: Glyph,
    path: PathBuf,
    text: String,
    name_off: usize,
    unicode_offs: Vec<usize>,
    base_offs: Vec<usize>,
}

fn load_points(ctx: &mut Ctx<'_>, v: &Spanned<DeValue<'_>>) -> Option<Vec<ControlPoint>> {
    let DeValue::Array(arr) = v.get_ref() else {
        ctx.err(v.span().start, "`points` must be an array of [x, y, s]");
        return None;
    };
    let mut pts = Vec::new();
    let mut offs = Vec::new();
    let mut ok = true;
    for p in arr {
        let items = match p.get_ref() {
            DeValue::Array(a) if a.len() == 3 => a,
            _ => {
                ctx.err(p.span().start, "a point must be an array [x, y, s]");
                ok = false;
                continue;
            }
        };
        let x = number(ctx, &items[0], "x");
        let y = number(ctx, &items[1], "y");
        let s = number(ctx, &items[2], "s");
        if let Some(s) = s {
            if !(-1.0..=1.0).contains(&s) {
                ctx.err(items[2].span().start, format!("s = {s} is outside [-1, 1]"));
                ok = false;
            }
        }
        match (x, y, s) {
            (Some(x), Some(y), Some(s)) => {
                pts.push(ControlPoint::new(x, y, s));
                offs.push(p.span().start);
            }
            _ => ok = false,
        }
    }
    if !ok {
        return None;
    }
    if pts.len() < 3 {
        ctx.err(
            v.span().start,
            format!("a contour needs at least 3 points, found {}", pts.len()),
        );
        return None;
    }
    let n = pts.len();
    let mut coincident = false;
    for i in 0..n {
        let j = (i + 1) % n;
        if pts[i].pos.x == pts[j].pos.x && pts[i].pos.y == pts[j].pos.y {
            ctx.err(
                offs[j],
                format!("point {j} coincides with point {i} before it"),
            );
            coincident = true;
        }
    }
    (!coincident).then_some(pts)
}

fn load_glyph(path: &Path, text: String, out: &mut Vec<Diagnostic>) -> Option<Loaded> {
    let stem = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    let mut ctx = Ctx {
        path,
        text: &text,
        out,
    };
    let table = parse_text(&mut ctx, &text)?;
    let t = table.get_ref();
    check_keys(
        &mut ctx,
        t,
        &["name", "unicode", "advance", "contour", "component"],
    );
    let mut ok = true;
    let (name, name_off) = match get(t, "name") {
        Some(v) => match string(&mut ctx, v, "name") {
            Some(n) if !n.is_empty() => (n, v.span().start),
            Some(_) => {
                ctx.err(v.span().start, "`name` must not be empty");
                ok = false;
                (stem, 0)
            }
            None => {
                ok = false;
                (stem, 0)
            }
        },
        None => (stem, 0),
    };
    let mut unicodes = Vec::new();
    let mut unicode_offs = Vec::new();
    if let Some(v) = get(t, "unicode") {
        let items: Vec<&Spanned<DeValue<'_>>> = match v.get_ref() {
            DeValue::Array(a) => a.iter().collect(),
            _ => vec![v],
        };
        for it in items {
            let Some(n) = integer(&mut ctx, it, "unicode") else {
                ok = false;
                continue;
            };
            match u32::try_from(n).ok().and_then(char::from_u32) {
                Some(c) => {
                    unicodes.push(c);
                    unicode_offs.push(it.span().start);
                }
                None => {
                    ctx.err(it.span().start, format!("invalid code point {n:#X}"));
                    ok = false;
                }
            }
        }
    }
    let advance = match get(t, "advance") {
        Some(v) => match number(&mut ctx, v, "advance") {
            Some(a) => a,
            None => {
                ok = false;
                0.0
            }
        },
        None => {
            ctx.err(0, "missing required key `advance`");
            ok = false;
            0.0
        }
    };
    let mut contours = Vec::new();
    if let Some(v) = get(t, "contour") {
        match v.get_ref() {
            DeValue::Array(a) => {
                for c in a {
                    let DeValue::Table(ct) = c.get_ref() else {
                        ctx.err(c.span().start, "`contour` entries must be tables");
                        ok = false;
                        continue;
                    };
                    check_keys(&mut ctx, ct, &["points"]);
                    match get(ct, "points") {
                        Some(p) => match load_points(&mut ctx, p) {
                            Some(points) => contours.push(Contour { points }),
                            None => ok = false,
                        },
                        None => {
                            ctx.err(c.span().start, "contour is missing `points`");
                            ok = false;
                        }
                    }
                }
            }
            _ => {
                ctx.err(v.span().start, "`contour` must be an array of tables");
                ok = false;
            }
        }
    }
    let mut components = Vec::new();
    let mut base_offs = Vec::new();
    if let Some(v) = get(t, "component") {
        match v.get_ref() {
            DeValue::Array(a) => {
                for c in a {
                    let DeValue::Table(ct) = c.get_ref() else {
                        ctx.err(c.span().start, "`component` entries must be tables");
                        ok = false;
                        continue;
                    };
                    check_keys(&mut ctx, ct, &["base", "offset"]);
                    let base = match get(ct, "base") {
                        Some(b) => string(&mut ctx, b, "base").map(|s| (s, b.span().start)),
                        None => {
                            ctx.err(c.span().start, "component is missing `base`");
                            None
                        }
                    };
                    let offset = match get(ct, "offset") {
                        Some(o) => match o.get_ref() {
                            DeValue::Array(xy) if xy.len() == 2 => {
                                match (number(&mut ctx, &xy[0], "x"), number(&mut ctx, &xy[1], "y"))
                                {
                                    (Some(x), Some(y)) => Some((x, y)),
                                    _ => None,
                                }
                            }
                            _ => {
                                ctx.err(o.span().start, "`offset` must be an array [x, y]");
                                None
                            }
                        },
                        None => Some((0.0, 0.0)),
                    };
                    match (base, offset) {
                        (Some((base, off)), Some(offset)) => {
                            components.push(Component { base, offset });
                            base_offs.push(off);
                        }
                        _ => ok = false,
                    }
                }
            }
            _ => {
                ctx.err(v.span().start, "`component` must be an array of tables");
                ok = false;
            }
        }
    }
    if !ok {
        return None;
    }
    if contours.is_empty() && components.is_empty() && advance == 0.0 {
        ctx.at(
            0,
            Severity::Warning,
            format!("glyph `{name}` is empty: no contours, no components and advance 0"),
        );
    }
    drop(table);
    Some(Loaded {
        glyph: Glyph {
            name,
            unicodes,
            advance,
            contours,
            components,
        },
        path: path.to_path_buf(),
        text,
        name_off,
        unicode_offs,
        base_offs,
    })
}

fn load_kerning(
    path: &Path,
    text: &str,
    names: &HashSet<String>,
    out: &mut Vec<Diagnostic>,
) -> Option<Vec<KernPair>> {
    let mut ctx = Ctx { path, text, out };
    let table = parse_text(&mut ctx, text)?;
    let t = table.get_ref();
    check_keys(&mut ctx, t, &["pair"]);
    let mut ok = true;
    let mut pairs = Vec::new();
    if let Some(v) = get(t, "pair") {
        let DeValue::Array(a) = v.get_ref() else {
            ctx.err(v.span().start, "`pair` must be an array of tables");
            return None;
        };
        for p in a {
            let DeValue::Table(pt) = p.get_ref() else {
                ctx.err(p.span().start, "`pair` entries must be tables");
                ok = false;
                continue;
            };
            check_keys(&mut ctx, pt, &["left", "right", "value"]);
            let side = |ctx: &mut Ctx<'_>, key: &str| -> Option<String> {
                let Some(v) = get(pt, key) else {
                    ctx.err(p.span().start, format!("pair is missing `{key}`"));
                    return None;
                };
                let s = string(ctx, v, key)?;
                if !names.contains(&s) {
                    ctx.err(v.span().start, format!("unknown glyph `{s}`"));
                    return None;
                }
                Some(s)
            };
            let left = side(&mut ctx, "left");
            let right = side(&mut ctx, "right");
            let value = match get(pt, "value") {
                Some(v) => number(&mut ctx, v, "value"),
                None => {
                    ctx.err(p.span().start, "pair is missing `value`");
                    None
                }
            };
            match (left, right, value) {
                (Some(left), Some(right), Some(value)) => {
                    pairs.push(KernPair { left, right, value })
                }
                _ => ok = false,
            }
        }
    }
    ok.then_some(pairs)
}

/// Load a font directory: `font.toml`, optional `kerning.toml`, and one glyph per other
/// `*.toml`. Returns the font and its warnings, or every diagnostic when there are errors.
pub fn load_font(dir: &Path) -> Result<(Font, Vec<Diagnostic>), Vec<Diagnostic>> {
    let mut out = Vec::new();
    let font_path = dir.join("font.toml");
    let info = read(&font_path, &mut out).and_then(|t| load_info(&font_path, &t, &mut out));
    let mut files: Vec<PathBuf> = match std::fs::read_dir(dir) {
        Ok(rd) => rd
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| p.extension().is_some_and(|e| e == "toml"))
            .filter(|p| {
                let f = p.file_name().map(|f| f.to_string_lossy().into_owned());
                f.as_deref() != Some("font.toml") && f.as_deref() != Some("kerning.toml")
            })
            .collect(),
        Err(_) => Vec::new(),
    };
    files.sort();
    let mut loaded = Vec::new();
    let mut glyph_failed = false;
    for f in &files {
        match read(f, &mut out).and_then(|t| load_glyph(f, t, &mut out)) {
            Some(l) => loaded.push(l),
            None => glyph_failed = true,
        }
    }
    // Duplicate names and code points.
    let mut seen_names: HashMap<String, PathBuf> = HashMap::new();
    let mut seen_cps: HashMap<char, String> = HashMap::new();
    for l in &loaded {
        let mut ctx = Ctx {
            path: &l.path,
            text: &l.text,
            out: &mut out,
        };
        if let Some(prev) = seen_names.get(&l.glyph.name) {
            ctx.err(
                l.name_off,
                format!(
                    "duplicate glyph name `{}` (also in {})",
                    l.glyph.name,
                    prev.display()
                ),
            );
        } else {
            seen_names.insert(l.glyph.name.clone(), l.path.clone());
        }
        for (c, off) in l.glyph.unicodes.iter().zip(&l.unicode_offs) {
            if let Some(prev) = seen_cps.get(c) {
                ctx.err(
                    *off,
                    format!(
                        "code point U+{:04X} is already mapped to `{prev}`",
                        u32::from(*c)
                    ),
                );
            } else {
                seen_cps.insert(*c, l.glyph.name.clone());
            }
        }
    }
    // Components: missing bases and cycles.
    let graph: BTreeMap<&str, Vec<&str>> = loaded
        .iter()
        .map(|l| {
            (
                l.glyph.name.as_str(),
                l.glyph.components.iter().map(|c| c.base.as_str()).collect(),
            )
        })
        .collect();
    for l in &loaded {
        let mut ctx = Ctx {
            path: &l.path,
            text: &l.text,
            out: &mut out,
        };
        for (c, off) in l.glyph.components.iter().zip(&l.base_offs) {
            if !graph.contains_key(c.base.as_str()) {
                ctx.err(*off, format!("component base `{}` does not exist", c.base));
            } else if reaches(&graph, &c.base, &l.glyph.name) {
                ctx.err(
                    *off,
                    format!(
                        "component cycle: `{}` uses `{}`, which leads back to it",
                        l.glyph.name, c.base
                    ),
                );
            }
        }
    }
    let names: HashSet<String> = loaded.iter().map(|l| l.glyph.name.clone()).collect();
    let kern_path = dir.join("kerning.toml");
    let kerning = if kern_path.exists() {
        read(&kern_path, &mut out).and_then(|t| load_kerning(&kern_path, &t, &names, &mut out))
    } else {
        Some(Vec::new())
    };
    if out.iter().any(|d| d.severity == Severity::Error) || glyph_failed {
        return Err(out);
    }
    let (Some(info), Some(kerning)) = (info, kerning) else {
        return Err(out);
    };
    let mut glyphs: Vec<Glyph> = loaded.into_iter().map(|l| l.glyph).collect();
    glyphs.sort_by(|a, b| (a.name != ".notdef", &a.name).cmp(&(b.name != ".notdef", &b.name)));
    Ok((
        Font {
            info,
            glyphs,
            kerning,
        },
        out,
    ))
}

/// Whether `target` is reachable from `from` along component edges.
fn reaches(graph: &BTreeMap<&str, Vec<&str>>, from: &str, target: &str) -> bool {
    let mut stack = vec![from];
    let mut seen = HashSet::new();
    while let Some(n) = stack.pop() {
        if n == target {
            return true;
        }
        if seen.insert(n) {
            if let Some(next) = graph.get(n) {
                stack.extend(next.iter().copied());
            }
        }
    }
    false
}
