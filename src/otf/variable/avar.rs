//! `avar`: the axis maps. Each axis's segment map takes the user-normalised coordinate to
//! the design-normalised one where the masters blend ([`Axis::normalized_map`]): the identity
//! -1 → -1, 0 → 0, 1 → 1 for an axis without a `map`. The table is written for linear axes
//! too: FontBakery's `mandatory_avar_table` asks every variable font for one, so that an
//! instancer never guesses the mapping.

use write_fonts::tables::avar::{Avar, AxisValueMap, SegmentMaps};
use write_fonts::types::F2Dot14;

use crate::designspace::Axis;

/// The `avar` of `axes`, one segment map each.
pub fn avar(axes: &[Axis]) -> Avar {
    let segments = |a: &Axis| {
        let mut maps: Vec<AxisValueMap> = a
            .normalized_map()
            .iter()
            .map(|&(from, to)| {
                AxisValueMap::new(F2Dot14::from_f32(from as f32), F2Dot14::from_f32(to as f32))
            })
            .collect();
        // Map entries closer than one F2Dot14 step would repeat a `from` coordinate, which
        // the table may not: the first is kept.
        maps.dedup_by_key(|m| m.from_coordinate);
        SegmentMaps::new(maps)
    };
    Avar::new(axes.iter().map(segments).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pairs(a: &Avar) -> Vec<Vec<(f32, f32)>> {
        a.axis_segment_maps
            .iter()
            .map(|m| {
                m.axis_value_maps
                    .iter()
                    .map(|v| (v.from_coordinate.to_f32(), v.to_coordinate.to_f32()))
                    .collect()
            })
            .collect()
    }

    fn axis(tag: &str, map: Vec<(f64, f64)>) -> Axis {
        Axis {
            tag: tag.into(),
            name: tag.into(),
            min: 100.0,
            default: 400.0,
            max: 900.0,
            map,
        }
    }

    #[test]
    fn a_linear_axis_maps_to_itself() {
        let a = avar(&[axis("wght", vec![]), axis("wdth", vec![])]);
        let identity = vec![(-1.0, -1.0), (0.0, 0.0), (1.0, 1.0)];
        assert_eq!(pairs(&a), vec![identity.clone(), identity]);
    }

    #[test]
    fn entries_closer_than_a_step_are_written_once() {
        // 400.001 lies 1/500000 of the way from 400 to 900: 0 as F2Dot14, as 400 does.
        let a = axis(
            "wght",
            vec![(100.0, 0.0), (400.0, 40.0), (400.001, 41.0), (900.0, 90.0)],
        );
        let froms: Vec<f32> = pairs(&avar(&[a]))[0].iter().map(|p| p.0).collect();
        assert_eq!(froms, [-1.0, 0.0, 1.0]);
    }

    #[test]
    fn a_map_becomes_its_normalised_pairs() {
        // 100..400 is linear in design values; 650 lies at 0.5 in user values and at 0.8
        // in design values (0.8 as F2Dot14 is 13107/16384).
        let map = vec![(100.0, 10.0), (400.0, 40.0), (650.0, 80.0), (900.0, 90.0)];
        let a = avar(&[axis("wght", map)]);
        assert_eq!(
            pairs(&a),
            vec![vec![
                (-1.0, -1.0),
                (0.0, 0.0),
                (0.5, 13107.0 / 16384.0),
                (1.0, 1.0)
            ]]
        );
    }
}
