//! `avar`: the axis mappings. xglyph's axes are linear (user values normalise piecewise
//! linearly around the default, [`crate::designspace::Axis::normalize`]), so each axis gets
//! the identity map -1 → -1, 0 → 0, 1 → 1. The table is written anyway: FontBakery's
//! `mandatory_avar_table` asks every variable font for one, so that an instancer never
//! guesses the mapping.

use write_fonts::tables::avar::{Avar, AxisValueMap, SegmentMaps};
use write_fonts::types::F2Dot14;

/// The identity `avar` for `axis_count` axes.
pub fn avar(axis_count: usize) -> Avar {
    let identity = || {
        SegmentMaps::new(
            [-1.0, 0.0, 1.0]
                .iter()
                .map(|&v| AxisValueMap::new(F2Dot14::from_f32(v), F2Dot14::from_f32(v)))
                .collect(),
        )
    };
    Avar::new((0..axis_count).map(|_| identity()).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_identity_map_per_axis() {
        let a = avar(2);
        assert_eq!(a.axis_segment_maps.len(), 2);
        for m in &a.axis_segment_maps {
            let pairs: Vec<(f32, f32)> = m
                .axis_value_maps
                .iter()
                .map(|v| (v.from_coordinate.to_f32(), v.to_coordinate.to_f32()))
                .collect();
            assert_eq!(pairs, [(-1.0, -1.0), (0.0, 0.0), (1.0, 1.0)]);
        }
    }
}
