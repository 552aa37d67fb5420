//! The RenderMan RIB reader: ASCII RIB → the format-neutral [`SceneDesc`] with a source
//! position for every element and value, plus located warnings for what it does not map.
//!
//! One module per step: [`text`] (the file's bytes as characters), [`lexer`] (tokens with
//! `line:column`), [`parse`] (requests and their arguments), [`params`] (parameter lists,
//! inline declarations, `Declare`), [`state`] (the graphics state: attribute and transform
//! stacks), [`build`] (request by request onto the description), with the request families
//! in [`shaders`] (surfaces, displacements, lights; the tutorial's own in [`tutorial`]), [`geometry`] (quadrics, polygons,
//! patches, NURBS, subdivision meshes; [`revolve`]: paraboloids and hyperboloids;
//! [`primvars`]: the `N` and `st` of polygon meshes per vertex, face corner or face;
//! [`surface_vars`]: those of patches, `NuPatch` and subdivision meshes in every class),
//! [`camera`] (options, the camera and its outputs), [`retained`] (`ObjectBegin`
//! definitions and motion blocks), `place` (a primitive and the current attributes onto an
//! object, a material and an instance), [`orientation`] (`Orientation`,
//! `ReverseOrientation`: which primitives are inside out), [`procedural`] (`Procedural`:
//! `DelayedReadArchive` read as `ReadArchive`, the others warned as missing geometry), [`requests`] (which RI requests are mapped, ignored
//! or silent) and [`names`] (object names, chosen once the whole file is read).
//!
//! **Conventions.** RenderMan's camera space is left-handed (+x right, +y up, +z into the
//! screen) and the transformation current at `WorldBegin` is camera-from-world. stagelight's
//! camera looks down −z of a right-handed frame, so the reader mirrors the world through
//! z = 0 (world `(x, y, z)` is written `(x, y, −z)`) whenever the camera transformation is a
//! proper motion, which makes the camera a proper rotation again; a camera transformation
//! that already mirrors (`Scale 1 1 -1`) needs no mirror. Every primitive keeps its RIB
//! object space; its instance carries the matrix `mirror · world-from-object`. `Rotate`
//! takes degrees, light-shader angles (`coneangle`, `conedeltaangle`) radians; missing
//! parameters take the values of the RenderMan Interface Specification 3.2. A primitive's
//! object-space front is RenderMan's outside; an inside-out one (see [`orientation`]) is an
//! object with `reverse_orientation`.

mod area_lights;
pub mod atmosphere;
pub mod build;
pub mod camera;
mod caustics;
pub mod display;
pub mod geometry;
mod holes;
pub mod lexer;
pub mod names;
pub mod orientation;
pub mod params;
pub mod parse;
mod place;
pub mod primvars;
pub mod procedural;
pub mod requests;
pub mod retained;
pub mod revolve;
pub mod shaders;
pub mod state;
pub mod surface_vars;
pub mod text;
pub mod tutorial;

use std::path::Path;

use super::located::{read_scene, LocatedProblem, LocatedScene};
use super::ReadScene;

/// What the reader made of one RIB file (its `read_files` are the `ReadArchive` files).
pub type RibScene = LocatedScene;

/// Reads the RIB file `path` whose contents are `bytes`. `ReadArchive` files are read from
/// disk relative to `path`. On failure, every problem found (the warnings too: `problem.warning`).
pub fn read_rib(path: &Path, bytes: &[u8]) -> Result<RibScene, Vec<LocatedProblem>> {
    build::Builder::run(path, bytes)
}

/// The [`super::ReadFn`] of `.rib`: [`read_rib`] with its positions in a [`super::PathTable`].
pub fn read(path: &Path, bytes: &[u8]) -> Result<ReadScene, super::ReadFailure> {
    read_scene(path, read_rib(path, bytes))
}
