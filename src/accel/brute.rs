//! The brute-force reference: every triangle, in index order, through the same watertight
//! test as the BVH. Ties at equal `t` go to the smallest index, as in the BVH.

use glam::Vec3;

use super::triangle::{is_degenerate, ray_is_valid, WoopRay};
use super::{Hit, Ray};

/// Closest hit by testing every triangle (the reference for tests). Same semantics as
/// [`super::Accel::intersect`]: `0 < t < ray.t_max`, degenerate triangles never hit, ties go
/// to the smallest index.
pub fn brute_force_intersect(triangles: &[[Vec3; 3]], ray: &Ray) -> Option<Hit> {
    if !ray_is_valid(ray) {
        return None;
    }
    let woop = WoopRay::new(ray.origin, ray.dir);
    let mut best: Option<Hit> = None;
    let mut best_t = ray.t_max;
    for (i, tri) in triangles.iter().enumerate() {
        if is_degenerate(tri) {
            continue;
        }
        if let Some((t, b1, b2)) = woop.intersect(tri) {
            if t < best_t {
                best_t = t;
                best = Some(Hit {
                    t,
                    prim: i as u32,
                    b1,
                    b2,
                });
            }
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn first_index_wins_ties() {
        let tri = [Vec3::ZERO, Vec3::X, Vec3::Y];
        let ray = Ray {
            origin: Vec3::new(0.2, 0.2, 1.0),
            dir: -Vec3::Z,
            t_max: 2.0,
        };
        let hit = brute_force_intersect(&[[Vec3::ZERO; 3], tri, tri], &ray).unwrap();
        assert_eq!((hit.prim, hit.t), (1, 1.0));
    }
}
