//! `fontinfo.plist` and the font lib from `font.toml`'s values.
//!
//! Besides the names and metrics, the fields FontBakery's UFO checks ask for are filled
//! the way xglyph's own font tables are: underline position and thickness as in `post`
//! (0.075 and 0.05 em), panose all zero ("any") as in `OS/2`, the version as major/minor
//! from `version` (`"0.1"` -> 0.100, as the `head` revision), and the vendor ID with
//! xglyph's default when `font.toml` names none. Fields the checks call unnecessary
//! (`openTypeNameVersion`, `year`, unique IDs) are left out: compilers derive them.

use norad::fontinfo::Os2Panose;
use plist::Value;

use super::lib::{
    categories_value, kerning_order_value, CATEGORIES_KEY, KERNING_ORDER_KEY, TOLERANCE_KEY,
    VERSION_KEY,
};
use crate::model::{FontInfo, DEFAULT_VENDOR};
use crate::outline::OutlinedFont;

/// Underline position below the baseline and thickness, in ems (as in `otf/post.rs`).
const UNDERLINE_POSITION: f64 = 0.075;
const UNDERLINE_THICKNESS: f64 = 0.05;

/// `fontinfo.plist` for `info`.
pub fn font_info(info: &FontInfo) -> norad::FontInfo {
    let em = f64::from(info.units_per_em);
    let (major, minor) = version_numbers(info.version.as_deref());
    norad::FontInfo {
        family_name: Some(info.family.clone()),
        style_name: Some(info.style.clone()),
        units_per_em: norad::fontinfo::NonNegativeIntegerOrFloat::new(em),
        ascender: Some(info.ascender + 0.0),
        descender: Some(info.descender + 0.0),
        x_height: Some(info.x_height + 0.0),
        cap_height: Some(info.cap_height + 0.0),
        copyright: info.copyright.clone(),
        open_type_name_designer: info.designer.clone(),
        open_type_name_license: info.license.clone(),
        open_type_name_license_url: info.license_url.clone(),
        open_type_os2_vendor_id: Some(
            info.vendor
                .clone()
                .unwrap_or_else(|| DEFAULT_VENDOR.to_string()),
        ),
        open_type_os2_panose: Some(Os2Panose::default()),
        postscript_underline_position: Some(-(UNDERLINE_POSITION * em).round()),
        postscript_underline_thickness: Some((UNDERLINE_THICKNESS * em).round()),
        version_major: Some(major),
        version_minor: Some(minor),
        ..norad::FontInfo::default()
    }
}

/// `(versionMajor, versionMinor)`: `"1.2"` -> (1, 200), `"Version 2.015"` -> (2, 15);
/// (1, 0) when there is no version or it is not a number (as the `head` revision).
pub fn version_numbers(version: Option<&str>) -> (i32, u32) {
    let text = version.map(str::trim).unwrap_or("1.0");
    let bare = text.strip_prefix("Version ").unwrap_or(text);
    match bare.parse::<f64>() {
        Ok(v) if v.is_finite() && (0.0..32768.0).contains(&v) => {
            let thousandths = (v * 1000.0).round() as i64;
            ((thousandths / 1000) as i32, (thousandths % 1000) as u32)
        }
        _ => (1, 0),
    }
}

/// The font lib: `public.glyphOrder`, `public.openTypeCategories` for a font with a
/// mark placed by its outline, and xglyph's own keys ([`super::lib`]).
pub fn font_lib(font: &OutlinedFont) -> norad::Plist {
    let mut lib = norad::Plist::new();
    lib.insert(
        "public.glyphOrder".into(),
        Value::Array(
            font.glyphs
                .iter()
                .map(|g| Value::String(g.name.clone()))
                .collect(),
        ),
    );
    lib.insert(TOLERANCE_KEY.into(), Value::Real(font.info.tolerance));
    if let Some(version) = &font.info.version {
        lib.insert(VERSION_KEY.into(), Value::String(version.clone()));
    }
    if !font.kerning.is_empty() {
        lib.insert(KERNING_ORDER_KEY.into(), kerning_order_value(&font.kerning));
    }
    if let Some(categories) = categories_value(font) {
        lib.insert(CATEGORIES_KEY.into(), categories);
    }
    lib
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn versions() {
        assert_eq!(version_numbers(Some("0.1")), (0, 100));
        assert_eq!(version_numbers(Some("Version 2.015")), (2, 15));
        assert_eq!(version_numbers(Some("1.0005")), (1, 1));
        assert_eq!(version_numbers(Some("beta")), (1, 0));
        assert_eq!(version_numbers(None), (1, 0));
    }

    #[test]
    fn fields_the_checks_want() {
        let info = crate::model::test_info();
        let ufo = font_info(&info);
        assert_eq!(ufo.family_name.as_deref(), Some("Test"));
        assert_eq!(ufo.units_per_em.map(|u| u.as_f64()), Some(1000.0));
        assert_eq!(ufo.postscript_underline_position, Some(-75.0));
        assert_eq!(ufo.postscript_underline_thickness, Some(50.0));
        assert_eq!(ufo.open_type_os2_vendor_id.as_deref(), Some("XGLY"));
        assert_eq!((ufo.version_major, ufo.version_minor), (Some(1), Some(0)));
        assert_eq!(ufo.year, None);
    }
}
