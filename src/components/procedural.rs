//! Geometry shaders: procedural descriptions that the `expand_geometry` stage turns into
//! parametric surfaces, meshes or instances.
//!
//! Each type is the plain data a scene-file `*Desc` maps onto one-to-one. Angles are in
//! degrees (as in RenderMan's RIB), lengths in object-space units. Out-of-range values are
//! reported by [`crate::tessellation::GeometryError`] through the `validate` helpers in
//! [`crate::procedural`]; nothing here panics.

use hecs::Entity;

/// RenderMan `Sphere radius zmin zmax thetamax`: a sphere about the origin, cut at `z_min`
/// and `z_max` and swept `theta_max` degrees about +Z. Outward normals.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sphere {
    /// Radius (> 0). Default 1.
    pub radius: f32,
    /// Lower cut, clamped to `[-radius, radius]`. Default `-radius`.
    pub z_min: f32,
    /// Upper cut, clamped to `[z_min, radius]`. Default `radius`.
    pub z_max: f32,
    /// Sweep about +Z in degrees, `(0, 360]`. Default 360.
    pub theta_max: f32,
}

/// RenderMan `Cylinder radius zmin zmax thetamax`: an open tube about +Z. Outward normals.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cylinder {
    /// Radius (> 0). Default 1.
    pub radius: f32,
    /// Bottom height. Default −1.
    pub z_min: f32,
    /// Top height (≠ `z_min`). Default 1.
    pub z_max: f32,
    /// Sweep about +Z in degrees, `(0, 360]`. Default 360.
    pub theta_max: f32,
}

/// RenderMan `Cone height radius thetamax`: base circle of `radius` in z = 0, apex at
/// (0, 0, `height`). Open at the base. Outward normals.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cone {
    /// Apex height (≠ 0). Default 1.
    pub height: f32,
    /// Base radius (> 0). Default 1.
    pub radius: f32,
    /// Sweep about +Z in degrees, `(0, 360]`. Default 360.
    pub theta_max: f32,
}

/// RenderMan `Disk height radius thetamax`: a flat disk in the plane z = `height`, facing +Z.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Disk {
    /// Height of the plane. Default 0.
    pub height: f32,
    /// Radius (> 0). Default 1.
    pub radius: f32,
    /// Sweep about +Z in degrees, `(0, 360]`. Default 360.
    pub theta_max: f32,
}

/// RenderMan `Torus rmajor rminor phimin phimax thetamax`: the circle of radius `r_minor`
/// centred `r_major` from the Z axis, swept `theta_max` degrees about +Z. `phi` is the angle
/// on the minor circle (0 = outermost point, 90 = top). Outward normals.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Torus {
    /// Distance from the Z axis to the centre of the tube (> 0). Default 1.
    pub r_major: f32,
    /// Tube radius (> 0, may exceed `r_major`: a spindle torus). Default 0.25.
    pub r_minor: f32,
    /// Start angle on the minor circle, degrees. Default 0.
    pub phi_min: f32,
    /// End angle on the minor circle, degrees, with `0 < phi_max − phi_min ≤ 360`. Default 360.
    pub phi_max: f32,
    /// Sweep about +Z in degrees, `(0, 360]`. Default 360.
    pub theta_max: f32,
}

/// The seed's stairs with real geometry: `steps` steps climbing +Y, each a riser (facing −Y)
/// and a tread (facing +Z), from (−w/2, 0, 0) to (w/2, `depth`, `height`). Closed below
/// with `closed`, so the solid is watertight.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stairs {
    /// Number of steps, clamped to `1..=100_000`. Default 10.
    pub steps: u32,
    /// Width along X (> 0). Default 2.
    pub width: f32,
    /// Total run along +Y (> 0). Default 2.
    pub depth: f32,
    /// Total rise along +Z (> 0). Default 2.
    pub height: f32,
    /// Add sides, back and bottom so the stairs form a closed solid. Default false.
    pub closed: bool,
}

/// A flat grid of `nx × ny` quads in the z = 0 plane, centred on the origin, facing +Z, with
/// uvs from (0, 0) to (1, 1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Grid {
    /// Size along X (> 0). Default 1.
    pub size_x: f32,
    /// Size along Y (> 0). Default 1.
    pub size_y: f32,
    /// Cells along X, clamped to `1..=16384`. Default 1.
    pub nx: u32,
    /// Cells along Y, clamped to `1..=16384`. Default 1.
    pub ny: u32,
}

/// A geometry shader on an object entity. `expand_geometry` replaces it: quadrics become a
/// [`crate::components::Surface`] (diced later by `tessellate`), stairs and grids become an
/// `Arc<TriMesh>` at once.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Procedural {
    /// See [`Sphere`].
    Sphere(Sphere),
    /// See [`Cylinder`].
    Cylinder(Cylinder),
    /// See [`Cone`].
    Cone(Cone),
    /// See [`Disk`].
    Disk(Disk),
    /// See [`Torus`].
    Torus(Torus),
    /// See [`Stairs`].
    Stairs(Stairs),
    /// See [`Grid`].
    Grid(Grid),
}

impl Procedural {
    /// The generator's name as reported in statistics and errors (`"torus"`, …).
    pub fn kind(&self) -> &'static str {
        match self {
            Procedural::Sphere(_) => "sphere",
            Procedural::Cylinder(_) => "cylinder",
            Procedural::Cone(_) => "cone",
            Procedural::Disk(_) => "disk",
            Procedural::Torus(_) => "torus",
            Procedural::Stairs(_) => "stairs",
            Procedural::Grid(_) => "grid",
        }
    }
}

/// A scatter/instancer on an object entity: places `count` copies of `prototype` over the
/// triangles of `surface` (area-uniform), in the scatter object's space. Each leaf instance of
/// the scatter object (an `Instance` whose `object` is this entity, with an empty mesh) is
/// replaced by `count` instances of the prototype, composed with the leaf's placement and
/// keeping its material.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scatter {
    /// Object entity whose copies are placed (any object, also a generated one).
    pub prototype: Entity,
    /// Object entity whose mesh is scattered over; it must carry an `Arc<TriMesh>` by the
    /// time `expand_geometry` runs (a loaded mesh, a grid or stairs).
    pub surface: Entity,
    /// Number of copies, clamped to `0..=10_000_000`. Default 100.
    pub count: u32,
    /// Seed of the distribution: copy `i` depends only on (`seed`, `i`).
    pub seed: u64,
    /// Uniform scale drawn from `[scale_min, scale_max]` (> 0). Default 1, 1.
    pub scale_min: f32,
    /// See `scale_min`.
    pub scale_max: f32,
    /// Random rotation about the placement normal, uniform in `±rotation_jitter` degrees.
    /// Default 180 (any orientation).
    pub rotation_jitter: f32,
    /// Align the prototype's +Z with the surface normal (otherwise it keeps its own
    /// orientation and jitter rotates about +Z). Default true.
    pub align_to_normal: bool,
}

/// Provenance of a generated entity: which scene element produced it and how, for error
/// messages and statistics. On an object whose mesh a stage generated, `source` is the object
/// itself (its `Name` / `SourceLink` locate the declaration); on scattered instances, it is
/// the scatter object.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct GeneratedFrom {
    /// The declaring entity.
    pub source: Entity,
    /// The generator: `"torus"`, `"stairs"`, `"scatter"`, `"nurbs"`, `"subdiv"`, …
    pub generator: &'static str,
}
