//! The knob setting of a rendered reference. A knob whose accuracy is a setting rather than a
//! sample count (`max_depth`, `tessellation`) is measured against a reference rendered at
//! its most accurate setting: with the scene's own setting, the scene's value would always
//! measure no bias and "win".
//!
//! The other knobs need no setting of their own: `spp`, `adaptive_contrast` and
//! `bake_samples` are sample counts, which the reference replaces with `--reference-spp`;
//! `light_samples` and the photon-map knobs (`photons`, `gather_radius`, `gather_count`,
//! `passes`, `filter`) change nothing under the path tracer that renders the reference; and
//! `bvh_quality` changes the time, not the image.

use crate::settings::RenderSettings;
use crate::sweep::knob::Knob;

/// The smallest trace depth of a `max_depth` sweep's reference: paths past 16 surface
/// interactions carry at most 0.8¹⁶ ≈ 3 % of the light even between walls of albedo 0.8.
pub const REFERENCE_MIN_DEPTH: u32 = 16;

/// The reference's setting of `knob` on a scene with `scene` settings, as a one-value knob
/// to apply after the scene loads; `None` when the reference keeps the scene's own setting.
/// - `max_depth`: the largest of the values swept, the scene's own and
///   [`REFERENCE_MIN_DEPTH`];
/// - `tessellation`: the smallest (finest) factor swept, or the scene's own (1) if finer.
pub fn reference_setting(knob: &Knob, scene: &RenderSettings) -> Option<Knob> {
    match knob {
        Knob::MaxDepth(values) => {
            let deepest = values.iter().copied().max().unwrap_or(0);
            Some(Knob::MaxDepth(vec![deepest
                .max(scene.max_depth)
                .max(REFERENCE_MIN_DEPTH)]))
        }
        Knob::Tessellation(values) => {
            let finest = values.iter().copied().fold(1.0f32, f32::min);
            Some(Knob::Tessellation(vec![finest]))
        }
        _ => None,
    }
}

/// `max_depth=16`: the setting as the reference's description and cache key write it.
pub fn describe(setting: &Knob) -> String {
    format!("{}={}", setting.name(), setting.label(0))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn setting(knob: &str, scene: &RenderSettings) -> Option<String> {
        reference_setting(&Knob::parse(knob).unwrap(), scene).map(|k| describe(&k))
    }

    #[test]
    fn accuracy_settings_take_their_most_accurate_value() {
        let scene = RenderSettings {
            max_depth: 2,
            ..RenderSettings::default()
        };
        assert_eq!(
            setting("max_depth=1,2,4", &scene).as_deref(),
            Some("max_depth=16")
        );
        assert_eq!(
            setting("max_depth=1,32", &scene).as_deref(),
            Some("max_depth=32")
        );
        let deep = RenderSettings {
            max_depth: 40,
            ..RenderSettings::default()
        };
        assert_eq!(
            setting("max_depth=1,2", &deep).as_deref(),
            Some("max_depth=40")
        );
        assert_eq!(
            setting("tessellation=4,1,0.25", &scene).as_deref(),
            Some("tessellation=0.25")
        );
        assert_eq!(
            setting("tessellation=4,2", &scene).as_deref(),
            Some("tessellation=1")
        );
        for k in [
            "spp=1,4",
            "light_samples=1,4",
            "bvh_quality=fast,high",
            "photons=10,100",
            "adaptive_contrast=0.1,0.2",
            "bake_samples=4,16",
        ] {
            assert_eq!(setting(k, &scene), None, "{k}");
        }
    }
}
