//! What a per-vertex bake becomes on disk: a binary little-endian PLY copy of the baked
//! mesh (object-space positions, normals and UVs when it has them, its triangles) whose
//! vertices carry the baked values twice — as 8-bit `red green blue` colours that viewers
//! show (sRGB-encoded for colour kinds, normals mapped from [−1, 1] to [0, 1], the rest
//! linear, clamped to [0, 1]) and as linear 32-bit floats `baked_r baked_g baked_b`
//! (unclamped: irradiance lightmaps keep their W/m²).

use std::path::Path;

use glam::Vec3;

use super::files::{safe_name, target_file, BakedFiles};
use super::request::PreparedBake;
use super::texels::TexelResults;
use super::vertices::{fill_missing, vertex_values};
use crate::components::{BakeKind, TriMesh};
use crate::image_io::{srgb, PendingFile};

/// Per target of a per-vertex request: its kind and one value per vertex.
pub type VertexValues = Vec<(BakeKind, Vec<Vec3>)>;

/// The files of one per-vertex request, and per target its kind and vertex values (for the
/// glTF copy's `COLOR_0`), and how many vertices were filled from their neighbours.
pub struct VertexBake {
    /// The PLY files, in target order.
    pub files: BakedFiles,
    /// Per target: its kind and one value per vertex.
    pub values: VertexValues,
    /// Vertices without a baked value, filled from their neighbours.
    pub filled: u64,
}

/// Reads the per-vertex values of `p` out of `results`, fills the missing ones and encodes
/// one PLY per target under `dir`.
pub fn encode_vertex_request(
    p: &PreparedBake,
    results: &TexelResults,
    mesh: &TriMesh,
    dir: &Path,
) -> VertexBake {
    let safe_name = safe_name(&p.request);
    let mut pending = Vec::new();
    let mut values = Vec::new();
    let mut filled = 0;
    for (target, img) in p.request.targets.iter().zip(&results.images) {
        let mut per_vertex = vertex_values(img, mesh.positions.len());
        filled = fill_missing(mesh, &mut per_vertex);
        let per_vertex: Vec<Vec3> = per_vertex
            .into_iter()
            .map(Option::unwrap_or_default)
            .collect();
        pending.push(PendingFile::new(
            dir.join(target_file(&safe_name, target)),
            encode_ply(mesh, &target.kind, &p.request.name, &per_vertex),
        ));
        values.push((target.kind.clone(), per_vertex));
    }
    VertexBake {
        files: BakedFiles { pending },
        values,
        filled,
    }
}

/// The 8-bit colour shown for a baked value of `kind`.
pub fn display_color(kind: &BakeKind, value: Vec3) -> [u8; 3] {
    let linear = |x: f32| {
        if x.is_nan() {
            0
        } else {
            (x.clamp(0.0, 1.0) * 255.0 + 0.5) as u8
        }
    };
    match kind {
        BakeKind::Lightmap { .. } | BakeKind::Albedo => value.to_array().map(srgb::to_u8),
        BakeKind::Normals { .. } => (value * 0.5 + Vec3::splat(0.5)).to_array().map(linear),
        _ => value.to_array().map(linear),
    }
}

/// The PLY file of one per-vertex bake: `mesh` with `values` (one per vertex).
pub fn encode_ply(mesh: &TriMesh, kind: &BakeKind, instance: &str, values: &[Vec3]) -> Vec<u8> {
    let mut header = String::from("ply\nformat binary_little_endian 1.0\n");
    // Comments hold no line breaks.
    let clean: String = instance
        .chars()
        .map(|c| if c.is_control() { '_' } else { c })
        .collect();
    header += &format!(
        "comment stagelight per-vertex bake: {} of {clean}\n",
        kind.suffix()
    );
    header += &format!("element vertex {}\n", mesh.positions.len());
    header += "property float x\nproperty float y\nproperty float z\n";
    if mesh.normals.is_some() {
        header += "property float nx\nproperty float ny\nproperty float nz\n";
    }
    if mesh.uvs.is_some() {
        header += "property float s\nproperty float t\n";
    }
    header += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
    header += "property float baked_r\nproperty float baked_g\nproperty float baked_b\n";
    header += &format!("element face {}\n", mesh.triangles.len());
    header += "property list uchar uint vertex_indices\nend_header\n";
    let mut out = header.into_bytes();
    let floats = |out: &mut Vec<u8>, xs: &[f32]| {
        for x in xs {
            out.extend_from_slice(&x.to_le_bytes());
        }
    };
    for (v, p) in mesh.positions.iter().enumerate() {
        floats(&mut out, &p.to_array());
        if let Some(n) = &mesh.normals {
            floats(&mut out, &n[v].to_array());
        }
        if let Some(uv) = &mesh.uvs {
            floats(&mut out, &uv[v].to_array());
        }
        let value = values.get(v).copied().unwrap_or(Vec3::ZERO);
        out.extend_from_slice(&display_color(kind, value));
        floats(&mut out, &value.to_array());
    }
    for tri in &mesh.triangles {
        out.push(3);
        for i in tri {
            out.extend_from_slice(&i.to_le_bytes());
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_ply_holds_the_mesh_and_both_colour_forms() {
        let mesh = TriMesh {
            positions: vec![Vec3::X, Vec3::Y, Vec3::Z],
            normals: None,
            uvs: None,
            triangles: vec![[0, 1, 2]],
        };
        let kind = BakeKind::AmbientOcclusion {
            samples: 1,
            max_distance: f32::INFINITY,
            bent_normals: false,
        };
        let values = [Vec3::splat(0.5), Vec3::ONE, Vec3::splat(2.0)];
        let bytes = encode_ply(&mesh, &kind, "a\nb", &values);
        let end = b"end_header\n";
        let at = bytes.windows(end.len()).position(|w| w == end).unwrap() + end.len();
        let header = std::str::from_utf8(&bytes[..at]).unwrap();
        assert!(header.contains("comment stagelight per-vertex bake: ao of a_b\n"));
        assert!(header.contains("element vertex 3\n") && header.contains("element face 1\n"));
        // Per vertex: 3 floats, 3 bytes, 3 floats = 27 bytes; the face: 1 + 12.
        assert_eq!(bytes.len() - at, 3 * 27 + 13);
        let first = &bytes[at..at + 27];
        assert_eq!(&first[12..15], &[128, 128, 128]);
        assert_eq!(f32::from_le_bytes(first[15..19].try_into().unwrap()), 0.5);
        let third = &bytes[at + 54..at + 81];
        assert_eq!(&third[12..15], &[255, 255, 255], "clamped for display");
        assert_eq!(f32::from_le_bytes(third[15..19].try_into().unwrap()), 2.0);
    }
}
