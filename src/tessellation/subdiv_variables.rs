//! User texture coordinates and normals (RenderMan's `s`, `t`, `N`) on a Catmull-Clark
//! limit cage: `Control` values are refined by the position rules and pushed to their limit
//! (RenderMan's `vertex`), `Corners` values (one per face corner) are refined linearly over
//! each face (`varying`, `facevarying`, `uniform`, `constant`). The results replace the
//! cage's per-quad-corner uvs and normals; a variable not given keeps the cage's own.

use glam::DVec3;

use super::polymesh::QuadCage;
use super::GeometryError;
use crate::components::{SurfaceValues, SurfaceVariables};

/// Sets the uvs and normals of `cage` (refined `levels` ≥ 1 times from `faces` over
/// `controls` vertices) from `vars`; `smooth` refines per-vertex values to their limit.
pub fn apply(
    cage: &mut QuadCage,
    vars: &SurfaceVariables,
    (faces, controls): (&[Vec<u32>], usize),
    levels: u32,
    smooth: impl Fn(&[DVec3]) -> Result<Vec<DVec3>, GeometryError>,
) -> Result<(), GeometryError> {
    let corners: usize = faces.iter().map(Vec::len).sum();
    super::variables::check(vars, controls, corners, "subdivision mesh")?;
    let per_quad = |v: &SurfaceValues| -> Result<Vec<[DVec3; 4]>, GeometryError> {
        let values: Vec<DVec3> = v.values().iter().map(|x| x.as_dvec3()).collect();
        Ok(match v {
            SurfaceValues::Control(_) => {
                let limit = smooth(&values)?;
                cage.quads
                    .iter()
                    .map(|q| q.map(|i| limit[i as usize]))
                    .collect()
            }
            SurfaceValues::Corners(_) => linear(faces, &values, levels),
        })
    };
    let s = vars.s.as_ref().map(per_quad).transpose()?;
    let t = vars.t.as_ref().map(per_quad).transpose()?;
    let n = vars.normals.as_ref().map(per_quad).transpose()?;
    for q in 0..cage.quads.len() {
        for k in 0..4 {
            if let Some(s) = &s {
                cage.uvs[q][k].x = s[q][k].x;
            }
            if let Some(t) = &t {
                cage.uvs[q][k].y = t[q][k].x;
            }
            if let Some(n) = n.as_ref().and_then(|n| n[q][k].try_normalize()) {
                cage.normals[q][k] = n;
            }
        }
    }
    Ok(())
}

/// Face-corner values refined linearly `levels` times, in the order Catmull-Clark refinement
/// makes its quads: face by face, one quad per corner `(corner, next edge's midpoint, centre,
/// previous edge's midpoint)`.
fn linear(faces: &[Vec<u32>], values: &[DVec3], levels: u32) -> Vec<[DVec3; 4]> {
    let mut polys: Vec<Vec<DVec3>> = Vec::with_capacity(faces.len());
    let mut at = 0;
    for f in faces {
        polys.push(values[at..at + f.len()].to_vec());
        at += f.len();
    }
    for _ in 0..levels {
        let mut next = Vec::with_capacity(polys.iter().map(Vec::len).sum());
        for c in &polys {
            let m = c.len();
            let centre = c.iter().sum::<DVec3>() / m as f64;
            for k in 0..m {
                let (prev, here, after) = (c[(k + m - 1) % m], c[k], c[(k + 1) % m]);
                next.push(vec![
                    here,
                    (here + after) * 0.5,
                    centre,
                    (prev + here) * 0.5,
                ]);
            }
        }
        polys = next;
    }
    polys
        .into_iter()
        .map(|c| [c[0], c[1], c[2], c[3]])
        .collect()
}
