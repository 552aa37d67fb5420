//! The settings of a rendered reference. A knob whose accuracy is a setting rather than a
//! sample count (`max_depth`, `tessellation`) is measured against a reference rendered at
//! its most accurate setting: with the scene's own setting, the scene's value would always
//! measure no bias and "win".
//!
//! The other knobs need no setting of their own: `spp`, `adaptive_contrast` and
//! `bake_samples` are sample counts, which the reference replaces with `--reference-spp`;
//! `light_samples` and the photon-map knobs (`photons`, `gather_radius`, `gather_count`,
//! `passes`, `filter`) change nothing under the path tracer that renders the reference; and
//! `bvh_quality` changes the time, not the image.
//!
//! The reference's trace depth ([`ReferenceDepth`]): a `max_depth` sweep sets it as above.
//! Otherwise it is the scene's own when the swept runs are cut at that depth as the path
//! tracer is (the path and direct-lighting integrators without photon maps: every light
//! path they add has at most `max_depth` surface interactions), and it is raised to
//! [`REFERENCE_MIN_DEPTH`] when the swept runs read photon maps (the direct-lighting
//! integrator with caustics or global illumination): their photons bounce without a depth
//! limit (`photon_depth` is unlimited unless the scene sets it), so a reference cut at the
//! scene's depth would lack light the runs carry and count its own bias as theirs.

use crate::settings::{Integrator, RenderSettings};
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

/// The trace depth of a rendered reference, and why it is that depth.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ReferenceDepth {
    /// A `max_depth` sweep's: its knob setting ([`reference_setting`]) says it.
    Knob,
    /// The scene's own `max_depth`: the swept runs are cut at it as the path tracer is.
    Scene(u32),
    /// At least [`REFERENCE_MIN_DEPTH`] (raised from the scene's `max_depth` when that is
    /// less): the swept runs read photon maps, whose light is not cut at the scene's depth.
    Photons {
        /// The scene's `max_depth`.
        scene: u32,
        /// The reference's.
        depth: u32,
    },
}

/// Whether runs with `settings` under `integrator` read photon maps (the direct-lighting
/// integrator with caustics or global illumination on; the path tracer reads none).
pub fn reads_photon_maps(settings: &RenderSettings, integrator: Integrator) -> bool {
    integrator == Integrator::Direct && settings.photons.any()
}

/// The reference's trace depth for a sweep of `knob` on a scene with `scene` settings whose
/// runs integrate with `swept` (`--integrator`, else the scene's).
pub fn reference_depth(knob: &Knob, scene: &RenderSettings, swept: Integrator) -> ReferenceDepth {
    if matches!(knob, Knob::MaxDepth(_)) {
        ReferenceDepth::Knob
    } else if reads_photon_maps(scene, swept) {
        ReferenceDepth::Photons {
            scene: scene.max_depth,
            depth: scene.max_depth.max(REFERENCE_MIN_DEPTH),
        }
    } else {
        ReferenceDepth::Scene(scene.max_depth)
    }
}

impl ReferenceDepth {
    /// The depth to set on the reference (`None`: the knob's setting or the scene's own).
    pub fn setting(self) -> Option<Knob> {
        match self {
            ReferenceDepth::Photons { scene, depth } if depth > scene => {
                Some(Knob::MaxDepth(vec![depth]))
            }
            _ => None,
        }
    }

    /// What the reference's description says of its depth (`None` for a `max_depth` sweep,
    /// whose knob setting says it): `max_depth=4 (the scene's, as in the swept runs)` or
    /// `max_depth=16 (the scene's is 4, but the swept runs' photon maps carry light past
    /// it)`.
    pub fn describe(self) -> Option<String> {
        match self {
            ReferenceDepth::Knob => None,
            ReferenceDepth::Scene(depth) => Some(format!(
                "max_depth={depth} (the scene's, as in the swept runs)"
            )),
            ReferenceDepth::Photons { scene, depth } if depth > scene => Some(format!(
                "max_depth={depth} (the scene's is {scene}, but the swept runs' photon maps carry light past it)"
            )),
            ReferenceDepth::Photons { depth, .. } => Some(format!(
                "max_depth={depth} (the scene's, at least {REFERENCE_MIN_DEPTH}: the swept runs' photon maps carry light past any depth)"
            )),
        }
    }
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

    #[test]
    fn a_reference_is_deepened_only_for_runs_that_read_photon_maps() {
        let depth = |knob: &str, scene: &RenderSettings, swept| {
            let d = reference_depth(&Knob::parse(knob).unwrap(), scene, swept);
            (d.setting().map(|k| describe(&k)), d.describe())
        };
        let path = RenderSettings::default();
        let mut gi = RenderSettings::default();
        gi.photons.global_illumination = Some(crate::settings::PhotonMapSettings {
            photons: 100,
            radius: 0.0,
            gather: 8,
            final_gather: 4,
            precompute: true,
            aim: false,
            filter: crate::settings::PhotonFilter::Box,
            progressive: None,
        });
        assert_eq!(
            depth("spp=1,4", &gi, Integrator::Direct),
            (
                Some("max_depth=16".into()),
                Some("max_depth=16 (the scene's is 4, but the swept runs' photon maps carry light past it)".into())
            )
        );
        let scene_s = Some("max_depth=4 (the scene's, as in the swept runs)".to_string());
        // The path tracer reads no photon map; nor does direct lighting without one.
        assert_eq!(
            depth("spp=1,4", &gi, Integrator::Path),
            (None, scene_s.clone())
        );
        assert_eq!(
            depth("spp=1,4", &path, Integrator::Direct),
            (None, scene_s.clone())
        );
        assert_eq!(
            depth("tessellation=1,2", &path, Integrator::Path),
            (None, scene_s)
        );
        let deep = RenderSettings {
            max_depth: 20,
            ..gi.clone()
        };
        assert_eq!(
            depth("photons=10,100", &deep, Integrator::Direct),
            (
                None,
                Some("max_depth=20 (the scene's, at least 16: the swept runs' photon maps carry light past any depth)".into())
            )
        );
        // A `max_depth` sweep's knob setting says its depth.
        assert_eq!(
            depth("max_depth=1,2", &gi, Integrator::Direct),
            (None, None)
        );
    }
}
