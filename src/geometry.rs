//! World-space scene geometry produced by `build_accel`. STUB.

/// Scene geometry.
pub struct SceneGeometry;
