//! Where a bake's UVs come from (the mesh's own set or generated lightmap UVs) and how large
//! the texture is.

use glam::Vec2;

use crate::components::{BakeResolution, TriMesh, UvSource};

/// Why a request has no usable UVs.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BakeUvError {
    /// The mesh has no UVs and unwrapping is off.
    #[error("the mesh has no texture coordinates and `uvs: Mesh` forbids generating them")]
    NoUvs,
    /// `uvs: MeshSet(1)`, but the mesh as placed has no second UV set (one per vertex).
    #[error("the mesh has no second UV set (TEXCOORD_1) matching its vertices (displacement or dicing replaces the vertices and drops it)")]
    NoSecondSet,
    /// The unwrapper failed.
    #[error("generating lightmap UVs failed: {0}")]
    Unwrap(String),
    /// The resolution is zero or too large.
    #[error("bake resolution {0}×{1} is out of range (1 … 16384 texels per side)")]
    Resolution(u32, u32),
}

/// Per-triangle corner UVs (v up), aligned with `mesh.triangles`. Generated UVs are packed
/// for a `page × page` texture with `padding` texels between charts.
pub fn corner_uvs(
    mesh: &TriMesh,
    source: UvSource,
    page: u32,
    padding: u32,
) -> Result<Vec<[Vec2; 3]>, BakeUvError> {
    let from_mesh = |uvs: &Vec<Vec2>| {
        mesh.triangles
            .iter()
            .map(|t| t.map(|i| uvs[i as usize]))
            .collect::<Vec<_>>()
    };
    match (source, &mesh.uvs) {
        (UvSource::Mesh, Some(uvs)) | (UvSource::MeshOrUnwrap, Some(uvs)) => Ok(from_mesh(uvs)),
        (UvSource::Mesh, None) => Err(BakeUvError::NoUvs),
        (UvSource::SecondSet, _) => Err(BakeUvError::NoSecondSet),
        _ => unwrap(mesh, page, padding),
    }
}

/// Per-triangle corner UVs from a second UV set (`uvs: MeshSet(1)`), which must have one
/// entry per vertex of `mesh`.
pub fn second_set_corner_uvs(
    mesh: &TriMesh,
    second: &[Vec2],
) -> Result<Vec<[Vec2; 3]>, BakeUvError> {
    if second.len() != mesh.positions.len() {
        return Err(BakeUvError::NoSecondSet);
    }
    Ok(mesh
        .triangles
        .iter()
        .map(|t| t.map(|i| second[i as usize]))
        .collect())
}

fn unwrap(mesh: &TriMesh, page: u32, padding: u32) -> Result<Vec<[Vec2; 3]>, BakeUvError> {
    let positions: Vec<[f32; 3]> = mesh.positions.iter().map(|p| p.to_array()).collect();
    let indices: Vec<u32> = mesh.triangles.iter().flatten().copied().collect();
    let input = uvunwrap::MeshInput::new(&positions, &indices);
    let options = uvunwrap::Options {
        density: uvunwrap::Density::Auto {
            page_size: page.max(2 * padding + 8),
        },
        padding,
        ..uvunwrap::Options::default()
    };
    let atlas =
        uvunwrap::generate(&[input], &options).map_err(|e| BakeUvError::Unwrap(e.to_string()))?;
    let out = &atlas.meshes[0];
    // uvunwrap's v grows with the image row over a page of `width × height`; rescale to the
    // full square page and flip to v up.
    let sx = atlas.width as f32 / page as f32;
    let sy = atlas.height as f32 / page as f32;
    Ok(out
        .indices
        .chunks_exact(3)
        .map(|t| {
            [0, 1, 2].map(|k| {
                let uv = out.vertices[t[k] as usize].uv;
                Vec2::new(uv[0] * sx, 1.0 - uv[1] * sy)
            })
        })
        .collect())
}

/// Relative tolerance of the texel side a density asks for before it is rounded up to a
/// power of two: a side up to 10⁻⁶ (about 8 f32 ulps) above a power of two takes that power.
pub const SIDE_TOLERANCE: f64 = 1e-6;

/// Texture size of a request: explicit, or from texel density with power-of-two rounding
/// (a side within [`SIDE_TOLERANCE`] above a power of two rounds down to it).
/// `world_area` is the instance's surface area in world units², `uv_area` the area its UVs
/// cover in the unit square.
pub fn bake_resolution(
    resolution: BakeResolution,
    world_area: f64,
    uv_area: f64,
) -> Result<(u32, u32), BakeUvError> {
    let (w, h) = match resolution {
        BakeResolution::Fixed { width, height } => (width, height),
        BakeResolution::Density {
            texels_per_unit,
            max_size,
        } => {
            let side = if uv_area > 0.0 && world_area > 0.0 {
                (world_area / uv_area).sqrt() * texels_per_unit as f64
            } else {
                1.0
            };
            // A side a few f32 ulps above a power of two is that power: the mesh's
            // coordinates are f32, so an exact 8 comes out as 8.0000001.
            let side = side * (1.0 - SIDE_TOLERANCE);
            let pow2 = (side.clamp(1.0, 1e9).ceil() as u64)
                .next_power_of_two()
                .min(u32::MAX as u64) as u32;
            let size = pow2.min(max_size.max(1));
            (size, size)
        }
    };
    if w == 0 || h == 0 || w > 16384 || h > 16384 {
        return Err(BakeUvError::Resolution(w, h));
    }
    Ok((w, h))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn density_rounds_up_to_a_power_of_two() {
        // 4 m² on the full unit square at 100 texels/m: 200 texels → 256.
        let r = BakeResolution::Density {
            texels_per_unit: 100.0,
            max_size: 4096,
        };
        assert_eq!(bake_resolution(r, 4.0, 1.0).unwrap(), (256, 256));
        let capped = BakeResolution::Density {
            texels_per_unit: 1e6,
            max_size: 512,
        };
        assert_eq!(bake_resolution(capped, 4.0, 1.0).unwrap(), (512, 512));
    }

    #[test]
    fn a_side_a_few_ulps_above_a_power_of_two_takes_that_power() {
        let r = BakeResolution::Density {
            texels_per_unit: 40.0,
            max_size: 4096,
        };
        // A 0.2 quad of f32 corners (±0.1): area 0.0400000012, side 8.0000001.
        let area = (2.0 * 0.1f32 as f64).powi(2);
        assert_eq!(bake_resolution(r, area, 1.0).unwrap(), (8, 8));
        assert_eq!(
            bake_resolution(r, 0.04 * (1.0 + 1e-7), 1.0).unwrap(),
            (8, 8)
        );
        // Clearly above: the next power.
        assert_eq!(bake_resolution(r, 0.04 * 1.0001, 1.0).unwrap(), (16, 16));
        // Exact powers at other sizes: 1 m² at 64, 256 and 1024 texels/m.
        for n in [64u32, 256, 1024] {
            let r = BakeResolution::Density {
                texels_per_unit: n as f32,
                max_size: 4096,
            };
            assert_eq!(bake_resolution(r, 1.0, 1.0).unwrap(), (n, n));
            assert_eq!(bake_resolution(r, 1.01, 1.0).unwrap(), (2 * n, 2 * n));
        }
    }

    #[test]
    fn zero_resolution_is_refused() {
        let r = BakeResolution::Fixed {
            width: 0,
            height: 16,
        };
        assert!(bake_resolution(r, 1.0, 1.0).is_err());
    }
}
