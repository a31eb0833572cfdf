//! The design space of a font with masters: axes, named instances, master locations, and
//! how a position blends the masters.
//!
//! Locations are in **user coordinates** (e.g. `wght = 650`), keyed by axis tag. An axis
//! may map user values to design values (`map`, a designspace `<map>`, OpenType `avar`); the
//! masters blend linearly in design values. Each axis normalises to -1..0..1 around its
//! default as OpenType does: `fvar` normalisation of the design values, which is the user
//! normalisation followed by `avar`.
//!
//! Limit: every master other than the default lies **on one axis** (all other coordinates at
//! their defaults). Masters on the same axis split it into tents, so a position blends the
//! two masters around it on each axis, and the axes add up. This is the OpenType delta model
//! (`gvar`, `HVAR`, item variation stores) restricted to single-axis regions, which is
//! what a weight axis, or several independent axes without corner masters, need.

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

/// Axes and named instances of a font with masters.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Designspace {
    /// The axes, in `font.toml` order (the `fvar` order).
    pub axes: Vec<Axis>,
    /// Named instances, in `font.toml` order.
    pub instances: Vec<NamedInstance>,
}

/// One non-default master's region on its axis: the blend weight of its deltas is a tent
/// that is 0 at `start`, 1 at `peak` and 0 again at `end` (normalised coordinates), as an
/// OpenType `RegionAxisCoordinates` / gvar tuple with intermediate region.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Region {
    /// Index of the axis in [`Designspace::axes`].
    pub axis: usize,
    /// Where the weight starts to rise (normalised).
    pub start: f64,
    /// Where the weight is 1: the master's own normalised coordinate.
    pub peak: f64,
    /// Where the weight is back to 0 (normalised).
    pub end: f64,
}

impl Region {
    /// The tent's height at normalised coordinate `v` on its axis (the OpenType region
    /// scalar for one axis).
    pub fn scalar(&self, v: f64) -> f64 {
        if v == self.peak {
            return 1.0;
        }
        if v <= self.start.min(self.end) || v >= self.start.max(self.end) {
            return 0.0;
        }
        if (v < self.peak) == (self.start < self.peak) {
            (v - self.start) / (self.peak - self.start)
        } else {
            (self.end - v) / (self.end - self.peak)
        }
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

    /// The regions of the non-default masters at `masters` (user locations, in master
    /// order, the default master left out), or why they do not form a valid set: a master
    /// off the axes (two coordinates away from the default), at the default, two masters at
    /// the same place, or an axis end with no master (the blend would fall back to the
    /// default beyond the outermost master, as OpenType regions do).
    ///
    /// On each axis the masters split the range: a master's tent starts at its neighbour
    /// towards the default (or the default, 0) and ends at its neighbour away from it (or at
    /// its own peak, the axis end, when it is the outermost).
    pub fn regions(&self, masters: &[Location]) -> Result<Vec<Region>, RegionError> {
        let mut on_axis = Vec::with_capacity(masters.len());
        for (i, loc) in masters.iter().enumerate() {
            let norm = self.normalize(loc);
            let off: Vec<usize> = (0..norm.len()).filter(|&a| norm[a] != 0.0).collect();
            match off[..] {
                [] => return Err(RegionError::AtDefault { master: i }),
                [axis] => on_axis.push((axis, norm[axis])),
                _ => return Err(RegionError::OffAxis { master: i }),
            }
        }
        let mut regions = Vec::with_capacity(masters.len());
        for (i, &(axis, peak)) in on_axis.iter().enumerate() {
            let same_side = |&(a, p): &(usize, f64)| a == axis && p * peak > 0.0;
            if let Some(j) = on_axis
                .iter()
                .enumerate()
                .position(|(j, m)| j != i && m.0 == axis && m.1 == peak)
            {
                return Err(RegionError::Duplicate {
                    first: i.min(j),
                    second: i.max(j),
                });
            }
            let inner = on_axis
                .iter()
                .filter(|m| same_side(m) && m.1.abs() < peak.abs())
                .map(|m| m.1)
                .max_by(|a, b| a.abs().total_cmp(&b.abs()))
                .unwrap_or(0.0);
            let outer = on_axis
                .iter()
                .filter(|m| same_side(m) && m.1.abs() > peak.abs())
                .map(|m| m.1)
                .min_by(|a, b| a.abs().total_cmp(&b.abs()))
                .unwrap_or(peak);
            regions.push(Region {
                axis,
                start: inner,
                peak,
                end: outer,
            });
        }
        for (axis, a) in self.axes.iter().enumerate() {
            for (end, user) in [(-1.0, a.min), (1.0, a.max)] {
                let covered = regions.iter().any(|r| r.axis == axis && r.peak == end);
                if user != a.default && !covered {
                    return Err(RegionError::UncoveredEnd { axis, user });
                }
            }
        }
        Ok(regions)
    }

    /// How much each master counts at `location`: index 0 is the default master, then the
    /// masters of `regions` in order. The weights sum to 1; inside the masters' span they
    /// are all in 0..=1, so the blend is a convex combination.
    pub fn weights(&self, regions: &[Region], location: &Location) -> Vec<f64> {
        let at = self.normalize(location);
        let deltas: Vec<f64> = regions.iter().map(|r| r.scalar(at[r.axis])).collect();
        let mut weights = Vec::with_capacity(regions.len() + 1);
        weights.push(1.0 - deltas.iter().sum::<f64>());
        weights.extend(deltas);
        weights
    }
}

/// Why a set of master locations cannot be blended ([`Designspace::regions`]).
#[derive(Clone, Debug, PartialEq)]
pub enum RegionError {
    /// The master (index among the non-default masters) sits at the default location.
    AtDefault {
        /// The master.
        master: usize,
    },
    /// The master is away from the default on more than one axis.
    OffAxis {
        /// The master.
        master: usize,
    },
    /// An axis end (`min` or `max` away from the default) has no master.
    UncoveredEnd {
        /// Index of the axis.
        axis: usize,
        /// The user value of the end.
        user: f64,
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

    fn wght() -> Designspace {
        Designspace {
            axes: vec![Axis::linear("wght", "Weight", 400.0, 400.0, 700.0)],
            instances: vec![],
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
        };
        let regions = ds.regions(&[at(100.0), at(900.0)]).unwrap();
        let w = ds.weights(&regions, &at(600.0));
        assert!((w[0] - 0.2).abs() < 1e-12 && w[1] == 0.0 && (w[2] - 0.8).abs() < 1e-12);
    }

    #[test]
    fn two_masters_blend_linearly() {
        let ds = wght();
        let regions = ds.regions(&[at(700.0)]).unwrap();
        assert_eq!(
            regions,
            vec![Region {
                axis: 0,
                start: 0.0,
                peak: 1.0,
                end: 1.0
            }]
        );
        assert_eq!(ds.weights(&regions, &at(400.0)), vec![1.0, 0.0]);
        assert_eq!(ds.weights(&regions, &at(550.0)), vec![0.5, 0.5]);
        assert_eq!(ds.weights(&regions, &at(700.0)), vec![0.0, 1.0]);
    }

    #[test]
    fn an_intermediate_master_splits_the_axis() {
        let ds = wght();
        // Bold at 700, Medium at 500 (normalised 1/3).
        let regions = ds.regions(&[at(700.0), at(500.0)]).unwrap();
        assert_eq!(regions[0].start, 1.0 / 3.0);
        assert_eq!(regions[1].end, 1.0);
        let w = ds.weights(&regions, &at(600.0));
        // Halfway between Medium and Bold.
        assert!((w[0]).abs() < 1e-12, "{w:?}");
        assert!((w[1] - 0.5).abs() < 1e-12, "{w:?}");
        assert!((w[2] - 0.5).abs() < 1e-12, "{w:?}");
        let w = ds.weights(&regions, &at(450.0));
        assert!((w[0] - 0.5).abs() < 1e-12 && w[1] == 0.0 && (w[2] - 0.5).abs() < 1e-12);
    }

    #[test]
    fn bad_master_sets_are_named() {
        let ds = wght();
        assert_eq!(
            ds.regions(&[at(400.0)]),
            Err(RegionError::AtDefault { master: 0 })
        );
        assert_eq!(
            ds.regions(&[at(700.0), at(700.0)]),
            Err(RegionError::Duplicate {
                first: 0,
                second: 1
            })
        );
        let mut two = wght();
        two.axes
            .push(Axis::linear("wdth", "Width", 75.0, 100.0, 100.0));
        let mut corner = at(700.0);
        corner.0.insert("wdth".into(), 75.0);
        assert_eq!(
            two.regions(&[corner]),
            Err(RegionError::OffAxis { master: 0 })
        );
        assert_eq!(
            ds.regions(&[at(600.0)]),
            Err(RegionError::UncoveredEnd {
                axis: 0,
                user: 700.0
            })
        );
    }
}
