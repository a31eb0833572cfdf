//! Designspace export: a font with masters as one UFO per master plus a `.designspace`
//! file (format 5.0), written with norad, the input fontmake and fontc build variable fonts
//! from.
//!
//! ```text
//! OutlinedFamily (compatible cubics) + Family (X-splines, components, anchors per master)
//!   -> master_font(): one OutlinedFont per master -> super::export -> <Family>-<Master>.ufo
//!   -> document(): axes, sources, named instances  -> <Family>.designspace
//! ```
//!
//! Every master UFO holds that master's **compatible** cubics from
//! [`crate::family::outline_family`] (not a static fit of the master), so the UFOs have the
//! same points in the same order and interpolate into the variable TTF's outlines. Advances,
//! kerning, components (with this master's offsets), anchors and the X-spline sources (the
//! glyph lib key of [`super::lib`]) are the master's own.
//!
//! Locations are written as design coordinates (`xvalue`): the user coordinates through the
//! axis `map` (written as `<map>`), equal to them on an axis without one. Instances carry no
//! `filename` (fontmake then names their UFOs itself when asked for static instances).

use std::collections::{HashMap, HashSet};
use std::path::PathBuf;

use norad::designspace::{self, DesignSpaceDocument, Dimension};

use super::{ufo_dir_name, UfoError};
use crate::designspace::{Designspace, Location};
use crate::family::OutlinedFamily;
use crate::model::{Family, FontInfo, Glyph, Master};
use crate::outline::OutlinedFont;
use crate::reuse::{OutlineKeys, Reuse};
use crate::svg::output_stem;

/// The designspace's file name: `<Family>.designspace`, the family part of the static
/// stem (`XglyphSans.designspace` next to `XglyphSans-Regular.ufo`).
pub fn designspace_file_name(info: &FontInfo) -> String {
    format!("{}.designspace", family_stem(info))
}

/// `<Family>-<Style>` without its `-<Style>`.
fn family_stem(info: &FontInfo) -> String {
    let stem = output_stem(info);
    let style: String = info.style.chars().filter(|c| !c.is_whitespace()).collect();
    match stem.strip_suffix(&format!("-{style}")) {
        Some(family) if !family.is_empty() => family.to_string(),
        _ => stem,
    }
}

/// Master `m` of `family` (an index into [`OutlinedFamily::masters`]) as an outlined font:
/// the default master's glyphs with this master's compatible paths, advances, own
/// X-spline contours, components, anchors and kerning, and its name as the style.
///
/// What [`super::export`] reads is the master's; the rest (`max_error`, the components'
/// placed contours) stays the default master's.
pub fn master_font(family: &OutlinedFamily, model: &Family, m: usize) -> OutlinedFont {
    let master = &family.masters[m];
    let sources: HashMap<&str, &Glyph> = model
        .masters
        .get(m)
        .map(|source| source.glyphs.iter().map(|g| (g.name.as_str(), g)).collect())
        .unwrap_or_default();
    let mut font = family.default.clone();
    font.info.style = master.name.clone();
    font.kerning = master.kerning.clone();
    for (g, mg) in font.glyphs.iter_mut().zip(&master.glyphs) {
        g.advance = mg.advance;
        g.path = mg.path.clone();
        if let Some(source) = sources.get(g.name.as_str()) {
            g.components = source.components.clone();
            g.anchors = source.anchors.clone();
            for (placed, own) in g.contours.iter_mut().zip(&source.contours) {
                placed.spline = own.spline().clone();
            }
        }
    }
    font
}

/// The designspace document of `family`, whose master UFOs (and layers, for sparse
/// masters) are `files` (the default master's first, then [`OutlinedFamily::masters`] in
/// order).
pub fn document(
    family: &OutlinedFamily,
    files: &[(String, Option<String>)],
) -> DesignSpaceDocument {
    let ds = &family.designspace;
    let info = &family.default.info;
    let axes = ds
        .axes
        .iter()
        .map(|a| designspace::Axis {
            name: a.name.clone(),
            tag: a.tag.clone(),
            default: a.default,
            minimum: Some(a.min),
            maximum: Some(a.max),
            map: (!a.map.is_empty()).then(|| {
                a.map
                    .iter()
                    .map(|&(input, output)| designspace::AxisMapping { input, output })
                    .collect()
            }),
            ..designspace::Axis::default()
        })
        .collect();
    let masters = std::iter::once((info.style.as_str(), Location::default())).chain(
        family
            .masters
            .iter()
            .map(|m| (m.name.as_str(), m.location.clone())),
    );
    let sources = masters
        .zip(files)
        .map(
            |((style, location), (filename, layer))| designspace::Source {
                familyname: Some(info.family.clone()),
                stylename: Some(style.to_string()),
                name: Some(format!("master.{style}")),
                filename: filename.clone(),
                layer: layer.clone(),
                location: dimensions(ds, &location),
                ..designspace::Source::default()
            },
        )
        .collect();
    let instances = ds
        .instances
        .iter()
        .map(|i| designspace::Instance {
            familyname: Some(info.family.clone()),
            stylename: Some(i.name.clone()),
            name: Some(format!("{} {}", info.family, i.name)),
            location: dimensions(ds, &i.location),
            ..designspace::Instance::default()
        })
        .collect();
    DesignSpaceDocument {
        format: 5.0,
        axes,
        rules: rules(ds),
        sources,
        instances,
        ..DesignSpaceDocument::default()
    }
}

/// The rules as `<rules>`: each box a `<conditionset>` in design coordinates.
fn rules(ds: &Designspace) -> designspace::Rules {
    designspace::Rules {
        processing: if ds.rules_last {
            designspace::RuleProcessing::Last
        } else {
            designspace::RuleProcessing::First
        },
        rules: ds
            .rules
            .iter()
            .map(|r| designspace::Rule {
                name: Some(r.name.clone()),
                condition_sets: r
                    .conditions
                    .iter()
                    .map(|b| designspace::ConditionSet {
                        conditions: ds
                            .axes
                            .iter()
                            .filter_map(|a| {
                                let &(min, max) = b.get(&a.tag)?;
                                Some(designspace::Condition {
                                    name: a.name.clone(),
                                    minimum: Some(a.design(min) + 0.0),
                                    maximum: Some(a.design(max) + 0.0),
                                })
                            })
                            .collect(),
                    })
                    .collect(),
                // The names are the font's glyph names (`check` requires it), which the
                // UFOs hold as `Name`s already, so none is left out here.
                substitutions: r
                    .substitutions
                    .iter()
                    .filter_map(|(from, to)| {
                        Some(designspace::Substitution {
                            name: norad::Name::new(from).ok()?,
                            with: norad::Name::new(to).ok()?,
                        })
                    })
                    .collect(),
            })
            .collect(),
    }
}

/// A location on every axis (an axis it leaves out is at its default), as design
/// coordinates.
fn dimensions(ds: &Designspace, location: &Location) -> Vec<Dimension> {
    ds.axes
        .iter()
        .map(|a| Dimension {
            name: a.name.clone(),
            xvalue: Some(a.design(location.get(a)) + 0.0),
            ..Dimension::default()
        })
        .collect()
}

/// Every file of the family's UFOs and designspace, paths relative to the build's output
/// folder, the UFOs' files sorted by path within each UFO, the designspace last: what
/// `build` writes for a font with masters.
pub fn output_files(
    family: &OutlinedFamily,
    model: &Family,
) -> Result<Vec<(PathBuf, Vec<u8>)>, UfoError> {
    output_files_reusing(family, model, &Reuse::off())
}

/// [`output_files`], leaving out each `.glif` that OUT holds already as the last build made
/// it ([`super::output_files_reusing`]).
pub fn output_files_reusing(
    family: &OutlinedFamily,
    model: &Family,
    reuse: &Reuse,
) -> Result<Vec<(PathBuf, Vec<u8>)>, UfoError> {
    let fonts: Vec<OutlinedFont> = std::iter::once(family.default.clone())
        .chain((0..family.masters.len()).map(|m| {
            let font = master_font(family, model, m);
            let master = &model.masters[m];
            if master.sparse && master.kerned {
                drawn_only(font, master)
            } else {
                font
            }
        }))
        .collect();
    // A sparse master without kerning of its own is a layer of the default master's UFO;
    // every other master a UFO.
    let on_layer = |k: usize| k > 0 && model.masters[k - 1].sparse && !model.masters[k - 1].kerned;
    let dirs: Vec<String> = fonts.iter().map(ufo_dir_name).collect();
    let mut seen = HashSet::new();
    if let Some(dir) = dirs
        .iter()
        .enumerate()
        .filter(|&(k, _)| !on_layer(k))
        .map(|(_, d)| d)
        .find(|d| !seen.insert(d.to_lowercase()))
    {
        return Err(UfoError::MasterName(dir.clone()));
    }
    let layers: Vec<super::ExtraLayer<'_>> = (1..fonts.len())
        .filter(|&k| on_layer(k))
        .map(|k| super::ExtraLayer {
            name: &model.masters[k - 1].name,
            font: &fonts[k],
            glyphs: &model.masters[k - 1].drawn,
        })
        .collect();
    let mut out = Vec::new();
    for (k, font) in fonts.iter().enumerate() {
        if on_layer(k) {
            continue;
        }
        let outlines = OutlineKeys::new(font, reuse);
        let extra = if k == 0 { &layers[..] } else { &[] };
        out.extend(super::output_files_reusing(font, reuse, &outlines, extra)?);
    }
    // The sources: a master on a layer reads its layer of the default master's UFO.
    let files: Vec<(String, Option<String>)> = dirs
        .iter()
        .enumerate()
        .map(|(k, d)| match on_layer(k) {
            true => (dirs[0].clone(), Some(model.masters[k - 1].name.clone())),
            false => (d.clone(), None),
        })
        .collect();
    let xml = document(family, &files)
        .serialize_to_string()
        .map_err(|e| UfoError::Write(format!("designspace: {}", super::error_chain(&e))))?;
    out.push((
        PathBuf::from(designspace_file_name(&family.default.info)),
        xml.into_bytes(),
    ));
    Ok(out)
}

/// A sparse master with kerning of its own as a UFO of its own (a layer holds no kerning):
/// the glyphs it draws and the bases of their components, which fontmake and fontc take
/// as a source that is sparse for outlines and kerned. A base the master does not draw
/// is written as its blend there, which along one axis changes no outline.
fn drawn_only(mut font: OutlinedFont, master: &Master) -> OutlinedFont {
    let mut keep: HashSet<String> = master
        .glyphs
        .iter()
        .zip(&master.drawn)
        .filter(|&(_, &d)| d)
        .map(|(g, _)| g.name.clone())
        .collect();
    let by_name: HashMap<&str, &crate::outline::OutlinedGlyph> =
        font.glyphs.iter().map(|g| (g.name.as_str(), g)).collect();
    let mut todo: Vec<String> = keep.iter().cloned().collect();
    while let Some(name) = todo.pop() {
        for c in by_name
            .get(name.as_str())
            .map_or(&[][..], |g| &g.components[..])
        {
            if keep.insert(c.base.clone()) {
                todo.push(c.base.clone());
            }
        }
    }
    font.glyphs.retain(|g| keep.contains(&g.name));
    font
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::designspace::{Axis, NamedInstance};

    fn info(family: &str, style: &str) -> FontInfo {
        FontInfo {
            family: family.into(),
            style: style.into(),
            ..crate::model::test_info()
        }
    }

    #[test]
    fn the_file_is_named_after_the_family() {
        assert_eq!(
            designspace_file_name(&info("Xglyph Sans", "Regular")),
            "XglyphSans.designspace"
        );
        assert_eq!(
            designspace_file_name(&info("Xglyph Sans", "Semi Bold")),
            "XglyphSans.designspace"
        );
    }

    #[test]
    fn axes_maps_sources_and_instances_in_the_xml() {
        let axis = Axis {
            tag: "wght".into(),
            name: "Weight".into(),
            min: 400.0,
            default: 400.0,
            max: 700.0,
            map: vec![(400.0, 0.0), (500.0, 40.0), (700.0, 100.0)],
        };
        let at = |v: f64| Location([("wght".to_string(), v)].into_iter().collect());
        let model = Designspace {
            axes: vec![Axis::linear("wght", "Weight", 400.0, 400.0, 700.0)],
            instances: Vec::new(),
            rules: Vec::new(),
            rules_last: false,
        }
        .model(&[at(700.0)])
        .expect("one master at the end");
        let family = OutlinedFamily {
            designspace: Designspace {
                axes: vec![axis],
                instances: vec![NamedInstance {
                    name: "Medium".into(),
                    location: at(500.0),
                }],
                rules: Vec::new(),
                rules_last: false,
            },
            default: OutlinedFont {
                info: info("Xglyph Sans", "Regular"),
                kerning: Vec::new(),
                features: None,
                tolerance: 0.5,
                glyphs: Vec::new(),
            },
            masters: vec![crate::family::OutlinedMaster {
                name: "Bold".into(),
                location: at(700.0),
                glyphs: Vec::new(),
                kerning: Vec::new(),
            }],
            models: crate::model::GlyphModels::full(1, &model, 0),
            model,
        };
        let files = [
            ("A-Regular.ufo".to_string(), None),
            ("A-Bold.ufo".to_string(), None),
        ];
        let xml = document(&family, &files)
            .serialize_to_string()
            .expect("serialises");
        let want = "<?xml version='1.0' encoding='UTF-8'?>
<designspace format=\"5.0\">
  <axes>
    <axis name=\"Weight\" tag=\"wght\" default=\"400\" minimum=\"400\" maximum=\"700\">
      <map input=\"400\" output=\"0\"/>
      <map input=\"500\" output=\"40\"/>
      <map input=\"700\" output=\"100\"/>
    </axis>
  </axes>
  <sources>
    <source familyname=\"Xglyph Sans\" stylename=\"Regular\" name=\"master.Regular\" filename=\"A-Regular.ufo\">
      <location>
        <dimension name=\"Weight\" xvalue=\"0\"/>
      </location>
    </source>
    <source familyname=\"Xglyph Sans\" stylename=\"Bold\" name=\"master.Bold\" filename=\"A-Bold.ufo\">
      <location>
        <dimension name=\"Weight\" xvalue=\"100\"/>
      </location>
    </source>
  </sources>
  <instances>
    <instance familyname=\"Xglyph Sans\" stylename=\"Medium\" name=\"Xglyph Sans Medium\">
      <location>
        <dimension name=\"Weight\" xvalue=\"40\"/>
      </location>
    </instance>
  </instances>
</designspace>
";
        assert_eq!(xml, want);
    }
}
