//! What a bake request did: the per-object bake report.

use serde::Serialize;

/// The report of one bake request.
#[derive(Debug, Clone, PartialEq, Serialize)]
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
    #[serde(skip_serializing_if = "Option::is_none")]
    pub vertices: Option<u64>,
}

impl BakeReport {
    /// One line for the terminal.
    pub fn summary(&self) -> String {
        if let Some(vertices) = self.vertices {
            return format!(
                "{}: {vertices} vertices, {} baked, {} invalid, {} filled from neighbours, {} rays in {:.3} s ({:.2} Mrays/s)",
                self.name,
                self.covered_texels,
                self.invalid_texels,
                self.dilated_texels,
                self.rays,
                self.seconds,
                self.rays_per_second / 1e6
            );
        }
        format!(
            "{}: {}×{} texels, {:.1} texels/unit, {} covered, {} invalid, {} dilated, {} rays in {:.3} s ({:.2} Mrays/s)",
            self.name,
            self.width,
            self.height,
            self.texels_per_unit,
            self.covered_texels,
            self.invalid_texels,
            self.dilated_texels,
            self.rays,
            self.seconds,
            self.rays_per_second / 1e6
        )
    }
}
