//! Local shading frames: an orthonormal basis around the shading normal in which BSDFs are
//! written (normal = +Z, so `cosθ = w.z`).

use glam::Vec3;

/// Orthonormal basis `(s, t, n)`; world = `x·s + y·t + z·n`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShadingFrame {
    /// First tangent.
    pub s: Vec3,
    /// Second tangent.
    pub t: Vec3,
    /// Normal (local +Z).
    pub n: Vec3,
}

impl ShadingFrame {
    /// A frame around the unit vector `n` (Duff et al. 2017: branch-free, continuous except
    /// at `n.z = 0` crossings, exact near the poles).
    pub fn from_normal(n: Vec3) -> Self {
        let sign = 1f32.copysign(n.z);
        let a = -1.0 / (sign + n.z);
        let b = n.x * n.y * a;
        let s = Vec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
        let t = Vec3::new(b, sign + n.y * n.y * a, -n.y);
        Self { s, t, n }
    }

    /// World direction in local coordinates.
    #[inline]
    pub fn to_local(&self, v: Vec3) -> Vec3 {
        Vec3::new(v.dot(self.s), v.dot(self.t), v.dot(self.n))
    }

    /// Local direction in world coordinates.
    #[inline]
    pub fn to_world(&self, v: Vec3) -> Vec3 {
        self.s * v.x + self.t * v.y + self.n * v.z
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frames_are_orthonormal_near_the_poles() {
        let normals = [
            Vec3::Z,
            Vec3::NEG_Z,
            Vec3::new(1e-7, 0.0, -1.0).normalize(),
            Vec3::new(0.0, 1e-6, 1.0).normalize(),
            Vec3::new(0.3, -0.4, 0.866).normalize(),
            Vec3::X,
        ];
        for n in normals {
            let f = ShadingFrame::from_normal(n);
            for (a, b) in [(f.s, f.t), (f.s, f.n), (f.t, f.n)] {
                assert!(a.dot(b).abs() < 1e-6, "{n}");
            }
            for v in [f.s, f.t] {
                assert!((v.length() - 1.0).abs() < 1e-6, "{n}");
            }
            assert!(
                (f.s.cross(f.t) - f.n).length() < 1e-5,
                "right-handed at {n}"
            );
            let w = Vec3::new(0.2, -0.5, 0.7);
            assert!((f.to_local(f.to_world(w)) - w).length() < 1e-6);
        }
    }
}
