//! What a lat-long environment map takes in memory, from its size alone (the scene loader
//! counts it against the run's memory budget before reading the file, and the run-wide
//! estimate counts it once read): its radiance texels, one `Vec3` each as the loader keeps
//! them, and for the scene's environment, which is also a light, what [`EnvLight::new`]
//! builds from them — the sampling tables (one [`Distribution1D`] of cells and CDF per row,
//! and the marginal over rows), and while it builds them, the luminance × sinθ weight of
//! every texel and one row's CDF in `f64`.
//!
//! [`EnvLight::new`]: super::EnvLight::new

use std::mem::size_of;

use glam::Vec3;

use super::Distribution1D;

/// Bytes of the radiance texels of a `width × height` map.
pub fn texel_bytes(width: u32, height: u32) -> u64 {
    texels(width, height).saturating_mul(size_of::<Vec3>() as u64)
}

/// Bytes of the sampling tables [`EnvLight::new`](super::EnvLight::new) keeps for a
/// `width × height` map (what [`EnvLight::table_bytes`](super::EnvLight::table_bytes)
/// reports of the built light).
pub fn table_bytes(width: u32, height: u32) -> u64 {
    // A distribution over n cells keeps n cells and n + 1 CDF entries, f32 each.
    let distribution = |n: u64| {
        n.saturating_mul(2)
            .saturating_add(1)
            .saturating_mul(size_of::<f32>() as u64)
    };
    let row = distribution(u64::from(width)).saturating_add(size_of::<Distribution1D>() as u64);
    row.saturating_mul(u64::from(height))
        .saturating_add(distribution(u64::from(height)))
}

/// Bytes [`EnvLight::new`](super::EnvLight::new) holds only while it builds the tables: the
/// weight of every texel (f32) and the `f64` CDF of the longest distribution being built.
pub fn building_bytes(width: u32, height: u32) -> u64 {
    let weights = texels(width, height).saturating_mul(size_of::<f32>() as u64);
    let cdf = (u64::from(width.max(height)) + 1) * size_of::<f64>() as u64;
    weights.saturating_add(cdf)
}

/// The peak bytes of a `width × height` map: its texels, and when it is `sampled` (the
/// scene's environment), its tables and what building them takes.
pub fn peak_bytes(width: u32, height: u32, sampled: bool) -> u64 {
    let texels = texel_bytes(width, height);
    if sampled {
        texels
            .saturating_add(table_bytes(width, height))
            .saturating_add(building_bytes(width, height))
    } else {
        texels
    }
}

fn texels(width: u32, height: u32) -> u64 {
    u64::from(width) * u64::from(height)
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use super::*;
    use crate::components::{DepthExceeded, Environment, EnvironmentSource, LatLongMap};
    use crate::shading::lights::environment::EnvLight;

    /// The counts are what the built light allocates: its tables' capacities, for maps that
    /// are wide, tall, one texel, and lit or black (a black map still builds its tables).
    #[test]
    fn table_bytes_are_the_built_lights_allocations() {
        for (w, h, radiance) in [(37, 19, 1.0), (3, 40, 0.5), (1, 1, 2.0), (8, 4, 0.0)] {
            let map = LatLongMap {
                width: w,
                height: h,
                texels: vec![Vec3::splat(radiance); (w * h) as usize],
                rotation: 0.0,
            };
            assert_eq!(
                texel_bytes(w, h),
                (map.texels.capacity() * size_of::<Vec3>()) as u64
            );
            let light = EnvLight::new(&Environment {
                source: EnvironmentSource::LatLong(Arc::new(map)),
                samples: 1,
                depth_exceeded: DepthExceeded::Black,
            });
            assert_eq!(table_bytes(w, h), light.table_bytes(), "{w}×{h}");
        }
        // 1024×512: 6 MiB of texels, 4 MiB of tables (+ 12 KiB of row headers and the
        // marginal), 2 MiB of weights while they are built.
        assert_eq!(texel_bytes(1024, 512), 6 << 20);
        assert_eq!(
            table_bytes(1024, 512),
            (4 << 20) + 512 * (4 + 56) + 1025 * 4
        );
        assert_eq!(building_bytes(1024, 512), (2 << 20) + 1025 * 8);
        assert_eq!(peak_bytes(1024, 512, false), 6 << 20);
    }
}
