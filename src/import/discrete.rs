//! A designspace at one discrete location: a designspace 5 document with discrete axes
//! (`<axis … values="0 1" default="0"/>`, no minimum and maximum) cut down to the
//! interpolable space at one value of each, which is what xglyph's font format (continuous
//! axes only) can hold.
//!
//! fontmake builds one variable font per combination of discrete values (fontTools'
//! `designspaceLib.split.splitInterpolable`); [`at_discrete_location`] keeps one of them,
//! with the same semantics:
//!
//! - the discrete location is `--at`'s (`ital=1`, user values, several separated by
//!   commas); a discrete axis it does not name takes its default;
//! - a source or instance is kept when it sits at that value on every discrete axis (a
//!   dimension it leaves out is at the axis default; a design `xvalue` goes through the
//!   inverse axis map), and loses its discrete dimensions; a continuous axis its location
//!   leaves out is written at its default (so one place is one location);
//! - a rule's condition on a discrete axis is evaluated there (in design values, as the
//!   conditions are written): one that holds is dropped, one that fails drops its
//!   condition set, and a rule left without condition sets is left out; conditions on the
//!   continuous axes are kept;
//! - `<variable-fonts>` are dropped (the selection is `--at`'s), labels are ignored.
//!
//! One step further than the split: a continuous axis on which no source kept leaves the
//! default (the upright-only width of a family whose italic has one width) is pinned at its
//! default like a discrete axis, as fontmake's `<variable-font>` of that location leaves it
//! out; the instances off its default are left out, with a note. When no axis is left, the
//! family is the one source at that location, imported as a plain UFO: its named instances
//! and rules are not kept (a font without axes has one style), and a note says so.
//!
//! Errors, before any UFO is read: a tag that is not an axis, a continuous axis, a value
//! that is not among the axis values, and no source at the default of the location.

use norad::designspace::{Axis as DsAxis, DesignSpaceDocument, Dimension, RuleProcessing};

use crate::designspace::Axis;
use crate::instance::assignments;
use crate::source::emit::number;

/// Two user or design values this close are one (a value read through a map may be off in
/// the last bits).
const SAME: f64 = 1e-9;

/// One discrete axis of the designspace and the value imported.
#[derive(Clone, Debug, PartialEq)]
pub struct DiscreteAxis {
    /// Its name, e.g. `Italic`.
    pub name: String,
    /// Its tag, e.g. `ital`.
    pub tag: String,
    /// Its values (user), in the designspace's order.
    pub values: Vec<f64>,
    /// The value imported.
    pub value: f64,
    /// Whether `--at` named it (else it is at its default).
    pub named: bool,
}

/// The discrete location a designspace was imported at, and what was left out.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct DiscreteLocation {
    /// The discrete axes, in the designspace's order, each with the value imported.
    pub axes: Vec<DiscreteAxis>,
    /// Sources kept, of all.
    pub sources: (usize, usize),
    /// Named instances at this location, of all (before one place named twice is one).
    pub instances: (usize, usize),
    /// What was pinned or left out beyond the other discrete locations (axes pinned at
    /// their default, instances off them, rules that do not apply there).
    pub notes: Vec<String>,
}

impl DiscreteLocation {
    /// The location as `--at` takes it, e.g. `ital=1` or `wdth=75,ital=1`.
    pub fn at(&self) -> String {
        self.axes
            .iter()
            .map(|a| format!("{}={}", a.tag, number(a.value)))
            .collect::<Vec<_>>()
            .join(",")
    }

    /// One notice per discrete axis that `--at` did not name and that has other values:
    /// its values, the one imported and the `--at` that imports the others.
    pub fn notices(&self) -> Vec<String> {
        self.axes
            .iter()
            .filter(|a| !a.named)
            .filter_map(|a| {
                let others: Vec<String> = a
                    .values
                    .iter()
                    .filter(|&&v| !same(v, a.value))
                    .map(|&v| format!("`--at {}={}`", a.tag, number(v)))
                    .collect();
                let how = match others.len() {
                    0 => return None,
                    1 => format!("{} imports the other", others[0]),
                    _ => format!("{} imports another", others.join(" or ")),
                };
                Some(format!(
                    "axis `{}` ({}) is discrete, values {}: imported {}={}; {how}",
                    a.name,
                    a.tag,
                    values(&a.values),
                    a.tag,
                    number(a.value)
                ))
            })
            .collect()
    }

    /// The summary line: the location, the sources kept and the named instances the
    /// family has (`instances`; one place named twice is one).
    pub fn summary(&self, instances: usize) -> String {
        format!(
            "discrete location {}: {} of {} sources, {instances} named instances (of {} in \
             the designspace)",
            self.at(),
            self.sources.0,
            self.sources.1,
            self.instances.1
        )
    }
}

/// `doc` at one discrete location (see the module docs): `at` is `--at`'s text (`None`:
/// every discrete axis at its default). The document keeps only its continuous axes (less
/// those pinned), and the sources, instances and rules of that location; the location is
/// `None` when the designspace has no discrete axis (and no `--at`), which leaves it as it
/// was. The error says what is wrong, naming `--at` when it is at fault.
pub fn at_discrete_location(
    mut doc: DesignSpaceDocument,
    at: Option<&str>,
) -> Result<(DesignSpaceDocument, Option<DiscreteLocation>), String> {
    let discrete: Vec<usize> = (0..doc.axes.len())
        .filter(|&i| is_discrete(&doc.axes[i]))
        .collect();
    let chosen = match at {
        Some(text) => chosen_values(&doc, text)?,
        None if discrete.is_empty() => return Ok((doc, None)),
        None => Vec::new(),
    };
    let conversions: Vec<Axis> = doc.axes.iter().map(conversion).collect();
    // Each pinned axis (by index) and its user value: the discrete ones first.
    let mut pinned: Vec<(usize, f64)> = discrete
        .iter()
        .map(|&i| {
            let tag = &doc.axes[i].tag;
            let value = chosen
                .iter()
                .find(|(t, _)| t == tag)
                .map_or(doc.axes[i].default, |&(_, v)| v);
            (i, value)
        })
        .collect();
    let mut place = DiscreteLocation {
        axes: pinned
            .iter()
            .map(|&(i, value)| {
                let a = &doc.axes[i];
                DiscreteAxis {
                    name: a.name.clone(),
                    tag: a.tag.clone(),
                    values: a.values.clone().unwrap_or_default(),
                    value,
                    named: chosen.iter().any(|(t, _)| t == &a.tag),
                }
            })
            .collect(),
        sources: (0, doc.sources.len()),
        instances: (0, doc.instances.len()),
        notes: Vec::new(),
    };
    let user_at =
        |dims: &[Dimension], axis: usize| user_value(&doc.axes[axis], &conversions[axis], dims);
    let at_pinned = |dims: &[Dimension], pinned: &[(usize, f64)]| {
        pinned.iter().all(|&(i, v)| same(user_at(dims, i), v))
    };
    let sources: Vec<usize> = (0..doc.sources.len())
        .filter(|&k| at_pinned(&doc.sources[k].location, &pinned))
        .collect();
    if sources.is_empty() {
        return Err(format!(
            "no source sits at the discrete location {}",
            place.at()
        ));
    }
    // A continuous axis that no source here leaves the default of is pinned there too.
    let flat: Vec<usize> = (0..doc.axes.len())
        .filter(|i| !discrete.contains(i))
        .filter(|&i| {
            sources
                .iter()
                .all(|&k| same(user_at(&doc.sources[k].location, i), doc.axes[i].default))
        })
        .collect();
    for &i in &flat {
        let a = &doc.axes[i];
        place.notes.push(format!(
            "axis `{}` ({}) left out: no source at {} leaves its default {}",
            a.name,
            a.tag,
            place.at(),
            number(a.default)
        ));
    }
    let at_discrete: Vec<usize> = (0..doc.instances.len())
        .filter(|&k| at_pinned(&doc.instances[k].location, &pinned))
        .collect();
    pinned.extend(flat.iter().map(|&i| (i, doc.axes[i].default)));
    let continuous: Vec<usize> = (0..doc.axes.len())
        .filter(|i| !pinned.iter().any(|(p, _)| p == i))
        .collect();
    let instances: Vec<usize> = if continuous.is_empty() {
        if !at_discrete.is_empty() {
            place.notes.push(format!(
                "no continuous axis is left at {}, so the font has one style: its {} named \
                 instances are not kept",
                place.at(),
                at_discrete.len()
            ));
        }
        Vec::new()
    } else {
        let (kept, off): (Vec<usize>, Vec<usize>) = at_discrete
            .iter()
            .partition(|&&k| at_pinned(&doc.instances[k].location, &pinned));
        if !off.is_empty() {
            let names: Vec<String> = off
                .iter()
                .map(|&k| instance_name(&doc.instances[k]))
                .collect();
            place.notes.push(format!(
                "named instances off the default of the axes left out, not kept: {}",
                names.join(", ")
            ));
        }
        kept
    };
    // The sources there, by default the one at every continuous axis default.
    if !sources.iter().any(|&k| {
        continuous
            .iter()
            .all(|&i| same(user_at(&doc.sources[k].location, i), doc.axes[i].default))
    }) {
        let defaults: Vec<String> = continuous
            .iter()
            .map(|&i| format!("{} = {}", doc.axes[i].tag, number(doc.axes[i].default)))
            .collect();
        return Err(format!(
            "no source sits at the default of the discrete location {} ({})",
            place.at(),
            defaults.join(", ")
        ));
    }
    place.sources.0 = sources.len();
    place.instances.0 = instances.len();
    let rules = rules_at(&doc, &conversions, &pinned, continuous.is_empty());
    place.notes.extend(rules.1);
    doc.rules.rules = rules.0;
    if doc.rules.rules.is_empty() {
        doc.rules.processing = RuleProcessing::First;
    }
    let pinned_names: Vec<String> = pinned
        .iter()
        .map(|&(i, _)| doc.axes[i].name.clone())
        .collect();
    // Without the pinned axes, and full: a continuous axis left out is at its default (as
    // the split's expanded locations), so one place is written one way.
    let full: Vec<(String, f64)> = continuous
        .iter()
        .map(|&i| (doc.axes[i].name.clone(), doc.axes[i].default))
        .collect();
    let keep = |dims: &mut Vec<Dimension>| {
        dims.retain(|d| !pinned_names.contains(&d.name));
        for (name, default) in &full {
            if !dims.iter().any(|d| &d.name == name) {
                dims.push(Dimension {
                    name: name.clone(),
                    uservalue: Some(*default),
                    ..Dimension::default()
                });
            }
        }
    };
    doc.sources = keep_indices(std::mem::take(&mut doc.sources), &sources);
    doc.instances = keep_indices(std::mem::take(&mut doc.instances), &instances);
    doc.sources.iter_mut().for_each(|s| keep(&mut s.location));
    doc.instances.iter_mut().for_each(|i| keep(&mut i.location));
    doc.axes = keep_indices(std::mem::take(&mut doc.axes), &continuous);
    doc.variable_fonts.clear();
    Ok((doc, Some(place)))
}

/// Whether `axis` is discrete: it lists `values` (as fontTools takes it).
fn is_discrete(axis: &DsAxis) -> bool {
    axis.values.is_some()
}

/// `--at`'s values, each checked: on a discrete axis of `doc`, and one of its values.
fn chosen_values(doc: &DesignSpaceDocument, text: &str) -> Result<Vec<(String, f64)>, String> {
    let flag = format!("--at {text}");
    let discrete: Vec<&DsAxis> = doc.axes.iter().filter(|a| is_discrete(a)).collect();
    let listed = || {
        if discrete.is_empty() {
            return "the designspace has no discrete axis; leave out --at".to_string();
        }
        let each: Vec<String> = discrete
            .iter()
            .map(|a| {
                format!(
                    "`{}` ({}: {})",
                    a.tag,
                    a.name,
                    values(a.values.as_deref().unwrap_or_default())
                )
            })
            .collect();
        format!("the discrete axes are {}", each.join(", "))
    };
    let chosen = assignments(text)?;
    for (tag, value) in &chosen {
        let Some(axis) = doc.axes.iter().find(|a| &a.tag == tag) else {
            return Err(format!(
                "{flag}: `{tag}` is not an axis of the designspace; {}",
                listed()
            ));
        };
        let Some(all) = axis.values.as_deref() else {
            return Err(format!(
                "{flag}: axis `{}` ({tag}) is continuous; --at on import picks a discrete \
                 location, and continuous axes come whole; {}",
                axis.name,
                listed()
            ));
        };
        if !all.iter().any(|&v| same(v, *value)) {
            return Err(format!(
                "{flag}: {tag} = {} is not a value of the discrete axis `{}`; its values are {}",
                number(*value),
                axis.name,
                values(all)
            ));
        }
    }
    Ok(chosen)
}

/// An axis of the document as xglyph's, for reading its values: range from the minimum
/// and maximum (a discrete axis: its smallest and largest value), and its map sorted (not
/// checked: [`super::designspace`] checks the continuous axes' maps).
fn conversion(a: &DsAxis) -> Axis {
    let listed = a.values.as_deref().unwrap_or_default();
    let min = a
        .minimum
        .unwrap_or_else(|| listed.iter().copied().fold(a.default, f64::min));
    let max = a
        .maximum
        .unwrap_or_else(|| listed.iter().copied().fold(a.default, f64::max));
    let mut map: Vec<(f64, f64)> = a
        .map
        .iter()
        .flatten()
        .map(|m| (m.input, m.output))
        .collect();
    map.sort_by(|x, y| x.0.total_cmp(&y.0));
    map.dedup_by(|x, y| x.0 == y.0);
    Axis {
        map,
        ..Axis::linear(a.tag.clone(), a.name.clone(), min, a.default, max)
    }
}

/// The user value of `axis` in the location `dims` (by axis name): its `uservalue`, else
/// its `xvalue` through the inverse map, else (left out, or without a value) the default.
fn user_value(axis: &DsAxis, conversion: &Axis, dims: &[Dimension]) -> f64 {
    dims.iter()
        .find(|d| d.name == axis.name)
        .and_then(|d| d.uservalue.or(d.xvalue.map(|x| conversion.user(x))))
        .unwrap_or(axis.default)
}

/// The rules at the pinned axes (`pinned`: axis index and user value) with their
/// conditions on them evaluated, and notes on the rules left out. With `no_axes`, none is
/// kept (a font without axes has no rules), and a note names those that apply there.
fn rules_at(
    doc: &DesignSpaceDocument,
    conversions: &[Axis],
    pinned: &[(usize, f64)],
    no_axes: bool,
) -> (Vec<norad::designspace::Rule>, Vec<String>) {
    let mut kept = Vec::new();
    let mut elsewhere = Vec::new();
    for (k, rule) in doc.rules.rules.iter().enumerate() {
        let mut rule = rule.clone();
        let name = rule
            .name
            .clone()
            .filter(|n| !n.trim().is_empty())
            .unwrap_or_else(|| format!("rule {}", k + 1));
        rule.condition_sets.retain_mut(|set| {
            let mut holds = true;
            set.conditions.retain(|c| {
                let Some(&(i, user)) = pinned
                    .iter()
                    .find(|&&(i, _)| doc.axes[i].name == c.name || doc.axes[i].tag == c.name)
                else {
                    return true;
                };
                let design = conversions[i].design(user);
                holds &= c.minimum.is_none_or(|m| m <= design + SAME)
                    && c.maximum.is_none_or(|m| design <= m + SAME);
                false
            });
            holds
        });
        if rule.condition_sets.is_empty() {
            // It never applies here (a rule with no condition set at all applies nowhere).
            if !doc.rules.rules[k].condition_sets.is_empty() {
                elsewhere.push(name);
            }
            continue;
        }
        kept.push((name, rule));
    }
    let mut notes = Vec::new();
    if !elsewhere.is_empty() {
        notes.push(format!(
            "rules that do not apply here left out: {}",
            elsewhere.join(", ")
        ));
    }
    if no_axes && !kept.is_empty() {
        let names: Vec<&str> = kept.iter().map(|(n, _)| n.as_str()).collect();
        notes.push(format!(
            "rules not kept (a font without axes has no rules), though they apply here: {}",
            names.join(", ")
        ));
        kept.clear();
    }
    (kept.into_iter().map(|(_, r)| r).collect(), notes)
}

/// The name of an instance in notes: its style name, else its name, else `instance`.
fn instance_name(i: &norad::designspace::Instance) -> String {
    let name = i
        .stylename
        .clone()
        .or_else(|| i.name.clone())
        .filter(|n| !n.trim().is_empty())
        .unwrap_or_else(|| "(unnamed)".into());
    format!("`{name}`")
}

/// The items of `all` at `indices` (increasing), in order.
fn keep_indices<T>(all: Vec<T>, indices: &[usize]) -> Vec<T> {
    all.into_iter()
        .enumerate()
        .filter(|(i, _)| indices.contains(i))
        .map(|(_, x)| x)
        .collect()
}

/// Values as a list, `0, 1`.
fn values(all: &[f64]) -> String {
    all.iter()
        .map(|&v| number(v))
        .collect::<Vec<_>>()
        .join(", ")
}

/// Whether two values are one ([`SAME`]).
fn same(a: f64, b: f64) -> bool {
    (a - b).abs() <= SAME * a.abs().max(b.abs()).max(1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A designspace read by norad from `xml`.
    fn doc(xml: &str) -> DesignSpaceDocument {
        let dir = tempfile::tempdir().expect("temp dir");
        let path = dir.path().join("test.designspace");
        std::fs::write(&path, xml).expect("writes");
        DesignSpaceDocument::load(&path).expect("loads")
    }

    /// Italic discrete (design 0 and 100), Weight and Width continuous; the italic has no
    /// narrow source.
    const XML: &str = r#"<?xml version='1.0' encoding='UTF-8'?>
<designspace format="5.0">
  <axes>
    <axis tag="ital" name="Italic" values="0 1" default="0">
      <map input="0" output="0"/><map input="1" output="100"/>
    </axis>
    <axis tag="wght" name="Weight" minimum="100" maximum="900" default="100"/>
    <axis tag="wdth" name="Width" minimum="75" maximum="100" default="100"/>
  </axes>
  <rules>
    <rule name="upright heavy">
      <conditionset>
        <condition name="Italic" minimum="0" maximum="0"/>
        <condition name="Weight" minimum="600"/>
      </conditionset>
      <sub name="a" with="a.alt"/>
    </rule>
    <rule name="italic">
      <conditionset><condition name="ital" minimum="50"/></conditionset>
      <conditionset><condition name="Width" maximum="80"/></conditionset>
      <sub name="b" with="b.alt"/>
    </rule>
  </rules>
  <sources>
    <source filename="L.ufo" name="L"><location><dimension name="Weight" xvalue="100"/></location></source>
    <source filename="B.ufo" name="B"><location><dimension name="Weight" xvalue="900"/></location></source>
    <source filename="N.ufo" name="N"><location><dimension name="Width" xvalue="75"/></location></source>
    <source filename="LI.ufo" name="LI"><location><dimension name="Italic" xvalue="100"/></location></source>
    <source filename="BI.ufo" name="BI">
      <location><dimension name="Italic" xvalue="100"/><dimension name="Weight" xvalue="900"/></location>
    </source>
  </sources>
  <instances>
    <instance stylename="Regular"><location><dimension name="Weight" uservalue="400"/></location></instance>
    <instance stylename="Italic"><location><dimension name="Italic" uservalue="1"/></location></instance>
    <instance stylename="Narrow Italic">
      <location><dimension name="Italic" uservalue="1"/><dimension name="Width" uservalue="75"/></location>
    </instance>
  </instances>
</designspace>
"#;

    fn names(doc: &DesignSpaceDocument) -> Vec<String> {
        doc.sources.iter().filter_map(|s| s.name.clone()).collect()
    }

    /// Each location as `(axis, user value)` pairs.
    fn places(dims: impl Iterator<Item = Vec<Dimension>>) -> Vec<Vec<(String, f64)>> {
        dims.map(|d| {
            d.iter()
                .map(|d| (d.name.clone(), d.uservalue.or(d.xvalue).unwrap_or(f64::NAN)))
                .collect()
        })
        .collect()
    }

    /// Each rule's name and condition sets, each condition `(axis, min, max)`.
    type Conditions = Vec<(String, Vec<Vec<(String, Option<f64>, Option<f64>)>>)>;

    fn conditions(doc: &DesignSpaceDocument) -> Conditions {
        doc.rules
            .rules
            .iter()
            .map(|r| {
                let sets = r
                    .condition_sets
                    .iter()
                    .map(|s| {
                        s.conditions
                            .iter()
                            .map(|c| (c.name.clone(), c.minimum, c.maximum))
                            .collect()
                    })
                    .collect();
                (r.name.clone().unwrap_or_default(), sets)
            })
            .collect()
    }

    #[test]
    fn the_default_location_keeps_its_sources_instances_and_rules() {
        let (doc, place) = at_discrete_location(doc(XML), None).expect("cuts");
        let place = place.expect("a discrete location");
        let tags: Vec<&str> = doc.axes.iter().map(|a| a.tag.as_str()).collect();
        assert_eq!(tags, ["wght", "wdth"]);
        assert_eq!(names(&doc), ["L", "B", "N"]);
        // Full locations, without the discrete axis.
        let w = |v: f64| ("Weight".to_string(), v);
        let d = |v: f64| ("Width".to_string(), v);
        assert_eq!(
            places(doc.sources.iter().map(|s| s.location.clone())),
            [
                vec![w(100.0), d(100.0)],
                vec![w(900.0), d(100.0)],
                vec![d(75.0), w(100.0)]
            ]
        );
        assert_eq!(
            places(doc.instances.iter().map(|i| i.location.clone())),
            [vec![w(400.0), d(100.0)]]
        );
        // `upright heavy` keeps its Weight condition; `italic` keeps the set on Width
        // only (Italic ≥ 50 fails at 0).
        assert_eq!(
            conditions(&doc),
            [
                (
                    "upright heavy".to_string(),
                    vec![vec![("Weight".to_string(), Some(600.0), None)]]
                ),
                (
                    "italic".to_string(),
                    vec![vec![("Width".to_string(), None, Some(80.0))]]
                ),
            ]
        );
        assert_eq!(place.at(), "ital=0");
        assert_eq!((place.sources, place.instances), ((3, 5), (1, 3)));
        assert!(place.notes.is_empty(), "{:?}", place.notes);
        assert_eq!(
            place.notices(),
            [
                "axis `Italic` (ital) is discrete, values 0, 1: imported ital=0; `--at ital=1` \
              imports the other"
            ]
        );
    }

    #[test]
    fn a_continuous_axis_that_no_source_there_leaves_is_pinned_at_its_default() {
        let (doc, place) = at_discrete_location(doc(XML), Some("ital=1")).expect("cuts");
        let place = place.expect("a discrete location");
        let tags: Vec<&str> = doc.axes.iter().map(|a| a.tag.as_str()).collect();
        assert_eq!(tags, ["wght"]);
        assert_eq!(names(&doc), ["LI", "BI"]);
        // The instance at Width 75 is left out; the one at the italic's default kept.
        let styles: Vec<_> = doc.instances.iter().map(|i| i.stylename.clone()).collect();
        assert_eq!(styles, [Some("Italic".to_string())]);
        // `italic` holds on its first set everywhere here (an empty set), and its second
        // (Width ≤ 80) fails at the pinned Width 100; `upright heavy` fails.
        assert_eq!(conditions(&doc), [("italic".to_string(), vec![vec![]])]);
        assert_eq!(
            place.notes,
            [
                "axis `Width` (wdth) left out: no source at ital=1 leaves its default 100",
                "named instances off the default of the axes left out, not kept: `Narrow Italic`",
                "rules that do not apply here left out: upright heavy",
            ]
        );
        assert!(place.notices().is_empty());
    }

    #[test]
    fn a_designspace_without_discrete_axes_is_left_as_it_was() {
        let xml = XML.replace(
            r#"<axis tag="ital" name="Italic" values="0 1" default="0">
      <map input="0" output="0"/><map input="1" output="100"/>
    </axis>"#,
            "",
        );
        let (cut, place) = at_discrete_location(doc(&xml), None).expect("cuts");
        assert_eq!(place, None);
        assert_eq!(cut, doc(&xml));
    }

    #[test]
    fn notices_name_each_other_value() {
        let place = DiscreteLocation {
            axes: vec![
                DiscreteAxis {
                    name: "Weight".into(),
                    tag: "wght".into(),
                    values: vec![400.0, 700.0, 900.0],
                    value: 400.0,
                    named: false,
                },
                DiscreteAxis {
                    name: "Italic".into(),
                    tag: "ital".into(),
                    values: vec![0.0, 1.0],
                    value: 1.0,
                    named: true,
                },
            ],
            ..DiscreteLocation::default()
        };
        assert_eq!(place.at(), "wght=400,ital=1");
        assert_eq!(
            place.notices(),
            [
                "axis `Weight` (wght) is discrete, values 400, 700, 900: imported wght=400; \
              `--at wght=700` or `--at wght=900` imports another"
            ]
        );
    }
}
