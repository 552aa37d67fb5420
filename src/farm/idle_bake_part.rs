//! A bake part (`bake --part K/N`) that owns no texel, known from the scene alone: when
//! every bake request has a fixed `resolution` and only texture targets, the requests'
//! texel tiles are counted before any geometry is made, so a part past the last tile needs
//! no geometry at all. The geometry stages skip there and `bake_lightmaps` writes the empty
//! part file from the requests' sizes. Density-sized requests (their size comes from the
//! placed surface area) and per-vertex ones (their texels are the mesh's vertices) are sized
//! by the built geometry: a part of those is found idle only after the geometry stages
//! (`bake_lightmaps`).

use hecs::{Entity, World};

use super::bake_part::{tiles_of, BakePartRequest};
use super::part::{plural, TILE};
use super::Part;
use crate::bake::texels::image_count;
use crate::bake::TexelImage;
use crate::components::{BakeKind, BakeRequest, BakeResolution};

/// One request's texture as the scene fixes it.
struct FixedRequest {
    name: String,
    width: u32,
    height: u32,
    /// Images the bake produces (`image_count`).
    images: usize,
}

/// Every bake request of `world` in entity order (the order the bake prepares them in), or
/// `None` when there is none or the size of one comes from the geometry.
fn fixed_requests(world: &World) -> Option<Vec<FixedRequest>> {
    let mut requests: Vec<(Entity, FixedRequest)> = Vec::new();
    for (entity, r) in world.query::<(Entity, &BakeRequest)>().iter() {
        let BakeResolution::Fixed { width, height } = r.resolution else {
            return None;
        };
        if r.targets.is_empty() || r.targets.iter().any(|t| t.format.is_per_vertex()) {
            return None;
        }
        let kinds: Vec<BakeKind> = r.targets.iter().map(|t| t.kind.clone()).collect();
        let fixed = FixedRequest {
            name: r.name.clone(),
            width,
            height,
            images: image_count(&kinds),
        };
        requests.push((entity, fixed));
    }
    requests.sort_by_key(|(e, _)| e.to_bits());
    (!requests.is_empty()).then(|| requests.into_iter().map(|(_, r)| r).collect())
}

/// Why `part` of a bake of `world` owns no texel, when the scene alone tells (see the
/// module header); `None` when it owns texels or only the geometry can tell.
pub fn idle_before_geometry(world: &World, part: Part) -> Option<String> {
    let requests = fixed_requests(world)?;
    let tiles = requests.iter().map(|r| tiles_of(r.width, r.height)).sum();
    (u64::from(part.index) > tiles).then(|| owns_no_texel(part, tiles, requests.len()))
}

/// `part 12/12 owns no texel: the bake request has 9 tiles of 16×16 texels`: why `part`
/// owns no texel of `requests` requests with `tiles` tiles in all.
pub fn owns_no_texel(part: Part, tiles: u64, requests: usize) -> String {
    format!(
        "part {}/{} owns no texel: the bake {} {} of {TILE}×{TILE} texels",
        part.index,
        part.count,
        if requests == 1 {
            "request has"
        } else {
            "requests have"
        },
        plural(tiles, "tile", "tiles")
    )
}

/// What the part file of a part that owns no texel holds for the requests of `world`, as
/// the bake of such a part leaves them: every image of every request with no valid texel,
/// no ray, no invalid texel. `None` when only the geometry tells the requests' sizes.
pub fn empty_requests(world: &World) -> Option<Vec<BakePartRequest>> {
    let requests = fixed_requests(world)?;
    Some(
        requests
            .into_iter()
            .map(|r| BakePartRequest {
                name: r.name,
                images: (0..r.images)
                    .map(|_| TexelImage::new(r.width, r.height))
                    .collect(),
                rays: 0,
                invalid: 0,
            })
            .collect(),
    )
}
