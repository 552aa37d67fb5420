//! The plain value types every part of the scene description is written with (`V3`, `M4`).
//! A leaf: the description modules (`desc`, `desc_camera`, `desc_environment`,
//! `desc_geometry`, `desc_material_shaders`, `nodes_desc`) all use it, so none of them
//! imports another for these (`desc` re-exports them). Also the one test a transform value
//! must pass to place anything ([`is_singular`]), shared by the RON checker and the glTF
//! reader.

/// A 3-vector as written in the file: `(x, y, z)`.
pub type V3 = (f64, f64, f64);

/// A row-major 4×4 matrix: `((r0), (r1), (r2), (r3))`.
pub type M4 = [[f64; 4]; 4];

/// Whether a transform's linear part flattens space (an axis of length 0, or a determinant
/// within 1e-12 of 0 relative to its axes' lengths): not invertible, so not a placement.
pub fn is_singular(m: &glam::DMat3) -> bool {
    let scale = [m.x_axis, m.y_axis, m.z_axis]
        .iter()
        .map(|c| c.length())
        .product::<f64>();
    scale == 0.0 || m.determinant().abs() <= 1e-12 * scale
}
