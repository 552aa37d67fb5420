//! Tracing one photon (the interaction itself is [`super::walk`]'s): scattering through the materials' BSDFs in importance mode, Russian
//! roulette by the scattering weight, deposits at diffuse surfaces, and an exact account of
//! where its power went (absorbed, escaped, truncated).
//!
//! At each hit the photon's power is first attenuated by the absorption of the segment it
//! crossed (dielectric `col`), then — if the surface has a non-delta lobe — deposited, then
//! scattered: the BSDF is sampled with [`TransportMode::Importance`] (refraction conserves power,
//! no `1/η²`; H14) and the weight gets Veach's shading-normal correction
//! `|wo·nₛ||wi·n_g| / (|wo·n_g||wi·nₛ|)`. The photon survives with probability
//! `q = min(1, max channel of the weight)` and carries `power·weight/q` (Jensen): for grey
//! materials a surviving photon keeps its power, so a map's photons have even powers.
//!
//! **Roles** ([`super::roles`]): a photon is stored only on a surface that receives for its
//! map, and is absorbed at a surface that does not cast. **Pass-through** (the straight
//! transmission of a material whose shadow shader lets light through, `Opacity`) does not
//! make a path a caustic: shadow rays already carry that light, so `L T D` is direct light,
//! while `L S T D` or `L T S D` with a mirror or refraction `S` stays a caustic.

use glam::Vec3;

use super::walk::Walk;
use crate::accel::Ray;
use crate::components::PhotonRole;
use crate::sampling::Sampler;
use crate::shading::integrator::ShadeContext;

pub use super::walk::{Deposit, Fate, MAX_BOUNCES};

/// Traces a photon along `ray` carrying `power`, calling `deposit` at every diffuse hit. With
/// `stop_after_diffuse`, the path ends after its first non-specular scattering (no caustic
/// photon can follow: the caustic pass uses it). Every surface casts and receives.
pub fn trace_photon(
    ctx: &ShadeContext<'_>,
    ray: Ray,
    power: Vec3,
    sampler: &mut Sampler,
    stop_after_diffuse: bool,
    deposit: impl FnMut(Deposit),
) -> Fate {
    trace_photon_with_roles(ctx, &[], ray, power, sampler, stop_after_diffuse, deposit)
}

/// [`trace_photon`] with each instance's role (`roles[instance slot]`; an instance beyond
/// the slice casts and receives).
pub fn trace_photon_with_roles(
    ctx: &ShadeContext<'_>,
    roles: &[PhotonRole],
    ray: Ray,
    power: Vec3,
    sampler: &mut Sampler,
    stop_after_diffuse: bool,
    deposit: impl FnMut(Deposit),
) -> Fate {
    walk_to_end(
        ctx,
        roles,
        Walk::new(ctx, ray, power),
        sampler,
        stop_after_diffuse,
        deposit,
    )
}

/// [`trace_photon_with_roles`] for a walk already started (a photon with its light's
/// [`super::emit::Falloff`]).
pub fn walk_to_end(
    ctx: &ShadeContext<'_>,
    roles: &[PhotonRole],
    mut walk: Walk,
    sampler: &mut Sampler,
    stop_after_diffuse: bool,
    mut deposit: impl FnMut(Deposit),
) -> Fate {
    while walk.live() {
        let hit = ctx.geometry.accel.intersect(walk.ray());
        walk.step(ctx, roles, hit, sampler, stop_after_diffuse, &mut deposit);
    }
    walk.fate()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::settings::RenderSettings;
    use crate::shading::integrator::fixture::{self, Object};
    use crate::shading::lights::LightSet;

    fn ray(origin: Vec3, dir: Vec3) -> Ray {
        Ray {
            origin,
            dir,
            t_max: f32::INFINITY,
        }
    }

    #[test]
    fn every_photon_power_is_accounted_for_in_a_closed_box() {
        // Grey walls (ρ = 0.5): survivors keep their power exactly, nothing escapes, and the
        // mean number of diffuse hits is 1/(1 − ρ) = 2.
        let geometry = fixture::geometry(vec![Object {
            triangles: fixture::inward_cube(1.0),
            material: fixture::lambert(0.5),
        }]);
        let lights = LightSet::default();
        let s = RenderSettings::default();
        let ctx = ShadeContext::new(&geometry, &lights, &s);
        let power = Vec3::new(1.0, 2.0, 3.0);
        let n = 2000u64;
        let mut deposits = 0usize;
        for i in 0..n {
            let mut sampler = Sampler::for_item(9, i, 0);
            let u = sampler.next_2d();
            let z = 1.0 - 2.0 * u.x;
            let r = (1.0 - z * z).max(0.0).sqrt();
            let phi = std::f32::consts::TAU * u.y;
            let dir = Vec3::new(r * phi.cos(), r * phi.sin(), z);
            let fate = trace_photon(
                &ctx,
                ray(Vec3::ZERO, dir),
                power,
                &mut sampler,
                false,
                |d| {
                    assert_eq!(d.photon.power, power);
                    assert!(!d.caustic);
                    deposits += 1;
                },
            );
            assert_eq!(fate.escaped, Vec3::ZERO);
            let total = fate.absorbed + fate.escaped + fate.truncated;
            assert!((total - power).abs().max_element() < 1e-5, "{fate:?}");
        }
        let mean = deposits as f64 / n as f64;
        println!("mean diffuse hits per photon: {mean} (expected 2)");
        assert!((mean - 2.0).abs() < 0.1, "{mean}");
    }

    #[test]
    fn a_photon_via_a_mirror_is_a_caustic_and_stops_after_the_diffuse_hit() {
        // Mirror ceiling at z = 1 facing down, grey floor at z = 0.
        let geometry = fixture::mirror_over_floor();
        let lights = LightSet::default();
        let s = RenderSettings::default();
        let ctx = ShadeContext::new(&geometry, &lights, &s);
        let power = Vec3::splat(0.5);
        let start = ray(Vec3::new(0.2, 0.1, 0.5), Vec3::new(0.1, 0.0, 1.0));
        for seed in 0..32 {
            let mut got = Vec::new();
            let mut sampler = Sampler::new(seed, 0);
            let fate = trace_photon(&ctx, start, power, &mut sampler, true, |d| got.push(d));
            assert_eq!(got.len(), 1, "{got:?}");
            let d = got[0];
            assert!(d.caustic && d.bounces == 1, "{d:?}");
            // Up 0.5 to the mirror, down 1 to the floor: 1.5 × 0.1 along x.
            let p = d.photon.position;
            assert!((p - Vec3::new(0.35, 0.1, 0.0)).length() < 1e-4, "{p}");
            assert_eq!(d.photon.normal, Vec3::Z);
            assert_eq!(fate.escaped, Vec3::ZERO);
            let total = fate.absorbed + fate.truncated;
            assert!((total - power).abs().max_element() < 1e-5, "{fate:?}");
        }
        // Straight down: a direct hit, not a caustic.
        let mut got = Vec::new();
        let down = ray(Vec3::new(0.0, 0.0, 0.5), -Vec3::Z);
        trace_photon(&ctx, down, power, &mut Sampler::new(0, 0), true, |d| {
            got.push(d)
        });
        assert_eq!(got.len(), 1);
        assert!(!got[0].caustic && got[0].bounces == 0);
    }
}
