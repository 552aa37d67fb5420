//! The plain value types every part of the scene description is written with (`V3`, `M4`).
//! A leaf: the description modules (`desc`, `desc_camera`, `desc_environment`,
//! `desc_geometry`, `desc_material_shaders`, `nodes_desc`) all use it, so none of them
//! imports another for these (`desc` re-exports them).

/// A 3-vector as written in the file: `(x, y, z)`.
pub type V3 = (f64, f64, f64);

/// A row-major 4×4 matrix: `((r0), (r1), (r2), (r3))`.
pub type M4 = [[f64; 4]; 4];
