//! Irradiance estimators for lightmaps: direct irradiance from the scene's lights with
//! shadow rays, and diffuse interreflection gathered with cosine-weighted paths.
//!
//! Emission seen by gather rays is not added: emitting meshes are lights already sampled by
//! next-event estimation, so counting them again would double their contribution.

use glam::Vec3;

use crate::accel::{spawn_ray, RayKind, SurfacePoint};
use crate::bake::ao::basis;
use crate::components::{Material, Shader};
use crate::geometry::SceneGeometry;
use crate::sampling::{sample_cosine_hemisphere, Sampler};
use crate::shading::shadow::transmittance;
use crate::shading::LightSet;

/// Direct irradiance (W/m²) at `surface` with unit normal `normal` from every light that
/// lights `material` (its light list), with shadow rays (tinted by transparent surfaces, as
/// in renders); each light uses its own sample count, drawn from child sequences of
/// `sampler`.
pub fn direct_irradiance(
    geometry: &SceneGeometry,
    lights: &LightSet,
    material: &Material,
    surface: &SurfacePoint,
    normal: Vec3,
    ng_facing: Vec3,
    sampler: &mut Sampler,
) -> Vec3 {
    let mut e = Vec3::ZERO;
    for (i, light) in lights.lights.iter().enumerate() {
        if !material.sees_light(i) {
            continue;
        }
        let n = light.sample_count();
        let seed = sampler.child_seed();
        let mut sum = Vec3::ZERO;
        for j in 0..n {
            let u = Sampler::new(seed, j).next_2d();
            let Some(ls) = light.sample(surface.p, u, Some(geometry)) else {
                continue;
            };
            let cos = normal.dot(ls.wi);
            if cos <= 0.0 || ng_facing.dot(ls.wi) <= 0.0 {
                continue;
            }
            let shadow = if ls.shadows {
                ls.lighten(transmittance(
                    geometry,
                    surface,
                    ls.wi,
                    ls.target,
                    lights.transmissive_shadows,
                ))
            } else {
                Vec3::ONE
            };
            sum += ls.contribution * shadow * cos;
        }
        e += sum / n as f32;
    }
    e
}

/// Diffuse reflectance used for interreflection (lightmaps gather diffuse light only):
/// the diffuse lobe of each shader, the colour of the light-independent ones, zero for purely
/// specular ones (mirror, metal, glass).
pub fn diffuse_albedo(shader: &Shader) -> Vec3 {
    match shader {
        Shader::Lambert { albedo } => *albedo,
        Shader::Constant { color } | Shader::DefaultSurface { color, .. } => *color,
        Shader::Phong { diffuse, .. }
        | Shader::Blinn { diffuse, .. }
        | Shader::CookTorrance { diffuse, .. }
        | Shader::Blong { diffuse, .. }
        | Shader::FresnelSpecular { diffuse, .. }
        | Shader::Dgs { diffuse, .. } => *diffuse,
        Shader::Matte { kd, color, .. }
        | Shader::Plastic { kd, color, .. }
        | Shader::PaintedPlastic { kd, color, .. } => *color * *kd,
        Shader::Metal { .. }
        | Shader::ShinyMetal { .. }
        | Shader::Mirror { .. }
        | Shader::Dielectric { .. } => Vec3::ZERO,
        // The diffuse term of the metallic-roughness model (at normal incidence).
        Shader::MetallicRoughness {
            base_color,
            metallic,
            ..
        } => *base_color * ((1.0 - metallic) * 0.96),
        // The local model's diffuse weight (its sum has no 1/π: not a reflectance).
        Shader::Local(m) => m.color * m.kd,
        Shader::Opacity { opacity, input } => diffuse_albedo(input) * *opacity,
    }
}

/// The surface's base colour, as the `Albedo` bake kind writes it: the diffuse reflectance,
/// or for specular shaders their reflectance colour.
pub fn base_color(shader: &Shader) -> Vec3 {
    match shader {
        Shader::Metal { color, .. }
        | Shader::ShinyMetal { color, .. }
        | Shader::Mirror { color } => *color,
        Shader::MetallicRoughness { base_color, .. } => *base_color,
        Shader::Dielectric { col, .. } => *col,
        Shader::Opacity { input, .. } => base_color(input),
        other => diffuse_albedo(other),
    }
}

/// Indirect irradiance (W/m²) at `surface` from one cosine-weighted gather path of at most
/// `depth` bounces: `π · L_in` for the sampled direction (pdf cosθ/π), with direct lighting
/// at every vertex.
#[allow(clippy::too_many_arguments)] // the state of one path; called from one place
pub fn indirect_irradiance_sample(
    geometry: &SceneGeometry,
    lights: &LightSet,
    surface: &SurfacePoint,
    normal: Vec3,
    ng_facing: Vec3,
    depth: u32,
    sampler: &mut Sampler,
) -> Vec3 {
    let mut throughput = Vec3::splat(std::f32::consts::PI);
    let (mut sp, mut n, mut ngf) = (*surface, normal, ng_facing);
    let mut e = Vec3::ZERO;
    for _ in 0..depth {
        let (t, b) = basis(n);
        let local = sample_cosine_hemisphere(sampler.next_2d());
        let dir = t * local.x + b * local.y + n * local.z;
        if dir.dot(ngf) <= 0.0 {
            break;
        }
        let ray = spawn_ray(&sp, dir);
        let Some(hit) = geometry.accel.intersect_as(&ray, RayKind::Secondary) else {
            break;
        };
        let hp = geometry.shading_point(&hit);
        let material = &geometry.materials[hp.material as usize];
        let front = hp.surface.ng.dot(-dir) > 0.0;
        if !front && !material.two_sided {
            break;
        }
        let sign = if front { 1.0 } else { -1.0 };
        let (hn, hng) = (hp.normal * sign, hp.surface.ng * sign);
        let albedo = diffuse_albedo(&material.shader);
        // L_in = albedo/π · E(hit); the path weight π/π·albedo carries on.
        let e_hit = direct_irradiance(geometry, lights, material, &hp.surface, hn, hng, sampler);
        throughput *= albedo / std::f32::consts::PI;
        e += throughput * e_hit;
        if throughput.max_element() <= 0.0 {
            break;
        }
        // Next bounce: the estimator of E at the hit is π·L_in, so scale by π.
        throughput *= std::f32::consts::PI;
        sp = hp.surface;
        n = hn;
        ngf = hng;
    }
    e
}

/// Indirect irradiance (W/m²) from one cosine-weighted gather ray whose incoming radiance is
/// estimated by the path-traced reference integrator (`--integrator path`): `π · (L − Le)`,
/// where `Le` — the hit surface's own emission — is left out because emitters are counted by
/// [`direct_irradiance`] already.
pub fn indirect_irradiance_path(
    ctx: &crate::shading::ShadeContext<'_>,
    surface: &SurfacePoint,
    normal: Vec3,
    ng_facing: Vec3,
    sampler: &mut Sampler,
) -> Vec3 {
    let (t, b) = basis(normal);
    let local = sample_cosine_hemisphere(sampler.next_2d());
    let dir = t * local.x + b * local.y + normal * local.z;
    if dir.dot(ng_facing) <= 0.0 {
        return Vec3::ZERO;
    }
    let ray = spawn_ray(surface, dir);
    let Some(hit) = ctx.geometry.accel.intersect_as(&ray, RayKind::Secondary) else {
        return Vec3::ZERO;
    };
    let vertex = crate::shading::integrator::Vertex::new(ctx, &ray, &hit);
    let l = crate::shading::integrator::path::radiance(ctx, &ray, &hit, sampler) - vertex.emitted();
    let e = l.max(Vec3::ZERO) * std::f32::consts::PI;
    if e.is_finite() {
        e
    } else {
        Vec3::ZERO
    }
}
