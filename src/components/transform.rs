//! Placement of instances in the world, and the origin of render space.

use glam::{Affine3A, DVec3};

/// Transform from an object's own space into world space (the instance DAG already
/// composed, in f64, then rounded once to f32).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WorldFromObject(pub Affine3A);

/// Where render space's zero lies in world space (world = render + origin), for scenes the
/// loader rebased (hard case H5). One entity carries it, and only when it is not zero:
/// every position in components and stage outputs is in render space; outputs that expose
/// absolute positions add it back.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SceneOrigin(pub DVec3);
