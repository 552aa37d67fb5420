//! Component data carried by scene entities: plain data, one file per concept.
//!
//! The scene loader spawns these; stages read them. No behaviour lives here beyond small,
//! pure helpers on the data itself.

mod camera;
mod contour;
mod label;
mod light;
mod local_model;
mod material;
mod mesh;
mod naming;
mod transform;

pub use camera::{
    world_from_look_at, Camera, ImageFormat, Lens, Lenses, OutputLinks, OutputSpec, Pass,
    RenderCamera, ResolutionLink,
};
pub use contour::{ContourContrast, ContourShader};
pub use label::ObjectLabel;
pub use light::{attenuation_factor, Emitter, LightShape};
pub use local_model::{LocalLobe, LocalModel};
pub use material::{Material, MaterialRef, Shader};
pub use mesh::{
    FaceMaterials, Instance, ReverseOrientation, SecondUvs, TriMesh, VertexColours, VertexTangents,
};
pub use naming::{Name, SourceLink};
pub use transform::{SceneOrigin, WorldFromObject};

mod bake;
mod environment;
pub mod graph;
mod imager;
pub use bake::{
    BakeFormat, BakeKind, BakeRequest, BakeResolution, BakeTarget, Denoise, LightmapStore,
    NormalSpace, UvSource,
};
pub use environment::{
    DepthExceeded, Environment, EnvironmentSource, LatLongMap, MaterialEnvironment,
};
pub use imager::{Imager, ImagerPattern, ToneMap};

mod volume;
pub use volume::{Atmosphere, AtmosphereFade, DensityNoise, Fade, Falloff, Fog, Interior};

mod approximation;
mod displacement;
mod procedural;
mod surface;

pub use approximation::{Approximation, ApproximationLink, LengthSpace, Technique};
pub use displacement::{
    DerivativeRequest, Displacement, DisplacementMode, ImageMap, ScalarNode, SurfaceDerivatives,
    UvAxis,
};
pub use procedural::{
    Cone, Cylinder, Disk, GeneratedFrom, Grid, Procedural, Scatter, Sphere, Stairs, Torus,
};
pub use surface::{
    CubicBasis, NurbsSurface, PatchKind, PatchMesh, Quadric, SubdivMesh, Surface, SurfaceValues,
    SurfaceVariables,
};

mod photon_flags;
pub use photon_flags::{LightPhotons, PhotonFlags, PhotonRole};

mod photon_shader;
pub use photon_shader::PhotonShader;

mod decoded_image;
pub use decoded_image::{DecodedImage, ImageContent};

mod ray_flags;
pub use ray_flags::{RayFlags, ALL_RAYS, CAMERA_RAYS, FRONT_ONLY, SECONDARY_RAYS, SHADOW_RAYS};
