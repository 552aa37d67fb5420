//! Local illumination models as a shading-language specification writes them (the RenderMan
//! Interface 3.2 standard surfaces; mental ray's base shaders can use the same terms): sums
//! over the lights of `Cl` times a cosine or a highlight lobe, plus ambient terms. They are
//! not physically based — the diffuse term has no 1/π, nothing conserves energy — and they
//! are evaluated as written, never clamped.

use glam::Vec3;

/// The specular highlight of a [`LocalModel`], per light: `Cl · lobe(N, L, V)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LocalLobe {
    /// The RenderMan Interface 3.2 `specularbrdf`: `max(0, N·H)^(1/roughness)` with the
    /// half vector `H = normalize(L + V)`.
    RenderMan {
        /// RenderMan roughness (> 0).
        roughness: f32,
    },
    /// mental ray's `mib_illum_phong`: `max(0, R·L)^exponent` with `R` the viewer's direction
    /// mirrored about the normal.
    Phong {
        /// Phong exponent (≥ 0).
        exponent: f32,
    },
    /// mental ray's `mib_illum_cooktorr` (and `mib_illum_blinn`, the same with one index):
    /// the Cook–Torrance (1982) specular term as the per-light factor,
    /// `F(L·H, ior) · D · G / (π · N·V)` — the paper's `R_s = F·D·G / (π (N·L)(N·V))` times
    /// the `N·L` of the light — with Beckmann `D = exp(−(tan α / m)²) / (m² cos⁴ α)` (`α` the
    /// angle of `H` from `N`, `m` the roughness, the average microfacet slope), the V-cavity
    /// `G = min(1, 2 (N·H)(N·V)/(V·H), 2 (N·H)(N·L)/(V·H))` and the unpolarised dielectric
    /// Fresnel reflectance `F` with one relative index per channel (below 1 read as 1).
    CookTorrance {
        /// Average microfacet slope `m` (> 0).
        roughness: f32,
        /// Relative index of refraction per channel.
        ior: Vec3,
    },
}

/// The unpolarised Fresnel reflectance of a dielectric of relative index `n` (≥ 1) at
/// `c = cos θ` (Cook and Torrance 1982, eq. 9): `½ (g−c)²/(g+c)² · (1 + ((c(g+c)−1) /
/// (c(g−c)+1))²)`, `g² = n² + c² − 1`.
fn fresnel_ct(c: f32, n: f32) -> f32 {
    let n = n.max(1.0);
    let g = (n * n + c * c - 1.0).max(0.0).sqrt();
    if g + c <= 0.0 {
        return 1.0;
    }
    let a = (g - c) / (g + c);
    let b = (c * (g + c) - 1.0) / (c * (g - c) + 1.0);
    0.5 * a * a * (1.0 + b * b)
}

/// The Cook–Torrance factor of [`LocalLobe::CookTorrance`] without its Fresnel term, and the
/// cosine `L·H` the Fresnel term takes; `None` where it is zero.
fn cook_torrance_dg(roughness: f32, wo: Vec3, wi: Vec3) -> Option<(f32, f32)> {
    if wo.z <= 0.0 || wi.z <= 0.0 {
        return None;
    }
    let h = (wo + wi).normalize_or_zero();
    let (nh, vh) = (h.z, wo.dot(h));
    if nh <= 0.0 || vh <= 0.0 {
        return None;
    }
    let m2 = roughness.max(1e-4).powi(2);
    let cos2 = nh * nh;
    let tan2 = (1.0 - cos2).max(0.0) / cos2;
    let d = (-tan2 / m2).exp() / (m2 * cos2 * cos2);
    let g = (2.0 * nh * wo.z / vh).min(2.0 * nh * wi.z / vh).min(1.0);
    let v = d * g / (std::f32::consts::PI * wo.z);
    v.is_finite().then_some((v, wi.dot(h)))
}

impl LocalLobe {
    /// The lobe for the unit directions `wo` (toward the viewer) and `wi` (toward the light)
    /// in the local frame whose +Z is the shading normal, per colour channel.
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        let scalar = match *self {
            LocalLobe::RenderMan { roughness } => {
                let h = (wo + wi).normalize_or_zero();
                let c = h.z.max(0.0);
                if c <= 0.0 {
                    0.0
                } else {
                    c.powf(1.0 / roughness.max(1e-4))
                }
            }
            LocalLobe::Phong { exponent } => {
                // The mirror direction of `wo` about +Z.
                let r = Vec3::new(-wo.x, -wo.y, wo.z).normalize_or_zero();
                let c = r.dot(wi);
                if c <= 0.0 {
                    0.0
                } else {
                    c.powf(exponent)
                }
            }
            LocalLobe::CookTorrance { roughness, ior } => {
                return cook_torrance_dg(roughness, wo, wi).map_or(Vec3::ZERO, |(v, lh)| {
                    v * Vec3::new(
                        fresnel_ct(lh, ior.x),
                        fresnel_ct(lh, ior.y),
                        fresnel_ct(lh, ior.z),
                    )
                });
            }
        };
        Vec3::splat(scalar)
    }
}

/// A local illumination model's terms. The radiance toward the viewer is
///
/// `color · (ka · A + kd · Σ Cl·max(0, N·L)) + ambient + specular · Σ Cl·lobe(N, L, V)
///  + reflection · (radiance along the mirror direction)`
///
/// where `A` is the scene's ambient light (the sum of its `Ambient` lights, RenderMan's
/// `ambient()`), `Cl` the light arriving from each light (a point light's `I/d²`) and `N` the
/// shading normal turned toward the viewer (RenderMan's `Nf`). RenderMan's `plastic` is
/// `color = Cs, specular = Ks·specularcolor`; `metal` is `kd = 0, specular = Ks·Cs`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LocalModel {
    /// Surface colour `Cs` (linear RGB): multiplies the ambient-light and diffuse terms (a
    /// texture binds here: RenderMan's `paintedplastic`).
    pub color: Vec3,
    /// Weight of the scene's ambient light (`Ka`).
    pub ka: f32,
    /// Weight of the diffuse sum (`Kd`).
    pub kd: f32,
    /// Weight of the highlight sum per channel (`Ks · specularcolor`).
    pub specular: Vec3,
    /// The highlight lobe.
    pub lobe: LocalLobe,
    /// Weight of the perfect-mirror reflection, traced (`shinymetal`'s `Kr · Cs`).
    pub reflection: Vec3,
    /// Radiance added as it is, independent of lights (mental ray's `ambience · ambient`).
    pub ambient: Vec3,
}

impl LocalModel {
    /// The light-independent part: `color · ka · scene_ambient + ambient`.
    pub fn ambient_term(&self, scene_ambient: Vec3) -> Vec3 {
        self.color * (self.ka * scene_ambient) + self.ambient
    }

    /// What one light arriving from `wi` (local frame, `wi.z = N·L > 0`) with radiance `cl`
    /// adds toward `wo`: `cl · (color·kd·N·L + specular·lobe)`.
    pub fn per_light(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        let cos = wi.z.max(0.0);
        self.color * (self.kd * cos) + self.specular * self.lobe.eval(wo, wi)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn renderman_lobe_is_the_half_vector_power() {
        let lobe = LocalLobe::RenderMan { roughness: 0.25 };
        // Mirror configuration: H = N, full highlight.
        let wo = Vec3::new(0.6, 0.0, 0.8);
        let wi = Vec3::new(-0.6, 0.0, 0.8);
        assert!((lobe.eval(wo, wi).x - 1.0).abs() < 1e-6);
        // V = N, L at 60°: H at 30°, cos 30°^4.
        let wi = Vec3::new(60f32.to_radians().sin(), 0.0, 0.5);
        let expected = 30f32.to_radians().cos().powi(4);
        assert!((lobe.eval(Vec3::Z, wi).x - expected).abs() < 1e-6);
    }

    #[test]
    fn cook_torrance_lobe_is_the_papers_specular_term() {
        // Viewer and light along N: H = N, tan α = 0, G = 1, D = 1/m²,
        // F at normal incidence ((n−1)/(n+1))²: the factor is F / (π m²).
        let lobe = LocalLobe::CookTorrance {
            roughness: 0.5,
            ior: Vec3::new(1.5, 2.0, 1.0),
        };
        let v = lobe.eval(Vec3::Z, Vec3::Z);
        let f = |n: f32| ((n - 1.0) / (n + 1.0)).powi(2);
        let want = Vec3::new(f(1.5), f(2.0), 0.0) / (std::f32::consts::PI * 0.25);
        assert!((v - want).abs().max_element() < 1e-6, "{v} vs {want}");
        // Light at 60° in the plane, viewer along N: H at 30°, L·H = cos 30°.
        let wi = Vec3::new(60f32.to_radians().sin(), 0.0, 0.5);
        let (nh, lh) = (30f32.to_radians().cos(), 30f32.to_radians().cos());
        let tan2 = (1.0 - nh * nh) / (nh * nh);
        let d = (-tan2 / 0.25).exp() / (0.25 * nh.powi(4));
        let g = (2.0 * nh * 1.0 / lh).min(2.0 * nh * 0.5 / lh).min(1.0);
        let n = 1.5f32;
        let gg = (n * n + lh * lh - 1.0).sqrt();
        let fr = 0.5
            * ((gg - lh) / (gg + lh)).powi(2)
            * (1.0 + ((lh * (gg + lh) - 1.0) / (lh * (gg - lh) + 1.0)).powi(2));
        let want = fr * d * g / std::f32::consts::PI;
        assert!((lobe.eval(Vec3::Z, wi).x - want).abs() < 1e-6);
        // Light below the horizon: nothing.
        assert_eq!(lobe.eval(Vec3::Z, -Vec3::Z), Vec3::ZERO);
    }

    #[test]
    fn plastic_terms_add_without_normalisation() {
        let m = LocalModel {
            color: Vec3::new(1.0, 0.5, 0.25),
            ka: 1.0,
            kd: 0.5,
            specular: Vec3::splat(0.5),
            lobe: LocalLobe::RenderMan { roughness: 0.1 },
            reflection: Vec3::ZERO,
            ambient: Vec3::ZERO,
        };
        // Light and viewer along N: Kd·Cs + Ks (no 1/π, no clamp).
        let c = m.per_light(Vec3::Z, Vec3::Z);
        assert!((c - Vec3::new(1.0, 0.75, 0.625)).abs().max_element() < 1e-6);
        assert_eq!(m.ambient_term(Vec3::splat(0.2)), Vec3::new(0.2, 0.1, 0.05));
    }
}
