//! What a bake request did: the per-object bake report, and its JSON (`--stats-json`), which
//! reports a per-vertex bake in vertices, without the texture fields.

use serde::ser::SerializeMap;
use serde::{Serialize, Serializer};

/// The report of one bake request. In JSON a per-vertex bake (`vertices` set) has
/// `vertices`, `baked_vertices`, `invalid_vertices` and `filled_vertices` in place of
/// `width`, `height`, `texels_per_unit`, `covered_texels`, `invalid_texels` and
/// `dilated_texels` (the grid its vertices are laid out on is internal).
#[derive(Debug, Clone, PartialEq)]
pub struct BakeReport {
    /// Instance name.
    pub name: String,
    /// Texture width.
    pub width: u32,
    /// Texture height.
    pub height: u32,
    /// Achieved texel density: √(covered texels / world surface area), texels per world unit.
    pub texels_per_unit: f64,
    /// Texels with at least one sample on the surface.
    pub covered_texels: u64,
    /// Covered texels whose every sample lay inside other geometry (filled by dilation).
    pub invalid_texels: u64,
    /// Texels filled by dilation.
    pub dilated_texels: u64,
    /// Rays traced.
    pub rays: u64,
    /// Wall time of the bake, seconds.
    pub seconds: f64,
    /// Rays per second.
    pub rays_per_second: f64,
    /// Files written.
    pub files: Vec<String>,
    /// For a per-vertex bake (`target: Vertices`): the mesh's vertex count (its texels are
    /// the vertices laid out on a grid; `dilated_texels` counts vertices filled from their
    /// neighbours).
    pub vertices: Option<u64>,
    /// UV seams of a texture bake with AO or a lightmap, and the difference across them.
    pub seams: Option<SeamReport>,
    /// True for a `merge` of bake parts: `rays` is the parts' total, traced in their own
    /// runs, `seconds` the merge's own time, and no ray rate is known (`rays_per_second` 0;
    /// the terminal line says `n/a`).
    pub merged_parts: bool,
}

impl Serialize for BakeReport {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(None)?;
        map.serialize_entry("name", &self.name)?;
        if let Some(vertices) = self.vertices {
            map.serialize_entry("vertices", &vertices)?;
            map.serialize_entry("baked_vertices", &self.covered_texels)?;
            map.serialize_entry("invalid_vertices", &self.invalid_texels)?;
            map.serialize_entry("filled_vertices", &self.dilated_texels)?;
        } else {
            map.serialize_entry("width", &self.width)?;
            map.serialize_entry("height", &self.height)?;
            map.serialize_entry("texels_per_unit", &self.texels_per_unit)?;
            map.serialize_entry("covered_texels", &self.covered_texels)?;
            map.serialize_entry("invalid_texels", &self.invalid_texels)?;
            map.serialize_entry("dilated_texels", &self.dilated_texels)?;
        }
        map.serialize_entry("rays", &self.rays)?;
        map.serialize_entry("seconds", &self.seconds)?;
        map.serialize_entry("rays_per_second", &self.rays_per_second)?;
        map.serialize_entry("files", &self.files)?;
        if let Some(seams) = &self.seams {
            map.serialize_entry("seams", seams)?;
        }
        if self.merged_parts {
            map.serialize_entry("merged_parts", &true)?;
        }
        map.end()
    }
}

/// The seam metric of one bake: the largest channel difference of the first AO or lightmap
/// texture read (bilinearly) at the two UV points of each seam sample pair.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SeamReport {
    /// Seam edges (mesh edges whose two sides have different UVs).
    pub edges: u64,
    /// Sample pairs along them (3 per texel of seam length).
    pub samples: u64,
    /// Mean difference before stitching (after dilation).
    pub mean_before: f64,
    /// Largest difference before stitching.
    pub max_before: f64,
    /// Mean difference of the written texture (equal to before without `stitch_seams`).
    pub mean_after: f64,
    /// Largest difference of the written texture.
    pub max_after: f64,
    /// Whether the seams were stitched.
    pub stitched: bool,
    /// Texels the stitch changed (over all stitched textures of the request).
    pub texels_changed: u64,
}

impl SeamReport {
    /// The seam part of the terminal line.
    fn summary(&self) -> String {
        if self.stitched {
            format!(
                ", {} seam edges: difference mean {:.4} max {:.4} → stitched mean {:.4} max {:.4} ({} texels changed)",
                self.edges,
                self.mean_before,
                self.max_before,
                self.mean_after,
                self.max_after,
                self.texels_changed
            )
        } else {
            format!(
                ", {} seam edges: difference mean {:.4} max {:.4} (not stitched)",
                self.edges, self.mean_before, self.max_before
            )
        }
    }
}

impl BakeReport {
    /// One line for the terminal.
    pub fn summary(&self) -> String {
        let rays = self.rays_summary();
        if let Some(vertices) = self.vertices {
            return format!(
                "{}: {vertices} vertices, {} baked, {} invalid, {} filled from neighbours, {rays}",
                self.name, self.covered_texels, self.invalid_texels, self.dilated_texels,
            );
        }
        let seams = self
            .seams
            .filter(|s| s.edges > 0)
            .map(|s| s.summary())
            .unwrap_or_default();
        format!(
            "{}: {}×{} texels, {:.1} texels/unit, {} covered, {} invalid, {} dilated, {rays}{seams}",
            self.name,
            self.width,
            self.height,
            self.texels_per_unit,
            self.covered_texels,
            self.invalid_texels,
            self.dilated_texels,
        )
    }

    /// `N rays in S s (R Mrays/s)`; for merged parts, whose time is not the rays' time,
    /// `N rays traced by the parts (Mrays/s n/a), merged in S s`.
    fn rays_summary(&self) -> String {
        if self.merged_parts {
            format!(
                "{} rays traced by the parts (Mrays/s n/a), merged in {:.3} s",
                self.rays, self.seconds
            )
        } else {
            format!(
                "{} rays in {:.3} s ({:.2} Mrays/s)",
                self.rays,
                self.seconds,
                self.rays_per_second / 1e6
            )
        }
    }
}
