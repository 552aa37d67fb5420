//! Rendering past one machine: a render divided into parts (`render --part K/N`), each part
//! written as a part file, and an exact merge (`stagelight merge`) whose output is
//! bit-identical to the single-machine render for any part count and either split; plus the
//! Slurm batch scripts that run the parts as a job array (`stagelight farm`).
//!
//! This module owns the division ([`part`]), the part file ([`part_file`]), the merge
//! ([`merge`]) and the script writer ([`slurm`]). The `shade` stage computes a part's
//! pixels and the `write_output` stage writes its file; the merge feeds the merged buffers
//! back through the stage table as a run input.

pub mod bake_part;
pub mod bake_part_file;
pub mod changed_scene;
pub mod exr_meta;
pub mod idle_bake_part;
pub mod merge;
pub mod part;
pub mod part_file;
pub mod recorded_settings;
pub mod sbatch_directive;
pub mod slurm;

use std::sync::Arc;

use crate::components::TriMesh;
use crate::framebuffer::FrameBuffers;
use crate::hash::Fnv64;
use crate::settings::RenderSettings;
pub use part::{Part, PartNumber, Split};
use part_file::{PartHeader, PartPixels};

/// What a part run needs to know beyond the part itself (written into the part file).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PartRun {
    /// Which part.
    pub part: Part,
    /// The scene path as given on the command line.
    pub scene: String,
    /// The scene's content hash ([`scene_hash`]).
    pub scene_hash: u64,
}

/// Hash of the effective render settings: parts rendered with different overrides (`--spp`,
/// `--seed`, `--integrator`) do not merge.
pub fn settings_hash(settings: &RenderSettings) -> u64 {
    Fnv64::default()
        .bytes(format!("{settings:?}").as_bytes())
        .finish()
}

/// Content hash of the scene at `scene`, loaded as `source_hash` and `world`: its files'
/// bytes (scene, includes, RIB archives and `.mi` includes, as the loaders read them:
/// `source_hash`), the bytes of every other input file but the OBJ and PLY meshes (MTL
/// libraries, textures, displacement and environment maps, glTF files:
/// [`crate::scene::inputs::inputs_hash`]) and every loaded triangle mesh.
pub fn scene_hash(scene: &std::path::Path, source_hash: u64, world: &hecs::World) -> u64 {
    let mut h = Fnv64::default();
    h.bytes(&source_hash.to_le_bytes());
    h.bytes(&crate::scene::inputs::inputs_hash(scene).to_le_bytes());
    for mesh in world.query::<&Arc<TriMesh>>().iter() {
        for p in &mesh.positions {
            for c in p.to_array() {
                h.bytes(&c.to_bits().to_le_bytes());
            }
        }
        for t in &mesh.triangles {
            for i in t {
                h.bytes(&i.to_le_bytes());
            }
        }
    }
    h.finish()
}

/// The part file of a part run from its frame buffers (which carry the exact sums).
pub fn part_file(
    run: &PartRun,
    settings: &RenderSettings,
    fb: &FrameBuffers,
) -> Option<part_file::PartFile> {
    let sums = fb.sums.as_ref()?;
    let pixels = PartPixels {
        sums: sums.sums.clone(),
        taken: fb.samples.clone(),
        covered: sums.covered.clone(),
        dropped: sums.dropped.clone(),
        depth: fb.depth.clone(),
        normal: fb.normal.clone(),
        object_id: fb.object_id.clone(),
        material_id: fb.material_id.clone(),
        components: fb.components.clone(),
        environment: sums.environment.clone(),
    };
    Some(part_file::PartFile {
        header: PartHeader {
            version: env!("CARGO_PKG_VERSION").into(),
            scene: run.scene.clone(),
            scene_hash: run.scene_hash,
            settings_hash: settings_hash(settings),
            recorded: recorded_settings::RecordedSettings::of(settings),
            seed: settings.seed,
            part: run.part,
            width: fb.width,
            height: fb.height,
        },
        pixels,
    })
}
