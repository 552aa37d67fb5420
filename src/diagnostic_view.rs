//! The grid and photon diagnostic views (mental ray `diagnostic grid …`, `diagnostic photon
//! …`): the beauty replaced by what the camera's pixel-centre rays meet, drawn without any
//! random number, so a view is the same at any thread count and sample setting.
//!
//! **Grid:** a pixel is on a line of axis `a` when the grid cell `⌊c_a / size⌋` of its hit
//! (`c` in object, world or camera coordinates) differs from that of its right or lower
//! neighbour on the same instance: lines one pixel wide wherever a plane `c_a = k·size`
//! passes between two pixel centres, red for x, green for y, blue for z (mixed where lines
//! cross), on grey surfaces; nothing hit is black.
//!
//! **Photon:** every material replaced by the photon maps' estimate at the hit (both maps
//! summed; `Density`: photons per unit area, the estimate with each photon counted once;
//! `Irradiance`: W/m², the channel mean), shown as `t = value / max` on the scale
//! [`false_colour`]: black where no photon is in reach, blue for little, red at `max` and above.
//!
//! **BVH:** what the pixel-centre ray cost the hierarchy ([`Accel::intersect_with_cost`], the
//! closest-hit traversal; hidden surfaces count as the tree holds them): `Depth`, the deepest
//! level entered over the tree's depth; `Size`, the triangles tested over the image's largest
//! count (or over `max` when given), on the same scale: black where the ray entered nothing.

use glam::{Affine3A, DVec3, Vec2, Vec3};
use rayon::prelude::*;

use crate::accel::{Accel, RayKind, TraversalCost};
use crate::diagnostic::{BvhQuantity, Diagnostic, GridSpace, PhotonQuantity};
use crate::geometry::SceneGeometry;
use crate::photon::{Neighbour, PhotonMaps};
use crate::shading::CameraRays;

/// Colours of lines of constant x, y and z.
pub const GRID_COLOURS: [Vec3; 3] = [Vec3::X, Vec3::Y, Vec3::Z];

/// Surfaces between grid lines.
pub const GRID_SURFACE: Vec3 = Vec3::splat(0.25);

/// What a pixel-centre ray met: the instance slot, the point (render space) and the
/// geometric normal facing the ray.
#[derive(Debug, Clone, Copy)]
struct CentreHit {
    instance: u32,
    p: Vec3,
    normal: Vec3,
}

/// The view `d` draws of `width × height` pixels through `rays`, or `None` for a diagnostic
/// that is not drawn from hits (`Samples`). `world_from_camera` places the camera (grid in
/// camera space); `photons` are the maps the photon view reads (none: black).
pub fn view(
    d: Diagnostic,
    geometry: &SceneGeometry,
    rays: &CameraRays,
    world_from_camera: Affine3A,
    photons: Option<&PhotonMaps>,
    (width, height): (usize, usize),
) -> Option<Vec<Vec3>> {
    let hits = || centre_hits(geometry, rays, width, height);
    match d {
        Diagnostic::Samples => None,
        Diagnostic::Bvh { quantity, max } => {
            Some(bvh(&geometry.accel, rays, quantity, max, (width, height)))
        }
        Diagnostic::Grid { space, size } => {
            let hits = hits();
            let camera_from_world = world_from_camera.inverse();
            let coords: Vec<Option<DVec3>> = hits
                .iter()
                .map(|h| {
                    h.map(|h| match space {
                        GridSpace::World => h.p.as_dvec3() + geometry.origin,
                        GridSpace::Object => {
                            let inst = &geometry.instances[h.instance as usize];
                            inst.world_from_object
                                .inverse()
                                .transform_point3(h.p)
                                .as_dvec3()
                        }
                        GridSpace::Camera => camera_from_world.transform_point3(h.p).as_dvec3(),
                    })
                })
                .collect();
            Some(grid(&hits, &coords, f64::from(size), width, height))
        }
        Diagnostic::Photon { quantity, max } => Some(
            hits()
                .par_iter()
                .map_init(Vec::new, |scratch, h| {
                    let value = match (h, photons) {
                        (Some(h), Some(maps)) => photon_value(maps, quantity, h, scratch),
                        _ => 0.0,
                    };
                    false_colour(value / max)
                })
                .collect(),
        ),
    }
}

/// The colour scale of the photon view: black at `t ≤ 0`, then `(t, 0, 1 − t)` from blue to
/// red, red from `t = 1` on (so the red channel is `t` clamped).
pub fn false_colour(t: f32) -> Vec3 {
    if t.is_nan() || t <= 0.0 {
        return Vec3::ZERO;
    }
    let t = t.min(1.0);
    Vec3::new(t, 0.0, 1.0 - t)
}

/// The BVH view (see the module header).
fn bvh(
    accel: &Accel,
    rays: &CameraRays,
    quantity: BvhQuantity,
    max: Option<u32>,
    (width, height): (usize, usize),
) -> Vec<Vec3> {
    let costs: Vec<Option<TraversalCost>> = (0..width * height)
        .into_par_iter()
        .map(|i| {
            let (x, y) = ((i % width) as f32 + 0.5, (i / width) as f32 + 0.5);
            let ray = rays.ray(x, y, Vec2::splat(0.5))?;
            Some(accel.intersect_with_cost(&ray).1)
        })
        .collect();
    let value = |c: &TraversalCost| match quantity {
        BvhQuantity::Depth => c.deepest,
        BvhQuantity::Size => c.triangles,
    };
    let top = max
        .unwrap_or_else(|| match quantity {
            BvhQuantity::Depth => accel.stats().depth,
            BvhQuantity::Size => costs.iter().flatten().map(value).max().unwrap_or(0),
        })
        .max(1);
    costs
        .iter()
        .map(|c| c.map_or(Vec3::ZERO, |c| false_colour(value(&c) as f32 / top as f32)))
        .collect()
}

fn centre_hits(
    geometry: &SceneGeometry,
    rays: &CameraRays,
    width: usize,
    height: usize,
) -> Vec<Option<CentreHit>> {
    (0..width * height)
        .into_par_iter()
        .map(|i| {
            let (x, y) = ((i % width) as f32 + 0.5, (i / width) as f32 + 0.5);
            let ray = rays.ray(x, y, Vec2::splat(0.5))?;
            let hit = geometry.accel.intersect_as(&ray, RayKind::Camera)?;
            let sp = geometry.shading_point(&hit);
            let ng = sp.surface.ng;
            Some(CentreHit {
                instance: sp.instance,
                p: sp.surface.p,
                normal: if ng.dot(ray.dir) > 0.0 { -ng } else { ng },
            })
        })
        .collect()
}

fn grid(
    hits: &[Option<CentreHit>],
    coords: &[Option<DVec3>],
    size: f64,
    width: usize,
    height: usize,
) -> Vec<Vec3> {
    let cell = |i: usize| coords[i].map(|c| (c / size).floor());
    (0..width * height)
        .map(|i| {
            let (Some(h), Some(here)) = (hits[i], cell(i)) else {
                return Vec3::ZERO;
            };
            let (x, y) = (i % width, i / width);
            let neighbours = [
                (x + 1 < width).then_some(i + 1),
                (y + 1 < height).then_some(i + width),
            ];
            let mut colour = Vec3::ZERO;
            for j in neighbours.into_iter().flatten() {
                let same = hits[j].is_some_and(|n| n.instance == h.instance);
                let Some(there) = cell(j).filter(|_| same) else {
                    continue;
                };
                for (axis, line) in GRID_COLOURS.iter().enumerate() {
                    if here[axis] != there[axis] {
                        colour = colour.max(*line);
                    }
                }
            }
            if colour == Vec3::ZERO {
                GRID_SURFACE
            } else {
                colour
            }
        })
        .collect()
}

fn photon_value(
    maps: &PhotonMaps,
    quantity: PhotonQuantity,
    h: &CentreHit,
    scratch: &mut Vec<Neighbour>,
) -> f32 {
    [&maps.caustics, &maps.global]
        .into_iter()
        .flatten()
        .map(|m| {
            let v = match quantity {
                PhotonQuantity::Irradiance => m.density(h.p, h.normal, scratch, |_| Vec3::ONE),
                PhotonQuantity::Density => m.density(h.p, h.normal, scratch, |ph| {
                    let inv = |x: f32| if x > 0.0 { 1.0 / x } else { 0.0 };
                    Vec3::new(inv(ph.power.x), inv(ph.power.y), inv(ph.power.z))
                }),
            };
            (v.x + v.y + v.z) / 3.0
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_false_colour_scale_is_black_then_blue_to_red() {
        assert_eq!(false_colour(0.0), Vec3::ZERO);
        assert_eq!(false_colour(f32::NAN), Vec3::ZERO);
        assert_eq!(false_colour(0.25), Vec3::new(0.25, 0.0, 0.75));
        assert_eq!(false_colour(3.0), Vec3::X);
    }
}
