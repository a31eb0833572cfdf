//! `STAT`: one axis record per axis and one axis value (format 1) per named instance on
//! that axis; the value at the axis default is elidable ("Regular" is left out of
//! "Family Bold"), and name ID 2 is the fallback when every value is elided.
//!
//! Limit: an instance away from the default on several axes gets no axis value (format 4
//! would be needed); with one axis every instance has its value.

use write_fonts::tables::stat::{AxisRecord, AxisValue, AxisValueTableFlags, Stat};
use write_fonts::types::{Fixed, NameId};

use super::naming::VariableNames;
use super::tag;
use crate::designspace::Designspace;
use crate::otf::OtfError;

/// The `STAT` table of `designspace`.
pub fn stat(designspace: &Designspace, names: &VariableNames) -> Result<Stat, OtfError> {
    let axes = designspace
        .axes
        .iter()
        .zip(&names.axes)
        .enumerate()
        .map(|(i, (a, &id))| Ok(AxisRecord::new(tag(&a.tag)?, NameId::new(id), i as u16)))
        .collect::<Result<Vec<_>, OtfError>>()?;
    let mut values: Vec<(u16, f64, u16)> = Vec::new();
    for (instance, &name) in designspace.instances.iter().zip(&names.instances) {
        let away: Vec<usize> = (0..designspace.axes.len())
            .filter(|&i| {
                let a = &designspace.axes[i];
                instance.location.get(a) != a.default
            })
            .collect();
        // On the axis it moves along, or on every axis for the default instance.
        let on: Vec<usize> = match away[..] {
            [] => (0..designspace.axes.len()).collect(),
            [axis] => vec![axis],
            _ => continue,
        };
        for axis in on {
            let value = instance.location.get(&designspace.axes[axis]);
            if !values
                .iter()
                .any(|&(a, v, _)| a == axis as u16 && v == value)
            {
                values.push((axis as u16, value, name));
            }
        }
    }
    values.sort_by(|a, b| a.0.cmp(&b.0).then(a.1.total_cmp(&b.1)));
    let axis_values = values
        .into_iter()
        .map(|(axis, value, name)| {
            let flags = if value == designspace.axes[usize::from(axis)].default {
                AxisValueTableFlags::ELIDABLE_AXIS_VALUE_NAME
            } else {
                AxisValueTableFlags::empty()
            };
            AxisValue::format_1(axis, flags, NameId::new(name), Fixed::from_f64(value))
        })
        .collect();
    Ok(Stat::new(axes, axis_values, NameId::new(2)))
}
