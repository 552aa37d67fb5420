//! Material light lists (`lights: ["key", …]`, mental ray's `"lights"` parameter): each
//! name resolved to the light's index in the light set (lights are spawned in merged order,
//! so the emitter index is the merged index). An unknown name is a located error with a
//! suggestion; a repeated name is harmless.

use std::sync::Arc;

use super::diagnostics::Sources;
use super::suggest::suggestion;
use super::validate::Merged;
use crate::components::Material;

/// Sets the light list of every checked material that writes one.
pub fn attach(
    src: &mut Sources,
    m: &Merged<'_>,
    materials: &mut [Option<crate::components::Material>],
) {
    let names: Vec<&str> = m.lights.iter().map(|l| l.desc.name.as_str()).collect();
    for (item, material) in m.materials.iter().zip(materials.iter_mut()) {
        let Some(list) = &item.desc.lights else {
            continue;
        };
        let mut indices = Vec::with_capacity(list.len());
        for (j, name) in list.iter().enumerate() {
            match names.iter().position(|n| n == name) {
                Some(i) => indices.push(i as u32),
                None => src.error(
                    item.file,
                    &item.at(&format!(".lights[{j}]")),
                    format!("unknown light \"{name}\""),
                    suggestion(name, &names, "lights"),
                ),
            }
        }
        if let Some(Material { lights, .. }) = material.as_mut() {
            *lights = Some(Arc::from(indices));
        }
    }
}
