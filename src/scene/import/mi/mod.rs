//! The mental ray `.mi` reader: scene text → the format-neutral [`SceneDesc`] with a source
//! position for every element and value, plus located warnings for what it does not map.
//!
//! One module per step: [`lexer`] (tokens with `line:column`), [`cursor`] (a file's tokens
//! and the shader parameter lists `("name" value, …)`), [`include`] (an `$include`d file,
//! at the top level or spliced into a block), [`statements`] (the top-level
//! statements, `incremental` ([`incremental`]: the changed element keeps its earlier values), `$include` and `link`), [`blocks`] (`options`, `camera`, `light`,
//! `material` and `declare phenomenon` blocks; [`photon_options`] maps the photon
//! statements of `options`, [`switches`] its feature switches, [`unmapped_options`] the
//! standard options read and warned), [`object`] (`object … group … end group
//! end object`; [`surface`] its free-form surfaces, [`transform`] an instance `transform`,
//! a homogeneous one divided by its `w`), [`shaders`] (the built-in shaders' parameters and what each maps onto;
//! [`textures`] the `mib_texture_*` chains onto shader-graph nodes, [`volumes`] volume
//! shaders onto fog, [`tutorial`] the tutorial's native shaders once linked)
//! and [`assemble`] (the instance tree → cameras, lights, objects, instances and groups).
//! [`value_positions`] keeps where each element's values were written ([`param_paths`]:
//! where each shader parameter lands), so that a validation error points at the value.
//!
//! **Conventions.** A mental ray `transform` is the 4×4 matrix, written row by row, that
//! takes *world* space to the instance's *object* space with row vectors
//! (`p_object = p_world · M`, translation in the last row); its inverse transpose is the
//! `world_from_object` stagelight writes. In camera-space mode (mental ray's default)
//! instance transformations have no effect: world space is camera space, the camera sits at
//! the origin looking down −z. In object-space mode the camera, lights and objects are
//! placed by their instances, composed down the instance groups from the render root.
//! Light and camera elements become one stagelight light or camera per instance, named after
//! the instance (the name materials' `"lights"` lists use). Shaders keep mental ray's
//! semantics (see `docs/mi.md`): `mib_illum_*` are local models without 1/π,
//! `mib_light_point`/`mib_light_spot` do not fall off with distance unless `atten` is on.

pub mod assemble;
pub mod blocks;
pub mod contours;
pub mod cursor;
pub mod displace;
pub mod fade;
pub mod include;
pub mod incremental;
pub mod lexer;
pub mod material_shaders;
pub mod model;
pub mod object;
pub mod param_paths;
pub mod photon_options;
pub mod shaders;
pub mod statements;
pub mod surface;
pub mod switches;
pub mod textures;
pub mod transform;
pub mod tutorial;
pub mod unmapped_options;
pub mod value_positions;
pub mod volumes;

use std::path::Path;

use super::located::{read_scene, LocatedProblem, LocatedScene};
use super::ReadScene;

/// What the reader made of one `.mi` file (its `read_files` are the `$include` files).
pub type MiScene = LocatedScene;

/// Reads the `.mi` file `path` whose contents are `bytes`. `$include "file"` files are read
/// from disk relative to the including file. On failure, every problem found (the warnings
/// too: `problem.warning`).
pub fn read_mi(path: &Path, bytes: &[u8]) -> Result<MiScene, Vec<LocatedProblem>> {
    let mut reader = statements::Reader::new(path);
    reader.read_file(path, bytes);
    assemble::assemble(reader)
}

/// The [`super::ReadFn`] of `.mi`: [`read_mi`] with its positions in a [`super::PathTable`].
pub fn read(path: &Path, bytes: &[u8]) -> Result<ReadScene, super::ReadFailure> {
    read_scene(path, read_mi(path, bytes))
}
