//! `fvar`: the axes (user ranges) and the named instances.

use write_fonts::tables::fvar::{AxisInstanceArrays, Fvar, InstanceRecord, VariationAxisRecord};
use write_fonts::types::{Fixed, NameId};

use super::naming::VariableNames;
use super::tag;
use crate::designspace::Designspace;
use crate::otf::OtfError;

/// The `fvar` table, axes and instances in design-space order.
pub fn fvar(designspace: &Designspace, names: &VariableNames) -> Result<Fvar, OtfError> {
    let f = |v: f64| Fixed::from_f64(v);
    let axes = designspace
        .axes
        .iter()
        .zip(&names.axes)
        .map(|(a, &id)| {
            Ok(VariationAxisRecord::new(
                tag(&a.tag)?,
                f(a.min),
                f(a.default),
                f(a.max),
                0,
                NameId::new(id),
            ))
        })
        .collect::<Result<Vec<_>, OtfError>>()?;
    let instances = designspace
        .instances
        .iter()
        .zip(names.instances.iter().zip(&names.ps_names))
        .map(|(instance, (&id, &ps_id))| InstanceRecord {
            subfamily_name_id: NameId::new(id),
            flags: 0,
            coordinates: designspace
                .axes
                .iter()
                .map(|a| f(instance.location.get(a)))
                .collect(),
            post_script_name_id: Some(NameId::new(ps_id)),
        })
        .collect();
    Ok(Fvar::new(AxisInstanceArrays::new(axes, instances)))
}
