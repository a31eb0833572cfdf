//! Name IDs of the variable font's axes and named instances (from 256, as `fvar` and
//! `STAT` require), shared by `fvar`, `STAT` and `name`: axis names, instance style names
//! and instance PostScript names (`Family-Style`, as for a static font), plus name ID 25,
//! the PostScript family prefix for instances a consumer makes itself.

use crate::designspace::Designspace;
use crate::otf::naming::ps_font_name;

/// Name IDs given out for one design space, and the records to add to `name`.
pub struct VariableNames {
    /// Per axis, the ID of its name.
    pub axes: Vec<u16>,
    /// Per named instance, the ID of its style name.
    pub instances: Vec<u16>,
    /// Per named instance, the ID of its PostScript name.
    pub ps_names: Vec<u16>,
    /// `(id, text)` records, IDs from `first` (256, or after the layout's names) upwards;
    /// equal texts share one ID.
    pub records: Vec<(u16, String)>,
}

impl VariableNames {
    /// IDs for the axis names, the instance names, then their PostScript names, in
    /// design-space order, for the family named `family`, from ID `first` (at least 256).
    pub fn new(designspace: &Designspace, family: &str, first: u16) -> Self {
        let mut records: Vec<(u16, String)> = Vec::new();
        let mut id_of = |text: &str| -> u16 {
            if let Some((id, _)) = records.iter().find(|(_, t)| t == text) {
                return *id;
            }
            let id = first + records.len() as u16;
            records.push((id, text.to_owned()));
            id
        };
        let axes = designspace.axes.iter().map(|a| id_of(&a.name)).collect();
        let instances = designspace
            .instances
            .iter()
            .map(|i| id_of(&i.name))
            .collect();
        let ps_names = designspace
            .instances
            .iter()
            .map(|i| id_of(&ps_font_name(family, &i.name)))
            .collect();
        records.push((25, ps_font_name(family, "")));
        VariableNames {
            axes,
            instances,
            ps_names,
            records,
        }
    }
}
