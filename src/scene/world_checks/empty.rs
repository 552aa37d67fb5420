//! Objects that would render nothing without a word (issue 18, family 8): a mesh file with
//! no triangles, a subdivision mesh with no faces. The scene still loads; each placed object
//! gets a located warning.

use std::collections::BTreeMap;
use std::sync::Arc;

use hecs::World;

use crate::components::{Instance, Name, SourceLink, SubdivMesh, TriMesh};

/// `file:line:col: warning: …` texts for every placed object with no geometry, in entity
/// order.
pub fn warnings(world: &World) -> Vec<String> {
    let mut found: BTreeMap<u64, String> = BTreeMap::new();
    for inst in world.query::<&Instance>().iter() {
        let o = inst.object;
        let why = if let Ok(m) = world.get::<&Arc<TriMesh>>(o) {
            m.triangles
                .is_empty()
                .then_some("its mesh has no triangles")
        } else if let Ok(s) = world.get::<&SubdivMesh>(o) {
            s.face_sizes
                .is_empty()
                .then_some("its subdivision mesh has no faces")
        } else {
            None
        };
        let Some(why) = why else { continue };
        let name = world
            .get::<&Name>(o)
            .map_or_else(|_| "?".to_string(), |n| n.0.clone());
        let at = world.get::<&SourceLink>(o).map_or_else(
            |_| String::new(),
            |l| format!("{}:{}:{}: ", l.file.display(), l.line, l.column),
        );
        found.entry(o.to_bits().get()).or_insert_with(|| {
            format!(
                "{at}warning: object \"{name}\": {why}; it renders nothing\n  help: check the mesh, or leave the object out"
            )
        });
    }
    found.into_values().collect()
}
