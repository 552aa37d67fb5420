//! Analytic test meshes: a UV sphere with outward faces (the closed box is `box_mesh` in `mod.rs`).

use glam::DVec3;
use stagelight::components::TriMesh;

/// A UV sphere (poles on ±Z) of radius `r`, `nu × nv` segments, outward, no UVs.
pub fn sphere(r: f32, nu: u32, nv: u32) -> TriMesh {
    let mut positions = Vec::new();
    for j in 0..=nv {
        let theta = std::f64::consts::PI * j as f64 / nv as f64;
        for i in 0..nu {
            let phi = 2.0 * std::f64::consts::PI * i as f64 / nu as f64;
            let p = DVec3::new(
                theta.sin() * phi.cos(),
                theta.sin() * phi.sin(),
                theta.cos(),
            );
            positions.push((p * r as f64).as_vec3());
        }
    }
    let mut triangles = Vec::new();
    for j in 0..nv {
        for i in 0..nu {
            let (a, b) = (j * nu + i, j * nu + (i + 1) % nu);
            let (c, d) = ((j + 1) * nu + (i + 1) % nu, (j + 1) * nu + i);
            if j != 0 {
                triangles.push([a, d, b]);
            }
            if j != nv - 1 {
                triangles.push([b, d, c]);
            }
        }
    }
    TriMesh {
        positions,
        normals: None,
        uvs: None,
        triangles,
    }
}
