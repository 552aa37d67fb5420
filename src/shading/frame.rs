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

    /// The frame [`ShadingFrame::from_normal`] gives for `-n`, bit for bit: `(s, −t, −n)`
    /// (every term of the construction changes sign in pairs, and rounding is symmetric),
    /// except that `t.y`, a sum `sign + …`, is `+0.0` for both normals when it cancels.
    #[inline]
    pub fn flipped(&self) -> Self {
        let t = -self.t;
        Self {
            s: self.s,
            t: Vec3::new(t.x, if t.y == 0.0 { 0.0 } else { t.y }, t.z),
            n: -self.n,
        }
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

    /// The components' bit patterns (so `-0.0` and `0.0` differ).
    fn bits(f: &ShadingFrame) -> [u32; 9] {
        let [a, b, c] = [f.s, f.t, f.n].map(|v| v.to_array().map(f32::to_bits));
        [a[0], a[1], a[2], b[0], b[1], b[2], c[0], c[1], c[2]]
    }

    #[test]
    fn flipped_equals_the_frame_of_the_opposite_normal_bit_for_bit() {
        let mut normals = vec![
            Vec3::Z,
            Vec3::NEG_Z,
            Vec3::X,
            Vec3::new(0.0, -1.0, -0.0),
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(-0.0, 1.0, -0.0),
            Vec3::ZERO,
            Vec3::new(1e-7, 0.0, -1.0).normalize(),
        ];
        for i in 0..20_000 {
            let a = i as f32 * 0.618_034;
            let z = ((i as f32 * 0.377).fract() * 2.0 - 1.0).clamp(-1.0, 1.0);
            let r = (1.0 - z * z).sqrt();
            normals.push(Vec3::new(r * a.cos(), r * a.sin(), z).normalize());
        }
        for n in normals {
            let f = ShadingFrame::from_normal(n);
            assert_eq!(
                bits(&f.flipped()),
                bits(&ShadingFrame::from_normal(-n)),
                "{n}"
            );
        }
    }

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
