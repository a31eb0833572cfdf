//! The design space of a font with masters: axes, named instances, master locations, and
//! how a position blends the masters.
//!
//! Locations are in **user coordinates** (e.g. `wght = 650`), keyed by axis tag. An axis
//! may map user values to design values (`map`, a designspace `<map>`, OpenType `avar`); the
//! masters blend linearly in design values. Each axis normalises to -1..0..1 around its
//! default as OpenType does: `fvar` normalisation of the design values, which is the user
//! normalisation followed by `avar`.
//!
//! How masters blend is OpenType's delta model (`gvar`, `HVAR`, item variation stores), with
//! the regions fontTools' `VariationModel` gives, which fontmake and fontc build with
//! ([`VariationModel`]):
//! - Masters on one axis (the others at their defaults) split it into tents, so a position
//!   blends the two masters around it on each axis, and the axes add up.
//! - A **corner master**, away from the default on several axes, gets a region that is a
//!   product of tents, cut at the earlier masters on the same axes. Its delta is what it
//!   adds to the blend of the masters before it, so a full grid of corners blends
//!   multilinearly, and a sparse one as fontTools blends it: there some weights can be
//!   negative between the masters.
//!
//! - An axis end without a master on that axis: past the outermost master the axis blends
//!   back towards the default, which it reaches at the end (OpenType's regions, as
//!   fontmake and fontc build them). `check` warns about such an end
//!   ([`Designspace::uncovered_ends`]).
//!
//! Limits: no extrapolation beyond the axes.

use std::collections::BTreeMap;

/// One design axis (`[[axis]]` in `font.toml`).
#[derive(Clone, Debug, PartialEq)]
pub struct Axis {
    /// OpenType tag, 1 to 4 printable ASCII characters, e.g. `"wght"`.
    pub tag: String,
    /// Name shown to users, e.g. `"Weight"`.
    pub name: String,
    /// Smallest user value.
    pub min: f64,
    /// User value of the default master.
    pub default: f64,
    /// Largest user value.
    pub max: f64,
    /// The axis map: `(user, design)` pairs, both strictly increasing, from `min` to `max`;
    /// design values are piecewise linear in between. Empty: design = user (linear).
    pub map: Vec<(f64, f64)>,
}

impl Axis {
    /// An axis without a map: design values are user values.
    pub fn linear(
        tag: impl Into<String>,
        name: impl Into<String>,
        min: f64,
        default: f64,
        max: f64,
    ) -> Axis {
        Axis {
            tag: tag.into(),
            name: name.into(),
            min,
            default,
            max,
            map: Vec::new(),
        }
    }

    /// `user` normalised to -1..1 in design space: `min` → -1, `default` → 0, `max` → 1,
    /// linear in the design values in between, clamped to the axis range. This is where the
    /// masters blend, OpenType's normalised coordinate after `avar`.
    pub fn normalize(&self, user: f64) -> f64 {
        if self.map.is_empty() {
            return self.normalize_user(user);
        }
        let v = self.design(user.clamp(self.min, self.max));
        normalize_between(
            v,
            self.design(self.min),
            self.design(self.default),
            self.design(self.max),
        )
    }

    /// `user` normalised linearly in user values (OpenType's coordinate before `avar`).
    pub fn normalize_user(&self, user: f64) -> f64 {
        normalize_between(
            user.clamp(self.min, self.max),
            self.min,
            self.default,
            self.max,
        )
    }

    /// The design value of `user` (itself without a map; the end pairs beyond the map).
    pub fn design(&self, user: f64) -> f64 {
        piecewise(self.map.iter().copied(), user)
    }

    /// The user value of `design`: the inverse of [`Axis::design`].
    pub fn user(&self, design: f64) -> f64 {
        piecewise(self.map.iter().map(|&(u, d)| (d, u)), design)
    }

    /// The `avar` segment map of this axis: `(user, design)` normalised pairs, one per map
    /// entry (with -1, 0 and 1 always present). Identity pairs for an axis without a map.
    pub fn normalized_map(&self) -> Vec<(f64, f64)> {
        let mut pairs: Vec<(f64, f64)> = vec![(-1.0, -1.0), (0.0, 0.0), (1.0, 1.0)];
        pairs.extend(
            self.map
                .iter()
                .map(|&(u, _)| (self.normalize_user(u), self.normalize(u))),
        );
        pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
        pairs.dedup_by(|a, b| a.0 == b.0);
        pairs
    }
}

/// `v` normalised against `min`, `default`, `max` (each side linear; 0 for an empty side).
fn normalize_between(v: f64, min: f64, default: f64, max: f64) -> f64 {
    if v < default {
        (v - default) / (default - min)
    } else if v > default {
        (v - default) / (max - default)
    } else {
        0.0
    }
}

/// The piecewise-linear function through `pairs` (sorted by input, strictly increasing) at
/// `x`; the identity when there are none. Beyond the ends it keeps the end's offset, as
/// fontTools' `piecewiseLinearMap` does (xglyph's maps span the axis, so this is only for
/// values clamped to it).
fn piecewise(pairs: impl Iterator<Item = (f64, f64)> + Clone, x: f64) -> f64 {
    let mut prev: Option<(f64, f64)> = None;
    for (a, b) in pairs.clone() {
        if x == a {
            return b;
        }
        if x < a {
            return match prev {
                Some((a0, b0)) => b0 + (x - a0) / (a - a0) * (b - b0),
                None => x + (b - a),
            };
        }
        prev = Some((a, b));
    }
    match prev {
        Some((a, b)) => x + (b - a),
        None => x,
    }
}

/// A position in the design space: user coordinates by axis tag. An axis left out is at
/// its default.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Location(pub BTreeMap<String, f64>);

impl Location {
    /// The user coordinate on `axis` (its default when the location leaves it out).
    pub fn get(&self, axis: &Axis) -> f64 {
        self.0.get(&axis.tag).copied().unwrap_or(axis.default)
    }
}

/// A named instance (`[[instance]]` in `font.toml`): a style with its position.
#[derive(Clone, Debug, PartialEq)]
pub struct NamedInstance {
    /// Style name, e.g. `"SemiBold"`.
    pub name: String,
    /// Where it sits.
    pub location: Location,
}

/// Axes, named instances and rules of a font with masters.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Designspace {
    /// The axes, in `font.toml` order (the `fvar` order).
    pub axes: Vec<Axis>,
    /// Named instances, in `font.toml` order.
    pub instances: Vec<NamedInstance>,
    /// Glyph substitutions by place, in `font.toml` order.
    pub rules: Vec<Rule>,
    /// Whether the rules apply after the font's other substitutions (the `rclt` feature,
    /// a designspace's `processing="last"`), rather than before them (`rvrn`).
    pub rules_last: bool,
}

/// Most condition boxes, over all rules, that [`Designspace::rule_regions`] overlays (every
/// combination of boxes is tried).
pub const MAX_RULE_BOXES: usize = 12;

/// A glyph substitution by place (`[[rule]]` in `font.toml`, a designspace `<rule>`): where
/// any of its condition boxes holds, each glyph of `substitutions` is drawn as its
/// alternate (the variable font's `rvrn` feature; static instances swap the two glyphs).
#[derive(Clone, Debug, PartialEq)]
pub struct Rule {
    /// Name, for messages and the designspace.
    pub name: String,
    /// Boxes in user coordinates: per axis tag, an inclusive (min, max); an axis left out
    /// is not constrained. The rule holds where any box holds.
    pub conditions: Vec<BTreeMap<String, (f64, f64)>>,
    /// (glyph, alternate) pairs, in order.
    pub substitutions: Vec<(String, String)>,
}

impl Rule {
    /// Whether the rule holds at `location` (user coordinates).
    pub fn holds_at(&self, axes: &[Axis], location: &Location) -> bool {
        self.conditions.iter().any(|b| {
            b.iter().all(|(tag, &(min, max))| {
                let v = axes
                    .iter()
                    .find(|a| &a.tag == tag)
                    .map_or(0.0, |a| location.get(a));
                min <= v && v <= max
            })
        })
    }
}

/// A master's tent on one axis: the blend weight of its deltas rises from 0 at `lower`
/// to 1 at `peak` and falls to 0 again at `upper` (normalised coordinates,
/// `lower <= peak <= upper`), as an OpenType `RegionAxisCoordinates`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tent {
    /// Index of the axis in [`Designspace::axes`].
    pub axis: usize,
    /// Where the weight starts to rise (normalised).
    pub lower: f64,
    /// Where the weight is 1: the master's own normalised coordinate.
    pub peak: f64,
    /// Where the weight is back to 0 (normalised).
    pub upper: f64,
}

impl Tent {
    /// The tent's height at normalised coordinate `v` on its axis (OpenType's scalar for
    /// one axis).
    pub fn scalar(&self, v: f64) -> f64 {
        if v == self.peak {
            1.0
        } else if v <= self.lower || v >= self.upper {
            0.0
        } else if v < self.peak {
            (v - self.lower) / (self.peak - self.lower)
        } else {
            (self.upper - v) / (self.upper - self.peak)
        }
    }
}

/// One non-default master's region: a tent on each axis where the master is away from the
/// default (in axis order), 1 on the others. A master on one axis has one tent.
#[derive(Clone, Debug, PartialEq)]
pub struct Region {
    /// The tents, by increasing axis index.
    pub tents: Vec<Tent>,
}

impl Region {
    /// The region's weight at normalised coordinates `at` (one per axis): the product of
    /// its tents' heights.
    pub fn scalar(&self, at: &[f64]) -> f64 {
        let mut scalar = 1.0;
        for tent in &self.tents {
            scalar *= tent.scalar(at[tent.axis]);
            if scalar == 0.0 {
                break;
            }
        }
        scalar
    }

    /// The region's (lower, peak, upper) on each of `axis_count` axes: zeros on the axes
    /// it does not use.
    pub fn per_axis(&self, axis_count: usize) -> Vec<[f64; 3]> {
        let mut out = vec![[0.0; 3]; axis_count];
        for t in &self.tents {
            out[t.axis] = [t.lower, t.peak, t.upper];
        }
        out
    }
}

/// The blend of a set of masters: each non-default master's region, and how much of the
/// masters before it (in the model's order) its delta leaves out, so that the sum of the
/// deltas weighted by their regions' scalars is the master itself at its location.
///
/// The regions are fontTools' (`fontTools.varLib.models.VariationModel`, with the axes in
/// `font.toml` order), except that a master on one axis ends its tent at the next master
/// outwards rather than at the axis end: the same blend, with deltas that are plain
/// differences from the default (whole numbers stay whole, so each master's rounded outline
/// comes back exactly).
#[derive(Clone, Debug, PartialEq)]
pub struct VariationModel {
    /// Per non-default master, in the order given, its region.
    pub regions: Vec<Region>,
    /// The non-default masters in the order their deltas are computed: fewer axes first.
    order: Vec<usize>,
    /// Per non-default master, the earlier masters (in [`Self::order`]) whose regions are
    /// not zero at its location, with their scalars there. The default always counts 1.
    delta_weights: Vec<Vec<(usize, f64)>>,
}

impl VariationModel {
    /// Whether every region is on one axis with plain differences as deltas (the blend is
    /// then a convex combination inside the axes).
    pub fn on_axes(&self) -> bool {
        self.delta_weights.iter().all(Vec::is_empty)
    }

    /// The regions' scalars at normalised coordinates `at`.
    pub fn scalars(&self, at: &[f64]) -> Vec<f64> {
        self.regions.iter().map(|r| r.scalar(at)).collect()
    }

    /// How much each master counts at normalised coordinates `at`: index 0 is the default
    /// master, then the non-default masters in order. The weights sum to 1. With masters on
    /// the axes only, or a full grid of corners, they are all in 0..=1 inside the axes; a
    /// sparse set of corners gives some negative weights (fontTools' "master scalars").
    pub fn weights_at(&self, at: &[f64]) -> Vec<f64> {
        let scalars = self.scalars(at);
        let mut weights = Vec::with_capacity(scalars.len() + 1);
        if self.on_axes() {
            weights.push(1.0 - scalars.iter().sum::<f64>());
            weights.extend(scalars);
            return weights;
        }
        // Each delta is its master minus the default minus the earlier deltas by their
        // weights: unfold from the last delta down, as fontTools' `getMasterScalars`.
        let mut out = scalars;
        let mut default = 1.0;
        for &i in self.order.iter().rev() {
            let w = out[i];
            default -= w;
            for &(j, dw) in &self.delta_weights[i] {
                out[j] -= w * dw;
            }
        }
        weights.push(default);
        weights.extend(out);
        weights
    }

    /// Each non-default master's delta (in order) for `values` (default first, then the
    /// non-default masters), each rounded by `round` as it is computed, so that the later
    /// deltas take up the rounding of the earlier ones (fontTools' `getDeltas`).
    pub fn deltas_by(&self, values: &[f64], round: impl Fn(f64) -> f64) -> Vec<f64> {
        let mut deltas = vec![0.0; self.regions.len()];
        for &i in &self.order {
            let mut d = values[i + 1] - values[0];
            for &(j, dw) in &self.delta_weights[i] {
                d -= deltas[j] * dw;
            }
            deltas[i] = round(d);
        }
        deltas
    }

    /// [`Self::deltas_by`] for whole numbers, rounded half to even as fontTools' varLib
    /// rounds them (Python's `round`, for `gvar`, `HVAR` and the variation store): the
    /// deltas of `gvar`, `HVAR` and the layout's variation store. A half arises only where a
    /// master's prediction weighs an odd delta by 1/2 (a master inside a corner region).
    pub fn int_deltas(&self, values: &[i32]) -> Vec<i32> {
        let values: Vec<f64> = values.iter().map(|&v| f64::from(v)).collect();
        self.deltas_by(&values, f64::round_ties_even)
            .into_iter()
            .map(|d| d as i32)
            .collect()
    }
}

impl Designspace {
    /// Normalised coordinates of `location`, one per axis.
    pub fn normalize(&self, location: &Location) -> Vec<f64> {
        self.axes
            .iter()
            .map(|a| a.normalize(location.get(a)))
            .collect()
    }

    /// The axis ends (axis index, user value) that no master on that axis alone sits at,
    /// among `masters` (user locations, the default master left out). The blend is defined
    /// there all the same: past its outermost master an axis blends back towards the
    /// default, reaching it at the end, as OpenType's regions do.
    pub fn uncovered_ends(&self, masters: &[Location]) -> Vec<(usize, f64)> {
        let norms: Vec<Vec<f64>> = masters.iter().map(|l| self.normalize(l)).collect();
        let mut ends = Vec::new();
        for (axis, a) in self.axes.iter().enumerate() {
            for (end, user) in [(-1.0, a.min), (1.0, a.max)] {
                let covered = norms
                    .iter()
                    .any(|n| off_default(n) == [axis] && n[axis] == end);
                if user != a.default && !covered {
                    ends.push((axis, user));
                }
            }
        }
        ends
    }

    /// The blend of the non-default masters at `masters` (user locations, in master order,
    /// the default master left out), or why they do not form a valid set: a master at the
    /// default, or two masters at the same place.
    pub fn model(&self, masters: &[Location]) -> Result<VariationModel, RegionError> {
        let norms: Vec<Vec<f64>> = masters.iter().map(|l| self.normalize(l)).collect();
        for (i, norm) in norms.iter().enumerate() {
            if norm.iter().all(|&v| v == 0.0) {
                return Err(RegionError::AtDefault { master: i });
            }
            if let Some(j) = norms[..i].iter().position(|n| n == norm) {
                return Err(RegionError::Duplicate {
                    first: j,
                    second: i,
                });
            }
        }
        let off = |m: usize| off_default(&norms[m]);
        let order = model_order(&norms, self.axes.len());
        let mut regions: Vec<Option<Region>> = vec![None; norms.len()];
        for (k, &m) in order.iter().enumerate() {
            let axes = off(m);
            let region = if let [axis] = axes[..] {
                on_axis_region(&norms, m, axis)
            } else {
                corner_region(&norms, m, &axes, &order[..k])
            };
            regions[m] = Some(region);
        }
        let regions: Vec<Region> = regions.into_iter().flatten().collect();
        let mut delta_weights = vec![Vec::new(); norms.len()];
        for (k, &m) in order.iter().enumerate() {
            delta_weights[m] = order[..k]
                .iter()
                .map(|&j| (j, regions[j].scalar(&norms[m])))
                .filter(|&(_, s)| s != 0.0)
                .collect();
        }
        Ok(VariationModel {
            regions,
            order,
            delta_weights,
        })
    }

    /// The axes (indices) on which `location` is away from the default.
    pub fn axes_off_default(&self, location: &Location) -> Vec<usize> {
        off_default(&self.normalize(location))
    }

    /// The glyphs drawn as others at `location`: each glyph name in `names` mapped by the
    /// rules that hold there, in order, each rule applied to the result of the ones before
    /// (as designspaceLib's `processRules`). Only the names that change are returned, in
    /// the order of `names`.
    pub fn substitutions_at<'a>(
        &self,
        location: &Location,
        names: impl IntoIterator<Item = &'a str>,
    ) -> Vec<(String, String)> {
        let holding: Vec<&Rule> = self
            .rules
            .iter()
            .filter(|r| r.holds_at(&self.axes, location))
            .collect();
        if holding.is_empty() {
            return Vec::new();
        }
        names
            .into_iter()
            .filter_map(|name| {
                let now = substituted(holding.iter().copied(), name);
                (now != name).then(|| (name.to_string(), now.to_string()))
            })
            .collect()
    }

    /// The rules as a variable font's feature variations: boxes in normalised coordinates
    /// (per constrained axis, its index and the inclusive range), each with the glyphs
    /// drawn as others inside it, the first box that holds deciding. Where boxes of several
    /// rules overlap, their intersection comes first with the rules' substitutions composed
    /// in order (as fontTools' `overlayFeatureVariations` does), so every place gets what
    /// [`Self::substitutions_at`] gives there. Fails (with the count) when the rules have
    /// more than [`MAX_RULE_BOXES`] boxes in all.
    #[allow(clippy::type_complexity)]
    pub fn rule_regions(
        &self,
    ) -> Result<Vec<(Vec<(usize, f64, f64)>, Vec<(String, String)>)>, usize> {
        // (rule, box) in normalised coordinates.
        let boxes: Vec<(usize, Vec<(usize, f64, f64)>)> = self
            .rules
            .iter()
            .enumerate()
            .flat_map(|(r, rule)| {
                rule.conditions.iter().map(move |b| {
                    let ranges = self
                        .axes
                        .iter()
                        .enumerate()
                        .filter_map(|(i, a)| {
                            let &(min, max) = b.get(&a.tag)?;
                            Some((i, a.normalize(min), a.normalize(max)))
                        })
                        .collect();
                    (r, ranges)
                })
            })
            .collect();
        if boxes.len() > MAX_RULE_BOXES {
            return Err(boxes.len());
        }
        let mut records: Vec<(Vec<usize>, Vec<(usize, f64, f64)>, Vec<(String, String)>)> =
            Vec::new();
        for subset in 1u32..(1 << boxes.len()) {
            let members: Vec<usize> = (0..boxes.len())
                .filter(|&k| subset & (1 << k) != 0)
                .collect();
            let rules: Vec<usize> = members.iter().map(|&k| boxes[k].0).collect();
            if rules.windows(2).any(|w| w[0] == w[1]) {
                continue;
            }
            // The intersection, per axis.
            let mut ranges: BTreeMap<usize, (f64, f64)> = BTreeMap::new();
            for &k in &members {
                for &(axis, min, max) in &boxes[k].1 {
                    let r = ranges.entry(axis).or_insert((min, max));
                    *r = (r.0.max(min), r.1.min(max));
                }
            }
            if ranges.values().any(|&(min, max)| min > max) {
                continue;
            }
            // The rules' substitutions composed in order, for every name they mention.
            let mut names: Vec<&str> = Vec::new();
            for &r in &rules {
                for (from, to) in &self.rules[r].substitutions {
                    for n in [from.as_str(), to.as_str()] {
                        if !names.contains(&n) {
                            names.push(n);
                        }
                    }
                }
            }
            let substitutions: Vec<(String, String)> = names
                .iter()
                .filter_map(|&name| {
                    let now = substituted(rules.iter().map(|&r| &self.rules[r]), name);
                    (now != name).then(|| (name.to_string(), now.to_string()))
                })
                .collect();
            records.push((
                rules,
                ranges
                    .into_iter()
                    .map(|(a, (min, max))| (a, min, max))
                    .collect(),
                substitutions,
            ));
        }
        // The most rules first; then in rule order.
        records.sort_by(|a, b| b.0.len().cmp(&a.0.len()).then_with(|| a.0.cmp(&b.0)));
        Ok(records.into_iter().map(|(_, b, s)| (b, s)).collect())
    }

    /// How much each master counts at `location` (default first): see
    /// [`VariationModel::weights_at`].
    pub fn weights(&self, model: &VariationModel, location: &Location) -> Vec<f64> {
        model.weights_at(&self.normalize(location))
    }
}

/// The axes (indices) on which normalised coordinates `norm` are away from the default.
fn off_default(norm: &[f64]) -> Vec<usize> {
    (0..norm.len()).filter(|&a| norm[a] != 0.0).collect()
}

/// The glyph `name` is drawn as once `rules` apply in order, each to the result of the
/// ones before (designspaceLib's `processRules`).
fn substituted<'a>(rules: impl IntoIterator<Item = &'a Rule>, name: &'a str) -> &'a str {
    let mut now = name;
    for rule in rules {
        if let Some((_, to)) = rule.substitutions.iter().find(|(from, _)| from == now) {
            now = to;
        }
    }
    now
}

/// The order fontTools computes deltas in (`getMasterLocationsSortKeyFunc`, axes in
/// `font.toml` order): fewer axes first; then more coordinates that are also on-axis
/// masters' coordinates; then by the axes used, their signs, and the distance from the
/// default.
fn model_order(norms: &[Vec<f64>], axis_count: usize) -> Vec<usize> {
    let off = |m: usize| off_default(&norms[m]);
    // Per axis, the coordinates of the masters on that axis alone.
    let on_axis: Vec<Vec<f64>> = (0..axis_count)
        .map(|a| {
            (0..norms.len())
                .filter(|&m| off(m) == [a])
                .map(|m| norms[m][a])
                .collect()
        })
        .collect();
    let key = |m: usize| {
        let axes = off(m);
        let on_points = axes
            .iter()
            .filter(|&&a| on_axis[a].contains(&norms[m][a]))
            .count();
        let signs: Vec<i8> = axes
            .iter()
            .map(|&a| if norms[m][a] < 0.0 { -1 } else { 1 })
            .collect();
        let sizes: Vec<f64> = axes.iter().map(|&a| norms[m][a].abs()).collect();
        (axes.len(), usize::MAX - on_points, axes, signs, sizes)
    };
    let mut order: Vec<usize> = (0..norms.len()).collect();
    order.sort_by(|&a, &b| {
        let (ka, kb) = (key(a), key(b));
        (ka.0, ka.1, &ka.2, &ka.3)
            .cmp(&(kb.0, kb.1, &kb.2, &kb.3))
            .then_with(|| {
                ka.4.iter()
                    .zip(&kb.4)
                    .map(|(x, y)| x.total_cmp(y))
                    .find(|o| o.is_ne())
                    .unwrap_or(std::cmp::Ordering::Equal)
            })
    });
    order
}

/// The tent of master `m`, on `axis` alone: from its neighbour towards the default (or the
/// default) to its neighbour away from it (or, when it is the outermost, the axis end: its
/// own peak when it sits there, else the blend goes back to the default at the end, as in
/// fontTools).
fn on_axis_region(norms: &[Vec<f64>], m: usize, axis: usize) -> Region {
    let peak = norms[m][axis];
    let same_side: Vec<f64> = norms
        .iter()
        .filter(|n| n[axis] * peak > 0.0 && off_default(n) == [axis])
        .map(|n| n[axis])
        .collect();
    let inner = same_side
        .iter()
        .copied()
        .filter(|v| v.abs() < peak.abs())
        .max_by(|a, b| a.abs().total_cmp(&b.abs()))
        .unwrap_or(0.0);
    let outer = same_side
        .iter()
        .copied()
        .filter(|v| v.abs() > peak.abs())
        .min_by(|a, b| a.abs().total_cmp(&b.abs()))
        .unwrap_or(peak.signum());
    Region {
        tents: vec![Tent {
            axis,
            lower: inner.min(outer),
            peak,
            upper: inner.max(outer),
        }],
    }
}

/// The region of corner master `m` on `axes`, fontTools' way: the box from the default to
/// the axis ends on its side, cut at each earlier master on the same axes inside it, on
/// the axes where the cut leaves the largest share of the box (all of them on a tie).
fn corner_region(norms: &[Vec<f64>], m: usize, axes: &[usize], earlier: &[usize]) -> Region {
    let mut tents: Vec<Tent> = axes
        .iter()
        .map(|&axis| {
            let peak = norms[m][axis];
            let (lower, upper) = if peak > 0.0 { (0.0, 1.0) } else { (-1.0, 0.0) };
            Tent {
                axis,
                lower,
                peak,
                upper,
            }
        })
        .collect();
    for &j in earlier.iter().filter(|&&j| off_default(&norms[j]) == axes) {
        let inside = tents.iter().all(|t| {
            let v = norms[j][t.axis];
            v == t.peak || (t.lower < v && v < t.upper)
        });
        if !inside {
            continue;
        }
        let mut best: Vec<(usize, Tent)> = Vec::new();
        let mut best_ratio = -1.0;
        for (k, t) in tents.iter().enumerate() {
            let v = norms[j][t.axis];
            let (cut, ratio) = if v < t.peak {
                (Tent { lower: v, ..*t }, (v - t.peak) / (t.lower - t.peak))
            } else if v > t.peak {
                (Tent { upper: v, ..*t }, (v - t.peak) / (t.upper - t.peak))
            } else {
                continue;
            };
            if ratio > best_ratio {
                best.clear();
                best_ratio = ratio;
            }
            if ratio == best_ratio {
                best.push((k, cut));
            }
        }
        for (k, cut) in best {
            tents[k] = cut;
        }
    }
    Region { tents }
}

/// Why a set of master locations cannot be blended ([`Designspace::model`]).
#[derive(Clone, Debug, PartialEq)]
pub enum RegionError {
    /// The master (index among the non-default masters) sits at the default location.
    AtDefault {
        /// The master.
        master: usize,
    },
    /// Two masters at the same location.
    Duplicate {
        /// The first of the two.
        first: usize,
        /// The second.
        second: usize,
    },
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Axes `w` and `h`, each from `min` to `max` of its pair with the default 0.
    fn plane(w: (f64, f64), h: (f64, f64)) -> Designspace {
        Designspace {
            axes: vec![
                Axis::linear("w", "W", w.0, 0.0, w.1),
                Axis::linear("h", "H", h.0, 0.0, h.1),
            ],
            instances: vec![],
            rules: Vec::new(),
            rules_last: false,
        }
    }

    /// The location `{ w, h }` of [`plane`].
    fn loc(w: f64, h: f64) -> Location {
        Location([("w".into(), w), ("h".into(), h)].into_iter().collect())
    }

    fn wght() -> Designspace {
        Designspace {
            axes: vec![Axis::linear("wght", "Weight", 400.0, 400.0, 700.0)],
            instances: vec![],
            rules: Vec::new(),
            rules_last: false,
        }
    }

    fn at(w: f64) -> Location {
        Location([("wght".to_string(), w)].into_iter().collect())
    }

    #[test]
    fn normalise_is_piecewise_linear_and_clamped() {
        let a = Axis::linear("wght", "Weight", 100.0, 400.0, 900.0);
        assert_eq!(a.normalize(100.0), -1.0);
        assert_eq!(a.normalize(250.0), -0.5);
        assert_eq!(a.normalize(400.0), 0.0);
        assert_eq!(a.normalize(650.0), 0.5);
        assert_eq!(a.normalize(1000.0), 1.0);
    }

    /// Weight 100..400..900 whose design values crowd the heavy end: 600 is 80 % of the
    /// way to the Black master in design space, though 40 % in user values.
    fn mapped() -> Axis {
        Axis {
            tag: "wght".into(),
            name: "Weight".into(),
            min: 100.0,
            default: 400.0,
            max: 900.0,
            map: vec![(100.0, 0.0), (400.0, 50.0), (600.0, 90.0), (900.0, 100.0)],
        }
    }

    #[test]
    fn a_map_normalises_in_design_values() {
        let a = mapped();
        assert_eq!(a.design(750.0), 95.0);
        assert_eq!(a.user(95.0), 750.0);
        assert_eq!(a.normalize(600.0), 0.8);
        assert_eq!(a.normalize_user(600.0), 0.4);
        assert_eq!(a.normalize(750.0), 0.9);
        assert_eq!(a.normalize(250.0), -0.5);
        assert_eq!(a.normalize(100.0), -1.0);
        assert_eq!(a.normalize(2000.0), 1.0);
        assert_eq!(
            a.normalized_map(),
            vec![(-1.0, -1.0), (0.0, 0.0), (0.4, 0.8), (1.0, 1.0)]
        );
        let mut linear = mapped();
        linear.map.clear();
        assert_eq!(
            linear.normalized_map(),
            vec![(-1.0, -1.0), (0.0, 0.0), (1.0, 1.0)]
        );
        assert_eq!(linear.design(650.0), 650.0);
    }

    #[test]
    fn masters_blend_along_the_map() {
        let ds = Designspace {
            axes: vec![mapped()],
            instances: vec![],
            rules: Vec::new(),
            rules_last: false,
        };
        let model = ds.model(&[at(100.0), at(900.0)]).unwrap();
        let w = ds.weights(&model, &at(600.0));
        assert!((w[0] - 0.2).abs() < 1e-12 && w[1] == 0.0 && (w[2] - 0.8).abs() < 1e-12);
    }

    fn tent(axis: usize, lower: f64, peak: f64, upper: f64) -> Tent {
        Tent {
            axis,
            lower,
            peak,
            upper,
        }
    }

    #[test]
    fn two_masters_blend_linearly() {
        let ds = wght();
        let model = ds.model(&[at(700.0)]).unwrap();
        assert_eq!(
            model.regions,
            vec![Region {
                tents: vec![tent(0, 0.0, 1.0, 1.0)]
            }]
        );
        assert!(model.on_axes());
        assert_eq!(ds.weights(&model, &at(400.0)), vec![1.0, 0.0]);
        assert_eq!(ds.weights(&model, &at(550.0)), vec![0.5, 0.5]);
        assert_eq!(ds.weights(&model, &at(700.0)), vec![0.0, 1.0]);
        assert_eq!(model.int_deltas(&[10, 25]), vec![15]);
    }

    #[test]
    fn an_intermediate_master_splits_the_axis() {
        let ds = wght();
        // Bold at 700, Medium at 500 (normalised 1/3).
        let model = ds.model(&[at(700.0), at(500.0)]).unwrap();
        assert_eq!(model.regions[0].tents, vec![tent(0, 1.0 / 3.0, 1.0, 1.0)]);
        assert_eq!(model.regions[1].tents, vec![tent(0, 0.0, 1.0 / 3.0, 1.0)]);
        let w = ds.weights(&model, &at(600.0));
        // Halfway between Medium and Bold.
        assert!((w[0]).abs() < 1e-12, "{w:?}");
        assert!((w[1] - 0.5).abs() < 1e-12, "{w:?}");
        assert!((w[2] - 0.5).abs() < 1e-12, "{w:?}");
        let w = ds.weights(&model, &at(450.0));
        assert!((w[0] - 0.5).abs() < 1e-12 && w[1] == 0.0 && (w[2] - 0.5).abs() < 1e-12);
        // Plain differences from the default.
        assert_eq!(model.int_deltas(&[10, 30, 14]), vec![20, 4]);
    }

    /// Two axes normalised as user value / 100, with masters on both and three corners,
    /// one of them between the others (`w` 50). Expected values are fontTools 4.68's
    /// `VariationModel(locations, axisOrder=["w", "h"])`: `supports`,
    /// `getMasterScalars` and `getDeltas(round=round)`, for the same master order.
    #[test]
    fn corner_masters_blend_as_fonttools() {
        let ds = plane((-100.0, 100.0), (-100.0, 100.0));
        let masters = [
            loc(100.0, 100.0),
            loc(-100.0, 0.0),
            loc(0.0, 100.0),
            loc(100.0, 0.0),
            loc(50.0, 100.0),
            loc(0.0, -100.0),
            loc(-100.0, -100.0),
        ];
        let model = ds.model(&masters).unwrap();
        assert!(!model.on_axes());
        let tents: Vec<Vec<Tent>> = model.regions.iter().map(|r| r.tents.clone()).collect();
        assert_eq!(
            tents,
            vec![
                vec![tent(0, 0.0, 1.0, 1.0), tent(1, 0.0, 1.0, 1.0)],
                vec![tent(0, -1.0, -1.0, 0.0)],
                vec![tent(1, 0.0, 1.0, 1.0)],
                vec![tent(0, 0.0, 1.0, 1.0)],
                vec![tent(0, 0.0, 0.5, 1.0), tent(1, 0.0, 1.0, 1.0)],
                vec![tent(1, -1.0, -1.0, 0.0)],
                vec![tent(0, -1.0, -1.0, 0.0), tent(1, -1.0, -1.0, 0.0)],
            ]
        );
        for ((w, h), expected) in [
            ((75.0, 50.0), [0.125, 0.25, 0.0, 0.0, 0.375, 0.25, 0.0, 0.0]),
            ((-100.0, 100.0), [-1.0, 0.0, 1.0, 1.0, 0.0, 0.0, 0.0, 0.0]),
            (
                (-50.0, -25.0),
                [0.375, 0.0, 0.375, 0.0, 0.0, 0.0, 0.125, 0.125],
            ),
            ((25.0, 100.0), [0.0, 0.0, 0.0, 0.5, 0.0, 0.5, 0.0, 0.0]),
        ] {
            let got = ds.weights(&model, &loc(w, h));
            let off = got
                .iter()
                .zip(expected)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            assert!(off < 1e-12, "at ({w}, {h}): {got:?}, expected {expected:?}");
        }
        // At every master its own weight is 1 and the others 0.
        for (m, l) in masters.iter().enumerate() {
            let got = ds.weights(&model, l);
            for (k, w) in got.iter().enumerate() {
                assert!(
                    (w - f64::from(k == m + 1)).abs() < 1e-12,
                    "master {m}: {got:?}"
                );
            }
        }
        assert_eq!(
            model.int_deltas(&[10, 57, 3, 21, 30, 41, -4, -20]),
            vec![16, -7, 11, 20, 2, -14, -9]
        );
    }

    /// A master inside a corner region, where its prediction is a half: fontTools 4.68's
    /// `getDeltas(round=round)` (what varLib uses for `gvar` and `HVAR`) gives 108, where
    /// `otRound` would give 109.
    #[test]
    fn deltas_round_half_to_even_as_varlib() {
        let ds = plane((0.0, 100.0), (-100.0, 0.0));
        let masters = [
            loc(100.0, 0.0),
            loc(0.0, -100.0),
            loc(100.0, -100.0),
            loc(50.0, -50.0),
        ];
        let model = ds.model(&masters).unwrap();
        assert_eq!(
            model.int_deltas(&[560, 590, 448, 448, 620]),
            vec![30, -112, -30, 108]
        );
    }

    #[test]
    fn bad_master_sets_are_named() {
        let ds = wght();
        assert_eq!(
            ds.model(&[at(400.0)]),
            Err(RegionError::AtDefault { master: 0 })
        );
        assert_eq!(
            ds.model(&[at(700.0), at(700.0)]),
            Err(RegionError::Duplicate {
                first: 0,
                second: 1
            })
        );
    }

    /// An axis end without a master on that axis: the blend goes back to the default there,
    /// with fontTools' master scalars (`VariationModel.getMasterScalars`, fontTools 4.68:
    /// a master at 2/3 gives `[0.25, 0.75]` at 0.5, `[0.4, 0.6]` at 0.8, `[1, 0]` at 1; a
    /// corner alone at (1, -1) beside a master at (1, 0) gives `[0.5, 0.25, 0.25]` at
    /// (0.5, -0.5) and the default at (0, -1)).
    #[test]
    fn an_uncovered_end_blends_back_to_the_default_as_fonttools() {
        let ds = wght();
        let model = ds.model(&[at(600.0)]).expect("a valid set");
        assert_eq!(ds.uncovered_ends(&[at(600.0)]), vec![(0, 700.0)]);
        assert!(ds.uncovered_ends(&[at(700.0)]).is_empty());
        let close = |got: Vec<f64>, want: &[f64]| {
            assert_eq!(got.len(), want.len());
            for (g, w) in got.iter().zip(want) {
                assert!((g - w).abs() < 1e-12, "{got:?} against {want:?}");
            }
        };
        close(model.weights_at(&[0.5]), &[0.25, 0.75]);
        close(model.weights_at(&[2.0 / 3.0]), &[0.0, 1.0]);
        close(model.weights_at(&[0.8]), &[0.4, 0.6]);
        close(model.weights_at(&[1.0]), &[1.0, 0.0]);

        // A corner master alone leaves the width axis's end without a master on it.
        let mut two = wght();
        two.axes
            .push(Axis::linear("wdth", "Width", 75.0, 100.0, 100.0));
        let mut corner = at(700.0);
        corner.0.insert("wdth".into(), 75.0);
        let masters = [at(700.0), corner];
        assert_eq!(two.uncovered_ends(&masters), vec![(1, 75.0)]);
        let model = two.model(&masters).expect("a valid set");
        close(model.weights_at(&[0.5, -0.5]), &[0.5, 0.25, 0.25]);
        close(model.weights_at(&[0.0, -1.0]), &[1.0, 0.0, 0.0]);
        close(model.weights_at(&[1.0, -1.0]), &[0.0, 0.0, 1.0]);
    }
}
