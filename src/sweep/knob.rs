//! Accuracy knobs: parsing `NAME=V1,V2,…` and applying one value to a loaded scene. A knob
//! the scene does not have (area-light samples without area lights, tessellation tolerance
//! without approximations, bake samples without bake requests, adaptive contrast without
//! adaptive sampling) is an error, never a no-op.

use hecs::World;

use super::photon_knobs::{apply_passes, filter_label, parse_filters, FILTER_VALUES};
use crate::components::{
    Approximation, BakeKind, BakeRequest, Emitter, LightShape, Material, Technique,
};
use crate::settings::{BvhQuality, PhotonFilter, PhotonMapSettings, RenderSettings};

/// A knob and the values to sweep.
#[derive(Debug, Clone, PartialEq)]
pub enum Knob {
    /// Samples per pixel.
    Spp(Vec<u32>),
    /// Samples per shading point of every area light (rectangles and emitting meshes).
    LightSamples(Vec<u32>),
    /// Maximum trace depth.
    MaxDepth(Vec<u32>),
    /// BVH build quality.
    BvhQuality(Vec<BvhQuality>),
    /// Tessellation tolerance: multiplies every approximation's tolerance (curvature distance,
    /// spatial edge length) by the value.
    Tessellation(Vec<f32>),
    /// Rays (AO) or gather paths (lightmaps) per texel of every bake request.
    BakeSamples(Vec<u32>),
    /// Adaptive anti-aliasing contrast, the same threshold in every channel (the scene's
    /// `samples: (min, max, contrast)` keeps its `min` and `max`).
    AdaptiveContrast(Vec<f32>),
    /// Photons emitted for every photon map the scene turns on.
    Photons(Vec<u32>),
    /// Largest gather radius of every photon map (world units; 0 = automatic).
    GatherRadius(Vec<f32>),
    /// Photons per estimate (k) of every photon map.
    GatherCount(Vec<u32>),
    /// Progressive passes of the caustic map (made progressive with α = 0.7 if it is not).
    Passes(Vec<u32>),
    /// Estimate filter of every photon map.
    PhotonFilter(Vec<PhotonFilter>),
}

/// Why a knob cannot be swept.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum KnobError {
    /// Not of the form `NAME=V1,V2`.
    #[error("expected --knob NAME=V1,V2,… (e.g. spp=1,4,16), found \"{0}\"")]
    Syntax(String),
    /// Unknown knob name.
    #[error("unknown knob \"{0}\"\n  help: the knobs are spp, adaptive_contrast, light_samples, max_depth, bvh_quality, tessellation, bake_samples, photons, gather_radius, gather_count, passes and filter (e.g. --knob spp=1,4,16,64)")]
    Unknown(String),
    /// A value does not parse.
    #[error("knob {knob}: cannot read \"{value}\" ({expected})")]
    Value {
        /// Knob name.
        knob: String,
        /// The value.
        value: String,
        /// What was expected.
        expected: &'static str,
    },
    /// `--denoise` with a knob that does not bake.
    #[error("--denoise filters baked textures, but knob {0} renders images; sweep `--knob bake_samples=…` with it")]
    DenoiseNeedsBake(&'static str),
    /// A value is given twice (each value is one row of the table).
    #[error("knob {knob}: the value {value} is given twice; give each value once (every value is one row of the table)")]
    Repeated {
        /// Knob name as written.
        knob: String,
        /// The repeated value, as the table writes it.
        value: String,
    },
    /// The swept runs' integrator ignores what this knob changes (a flat table).
    #[error("knob {knob} changes nothing in the swept runs: {why}\n  help: sweep it with `--integrator direct`, or under the path integrator sweep spp or max_depth")]
    IgnoredByPath {
        /// Knob name.
        knob: &'static str,
        /// Why the path integrator ignores it.
        why: &'static str,
    },
    /// The scene has nothing this knob changes.
    #[error("knob {knob} is not in this scene: {why}")]
    Absent {
        /// Knob name.
        knob: &'static str,
        /// What is missing.
        why: &'static str,
    },
}

impl KnobError {
    /// Whether the command line, not the scene, is at fault (exit 2): the knob's text, a
    /// knob the swept integrator ignores, or `--denoise` with a render knob.
    pub fn is_usage(&self) -> bool {
        !matches!(self, KnobError::Absent { .. })
    }
}

fn parse_list<T: std::str::FromStr>(
    knob: &str,
    values: &str,
    expected: &'static str,
    ok: impl Fn(&T) -> bool,
) -> Result<Vec<T>, KnobError> {
    values
        .split(',')
        .map(|v| {
            let v = v.trim();
            v.parse::<T>()
                .ok()
                .filter(|x| ok(x))
                .ok_or_else(|| KnobError::Value {
                    knob: knob.to_string(),
                    value: v.to_string(),
                    expected,
                })
        })
        .collect()
}

impl Knob {
    /// Parses `NAME=V1,V2,…`.
    pub fn parse(text: &str) -> Result<Self, KnobError> {
        let (name, values) = text
            .split_once('=')
            .ok_or_else(|| KnobError::Syntax(text.to_string()))?;
        let name = name.trim();
        if values.trim().is_empty() {
            return Err(KnobError::Syntax(text.to_string()));
        }
        let positive = "a whole number ≥ 1";
        let knob = match name {
            "spp" | "samples" => Knob::Spp(parse_list(name, values, positive, |&v: &u32| v >= 1)?),
            "light_samples" => {
                Knob::LightSamples(parse_list(name, values, positive, |&v: &u32| v >= 1)?)
            }
            "max_depth" | "trace_depth" => {
                Knob::MaxDepth(parse_list(name, values, positive, |&v: &u32| v >= 1)?)
            }
            "bake_samples" => {
                Knob::BakeSamples(parse_list(name, values, positive, |&v: &u32| v >= 1)?)
            }
            "tessellation" => Knob::Tessellation(parse_list(
                name,
                values,
                "a positive factor",
                |&v: &f32| v.is_finite() && v > 0.0,
            )?),
            "adaptive_contrast" | "contrast" => Knob::AdaptiveContrast(parse_list(
                name,
                values,
                "a non-negative number",
                |&v: &f32| v.is_finite() && v >= 0.0,
            )?),
            "bvh_quality" => Knob::BvhQuality(
                values
                    .split(',')
                    .map(|v| match v.trim().to_ascii_lowercase().as_str() {
                        "fast" => Ok(BvhQuality::Fast),
                        "medium" => Ok(BvhQuality::Medium),
                        "high" => Ok(BvhQuality::High),
                        other => Err(KnobError::Value {
                            knob: name.to_string(),
                            value: other.to_string(),
                            expected: "fast, medium or high",
                        }),
                    })
                    .collect::<Result<_, _>>()?,
            ),
            "photons" => Knob::Photons(parse_list(name, values, positive, |&v: &u32| v >= 1)?),
            "gather_count" => Knob::GatherCount(parse_list(
                name,
                values,
                "a whole number ≥ 2",
                |&v: &u32| v >= 2,
            )?),
            "gather_radius" => Knob::GatherRadius(parse_list(
                name,
                values,
                "a radius ≥ 0 (0 = automatic)",
                |&v: &f32| v.is_finite() && v >= 0.0,
            )?),
            "passes" => Knob::Passes(parse_list(
                name,
                values,
                "a whole number of passes from 1 to 65536",
                |&v: &u32| (1..=65536).contains(&v),
            )?),
            "filter" | "photon_filter" => {
                Knob::PhotonFilter(parse_filters(values).map_err(|value| KnobError::Value {
                    knob: name.to_string(),
                    value,
                    expected: FILTER_VALUES,
                })?)
            }
            other => return Err(KnobError::Unknown(other.to_string())),
        };
        // Values are compared as the table writes them, so `0.5` and `0.50` are the same.
        let mut seen = std::collections::HashSet::new();
        if let Some(value) = (0..knob.len())
            .map(|i| knob.label(i))
            .find(|l| !seen.insert(l.clone()))
        {
            return Err(KnobError::Repeated {
                knob: name.to_string(),
                value,
            });
        }
        Ok(knob)
    }

    /// The knob's name in tables.
    pub fn name(&self) -> &'static str {
        match self {
            Knob::Spp(_) => "spp",
            Knob::LightSamples(_) => "light_samples",
            Knob::MaxDepth(_) => "max_depth",
            Knob::BvhQuality(_) => "bvh_quality",
            Knob::Tessellation(_) => "tessellation",
            Knob::BakeSamples(_) => "bake_samples",
            Knob::AdaptiveContrast(_) => "adaptive_contrast",
            Knob::Photons(_) => "photons",
            Knob::GatherRadius(_) => "gather_radius",
            Knob::GatherCount(_) => "gather_count",
            Knob::Passes(_) => "passes",
            Knob::PhotonFilter(_) => "filter",
        }
    }

    /// Number of values.
    pub fn len(&self) -> usize {
        match self {
            Knob::Spp(v) | Knob::LightSamples(v) | Knob::MaxDepth(v) | Knob::BakeSamples(v) => {
                v.len()
            }
            Knob::BvhQuality(v) => v.len(),
            Knob::Tessellation(v) | Knob::AdaptiveContrast(v) => v.len(),
            Knob::Photons(v) | Knob::GatherCount(v) => v.len(),
            Knob::GatherRadius(v) => v.len(),
            Knob::Passes(v) => v.len(),
            Knob::PhotonFilter(v) => v.len(),
        }
    }

    /// True when there are no values.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Value `i` as text (for tables).
    pub fn label(&self, i: usize) -> String {
        match self {
            Knob::Spp(v) | Knob::LightSamples(v) | Knob::MaxDepth(v) | Knob::BakeSamples(v) => {
                v[i].to_string()
            }
            Knob::BvhQuality(v) => format!("{:?}", v[i]).to_ascii_lowercase(),
            Knob::Tessellation(v) | Knob::AdaptiveContrast(v) => v[i].to_string(),
            Knob::Photons(v) | Knob::GatherCount(v) => v[i].to_string(),
            Knob::GatherRadius(v) => v[i].to_string(),
            Knob::Passes(v) => v[i].to_string(),
            Knob::PhotonFilter(v) => filter_label(v[i]),
        }
    }

    /// The value indices from the cheapest setting to the costliest, for the knobs whose
    /// values order their cost: more samples, depth, photons, gather count or passes cost
    /// more; a smaller tessellation factor or adaptive contrast costs more. `None` for the
    /// knobs whose values imply no order of time (`bvh_quality`, `gather_radius` with its
    /// automatic 0, `filter`).
    pub fn cost_order(&self) -> Option<Vec<usize>> {
        fn by<T: Copy>(v: &[T], key: impl Fn(T) -> f64) -> Vec<usize> {
            let mut order: Vec<usize> = (0..v.len()).collect();
            order.sort_by(|&a, &b| key(v[a]).total_cmp(&key(v[b])));
            order
        }
        match self {
            Knob::Spp(v)
            | Knob::LightSamples(v)
            | Knob::MaxDepth(v)
            | Knob::BakeSamples(v)
            | Knob::Photons(v)
            | Knob::GatherCount(v)
            | Knob::Passes(v) => Some(by(v, f64::from)),
            Knob::Tessellation(v) | Knob::AdaptiveContrast(v) => Some(by(v, |x| -f64::from(x))),
            Knob::BvhQuality(_) | Knob::GatherRadius(_) | Knob::PhotonFilter(_) => None,
        }
    }

    /// Whether this knob sweeps a bake (its results are baked textures).
    pub fn is_bake(&self) -> bool {
        matches!(self, Knob::BakeSamples(_))
    }

    /// Checks the scene (its world and settings) has what the knob changes.
    pub fn check(&self, world: &World, settings: &RenderSettings) -> Result<(), KnobError> {
        let absent = |why| {
            Err(KnobError::Absent {
                knob: self.name(),
                why,
            })
        };
        match self {
            Knob::LightSamples(_) => {
                let rect = world
                    .query::<&Emitter>()
                    .iter()
                    .any(|e| matches!(e.shape, LightShape::Rect { .. }));
                let mesh = world.query::<&Material>().iter().any(Material::is_emissive);
                if !rect && !mesh {
                    return absent("the scene has no area lights or emitting meshes");
                }
            }
            Knob::Tessellation(_) => {
                if world.query::<&Approximation>().iter().next().is_none() {
                    return absent("no object has an approximation");
                }
            }
            Knob::BakeSamples(_) => {
                let any = world.query::<&BakeRequest>().iter().any(|r| {
                    r.targets.iter().any(|t| {
                        matches!(
                            t.kind,
                            BakeKind::AmbientOcclusion { .. }
                                | BakeKind::Lightmap { indirect: true, .. }
                        )
                    })
                });
                if !any {
                    return absent("no bake request has ambient occlusion or an indirect lightmap");
                }
            }
            Knob::AdaptiveContrast(_) => {
                if settings.adaptive.is_none() {
                    return absent(
                        "options.samples is a fixed count; write `samples: (min: 4, max: 64)`",
                    );
                }
            }
            Knob::Passes(_) => {
                if settings.photons.caustics.is_none() {
                    return absent("the scene does not turn on caustics");
                }
            }
            Knob::Photons(_)
            | Knob::GatherRadius(_)
            | Knob::GatherCount(_)
            | Knob::PhotonFilter(_) => {
                if !settings.photons.any() {
                    return absent("the scene turns on neither caustics nor global_illumination");
                }
            }
            Knob::Spp(_) | Knob::MaxDepth(_) | Knob::BvhQuality(_) => {}
        }
        Ok(())
    }

    /// Applies value `i` to a freshly loaded scene.
    pub fn apply(&self, i: usize, world: &mut World, settings: &mut RenderSettings) {
        match self {
            Knob::Spp(v) => {
                settings.spp = v[i];
                settings.adaptive = None;
            }
            Knob::AdaptiveContrast(v) => {
                if let Some(a) = &mut settings.adaptive {
                    a.contrast = glam::Vec3::splat(v[i]);
                }
            }
            Knob::MaxDepth(v) => settings.max_depth = v[i],
            Knob::BvhQuality(v) => settings.bvh_quality = v[i],
            Knob::LightSamples(v) => {
                settings.light_samples = v[i];
                for e in world.query_mut::<&mut Emitter>() {
                    if matches!(e.shape, LightShape::Rect { .. }) {
                        e.samples = v[i];
                    }
                }
            }
            Knob::Tessellation(v) => {
                for a in world.query_mut::<&mut Approximation>() {
                    scale_tolerance(&mut a.technique, v[i]);
                }
            }
            Knob::Photons(v) => photon_maps(settings, |m| m.photons = v[i]),
            Knob::GatherRadius(v) => photon_maps(settings, |m| m.radius = v[i]),
            Knob::GatherCount(v) => photon_maps(settings, |m| m.gather = v[i]),
            Knob::Passes(v) => apply_passes(settings, v[i]),
            Knob::PhotonFilter(v) => photon_maps(settings, |m| m.filter = v[i]),
            Knob::BakeSamples(v) => {
                for r in world.query_mut::<&mut BakeRequest>() {
                    for t in &mut r.targets {
                        match &mut t.kind {
                            BakeKind::AmbientOcclusion { samples, .. }
                            | BakeKind::Lightmap { samples, .. } => *samples = v[i],
                            _ => {}
                        }
                    }
                }
            }
        }
    }
}

/// Applies `f` to every photon map the settings turn on.
fn photon_maps(settings: &mut RenderSettings, f: impl Fn(&mut PhotonMapSettings)) {
    let p = &mut settings.photons;
    for m in [&mut p.caustics, &mut p.global_illumination]
        .into_iter()
        .flatten()
    {
        f(m);
    }
}

/// Multiplies a technique's tolerance by `factor` (rates divided for the uniform ones, within
/// the tessellator's `1..=MAX_FIXED_RATE`). What the result costs is checked against the
/// memory budget before the sweep runs (`budget_check`).
fn scale_tolerance(t: &mut Technique, factor: f32) {
    use crate::tessellation::rates::MAX_FIXED_RATE;
    let scale = |r: u32| ((r as f32 / factor).round() as u32).clamp(1, MAX_FIXED_RATE);
    match t {
        Technique::Curvature { distance, .. } => *distance *= factor,
        Technique::Spatial { edge, .. } => *edge *= factor,
        Technique::Parametric { u, v } | Technique::Regular { u, v } => {
            *u = scale(*u);
            *v = scale(*v);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_names_and_values() {
        assert_eq!(
            Knob::parse("spp=1,4,16").unwrap(),
            Knob::Spp(vec![1, 4, 16])
        );
        assert_eq!(
            Knob::parse("bvh_quality=fast,High").unwrap(),
            Knob::BvhQuality(vec![BvhQuality::Fast, BvhQuality::High])
        );
        assert!(matches!(Knob::parse("spp=0"), Err(KnobError::Value { .. })));
        assert!(matches!(
            Knob::parse("photon_count=1"),
            Err(KnobError::Unknown(_))
        ));
        assert_eq!(
            Knob::parse("photons=1000,4000").unwrap(),
            Knob::Photons(vec![1000, 4000])
        );
        assert!(matches!(
            Knob::parse("gather_count=1"),
            Err(KnobError::Value { .. })
        ));
        assert!(matches!(Knob::parse("spp"), Err(KnobError::Syntax(_))));
    }

    #[test]
    fn a_repeated_value_is_refused_naming_it() {
        assert_eq!(
            Knob::parse("spp=1,4,1").unwrap_err().to_string(),
            "knob spp: the value 1 is given twice; give each value once (every value is one row of the table)"
        );
        // Compared as the table writes them.
        assert_eq!(
            Knob::parse("tessellation=0.5,1,0.50").unwrap_err(),
            KnobError::Repeated {
                knob: "tessellation".into(),
                value: "0.5".into()
            }
        );
        assert!(matches!(
            Knob::parse("filter=cone,cone:1.1"),
            Err(KnobError::Repeated { .. })
        ));
        assert!(Knob::parse("spp=4,1,16").is_ok());
    }

    #[test]
    fn cost_order_runs_from_the_cheapest_setting() {
        let order = |k: &str| Knob::parse(k).unwrap().cost_order();
        assert_eq!(order("spp=4,1,16"), Some(vec![1, 0, 2]));
        assert_eq!(order("tessellation=1,4,0.5"), Some(vec![1, 0, 2]));
        assert_eq!(order("adaptive_contrast=0.05,0.2"), Some(vec![1, 0]));
        assert_eq!(order("filter=box,gauss"), None);
        assert_eq!(order("bvh_quality=fast,high"), None);
    }

    #[test]
    fn absent_knobs_are_errors() {
        let world = World::new();
        assert!(matches!(
            Knob::parse("light_samples=1,2")
                .unwrap()
                .check(&world, &RenderSettings::default()),
            Err(KnobError::Absent { .. })
        ));
        assert!(matches!(
            Knob::parse("tessellation=1,0.5")
                .unwrap()
                .check(&world, &RenderSettings::default()),
            Err(KnobError::Absent { .. })
        ));
        assert!(Knob::parse("spp=1")
            .unwrap()
            .check(&world, &RenderSettings::default())
            .is_ok());
        for k in [
            "photons=10",
            "gather_radius=0.1",
            "gather_count=8",
            "passes=1,4",
            "filter=box,gauss",
        ] {
            assert!(matches!(
                Knob::parse(k)
                    .unwrap()
                    .check(&world, &RenderSettings::default()),
                Err(KnobError::Absent { .. })
            ));
        }
        let contrast = Knob::parse("adaptive_contrast=0.2,0.05").unwrap();
        assert_eq!(contrast, Knob::AdaptiveContrast(vec![0.2, 0.05]));
        assert!(matches!(
            contrast.check(&world, &RenderSettings::default()),
            Err(KnobError::Absent { .. })
        ));
        let mut settings = RenderSettings {
            adaptive: Some(crate::settings::AdaptiveSamples {
                min: 4,
                max: 64,
                contrast: glam::Vec3::splat(0.1),
            }),
            ..RenderSettings::default()
        };
        assert!(contrast.check(&world, &settings).is_ok());
        let mut world = World::new();
        contrast.apply(1, &mut world, &mut settings);
        assert_eq!(
            settings.adaptive.map(|a| a.contrast),
            Some(glam::Vec3::splat(0.05))
        );
    }
}
