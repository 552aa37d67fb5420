//! Baked glTF of a scene that is not glTF (`stagelight bake scene.ron --write-gltf`): a
//! standalone glTF 2.0 binary of the baked geometry with the bakes applied, for a game
//! engine or Blender.
//!
//! Every placed instance with triangles (in entity order, as `build_accel` placed it) is one
//! node named by the instance; its mesh holds the instance's triangles as baked (after
//! tessellation, displacement and geometry shaders) in the world triangles' winding (a
//! mirrored instance's corners swapped, so the front stays the front). Where the vertices go
//! is [`super::gltf_translation`]'s rule: in **world space** — render space plus the scene
//! origin, in f64, rounded once to f32 — under a node without a transform (every instance of
//! a scene that was not rebased, and of a rebased one when f32 world coordinates keep its
//! shape), else in render space under a node whose `translation` is the scene origin, so a
//! small part far from the origin keeps its shape (node translation + vertex = the traced
//! world position). Attributes: `POSITION` (with `min`/`max`),
//! `NORMAL` (the mesh's shading normals in world space, turned to the front of the written
//! winding where they point behind it, as the renderer turns them; else the triangle's normal),
//! `TEXCOORD_0` (the mesh's own UVs; without them the bake's, the same accessor, since glTF
//! numbers the sets without gaps), `TEXCOORD_1` (the bake's UVs) and
//! `COLOR_0` (a per-vertex bake). glTF's `v` runs down the image: every UV is written as
//! `(u, 1 − v)`, the inverse of the glTF reader's mapping. Vertices are the triangles'
//! corners, welded where every attribute is bit-identical, so generated lightmap UVs keep
//! their chart seams.
//!
//! A baked instance gets a material of its own: `baseColorFactor` the scene material's base
//! colour when it is a constant (no texture nodes; else white), the ambient occlusion as
//! `occlusionTexture` and the lightmap as `MSFT_lightmap`'s `lightmapTexture`, both on
//! `TEXCOORD_1` (written by [`super::glb_build`], as in the glTF copy). Instances without a
//! bake request are written as plain geometry and share one material per scene material.
//! Lights, cameras and the scene's other elements are not written.

use std::collections::HashMap;

use glam::{DVec3, Vec2, Vec3};
use serde_json::{json, Value};

use super::glb_build::{
    add_float_accessor, add_view_for, encode_glb, list, use_lightmap_extension, wire_texture,
    TextureSlot, ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER,
};
use super::gltf_translation::{node_translation, written_position};
use crate::geometry::{InstanceGeometry, SceneGeometry};

/// What an instance's bake puts in the file.
pub enum InstanceBake<'a> {
    /// A texture bake: its per-triangle corner UVs (aligned with the mesh's triangles, v
    /// up) and its PNG textures with the slot each fills.
    Textures {
        /// `PreparedBake::uvs`.
        uvs: &'a [[Vec2; 3]],
        /// The encoded PNGs.
        textures: Vec<(TextureSlot, &'a [u8])>,
    },
    /// A per-vertex bake: one value per mesh vertex for `COLOR_0` (none: the bake has no
    /// value that colours a vertex, such as normals).
    Colors(Option<Vec<Vec3>>),
}

/// One instance of [`SceneGeometry::instances`] as the file writes it.
pub struct ExportedInstance<'a> {
    /// The node's (and mesh's) name: the instance's scene name.
    pub name: String,
    /// Its bake, if it has a request.
    pub bake: Option<InstanceBake<'a>>,
}

/// One written vertex: every attribute, compared by bits for welding.
#[derive(Clone, Copy)]
struct Vertex {
    position: [f32; 3],
    normal: [f32; 3],
    uv0: Option<[f32; 2]>,
    uv1: Option<[f32; 2]>,
    color: Option<[f32; 3]>,
}

impl Vertex {
    fn key(&self) -> Vec<u32> {
        let mut k: Vec<u32> = self
            .position
            .iter()
            .chain(&self.normal)
            .map(|x| x.to_bits())
            .collect();
        k.extend(self.uv0.iter().flatten().map(|x| x.to_bits()));
        k.extend(self.uv1.iter().flatten().map(|x| x.to_bits()));
        k.extend(self.color.iter().flatten().map(|x| x.to_bits()));
        k
    }
}

/// The attributes of one mesh primitive as they are written: each a float accessor, in a
/// view of its own, appended to `json` and `bin`.
struct Attributes<'a> {
    json: &'a mut Value,
    bin: &'a mut Vec<u8>,
    /// The written vertices.
    vertices: &'a [Vertex],
    /// The primitive's `attributes` object.
    map: Value,
}

impl Attributes<'_> {
    /// Writes attribute `name`, each vertex's `value` (every vertex has one, or none has and
    /// nothing is written), with its `min` and `max` when `bounds`; returns its accessor.
    fn add<const N: usize>(
        &mut self,
        name: &str,
        bounds: bool,
        value: impl Fn(&Vertex) -> Option<[f32; N]>,
    ) -> Option<usize> {
        let values: Vec<[f32; N]> = self.vertices.iter().filter_map(value).collect();
        if values.is_empty() {
            return None;
        }
        let kind = if N == 2 { "VEC2" } else { "VEC3" };
        let accessor = add_float_accessor(
            self.json,
            self.bin,
            &values,
            kind,
            bounds,
            Some(ARRAY_BUFFER),
        );
        self.map[name] = json!(accessor);
        Some(accessor)
    }
}

/// A glTF UV (`v` down) of a stagelight UV (`v` up).
fn gltf_uv(uv: Vec2) -> [f32; 2] {
    [uv.x, 1.0 - uv.y]
}

/// The GLB of `geometry`'s instances (`instances` aligned with `geometry.instances`),
/// `material_names` naming `geometry.materials`.
pub fn standalone_glb(
    geometry: &SceneGeometry,
    instances: &[ExportedInstance<'_>],
    material_names: &[String],
) -> Result<Vec<u8>, String> {
    if instances.len() != geometry.instances.len() {
        return Err(format!(
            "{} instances described for {} placed",
            instances.len(),
            geometry.instances.len()
        ));
    }
    let mut json = json!({
        "asset": {"version": "2.0", "generator": concat!("stagelight ", env!("CARGO_PKG_VERSION"))},
        "scene": 0,
    });
    let mut bin = Vec::new();
    let mut nodes = Vec::new();
    let mut shared_materials: HashMap<u32, usize> = HashMap::new();
    let mut lightmaps = false;
    for (inst, exported) in geometry.instances.iter().zip(instances) {
        if inst.mesh.triangles.is_empty() {
            continue;
        }
        let translation = node_translation(geometry.origin, &render_triangles(inst));
        let vertices = corner_vertices(geometry, inst, translation, exported.bake.as_ref())?;
        let (unique, indices) = weld(&vertices);
        let mut written = Attributes {
            json: &mut json,
            bin: &mut bin,
            vertices: &unique,
            map: json!({}),
        };
        written.add("POSITION", true, |v| Some(v.position));
        written.add("NORMAL", false, |v| Some(v.normal));
        written.add("TEXCOORD_0", false, |v| v.uv0);
        let bake_uvs = written.add("TEXCOORD_1", false, |v| v.uv1);
        written.add("COLOR_0", true, |v| v.color);
        let mut attributes = written.map;
        // glTF numbers texture coordinate sets from 0 without gaps: a mesh without UVs of
        // its own has the bake's as `TEXCOORD_0` too.
        if let (Some(accessor), false) = (bake_uvs, attributes.get("TEXCOORD_0").is_some()) {
            attributes["TEXCOORD_0"] = json!(accessor);
        }
        let index_bytes: Vec<u8> = indices.iter().flat_map(|i| i.to_le_bytes()).collect();
        let view = add_view_for(
            &mut json,
            &mut bin,
            &index_bytes,
            Some(ELEMENT_ARRAY_BUFFER),
        );
        let accessors = list(&mut json, "accessors");
        accessors.push(json!({
            "bufferView": view,
            "componentType": 5125,
            "count": indices.len(),
            "type": "SCALAR",
        }));
        let index_accessor = accessors.len() - 1;
        let scene_material = &geometry.materials[inst.material as usize];
        let slot_name = material_names
            .get(inst.material as usize)
            .cloned()
            .unwrap_or_else(|| format!("material{}", inst.material));
        let material = match &exported.bake {
            Some(bake) => {
                let m = push_material(
                    &mut json,
                    format!("{}_baked", exported.name),
                    scene_material,
                );
                if let InstanceBake::Textures { textures, .. } = bake {
                    for (slot, png) in textures {
                        lightmaps |= wire_texture(&mut json, &mut bin, m, *slot, png);
                    }
                }
                m
            }
            None => *shared_materials
                .entry(inst.material)
                .or_insert_with(|| push_material(&mut json, slot_name, scene_material)),
        };
        let meshes = list(&mut json, "meshes");
        meshes.push(json!({
            "name": exported.name,
            "primitives": [{"attributes": attributes, "indices": index_accessor, "material": material}],
        }));
        let mesh = meshes.len() - 1;
        let node_list = list(&mut json, "nodes");
        let mut node = json!({"name": exported.name, "mesh": mesh});
        if translation != DVec3::ZERO {
            // An f32 value (the scene origin, which f32 holds exactly), in its f64 digits.
            node["translation"] = json!(translation.to_array());
        }
        node_list.push(node);
        nodes.push(node_list.len() - 1);
    }
    json["scenes"] = json!([{"nodes": nodes}]);
    if nodes.is_empty() {
        return Err("no instance has triangles to write".into());
    }
    if lightmaps {
        use_lightmap_extension(&mut json);
    }
    encode_glb(json, bin)
}

/// Adds a metallic-roughness material named `name` whose base colour is `material`'s when
/// it is a constant (no texture nodes), else white; returns its index.
fn push_material(json: &mut Value, name: String, material: &crate::components::Material) -> usize {
    let color = match material.graph {
        None => crate::bake::irradiance::base_color(&material.shader),
        Some(_) => Vec3::ONE,
    };
    let color = if color.is_finite() {
        color.clamp(Vec3::ZERO, Vec3::ONE)
    } else {
        Vec3::ONE
    };
    let mut m = json!({
        "name": name,
        "pbrMetallicRoughness": {
            "baseColorFactor": [color.x, color.y, color.z, 1.0],
            "metallicFactor": 0.0,
        },
    });
    if material.two_sided {
        m["doubleSided"] = json!(true);
    }
    let materials = list(json, "materials");
    materials.push(m);
    materials.len() - 1
}

/// The render-space corners of `inst`'s triangles in world order: the triangles the bake
/// traced.
fn render_triangles(inst: &InstanceGeometry) -> Vec<[Vec3; 3]> {
    (0..inst.mesh.triangles.len())
        .map(|local| {
            inst.corners(local).map(|i| {
                inst.world_from_object
                    .transform_point3(inst.mesh.positions[i])
            })
        })
        .collect()
}

/// The corners of `inst`'s triangles in world order, three per triangle, with every
/// attribute the file writes; positions relative to the node's `translation`
/// ([`written_position`]).
fn corner_vertices(
    geometry: &SceneGeometry,
    inst: &InstanceGeometry,
    translation: DVec3,
    bake: Option<&InstanceBake<'_>>,
) -> Result<Vec<Vertex>, String> {
    let mesh = &inst.mesh;
    let (bake_uvs, colors) = match bake {
        Some(InstanceBake::Textures { uvs, .. }) => (Some(*uvs), None),
        Some(InstanceBake::Colors(c)) => (None, c.as_deref()),
        None => (None, None),
    };
    if bake_uvs.is_some_and(|u| u.len() != mesh.triangles.len()) {
        return Err("the bake's UVs do not match the instance's triangles".into());
    }
    if colors.is_some_and(|c| c.len() != mesh.positions.len()) {
        return Err("the per-vertex bake does not match the instance's vertices".into());
    }
    let position = |p: Vec3| -> [f32; 3] {
        let render = inst.world_from_object.transform_point3(p);
        written_position(render, geometry.origin, translation).to_array()
    };
    let mut out = Vec::with_capacity(mesh.triangles.len() * 3);
    for local in 0..mesh.triangles.len() {
        let corners = inst.corners(local);
        // The triangle's normal in f64, so coplanar triangles get the same bits (and weld).
        let p = corners.map(|i| {
            inst.world_from_object
                .transform_point3(mesh.positions[i])
                .as_dvec3()
        });
        let face = (p[1] - p[0])
            .cross(p[2] - p[0])
            .try_normalize()
            .map_or(Vec3::Z, |n| n.as_vec3());
        let bake_corner = bake_uvs.map(|u| inst.world_order(u[local]));
        for (k, &i) in corners.iter().enumerate() {
            // A shading normal on the other side of the front (an object whose orientation is
            // reversed keeps its normals as written) is turned over, as the renderer turns
            // it at every hit (`SceneGeometry::shading_point_on`): glTF's front is the
            // counter-clockwise winding, and its `NORMAL` must point out of it.
            let normal = mesh
                .normals
                .as_ref()
                .and_then(|ns| {
                    Vec3::from(inst.normal_from_object * glam::Vec3A::from(ns[i])).try_normalize()
                })
                .map_or(face, |n| if n.dot(face) < 0.0 { -n } else { n });
            out.push(Vertex {
                position: position(mesh.positions[i]),
                normal: normal.to_array(),
                uv0: mesh.uvs.as_ref().map(|uvs| gltf_uv(uvs[i])),
                uv1: bake_corner.map(|c| gltf_uv(c[k])),
                color: colors.map(|c| c[i].to_array()),
            });
        }
    }
    Ok(out)
}

/// The distinct vertices of `corners` (bit-identical ones welded, in first-use order) and
/// the index of each corner among them.
fn weld(corners: &[Vertex]) -> (Vec<Vertex>, Vec<u32>) {
    let mut seen: HashMap<Vec<u32>, u32> = HashMap::new();
    let mut unique = Vec::new();
    let mut indices = Vec::with_capacity(corners.len());
    for v in corners {
        let index = *seen.entry(v.key()).or_insert_with(|| {
            unique.push(*v);
            (unique.len() - 1) as u32
        });
        indices.push(index);
    }
    (unique, indices)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn vertex(x: f32, u: f32) -> Vertex {
        Vertex {
            position: [x, 0.0, 0.0],
            normal: [0.0, 0.0, 1.0],
            uv0: None,
            uv1: Some([u, 0.0]),
            color: None,
        }
    }

    #[test]
    fn corners_weld_only_when_every_attribute_is_the_same() {
        // Two corners at one position but on two charts stay two vertices.
        let corners = [
            vertex(0.0, 0.0),
            vertex(1.0, 0.0),
            vertex(0.0, 0.0),
            vertex(0.0, 0.5),
        ];
        let (unique, indices) = weld(&corners);
        assert_eq!(unique.len(), 3);
        assert_eq!(indices, vec![0, 1, 0, 2]);
    }

    #[test]
    fn uvs_are_written_with_v_down() {
        assert_eq!(gltf_uv(Vec2::new(0.25, 0.75)), [0.25, 0.25]);
    }
}
