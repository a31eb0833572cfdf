//! TrueType/OpenType fonts (ttf-parser) -> original outlines, advances, code points, metrics.
//!
//! Quadratic (`glyf`) and cubic (`CFF`) outlines both arrive as kurbo paths in font units
//! (y up). Composite glyphs arrive flattened (ttf-parser resolves them), so they import as
//! plain contours. Limits: one font of a collection at a time; a variable font's masters
//! are read by `variable.rs` (this module gives its names, metrics and code points);
//! metrics from hhea/OS/2 as ttf-parser reports them. A collection (.ttc, .otc) gives one
//! of its fonts, by index.

use std::collections::BTreeMap;
use std::path::Path;

use kurbo::BezPath;
use ttf_parser::{name_id, Face, GlyphId, OutlineBuilder};

use super::{ImportError, SourceGlyph};
use crate::model::FontInfo;
use crate::source::DEFAULT_TOLERANCE;

/// What [`read_font`] found: names and metrics, glyphs in code point order, and notes on
/// requested characters the font does not have.
#[derive(Clone, Debug)]
pub struct SourceFont {
    /// Names and vertical metrics; `tolerance` is the default until the importer sets it.
    pub info: FontInfo,
    /// The glyphs asked for, with their outlines.
    pub glyphs: Vec<SourceGlyph>,
    /// Characters asked for (`--glyphs`) that the font does not map.
    pub missing: Vec<char>,
    /// Notes on visible characters whose glyph the font leaves empty (imported empty).
    pub empty: Vec<String>,
    /// The glyph id of each of `glyphs`, in the same order.
    pub ids: Vec<u16>,
}

/// Parses a glyph list: comma-separated characters and inclusive ranges, e.g.
/// `A-Z,a-z,0-9`; `U+0041` and `U+0041-U+005A` also work. A lone `-` is the hyphen.
pub fn parse_glyph_list(list: &str) -> Result<Vec<char>, ImportError> {
    let mut out = Vec::new();
    for item in list.split(',') {
        if item.is_empty() {
            continue;
        }
        let (lo, hi) = match split_range(item) {
            Some((a, b)) => (one_char(a, list)?, one_char(b, list)?),
            None => {
                let c = one_char(item, list)?;
                (c, c)
            }
        };
        if lo > hi {
            return Err(ImportError::plain(format!(
                "glyph list: range `{item}` runs backwards (write `{hi}-{lo}`)"
            )));
        }
        out.extend((u32::from(lo)..=u32::from(hi)).filter_map(char::from_u32));
    }
    out.sort_unstable();
    out.dedup();
    if out.is_empty() {
        return Err(ImportError::plain(format!(
            "glyph list `{list}` names no character"
        )));
    }
    Ok(out)
}

/// `a-b` with a non-empty side on both ends of one `-` (so `-` alone is a character).
fn split_range(item: &str) -> Option<(&str, &str)> {
    let chars: Vec<(usize, char)> = item.char_indices().collect();
    chars
        .iter()
        .skip(1)
        .find(|&&(_, c)| c == '-')
        .map(|&(i, _)| (&item[..i], &item[i + 1..]))
        .filter(|(_, b)| !b.is_empty())
}

fn one_char(s: &str, list: &str) -> Result<char, ImportError> {
    let bad = || {
        ImportError::plain(format!(
            "glyph list `{list}`: `{s}` is not one character or U+XXXX code point"
        ))
    };
    if let Some(hex) = s.strip_prefix("U+").or_else(|| s.strip_prefix("u+")) {
        return u32::from_str_radix(hex, 16)
            .ok()
            .and_then(char::from_u32)
            .ok_or_else(bad);
    }
    let mut it = s.chars();
    match (it.next(), it.next()) {
        (Some(c), None) => Ok(c),
        _ => Err(bad()),
    }
}

/// Reads `chars` (or every mapped character when `None`) from the font bytes `data`; font
/// `index` of a collection (0 for a single font). `extra` gives, from the mapped glyph ids,
/// glyphs without a character to read too (named from `post`, else `glyph00123`).
pub fn read_font(
    path: &Path,
    data: &[u8],
    index: u32,
    chars: Option<&[char]>,
    extra: impl Fn(&[u16]) -> Vec<u16>,
) -> Result<SourceFont, ImportError> {
    if let Some(count) = ttf_parser::fonts_in_collection(data) {
        if index >= count {
            return Err(ImportError::at(
                path,
                format!(
                    "--face {index}: this collection has {count} fonts (--face 0 to {})",
                    count.saturating_sub(1)
                ),
            ));
        }
    } else if index > 0 {
        return Err(ImportError::at(
            path,
            format!("--face {index}: this is a single font, not a collection"),
        ));
    }
    let face = Face::parse(data, index).map_err(|e| {
        ImportError::at(path, format!("not a readable TrueType/OpenType font ({e})"))
    })?;
    let info = read_info(&face);
    let wanted: Vec<char> = match chars {
        Some(list) => list.to_vec(),
        None => mapped_chars(&face),
    };
    // Several characters can share one glyph; group them by glyph id.
    let mut by_glyph: BTreeMap<u16, Vec<char>> = BTreeMap::new();
    let mut missing = Vec::new();
    for &c in &wanted {
        match face.glyph_index(c) {
            Some(gid) if gid.0 != 0 => by_glyph.entry(gid.0).or_default().push(c),
            // A whole-font import lists the code points of the cmap's segments, and a
            // format-4 segment can map some of its range to glyph 0: those are not mapped
            // (fontTools leaves them out too), so they are no news to the user.
            _ if chars.is_none() => {}
            _ => missing.push(c),
        }
    }
    let mut glyphs = Vec::new();
    let mut ids = Vec::new();
    let mut used_names = std::collections::BTreeSet::new();
    let mut empty = Vec::new();
    // Glyphs without a character of their own come after: `extra` of the mapped ones
    // (rules' alternates).
    let mapped: Vec<u16> = by_glyph.keys().copied().collect();
    let unmapped: Vec<(u16, Vec<char>)> = extra(&mapped)
        .into_iter()
        .filter(|g| !by_glyph.contains_key(g))
        .map(|g| (g, Vec::new()))
        .collect();
    for (gid, unicodes) in by_glyph.into_iter().chain(unmapped) {
        let gid = GlyphId(gid);
        let name = glyph_name(&face, gid, unicodes.first().copied(), &used_names);
        used_names.insert(name.clone());
        let advance = face.glyph_hor_advance(gid).ok_or_else(|| {
            ImportError::at(
                path,
                format!("glyph `{name}` has no horizontal advance (damaged hmtx table)"),
            )
        })?;
        // ttf-parser gives `None` both for an empty glyph (a space, or a letter a font
        // leaves blank) and for an outline it cannot read; skrifa, which reports read
        // errors, tells the two apart.
        let outline = match glyph_outline(&face, gid) {
            Some(outline) => outline,
            None if unicodes.iter().any(|&c| visible(c)) => {
                let skrifa_font = skrifa::FontRef::from_index(data, index).ok();
                if !skrifa_font.is_some_and(|f| stores_no_outline(&f, gid.0)) {
                    return Err(ImportError::at(
                        path,
                        format!(
                            "glyph `{name}` (U+{:04X}) has no readable outline; \
                             the font may be damaged",
                            u32::from(unicodes[0])
                        ),
                    ));
                }
                empty.push(format!(
                    "glyph `{name}` (U+{:04X}) is empty in the font",
                    u32::from(unicodes[0])
                ));
                BezPath::new()
            }
            None => BezPath::new(),
        };
        if !outline.is_finite() {
            return Err(ImportError::at(
                path,
                format!("glyph `{name}` has non-finite coordinates"),
            ));
        }
        check_limits(path, &name, f64::from(advance), &outline)?;
        ids.push(gid.0);
        glyphs.push(SourceGlyph {
            name,
            unicodes,
            advance: f64::from(advance),
            path: outline,
        });
    }
    Ok(SourceFont {
        info,
        glyphs,
        missing,
        empty,
        ids,
    })
}

impl SourceFont {
    /// The import report's notes on the characters read: one per character asked for that
    /// the font lacks, then one per glyph left empty.
    pub fn notes(&self) -> Vec<String> {
        let mut notes: Vec<String> = self
            .missing
            .iter()
            .map(|c| format!("no glyph for '{c}' (U+{:04X}) in the font", u32::from(*c)))
            .collect();
        notes.extend(self.empty.iter().cloned());
        notes
    }
}

/// Refuses a glyph that the sources could not hold ([`crate::source::limits`]): an
/// advance above 32767 or a point beyond ±16384 font units (legal in a TrueType font, but
/// only a damaged or extreme one has them).
fn check_limits(
    path: &Path,
    name: &str,
    advance: f64,
    outline: &kurbo::BezPath,
) -> Result<(), ImportError> {
    use crate::source::limits::{MAX_ADVANCE, MAX_COORDINATE};
    use kurbo::Shape;
    if advance > MAX_ADVANCE {
        return Err(ImportError::at(
            path,
            format!(
                "glyph `{name}` has advance {advance}, more than the {MAX_ADVANCE} font units \
                 xglyph sources hold; the font may be damaged"
            ),
        ));
    }
    let b = outline.bounding_box();
    let far = [b.x0, b.x1, b.y0, b.y1]
        .into_iter()
        .find(|v| v.abs() > MAX_COORDINATE);
    if let (false, Some(v)) = (outline.is_empty(), far) {
        return Err(ImportError::at(
            path,
            format!(
                "glyph `{name}` reaches {v}, outside the -{MAX_COORDINATE}..{MAX_COORDINATE} \
                 font units xglyph sources hold; the font may be damaged"
            ),
        ));
    }
    Ok(())
}

/// Every character of the font's Unicode cmap subtables, in order.
fn mapped_chars(face: &Face) -> Vec<char> {
    let mut set = std::collections::BTreeSet::new();
    if let Some(cmap) = face.tables().cmap {
        for sub in cmap.subtables {
            if sub.is_unicode() {
                sub.codepoints(|cp| {
                    if let Some(c) = char::from_u32(cp) {
                        set.insert(c);
                    }
                });
            }
        }
    }
    set.into_iter().collect()
}

/// The post-table name when it follows the glyph-name rule ([`crate::names`]), else
/// `uniXXXX` from the first code point; unique within the import.
fn glyph_name(
    face: &Face,
    gid: GlyphId,
    first: Option<char>,
    used: &std::collections::BTreeSet<String>,
) -> String {
    let stored = face
        .glyph_name(gid)
        .filter(|n| crate::names::is_valid_glyph_name(n))
        .map(str::to_string);
    let base = stored.unwrap_or_else(|| match first {
        Some(c) => format!("uni{:04X}", u32::from(c)),
        None => format!("glyph{:05}", gid.0),
    });
    let mut name = base.clone();
    let mut k = 1;
    while used.contains(&name) {
        name = format!("{base}.{k}");
        k += 1;
    }
    name
}

fn read_info(face: &Face) -> FontInfo {
    let upm = face.units_per_em();
    // The US English record first, as fontTools' `getDebugName` takes it: a font's
    // records in other languages are its localised names (WenQuanYi's Chinese family name
    // comes first in its table), and the PostScript name is made from the family. Leading
    // and trailing white space is dropped.
    let name = |ids: &[u16]| -> Option<String> {
        ids.iter().find_map(|&id| {
            let mut any = None;
            for n in face.names() {
                if n.name_id != id || !n.is_unicode() {
                    continue;
                }
                // Trimmed: old tools ended records with "\r\n" (Gentium's copyright and
                // license), which FontBakery fails as trailing spaces in the built fonts.
                let text = n.to_string().map(|s| s.trim().to_string());
                let Some(text) = text.filter(|s| !s.is_empty()) else {
                    continue;
                };
                if n.language() == ttf_parser::Language::English_UnitedStates {
                    return Some(text);
                }
                any.get_or_insert(text);
            }
            any
        })
    };
    let measured_top = |c: char| -> Option<f64> {
        let gid = face.glyph_index(c)?;
        face.glyph_bounding_box(gid).map(|b| f64::from(b.y_max))
    };
    let em = f64::from(upm);
    let ascender = f64::from(face.ascender());
    let descender = f64::from(face.descender());
    // A damaged hhea can give ascender <= descender; fall back to the usual 0.8/-0.2 em.
    let (ascender, descender) = if ascender > descender {
        (ascender, descender)
    } else {
        (0.8 * em, -0.2 * em)
    };
    FontInfo {
        family: name(&[name_id::TYPOGRAPHIC_FAMILY, name_id::FAMILY])
            .unwrap_or_else(|| "Imported".to_string()),
        style: name(&[name_id::TYPOGRAPHIC_SUBFAMILY, name_id::SUBFAMILY])
            .unwrap_or_else(|| "Regular".to_string()),
        units_per_em: upm,
        ascender,
        descender,
        x_height: face
            .x_height()
            .map(f64::from)
            .filter(|&h| h > 0.0)
            .or_else(|| measured_top('x'))
            .unwrap_or(0.5 * em),
        cap_height: face
            .capital_height()
            .map(f64::from)
            .filter(|&h| h > 0.0)
            .or_else(|| measured_top('H'))
            .unwrap_or(0.7 * em),
        tolerance: DEFAULT_TOLERANCE,
        copyright: name(&[name_id::COPYRIGHT_NOTICE]),
        version: name(&[name_id::VERSION]),
        designer: name(&[name_id::DESIGNER]),
        license: name(&[name_id::LICENSE]),
        license_url: name(&[name_id::LICENSE_URL]),
        vendor: None,
    }
}

/// A glyph's outline as ttf-parser reads it (quadratic or cubic), in font units, y up;
/// `None` for a glyph without one (a space) or one ttf-parser cannot read. Coordinates are
/// passed on as they are: check [`BezPath::is_finite`] before trusting them.
pub fn glyph_outline(face: &Face, glyph: GlyphId) -> Option<BezPath> {
    let mut pen = PathPen(BezPath::new());
    face.outline_glyph(glyph, &mut pen)?;
    Some(pen.0)
}

/// Whether the font stores an empty outline for `gid`, as for a space: an empty `loca`
/// range or a simple glyph whose points, read whole, all lie on one spot (glyf; Material
/// Icons keeps its digits as one point at the origin), or a charstring that draws nothing
/// (CFF, CFF2). Other glyf data that draws nothing is not empty but unreadable: skrifa
/// reads simple glyphs lazily and draws nothing, without an error, from a header whose
/// arrays overrun the glyph.
pub(super) fn stores_no_outline(font: &skrifa::FontRef, gid: u16) -> bool {
    use skrifa::raw::tables::glyf::Glyph;
    use skrifa::raw::tables::loca::LocaGlyph;
    use skrifa::raw::TableProvider;
    let id = skrifa::GlyphId::new(u32::from(gid));
    if let Ok(glyf) = font.glyf() {
        let Ok(loca) = font.loca(None) else {
            return false;
        };
        return match loca.get(id, &glyf) {
            Some(LocaGlyph::Empty) => true,
            Some(LocaGlyph::Glyph(Glyph::Simple(simple))) => {
                // A header whose arrays overrun the glyph reads as fewer contours.
                let contours = usize::try_from(simple.number_of_contours()).unwrap_or(0);
                let n = simple.num_points();
                if contours == 0 || simple.end_pts_of_contours().len() != contours || n == 0 {
                    return false;
                }
                let mut points = vec![skrifa::raw::types::Point::<i32>::default(); n];
                let mut flags = vec![skrifa::raw::tables::glyf::PointFlags::default(); n];
                simple.read_points_fast(&mut points, &mut flags).is_ok()
                    && points.windows(2).all(|pair| pair[0] == pair[1])
            }
            _ => false,
        };
    }
    super::variable::outline_at(font, gid, &skrifa::instance::Location::default())
        .is_ok_and(|(outline, _)| outline.elements().is_empty())
}

/// A character a font would normally draw: its glyph is expected to have an outline.
fn visible(c: char) -> bool {
    c.is_alphanumeric() || c.is_ascii_graphic()
}

/// Collects ttf-parser's outline calls into a kurbo path.
struct PathPen(BezPath);

impl OutlineBuilder for PathPen {
    fn move_to(&mut self, x: f32, y: f32) {
        self.0.move_to(point(x, y));
    }
    fn line_to(&mut self, x: f32, y: f32) {
        self.0.line_to(point(x, y));
    }
    fn quad_to(&mut self, x1: f32, y1: f32, x: f32, y: f32) {
        self.0.quad_to(point(x1, y1), point(x, y));
    }
    fn curve_to(&mut self, x1: f32, y1: f32, x2: f32, y2: f32, x: f32, y: f32) {
        self.0.curve_to(point(x1, y1), point(x2, y2), point(x, y));
    }
    fn close(&mut self) {
        self.0.close_path();
    }
}

fn point(x: f32, y: f32) -> kurbo::Point {
    kurbo::Point::new(f64::from(x), f64::from(y))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn glyph_lists() {
        let az = parse_glyph_list("A-Z,a-z,0-9").unwrap();
        assert_eq!(az.len(), 62);
        assert_eq!(az[0], '0');
        assert_eq!(parse_glyph_list("-,x").unwrap(), vec!['-', 'x']);
        assert_eq!(parse_glyph_list("U+41-U+43").unwrap(), vec!['A', 'B', 'C']);
        assert_eq!(
            parse_glyph_list("Z-A").unwrap_err().to_string(),
            "glyph list: range `Z-A` runs backwards (write `A-Z`)"
        );
        assert_eq!(
            parse_glyph_list("AB").unwrap_err().to_string(),
            "glyph list `AB`: `AB` is not one character or U+XXXX code point"
        );
    }
}
