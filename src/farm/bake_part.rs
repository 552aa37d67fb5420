//! Bakes past one machine: which texels a `bake --part K/N` computes, what its part file
//! holds, and the exact merge of a complete set of bake parts.
//!
//! Every request's texture is cut into [`TILE`]×[`TILE`] texel tiles in row-major order; the
//! tiles of all requests are numbered one after the other (request order, as the loader
//! spawned them) and tile `t` belongs to part `t mod N + 1`, so parts share out both the
//! requests and the texels of a large request. A texel's value depends only on (seed,
//! request index, texel index), so a part computes exactly the values the single-machine
//! bake computes for its texels. Parts store texels *before* dilation; the merge assembles
//! every texture and then dilates and encodes it as `stagelight bake` does, so seams and
//! padding are the single bake's bits.

use std::path::{Path, PathBuf};

use super::part::TILE;
use super::part_file::PartHeader;
use crate::bake::TexelImage;
use glam::Vec3;

/// The texels of one request that one part computes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TexelOwner {
    /// Global number of this request's first tile.
    pub first_tile: u64,
    /// Texture width in texels.
    pub width: u32,
    /// `N`.
    pub count: u32,
    /// `K` (1-based).
    pub index: u32,
}

impl TexelOwner {
    /// Whether this part computes texel `(i, j)`.
    pub fn owns(&self, i: u32, j: u32) -> bool {
        owner_of_texel(self.first_tile, self.width, self.count, i, j) == self.index
    }
}

/// The part (1-based) that computes texel `(i, j)` of a request whose first tile is
/// `first_tile` and whose texture is `width` texels wide.
pub fn owner_of_texel(first_tile: u64, width: u32, count: u32, i: u32, j: u32) -> u32 {
    let tiles_x = (width as u64).div_ceil(TILE as u64).max(1);
    let tile = first_tile + (j as u64 / TILE as u64) * tiles_x + i as u64 / TILE as u64;
    (tile % count as u64) as u32 + 1
}

/// Number of tiles of a `width`×`height` texture.
pub fn tiles_of(width: u32, height: u32) -> u64 {
    (width as u64).div_ceil(TILE as u64) * (height as u64).div_ceil(TILE as u64)
}

/// The global number of each request's first tile, for textures of these sizes in order.
pub fn first_tiles(sizes: impl IntoIterator<Item = (u32, u32)>) -> Vec<u64> {
    let mut next = 0u64;
    sizes
        .into_iter()
        .map(|(w, h)| {
            let first = next;
            next += tiles_of(w, h);
            first
        })
        .collect()
}

/// One request's share of a bake part: its images before dilation (texels this part did
/// not compute are zero and invalid) and its counters.
#[derive(Debug, Clone, PartialEq)]
pub struct BakePartRequest {
    /// The request's (instance's) name.
    pub name: String,
    /// The images, in the order the bake produces them (targets, then bent normals).
    pub images: Vec<TexelImage>,
    /// Rays this part traced for the request.
    pub rays: u64,
    /// Covered texels this part found inside geometry.
    pub invalid: u64,
}

/// A bake part file's content. The header's `width`/`height` are 0: sizes are per image.
#[derive(Debug, Clone, PartialEq)]
pub struct BakePartFile {
    /// Metadata shared with render parts (scene, hashes, seed, K/N).
    pub header: PartHeader,
    /// Every request of the scene, in order.
    pub requests: Vec<BakePartRequest>,
}

/// The file name a bake part is written to inside the bake directory.
pub fn part_file_name(index: u32, count: u32) -> String {
    format!("bake_part_{index}_of_{count}.exr")
}

/// A bake part file that was read, with the path it came from.
pub struct LoadedBakePart {
    /// Where it was read from (for messages).
    pub path: PathBuf,
    /// Its content.
    pub file: BakePartFile,
}

/// The merged bake: every request's images before dilation, with the summed counters.
#[derive(Debug, Clone, PartialEq)]
pub struct MergedBake {
    /// Requests in order.
    pub requests: Vec<BakePartRequest>,
}

/// Merges a complete set of bake parts (see the module header); the error names the files.
/// A part with a value or a valid flag in a texel it does not own is refused as damaged.
pub fn merge(parts: &[LoadedBakePart]) -> Result<MergedBake, String> {
    let headers: Vec<(&Path, &PartHeader)> = parts
        .iter()
        .map(|p| (p.path.as_path(), &p.file.header))
        .collect();
    super::merge::check_headers(&headers, "bake")?;
    let first = &parts[0];
    for p in &parts[1..] {
        let same_shape = p.file.requests.len() == first.file.requests.len()
            && p.file
                .requests
                .iter()
                .zip(&first.file.requests)
                .all(|(a, b)| {
                    a.name == b.name
                        && a.images.len() == b.images.len()
                        && a.images
                            .iter()
                            .zip(&b.images)
                            .all(|(x, y)| (x.width, x.height) == (y.width, y.height))
                });
        if !same_shape {
            return Err(format!(
                "{} and {} hold different bake requests or texture sizes\n  help: merge only the parts of one `stagelight bake --part K/N` run",
                p.path.display(),
                first.path.display()
            ));
        }
    }
    let count = first.file.header.part.count;
    let firsts = first_tiles(first.file.requests.iter().map(|r| {
        r.images
            .first()
            .map_or((0, 0), |img| (img.width, img.height))
    }));
    // The parts in part order (`paths[k]`: where part k + 1 came from, for messages).
    let mut paths: Vec<usize> = (0..parts.len()).collect();
    paths.sort_by_key(|&p| parts[p].file.header.part.index);
    let by_index: Vec<&BakePartFile> = paths.iter().map(|&p| &parts[p].file).collect();
    let mut requests = Vec::with_capacity(first.file.requests.len());
    for (r, template) in first.file.requests.iter().enumerate() {
        let mut images: Vec<TexelImage> = template
            .images
            .iter()
            .map(|img| TexelImage::new(img.width, img.height))
            .collect();
        for (m, img) in images.iter_mut().enumerate() {
            let w = img.width;
            for j in 0..img.height {
                for i in 0..w {
                    let owner = owner_of_texel(firsts[r], w, count, i, j);
                    let idx = (j * w + i) as usize;
                    for (k, part) in by_index.iter().enumerate() {
                        let source = &part.requests[r].images[m];
                        if k + 1 == owner as usize {
                            img.texels[idx] = source.texels[idx];
                            img.valid[idx] = source.valid[idx];
                        } else if source.valid[idx] || source.texels[idx] != Vec3::ZERO {
                            let path = &parts[paths[k]].path;
                            return Err(format!(
                                "{}: damaged bake part file (texel ({i}, {j}) of `{}` holds a value, but it belongs to part {owner}/{count}, not to this part {}/{count})",
                                path.display(),
                                template.name,
                                k + 1
                            ));
                        }
                    }
                }
            }
        }
        requests.push(BakePartRequest {
            name: template.name.clone(),
            images,
            rays: by_index.iter().map(|f| f.requests[r].rays).sum(),
            invalid: by_index.iter().map(|f| f.requests[r].invalid).sum(),
        });
    }
    Ok(MergedBake { requests })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Part `index` of 2 of one 32×16 request (tile 1 is part 1's, tile 2 part 2's).
    fn bake_part(index: u32) -> LoadedBakePart {
        let mut image = TexelImage::new(32, 16);
        for j in 0..16 {
            for i in 0..32 {
                if owner_of_texel(0, 32, 2, i, j) == index {
                    image.texels[(j * 32 + i) as usize] = Vec3::ONE;
                    image.valid[(j * 32 + i) as usize] = true;
                }
            }
        }
        LoadedBakePart {
            path: format!("b{index}.exr").into(),
            file: BakePartFile {
                header: PartHeader::for_tests(index, 0, 0),
                requests: vec![BakePartRequest {
                    name: "floor".into(),
                    images: vec![image],
                    rays: 1,
                    invalid: 0,
                }],
            },
        }
    }

    #[test]
    fn a_bake_part_with_texels_outside_its_tiles_is_refused() {
        let merged = merge(&[bake_part(2), bake_part(1)]).unwrap();
        assert!(merged.requests[0].images[0].valid.iter().all(|&v| v));
        let mut a = bake_part(2);
        a.file.header.part.index = 1;
        let mut b = bake_part(1);
        b.file.header.part.index = 2;
        assert_eq!(
            merge(&[b, a]).err().unwrap(),
            "b1.exr: damaged bake part file (texel (0, 0) of `floor` holds a value, but it belongs to part 1/2, not to this part 2/2)"
        );
    }

    #[test]
    fn tiles_are_numbered_across_requests_and_dealt_round_robin() {
        // 40×20 → 3×2 tiles; 16×16 → 1 tile; 17×1 → 2 tiles.
        assert_eq!(first_tiles([(40, 20), (16, 16), (17, 1)]), vec![0, 6, 7]);
        assert_eq!(owner_of_texel(0, 40, 4, 0, 0), 1);
        assert_eq!(owner_of_texel(0, 40, 4, 16, 0), 2);
        assert_eq!(owner_of_texel(0, 40, 4, 39, 19), 2, "tile 5 → part 2");
        assert_eq!(owner_of_texel(6, 16, 4, 15, 15), 3, "tile 6 → part 3");
        assert_eq!(owner_of_texel(7, 17, 4, 16, 0), 1, "tile 8 → part 1");
    }

    #[test]
    fn every_texel_has_exactly_one_owner() {
        for count in [1, 2, 3, 7] {
            for (j, i) in [(0, 0), (5, 33), (47, 47)] {
                let owners = (1..=count)
                    .filter(|&index| {
                        TexelOwner {
                            first_tile: 3,
                            width: 48,
                            count,
                            index,
                        }
                        .owns(i, j)
                    })
                    .count();
                assert_eq!(owners, 1);
            }
        }
    }
}
