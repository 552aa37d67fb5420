//! Placement of instances in the world.

use glam::Affine3A;

/// Transform from an object's own space into world space (the instance DAG already
/// composed, in f64, then rounded once to f32).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WorldFromObject(pub Affine3A);
